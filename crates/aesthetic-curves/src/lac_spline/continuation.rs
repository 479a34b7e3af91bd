//! The G2 solve's globalisation: where Newton from the circles' tangents stops short
//! (closed curves of sharp turns and uneven chords, where the start lies in another
//! basin), the problem is walked to from one whose solution is known, by moving its
//! points. An open curve starts from its points laid out on a line at their chord
//! lengths (every span a line: every tangent the line's), a closed one from its points on
//! a circle at their chord lengths (every span an arc of it), either fitted to the points
//! by a similarity; the points then move straight to their own places in adaptive steps,
//! each solved by Newton from the last tangents (a natural-parameter continuation).

use super::system::{newton_from, Branch, Problem, Solution};
use crate::lac::{cmul, conj};
use crate::solve::systems::SystemStop;
use kurbo::{Point, Vec2};
use std::f64::consts::PI;

/// The smallest step in the homotopy parameter before the walk gives up.
const MIN_STEP: f64 = 1.0 / 4096.0;

/// Newton steps at most for one step of the walk (they start a short step away).
const STEP_ITERATIONS: usize = 12;

/// The jump an intermediate solve must reach: close enough that the next step starts in
/// the basin of its solution, not the final target.
const STEP_TOLERANCE: f64 = 1e-8;

/// Steps of the walk at most (each a Newton run).
const MAX_STEPS: usize = 200;

/// The solution of `problem` reached by continuation from its easy version, if the walk
/// gets there (module documentation); `None` where a step cannot be made small enough.
/// `winding`: each step on the branch of the last step's deviations (a span's tangent
/// may turn past a half turn from its chord as the points move), else every deviation
/// wrapped.
pub(super) fn solve(
    problem: &Problem,
    winding: bool,
    tol: f64,
    max_iterations: usize,
) -> Option<Solution> {
    let closed = problem.is_closed();
    let easy = fitted(problem.points, &laid_out(problem.points, closed));
    let start = problem.with_points(&easy);
    let mut theta = start.known_solution();
    let mut near = start.all_deviations(&theta);
    let (mut t, mut h) = (0.0f64, 0.25f64);
    let mut iterations = 0;
    for _ in 0..MAX_STEPS {
        let next = (t + h).min(1.0);
        let pts: Vec<Point> = easy
            .iter()
            .zip(problem.points)
            .map(|(e, p)| e.lerp(*p, next))
            .collect();
        let last = next >= 1.0;
        let (step_tol, step_max) = if last {
            (tol, max_iterations)
        } else {
            (STEP_TOLERANCE, STEP_ITERATIONS)
        };
        let here = problem.with_points(&pts);
        let branch = if winding {
            Branch::Near(&near)
        } else {
            Branch::Wrapped
        };
        match newton_from(&here, (theta.clone(), branch), step_tol, step_max) {
            Some(sol) if sol.stop == SystemStop::Converged => {
                iterations += sol.iterations;
                if last {
                    return Some(Solution { iterations, ..sol });
                }
                near = here.solved_as(&sol).all_deviations(&sol.theta);
                theta = sol.theta;
                t = next;
                h = (2.0 * h).min(0.5);
            }
            other => {
                if let Some(s) = other {
                    iterations += s.iterations;
                }
                h *= 0.5;
                if h < MIN_STEP {
                    return None;
                }
            }
        }
    }
    None
}

/// The points laid out where the spline's solution is known, at their chord lengths: on a
/// line for an open curve, on a circle (turning the way the polygon does) for a closed one.
fn laid_out(points: &[Point], closed: bool) -> Vec<Point> {
    let n = points.len();
    let chords: Vec<f64> = (0..n)
        .map(|i| (points[(i + 1) % n] - points[i]).hypot())
        .collect();
    let mut along = vec![0.0];
    for c in &chords[..n - 1] {
        along.push(along.last().copied().unwrap_or(0.0) + c);
    }
    if !closed {
        return along.iter().map(|&s| Point::new(s, 0.0)).collect();
    }
    let perimeter: f64 = chords.iter().sum();
    let area2: f64 = (0..n)
        .map(|i| points[i].to_vec2().cross(points[(i + 1) % n].to_vec2()))
        .sum();
    let turn = if area2 < 0.0 { -1.0 } else { 1.0 };
    along
        .iter()
        .map(|&s| {
            let a = turn * 2.0 * PI * s / perimeter;
            Point::new(a.cos(), a.sin())
        })
        .collect()
}

/// `shape` moved, turned and scaled onto `points` (least squares, no reflection).
fn fitted(points: &[Point], shape: &[Point]) -> Vec<Point> {
    let n = points.len() as f64;
    let mean = |ps: &[Point]| ps.iter().fold(Vec2::ZERO, |m, p| m + p.to_vec2()) / n;
    let (mp, ms) = (mean(points), mean(shape));
    // The complex factor a minimising Σ |p - mp - a (s - ms)|²: Σ u v̄ / Σ |v|².
    let (mut uv, mut norm) = (Vec2::ZERO, 0.0);
    for (p, s) in points.iter().zip(shape) {
        let (u, v) = (p.to_vec2() - mp, s.to_vec2() - ms);
        uv += cmul(u, conj(v));
        norm += v.hypot2();
    }
    let a = uv / norm;
    shape
        .iter()
        .map(|s| (mp + cmul(a, s.to_vec2() - ms)).to_point())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_shape_fitted_onto_its_own_similar_copy_lands_on_it() {
        let shape = [
            Point::new(0.0, 0.0),
            Point::new(2.0, 0.0),
            Point::new(1.0, 3.0),
        ];
        // Turned by 0.7 rad, scaled by 2.5, moved.
        let (c, s) = (0.7f64.cos() * 2.5, 0.7f64.sin() * 2.5);
        let pts: Vec<Point> = shape
            .iter()
            .map(|p| Point::new(c * p.x - s * p.y + 4.0, s * p.x + c * p.y - 1.0))
            .collect();
        for (a, b) in fitted(&pts, &shape).iter().zip(&pts) {
            assert!((*a - *b).hypot() < 1e-12, "{a:?} {b:?}");
        }
    }

    #[test]
    fn a_closed_layout_turns_the_way_the_polygon_does() {
        let ccw = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(0.0, 1.0),
        ];
        let cw = [ccw[0], ccw[2], ccw[1]];
        let area = |ps: &[Point]| {
            (0..3)
                .map(|i| ps[i].to_vec2().cross(ps[(i + 1) % 3].to_vec2()))
                .sum::<f64>()
        };
        assert!(area(&laid_out(&ccw, true)) > 0.0);
        assert!(area(&laid_out(&cw, true)) < 0.0);
    }
}
