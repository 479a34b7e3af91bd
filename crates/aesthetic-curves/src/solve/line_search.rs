//! Minimisers of one variable on an interval: golden sections ([`golden_section`] for a
//! fixed number of steps, [`golden_bracket`] to a width), Brent's parabolic steps
//! ([`brent`]) and a descent-safeguarded Newton iteration ([`newton_min_1d`]).

use super::roots::Stop1d;

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

#[cfg(test)]
mod tests {
    use super::*;

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
    fn brent_finds_the_minimum_of_a_unimodal_function() {
        // cos on [2, 5]: minimum at π; x^4 at 0 (no parabola fits exactly there).
        let (x, v) = brent(&mut |x: f64| x.cos(), 2.0, 5.0, 1e-10);
        assert!((x - std::f64::consts::PI).abs() < 1e-8 && (v + 1.0).abs() < 1e-15);
        let (x, _) = brent(&mut |x: f64| x.powi(4), -1.0, 2.0, 1e-10);
        assert!(x.abs() < 1e-3, "{x}");
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
}
