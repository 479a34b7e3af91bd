//! Derivative-free minimisation with a report: the solver layer's first member.
//!
//! [`nelder_mead`] minimises a function of a few variables (the simplex method of Nelder and
//! Mead with the standard coefficients: reflection 1, expansion 2, contraction 1/2, shrink
//! 1/2). It stops when the simplex's spread of values is below `f_tol` (absolute) and its
//! extent below `x_tol`, or after `max_evaluations`; the returned [`Minimum`] says which.
//! Infeasible points are the caller's to map to a large value (`f64::INFINITY` works: such
//! vertices are always replaced first).

/// Stopping rules of [`nelder_mead`].
#[derive(Clone, Copy, Debug)]
pub struct Options {
    /// Stop when the simplex's values differ by less than this.
    pub f_tol: f64,
    /// ... and its vertices by less than this in every coordinate.
    pub x_tol: f64,
    /// Most function evaluations.
    pub max_evaluations: usize,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            f_tol: 1e-12,
            x_tol: 1e-8,
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
    let mut simplex: Vec<(Vec<f64>, f64)> = Vec::with_capacity(n + 1);
    let v0 = eval(x0, &mut evals);
    simplex.push((x0.to_vec(), v0));
    for i in 0..n {
        let mut x = x0.to_vec();
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
        if (worst - best).abs() <= opts.f_tol && extent <= opts.x_tol {
            converged = true;
            break;
        }
        let centroid: Vec<f64> = (0..n)
            .map(|i| simplex[..n].iter().map(|s| s.0[i]).sum::<f64>() / n as f64)
            .collect();
        let along = |t: f64| -> Vec<f64> {
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
        x,
        value,
        evaluations: evals,
        converged,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
