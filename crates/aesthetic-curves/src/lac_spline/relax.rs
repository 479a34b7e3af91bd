//! The spline at an α its spans cannot all hold: each span takes the nearest α that can.
//!
//! A log-aesthetic segment of α ≥ 0 never reaches zero curvature, and a segment's turning
//! is bounded, so for some point sets the G2 equations at the requested α have no
//! solution (or none Newton finds), while at α = -1 (clothoids, Spiro's family) the same
//! points solve almost always. So the spline is solved at α = -1 (the anchor) and moved
//! from there:
//!
//! 0. where spans ask for α ≥ 0 ([`held`], tried before the requested α itself): the
//!    spans the anchor builds as a pair of inflection-end halves keep α = -1, every other
//!    span takes its α, in one Newton run from the anchor. At α ≥ 0 an S-span's halves are
//!    clothoid-like anyway, so the spans that stay S-shaped are at their requested α; the
//!    others that keep -1 are the spans whose bend needs an inflection nearby (a lopsided
//!    bend, whose curvature must come near zero at one end);
//! 1. otherwise (α < 0, or that run failed), every span's α moves together from -1
//!    towards its requested value, each step's Newton run starting from the last
//!    solution, the step halved where a run fails and doubled where it succeeds, down to
//!    1/64 of the way;
//! 2. then each span not at its α tries it alone, the others as they are (a span whose
//!    own triangle cannot hold it keeps the α it has).
//!
//! A step's Newton run gets a few iterations ([`STEP_ITERATIONS`]): it starts from a
//! solution of nearby α, and a run that will not converge must fail cheaply. The result
//! says which spans got another α than the requested one, and which. Every answer is a
//! checked spline (G2 solve converged, pieces built and their cubics proven monotone or
//! flagged) at the α values it reports.

use super::span;
use super::system::{self, Branch, Problem, Solution};
use super::{problem_of, LacSplineOptions, ACCEPTED_JUMP};
use crate::solve::systems::SystemStop;
use kurbo::Point;

/// The smallest share of the way from -1 to the requested α a step of the walk takes.
const SMALLEST_STEP: f64 = 1.0 / 64.0;

/// Spans up to this many try their requested α one by one after the walk (each try is a
/// Newton run over the whole spline).
const MOST_SPANS_ONE_BY_ONE: usize = 64;

/// Newton steps at most for one step of the walk or one span's try (each starts from a
/// solution of nearby α: a run that will converge does so in a few steps, and a run that
/// will not should fail cheaply).
const STEP_ITERATIONS: usize = 12;

/// The α every span starts the walk from (the clothoid spline: the family that solves).
pub(super) const ANCHOR: f64 = -1.0;

/// A solve accepted as G2 (as [`super::lac_spline`] accepts one).
pub(super) fn accepted(sol: &Solution) -> bool {
    sol.stop == SystemStop::Converged || sol.jump <= ACCEPTED_JUMP
}

/// The α per span and the solution of the walk from the anchor towards `target` (one α
/// per span), or None when the anchor itself does not solve or nothing is to relax.
/// `held`: [`held`]'s answer, where it had one (the walk then goes on from there).
pub(super) fn walk(
    points: &[Point],
    opts: &LacSplineOptions,
    target: &[f64],
    held: Option<(Vec<f64>, Solution)>,
) -> Option<(Vec<f64>, Solution)> {
    if target.iter().all(|&a| a == ANCHOR) {
        return None;
    }
    let (alphas, sol) = match held {
        Some(h) => h,
        None => {
            let anchor = vec![ANCHOR; target.len()];
            let sol = solve_with(points, opts, &anchor, None)?;
            uniform_walk(points, opts, target, sol)
        }
    };
    Some(one_by_one(points, opts, target, alphas, sol))
}

/// Where some spans ask for α ≥ 0: the clothoid spline (every span at the anchor), then
/// the spans it builds as a pair of inflection-end halves kept at the anchor and every
/// other span at its target, in one Newton run from there. An S-span's halves are
/// clothoid-like at any α ≥ 0 ([`super::span`]), so a span that stays S-shaped is at its
/// target (relabelled so); walking every span's α together instead moves the halves from
/// α = -1 towards 0 and back to -1 at 0, a jump no Newton step takes. `None` where no
/// span asks for α ≥ 0 or a run does not converge.
pub(super) fn held(
    points: &[Point],
    opts: &LacSplineOptions,
    target: &[f64],
) -> Option<(Vec<f64>, Solution)> {
    if !target.iter().any(|&a| a >= 0.0) {
        return None;
    }
    let anchor_alphas = vec![ANCHOR; target.len()];
    let anchor = solve_with(points, opts, &anchor_alphas, None)?;
    let pairs = paired(points, opts, &anchor_alphas, &anchor)?;
    let alphas: Vec<f64> = (0..target.len())
        .map(|k| {
            if pairs[k] && target[k] >= 0.0 {
                ANCHOR
            } else {
                target[k]
            }
        })
        .collect();
    let sol = solve_with(points, opts, &alphas, Some(&anchor))?;
    let alphas = relabelled(points, opts, target, alphas, &sol);
    Some((alphas, sol))
}

/// Which spans the solution `sol` of the problem with `alphas` builds as a pair of
/// inflection-end halves.
fn paired(
    points: &[Point],
    opts: &LacSplineOptions,
    alphas: &[f64],
    sol: &Solution,
) -> Option<Vec<bool>> {
    per_span(points, opts, alphas, sol, |p, theta, k| {
        let s = p.span(k, theta).ok()?;
        Some(matches!(s.shape, span::Shape::Pair { .. }))
    })
}

/// `f` of every span of the problem with `alphas` as `sol` solved it (in its family, on its
/// branch), at `sol`'s tangents.
fn per_span<T>(
    points: &[Point],
    opts: &LacSplineOptions,
    alphas: &[f64],
    sol: &Solution,
    f: impl Fn(&Problem, &[f64], usize) -> Option<T>,
) -> Option<Vec<T>> {
    let problem = problem_of(points, &with_alphas(opts, alphas)).ok()?;
    let solved = problem.solved_as(sol);
    (0..alphas.len())
        .map(|k| f(&solved, &sol.theta, k))
        .collect()
}

/// `opts` with α per span.
fn with_alphas(opts: &LacSplineOptions, alphas: &[f64]) -> LacSplineOptions {
    LacSplineOptions {
        span_alphas: Some(alphas.to_vec()),
        ..opts.clone()
    }
}

/// Which spans the solution `sol` of the problem with `alphas` holds S-shaped (tangent
/// deviations from the chord of one sign, or one of them zero: [`super::span::solve`]
/// builds those as a pair of inflection-end halves whatever α ≥ 0 they ask).
fn s_shaped(
    points: &[Point],
    opts: &LacSplineOptions,
    alphas: &[f64],
    sol: &Solution,
) -> Option<Vec<bool>> {
    per_span(points, opts, alphas, sol, |p, theta, k| {
        let (a, b) = p.deviations(k, theta);
        Some(a * b >= 0.0)
    })
}

/// `alphas` with each span whose curve is the one its target α builds named by its target:
/// an S-shaped span held at α = -1 whose target is α ≥ 0 (both give the same halves).
fn relabelled(
    points: &[Point],
    opts: &LacSplineOptions,
    target: &[f64],
    mut alphas: Vec<f64>,
    sol: &Solution,
) -> Vec<f64> {
    let Some(s) = s_shaped(points, opts, &alphas, sol) else {
        return alphas;
    };
    for k in 0..alphas.len() {
        if s[k] && target[k] >= 0.0 && span::pair_alpha(alphas[k]) == span::pair_alpha(target[k]) {
            alphas[k] = target[k];
        }
    }
    alphas
}

/// Every span's α moved together from the anchor towards its target (module
/// documentation, step 1), from the anchor's solution `sol`.
fn uniform_walk(
    points: &[Point],
    opts: &LacSplineOptions,
    target: &[f64],
    mut sol: Solution,
) -> (Vec<f64>, Solution) {
    let mix = |t: f64| -> Vec<f64> {
        if t >= 1.0 {
            return target.to_vec();
        }
        target.iter().map(|&a| ANCHOR + t * (a - ANCHOR)).collect()
    };
    let (mut t, mut step) = (0.0f64, 1.0f64);
    while t < 1.0 && step >= SMALLEST_STEP {
        let next = (t + step).min(1.0);
        match solve_with(points, opts, &mix(next), Some(&sol)) {
            Some(s) => {
                sol = s;
                t = next;
                step = (2.0 * step).min(1.0);
            }
            // Halved from the step just tried (clipped at the end of the way).
            None => step = 0.5 * (next - t),
        }
    }
    (mix(t), sol)
}

/// Each span not at its target tries it alone, the others as they are (module
/// documentation, step 2); a span whose own triangle cannot hold it keeps its α.
fn one_by_one(
    points: &[Point],
    opts: &LacSplineOptions,
    target: &[f64],
    mut alphas: Vec<f64>,
    mut sol: Solution,
) -> (Vec<f64>, Solution) {
    if target.len() > MOST_SPANS_ONE_BY_ONE {
        return (alphas, sol);
    }
    for k in 0..target.len() {
        if alphas[k] == target[k] {
            continue;
        }
        let mut trial = alphas.clone();
        trial[k] = target[k];
        if let Some(s) = solve_with(points, opts, &trial, Some(&sol)) {
            alphas = relabelled(points, opts, target, trial, &s);
            sol = s;
        }
    }
    (alphas, sol)
}

/// The G2 solve with these α per span: from scratch, or by Newton from a solution of
/// nearby α (in its family and on its branch); None unless accepted.
fn solve_with(
    points: &[Point],
    opts: &LacSplineOptions,
    alphas: &[f64],
    from: Option<&Solution>,
) -> Option<Solution> {
    let problem: Problem = problem_of(points, &with_alphas(opts, alphas)).ok()?;
    let tol = opts.g2_tolerance;
    let sol = match from {
        None => system::solve(&problem, tol, opts.max_iterations).ok()?,
        Some(prev) => {
            let wide = prev.wide.then(|| problem.widened());
            let p = wide.as_ref().unwrap_or(&problem);
            let branch = prev.branch.as_deref().map_or(Branch::Wrapped, Branch::Near);
            let most = opts.max_iterations.min(STEP_ITERATIONS);
            system::newton_from(p, (prev.theta.clone(), branch), tol, most)?
        }
    };
    accepted(&sol).then_some(sol)
}
