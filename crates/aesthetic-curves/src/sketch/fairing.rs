use super::constants::ALPHA_WEIGHT;
use super::pieces::{build_all, build_piece, Built};
use super::slot::{rotate, Slot};

use super::types::{FairingReport, PieceShape, SketchOptions};
use crate::error::Result;
use crate::lac::ALPHA_RANGE;
use kurbo::{Point, Vec2};
use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

/// The largest end curvature of the pieces.
pub(super) fn curvature_scale(built: &[Built]) -> f64 {
    built
        .iter()
        .map(|b| b.kappa.0.abs().max(b.kappa.1.abs()))
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE)
}

/// The pieces before and after joint `j` of `m` pieces: joint j (1 to m - 1) starts piece
/// j; joint 0 is a closed curve's seam, from the last piece to the first.
pub(super) fn sides(j: usize, m: usize) -> (usize, usize) {
    if j == 0 {
        (m - 1, 0)
    } else {
        (j - 1, j)
    }
}

/// Joint `j`'s tangent turned by `h` (the seam's at both ends of the curve, which share it).
pub(super) fn turn_joint(dirs: &mut [Vec2], j: usize, h: f64) {
    dirs[j] = rotate(dirs[j], h);
    if j == 0 {
        let m = dirs.len() - 1;
        dirs[m] = dirs[0];
    }
}

/// The pieces on both sides of joint `j` rebuilt in `built` with the tangents `dirs`.
pub(super) fn rebuild_joint(
    built: &mut [Built],
    (slots, pts, dirs): (&[Slot], &[Point], &[Vec2]),
    j: usize,
) -> Option<()> {
    let (a, b) = sides(j, slots.len());
    for i in [a, b] {
        built[i] = build_piece(&slots[i], pts[i], dirs[i], pts[i + 1], dirs[i + 1]).ok()?;
    }
    Some(())
}

/// The curvature mismatch at each active joint over `scale`.
pub(super) fn mismatches(built: &[Built], active: &[usize], scale: f64) -> Vec<f64> {
    active
        .iter()
        .map(|&j| {
            let (a, b) = sides(j, built.len());
            (built[b].kappa.0 - built[a].kappa.1) / scale
        })
        .collect()
}

pub(super) fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// One Jacobian column by finite differences of the mismatches: central from the values at
/// `+h` and `-h`, one-sided (against `d`, the values at 0) where one side cannot be built,
/// `None` where neither can.
pub(super) fn difference_column(
    plus: Option<Vec<f64>>,
    minus: Option<Vec<f64>>,
    d: &[f64],
    h: f64,
) -> Option<Vec<f64>> {
    let n = d.len();
    match (plus, minus) {
        (Some(p), Some(m)) => Some((0..n).map(|r| (p[r] - m[r]) / (2.0 * h)).collect()),
        (Some(p), None) => Some((0..n).map(|r| (p[r] - d[r]) / h).collect()),
        (None, Some(m)) => Some((0..n).map(|r| (d[r] - m[r]) / h).collect()),
        (None, None) => None,
    }
}

/// The fairing problem, read by both of its stages: the pieces' slots and joint points,
/// the joints faired (every joint but those with zero curvature by construction on both
/// sides), and the merit's scale, which stays that of the first build: measured against a
/// trial's own largest curvature, a step that blows one free end up into a hook (a triangle
/// at the edge of its existence region) would shrink every relative mismatch and be
/// accepted.
struct Fairing<'a> {
    slots: &'a [Slot],
    pts: &'a [Point],
    opts: &'a SketchOptions,
    active: Vec<usize>,
    scale: f64,
}

/// The state of the tangent stage: the joints' directions and the pieces built on them.
type Tangents = (Vec<Vec2>, Vec<Built>);

/// The state of the α stage: the directions, the slots with their α, the pieces.
type WithAlphas = (Vec<Vec2>, Vec<Slot>, Vec<Built>);

/// Step 5: G2 fairing by Newton on the active joints' tangent angles, then, where that
/// leaves a jump, with the α of the LAC pieces next to it ([`Fairing::alphas`]). Returns the
/// pieces and the report, whose jump covers every joint of the result.
pub(super) fn fair(
    slots: &[Slot],
    pts: &[Point],
    dirs: &mut [Vec2],
    opts: &SketchOptions,
) -> Result<(Vec<Built>, FairingReport)> {
    let built = build_all(slots, pts, dirs)?;
    let active = faired_joints(&built, opts.closed);
    let problem = Fairing {
        slots,
        pts,
        opts,
        scale: curvature_scale(&built),
        active,
    };
    let initial = max_abs(&problem.mismatches(&built));
    let (new_dirs, mut built, iterations) = problem.tangents(dirs.to_vec(), built)?;
    dirs.copy_from_slice(&new_dirs);
    let final_jump = problem.own(&built);
    let mut report = FairingReport {
        iterations,
        initial_jump: initial,
        final_jump,
        converged: final_jump <= opts.g2_tolerance,
    };
    if !report.converged {
        report.iterations += problem.alphas(dirs, &mut built)?;
    }
    // The report covers every joint of the result: a step can turn a piece next to a joint
    // left out (zero curvature on both sides) into an ordinary one, whose end curvature
    // there is not zero.
    report.final_jump = max_abs(&mismatches(
        &built,
        &faired_joints(&built, opts.closed),
        curvature_scale(&built),
    ));
    report.converged = report.final_jump <= opts.g2_tolerance;
    Ok((built, report))
}

/// The joints to fair: every joint (a closed curve's seam, joint 0, too) but those where
/// both sides are inflection ends, whose curvature is zero on both sides by construction
/// (an inflection cut whose piece could not be an inflection piece too is faired).
fn faired_joints(built: &[Built], closed: bool) -> Vec<usize> {
    let m = built.len();
    let zero_both = |j: usize| {
        let (a, b) = sides(j, m);
        built[a].curve.zero_curvature_ends()[1] && built[b].curve.zero_curvature_ends()[0]
    };
    (usize::from(!closed)..m)
        .filter(|&j| !zero_both(j))
        .collect()
}

impl Fairing<'_> {
    /// The mismatches at the active joints over the problem's scale.
    fn mismatches(&self, built: &[Built]) -> Vec<f64> {
        mismatches(built, &self.active, self.scale)
    }

    /// The largest mismatch over the build's own curvature (the final report's measure).
    fn own(&self, built: &[Built]) -> f64 {
        max_abs(&mismatches(built, &self.active, curvature_scale(built)))
    }

    /// The solver layer's limits for either stage.
    fn newton(&self) -> crate::solve::systems::DampedNewton {
        crate::solve::systems::DampedNewton {
            max_iterations: self.opts.max_fairing_iterations,
            halvings: 30,
        }
    }

    /// `dirs` with each active joint turned by `lam` times its share of `step`.
    fn turned(&self, dirs: &[Vec2], step: &[f64], lam: f64) -> Vec<Vec2> {
        let mut trial = dirs.to_vec();
        for (k, &j) in self.active.iter().enumerate() {
            turn_joint(&mut trial, j, lam * step[k]);
        }
        trial
    }

    /// The mismatches with joint `j` turned by `h` in `slots` (the pieces on both sides
    /// rebuilt), `None` where a side cannot be built.
    fn joint_moved(
        &self,
        (dirs, slots, built): (&[Vec2], &[Slot], &[Built]),
        j: usize,
        h: f64,
    ) -> Option<Vec<f64>> {
        let mut trial = dirs.to_vec();
        turn_joint(&mut trial, j, h);
        let mut b2 = built.to_vec();
        rebuild_joint(&mut b2, (slots, self.pts, &trial), j)?;
        Some(self.mismatches(&b2))
    }

    /// Stage 1: Newton on the active joints' tangent angles (square system; the Jacobian
    /// by central differences, one-sided where a side leaves the admissible set; its
    /// columns, a joint's two pieces each, in parallel: the same numbers in any order).
    /// Returns the directions, the pieces and the iterations.
    fn tangents(
        &self,
        dirs: Vec<Vec2>,
        built: Vec<Built>,
    ) -> Result<(Vec<Vec2>, Vec<Built>, usize)> {
        let na = self.active.len();
        let direction = |(dirs, built): &Tangents, d: &[f64]| {
            let column = |j: usize| {
                let h = 1e-6;
                let at = |h| self.joint_moved((dirs, self.slots, built), j, h);
                difference_column(at(h), at(-h), d, h)
            };
            let columns: Vec<Option<Vec<f64>>> = if na >= 4 {
                self.active.par_iter().map(|&j| column(j)).collect()
            } else {
                self.active.iter().map(|&j| column(j)).collect()
            };
            let mut jac = DMatrix::<f64>::zeros(na, na);
            for (k, c) in columns.into_iter().enumerate() {
                for (r, v) in c?.into_iter().enumerate() {
                    jac[(r, k)] = v;
                }
            }
            let step = jac
                .lu()
                .solve(&DVector::from_iterator(na, d.iter().map(|v| -v)))?;
            let big = step.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let lam = if big > 0.3 { 0.3 / big } else { 1.0 };
            Some((step.iter().copied().collect::<Vec<f64>>(), lam))
        };
        let trial = |(dirs, _): &Tangents, step: &[f64], lam: f64| {
            let trial = self.turned(dirs, step, lam);
            let b2 = build_all(self.slots, self.pts, &trial).ok()?;
            let d2 = self.mismatches(&b2);
            Some(((trial, b2), d2))
        };
        let converged =
            |(_, built): &Tangents, _: &[f64]| self.own(built) <= self.opts.g2_tolerance;
        let d = self.mismatches(&built);
        let run = crate::solve::systems::damped_newton(
            (dirs, built),
            d,
            direction,
            trial,
            converged,
            &self.newton(),
        )?;
        let (dirs, built) = run.state;
        Ok((dirs, built, run.iterations))
    }

    /// Stage 2, when the joint tangents alone leave a jump: the α of every LAC piece next
    /// to a joint that still jumps joins the unknowns (a joint between an inflection-end
    /// piece, whose end curvature its triangle fixes, and a short piece whose least-squares
    /// α sits on its bound can have no tangent that matches). More unknowns than equations:
    /// the minimum-norm Gauss–Newton step (α weighted by [`ALPHA_WEIGHT`]), α kept within
    /// [`ALPHA_RANGE`], the same merit and line search as stage 1. Updates `dirs` and
    /// `built`; returns the iterations.
    fn alphas(&self, dirs: &mut [Vec2], built: &mut Vec<Built>) -> Result<usize> {
        let free = self.free_pieces(built);
        if free.is_empty() {
            return Ok(0);
        }
        let (local, start) = self.alpha_start(&free, dirs, built);
        if let Some(b2) = start {
            *built = b2;
        }
        let d0 = self.mismatches(built);
        let direction = |state: &WithAlphas, d: &[f64]| self.alpha_step(&free, state, d);
        let trial = |(dirs, local, _): &WithAlphas, step: &[f64], lam: f64| {
            let trial = self.turned(dirs, step, lam);
            let na = self.active.len();
            let mut tl = local.clone();
            for (k, &i) in free.iter().enumerate() {
                let a = tl[i].alpha.unwrap_or(1.0) + lam * step[na + k];
                tl[i].alpha = Some(a.clamp(ALPHA_RANGE.0, ALPHA_RANGE.1));
            }
            let b2 = build_all(&tl, self.pts, &trial).ok()?;
            let d2 = self.mismatches(&b2);
            Some(((trial, tl, b2), d2))
        };
        let converged =
            |(_, _, built): &WithAlphas, _: &[f64]| self.own(built) <= self.opts.g2_tolerance;
        let run = crate::solve::systems::damped_newton(
            (dirs.to_vec(), local, std::mem::take(built)),
            d0,
            direction,
            trial,
            converged,
            &self.newton(),
        )?;
        let (new_dirs, _, new_built) = run.state;
        dirs.copy_from_slice(&new_dirs);
        *built = new_built;
        Ok(run.iterations)
    }

    /// The LAC pieces (α free) next to an active joint that still jumps, in order.
    fn free_pieces(&self, built: &[Built]) -> Vec<usize> {
        let d = self.mismatches(built);
        let mut free: Vec<usize> = Vec::new();
        for (k, &j) in self.active.iter().enumerate() {
            if d[k].abs() > self.opts.g2_tolerance {
                let (a, b) = sides(j, built.len());
                for i in [a, b] {
                    if built[i].curve.alpha_is_free() && !free.contains(&i) {
                        free.push(i);
                    }
                }
            }
        }
        free.sort_unstable();
        free
    }

    /// The slots with the free pieces' starting α: as built; an α that was outside its
    /// triangle's existence region and moved onto its edge (where an end curvature goes to
    /// 0 or infinity and no derivative helps) starts a tenth of the way from there to 0.5,
    /// which every triangle admits. With the pieces rebuilt when any α changed.
    fn alpha_start(
        &self,
        free: &[usize],
        dirs: &[Vec2],
        built: &[Built],
    ) -> (Vec<Slot>, Option<Vec<Built>>) {
        let mut local: Vec<Slot> = self.slots.to_vec();
        for &i in free {
            let a = built[i].alpha;
            let snapped = self.slots[i].alpha.is_some_and(|s| (s - a).abs() > 1e-9);
            local[i].alpha = Some(if snapped { a + 0.1 * (0.5 - a) } else { a });
        }
        let changed = free.iter().any(|&i| local[i].alpha != Some(built[i].alpha));
        let rebuilt = changed
            .then(|| build_all(&local, self.pts, dirs).ok())
            .flatten();
        (local, rebuilt)
    }

    /// The mismatches with free piece `i`'s α moved by `h`; `None` outside [`ALPHA_RANGE`]
    /// or where the piece moves back inside its existence region (no derivative there).
    fn alpha_moved(&self, (dirs, local, built): &WithAlphas, i: usize, h: f64) -> Option<Vec<f64>> {
        let mut sl = local[i].clone();
        let a = sl.alpha? + h;
        if !(ALPHA_RANGE.0..=ALPHA_RANGE.1).contains(&a) {
            return None;
        }
        sl.alpha = Some(a);
        let mut b2 = built.clone();
        b2[i] = build_piece(&sl, self.pts[i], dirs[i], self.pts[i + 1], dirs[i + 1]).ok()?;
        if (b2[i].alpha - a).abs() > 1e-12 {
            return None;
        }
        Some(self.mismatches(&b2))
    }

    /// Stage 2's step: the minimum-norm step in the weighted unknowns (the active joints'
    /// angles, then the free pieces' α), `x = Jᵀ (J Jᵀ + μ I)⁻¹ (-d)`, and its first length
    /// (angles by at most 0.3 rad, α by at most 1).
    fn alpha_step(&self, free: &[usize], state: &WithAlphas, d: &[f64]) -> Option<(Vec<f64>, f64)> {
        let na = self.active.len();
        let nx = na + free.len();
        let (dirs, local, built) = state;
        let column = |c: usize| -> Vec<f64> {
            let at = |h: f64| {
                if c < na {
                    self.joint_moved((dirs, local, built), self.active[c], h)
                } else {
                    self.alpha_moved(state, free[c - na], h)
                }
            };
            let h = if c < na { 1e-6 } else { 1e-5 };
            // An unknown that can move neither way does not move.
            difference_column(at(h), at(-h), d, h).unwrap_or_else(|| vec![0.0; na])
        };
        let columns: Vec<Vec<f64>> = (0..nx).into_par_iter().map(column).collect();
        let mut jac = DMatrix::<f64>::zeros(na, nx);
        for (c, col) in columns.into_iter().enumerate() {
            let w = if c < na { 1.0 } else { ALPHA_WEIGHT.sqrt() };
            for (r, v) in col.into_iter().enumerate() {
                jac[(r, c)] = v * w;
            }
        }
        let jjt = &jac * jac.transpose();
        let mu = 1e-12 * jjt.trace().max(f64::MIN_POSITIVE);
        let y = (jjt + DMatrix::identity(na, na) * mu)
            .lu()
            .solve(&DVector::from_iterator(na, d.iter().map(|v| -v)))?;
        let mut step = jac.transpose() * y;
        for c in na..nx {
            step[c] *= ALPHA_WEIGHT.sqrt();
        }
        let big_angle = (0..na).fold(0.0f64, |m, c| m.max(step[c].abs()));
        let big_alpha = (na..nx).fold(0.0f64, |m, c| m.max(step[c].abs()));
        let lam = 1.0f64
            .min(0.3 / big_angle.max(1e-300))
            .min(1.0 / big_alpha.max(1e-300));
        Some((step.iter().copied().collect::<Vec<f64>>(), lam))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sketch::slot::Cut;

    /// Two LAC pieces through (0, 0), (10, 3), (20, 0) (α 1 and -1) with the tangents given
    /// by their angles at the three points.
    fn two_pieces(angles: [f64; 3]) -> (Vec<Slot>, Vec<Point>, Vec<Vec2>) {
        let slot = |alpha: f64, cut_a: Cut, cut_b: Cut| Slot {
            ua: 0.0,
            ub: 1.0,
            cut_a,
            cut_b,
            alpha: Some(alpha),
            fitted: true,
            dir_a: None,
            dir_b: None,
        };
        let slots = vec![
            slot(1.0, Cut::End, Cut::Other),
            slot(-1.0, Cut::Other, Cut::End),
        ];
        let pts = vec![
            Point::new(0.0, 0.0),
            Point::new(10.0, 3.0),
            Point::new(20.0, 0.0),
        ];
        (
            slots,
            pts,
            angles.iter().map(|a| Vec2::from_angle(*a)).collect(),
        )
    }

    #[test]
    fn fairing_matches_the_curvature_at_a_joint_and_keeps_the_ends() {
        let (slots, pts, mut dirs) = two_pieces([0.5, 0.15, -0.6]);
        let ends = (dirs[0], dirs[2]);
        let opts = SketchOptions::with_tolerance(0.1);
        let before = build_all(&slots, &pts, &dirs).unwrap();
        let jump = |b: &[Built]| (b[1].kappa.0 - b[0].kappa.1).abs() / curvature_scale(b);
        assert!(
            jump(&before) > 0.01,
            "the start is not G2: {}",
            jump(&before)
        );
        let (built, report) = fair(&slots, &pts, &mut dirs, &opts).unwrap();
        assert!(report.converged && report.iterations >= 1, "{report:?}");
        assert!(report.final_jump <= opts.g2_tolerance, "{report:?}");
        assert!((report.initial_jump - jump(&before)).abs() < 1e-12);
        // The report is the built pieces' own mismatch; only the joint's tangent moved.
        assert!((jump(&built) - report.final_jump).abs() < 1e-15);
        assert_eq!((dirs[0], dirs[2]), ends);
        assert!(dirs[1].cross(Vec2::from_angle(0.15)).abs() > 1e-6);
    }

    #[test]
    fn fairing_that_cannot_move_says_so() {
        // No iteration allowed: the report says the jump is still there.
        let (slots, pts, mut dirs) = two_pieces([0.5, 0.15, -0.6]);
        let opts = SketchOptions {
            max_fairing_iterations: 0,
            ..SketchOptions::with_tolerance(0.1)
        };
        let start = dirs.clone();
        let (_, report) = fair(&slots, &pts, &mut dirs, &opts).unwrap();
        assert!(!report.converged && report.final_jump > 0.01, "{report:?}");
        assert_eq!(dirs[1], start[1]);
    }
}
