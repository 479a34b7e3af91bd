//! Minimisers of a few variables: the simplex method of Nelder and Mead ([`nelder_mead`],
//! with its [`NelderMead`] stopping rules), a compass search that keeps to a feasible set
//! ([`compass_search`], [`CompassSearch`]), and a walk along that set's boundary when the
//! minimum lies on it ([`along_boundary`]).
//!
//! [`nelder_mead`] uses the standard coefficients: reflection 1, expansion 2, contraction
//! 1/2, shrink 1/2. It stops when the simplex's spread of values is below
//! `f_tol + f_rel_tol |best|` and its extent below `x_tol`, or its extent below `collapse`
//! whatever the values, or after `max_evaluations`; the returned [`Minimum`] says which.
//! Infeasible points are the caller's to map to a large value (`f64::INFINITY` works: such
//! vertices are always replaced first).

use super::line_search::brent;

/// Stopping rules of [`nelder_mead`].
#[derive(Clone, Copy, Debug)]
pub struct NelderMead {
    /// Stop when the simplex's values differ by at most this plus `f_rel_tol` times the
    /// best value's magnitude,
    pub f_tol: f64,
    /// (see `f_tol`)
    pub f_rel_tol: f64,
    /// ... and its vertices by at most this in every coordinate.
    pub x_tol: f64,
    /// Stop (converged) when the vertices differ by at most this in every coordinate,
    /// whatever their values: the simplex has collapsed to rounding.
    pub collapse: f64,
    /// Most function evaluations.
    pub max_evaluations: usize,
}

impl Default for NelderMead {
    fn default() -> Self {
        NelderMead {
            f_tol: 1e-12,
            f_rel_tol: 0.0,
            x_tol: 1e-8,
            collapse: 0.0,
            max_evaluations: 2000,
        }
    }
}

/// The result of a minimisation.
#[derive(Clone, Debug, PartialEq)]
pub struct Minimum {
    /// The best point found.
    pub x: Vec<f64>,
    /// The function's value there.
    pub value: f64,
    /// Function evaluations spent.
    pub evaluations: usize,
    /// Whether the tolerances were met (false: the evaluation budget ran out first).
    pub converged: bool,
}

/// Minimise `f` from `x0` with initial simplex steps `step` (one per coordinate).
pub fn nelder_mead(
    f: &mut dyn FnMut(&[f64]) -> f64,
    x0: &[f64],
    step: &[f64],
    opts: NelderMead,
) -> Minimum {
    let n = x0.len();
    let mut evals = 0;
    let mut eval = |x: &[f64], evals: &mut usize| {
        *evals += 1;
        let v = f(x);
        if v.is_nan() {
            f64::INFINITY
        } else {
            v
        }
    };
    // Vertices on the stack up to 4 variables (the library's uses have 2 or 3).
    type Vertex = smallvec::SmallVec<[f64; 4]>;
    let mut simplex: Vec<(Vertex, f64)> = Vec::with_capacity(n + 1);
    let v0 = eval(x0, &mut evals);
    simplex.push((Vertex::from_slice(x0), v0));
    for i in 0..n {
        let mut x = Vertex::from_slice(x0);
        x[i] += step[i];
        let v = eval(&x, &mut evals);
        simplex.push((x, v));
    }
    let mut converged = false;
    while evals < opts.max_evaluations {
        simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
        let (best, worst) = (simplex[0].1, simplex[n].1);
        let extent = (0..n)
            .map(|i| {
                simplex
                    .iter()
                    .map(|s| (s.0[i] - simplex[0].0[i]).abs())
                    .fold(0.0, f64::max)
            })
            .fold(0.0, f64::max);
        if (worst - best).abs() <= opts.f_tol + opts.f_rel_tol * best.abs() && extent <= opts.x_tol
            || extent <= opts.collapse
        {
            converged = true;
            break;
        }
        let centroid: Vertex = (0..n)
            .map(|i| simplex[..n].iter().map(|s| s.0[i]).sum::<f64>() / n as f64)
            .collect();
        let along = |t: f64| -> Vertex {
            (0..n)
                .map(|i| centroid[i] + t * (simplex[n].0[i] - centroid[i]))
                .collect()
        };
        let xr = along(-1.0);
        let vr = eval(&xr, &mut evals);
        if vr < simplex[0].1 {
            let xe = along(-2.0);
            let ve = eval(&xe, &mut evals);
            simplex[n] = if ve < vr { (xe, ve) } else { (xr, vr) };
        } else if vr < simplex[n - 1].1 {
            simplex[n] = (xr, vr);
        } else {
            let xc = if vr < worst { along(-0.5) } else { along(0.5) };
            let vc = eval(&xc, &mut evals);
            if vc < worst.min(vr) {
                simplex[n] = (xc, vc);
            } else {
                let b = simplex[0].0.clone();
                for s in simplex.iter_mut().skip(1) {
                    for (x, bx) in s.0.iter_mut().zip(&b) {
                        *x = bx + 0.5 * (*x - bx);
                    }
                    s.1 = eval(&s.0, &mut evals);
                }
            }
        }
    }
    simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
    let (x, value) = simplex.swap_remove(0);
    Minimum {
        x: x.to_vec(),
        value,
        evaluations: evals,
        converged,
    }
}

/// Steps and limits of [`compass_search`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CompassSearch {
    /// The second coordinate's step is the first's times this.
    pub scale: f64,
    /// The first step.
    pub step: f64,
    /// Converged when the step is at most this.
    pub floor: f64,
    /// Most evaluations of the function.
    pub max_evaluations: usize,
}

/// The result of [`compass_search`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Compass {
    /// The best feasible point found.
    pub x: (f64, f64),
    /// The function's value there.
    pub value: f64,
    /// Evaluations spent (the start's not counted: the caller gives its value).
    pub evaluations: usize,
    /// The step the search ended with (0 when it started at 0: nothing searched).
    pub step: f64,
    /// Whether the step fell below the floor (else the evaluation budget ran out).
    pub converged: bool,
}

/// Compass search in two variables: from `start` (value `value`), the eight points at
/// `± step` along each axis and both diagonals (the second coordinate's step times
/// `scale`, all in [`CompassSearch`]); the best one that lowers the value and that `feasible` accepts is taken and the
/// step doubles, else the step halves. Stops when the step is at most `floor` or after
/// `max_evaluations`; the [`Compass`] says which. Derivative-free and monotone: the value
/// never rises, and an infeasible point is never returned.
pub fn compass_search(
    f: &mut dyn FnMut((f64, f64)) -> f64,
    feasible: &dyn Fn((f64, f64)) -> bool,
    (start, value): ((f64, f64), f64),
    opts: &CompassSearch,
) -> Compass {
    let CompassSearch {
        scale,
        step,
        floor,
        max_evaluations,
    } = *opts;
    const DIRECTIONS: [(f64, f64); 8] = [
        (1.0, 0.0),
        (-1.0, 0.0),
        (0.0, 1.0),
        (0.0, -1.0),
        (1.0, 1.0),
        (-1.0, -1.0),
        (1.0, -1.0),
        (-1.0, 1.0),
    ];
    let (mut x, mut value, mut h) = (start, value, step);
    let mut evaluations = 0;
    while h > floor && evaluations < max_evaluations {
        let mut best = (value, x);
        for (d0, d1) in DIRECTIONS {
            let y = (x.0 + d0 * h, x.1 + scale * d1 * h);
            let c = f(y);
            evaluations += 1;
            if c < best.0 && feasible(y) {
                best = (c, y);
            }
        }
        if best.0 < value {
            (value, x) = best;
            h *= 2.0;
        } else {
            h *= 0.5;
        }
    }
    Compass {
        x,
        value,
        evaluations,
        step: h,
        converged: h <= floor,
    }
}

/// Minimise a smooth `cost` of two variables over the set where `feasible` holds, from a
/// point `x` on that set's boundary where the cost keeps falling outwards: the constrained
/// minimum then lies on the boundary, which pattern searches with fixed directions cannot
/// follow once it runs between their directions.
///
/// The boundary is walked as a curve: `u` is the cost's descent direction at `x` (central
/// differences, step 1e-7 in the coordinates scaled by `scale`), the boundary near the line
/// `x + s t` (t perpendicular to u) is found by bisection along u, and Brent's method
/// minimises the cost of that boundary point over `s`, in a bracket grown until the cost
/// rises. Up to `rounds` walks, each from the last one's end (a curved boundary). Returns
/// None when the constraint is not active at `x` (a feasible step downhill exists) or no
/// walk improves; else the feasible point, its cost and the evaluations of `cost`.
pub fn along_boundary(
    cost: &dyn Fn((f64, f64)) -> f64,
    feasible: &dyn Fn((f64, f64)) -> bool,
    x: (f64, f64),
    scale: (f64, f64),
    rounds: usize,
) -> Option<((f64, f64), f64, usize)> {
    let at =
        |z: (f64, f64), d: (f64, f64), s: f64| (z.0 + s * d.0 * scale.0, z.1 + s * d.1 * scale.1);
    let mut evals = 0usize;
    let mut best = (x, cost(x));
    evals += 1;
    let mut improved = false;
    for _ in 0..rounds {
        let x = best.0;
        let h = 1e-7;
        let g0 = cost(at(x, (1.0, 0.0), h)) - cost(at(x, (1.0, 0.0), -h));
        let g1 = cost(at(x, (0.0, 1.0), h)) - cost(at(x, (0.0, 1.0), -h));
        evals += 4;
        let norm = g0.hypot(g1);
        if !(norm > 0.0 && norm.is_finite()) {
            break;
        }
        let u = (-g0 / norm, -g1 / norm);
        let t = (-u.1, u.0);
        // Active: a short step downhill leaves the set.
        let probe = at(x, u, 1e-6);
        if feasible(probe) {
            let c = cost(probe);
            evals += 1;
            if c < best.1 {
                return improved.then_some((best.0, best.1, evals));
            }
        }
        // The walk follows the boundary's own tangent (from two boundary points across
        // the line perpendicular to the gradient), not that line: where the boundary runs
        // at an angle to it, walks along the line crept on by a thousandth per round.
        let (t, u) = boundary_frame(feasible, &at, x, t, u);
        let boundary = |s: f64| boundary_point(feasible, &at, at(x, t, s), u, s);
        let mut count = 0usize;
        let mut phi = |s: f64| -> f64 {
            count += 1;
            boundary(s).map_or(f64::INFINITY, |z| {
                let c = cost(z);
                if c.is_nan() {
                    f64::INFINITY
                } else {
                    c
                }
            })
        };
        // Bracket: the falling side, steps doubling from 1e-4 until the cost rises.
        let f0 = phi(0.0);
        let mut side = 0.0;
        let mut step = 1e-4;
        let mut prev = f0;
        for dir in [1.0, -1.0] {
            let v = phi(dir * step);
            if v < f0 {
                (side, prev) = (dir, v);
                break;
            }
        }
        if side == 0.0 {
            evals += count;
            break;
        }
        let mut far = step;
        loop {
            let next = 2.0 * far;
            let v = phi(side * next);
            if v.is_nan() || v >= prev || next > 1.0 {
                far = next;
                break;
            }
            prev = v;
            step = far;
            far = next;
        }
        let (lo, hi) = if side > 0.0 {
            (0.5 * step, far)
        } else {
            (-far, -0.5 * step)
        };
        let (s, _) = brent(&mut phi, lo, hi, 1e-6);
        evals += count;
        let Some(z) = boundary(s) else { break };
        let c = cost(z);
        evals += 1;
        if c.is_nan() || c >= best.1 * (1.0 - 1e-9) {
            break;
        }
        // A round that gained less than a thousandth of the cost ends the walk: towards
        // the tip of a wedge the rounds shrink geometrically, and each costs dozens of
        // feasibility tests.
        let small = c > best.1 * (1.0 - WALK_GAIN);
        best = (z, c);
        improved = true;
        if small {
            break;
        }
    }
    improved.then_some((best.0, best.1, evals))
}

/// A point `z` moved `s` along a direction `d` (in scaled coordinates).
type Step<'a> = dyn Fn((f64, f64), (f64, f64), f64) -> (f64, f64) + 'a;

/// A walk along the boundary stops after a round that lowered the cost by less than this
/// share.
const WALK_GAIN: f64 = 1e-3;

/// The boundary point near `p` (on the walk's line at `s`): bisection along `u` between a
/// feasible point (the nearest to the line of offsets 0, -1/8, -1/2, -1 times the reach)
/// and an infeasible one, within ±(2|s| + 1e-4) of the line; the feasible end is kept.
/// None where the bracket does not hold a boundary.
fn boundary_point(
    feasible: &dyn Fn((f64, f64)) -> bool,
    at: &Step<'_>,
    p: (f64, f64),
    u: (f64, f64),
    s: f64,
) -> Option<(f64, f64)> {
    let reach = 2.0 * s.abs() + 1e-4;
    if feasible(at(p, u, reach)) {
        return None;
    }
    // The feasible end nearest the line: where the set narrows to a wedge (two boundaries
    // meeting), a fixed inner end crossed the other boundary and the walk crept towards
    // the tip by a few percent per round.
    let mut lo = [0.0, -0.125, -0.5, -1.0]
        .into_iter()
        .map(|k| k * reach)
        .find(|&o| feasible(at(p, u, o)))?;
    let mut hi = reach;
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if feasible(at(p, u, mid)) {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo < 1e-8 * reach {
            break;
        }
    }
    Some(at(p, u, lo))
}

/// The boundary's tangent at `x` and its normal towards the outside, in the scaled
/// coordinates of `at`, from the boundary points at ±1e-4 along `t` (perpendicular to the
/// descent direction `u`); `(t, u)` itself where those points are not found.
fn boundary_frame(
    feasible: &dyn Fn((f64, f64)) -> bool,
    at: &Step<'_>,
    x: (f64, f64),
    t: (f64, f64),
    u: (f64, f64),
) -> ((f64, f64), (f64, f64)) {
    let h = 1e-4;
    let (Some(a), Some(b)) = (
        boundary_point(feasible, at, at(x, t, -h), u, h),
        boundary_point(feasible, at, at(x, t, h), u, h),
    ) else {
        return (t, u);
    };
    // Back to the scaled coordinates: `at` moves by s d scale, so differences divide by it.
    let o = at((0.0, 0.0), (1.0, 1.0), 1.0);
    let d = ((b.0 - a.0) / o.0, (b.1 - a.1) / o.1);
    let len = d.0.hypot(d.1);
    if !(len > 0.0 && len.is_finite()) {
        return (t, u);
    }
    let tangent = (d.0 / len, d.1 / len);
    let mut normal = (-tangent.1, tangent.0);
    if normal.0 * u.0 + normal.1 * u.1 < 0.0 {
        normal = (-normal.0, -normal.1);
    }
    (tangent, normal)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rosenbrock_and_budget() {
        let mut f = |x: &[f64]| (1.0 - x[0]).powi(2) + 100.0 * (x[1] - x[0] * x[0]).powi(2);
        let m = nelder_mead(&mut f, &[-1.2, 1.0], &[0.1, 0.1], NelderMead::default());
        assert!(m.converged);
        assert!(
            (m.x[0] - 1.0).abs() < 1e-5 && (m.x[1] - 1.0).abs() < 1e-5,
            "{m:?}"
        );
        // A budget too small is reported, not hidden.
        let m = nelder_mead(
            &mut f,
            &[-1.2, 1.0],
            &[0.1, 0.1],
            NelderMead {
                max_evaluations: 20,
                ..NelderMead::default()
            },
        );
        assert!(!m.converged && m.evaluations >= 20);
    }

    #[test]
    fn infeasible_points_are_avoided() {
        // Minimum of (x - 2)² on x < 1 is at the boundary; beyond it the function is infinite.
        let mut f = |x: &[f64]| {
            if x[0] < 1.0 {
                (x[0] - 2.0).powi(2)
            } else {
                f64::INFINITY
            }
        };
        let m = nelder_mead(&mut f, &[0.0], &[0.3], NelderMead::default());
        assert!(m.x[0] < 1.0 && m.x[0] > 0.999, "{m:?}");
    }

    #[test]
    fn compass_search_descends_within_the_feasible_set_and_says_how_it_ended() {
        // (x - 1)² + 4 (y - 2)²: the minimum, to the floor.
        let mut f = |p: (f64, f64)| (p.0 - 1.0).powi(2) + 4.0 * (p.1 - 2.0).powi(2);
        let opts = CompassSearch {
            scale: 1.0,
            step: 0.5,
            floor: 1e-10,
            max_evaluations: 100_000,
        };
        let r = compass_search(&mut f, &|_| true, ((0.0, 0.0), 17.0), &opts);
        assert!(r.converged && r.step <= 1e-10);
        assert!(
            (r.x.0 - 1.0).abs() < 1e-9 && (r.x.1 - 2.0).abs() < 1e-9,
            "{r:?}"
        );
        // Kept to y <= 1: the constrained minimum's side, never outside.
        let r = compass_search(&mut f, &|p| p.1 <= 1.0, ((0.0, 0.0), 17.0), &opts);
        assert!(r.x.1 <= 1.0 && (r.x.1 - 1.0).abs() < 1e-8, "{r:?}");
        // Out of budget: reported.
        let short = CompassSearch {
            max_evaluations: 16,
            ..opts
        };
        let r = compass_search(&mut f, &|_| true, ((0.0, 0.0), 17.0), &short);
        assert!(!r.converged && r.evaluations == 16);
    }

    #[test]
    fn along_boundary_follows_a_tilted_edge() {
        // Minimise (x - 3)² + (y - 3)² over the half-plane x + 2y <= 1 (closed form: the
        // foot of the perpendicular from (3, 3), (1.4, -0.2)), starting from a boundary point
        // where a compass search with axis and diagonal steps is stuck.
        let cost = |p: (f64, f64)| (p.0 - 3.0).powi(2) + (p.1 - 3.0).powi(2);
        let feasible = |p: (f64, f64)| p.0 + 2.0 * p.1 <= 1.0;
        let start = (-1.0, 1.0);
        let (p, c, _) = along_boundary(&cost, &feasible, start, (1.0, 1.0), 12).unwrap();
        assert!(feasible(p));
        // The walk stops on the cost (relative progress below 1e-9), where the position is
        // known to about the square root of that.
        assert!(
            (p.0 - 1.4).abs() < 1e-4 && (p.1 + 0.2).abs() < 1e-4,
            "{p:?}"
        );
        assert!((c - 12.8).abs() < 1e-8 * 12.8, "{c}");
        // Not active (the minimum is inside): nothing to walk.
        let inside = |p: (f64, f64)| p.0 + 2.0 * p.1 <= 100.0;
        assert!(along_boundary(&cost, &inside, (3.0, 3.0), (1.0, 1.0), 4).is_none());
    }

    #[test]
    fn along_boundary_walks_into_a_wedge() {
        // Minimise (x + 1)² + y²/100 over the wedge 0.2 x <= y <= 0.5 x: the minimum is its
        // tip (0, 0), cost 1. From a point on the upper edge the walk follows it towards the
        // tip, where the lower edge closes in, with a bounded number of evaluations.
        let cost = |p: (f64, f64)| (p.0 + 1.0).powi(2) + 0.01 * p.1 * p.1;
        let feasible = |p: (f64, f64)| 0.2 * p.0 <= p.1 && p.1 <= 0.5 * p.0;
        let (p, c, evals) = along_boundary(&cost, &feasible, (4.0, 2.0), (1.0, 1.0), 60).unwrap();
        println!("wedge: {p:?} cost {c} after {evals} evaluations");
        assert!(feasible(p));
        // Measured: 5e-7 from the tip after 161 evaluations.
        assert!(c < 1.0 + 1e-3 && p.0.hypot(p.1) < 1e-3, "{p:?} {c}");
        assert!(evals < 1000, "{evals}");
    }
}
