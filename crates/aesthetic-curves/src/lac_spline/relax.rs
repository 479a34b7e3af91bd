//! The spline at an α its spans cannot all hold: each span takes the nearest α that can.
//!
//! A log-aesthetic segment of α ≥ 0 never reaches zero curvature, and a segment's turning
//! is bounded, so for some point sets the G2 equations at the requested α have no
//! solution (or none Newton finds), while at α = -1 (clothoids, Spiro's family) the same
//! points solve almost always. So where the requested α fails, the spline is solved at
//! α = -1 and walked towards the requested α span by span:
//!
//! 1. every span's α moves together from -1 towards its requested value, each step's
//!    Newton run starting from the last solution, the step halved where a run fails and
//!    doubled where it succeeds, down to 1/64 of the way;
//! 2. then each span that stopped short tries its requested α alone, the others as they
//!    are (a span whose own triangle cannot hold it keeps the α the walk reached).
//!
//! The result says which spans got another α than the requested one, and which. Every
//! answer is a checked spline (G2 solve converged, pieces built and their cubics proven
//! monotone or flagged) at the α values it reports.

use super::system::{self, Branch, Problem, Solution};
use super::{problem_of, LacSplineOptions, ACCEPTED_JUMP};
use crate::solve::systems::SystemStop;
use kurbo::Point;

/// The smallest share of the way from -1 to the requested α a step of the walk takes.
const SMALLEST_STEP: f64 = 1.0 / 64.0;

/// Spans up to this many try their requested α one by one after the walk (each try is a
/// Newton run over the whole spline).
const MOST_SPANS_ONE_BY_ONE: usize = 64;

/// The α every span starts the walk from (the clothoid spline: the family that solves).
const ANCHOR: f64 = -1.0;

/// A solve accepted as G2 (as [`super::lac_spline`] accepts one).
pub(super) fn accepted(sol: &Solution) -> bool {
    sol.stop == SystemStop::Converged || sol.jump <= ACCEPTED_JUMP
}

/// The α per span and the solution of the walk from the anchor towards `target` (one α
/// per span), or None when the anchor itself does not solve or nothing is to relax.
pub(super) fn walk(
    points: &[Point],
    opts: &LacSplineOptions,
    target: &[f64],
) -> Option<(Vec<f64>, Solution)> {
    if target.iter().all(|&a| a == ANCHOR) {
        return None;
    }
    let anchor = vec![ANCHOR; target.len()];
    let mut sol = solve_with(points, opts, &anchor, None)?;
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
            None => step *= 0.5,
        }
    }
    let mut alphas = mix(t);
    if t < 1.0 && target.len() <= MOST_SPANS_ONE_BY_ONE {
        for k in 0..target.len() {
            let mut trial = alphas.clone();
            trial[k] = target[k];
            if let Some(s) = solve_with(points, opts, &trial, Some(&sol)) {
                alphas = trial;
                sol = s;
            }
        }
    }
    Some((alphas, sol))
}

/// The G2 solve with these α per span: from scratch, or by Newton from a solution of
/// nearby α (in its family and on its branch); None unless accepted.
fn solve_with(
    points: &[Point],
    opts: &LacSplineOptions,
    alphas: &[f64],
    from: Option<&Solution>,
) -> Option<Solution> {
    let o = LacSplineOptions {
        span_alphas: Some(alphas.to_vec()),
        ..opts.clone()
    };
    let problem: Problem = problem_of(points, &o).ok()?;
    let (tol, most) = (opts.g2_tolerance, opts.max_iterations);
    let sol = match from {
        None => system::solve(&problem, tol, most).ok()?,
        Some(prev) => {
            let wide = prev.wide.then(|| problem.widened());
            let p = wide.as_ref().unwrap_or(&problem);
            let branch = prev.branch.as_deref().map_or(Branch::Wrapped, Branch::Near);
            system::newton_from(p, (prev.theta.clone(), branch), tol, most)?
        }
    };
    accepted(&sol).then_some(sol)
}
