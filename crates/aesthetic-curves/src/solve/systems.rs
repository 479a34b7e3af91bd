//! Systems of equations and fixed points: damped Newton over an opaque state
//! ([`damped_newton`], with its [`DampedNewton`] limits and a [`System`] report) and
//! sweeps of block updates to a fixed point ([`sweep_to_fixed_point`], [`Sweeps`]).

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

#[cfg(test)]
mod tests {
    use super::*;

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
}
