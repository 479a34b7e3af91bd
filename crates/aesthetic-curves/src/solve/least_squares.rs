//! Levenberg–Marquardt for small nonlinear least-squares problems (N parameters fixed at
//! compile time, any number of residuals): the one implementation behind the rational-cubic
//! fit of a LAC segment and the single-LAC fit of a point sequence.
//!
//! **Algorithm.** At the current point x with residual vector r and forward-difference
//! Jacobian J (step `fd_step · max(|x_i|, 1)`, backwards when the forward point cannot be
//! evaluated), the damped normal equations `(JᵀJ + μ (diag JᵀJ + damping_floor)) d = -Jᵀr`
//! are solved by Cholesky; a step that lowers the sum of squares (and that `feasible`
//! accepts) is taken and μ shrinks by 0.3, otherwise μ grows by 10 and the step is retried
//! (at most `max_damping_tries` times).
//!
//! **Contract.** The returned [`LeastSquares`] says why the run ended ([`Stop`]): converged
//! (the Gauss–Newton step predicts a gain of at most `rel_progress` of the cost, an accepted
//! step gained at most that or moved less than `min_step` in the 1-norm, or no damping found
//! a better point), the iteration limit, abandoned (still
//! above `abandon_above` after `abandon_after` iterations, or the Gauss–Newton model's
//! minimum above `abandon_predicted_above`), a Jacobian point that could not
//! be evaluated, the thread's deadline ([`crate::deadline`]), or a start that could not be
//! evaluated. It never loops past its limits and never panics on NaN residuals (a point with
//! a non-finite cost is refused like an invalid one).

use nalgebra::allocator::Allocator;
use nalgebra::{Const, DefaultAllocator, Dim, Dyn, OMatrix, OVector};

/// Stopping rules and damping of [`levenberg_marquardt`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LmOptions {
    /// Most iterations (Jacobian evaluations).
    pub max_iterations: usize,
    /// The initial damping μ, relative to the diagonal of JᵀJ.
    pub mu0: f64,
    /// Converged when an accepted step gains no more than this fraction of the cost.
    pub rel_progress: f64,
    /// ... or moves less than this (1-norm).
    pub min_step: f64,
    /// Damping retries per iteration before the run counts as converged.
    pub max_damping_tries: usize,
    /// Added to the diagonal before it is scaled by μ (keeps a zero column solvable).
    pub damping_floor: f64,
    /// Relative step of the forward differences.
    pub fd_step: f64,
    /// Abandon a run still above `abandon_above` (sum of squares) after this many
    /// iterations: it is crawling along a valley towards a minimum worse than one known.
    pub abandon_after: usize,
    /// See `abandon_after`.
    pub abandon_above: f64,
    /// Abandon a run whose Gauss–Newton model predicts a minimum (the cost less the full
    /// step's predicted gain) above this, once the model has proven itself (the last step
    /// gained within 10 % of the model's prediction) and predicts at most a tenfold gain:
    /// the valley it is in bottoms out worse than a minimum already known.
    pub abandon_predicted_above: f64,
}

impl Default for LmOptions {
    /// To convergence at 1e-12 relative progress, 60 iterations, never abandoned.
    fn default() -> Self {
        LmOptions {
            max_iterations: 60,
            mu0: 1e-3,
            rel_progress: 1e-12,
            min_step: 0.0,
            max_damping_tries: 10,
            damping_floor: 1e-12,
            fd_step: 1e-7,
            abandon_after: usize::MAX,
            abandon_above: f64::INFINITY,
            abandon_predicted_above: f64::INFINITY,
        }
    }
}

/// Why [`levenberg_marquardt`] stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    /// The stopping test was met: the point is a local minimum to the stated progress.
    Converged,
    /// `max_iterations` ran out first.
    IterationLimit,
    /// Still above `abandon_above` after `abandon_after` iterations.
    Abandoned,
    /// A point of the finite-difference Jacobian could not be evaluated either way.
    Unevaluable,
    /// The thread's deadline passed.
    Deadline,
    /// The start could not be evaluated (the cost is infinite).
    InvalidStart,
}

/// The result of [`levenberg_marquardt`]: the best point found and how the run ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LeastSquares<const N: usize> {
    /// The best point found.
    pub x: [f64; N],
    /// Its sum of squared residuals (infinite for [`Stop::InvalidStart`]).
    pub cost: f64,
    /// Residual evaluations spent (the Jacobian's included).
    pub evaluations: usize,
    /// Iterations done.
    pub iterations: usize,
    /// Why the run ended.
    pub stop: Stop,
}

impl<const N: usize> LeastSquares<N> {
    /// Whether the run met its stopping test.
    pub fn converged(&self) -> bool {
        self.stop == Stop::Converged
    }
}

/// The residuals of a point: fills the vector, `None` where the problem is not defined.
pub type ResidualFn<'a, const N: usize> = dyn FnMut(&[f64; N], &mut Vec<f64>) -> Option<()> + 'a;

/// The residuals of a point and their derivatives (one column per parameter).
pub type JacobianFn<'a, const N: usize> =
    dyn FnMut(&[f64; N], &mut Vec<f64>, &mut [Vec<f64>; N]) -> Option<()> + 'a;

/// Minimise the sum of squares of `residuals(x)` (it fills its vector; `None` for a point
/// where the problem is not defined) from `x0`; a step is only taken where `feasible` holds.
/// See the module documentation for the algorithm and the stopping rules.
pub fn levenberg_marquardt<const N: usize>(
    residuals: &mut ResidualFn<N>,
    feasible: &dyn Fn(&[f64; N]) -> bool,
    x0: [f64; N],
    opts: &LmOptions,
) -> LeastSquares<N> {
    solve(residuals, None, feasible, x0, opts)
}

/// [`levenberg_marquardt`] with the Jacobian in closed form: `jacobian(x)` fills the
/// residuals and their columns, instead of N forward differences (it counts as one
/// evaluation). Trial points are evaluated with it, so an accepted step brings the next
/// iteration's Jacobian along; `residuals` serves only the start.
pub fn levenberg_marquardt_jac<const N: usize>(
    residuals: &mut ResidualFn<N>,
    jacobian: &mut JacobianFn<N>,
    feasible: &dyn Fn(&[f64; N]) -> bool,
    x0: [f64; N],
    opts: &LmOptions,
) -> LeastSquares<N> {
    solve(residuals, Some(jacobian), feasible, x0, opts)
}

fn solve<const N: usize>(
    residuals: &mut ResidualFn<N>,
    jacobian: Option<&mut JacobianFn<N>>,
    feasible: &dyn Fn(&[f64; N]) -> bool,
    x0: [f64; N],
    opts: &LmOptions,
) -> LeastSquares<N> {
    let mut res = |x: &[f64], r: &mut Vec<f64>| residuals(<&[f64; N]>::try_from(x).ok()?, r);
    let feas = |x: &[f64]| <&[f64; N]>::try_from(x).is_ok_and(feasible);
    let fit = match jacobian {
        Some(jf) => {
            let mut jac = |x: &[f64], r: &mut Vec<f64>, j: &mut [Vec<f64>]| {
                jf(
                    <&[f64; N]>::try_from(x).ok()?,
                    r,
                    <&mut [Vec<f64>; N]>::try_from(j).ok()?,
                )
            };
            solve_in(
                Const::<N>,
                &mut res,
                Some(&mut jac),
                &feas,
                x0.to_vec(),
                opts,
            )
        }
        None => solve_in(Const::<N>, &mut res, None, &feas, x0.to_vec(), opts),
    };
    LeastSquares {
        x: <[f64; N]>::try_from(&fit.x[..]).unwrap_or(x0),
        cost: fit.cost,
        evaluations: fit.evaluations,
        iterations: fit.iterations,
        stop: fit.stop,
    }
}

/// The residuals of a point of any dimension (see [`ResidualFn`]).
pub type DynResidualFn<'a> = dyn FnMut(&[f64], &mut Vec<f64>) -> Option<()> + 'a;

/// The residuals of a point of any dimension and their columns (see [`JacobianFn`]).
pub type DynJacobianFn<'a> = dyn FnMut(&[f64], &mut Vec<f64>, &mut [Vec<f64>]) -> Option<()> + 'a;

/// The result of [`levenberg_marquardt_dyn`]: as [`LeastSquares`], of any dimension.
#[derive(Clone, Debug, PartialEq)]
pub struct LeastSquaresDyn {
    /// The best point found.
    pub x: Vec<f64>,
    /// Its sum of squared residuals (infinite for [`Stop::InvalidStart`]).
    pub cost: f64,
    /// Residual evaluations spent (the Jacobian's included).
    pub evaluations: usize,
    /// Iterations done.
    pub iterations: usize,
    /// Why the run ended.
    pub stop: Stop,
}

/// [`levenberg_marquardt_jac`] for a number of parameters known only at run time (the
/// handle lengths of a whole contour): `jacobian` (None: forward differences) fills the
/// residuals and one column per parameter. The same algorithm and stopping rules.
pub fn levenberg_marquardt_dyn(
    residuals: &mut DynResidualFn,
    jacobian: Option<&mut DynJacobianFn>,
    feasible: &dyn Fn(&[f64]) -> bool,
    x0: Vec<f64>,
    opts: &LmOptions,
) -> LeastSquaresDyn {
    solve_in(Dyn(x0.len()), residuals, jacobian, feasible, x0, opts)
}

/// The forward-difference columns at `x` (backwards where the forward point cannot be
/// evaluated); false where neither can, with the evaluations spent added.
fn differences(
    residuals: &mut DynResidualFn,
    (x, r): (&[f64], &[f64]),
    jac: &mut [Vec<f64>],
    (fd_step, evaluations): (f64, &mut usize),
) -> bool {
    let mut rp = Vec::new();
    let mut xp = x.to_vec();
    for (i, col) in jac.iter_mut().enumerate() {
        let h = fd_step * x[i].abs().max(1.0);
        xp[i] = x[i] + h;
        *evaluations += 1;
        let s = if residuals(&xp, &mut rp).is_some() {
            h
        } else {
            xp[i] = x[i] - h;
            *evaluations += 1;
            if residuals(&xp, &mut rp).is_none() {
                return false;
            }
            -h
        };
        xp[i] = x[i];
        col.clear();
        col.extend(rp.iter().zip(r).map(|(a, b)| (a - b) / s));
    }
    true
}

/// JᵀJ and Jᵀr of the columns `jac` and residuals `r`.
fn normal_equations<D: Dim>(
    dim: D,
    jac: &[Vec<f64>],
    r: &[f64],
) -> (OMatrix<f64, D, D>, OVector<f64, D>)
where
    DefaultAllocator: Allocator<D, D> + Allocator<D>,
{
    let n = jac.len();
    let mut jtj = OMatrix::<f64, D, D>::zeros_generic(dim, dim);
    let mut g = OVector::<f64, D>::zeros_generic(dim, Const::<1>);
    for i in 0..n {
        for j in i..n {
            let v: f64 = jac[i].iter().zip(&jac[j]).map(|(a, b)| a * b).sum();
            jtj[(i, j)] = v;
            jtj[(j, i)] = v;
        }
        g[i] = jac[i].iter().zip(r).map(|(a, b)| a * b).sum();
    }
    (jtj, g)
}

/// The algorithm, with its matrices of dimension `dim` (on the stack for a `Const`).
fn solve_in<D: Dim>(
    dim: D,
    residuals: &mut DynResidualFn,
    mut jacobian: Option<&mut DynJacobianFn>,
    feasible: &dyn Fn(&[f64]) -> bool,
    x0: Vec<f64>,
    opts: &LmOptions,
) -> LeastSquaresDyn
where
    DefaultAllocator: Allocator<D, D> + Allocator<D>,
{
    let n = x0.len();
    let sum_sq = |r: &[f64]| r.iter().map(|v| v * v).sum::<f64>();
    let mut x = x0;
    let mut r = Vec::new();
    let mut rp = Vec::new();
    let mut out = LeastSquaresDyn {
        x: x.clone(),
        cost: f64::INFINITY,
        evaluations: 1,
        iterations: 0,
        stop: Stop::InvalidStart,
    };
    if residuals(&x, &mut r).is_none() {
        return out;
    }
    let mut cost = sum_sq(&r);
    if !cost.is_finite() {
        return out;
    }
    out.cost = cost;
    let mut mu = opts.mu0;
    let mut jac: Vec<Vec<f64>> = vec![Vec::new(); n];
    out.stop = Stop::IterationLimit;
    let mut trusted = false;
    // With a closed-form Jacobian, trial points are evaluated with it (most are accepted,
    // and then the next iteration needs it there): `have_jac` says `jac` belongs to `x`.
    let mut have_jac = false;
    let mut jac_trial: Vec<Vec<f64>> = vec![Vec::new(); n];
    for iter in 0..opts.max_iterations {
        if iter >= opts.abandon_after && cost > opts.abandon_above {
            out.stop = Stop::Abandoned;
            break;
        }
        if crate::deadline::expired() {
            out.stop = Stop::Deadline;
            break;
        }
        out.iterations = iter + 1;
        let evaluable = if let Some(jf) = jacobian.as_deref_mut() {
            // (An accepted trial point brought its Jacobian along.)
            let ok = have_jac || {
                out.evaluations += 1;
                jf(&x, &mut r, &mut jac).is_some()
            };
            have_jac = false;
            ok
        } else {
            let spent = (opts.fd_step, &mut out.evaluations);
            differences(residuals, (&x, &r), &mut jac, spent)
        };
        if !evaluable {
            out.stop = Stop::Unevaluable;
            break;
        }
        let (jtj, g) = normal_equations(dim, &jac, &r);
        // The Gauss–Newton step's predicted gain, -gᵀd (JᵀJ d = -g): when even it is below
        // the progress asked for, no damped step does better, and none is tried (with an
        // exact Jacobian, the steps at a minimum only find rounding).
        if let Some(ch) = jtj.clone().cholesky() {
            let d = ch.solve(&(-&g));
            let predicted = -g.dot(&d);
            if predicted.is_finite() && predicted <= opts.rel_progress * cost {
                out.stop = Stop::Converged;
                break;
            }
            // Only where the model has just proven itself (the last step gained within 10 %
            // of what the model predicted) and the run is near its floor (the model's
            // minimum within a factor 10 of the cost): far from a floor, or in a curved
            // valley, the model's minimum means little.
            let floor = cost - predicted;
            if trusted && floor >= 0.1 * cost && floor > opts.abandon_predicted_above {
                out.stop = Stop::Abandoned;
                break;
            }
        }
        let mut improved = false;
        for _ in 0..opts.max_damping_tries {
            let mut m = jtj.clone();
            for i in 0..n {
                m[(i, i)] += mu * (jtj[(i, i)] + opts.damping_floor);
            }
            let Some(step) = m.cholesky().map(|ch| ch.solve(&(-&g))) else {
                mu *= 10.0;
                continue;
            };
            let xn: Vec<f64> = x.iter().zip(step.iter()).map(|(a, d)| a + d).collect();
            let evaluated = feasible(&xn)
                && match jacobian.as_deref_mut() {
                    Some(jf) => jf(&xn, &mut rp, &mut jac_trial).is_some(),
                    None => residuals(&xn, &mut rp).is_some(),
                };
            let new_cost = if evaluated {
                out.evaluations += 1;
                sum_sq(&rp)
            } else {
                f64::INFINITY
            };
            if new_cost < cost {
                let small = step.iter().map(|d| d.abs()).sum::<f64>() < opts.min_step
                    || cost - new_cost <= opts.rel_progress * cost;
                // The model's gain for this step: -(2 gᵀd + dᵀ JᵀJ d).
                let model_gain = -(2.0 * g.dot(&step) + step.dot(&(&jtj * &step)));
                let ratio = (cost - new_cost) / model_gain;
                trusted = (0.9..=1.1).contains(&ratio);
                x = xn;
                cost = new_cost;
                std::mem::swap(&mut r, &mut rp);
                if jacobian.is_some() {
                    std::mem::swap(&mut jac, &mut jac_trial);
                    have_jac = true;
                }
                mu = (mu * 0.3).max(1e-12);
                improved = !small;
                break;
            }
            mu *= 10.0;
        }
        if !improved {
            out.stop = Stop::Converged;
            break;
        }
    }
    out.x = x;
    out.cost = cost;
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fits_an_exponential_and_reports_why_it_stopped() {
        // y = 2 e^{-1.5 t} sampled exactly: the parameters come back, converged.
        let ts: Vec<f64> = (0..20).map(|i| i as f64 * 0.1).collect();
        let mut res = |x: &[f64; 2], out: &mut Vec<f64>| {
            out.clear();
            out.extend(
                ts.iter()
                    .map(|&t| x[0] * (-x[1] * t).exp() - 2.0 * (-1.5 * t).exp()),
            );
            Some(())
        };
        let fit = levenberg_marquardt(&mut res, &|_| true, [1.0, 1.0], &LmOptions::default());
        assert!(fit.converged(), "{fit:?}");
        assert!(
            (fit.x[0] - 2.0).abs() < 1e-7 && (fit.x[1] - 1.5).abs() < 1e-7,
            "{fit:?}"
        );
        assert!(fit.cost < 1e-20);
        // Out of iterations: said so, with the best point so far.
        let opts = LmOptions {
            max_iterations: 1,
            ..LmOptions::default()
        };
        let fit = levenberg_marquardt(&mut res, &|_| true, [1.0, 1.0], &opts);
        assert_eq!(fit.stop, Stop::IterationLimit);
        assert_eq!(fit.iterations, 1);
        // Abandoned above a bound.
        let opts = LmOptions {
            abandon_after: 0,
            abandon_above: 1e-30,
            ..LmOptions::default()
        };
        let fit = levenberg_marquardt(&mut res, &|_| true, [1.0, 1.0], &opts);
        assert_eq!(fit.stop, Stop::Abandoned);
        // With data the model cannot fit exactly (minimum sum of squares about 2e-3): a run
        // is abandoned once the trusted Gauss–Newton model's minimum is above a bound below
        // that, and converges when the bound is above it.
        let mut noisy = |x: &[f64; 2], out: &mut Vec<f64>| {
            out.clear();
            out.extend(ts.iter().enumerate().map(|(i, &t)| {
                let wiggle = if i % 2 == 0 { 0.01 } else { -0.01 };
                x[0] * (-x[1] * t).exp() - 2.0 * (-1.5 * t).exp() - wiggle
            }));
            Some(())
        };
        let free = levenberg_marquardt(&mut noisy, &|_| true, [1.0, 1.0], &LmOptions::default());
        assert!(
            free.converged() && free.cost > 1e-3 && free.cost < 3e-3,
            "{free:?}"
        );
        let opts = LmOptions {
            abandon_predicted_above: 0.5 * free.cost,
            ..LmOptions::default()
        };
        let cut = levenberg_marquardt(&mut noisy, &|_| true, [1.0, 1.0], &opts);
        assert_eq!(cut.stop, Stop::Abandoned, "{cut:?}");
        assert!(cut.evaluations < free.evaluations, "{cut:?} vs {free:?}");
        let opts = LmOptions {
            abandon_predicted_above: 2.0 * free.cost,
            ..LmOptions::default()
        };
        assert!(levenberg_marquardt(&mut noisy, &|_| true, [1.0, 1.0], &opts).converged());
    }

    #[test]
    fn a_closed_form_jacobian_gives_the_same_minimum_for_fewer_evaluations() {
        let ts: Vec<f64> = (0..20).map(|i| i as f64 * 0.1).collect();
        let target = |t: f64| 2.0 * (-1.5 * t).exp() + 0.01 * (7.0 * t).sin();
        let mut res = |x: &[f64; 2], out: &mut Vec<f64>| {
            out.clear();
            out.extend(ts.iter().map(|&t| x[0] * (-x[1] * t).exp() - target(t)));
            Some(())
        };
        let mut jac = |x: &[f64; 2], out: &mut Vec<f64>, j: &mut [Vec<f64>; 2]| {
            out.clear();
            j[0].clear();
            j[1].clear();
            for &t in &ts {
                let e = (-x[1] * t).exp();
                out.push(x[0] * e - target(t));
                j[0].push(e);
                j[1].push(-t * x[0] * e);
            }
            Some(())
        };
        let opts = LmOptions::default();
        let fd = levenberg_marquardt(&mut res, &|_| true, [1.0, 1.0], &opts);
        let cf = levenberg_marquardt_jac(&mut res, &mut jac, &|_| true, [1.0, 1.0], &opts);
        assert!(fd.converged() && cf.converged(), "{fd:?} {cf:?}");
        assert!((fd.x[0] - cf.x[0]).abs() < 1e-7 && (fd.x[1] - cf.x[1]).abs() < 1e-7);
        assert!((fd.cost - cf.cost).abs() <= 1e-9 * fd.cost, "{fd:?} {cf:?}");
        assert!(cf.evaluations < fd.evaluations, "{fd:?} {cf:?}");
    }

    #[test]
    fn invalid_points_are_refused_not_followed() {
        // The minimum of (x - 3)² lies outside the feasible x <= 2: the run stops at the
        // boundary's side, never evaluates past it, and a bad start is reported.
        let mut res = |x: &[f64; 1], out: &mut Vec<f64>| {
            assert!(x[0] <= 2.0 + 1e-6, "evaluated at {}", x[0]);
            out.clear();
            out.push(x[0] - 3.0);
            Some(())
        };
        let fit = levenberg_marquardt(&mut res, &|x| x[0] <= 2.0, [0.0], &LmOptions::default());
        assert!(fit.x[0] <= 2.0 && fit.x[0] > 1.9, "{fit:?}");
        let mut nan = |_: &[f64; 1], out: &mut Vec<f64>| {
            out.clear();
            out.push(f64::NAN);
            Some(())
        };
        let fit = levenberg_marquardt(&mut nan, &|_| true, [0.0], &LmOptions::default());
        assert_eq!(fit.stop, Stop::InvalidStart);
        let mut none = |_: &[f64; 1], _: &mut Vec<f64>| None;
        let fit = levenberg_marquardt(&mut none, &|_| true, [0.0], &LmOptions::default());
        assert_eq!(fit.stop, Stop::InvalidStart);
        assert!(fit.cost.is_infinite());
    }
}
