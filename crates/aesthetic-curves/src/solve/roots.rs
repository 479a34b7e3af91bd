//! Roots of one variable: in a bracket (Illinois, Brent from guesses, a bracketed Newton),
//! without one (a safeguarded Newton), and the boundary of a yes/no test (bisection).
//!
//! [`illinois`]: regula falsi with the Illinois modification (the retained end's value is
//! halved when the same end is kept twice), plus a plain bisection step every fourth
//! iteration, so the bracket always shrinks at least geometrically. It needs `f(lo)` and
//! `f(hi)` of opposite signs, stops when the bracket is narrower than `x_tol`, and reports
//! [`Error::NoConvergence`] instead of looping past `max_iter`; [`illinois_bracket`] gives
//! the final bracket itself, for a caller that needs a point on one side of the root.
//!
//! [`brent`]: Brent's method (inverse quadratic interpolation, secant and bisection steps)
//! from a bracket narrowed by the caller's guesses, for callers that can guess.
//!
//! [`newton`]: Newton's method for a monotone function whose derivative comes with its value
//! at little extra cost, kept inside a bracket (a step that leaves it bisects instead),
//! stopping when the next step is predicted to move less than `x_tol`; it reports how it
//! ended ([`NewtonRoot::converged`]) instead of failing, so a caller can fall back.
//!
//! [`newton_1d`]: the safeguarded Newton (or Gauss–Newton projection) loop in one variable
//! without a bracket, with its [`Newton1d`] safeguards and a [`Root1d`] report.
//!
//! [`bisect_by`]: bisection of a bracket on a yes/no test (the longest piece that meets a
//! tolerance, the parameter where a condition starts to hold), carrying the last passing
//! test's value.

use crate::error::{Error, Result};

/// A root of `f` in the bracket `[lo, hi]` (with known values `flo`, `fhi` of opposite
/// signs) to within `x_tol`: the middle of [`illinois_bracket`]'s final bracket. Errors of
/// `f` are passed through.
pub fn illinois(
    f: impl FnMut(f64) -> Result<f64>,
    lo: (f64, f64),
    hi: (f64, f64),
    x_tol: f64,
    max_iter: usize,
) -> Result<f64> {
    let b = illinois_bracket(f, lo, hi, x_tol, max_iter)?;
    Ok(0.5 * (b.lo.0 + b.hi.0))
}

/// The final bracket of [`illinois_bracket`]: its ends with their values, of opposite
/// signs (or one of them zero, both ends then that point).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bracket {
    /// The lower end and its value.
    pub lo: (f64, f64),
    /// The upper end and its value.
    pub hi: (f64, f64),
    /// Evaluations of `f` made.
    pub evaluations: usize,
}

/// The bracket `[lo, hi]` of a sign change of `f` (known values `flo`, `fhi` of opposite
/// signs) narrowed by [`illinois`]' steps to within `x_tol`, for a caller that needs a point
/// on a given side of the root (the last `x` where a condition holds). Errors of `f` are
/// passed through; [`Error::NoConvergence`] where the bracket does not straddle a sign
/// change or `max_iter` evaluations do not narrow it.
pub fn illinois_bracket(
    mut f: impl FnMut(f64) -> Result<f64>,
    (mut lo, mut flo): (f64, f64),
    (mut hi, mut fhi): (f64, f64),
    x_tol: f64,
    max_iter: usize,
) -> Result<Bracket> {
    let at = |x: f64, evaluations: usize| Bracket {
        lo: (x, 0.0),
        hi: (x, 0.0),
        evaluations,
    };
    if flo == 0.0 {
        return Ok(at(lo, 0));
    }
    if fhi == 0.0 {
        return Ok(at(hi, 0));
    }
    if (flo > 0.0) == (fhi > 0.0) || flo.is_nan() || fhi.is_nan() {
        return Err(Error::NoConvergence(format!(
            "root bracket [{lo}, {hi}] does not straddle a sign change ({flo}, {fhi})"
        )));
    }
    let mut side = 0i32;
    // The tolerance never asks for less than the spacing of floats in the bracket.
    let tol = |lo: f64, hi: f64| x_tol.max(4.0 * f64::EPSILON * lo.abs().max(hi.abs()));
    // The values kept are the true ones (the Illinois halving works on copies).
    let (mut vlo, mut vhi) = (flo, fhi);
    for it in 0..max_iter {
        if hi - lo <= tol(lo, hi) {
            return Ok(Bracket {
                lo: (lo, vlo),
                hi: (hi, vhi),
                evaluations: it,
            });
        }
        let mut x = (lo * fhi - hi * flo) / (fhi - flo);
        if it % 4 == 3 || !(x > lo && x < hi) {
            x = 0.5 * (lo + hi);
        }
        let fx = f(x)?;
        if fx == 0.0 {
            return Ok(at(x, it + 1));
        }
        if (fx > 0.0) == (flo > 0.0) {
            (lo, flo, vlo) = (x, fx, fx);
            if side == -1 {
                fhi *= 0.5;
            }
            side = -1;
        } else {
            (hi, fhi, vhi) = (x, fx, fx);
            if side == 1 {
                flo *= 0.5;
            }
            side = 1;
        }
    }
    if hi - lo <= tol(lo, hi) {
        Ok(Bracket {
            lo: (lo, vlo),
            hi: (hi, vhi),
            evaluations: max_iter,
        })
    } else {
        Err(Error::NoConvergence(format!(
            "root not within {x_tol:e} after {max_iter} iterations (bracket [{lo}, {hi}])"
        )))
    }
}

/// A root of `f` in the bracket `[a, b]` (values `fa`, `fb` of opposite signs) by Brent's
/// method (Brent 1973, "Algorithms for minimization without derivatives", ch. 4: inverse
/// quadratic interpolation and secant steps, bisection whenever they do not shrink the
/// bracket fast enough), for a caller with good guesses: the points `guesses` (inside the
/// bracket, with their values) narrow the bracket first, and the best of them starts the
/// iteration. Stops when the bracket is narrower than `x_tol` (plus rounding) or
/// `|f| <= f_tol` (the noise of `f`); [`Error::NoConvergence`] after `max_iter` evaluations.
pub fn brent(
    mut f: impl FnMut(f64) -> Result<f64>,
    (a0, fa0): (f64, f64),
    (b0, fb0): (f64, f64),
    guesses: &[(f64, f64)],
    x_tol: f64,
    f_tol: f64,
    max_iter: usize,
) -> Result<f64> {
    // An end that is a root is the answer (f(a0) = 0 and f(b0) < 0 straddle nothing).
    if fa0 == 0.0 {
        return Ok(a0);
    }
    if fb0 == 0.0 {
        return Ok(b0);
    }
    if (fa0 > 0.0) == (fb0 > 0.0) || fa0.is_nan() || fb0.is_nan() {
        return Err(Error::NoConvergence(format!(
            "root bracket [{a0}, {b0}] does not straddle a sign change ({fa0}, {fb0})"
        )));
    }
    // The bracket [lo, hi] with f(lo) of the sign of fa0, narrowed by the guesses.
    let (mut lo, mut flo, mut hi, mut fhi) = (a0, fa0, b0, fb0);
    for &(x, fx) in guesses {
        if fx.abs() <= f_tol {
            return Ok(x);
        }
        let inside = (x - lo) * (x - hi) < 0.0;
        if inside && !fx.is_nan() {
            if (fx > 0.0) == (fa0 > 0.0) {
                (lo, flo) = (x, fx);
            } else {
                (hi, fhi) = (x, fx);
            }
        }
    }
    // Brent: b the best estimate, a the previous one, c the contrapoint (f(b), f(c) of
    // opposite signs).
    let (mut a, mut fa, mut b, mut fb) = if flo.abs() < fhi.abs() {
        (hi, fhi, lo, flo)
    } else {
        (lo, flo, hi, fhi)
    };
    let (mut c, mut fc) = (a, fa);
    let mut d = b - a;
    let mut e = d;
    for _ in 0..max_iter {
        if (fb > 0.0) == (fc > 0.0) {
            (c, fc) = (a, fa);
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            (a, fa) = (b, fb);
            (b, fb) = (c, fc);
            (c, fc) = (a, fa);
        }
        let tol1 = 2.0 * f64::EPSILON * b.abs() + 0.5 * x_tol;
        let xm = 0.5 * (c - b);
        if xm.abs() <= tol1 || fb == 0.0 || fb.abs() <= f_tol {
            return Ok(b);
        }
        if e.abs() >= tol1 && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q) = if a == c {
                (2.0 * xm * s, 1.0 - s)
            } else {
                let (qa, r) = (fa / fc, fb / fc);
                (
                    s * (2.0 * xm * qa * (qa - r) - (b - a) * (r - 1.0)),
                    (qa - 1.0) * (r - 1.0) * (s - 1.0),
                )
            };
            if p > 0.0 {
                q = -q;
            }
            p = p.abs();
            let min1 = 3.0 * xm * q - (tol1 * q).abs();
            let min2 = (e * q).abs();
            if 2.0 * p < min1.min(min2) {
                e = d;
                d = p / q;
            } else {
                d = xm;
                e = d;
            }
        } else {
            d = xm;
            e = d;
        }
        (a, fa) = (b, fb);
        b += if d.abs() > tol1 { d } else { tol1.copysign(xm) };
        fb = f(b)?;
    }
    Err(Error::NoConvergence(format!(
        "root not within {x_tol:e} after {max_iter} iterations (near {b})"
    )))
}

/// What [`newton`] found.
#[derive(Clone, Debug)]
pub struct NewtonRoot<P> {
    /// The root estimate.
    pub x: f64,
    /// The last point evaluated (`x` is one Newton step `x - at` beyond it, or equal to it).
    pub at: f64,
    /// `f(at)`.
    pub value: f64,
    /// `f'(at)`.
    pub slope: f64,
    /// What the function returned with its value at `at`.
    pub payload: P,
    /// Evaluations of `f`.
    pub evaluations: usize,
    /// Whether the stopping test was met (else the evaluation budget ran out or the slope
    /// was unusable, and `x` is the last iterate).
    pub converged: bool,
}

/// A root of a monotone `f` in the open bracket `(lo, hi)` (f changes sign across it; the
/// ends are never evaluated) by Newton's method from `x0`: `f(x)` returns `(f, f', payload)`.
/// A step that leaves the bracket known so far, or a slope of the wrong sign, is replaced by
/// bisection. Stops when `|f| <= f_tol`, when the step is below `x_tol`, or when two steps
/// show quadratic convergence (each at most a quarter of the previous) and the next is
/// predicted below `x_tol` (Kδ² with K = |δ_k|/δ_{k-1}², so the root is returned one step
/// past the last evaluation: no evaluation is spent to confirm it). At most `max_evals`
/// evaluations; errors of `f` are passed through.
pub fn newton<P>(
    mut f: impl FnMut(f64) -> Result<(f64, f64, P)>,
    x0: f64,
    (mut lo, mut hi): (f64, f64),
    increasing: bool,
    x_tol: f64,
    f_tol: f64,
    max_evals: usize,
) -> Result<NewtonRoot<P>> {
    let mut x = x0;
    let mut prev_step = f64::INFINITY;
    let mut evaluations = 0;
    loop {
        if !(x > lo && x < hi) {
            x = 0.5 * (lo + hi);
        }
        let (v, slope, payload) = f(x)?;
        evaluations += 1;
        let mut root = NewtonRoot {
            x,
            at: x,
            value: v,
            slope,
            payload,
            evaluations,
            converged: true,
        };
        if v.abs() <= f_tol {
            return Ok(root);
        }
        if (v > 0.0) == increasing {
            hi = x;
        } else {
            lo = x;
        }
        let usable = slope.is_finite() && slope != 0.0 && (slope > 0.0) == increasing;
        let step = if usable { v / slope } else { f64::NAN };
        let next = x - step;
        if usable && next > lo && next < hi {
            let quadratic = prev_step.is_finite()
                && step.abs() <= 0.25 * prev_step.abs()
                && step.abs() * step.abs() * (step.abs() / (prev_step * prev_step)) <= x_tol;
            if step.abs() <= x_tol || quadratic {
                root.x = next;
                return Ok(root);
            }
            prev_step = step;
            x = next;
        } else {
            prev_step = f64::INFINITY;
            x = 0.5 * (lo + hi);
        }
        if evaluations >= max_evals || hi - lo <= x_tol {
            root.converged = hi - lo <= x_tol;
            root.x = if root.converged { 0.5 * (lo + hi) } else { x };
            return Ok(root);
        }
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::SQRT_2;
    #[test]
    fn newton_converges_quadratically_and_reports_its_end() {
        // x^3 - 2 from 1: the root to rounding, in few evaluations, without a confirming one.
        let r = newton(
            |x| Ok((x * x * x - 2.0, 3.0 * x * x, ())),
            1.0,
            (0.0, 2.0),
            true,
            1e-15,
            0.0,
            20,
        )
        .unwrap();
        assert!(r.converged);
        assert!((r.x - 2f64.cbrt()).abs() < 2e-15, "{}", r.x);
        assert!(r.evaluations <= 6, "{} evaluations", r.evaluations);
        // A wild start outside the bracket bisects into it; a decreasing function too.
        let r = newton(
            |x: f64| Ok((1.0 - x.exp(), -x.exp(), ())),
            50.0,
            (-1.0, 3.0),
            false,
            1e-14,
            0.0,
            40,
        )
        .unwrap();
        assert!(r.converged && r.x.abs() < 1e-14, "{r:?}");
        // Out of budget: reported, not an error.
        let r = newton(
            |x: f64| Ok((x.atan(), 1.0 / (1.0 + x * x), ())),
            10.0,
            (-20.0, 30.0),
            true,
            1e-15,
            0.0,
            2,
        )
        .unwrap();
        assert!(!r.converged && r.evaluations == 2);
    }

    #[test]
    fn brent_from_guesses() {
        // x^3 - 2 on [0, 2] from two guesses straddling the root: few evaluations.
        let mut n = 0;
        let f = |x: f64| {
            n += 1;
            Ok(x * x * x - 2.0)
        };
        let g = [(1.2, 1.2f64.powi(3) - 2.0), (1.3, 1.3f64.powi(3) - 2.0)];
        let r = brent(f, (0.0, -2.0), (2.0, 6.0), &g, 1e-15, 0.0, 100).unwrap();
        assert!((r - 2f64.cbrt()).abs() < 1e-15, "{r}");
        assert!(n <= 8, "{n} evaluations");
        // Bad guesses (outside the bracket, NaN) are ignored; a bad bracket is an error.
        let g = [(5.0, 123.0), (1.0, f64::NAN)];
        let r = brent(
            |x| Ok(x.exp() - 3.0),
            (0.0, -2.0),
            (2.0, 4.389),
            &g,
            1e-14,
            0.0,
            100,
        );
        assert!((r.unwrap() - 3f64.ln()).abs() < 1e-13);
        assert!(brent(Ok, (1.0, 1.0), (2.0, 2.0), &[], 1e-12, 0.0, 10).is_err());
        // The evaluation budget is reported, not exceeded.
        let r = brent(
            |x| Ok(x.powi(3) - 0.3),
            (0.0, -0.3),
            (1.0, 0.7),
            &[],
            0.0,
            0.0,
            3,
        );
        assert!(matches!(r, Err(Error::NoConvergence(_))));
    }

    #[test]
    fn finds_roots_and_reports_bad_brackets() {
        let r = illinois(|x| Ok(x * x * x - 2.0), (0.0, -2.0), (2.0, 6.0), 1e-15, 200).unwrap();
        assert!((r - 2f64.cbrt()).abs() < 1e-15);
        assert!(illinois(Ok, (1.0, 1.0), (2.0, 2.0), 1e-12, 10).is_err());
        assert!(illinois(|x| Ok(x * x * x - 0.3), (0.0, -0.3), (1.0, 0.7), 0.0, 5).is_err());
        // A tolerance below the float spacing is met at the spacing.
        let r = illinois(|x| Ok(x * x - 0.5), (0.5, -0.25), (1.0, 0.5), 0.0, 400).unwrap();
        assert!((r - 0.5f64.sqrt()).abs() < 1e-15);
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
}
