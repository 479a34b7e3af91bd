//! Bracketed scalar root finding shared by the solvers of the library.
//!
//! [`illinois`]: regula falsi with the Illinois modification (the retained end's value is
//! halved when the same end is kept twice), plus a plain bisection step every fourth
//! iteration, so the bracket always shrinks at least geometrically. It needs `f(lo)` and
//! `f(hi)` of opposite signs, stops when the bracket is narrower than `x_tol`, and reports
//! [`Error::NoConvergence`] instead of looping past `max_iter`.
//!
//! [`brent`]: Brent's method (inverse quadratic interpolation, secant and bisection steps)
//! from a bracket narrowed by the caller's guesses, for callers that can guess.
//!
//! [`newton`]: Newton's method for a monotone function whose derivative comes with its value
//! at little extra cost, kept inside a bracket (a step that leaves it bisects instead),
//! stopping when the next step is predicted to move less than `x_tol`; it reports how it
//! ended ([`NewtonRoot::converged`]) instead of failing, so a caller can fall back.

use crate::error::{Error, Result};

/// A root of `f` in the bracket `[lo, hi]` (with known values `flo`, `fhi` of opposite
/// signs) to within `x_tol`. Errors of `f` are passed through.
pub fn illinois(
    mut f: impl FnMut(f64) -> Result<f64>,
    (mut lo, mut flo): (f64, f64),
    (mut hi, mut fhi): (f64, f64),
    x_tol: f64,
    max_iter: usize,
) -> Result<f64> {
    if flo == 0.0 {
        return Ok(lo);
    }
    if fhi == 0.0 {
        return Ok(hi);
    }
    if (flo > 0.0) == (fhi > 0.0) || flo.is_nan() || fhi.is_nan() {
        return Err(Error::NoConvergence(format!(
            "root bracket [{lo}, {hi}] does not straddle a sign change ({flo}, {fhi})"
        )));
    }
    let mut side = 0i32;
    // The tolerance never asks for less than the spacing of floats in the bracket.
    let tol = |lo: f64, hi: f64| x_tol.max(4.0 * f64::EPSILON * lo.abs().max(hi.abs()));
    for it in 0..max_iter {
        if hi - lo <= tol(lo, hi) {
            return Ok(0.5 * (lo + hi));
        }
        let mut x = (lo * fhi - hi * flo) / (fhi - flo);
        if it % 4 == 3 || !(x > lo && x < hi) {
            x = 0.5 * (lo + hi);
        }
        let fx = f(x)?;
        if fx == 0.0 {
            return Ok(x);
        }
        if (fx > 0.0) == (flo > 0.0) {
            lo = x;
            flo = fx;
            if side == -1 {
                fhi *= 0.5;
            }
            side = -1;
        } else {
            hi = x;
            fhi = fx;
            if side == 1 {
                flo *= 0.5;
            }
            side = 1;
        }
    }
    if hi - lo <= tol(lo, hi) {
        Ok(0.5 * (lo + hi))
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

#[cfg(test)]
mod tests {
    use super::*;

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
}
