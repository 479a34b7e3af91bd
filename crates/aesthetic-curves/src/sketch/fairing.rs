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

/// Step 4: G2 fairing by Newton on the active joints' tangent angles.
pub(super) fn fair(
    slots: &[Slot],
    pts: &[Point],
    dirs: &mut [Vec2],
    opts: &SketchOptions,
) -> Result<(Vec<Built>, FairingReport)> {
    let m = slots.len();
    let built = build_all(slots, pts, dirs)?;
    // Joints where both sides are inflection ends have zero curvature on both sides; every
    // other joint (an inflection cut whose piece could not be an inflection piece too) is
    // faired.
    let zero_both = |built: &[Built], j: usize| {
        let (a, b) = sides(j, m);
        built[a].curve.zero_curvature_ends()[1] && built[b].curve.zero_curvature_ends()[0]
    };
    // A closed curve's seam (joint 0) is faired too.
    let first = usize::from(!opts.closed);
    let faired =
        |built: &[Built]| -> Vec<usize> { (first..m).filter(|&j| !zero_both(built, j)).collect() };
    let active = faired(&built);
    // The merit's scale stays that of the first build: measured against the trial's own
    // largest curvature, a step that blows one free end up into a hook (a triangle at the
    // edge of its existence region) would shrink every relative mismatch and be accepted.
    let scale = curvature_scale(&built);
    let d = mismatches(&built, &active, scale);
    let initial = max_abs(&d);
    let na = active.len();
    let tol = opts.g2_tolerance;
    // Newton on the active joints' tangent angles (the solver layer's damped Newton); the
    // state is the tangent directions and the pieces built on them.
    let direction = |(dirs, built): &(Vec<Vec2>, Vec<Built>), d: &[f64]| {
        // Finite-difference Jacobian: joint k's angle moves pieces active[k]-1 and active[k].
        // Central difference; one-sided where a side leaves the admissible set. The columns
        // are independent: computed in parallel (the same numbers in any order).
        let column = |j: usize| -> Option<Vec<f64>> {
            let at = |h: f64| -> Option<Vec<f64>> {
                let mut trial = dirs.to_vec();
                turn_joint(&mut trial, j, h);
                let mut b2 = built.clone();
                rebuild_joint(&mut b2, (slots, pts, &trial), j)?;
                Some(mismatches(&b2, &active, scale))
            };
            let h = 1e-6;
            difference_column(at(h), at(-h), d, h)
        };
        let columns: Vec<Option<Vec<f64>>> = if na >= 4 {
            active.par_iter().map(|&j| column(j)).collect()
        } else {
            active.iter().map(|&j| column(j)).collect()
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
    let trial = |(dirs, _): &(Vec<Vec2>, Vec<Built>), step: &[f64], lam: f64| {
        let mut trial = dirs.to_vec();
        for (k, &j) in active.iter().enumerate() {
            turn_joint(&mut trial, j, lam * step[k]);
        }
        let b2 = build_all(slots, pts, &trial).ok()?;
        let d2 = mismatches(&b2, &active, scale);
        Some(((trial, b2), d2))
    };
    // Converged by the measure of the final report: over the build's own curvature.
    let own = |built: &[Built]| max_abs(&mismatches(built, &active, curvature_scale(built)));
    let converged = |(_, built): &(Vec<Vec2>, Vec<Built>), _: &[f64]| own(built) <= tol;
    let newton = crate::solve::systems::DampedNewton {
        max_iterations: opts.max_fairing_iterations,
        halvings: 30,
    };
    let run = crate::solve::systems::damped_newton(
        (dirs.to_vec(), built),
        d,
        direction,
        trial,
        converged,
        &newton,
    )?;
    let (new_dirs, mut built) = run.state;
    dirs.copy_from_slice(&new_dirs);
    let final_jump = own(&built);
    let mut report = FairingReport {
        iterations: run.iterations,
        initial_jump: initial,
        final_jump,
        converged: final_jump <= tol,
    };
    if !report.converged {
        free_alphas(
            slots,
            pts,
            dirs,
            opts,
            &active,
            scale,
            &mut built,
            &mut report,
        )?;
    }
    // The report covers every joint of the result: a step can turn a piece next to a joint
    // left out (zero curvature on both sides) into an ordinary one, whose end curvature
    // there is not zero.
    report.final_jump = max_abs(&mismatches(
        &built,
        &faired(&built),
        curvature_scale(&built),
    ));
    report.converged = report.final_jump <= opts.g2_tolerance;
    Ok((built, report))
}

/// The fairing's second stage, when the joint tangents alone leave a jump: the α of every
/// LAC piece next to a joint that still jumps joins the unknowns (a joint between an
/// inflection-end piece, whose end curvature its triangle fixes, and a short piece whose
/// least-squares α sits on its bound can have no tangent that matches). More unknowns than
/// equations: the minimum-norm Gauss–Newton step (α weighted by [`ALPHA_WEIGHT`]), α kept
/// within [`ALPHA_RANGE`], the same merit and line search as the first stage.
#[allow(clippy::too_many_arguments)]
pub(super) fn free_alphas(
    slots: &[Slot],
    pts: &[Point],
    dirs: &mut [Vec2],
    opts: &SketchOptions,
    active: &[usize],
    scale: f64,
    built: &mut Vec<Built>,
    report: &mut FairingReport,
) -> Result<()> {
    let na = active.len();
    let tol = opts.g2_tolerance;
    let mut d0 = mismatches(built, active, scale);
    let mut free: Vec<usize> = Vec::new();
    for (k, &j) in active.iter().enumerate() {
        if d0[k].abs() > tol {
            let (a, b) = sides(j, built.len());
            for i in [a, b] {
                if built[i].curve.alpha_is_free() && !free.contains(&i) {
                    free.push(i);
                }
            }
        }
    }
    if free.is_empty() {
        return Ok(());
    }
    free.sort_unstable();
    // α as built; an α that was outside its triangle's existence region and moved onto its
    // edge (where an end curvature goes to 0 or infinity and no derivative helps) starts a
    // tenth of the way from there to 0.5, which every triangle admits.
    let mut local: Vec<Slot> = slots.to_vec();
    for &i in &free {
        let a = built[i].alpha;
        let snapped = slots[i].alpha.is_some_and(|s| (s - a).abs() > 1e-9);
        local[i].alpha = Some(if snapped { a + 0.1 * (0.5 - a) } else { a });
    }
    if free.iter().any(|&i| local[i].alpha != Some(built[i].alpha)) {
        if let Ok(b2) = build_all(&local, pts, dirs) {
            *built = b2;
            d0 = mismatches(built, active, scale);
        }
    }
    let nx = na + free.len();
    type State = (Vec<Vec2>, Vec<Slot>, Vec<Built>);
    let direction = |(dirs, local, built): &State, d: &[f64]| {
        // Columns: the active joints' tangent angles, then the free pieces' α.
        let column = |c: usize| -> Vec<f64> {
            let at = |h: f64| -> Option<Vec<f64>> {
                let mut b2 = built.clone();
                if c < na {
                    let j = active[c];
                    let mut trial = dirs.to_vec();
                    turn_joint(&mut trial, j, h);
                    rebuild_joint(&mut b2, (local, pts, &trial), j)?;
                } else {
                    let i = free[c - na];
                    let mut sl = local[i].clone();
                    let a = sl.alpha? + h;
                    if !(ALPHA_RANGE.0..=ALPHA_RANGE.1).contains(&a) {
                        return None;
                    }
                    sl.alpha = Some(a);
                    b2[i] = build_piece(&sl, pts[i], dirs[i], pts[i + 1], dirs[i + 1]).ok()?;
                    if (b2[i].alpha - a).abs() > 1e-12 {
                        return None; // moved back inside the existence region: no derivative
                    }
                }
                Some(mismatches(&b2, active, scale))
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
        // Minimum-norm step in the weighted unknowns: x = Jᵀ (J Jᵀ + μ I)⁻¹ (-d).
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
    };
    let trial = |(dirs, local, _): &State, step: &[f64], lam: f64| {
        let mut trial = dirs.to_vec();
        for (k, &j) in active.iter().enumerate() {
            turn_joint(&mut trial, j, lam * step[k]);
        }
        let mut tl = local.clone();
        for (k, &i) in free.iter().enumerate() {
            let a = tl[i].alpha.unwrap_or(1.0) + lam * step[na + k];
            tl[i].alpha = Some(a.clamp(ALPHA_RANGE.0, ALPHA_RANGE.1));
        }
        let b2 = build_all(&tl, pts, &trial).ok()?;
        let d2 = mismatches(&b2, active, scale);
        Some(((trial, tl, b2), d2))
    };
    let own = |built: &[Built]| max_abs(&mismatches(built, active, curvature_scale(built)));
    let converged = |(_, _, built): &State, _: &[f64]| own(built) <= tol;
    let newton = crate::solve::systems::DampedNewton {
        max_iterations: opts.max_fairing_iterations,
        halvings: 30,
    };
    let run = crate::solve::systems::damped_newton(
        (dirs.to_vec(), local, std::mem::take(built)),
        d0,
        direction,
        trial,
        converged,
        &newton,
    )?;
    // The final jump and verdict are [`fair`]'s, over every joint of the result.
    report.iterations += run.iterations;
    let (new_dirs, _, new_built) = run.state;
    dirs.copy_from_slice(&new_dirs);
    *built = new_built;
    Ok(())
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
