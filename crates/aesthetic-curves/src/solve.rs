//! The solver layer: minimisers with options and a report of how they ended.
//!
//! [`roots`]: bracketed root finding (Illinois, Brent from guesses, a bracketed Newton that
//! reports whether it converged).
//!
//! [`least_squares`]: Levenberg–Marquardt for small nonlinear least-squares problems (the
//! rational-cubic fit and the single-LAC fit), with a [`least_squares::Stop`] reason.
//!
//! [`newton_1d`] is the safeguarded one-variable Newton (or Gauss–Newton projection) loop
//! with a [`Root1d`] report.
//!
//! [`brent`] minimises a function of one variable on an interval; [`compass_search`] is a
//! pattern search in two variables that keeps to a feasible set; [`along_boundary`]
//! follows the boundary of a feasible set in two variables when the minimum lies on it.
//!
//! [`sweep_to_fixed_point`] repeats a sweep of updates (block Gauss–Seidel) until its
//! largest change is small, with a [`Sweeps`] report.
//!
//! [`bisect_by`] bisects a bracket on a yes/no test (the longest piece that meets a
//! tolerance, the parameter where a condition starts to hold), carrying the last passing
//! test's value.
//!
//! [`nelder_mead`] minimises a function of a few variables (the simplex method of Nelder and
//! Mead with the standard coefficients: reflection 1, expansion 2, contraction 1/2, shrink
//! 1/2). It stops when the simplex's spread of values is below `f_tol + f_rel_tol |best|`
//! and its extent below `x_tol`, or its extent below `collapse` whatever the values, or
//! after `max_evaluations`; the returned [`Minimum`] says which.
//! Infeasible points are the caller's to map to a large value (`f64::INFINITY` works: such
//! vertices are always replaced first).

pub mod least_squares;
pub mod roots;

/// Stopping rules of [`nelder_mead`].
#[derive(Clone, Copy, Debug)]
pub struct Options {
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

impl Default for Options {
    fn default() -> Self {
        Options {
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
    opts: Options,
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

/// Golden-section search for a minimum of `f` on [lo, hi]: `iterations` steps after the
/// first two interior points (each shrinks the bracket by 0.618). Returns the better
/// interior point and its value. For a function too costly or too rough for Brent's
/// parabolic steps (the rational-cubic fit's valley profile, itself a minimisation).
pub fn golden_section(
    f: &mut dyn FnMut(f64) -> f64,
    mut lo: f64,
    mut hi: f64,
    iterations: usize,
) -> (f64, f64) {
    let r = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (hi - r * (hi - lo), lo + r * (hi - lo));
    let (mut fa, mut fb) = (f(a), f(b));
    for _ in 0..iterations {
        if fa < fb {
            hi = b;
            (b, fb) = (a, fa);
            a = hi - r * (hi - lo);
            fa = f(a);
        } else {
            lo = a;
            (a, fa) = (b, fb);
            b = lo + r * (hi - lo);
            fb = f(b);
        }
    }
    if fa < fb {
        (a, fa)
    } else {
        (b, fb)
    }
}

/// The final bracket of [`golden_bracket`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GoldenBracket {
    /// Its lower end.
    pub lo: f64,
    /// Its upper end.
    pub hi: f64,
    /// Evaluations after the first two interior points.
    pub iterations: usize,
    /// The bracket shrank below `x_tol` (false: `max_iterations` ran out first).
    pub converged: bool,
}

/// Golden-section search for a minimum of `f` on [lo, hi] until the bracket is narrower
/// than `x_tol` or after `max_iterations` evaluations past the first two interior points;
/// a tie keeps the lower part (so a region where `f` is infinite on both interior points
/// is left towards `lo`). Returns the final bracket (its midpoint is the estimate).
pub fn golden_bracket(
    f: &mut dyn FnMut(f64) -> f64,
    lo: f64,
    hi: f64,
    x_tol: f64,
    max_iterations: usize,
) -> GoldenBracket {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (lo, hi);
    let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
    let (mut fc, mut fd) = (f(c), f(d));
    let mut iterations = 0;
    while iterations < max_iterations && b - a >= x_tol {
        iterations += 1;
        if fc <= fd {
            (b, d, fd) = (d, c, fc);
            c = b - g * (b - a);
            fc = f(c);
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + g * (b - a);
            fd = f(d);
        }
    }
    GoldenBracket {
        lo: a,
        hi: b,
        iterations,
        converged: b - a < x_tol,
    }
}

/// Brent's minimisation of `f` on [lo, hi] to `tol` (golden sections with parabolic
/// steps; Brent 1973, "Algorithms for minimization without derivatives", ch. 5). Returns
/// the minimiser and its value: a local minimum, the global one for a unimodal `f`.
pub fn brent(f: &mut dyn FnMut(f64) -> f64, lo: f64, hi: f64, tol: f64) -> (f64, f64) {
    const CG: f64 = 0.381_966_011_250_105_1;
    let (mut a, mut b) = (lo, hi);
    let mut x = a + CG * (b - a);
    let (mut w, mut v) = (x, x);
    let mut fx = f(x);
    let (mut fw, mut fv) = (fx, fx);
    let (mut d, mut e): (f64, f64) = (0.0, 0.0);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        let tol1 = tol * 0.5 + 1e-12 * x.abs();
        let tol2 = 2.0 * tol1;
        if (x - m).abs() <= tol2 - 0.5 * (b - a) {
            break;
        }
        let mut golden_step = true;
        if e.abs() > tol1 {
            let r = (x - w) * (fx - fv);
            let q0 = (x - v) * (fx - fw);
            let mut p = (x - v) * q0 - (x - w) * r;
            let mut q = 2.0 * (q0 - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            if p.abs() < (0.5 * q * e).abs() && p > q * (a - x) && p < q * (b - x) {
                e = d;
                d = p / q;
                let u = x + d;
                if u - a < tol2 || b - u < tol2 {
                    d = if x < m { tol1 } else { -tol1 };
                }
                golden_step = false;
            }
        }
        if golden_step {
            e = if x < m { b - x } else { a - x };
            d = CG * e;
        }
        let u = if d.abs() >= tol1 {
            x + d
        } else if d > 0.0 {
            x + tol1
        } else {
            x - tol1
        };
        let fu = f(u);
        if fu <= fx {
            if u < x {
                b = x;
            } else {
                a = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    (x, fx)
}

/// Stopping rules and safeguards of [`newton_1d`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Newton1d {
    /// Most iterations (one evaluation each).
    pub max_iterations: usize,
    /// Each update is clamped to ±this.
    pub max_step: f64,
    /// Converged when an update moves x by at most `abs_tol + rel_tol |x|`.
    pub abs_tol: f64,
    /// See `abs_tol`.
    pub rel_tol: f64,
    /// The domain of x.
    pub bounds: (f64, f64),
    /// True: iterates are clamped into `bounds`; false: an iterate outside them ends the run
    /// ([`Stop1d::Refused`]).
    pub clamp: bool,
}

/// Why [`newton_1d`] stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop1d {
    /// An update was below the tolerance: `x` is the root to it.
    Converged,
    /// `max_iterations` ran out first; `x` is the last iterate.
    IterationLimit,
    /// The update function refused the point (outside its domain, or a slope of the wrong
    /// sign), or an iterate left `bounds` without `clamp`.
    Refused,
}

/// The result of [`newton_1d`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Root1d {
    /// The last iterate.
    pub x: f64,
    /// Evaluations of the update function.
    pub iterations: usize,
    /// Why the run ended.
    pub stop: Stop1d,
}

impl Root1d {
    /// Whether the stopping test was met.
    pub fn converged(&self) -> bool {
        self.stop == Stop1d::Converged
    }
}

/// Newton's method (or any fixed-point update) in one variable without a bracket: from
/// `x0`, `x <- x + update(x)`, the update (for Newton `-g/g'`, for a Gauss–Newton
/// projection `-(P - q)·P'/|P'|²`) clamped to `max_step` and the iterate kept in `bounds`
/// as [`Newton1d`] says. `update` returns `None` where it cannot go on. The one loop behind
/// the library's point projections and one-dimensional Newton iterations; it never runs
/// past `max_iterations` and says how it ended.
#[inline]
pub fn newton_1d(mut update: impl FnMut(f64) -> Option<f64>, x0: f64, opts: &Newton1d) -> Root1d {
    let mut x = x0;
    for i in 0..opts.max_iterations {
        let Some(d) = update(x).filter(|d| d.is_finite()) else {
            return Root1d {
                x,
                iterations: i + 1,
                stop: Stop1d::Refused,
            };
        };
        let mut next = x + d.clamp(-opts.max_step, opts.max_step);
        if opts.clamp {
            next = next.clamp(opts.bounds.0, opts.bounds.1);
        } else if !(opts.bounds.0..=opts.bounds.1).contains(&next) {
            return Root1d {
                x,
                iterations: i + 1,
                stop: Stop1d::Refused,
            };
        }
        let done = (next - x).abs() <= opts.abs_tol + opts.rel_tol * next.abs();
        x = next;
        if done {
            return Root1d {
                x,
                iterations: i + 1,
                stop: Stop1d::Converged,
            };
        }
    }
    Root1d {
        x,
        iterations: opts.max_iterations,
        stop: Stop1d::IterationLimit,
    }
}

/// Stopping rules of [`newton_min_1d`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NewtonMin1d {
    /// Most Newton steps.
    pub max_iterations: usize,
    /// Halvings of a step that does not lower the value before the run ends.
    pub max_halvings: usize,
    /// Converged when the Newton step is at most this long.
    pub x_tol: f64,
    /// ... or an accepted step moved at most this far.
    pub min_move: f64,
    /// The domain of x: every trial point is clamped into it.
    pub bounds: (f64, f64),
}

/// The result of [`newton_min_1d`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Min1d {
    /// The best point found.
    pub x: f64,
    /// The value there.
    pub value: f64,
    /// Newton steps taken.
    pub iterations: usize,
    /// [`Stop1d::Converged`]: a short step, a short accepted move, or no halving lowered
    /// the value (a minimum to the resolution of the value); [`Stop1d::Refused`]: the step
    /// function could not go on; or the iteration limit.
    pub stop: Stop1d,
}

/// Newton's method for a minimum in one variable, safeguarded by descent: from `x0` (clamped
/// into the bounds), `step(x)` proposes a move (for a minimum of f, `-f'/f''`; any descent
/// direction where f'' <= 0), which is halved until `value` falls, at most `max_halvings`
/// times. The foot-point projection of [`crate::bspline`], whose steps cross spans.
pub fn newton_min_1d(
    mut step: impl FnMut(f64) -> Option<f64>,
    mut value: impl FnMut(f64) -> f64,
    x0: f64,
    opts: &NewtonMin1d,
) -> Min1d {
    let (lo, hi) = opts.bounds;
    let mut x = x0.clamp(lo, hi);
    let mut v = value(x);
    for i in 0..opts.max_iterations {
        let done = |x: f64, v: f64, iterations: usize, stop: Stop1d| Min1d {
            x,
            value: v,
            iterations,
            stop,
        };
        let Some(mut h) = step(x).filter(|h| h.is_finite()) else {
            return done(x, v, i, Stop1d::Refused);
        };
        if h.abs() <= opts.x_tol {
            return done(x, v, i, Stop1d::Converged);
        }
        let mut moved = false;
        for _ in 0..opts.max_halvings {
            let nx = (x + h).clamp(lo, hi);
            let nv = value(nx);
            if nv < v {
                moved = (nx - x).abs() > opts.min_move;
                (x, v) = (nx, nv);
                break;
            }
            h *= 0.5;
        }
        if !moved {
            return done(x, v, i + 1, Stop1d::Converged);
        }
    }
    Min1d {
        x,
        value: v,
        iterations: opts.max_iterations,
        stop: Stop1d::IterationLimit,
    }
}

/// Limits of [`damped_newton`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DampedNewton {
    /// Most Newton steps.
    pub max_iterations: usize,
    /// Halvings of a step's length before the line search gives up.
    pub halvings: usize,
}

/// Why [`damped_newton`] stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SystemStop {
    /// The caller's test of convergence held.
    Converged,
    /// `max_iterations` ran out first.
    IterationLimit,
    /// No step was found (a Jacobian that could not be formed or solved).
    NoStep,
    /// No length of the step lowered the sum of squared residuals.
    NoDescent,
}

/// The result of [`damped_newton`].
#[derive(Clone, Debug, PartialEq)]
pub struct System<S> {
    /// The last accepted state.
    pub state: S,
    /// Its residuals.
    pub residuals: Vec<f64>,
    /// Newton steps tried.
    pub iterations: usize,
    /// Why the run ended.
    pub stop: SystemStop,
}

/// Damped Newton (or Gauss–Newton) for a system of equations over an opaque state: until
/// `converged(state, residuals)`, `direction(state, residuals)` gives a step and its first
/// length (the caller solves its own Jacobian: square, minimum-norm, weighted), and
/// `trial(state, step, length)` builds the state moved by that length of the step with its
/// residuals (`None` where it cannot be built); the first of the length, its half, ... (at
/// most `halvings` tries) that lowers the sum of squared residuals is taken. It checks the
/// thread's deadline ([`crate::deadline`]) every step and never runs past its limits. The
/// sketch's G2 fairing, in the joints' tangent angles and then with free α.
pub fn damped_newton<S>(
    state: S,
    residuals: Vec<f64>,
    mut direction: impl FnMut(&S, &[f64]) -> Option<(Vec<f64>, f64)>,
    mut trial: impl FnMut(&S, &[f64], f64) -> Option<(S, Vec<f64>)>,
    mut converged: impl FnMut(&S, &[f64]) -> bool,
    opts: &DampedNewton,
) -> crate::error::Result<System<S>> {
    let sum_sq = |r: &[f64]| r.iter().map(|x| x * x).sum::<f64>();
    let mut out = System {
        state,
        residuals,
        iterations: 0,
        stop: SystemStop::IterationLimit,
    };
    loop {
        if converged(&out.state, &out.residuals) {
            out.stop = SystemStop::Converged;
            return Ok(out);
        }
        if out.iterations >= opts.max_iterations {
            out.stop = SystemStop::IterationLimit;
            return Ok(out);
        }
        crate::deadline::check()?;
        out.iterations += 1;
        let Some((step, mut length)) = direction(&out.state, &out.residuals) else {
            out.stop = SystemStop::NoStep;
            return Ok(out);
        };
        let current = sum_sq(&out.residuals);
        let mut found = None;
        for _ in 0..opts.halvings {
            if let Some((s, r)) = trial(&out.state, &step, length) {
                if sum_sq(&r) < current {
                    found = Some((s, r));
                    break;
                }
            }
            length *= 0.5;
        }
        let Some((s, r)) = found else {
            out.stop = SystemStop::NoDescent;
            return Ok(out);
        };
        out.state = s;
        out.residuals = r;
    }
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
/// `scale`); the best one that lowers the value and that `feasible` accepts is taken and the
/// step doubles, else the step halves. Stops when the step is at most `floor` or after
/// `max_evaluations`; the [`Compass`] says which. Derivative-free and monotone: the value
/// never rises, and an infeasible point is never returned.
pub fn compass_search(
    f: &mut dyn FnMut((f64, f64)) -> f64,
    feasible: &dyn Fn((f64, f64)) -> bool,
    (start, value): ((f64, f64), f64),
    scale: f64,
    step: f64,
    floor: f64,
    max_evaluations: usize,
) -> Compass {
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
    use std::f64::consts::SQRT_2;

    #[test]
    fn golden_bracket_closes_on_the_minimum_and_says_when_it_ran_out() {
        let mut f = |x: f64| (x - 0.3).powi(2) + 1.0;
        let g = golden_bracket(&mut f, -1.0, 2.0, 1e-8, 100);
        assert!(g.converged && g.hi - g.lo < 1e-8, "{g:?}");
        // A quadratic is flat to f64 within about sqrt(ε) of its minimum.
        assert!((0.5 * (g.lo + g.hi) - 0.3).abs() < 1e-7, "{g:?}");
        let short = golden_bracket(&mut f, -1.0, 2.0, 1e-8, 5);
        assert!(!short.converged && short.iterations == 5, "{short:?}");
        // Infinite on both interior points: the lower part is kept.
        let mut wall = |x: f64| if x > -0.5 { f64::INFINITY } else { x * x };
        let w = golden_bracket(&mut wall, -1.0, 2.0, 1e-6, 100);
        assert!(w.hi <= -0.4, "{w:?}");
    }

    #[test]
    fn golden_section_shrinks_onto_the_minimum() {
        let mut calls = 0;
        let mut f = |x: f64| {
            calls += 1;
            (x - 0.3).powi(2)
        };
        let (x, v) = golden_section(&mut f, 0.0, 1.0, 40);
        assert!((x - 0.3).abs() < 1e-7 && v < 1e-13, "{x} {v}");
        assert_eq!(calls, 42);
    }

    #[test]
    fn damped_newton_solves_a_system_and_says_how_it_ended() {
        // x² + y² = 4, x y = 1 from (2, 0.3): the root (1.9319, 0.5176).
        let res = |x: &[f64; 2]| vec![x[0] * x[0] + x[1] * x[1] - 4.0, x[0] * x[1] - 1.0];
        let direction = |x: &[f64; 2], r: &[f64]| {
            let (a, b, c, d) = (2.0 * x[0], 2.0 * x[1], x[1], x[0]);
            let det = a * d - b * c;
            (det != 0.0).then(|| {
                let s = vec![-(d * r[0] - b * r[1]) / det, -(-c * r[0] + a * r[1]) / det];
                (s, 1.0)
            })
        };
        let trial = |x: &[f64; 2], s: &[f64], l: f64| {
            let y = [x[0] + l * s[0], x[1] + l * s[1]];
            Some((y, res(&y)))
        };
        let small = |_: &[f64; 2], r: &[f64]| r.iter().all(|v| v.abs() < 1e-13);
        let opts = DampedNewton {
            max_iterations: 30,
            halvings: 30,
        };
        let x0 = [2.0, 0.3];
        let sys = damped_newton(x0, res(&x0), direction, trial, small, &opts).unwrap();
        let root = (2.0 + 3f64.sqrt()).sqrt();
        assert_eq!(sys.stop, SystemStop::Converged);
        assert!((sys.state[0] - root).abs() < 1e-12 && (sys.state[1] - 1.0 / root).abs() < 1e-12);
        // Out of iterations, without a direction, without descent.
        let one = DampedNewton {
            max_iterations: 1,
            ..opts
        };
        let r = damped_newton(x0, res(&x0), direction, trial, small, &one).unwrap();
        assert_eq!((r.stop, r.iterations), (SystemStop::IterationLimit, 1));
        let none = |_: &[f64; 2], _: &[f64]| None;
        let r = damped_newton(x0, res(&x0), none, trial, small, &opts).unwrap();
        assert_eq!((r.stop, r.state), (SystemStop::NoStep, x0));
        let uphill =
            |x: &[f64; 2], r: &[f64]| direction(x, r).map(|(s, l)| (vec![-s[0], -s[1]], l));
        let r = damped_newton(x0, res(&x0), uphill, trial, small, &opts).unwrap();
        assert_eq!(r.stop, SystemStop::NoDescent);
    }

    #[test]
    fn newton_min_1d_finds_a_minimum_and_says_how_it_ended() {
        // f(x) = x^4 - 3x^2 + x: minima near -1.30 and 1.13, f'' < 0 near 0.
        let f = |x: f64| x.powi(4) - 3.0 * x * x + x;
        let step = |x: f64| {
            let (g, gg) = (4.0 * x.powi(3) - 6.0 * x + 1.0, 12.0 * x * x - 6.0);
            Some(if gg > 0.0 { -g / gg } else { -g.signum() * 0.5 })
        };
        let opts = NewtonMin1d {
            max_iterations: 50,
            max_halvings: 30,
            x_tol: 1e-13,
            min_move: 0.0,
            bounds: (-3.0, 3.0),
        };
        // From 0.5 and from 0.1 (f'' < 0 at both: the fallback step, downhill) to the
        // minimum on each side (the roots of 4x³ - 6x + 1, by Newton in f64).
        let m = newton_min_1d(step, f, 0.5, &opts);
        assert!(
            m.stop == Stop1d::Converged && (m.x - 1.130_901_122_629_986).abs() < 1e-10,
            "{m:?}"
        );
        let left = newton_min_1d(step, f, 0.1, &opts);
        assert!((left.x + 1.300_839_565_941_577).abs() < 1e-10, "{left:?}");
        assert_eq!(m.value, f(m.x));
        // A step function that gives up, and a limit too short to converge.
        let r = newton_min_1d(|_| None, f, 0.1, &opts);
        assert_eq!((r.stop, r.x), (Stop1d::Refused, 0.1));
        let short = NewtonMin1d {
            max_iterations: 1,
            ..opts
        };
        let s = newton_min_1d(step, f, 2.9, &short);
        assert_eq!(s.stop, Stop1d::IterationLimit);
        assert!(s.value < f(2.9));
    }

    #[test]
    fn newton_1d_converges_refuses_and_stops_as_it_says() {
        let opts = Newton1d {
            max_iterations: 40,
            max_step: 1.0,
            abs_tol: 1e-15,
            rel_tol: 1e-15,
            bounds: (0.0, 10.0),
            clamp: true,
        };
        // √2 from 3: steps clamped to 1 at first, then quadratic.
        let r = newton_1d(|x| Some(-(x * x - 2.0) / (2.0 * x)), 3.0, &opts);
        assert!(
            r.converged() && (r.x - 2f64.sqrt()).abs() < 1e-15 && r.iterations < 10,
            "{r:?}"
        );
        // A refusing update ends the run where it is.
        let r = newton_1d(|x| (x > 2.5).then_some(-0.3), 3.0, &opts);
        assert_eq!((r.stop, r.iterations), (Stop1d::Refused, 3));
        assert!((r.x - 2.4).abs() < 1e-12);
        // Clamped into the bounds: the root of x + 1 is outside, so x rests at 0 (an update
        // that moves nothing any more counts as converged); unclamped it is refused.
        let r = newton_1d(|x| Some(-(x + 1.0)), 0.5, &opts);
        assert_eq!((r.stop, r.x), (Stop1d::Converged, 0.0));
        let free = Newton1d {
            clamp: false,
            ..opts
        };
        assert_eq!(
            newton_1d(|x| Some(-(x + 1.0)), 0.5, &free).stop,
            Stop1d::Refused
        );
        // A cycle never converges: the iteration limit, said so.
        let r = newton_1d(|x| Some(if x < 1.0 { 1.0 } else { -1.0 }), 0.5, &opts);
        assert_eq!((r.stop, r.iterations), (Stop1d::IterationLimit, 40));
    }

    #[test]
    fn rosenbrock_and_budget() {
        let mut f = |x: &[f64]| (1.0 - x[0]).powi(2) + 100.0 * (x[1] - x[0] * x[0]).powi(2);
        let m = nelder_mead(&mut f, &[-1.2, 1.0], &[0.1, 0.1], Options::default());
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
            Options {
                max_evaluations: 20,
                ..Options::default()
            },
        );
        assert!(!m.converged && m.evaluations >= 20);
    }

    #[test]
    fn compass_search_descends_within_the_feasible_set_and_says_how_it_ended() {
        // (x - 1)² + 4 (y - 2)²: the minimum, to the floor.
        let mut f = |p: (f64, f64)| (p.0 - 1.0).powi(2) + 4.0 * (p.1 - 2.0).powi(2);
        let r = compass_search(
            &mut f,
            &|_| true,
            ((0.0, 0.0), 17.0),
            1.0,
            0.5,
            1e-10,
            100_000,
        );
        assert!(r.converged && r.step <= 1e-10);
        assert!(
            (r.x.0 - 1.0).abs() < 1e-9 && (r.x.1 - 2.0).abs() < 1e-9,
            "{r:?}"
        );
        // Kept to y <= 1: the constrained minimum's side, never outside.
        let r = compass_search(
            &mut f,
            &|p| p.1 <= 1.0,
            ((0.0, 0.0), 17.0),
            1.0,
            0.5,
            1e-10,
            100_000,
        );
        assert!(r.x.1 <= 1.0 && (r.x.1 - 1.0).abs() < 1e-8, "{r:?}");
        // Out of budget: reported.
        let r = compass_search(&mut f, &|_| true, ((0.0, 0.0), 17.0), 1.0, 0.5, 1e-10, 16);
        assert!(!r.converged && r.evaluations == 16);
    }

    #[test]
    fn brent_finds_the_minimum_of_a_unimodal_function() {
        // cos on [2, 5]: minimum at π; x^4 at 0 (no parabola fits exactly there).
        let (x, v) = brent(&mut |x: f64| x.cos(), 2.0, 5.0, 1e-10);
        assert!((x - std::f64::consts::PI).abs() < 1e-8 && (v + 1.0).abs() < 1e-15);
        let (x, _) = brent(&mut |x: f64| x.powi(4), -1.0, 2.0, 1e-10);
        assert!(x.abs() < 1e-3, "{x}");
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

    #[test]
    fn bisection_keeps_its_bracket_and_says_how_it_ended() {
        // √2 from below (the test passes for x² <= 2), the value carried along.
        let b = bisect_by(
            |x| (x * x <= 2.0).then_some(x * x),
            1.0,
            2.0,
            |a, b| 0.5 * (a + b),
            |a, b| (b - a).abs() <= 1e-12,
            100,
        );
        assert!(b.converged && b.inside <= SQRT_2 && b.outside >= SQRT_2);
        assert!((b.inside - SQRT_2).abs() <= 1e-12 && b.value == Some(b.inside * b.inside));
        // The bracket the other way round, in a scale (geometric means), to a ratio.
        let b = bisect_by(
            |x| (x >= 1e-3).then_some(()),
            1.0,
            1e-9,
            |a, b| (a * b).sqrt(),
            |a, b| a / b <= 1.01,
            100,
        );
        assert!(
            b.converged && b.inside >= 1e-3 && b.outside < 1e-3 && b.inside / b.outside <= 1.01
        );
        // The iteration limit, and a test that never passes (no value).
        let b = bisect_by(
            |_| None::<()>,
            0.0,
            1.0,
            |a, b| 0.5 * (a + b),
            |_, _| false,
            5,
        );
        assert!(!b.converged && b.iterations == 5 && b.value.is_none());
        assert_eq!((b.inside, b.outside), (0.0, 1.0 / 32.0));
        // A bracket exhausted in floating point ends, converged.
        let b = bisect_by(
            |_| Some(()),
            0.0,
            1.0,
            |a, b| 0.5 * (a + b),
            |_, _| false,
            10_000,
        );
        assert!(b.converged && b.iterations < 1100);
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
        let m = nelder_mead(&mut f, &[0.0], &[0.3], Options::default());
        assert!(m.x[0] < 1.0 && m.x[0] > 0.999, "{m:?}");
    }
}

/// The result of [`bisect_by`].
#[derive(Clone, Debug, PartialEq)]
pub struct Bisection<T> {
    /// The end of the final bracket where the test passes (the start's `inside` if no
    /// tested point passed).
    pub inside: f64,
    /// The end where it fails.
    pub outside: f64,
    /// The test's value at `inside`, if `inside` was tested (None: no tested point passed).
    pub value: Option<T>,
    /// Tests made.
    pub iterations: usize,
    /// `done` held (or the bracket could not be split further in floating point); false:
    /// `max_iterations` ran out first.
    pub converged: bool,
}

/// Bisection on a test: `test(inside)` is taken to pass and `test(outside)` to fail (either
/// may be the larger end); the point `split(inside, outside)` between them (the mean, or
/// the geometric mean for a bracket in a scale) replaces the end of its outcome, until
/// `done(inside, outside)` or `max_iterations` tests. `test` returns `Some(value)` to pass.
pub fn bisect_by<T>(
    mut test: impl FnMut(f64) -> Option<T>,
    inside: f64,
    outside: f64,
    split: impl Fn(f64, f64) -> f64,
    done: impl Fn(f64, f64) -> bool,
    max_iterations: usize,
) -> Bisection<T> {
    let mut out = Bisection {
        inside,
        outside,
        value: None,
        iterations: 0,
        converged: false,
    };
    while out.iterations < max_iterations {
        if done(out.inside, out.outside) {
            out.converged = true;
            return out;
        }
        let mid = split(out.inside, out.outside);
        if mid == out.inside || mid == out.outside || !mid.is_finite() {
            out.converged = true;
            return out;
        }
        out.iterations += 1;
        match test(mid) {
            Some(v) => {
                out.inside = mid;
                out.value = Some(v);
            }
            None => out.outside = mid,
        }
    }
    out.converged = done(out.inside, out.outside);
    out
}

/// How [`sweep_to_fixed_point`] ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sweeps {
    /// Sweeps done.
    pub sweeps: usize,
    /// The largest change the last sweep made (as `sweep` measures it).
    pub last_change: f64,
    /// Whether that change was at most the tolerance (else the sweep limit or the thread's
    /// deadline ended it).
    pub converged: bool,
}

/// Block Gauss–Seidel, or any fixed-point iteration done in sweeps: `sweep` updates the
/// unknowns in place and returns the largest change it made; sweeps repeat until that
/// change is at most `tolerance`, for at most `max_sweeps` sweeps (the thread's deadline
/// ends it too).
pub fn sweep_to_fixed_point(
    max_sweeps: usize,
    tolerance: f64,
    mut sweep: impl FnMut() -> f64,
) -> Sweeps {
    let mut out = Sweeps {
        sweeps: 0,
        last_change: f64::INFINITY,
        converged: false,
    };
    while out.sweeps < max_sweeps && !crate::deadline::expired() {
        out.last_change = sweep();
        out.sweeps += 1;
        // NaN is no convergence.
        if out.last_change <= tolerance {
            out.converged = true;
            break;
        }
    }
    out
}
