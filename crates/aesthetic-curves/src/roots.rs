//! Bracketed scalar root finding shared by the solvers of the library.
//!
//! [`illinois`]: regula falsi with the Illinois modification (the retained end's value is
//! halved when the same end is kept twice), plus a plain bisection step every fourth
//! iteration, so the bracket always shrinks at least geometrically. It needs `f(lo)` and
//! `f(hi)` of opposite signs, stops when the bracket is narrower than `x_tol`, and reports
//! [`Error::NoConvergence`] instead of looping past `max_iter`.

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

#[cfg(test)]
mod tests {
    use super::*;

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
