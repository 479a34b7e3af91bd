//! The G2 problem: unknown tangent angles at the smooth points, one equation per smooth
//! point (the curvature coming in equals the curvature going out), solved by
//! [`crate::solve::systems::damped_newton`] with a Jacobian of forward differences span by span
//! (each span depends on the angles at its two ends only, so a column costs two spans, and
//! the Jacobian is tridiagonal, cyclic for a closed curve: [`Tridiagonal`], O(n) a step),
//! kept from step to step while the steps converge fast (`FrozenJacobian`).
//!
//! A free end (an open curve's first or last point, a corner) has no unknown: its span
//! leaves it as a circular arc (the deviation mirrored from the other end), and a span
//! with two free ends is a line.

use super::clothoid;
use super::span::{self, Solved};
use crate::error::{Error, Result};
use crate::solve::linear::Tridiagonal;
use crate::solve::roots::bisect_by;
use crate::solve::systems::{damped_newton, DampedNewton, System, SystemStop};
use kurbo::Point;
use std::f64::consts::PI;
use std::sync::atomic::{AtomicU64, Ordering};

/// The spans' signed curvatures at their start and end (input units), and where the
/// clothoid's fast path gave them, their derivatives in the span's deviations (`[∂/∂a,
/// ∂/∂b]`, chord units): the Jacobian then needs no span solved again.
#[derive(Clone, Debug, Default)]
struct EndCurvatures {
    kappa: Vec<(f64, f64)>,
    slopes: Vec<Option<Slopes>>,
}

/// A span's end curvatures' derivatives in its start and end deviations (`[∂/∂a, ∂/∂b]`,
/// each the pair at its start and end).
type Slopes = [(f64, f64); 2];

/// A column of the Jacobian that a span adds to: the unknown and the derivatives of the
/// span's end curvatures in it.
type Column = Option<(usize, (f64, f64))>;

/// Step of the forward differences, radians.
const STEP: f64 = 1e-7;

/// The spline's data as the solver sees it.
pub(super) struct Problem<'a> {
    pub(super) points: &'a [Point],
    /// α per span.
    pub(super) alphas: Vec<f64>,
    /// Span `k` runs from point `ends[k].0` to point `ends[k].1`.
    pub(super) ends: Vec<(usize, usize)>,
    /// The unknown's index at each point, `None` at a free end.
    pub(super) unknown: Vec<Option<usize>>,
    /// The points of the unknowns, in order.
    pub(super) smooth: Vec<usize>,
    /// The most each half of an S-span may turn ([`span::HALF_TURN`], or
    /// [`span::WIDE_HALF`] in the wider family the solve falls back on).
    pub(super) half: f64,
    /// Per span, the clothoid's last root A (f64 bits; NaN: none yet): the next solve of
    /// that span, at tangents a Newton step away, starts there.
    pub(super) roots: Vec<AtomicU64>,
    /// Per span, the chord's angle plus the whole turns that its start's and its end's
    /// deviations are measured from ([`Problem::on_branch`]), so that a deviation moves
    /// continuously with its tangent past a half turn; `None`: every deviation wrapped
    /// into (-π, π].
    pub(super) branch: Option<Vec<(f64, f64)>>,
    /// Per span, its chord's angle and length ([`chords_of`]; read at every span solve).
    pub(super) chords: Vec<(f64, f64)>,
}

/// Each span's chord angle and length.
pub(super) fn chords_of(points: &[Point], ends: &[(usize, usize)]) -> Vec<(f64, f64)> {
    ends.iter()
        .map(|&(i, j)| {
            let c = points[j] - points[i];
            (c.y.atan2(c.x), c.hypot())
        })
        .collect()
}

/// The direction angle from `a` to `b`.
fn angle(a: Point, b: Point) -> f64 {
    (b - a).y.atan2((b - a).x)
}

/// `x` wrapped into (-π, π].
pub(super) fn wrap(x: f64) -> f64 {
    let y = x.rem_euclid(2.0 * PI);
    if y > PI {
        y - 2.0 * PI
    } else {
        y
    }
}

impl Problem<'_> {
    /// Whether the curve is closed (a span from the last point back to the first).
    pub(super) fn is_closed(&self) -> bool {
        self.ends.len() == self.points.len()
    }

    /// The same problem (α, corners, unknowns) through other points.
    pub(super) fn with_points<'b>(&self, points: &'b [Point]) -> Problem<'b> {
        self.rebuilt(points, chords_of(points, &self.ends))
    }

    /// The same problem through the same points (their chords kept), with no warm roots
    /// and its deviations wrapped.
    fn fresh(&self) -> Problem<'_> {
        self.rebuilt(self.points, self.chords.clone())
    }

    /// The problem through `points` whose chords are `chords`, with no warm roots and its
    /// deviations wrapped.
    fn rebuilt<'b>(&self, points: &'b [Point], chords: Vec<(f64, f64)>) -> Problem<'b> {
        Problem {
            points,
            half: self.half,
            alphas: self.alphas.clone(),
            ends: self.ends.clone(),
            unknown: self.unknown.clone(),
            smooth: self.smooth.clone(),
            roots: self
                .roots
                .iter()
                .map(|_| AtomicU64::new(f64::NAN.to_bits()))
                .collect(),
            branch: None,
            chords,
        }
    }

    /// The same problem with its deviations measured from the whole turns that put each
    /// one at `theta` nearest `near`'s (per span, start and end; zero where `None`: the
    /// wrapped deviations). A Newton run keeps the branch of its start, so a tangent
    /// turning past a half turn from its chord stays on the curve it was (libspiro's
    /// spans through sharp turns wind so); a continuation's step takes the last step's
    /// deviations as `near`.
    pub(super) fn on_branch(&self, theta: &[f64], near: Option<&[(f64, f64)]>) -> Problem<'_> {
        let turns = |p: usize, g: f64, d: f64| match self.unknown[p] {
            Some(u) => g + 2.0 * PI * ((theta[u] - g - d) / (2.0 * PI)).round(),
            None => g,
        };
        let branch = (0..self.ends.len())
            .map(|k| {
                let (i, j) = self.ends[k];
                let g = self.chord_angle(k);
                let (da, db) = near.map_or((0.0, 0.0), |n| n[k]);
                (turns(i, g, da), turns(j, g, db))
            })
            .collect();
        Problem {
            branch: Some(branch),
            ..self.fresh()
        }
    }

    /// The problem `sol` solved: in its family of spans, on its branch.
    pub(super) fn solved_as(&self, sol: &Solution) -> Problem<'_> {
        let family = if sol.wide {
            self.widened()
        } else {
            self.fresh()
        };
        Problem {
            branch: sol.branch.clone(),
            ..family
        }
    }

    /// Every span's deviations at `theta`.
    pub(super) fn all_deviations(&self, theta: &[f64]) -> Vec<(f64, f64)> {
        (0..self.ends.len())
            .map(|k| self.deviations(k, theta))
            .collect()
    }

    /// The same problem in the wider family of spans ([`span::WIDE_HALF`]).
    pub(super) fn widened(&self) -> Problem<'_> {
        Problem {
            half: span::WIDE_HALF,
            ..self.fresh()
        }
    }

    /// The solution where it is known: points on a line (every tangent along it) or, for
    /// a closed curve, on a circle (the circle's tangents).
    pub(super) fn known_solution(&self) -> Vec<f64> {
        if self.is_closed() {
            return self.circle_guess();
        }
        let line = angle(self.points[0], self.points[self.points.len() - 1]);
        vec![line; self.smooth.len()]
    }

    fn chord_angle(&self, k: usize) -> f64 {
        self.chords[k].0
    }

    fn chord_length(&self, k: usize) -> f64 {
        self.chords[k].1
    }

    /// The deviations (a, b) of span `k` from its chord at tangent angles `theta`.
    pub(super) fn deviations(&self, k: usize, theta: &[f64]) -> (f64, f64) {
        let (i, j) = self.ends[k];
        let g = self.chord_angle(k);
        // On a branch, from the chord angle plus the whole turns of each end; else wrapped.
        let from = self.branch.as_ref().map(|b| b[k]);
        let at = |p: usize, from: Option<f64>| {
            self.unknown[p].map(|u| from.map_or_else(|| wrap(theta[u] - g), |f| theta[u] - f))
        };
        match (at(i, from.map(|f| f.0)), at(j, from.map(|f| f.1))) {
            (Some(a), Some(b)) => (a, b),
            (Some(a), None) => (a, -a),
            (None, Some(b)) => (-b, b),
            (None, None) => (0.0, 0.0),
        }
    }

    /// Span `k` solved at tangent angles `theta`, its curvatures in input units.
    pub(super) fn span(&self, k: usize, theta: &[f64]) -> Result<Solved> {
        let (a, b) = self.deviations(k, theta);
        let mut s = span::solve(self.alphas[k], a, b, self.half)?;
        let l = self.chord_length(k);
        s.kappa = (s.kappa.0 / l, s.kappa.1 / l);
        Ok(s)
    }

    /// Span `k`'s end curvatures at `theta` (input units) and their slopes: at α = -1 the
    /// clothoid's fast path where it answers ([`clothoid::span`]), else the general span's
    /// (no slopes).
    fn kappa(&self, k: usize, theta: &[f64]) -> Result<((f64, f64), Option<Slopes>)> {
        if let Some(c) = self.clothoid(k, theta) {
            let l = self.chord_length(k);
            return Ok(((c.kappa.0 / l, c.kappa.1 / l), Some(c.d)));
        }
        self.span(k, theta).map(|s| (s.kappa, None))
    }

    /// Span `k` at `theta` by the clothoid's fast path, where its α is -1 and its tangents
    /// leave the chord by less than a half turn (the general path's own limit).
    fn clothoid(&self, k: usize, theta: &[f64]) -> Option<clothoid::Clothoid> {
        // The wider family may hold two spans for one pair of tangents; the fast path's
        // root need not be the general path's choice, which builds the pieces.
        if self.alphas[k] != -1.0 || self.half != span::HALF_TURN {
            return None;
        }
        let (a, b) = self.deviations(k, theta);
        if !(a.abs() < PI && b.abs() < PI) {
            return None;
        }
        let warm = f64::from_bits(self.roots[k].load(Ordering::Relaxed));
        let c = clothoid::span(a, b, Some(warm))?;
        self.roots[k].store(c.root.to_bits(), Ordering::Relaxed);
        Some(c)
    }

    /// The spans' end curvatures at `theta`.
    fn kappas(&self, theta: &[f64]) -> Result<EndCurvatures> {
        let mut out = EndCurvatures::default();
        for k in 0..self.ends.len() {
            let (kappa, slopes) = self.kappa(k, theta)?;
            out.kappa.push(kappa);
            out.slopes.push(slopes);
        }
        Ok(out)
    }

    /// The span ending at point `p` and the one starting there (both exist at a smooth
    /// point: span k runs from point k to point k + 1, the last of a closed curve back to 0).
    fn around(&self, p: usize) -> (usize, usize) {
        let spans = self.ends.len();
        ((p + spans - 1) % spans, p)
    }

    /// The length that makes a curvature jump at point `p` dimensionless: the mean of the
    /// chords on either side.
    fn length_at(&self, p: usize) -> f64 {
        let (i, o) = self.around(p);
        0.5 * (self.chord_length(i) + self.chord_length(o))
    }

    /// The residuals: at each smooth point, (κ in - κ out) times its length.
    fn residuals(&self, kappas: &[(f64, f64)]) -> Vec<f64> {
        self.smooth
            .iter()
            .map(|&p| {
                let (i, o) = self.around(p);
                (kappas[i].1 - kappas[o].0) * self.length_at(p)
            })
            .collect()
    }

    /// The spans' end curvatures and the residuals at `theta`, or `None` where a span
    /// cannot be built.
    fn state(&self, theta: &[f64]) -> Option<(EndCurvatures, Vec<f64>)> {
        let k = self.kappas(theta).ok()?;
        let r = self.residuals(&k.kappa);
        Some((k, r))
    }

    /// The Jacobian at `theta` (end curvatures `kappas` there), span by span: each span's
    /// end curvatures move with the tangent angles at its two ends only, and enter the
    /// residuals at those two points.
    fn jacobian(&self, theta: &[f64], spans: &EndCurvatures) -> Option<Tridiagonal> {
        let mut jac = Tridiagonal::zeros(self.smooth.len());
        for k in 0..self.ends.len() {
            let (a, b) = self.ends[k];
            for (u, d) in self.slopes(k, theta, spans)?.into_iter().flatten() {
                // κ at the span's end enters the residual at b (as κ in), its start at a
                // (as minus κ out).
                if let Some(r) = self.unknown[b] {
                    jac.add(r, u, d.1 * self.length_at(b));
                }
                if let Some(r) = self.unknown[a] {
                    jac.add(r, u, -d.0 * self.length_at(a));
                }
            }
        }
        Some(jac)
    }

    /// The derivatives of span `k`'s end curvatures (`kappa` at `theta`) in the unknown
    /// angle at its start and at its end (where those are unknowns): the clothoid's own
    /// at α = -1 (its deviations move with the angles, a free end's mirrored one against
    /// them), else forward differences of [`STEP`] (the residuals themselves are exact, so
    /// Newton still converges, by a factor of about 1e-7 a step once close; backward where
    /// a span cannot be built forward).
    fn slopes(&self, k: usize, theta: &[f64], spans: &EndCurvatures) -> Option<[Column; 2]> {
        let (i, j) = self.ends[k];
        let (ui, uj) = (self.unknown[i], self.unknown[j]);
        let l = self.chord_length(k);
        let kappa = spans.kappa[k];
        if let Some(d) = spans.slopes[k] {
            // (∂a, ∂b) per unit of the angle at the start and at the end.
            let (da_i, db_i) = if uj.is_some() {
                (1.0, 0.0)
            } else {
                (1.0, -1.0)
            };
            let (da_j, db_j) = if ui.is_some() {
                (0.0, 1.0)
            } else {
                (-1.0, 1.0)
            };
            let along = |da: f64, db: f64| {
                (
                    (d[0].0 * da + d[1].0 * db) / l,
                    (d[0].1 * da + d[1].1 * db) / l,
                )
            };
            return Some([
                ui.map(|u| (u, along(da_i, db_i))),
                uj.map(|u| (u, along(da_j, db_j))),
            ]);
        }
        let mut moved = theta.to_vec();
        let mut column = |u: usize| -> Column {
            moved[u] = theta[u] + STEP;
            let (kp, h) = match self.span(k, &moved) {
                Ok(s) => (s.kappa, STEP),
                Err(_) => {
                    moved[u] = theta[u] - STEP;
                    (self.span(k, &moved).ok()?.kappa, -STEP)
                }
            };
            moved[u] = theta[u];
            Some((u, ((kp.0 - kappa.0) / h, (kp.1 - kappa.1) / h)))
        };
        let start = match ui {
            Some(u) => Some(column(u)?),
            None => None,
        };
        let end = match uj {
            Some(u) => Some(column(u)?),
            None => None,
        };
        Some([start, end])
    }

    /// The largest |κ in - κ out| at a smooth point over the largest |κ| of the spans' ends.
    fn jump(&self, kappas: &[(f64, f64)]) -> f64 {
        let big = kappas
            .iter()
            .fold(0.0f64, |m, e| m.max(e.0.abs()).max(e.1.abs()));
        let worst = self.smooth.iter().fold(0.0f64, |m, &p| {
            let (i, o) = self.around(p);
            m.max((kappas[i].1 - kappas[o].0).abs())
        });
        if big > 0.0 {
            worst / big
        } else {
            0.0
        }
    }

    /// The error of the first span that cannot be built at `theta`, naming its points.
    fn first_failure(&self, theta: &[f64]) -> Error {
        for k in 0..self.ends.len() {
            if let Err(e) = self.span(k, theta) {
                let (i, j) = self.ends[k];
                return Error::NoSegment(format!(
                    "the span from point {i} to point {j} cannot start: {} (add a point \
                     between them, or make one a corner)",
                    e.message()
                ));
            }
        }
        Error::NoConvergence("the starting tangents give no spline".into())
    }

    /// Starting tangents at each smooth point: the tangent of the circle through it and its
    /// two neighbours (the chord-tangent angle equals the inscribed angle).
    fn circle_guess(&self) -> Vec<f64> {
        self.smooth
            .iter()
            .map(|&p| {
                let (prev, next) = self.neighbours(p);
                let gi = angle(self.points[prev], self.points[p]);
                let go = angle(self.points[p], self.points[next]);
                gi + wrap(go - gi) - wrap(angle(self.points[prev], self.points[next]) - gi)
            })
            .collect()
    }

    /// Starting tangents at each smooth point: the direction from its previous neighbour to
    /// its next (where a circle's tangent makes a span turn too far: a long closing chord).
    fn bisector_guess(&self) -> Vec<f64> {
        self.smooth
            .iter()
            .map(|&p| {
                let (prev, next) = self.neighbours(p);
                angle(self.points[prev], self.points[next])
            })
            .collect()
    }

    /// The points before and after point `p`.
    fn neighbours(&self, p: usize) -> (usize, usize) {
        let (i, o) = self.around(p);
        (self.ends[i].0, self.ends[o].1)
    }

    /// `theta` with the tangent at each smooth end of a span that cannot be built taken
    /// from its other span as if it were a free end there: that span a circular arc from
    /// its other end's tangent. A long span across a thin shape (S2's zig-zag closed: its
    /// closing chord) then starts as the S whose halves turn back along the short spans,
    /// near the root libspiro finds, where the circles' tangents ask it to turn 320°.
    fn mended(&self, theta: &[f64]) -> Vec<f64> {
        let mut out = theta.to_vec();
        let spans = self.ends.len();
        for k in (0..spans).filter(|&k| self.span(k, theta).is_err()) {
            let (i, j) = self.ends[k];
            for p in [i, j] {
                let Some(u) = self.unknown[p] else { continue };
                // The other span at p, and whether p is its start.
                let (before, after) = self.around(p);
                let (other, p_starts) = if before == k {
                    (after, true)
                } else {
                    (before, false)
                };
                if other == k {
                    continue;
                }
                let (a, b) = self.deviations(other, theta);
                let g = self.chord_angle(other);
                out[u] = if p_starts { g - b } else { g - a };
            }
            self.shrink_to_build(k, &mut out);
        }
        out
    }

    /// Span `k`'s end tangents turned towards its chord, both by the same share of their
    /// deviations, the least that builds it (bisection to 2⁻³⁰), if it cannot be built.
    fn shrink_to_build(&self, k: usize, theta: &mut [f64]) {
        if self.span(k, theta).is_ok() {
            return;
        }
        let (i, j) = self.ends[k];
        let g = self.chord_angle(k);
        let (a, b) = self.deviations(k, theta);
        let at = |share: f64, theta: &mut [f64]| {
            if let Some(u) = self.unknown[i] {
                theta[u] = g + share * a;
            }
            if let Some(u) = self.unknown[j] {
                theta[u] = g + share * b;
            }
        };
        let share = bisect_by(
            |share| {
                let mut trial = theta.to_vec();
                at(share, &mut trial);
                self.span(k, &trial).ok()
            },
            0.0,
            1.0,
            |a, b| 0.5 * (a + b),
            |a, b| (a - b).abs() <= 2f64.powi(-30),
            30,
        )
        .inside;
        at(share, theta);
    }
}

/// How the solve ended.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Solution {
    pub(super) theta: Vec<f64>,
    pub(super) iterations: usize,
    pub(super) stop: SystemStop,
    /// Largest |κ in - κ out| over the largest |κ| at any span end.
    pub(super) jump: f64,
    /// Solved in the wider family of spans ([`span::WIDE_HALF`]; read from the problem
    /// solved): the pieces are built in it too.
    pub(super) wide: bool,
    /// The branch of the deviations solved on ([`Problem::on_branch`]).
    pub(super) branch: Option<Vec<(f64, f64)>>,
}

/// The Jacobian kept from one Newton step to the next while the steps converge fast (each
/// residual norm at most [`FrozenJacobian::REUSE_BELOW`] of the one before: near the root,
/// where Newton's steps are quadratic, the old Jacobian still contracts by orders of
/// magnitude a step, and a step then costs one span solve each instead of three); formed
/// anew otherwise (Shamanskii's variant of Newton's method).
struct FrozenJacobian {
    jacobian: Option<Tridiagonal>,
    last_norm: f64,
    /// Whether a Jacobian may be kept at all.
    keep: bool,
    /// Steps that kept one.
    reused: usize,
}

impl Default for FrozenJacobian {
    fn default() -> Self {
        FrozenJacobian {
            jacobian: None,
            last_norm: 0.0,
            keep: true,
            reused: 0,
        }
    }
}

impl FrozenJacobian {
    const REUSE_BELOW: f64 = 0.05;

    /// The Jacobian for residuals `r`: the kept one, or `form()`'s.
    fn at(
        &mut self,
        r: &[f64],
        form: impl FnOnce() -> Option<Tridiagonal>,
    ) -> Option<&Tridiagonal> {
        let norm = r.iter().map(|x| x * x).sum::<f64>().sqrt();
        let fast = self.keep && norm <= Self::REUSE_BELOW * self.last_norm;
        self.last_norm = norm;
        if fast && self.jacobian.is_some() {
            self.reused += 1;
        } else {
            self.jacobian = Some(form()?);
        }
        self.jacobian.as_ref()
    }
}

/// How a Newton run measures the spans' deviations from their chords.
#[derive(Clone, Copy)]
pub(super) enum Branch<'n> {
    /// Each wrapped into (-π, π] (a span's tangent never more than a half turn from its
    /// chord).
    Wrapped,
    /// On the branch of the start ([`Problem::on_branch`]): continuous with the tangents,
    /// past a half turn where a span winds.
    Start,
    /// On the branch nearest these deviations (a continuation's last step's).
    Near(&'n [(f64, f64)]),
}

/// Solve the G2 equations from the circle guess to `tol` (largest jump over the largest
/// curvature); where Newton stops short from there, or no start builds, in the wider
/// family of spans from the same start, then by continuation from an easy version of the
/// problem ([`super::continuation`]): first with every deviation wrapped, then on
/// branches where a span may wind past a half turn (libspiro's solutions through sharp
/// turns do; tried last, as their Newton runs may wander to such a span where a plain
/// one exists).
pub(super) fn solve(problem: &Problem, tol: f64, max_iterations: usize) -> Result<Solution> {
    solve_in(problem, tol, max_iterations, true)
}

/// [`solve`] with its rescues (`rescue`: the wider family and the continuations), or the
/// Newton run from the first start that builds alone (its stop reported in the solution).
pub(super) fn solve_in(
    problem: &Problem,
    tol: f64,
    max_iterations: usize,
    rescue: bool,
) -> Result<Solution> {
    // The first start whose spans all build: the circles' tangents, those mended where a
    // span cannot be built (tried only then), the bisectors'.
    let circle = problem.circle_guess();
    let builds = |t: &Vec<f64>| problem.state(t).is_some();
    let theta0 = Some(circle.clone())
        .filter(builds)
        .or_else(|| Some(problem.mended(&circle)).filter(builds))
        .or_else(|| Some(problem.bisector_guess()).filter(builds));
    let direct = match &theta0 {
        Some(t) => Some(
            newton_from(problem, (t.clone(), Branch::Wrapped), tol, max_iterations)
                .ok_or_else(|| problem.first_failure(&circle))?,
        ),
        None => None,
    };
    if let Some(d) = direct.as_ref().filter(|d| d.stop == SystemStop::Converged) {
        return Ok(d.clone());
    }
    if !rescue {
        return direct.ok_or_else(|| problem.first_failure(&circle));
    }
    let wide = problem.widened();
    let mut spent = direct.as_ref().map_or(0, |d| d.iterations);
    for winding in [false, true] {
        let branch = if winding {
            Branch::Start
        } else {
            Branch::Wrapped
        };
        let from_start = theta0
            .as_ref()
            .and_then(|t| newton_from(&wide, (t.clone(), branch), tol, max_iterations));
        if let Some(run) = from_start {
            spent += run.iterations;
            if run.stop == SystemStop::Converged {
                return Ok(Solution {
                    iterations: spent,
                    ..run
                });
            }
        }
        if let Some(walked) = super::continuation::solve(&wide, winding, tol, max_iterations) {
            spent += walked.iterations;
            if walked.stop == SystemStop::Converged {
                return Ok(Solution {
                    iterations: spent,
                    ..walked
                });
            }
        }
    }
    direct.ok_or_else(|| problem.first_failure(&circle))
}

/// Newton on the G2 equations from the tangents `theta` (`None` where a span cannot be
/// built there): with the Jacobian kept while the steps converge fast, then, where that
/// stops short, on with a fresh one every step.
pub(super) fn newton_from(
    problem: &Problem,
    (theta, branch): (Vec<f64>, Branch),
    tol: f64,
    max_iterations: usize,
) -> Option<Solution> {
    let on_branch = match branch {
        Branch::Wrapped => None,
        Branch::Start => Some(problem.on_branch(&theta, None)),
        Branch::Near(near) => Some(problem.on_branch(&theta, Some(near))),
    };
    let problem = on_branch.as_ref().unwrap_or(problem);
    let (k0, r0) = problem.state(&theta)?;
    let mut frozen = FrozenJacobian::default();
    let mut run = newton(problem, ((theta, k0), r0), &mut frozen, tol, max_iterations).ok()?;
    if run.stop != SystemStop::Converged && frozen.reused > 0 {
        // A kept Jacobian that led nowhere: on from there with a fresh one every step.
        let mut fresh = FrozenJacobian {
            keep: false,
            ..Default::default()
        };
        let left = max_iterations.saturating_sub(run.iterations);
        let done = run.iterations;
        run = newton(problem, (run.state, run.residuals), &mut fresh, tol, left).ok()?;
        run.iterations += done;
    }
    let (theta, kappas) = run.state;
    Some(Solution {
        jump: problem.jump(&kappas.kappa),
        theta,
        iterations: run.iterations,
        stop: run.stop,
        wide: problem.half != span::HALF_TURN,
        branch: problem.branch.clone(),
    })
}

/// Damped Newton on the G2 equations from `state` (tangents and end curvatures, with their
/// residuals), its Jacobian from `jacobians`.
fn newton(
    problem: &Problem,
    (state, residuals): ((Vec<f64>, EndCurvatures), Vec<f64>),
    jacobians: &mut FrozenJacobian,
    tol: f64,
    max_iterations: usize,
) -> Result<System<(Vec<f64>, EndCurvatures)>> {
    damped_newton(
        state,
        residuals,
        |(theta, kappas), r| {
            let jac = jacobians.at(r, || problem.jacobian(theta, kappas))?;
            let minus: Vec<f64> = r.iter().map(|v| -v).collect();
            Some((jac.solve(&minus)?, 1.0))
        },
        |(theta, _), step, len| {
            // A Newton step may not turn a tangent by more than a quarter turn.
            let big = step.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let len = len * (1.0f64).min(0.5 * PI / big.max(1e-300));
            let t: Vec<f64> = theta.iter().zip(step).map(|(t, s)| t + len * s).collect();
            problem.state(&t).map(|(k, r)| ((t, k), r))
        },
        |(_, kappas), _| problem.jump(&kappas.kappa) <= tol,
        &DampedNewton {
            max_iterations,
            halvings: 30,
        },
    )
}
