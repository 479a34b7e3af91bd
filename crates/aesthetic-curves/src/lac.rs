//! Log-aesthetic curves (LAC) in standard form (math.md §3; seeds S0 §3, S4 §2).
//!
//! Tangent angle θ is the parameter; the radius of curvature is
//! `ρ(ψ) = ((α-1) Λ ψ + 1)^(1/(α-1))` (α ≠ 1) or `e^(Λψ)` (α = 1) and
//! `P(θ) = ∫_0^θ ρ(ψ) e^{iψ} dψ`, so `P(0) = 0`, the tangent at 0 is +x and curvature at 0 is 1.
//!
//! ## Evaluation
//!
//! - α = 1 (logarithmic spiral) and Λ = 0 (unit circle): closed forms.
//! - Otherwise the integral is taken in `w = ln u`, `u = (α-1) Λ ψ + 1`:
//!   `P(θ) = (1/c) ∫_0^{ln(1 + cθ)} e^{(p+1) w} e^{i expm1(w)/c} dw`, `c = (α-1) Λ`,
//!   `p + 1 = α/(α-1)`. The power singularity of ρ at the end of the domain (u → 0) becomes an
//!   exponential decay over a long but smooth interval, so adaptive Gauss–Kronrod converges
//!   right up to the singular end; `ln1p`/`expm1` keep full relative accuracy as Λ → 0 or
//!   α → 1. Requested accuracy: 1e-15 of the arc length.
//! - Arc length and curvature have closed forms for every α.
//!
//! The domain is `(α-1) Λ θ + 1 > 0`; outside it there is no curve: [`Error::InvalidInput`].

use crate::error::{Error, Result};
use crate::quadrature::{integrate, QuadOptions};
use kurbo::{Point, Vec2};

/// A log-aesthetic curve in standard form.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LacStandard {
    alpha: f64,
    lambda: f64,
}

/// Longest stretch of one integral, in quarter turns (1000 full turns).
pub const MAX_QUARTER_TURNS: f64 = 4000.0;

/// Largest |α| accepted.
pub const MAX_ABS_ALPHA: f64 = 1e6;

impl LacStandard {
    /// The standard-form curve with shape parameter `alpha` and `lambda` (both finite).
    pub fn new(alpha: f64, lambda: f64) -> Result<Self> {
        if !alpha.is_finite() || alpha.abs() > MAX_ABS_ALPHA {
            return Err(Error::invalid(
                "alpha",
                format!("must be a finite number with |alpha| <= {MAX_ABS_ALPHA}"),
            ));
        }
        if !lambda.is_finite() {
            return Err(Error::invalid("lambda", "must be finite"));
        }
        Ok(LacStandard { alpha, lambda })
    }

    /// α.
    pub fn alpha(&self) -> f64 {
        self.alpha
    }
    /// Λ.
    pub fn lambda(&self) -> f64 {
        self.lambda
    }

    fn c(&self) -> f64 {
        (self.alpha - 1.0) * self.lambda
    }

    /// Whether θ lies in the domain `(α-1) Λ θ + 1 > 0`.
    pub fn in_domain(&self, theta: f64) -> bool {
        theta.is_finite()
            && (self.alpha == 1.0 || {
                let (x, xe) = self.x_dd(theta);
                let (u, ue) = two_sum(1.0, x);
                u + (ue + xe) > 0.0
            })
    }

    /// The open interval of admissible θ.
    pub fn domain(&self) -> (f64, f64) {
        let c = self.c();
        if self.alpha == 1.0 || c == 0.0 {
            (f64::NEG_INFINITY, f64::INFINITY)
        } else if c > 0.0 {
            (-1.0 / c, f64::INFINITY)
        } else {
            (f64::NEG_INFINITY, -1.0 / c)
        }
    }

    fn check(&self, theta: f64) -> Result<()> {
        if !self.in_domain(theta) {
            let (lo, hi) = self.domain();
            return Err(Error::invalid(
                "theta",
                format!(
                    "theta = {theta} is outside the domain (alpha-1) lambda theta + 1 > 0, \
                     i.e. {lo} < theta < {hi}"
                ),
            ));
        }
        Ok(())
    }

    /// `x = (α-1) Λ θ` as an unevaluated sum `hi + lo` (error-free transformations): near the
    /// singular end `u = 1 + x` cancels, and θ's last bits matter.
    fn x_dd(&self, theta: f64) -> (f64, f64) {
        let (a1, a1e) = two_sum(self.alpha, -1.0);
        let (c, mut ce) = two_prod(a1, self.lambda);
        ce += a1e * self.lambda;
        let (x, mut xe) = two_prod(c, theta);
        xe += ce * theta;
        (x, xe)
    }

    /// `ln u = ln(1 + (α-1) Λ θ)` (α ≠ 1), to full relative accuracy near u = 0 and u = 1.
    fn log_u(&self, theta: f64) -> f64 {
        let (x, xe) = self.x_dd(theta);
        if x.abs() < 0.25 {
            x.ln_1p() + xe / (1.0 + x)
        } else {
            let (u, mut ue) = two_sum(1.0, x);
            ue += xe;
            u.ln() + ue / u
        }
    }

    /// Radius of curvature ρ(θ).
    pub fn rho(&self, theta: f64) -> Result<f64> {
        self.check(theta)?;
        Ok(if self.alpha == 1.0 {
            (self.lambda * theta).exp()
        } else {
            (self.log_u(theta) / (self.alpha - 1.0)).exp()
        })
    }

    /// Curvature 1/ρ(θ) (positive: the standard form turns counter-clockwise).
    pub fn kappa(&self, theta: f64) -> Result<f64> {
        self.check(theta)?;
        Ok(if self.alpha == 1.0 {
            (-self.lambda * theta).exp()
        } else {
            (-self.log_u(theta) / (self.alpha - 1.0)).exp()
        })
    }

    /// Signed arc length from θ = 0 (negative for θ < 0), closed form:
    /// `((1+(α-1)Λθ)^(α/(α-1)) - 1)/(αΛ)`; α = 0: `-ln(1-Λθ)/Λ`; α = 1: `(e^{Λθ}-1)/Λ`.
    pub fn arc_length(&self, theta: f64) -> Result<f64> {
        self.check(theta)?;
        let (a, l) = (self.alpha, self.lambda);
        Ok(if l == 0.0 {
            theta
        } else if a == 1.0 {
            (l * theta).exp_m1() / l
        } else if a == 0.0 {
            -(-l * theta).ln_1p() / l
        } else {
            (a / (a - 1.0) * self.log_u(theta)).exp_m1() / (a * l)
        })
    }

    /// The point P(θ).
    pub fn eval(&self, theta: f64) -> Result<Point> {
        Ok(self.integral(0.0, theta)?.to_point())
    }

    /// Points at many θ, integrating only between neighbours (sorted internally), so a
    /// polyline costs about as much as its last point.
    pub fn eval_many(&self, thetas: &[f64]) -> Result<Vec<Point>> {
        for &t in thetas {
            self.check(t)?;
        }
        let mut order: Vec<usize> = (0..thetas.len()).collect();
        order.sort_by(|&i, &j| thetas[i].total_cmp(&thetas[j]));
        let mut out = vec![Point::ZERO; thetas.len()];
        // Walk outward from θ = 0 in both directions.
        let split = order.partition_point(|&i| thetas[i] < 0.0);
        let mut acc = Vec2::ZERO;
        let mut prev = 0.0;
        for &i in &order[split..] {
            acc += self.integral(prev, thetas[i])?;
            prev = thetas[i];
            out[i] = acc.to_point();
        }
        acc = Vec2::ZERO;
        prev = 0.0;
        for &i in order[..split].iter().rev() {
            acc += self.integral(prev, thetas[i])?;
            prev = thetas[i];
            out[i] = acc.to_point();
        }
        Ok(out)
    }

    /// `∫_{t0}^{t1} ρ(ψ) e^{iψ} dψ` as a complex number (x = real part).
    pub fn integral(&self, t0: f64, t1: f64) -> Result<Vec2> {
        let v = self.integral_unchecked(t0, t1)?;
        if !v.is_finite() {
            return Err(Error::invalid(
                "theta",
                format!("the curve between theta = {t0} and {t1} is too large for f64"),
            ));
        }
        Ok(v)
    }

    fn integral_unchecked(&self, t0: f64, t1: f64) -> Result<Vec2> {
        self.check(t0)?;
        self.check(t1)?;
        if t0 == t1 {
            return Ok(Vec2::ZERO);
        }
        let (a, l) = (self.alpha, self.lambda);
        if l == 0.0 {
            // Unit circle: -i (e^{i t1} - e^{i t0}).
            return Ok(Vec2::new(t1.sin() - t0.sin(), t0.cos() - t1.cos()));
        }
        if a == 1.0 {
            return Ok(log_spiral(l, t1) - log_spiral(l, t0));
        }
        let c = self.c();
        let p1 = a / (a - 1.0);
        // At most a quarter turn per piece: adaptive quadrature must never be fooled by an
        // oscillation it did not sample.
        let pieces = ((t1 - t0).abs() / std::f64::consts::FRAC_PI_2)
            .ceil()
            .max(1.0);
        if pieces > MAX_QUARTER_TURNS {
            return Err(Error::invalid(
                "theta",
                format!(
                    "the curve from theta = {t0} to {t1} turns more than {} times",
                    MAX_QUARTER_TURNS / 4.0
                ),
            ));
        }
        let len = (self.arc_length(t1)? - self.arc_length(t0)?).abs();
        // The w-integral is c times the result: scale the accuracy alike.
        let opts = QuadOptions {
            accuracy: (1e-15 * len * c.abs() / pieces).max(f64::MIN_POSITIVE),
            max_panels: 2_000,
        };
        let n = pieces as usize;
        let mut sum = Vec2::ZERO;
        let mut w_prev = self.log_u(t0);
        for k in 1..=n {
            let t = if k == n {
                t1
            } else {
                t0 + (t1 - t0) * (k as f64 / n as f64)
            };
            let w = self.log_u(t);
            sum += integrate(
                |w| {
                    let mag = (p1 * w).exp();
                    let psi = w.exp_m1() / c;
                    Vec2::new(mag * psi.cos(), mag * psi.sin())
                },
                w_prev,
                w,
                opts,
            )?;
            w_prev = w;
        }
        Ok(sum / c)
    }
}

/// `a + b` as `(sum, rounding error)`.
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `a * b` as `(product, rounding error)`.
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// `(e^{(Λ+i)θ} - 1)/(Λ+i)`, with the numerator written to avoid cancellation for small θ.
fn log_spiral(l: f64, theta: f64) -> Vec2 {
    let e = (l * theta).exp_m1();
    let (s, co) = theta.sin_cos();
    let half = (0.5 * theta).sin();
    let num = Vec2::new(e * co - 2.0 * half * half, (e + 1.0) * s);
    // divide by (l + i): multiply by (l - i)/(l^2 + 1)
    let d = l * l + 1.0;
    Vec2::new((num.x * l + num.y) / d, (num.y * l - num.x) / d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    fn rel(a: Point, re: f64, im: f64) -> f64 {
        ((a.x - re).powi(2) + (a.y - im).powi(2)).sqrt() / (re * re + im * im).sqrt()
    }

    #[test]
    fn math_md_values() {
        let p = LacStandard::new(-1.0, 0.2)
            .unwrap()
            .eval(FRAC_PI_2)
            .unwrap();
        assert!(rel(p, 1.15706838800915, 1.32155123083178) < 1e-13, "{p:?}");
        let p = LacStandard::new(2.0, 0.5).unwrap().eval(FRAC_PI_2).unwrap();
        assert!(
            rel(p, std::f64::consts::FRAC_PI_4 + 0.5, 1.5) < 1e-14,
            "{p:?}"
        );
        let p = LacStandard::new(1.0, 0.5).unwrap().eval(FRAC_PI_2).unwrap();
        assert!(rel(p, 1.35462404059041, 1.67731202029521) < 1e-13, "{p:?}");
    }

    #[test]
    fn continuity_in_alpha_and_lambda() {
        let t = 1.3;
        let one = LacStandard::new(1.0, 0.7).unwrap().eval(t).unwrap();
        for a in [1.0 - 1e-9, 1.0 + 1e-9] {
            let q = LacStandard::new(a, 0.7).unwrap().eval(t).unwrap();
            assert!((q - one).hypot() < 1e-8, "{a}: {q:?} vs {one:?}");
        }
        let circle = LacStandard::new(-1.0, 0.0).unwrap().eval(t).unwrap();
        let near = LacStandard::new(-1.0, 1e-12).unwrap().eval(t).unwrap();
        assert!((circle - near).hypot() < 1e-11);
    }

    #[test]
    fn arc_length_matches_the_speed() {
        for (a, l) in [(-1.0, 0.3), (0.0, 0.4), (0.5, 0.2), (2.0, 0.5), (3.5, 0.1)] {
            let c = LacStandard::new(a, l).unwrap();
            let s = c.arc_length(1.0).unwrap();
            let q = integrate(
                |t| Vec2::new(c.rho(t).unwrap(), 0.0),
                0.0,
                1.0,
                QuadOptions::default(),
            )
            .unwrap();
            assert!((s - q.x).abs() < 1e-13 * s, "{a} {l}: {s} vs {}", q.x);
        }
    }

    #[test]
    fn eval_many_matches_eval_and_domain_is_checked() {
        let c = LacStandard::new(-2.0, 0.3).unwrap();
        let th = [0.5, -0.4, 1.0, 0.0, 0.7];
        let many = c.eval_many(&th).unwrap();
        for (t, p) in th.iter().zip(&many) {
            assert!((c.eval(*t).unwrap() - *p).hypot() < 1e-14);
        }
        // (α-1) Λ θ + 1 > 0: θ < 1/0.9 for α = -2, Λ = 0.3.
        assert!(c.eval(1.2).is_err());
        assert!(LacStandard::new(f64::NAN, 0.1).is_err());
    }
}
