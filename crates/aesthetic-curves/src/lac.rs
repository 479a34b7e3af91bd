//! Log-aesthetic curves (LAC) in standard form (docs/math.md §3; seeds S0 §3, S4 §2).
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
use crate::roots::{brent, illinois};
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
            let range = if lo.is_finite() {
                format!("theta > {lo}")
            } else {
                format!("theta < {hi}")
            };
            return Err(Error::invalid(
                "theta",
                format!(
                    "theta = {theta} is outside the domain (alpha-1) lambda theta + 1 > 0, \
                     i.e. {range}"
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

    /// ln ρ(θ), without overflow where ρ itself would overflow.
    pub fn log_rho(&self, theta: f64) -> Result<f64> {
        self.check(theta)?;
        finite_or_err(
            theta,
            if self.alpha == 1.0 {
                self.lambda * theta
            } else {
                self.log_u(theta) / (self.alpha - 1.0)
            },
        )
    }

    /// Curvature at many θ (one domain check for all of them).
    pub fn kappa_many(&self, thetas: &[f64]) -> Result<Vec<f64>> {
        if thetas.is_empty() {
            return Ok(Vec::new());
        }
        let lo = thetas.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = thetas.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if let Some(t) = thetas.iter().find(|t| !t.is_finite()) {
            self.check(*t)?;
        }
        self.check(lo)?;
        self.check(hi)?;
        let (a, l) = (self.alpha, self.lambda);
        let out: Vec<f64> = if a == 1.0 {
            thetas.iter().map(|t| (-l * t).exp()).collect()
        } else {
            // κ = u^(-1/(α-1)); ln u from the double-double u (accurate near u = 1 too).
            let e = -1.0 / (a - 1.0);
            thetas
                .iter()
                .map(|t| {
                    let (x, xe) = self.x_dd(*t);
                    let (u, ue) = two_sum(1.0, x);
                    (e * (u.ln() + (ue + xe) / u)).exp()
                })
                .collect()
        };
        match out.iter().position(|k| !k.is_finite()) {
            Some(i) => finite_or_err(thetas[i], out[i]).map(|_| out),
            None => Ok(out),
        }
    }

    /// Radius of curvature ρ(θ).
    pub fn rho(&self, theta: f64) -> Result<f64> {
        self.check(theta)?;
        finite_or_err(
            theta,
            if self.alpha == 1.0 {
                (self.lambda * theta).exp()
            } else {
                (self.log_u(theta) / (self.alpha - 1.0)).exp()
            },
        )
    }

    /// Curvature 1/ρ(θ) (positive: the standard form turns counter-clockwise).
    pub fn kappa(&self, theta: f64) -> Result<f64> {
        self.check(theta)?;
        finite_or_err(
            theta,
            if self.alpha == 1.0 {
                (-self.lambda * theta).exp()
            } else {
                (-self.log_u(theta) / (self.alpha - 1.0)).exp()
            },
        )
    }

    /// Signed arc length from θ = 0 (negative for θ < 0), closed form:
    /// `((1+(α-1)Λθ)^(α/(α-1)) - 1)/(αΛ)`; α = 0: `-ln(1-Λθ)/Λ`; α = 1: `(e^{Λθ}-1)/Λ`.
    pub fn arc_length(&self, theta: f64) -> Result<f64> {
        self.check(theta)?;
        let (a, l) = (self.alpha, self.lambda);
        finite_or_err(
            theta,
            if l == 0.0 {
                theta
            } else if a == 1.0 {
                (l * theta).exp_m1() / l
            } else if a == 0.0 {
                -(-l * theta).ln_1p() / l
            } else {
                (a / (a - 1.0) * self.log_u(theta)).exp_m1() / (a * l)
            },
        )
    }

    /// The point P(θ).
    pub fn eval(&self, theta: f64) -> Result<Point> {
        Ok(self.integral(0.0, theta)?.to_point())
    }

    /// Points at many θ, integrating only between neighbours (sorted internally), so a
    /// polyline costs about as much as its last point.
    pub fn eval_many(&self, thetas: &[f64]) -> Result<Vec<Point>> {
        Ok(self.eval_many_impl(thetas, false)?.0)
    }

    /// [`Self::eval_many`] and the curvature at the same θ.
    pub fn eval_many_with_kappa(&self, thetas: &[f64]) -> Result<(Vec<Point>, Vec<f64>)> {
        self.eval_many_impl(thetas, true)
    }

    fn eval_many_impl(&self, thetas: &[f64], want_kappa: bool) -> Result<(Vec<Point>, Vec<f64>)> {
        // The domain is an interval: its extremes decide (NaN is caught by the check).
        if let Some(t) = thetas.iter().find(|t| !t.is_finite()) {
            self.check(*t)?;
        }
        let lo = thetas.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = thetas.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if !thetas.is_empty() {
            self.check(lo)?;
            self.check(hi)?;
        }
        if self.alpha == 1.0 || self.lambda == 0.0 {
            // Closed forms: no need to accumulate.
            let pts = thetas
                .iter()
                .map(|t| self.eval(*t))
                .collect::<Result<Vec<_>>>()?;
            let k = if want_kappa {
                self.kappa_many(thetas)?
            } else {
                Vec::new()
            };
            return Ok((pts, k));
        }
        let mut order: Vec<usize> = (0..thetas.len()).collect();
        order.sort_by(|&i, &j| thetas[i].total_cmp(&thetas[j]));
        let mut out = vec![Point::ZERO; thetas.len()];
        let mut kappa = if want_kappa {
            vec![0.0; thetas.len()]
        } else {
            Vec::new()
        };
        // Walk outward from θ = 0 in both directions.
        let split = order.partition_point(|&i| thetas[i] < 0.0);
        let mut cache = RotationCache::default();
        let upward = order[split..].iter();
        let downward = order[..split].iter().rev();
        let walks: [&mut dyn Iterator<Item = &usize>; 2] = [&mut { upward }, &mut { downward }];
        for walk in walks {
            let mut acc = Vec2::ZERO;
            let mut prev = 0.0;
            for &i in walk {
                let (step, rho) = self.integral_step(prev, thetas[i], &mut cache)?;
                acc += step;
                prev = thetas[i];
                out[i] = acc.to_point();
                if want_kappa {
                    kappa[i] = match rho {
                        Some(r) => 1.0 / r,
                        None => self.kappa(thetas[i])?,
                    };
                }
            }
        }
        if out.iter().any(|p| !p.is_finite()) || kappa.iter().any(|k| !k.is_finite()) {
            return Err(Error::invalid(
                "theta",
                "the curve at these theta is too large for f64",
            ));
        }
        Ok((out, kappa))
    }

    /// The Gauss–Legendre rule with symmetric nodes `xs` (ascending) on [t0, t1]. ρ at the
    /// nodes mid ± δ comes from ρ(mid) (1 ± ε)^a, ε = c δ / U(mid), summed as a binomial
    /// series while it converges fast (|ε| <= 1/4), and e^{iψ} by rotating e^{i mid}.
    #[allow(clippy::too_many_arguments)]
    fn gauss_step(
        &self,
        t0: f64,
        t1: f64,
        a: f64,
        c: f64,
        xs: &[f64],
        ws: &[f64],
        cache: &mut RotationCache,
    ) -> (Vec2, f64) {
        let mid = 0.5 * (t0 + t1);
        let half = 0.5 * (t1 - t0);
        let (xu, xe) = self.x_dd(mid);
        let (u, ue) = two_sum(1.0, xu);
        let ue = ue + xe;
        let rho_mid = (a * (u.ln() + ue / u)).exp();
        // e^{i mid}: rotate the previous step's by e^{id}, d = mid - previous mid, from its
        // Taylor series when |d| <= 0.01 (truncation d^8/8! < 3e-21), recomputed every
        // 32 steps so the rounding of the products does not build up.
        let d = mid - cache.mid;
        let e_mid = if cache.uses < 32 && d.abs() <= 0.01 {
            let d2 = d * d;
            let re = 1.0 - d2 * (0.5 - d2 * (1.0 / 24.0 - d2 * (1.0 / 720.0)));
            let im = d * (1.0 - d2 * (1.0 / 6.0 - d2 * (1.0 / 120.0 - d2 * (1.0 / 5040.0))));
            cache.uses += 1;
            cmul(cache.e_mid, Vec2::new(re, im))
        } else {
            let (sm, cm) = mid.sin_cos();
            cache.uses = 0;
            Vec2::new(cm, sm)
        };
        cache.mid = mid;
        cache.e_mid = e_mid;
        let n = xs.len();
        if cache.half != half || cache.nodes != n {
            // Uniform steps (the usual polyline) reuse the node rotations e^{±iδ}.
            cache.half = half;
            cache.nodes = n;
            for j in 0..n / 2 {
                let (sd, cd) = (half * xs[n - 1 - j]).sin_cos();
                cache.rot[j] = Vec2::new(cd, sd);
            }
        }
        let mut sum = Vec2::ZERO;
        if n % 2 == 1 {
            sum += e_mid * (ws[n / 2] * rho_mid);
        }
        for j in 0..n / 2 {
            let x = xs[n - 1 - j];
            let w = ws[n - 1 - j];
            let delta = half * x;
            let eps = c * delta / (u + ue);
            let (plus, minus) = binomial_pair(a, eps);
            let rot = cache.rot[j];
            let ep = cmul(e_mid, rot);
            let em = cmul(e_mid, conj(rot));
            sum += (ep * plus + em * minus) * (w * rho_mid);
        }
        // ρ(t1) = ρ(mid) (1 + c half / U(mid))^a: the curvature at the step's end for free.
        let (rho_end, _) = binomial_pair(a, c * half / (u + ue));
        (sum * half, rho_mid * rho_end)
    }

    /// One step of a polyline: a fixed Gauss–Legendre rule (3, 4 or 5 nodes) when its
    /// a-priori error bound is below 2e-17 of the step's arc length, else [`Self::integral`].
    ///
    /// The bound: with ρ = U^a, U = 1 + cψ, a = 1/(α-1), r = |c|/U_min on the step,
    /// |ρ^(k)| <= ρ |a (a-1) ... (a-k+1)| r^k, so by Leibniz f = ρ e^{iψ} has
    /// |f^(m)| <= ρ_max Σ_k C(m,k) |a (a-1) ... (a-k+1)| r^k; the n-point rule errs by at most
    /// √2 (n!)^4 / ((2n+1) ((2n)!)^3) h^(2n+1) max|f^(2n)| (real and imaginary parts).
    fn integral_step(
        &self,
        t0: f64,
        t1: f64,
        cache: &mut RotationCache,
    ) -> Result<(Vec2, Option<f64>)> {
        let (alpha, l) = (self.alpha, self.lambda);
        if alpha == 1.0 || l == 0.0 || t0 == t1 {
            return Ok((self.integral(t0, t1)?, None));
        }
        let c = self.c();
        let a = 1.0 / (alpha - 1.0);
        let h = t1 - t0;
        let u0 = 1.0 + c * t0;
        let u1 = 1.0 + c * t1;
        let umin = u0.min(u1);
        if umin.is_nan() || umin <= 0.0 || h.abs() > 0.5 {
            return Ok((self.integral(t0, t1)?, None));
        }
        let r = c.abs() / umin;
        // ρ_max/ρ_min = (U_max/U_min)^|a| <= e^{|a| r |h|}.
        let spread = a.abs() * r * h.abs();
        if spread > 1.0 {
            return Ok((self.integral(t0, t1)?, None));
        }
        let ratio = 1.0 + 2.0 * spread; // >= e^spread for spread <= 1
        const RULES: [(&[f64], &[f64], f64); 3] = [
            (&GL3_X, &GL3_W, 4.96e-7),
            (&GL4_X, &GL4_W, 5.63e-10),
            (&GL5_X, &GL5_W, 3.95e-13),
        ];
        for (xs, ws, k) in RULES {
            let m = 2 * xs.len();
            let d = leibniz_bound(a, r, m);
            // Relative to the step's own length |h| ρ_min: √2 k h^m D ρ_max/ρ_min <= 2e-17.
            if 1.5 * k * h.abs().powi(m as i32) * d * ratio <= 2e-17 {
                let (v, rho) = self.gauss_step(t0, t1, a, c, xs, ws, cache);
                return Ok((v, Some(rho)));
            }
        }
        Ok((self.integral(t0, t1)?, None))
    }

    /// `P(θ_k) - P(t0)` and the curvature κ(θ_k) at the `n >= 2` evenly spaced angles
    /// `θ_k = t0 + (t1 - t0) k/(n-1)`: the polyline of a segment.
    ///
    /// Each sample is evaluated once (ρ, ρ', ρ'' in closed form from U = 1 + cθ, e^{iθ} by
    /// rotation, recomputed every 32 samples) and consecutive samples are joined by the
    /// two-point Hermite rule with second derivatives,
    /// `∫_0^h f = h/2 (f0 + f1) + h²/10 (f0' - f1') + h³/120 (f0'' + f1'') - h⁷/100800 f⁽⁶⁾(ξ)`,
    /// whenever the bound of [`Self::integral_step`] (m = 6) puts that error below 2e-17 of
    /// the step's arc length; other steps (near the singular end, coarse sampling) go
    /// through `integral_step`. Errors when `integral_step` would.
    pub(crate) fn uniform_walk(&self, t0: f64, t1: f64, n: usize) -> Result<(Vec<Vec2>, Vec<f64>)> {
        if n < 2 {
            return Err(Error::invalid("samples", "need at least 2"));
        }
        let last = (n - 1) as f64;
        let theta = |k: usize| {
            if k == n - 1 {
                t1
            } else {
                t0 + (t1 - t0) * (k as f64 / last)
            }
        };
        self.walk(n, theta, (t1 - t0).abs() / last, true)
    }

    /// [`Self::uniform_walk`] at any monotone sequence of angles (at least 2): e^{iθ} is
    /// computed at every sample instead of by rotation; the same error bound per step.
    pub(crate) fn walk_monotone(&self, thetas: &[f64]) -> Result<(Vec<Vec2>, Vec<f64>)> {
        let n = thetas.len();
        if n < 2 {
            return Err(Error::invalid("samples", "need at least 2"));
        }
        let up = thetas[n - 1] >= thetas[0];
        let mut hmax = 0.0f64;
        for w in thetas.windows(2) {
            if (w[1] >= w[0]) != up && w[1] != w[0] {
                return Err(Error::invalid("theta", "the angles must be monotone"));
            }
            hmax = hmax.max((w[1] - w[0]).abs());
        }
        self.walk(n, |k| thetas[k], hmax, false)
    }

    /// The walk of [`Self::uniform_walk`] over `theta(0..n)` (monotone), whose steps are at
    /// most `hmax`; `uniform`: the steps are all equal (e^{iθ} by rotation).
    fn walk(
        &self,
        n: usize,
        theta: impl Fn(usize) -> f64,
        hmax: f64,
        uniform: bool,
    ) -> Result<(Vec<Vec2>, Vec<f64>)> {
        let (t0, t1) = (theta(0), theta(n - 1));
        let last = (n - 1) as f64;
        let fallback = || -> Result<(Vec<Vec2>, Vec<f64>)> {
            let th: Vec<f64> = (0..n).map(&theta).collect();
            let (p, k) = self.eval_many_impl(&th, true)?;
            let p0 = p[0].to_vec2();
            Ok((p.iter().map(|q| q.to_vec2() - p0).collect(), k))
        };
        self.check(t0)?;
        self.check(t1)?;
        if (t1 - t0).abs() > 2.0 * std::f64::consts::PI {
            return fallback();
        }
        if self.alpha == 1.0 {
            if uniform {
                return self.spiral_walk(t0, t1, n, &theta).or_else(|_| fallback());
            }
            return self.spiral_at(n, &theta).or_else(|_| fallback());
        }
        let c = self.c();
        let a = 1.0 / (self.alpha - 1.0);
        // x = cθ in double-double as in `x_dd`, with c's parts and splitting hoisted.
        let (a1, a1e) = two_sum(self.alpha, -1.0);
        let (ch, mut ce) = two_prod(a1, self.lambda);
        ce += a1e * self.lambda;
        let (chh, chl) = split(ch);
        // U = 1 + cθ as (u, its rounding error), and ln U to full accuracy near U = 0.
        let u_of = |th: f64| {
            let x = ch * th;
            let (thh, thl) = split(th);
            let xe = ((chh * thh - x) + chh * thl + chl * thh) + chl * thl + ce * th;
            let (u, ue) = two_sum(1.0, x);
            (u, ue + xe)
        };
        // f = ρ e^{iθ}, f' = (ρ' + iρ) e^{iθ}, f'' = (ρ'' - ρ + 2iρ') e^{iθ}.
        let node = |rho: f64, inv_u: f64, e: Vec2| -> [Vec2; 3] {
            let r1 = a * c * rho * inv_u;
            let r2 = (a - 1.0) * c * r1 * inv_u;
            [
                e * rho,
                cmul(e, Vec2::new(r1, rho)),
                cmul(e, Vec2::new(r2 - rho, 2.0 * r1)),
            ]
        };
        // The Hermite rule's error bound for a step of width `h` where U >= `umin`: with
        // r = |c|/U_min, D = Σ_j C(6,j) |a (a-1) ... (a-j+1)| r^j bounds |f⁽⁶⁾| / ρ_max and
        // ρ_max/ρ_min <= e^{|a| r h} <= 1 + 2 |a| r h.
        let hermite_ok = |h: f64, umin: f64| {
            let r = c.abs() / umin;
            let spread = a.abs() * r * h.abs();
            if !(umin > 0.0 && spread <= 1.0) {
                return false;
            }
            let d = leibniz_bound(a, r, 6);
            let h6 = (h * h) * (h * h) * (h * h);
            1.5 * h6 * d * (1.0 + 2.0 * spread) * (1.0 / 100_800.0) <= 2e-17
        };
        // U is linear in θ: its minimum over the walk is at an end. When the widest step
        // passes at that minimum, every step does.
        let u_ends = (1.0 + c * t0).min(1.0 + c * t1) * (1.0 - 1e-12);
        let all_fine = hermite_ok(hmax * (1.0 + 1e-9), u_ends);
        let turn = Vec2::from_angle((t1 - t0) / last);
        let mut pts = vec![Vec2::ZERO; n];
        let mut kappa = vec![0.0; n];
        let mut cache = RotationCache::default();
        let (u, ue) = u_of(t0);
        let mut rho = (a * (u.ln() + ue / u)).exp();
        let mut u_prev = u + ue;
        let mut inv_prev = 1.0 / u_prev;
        if !(rho.is_finite() && rho > 0.0 && (1.0 / rho).is_finite() && u_prev > 0.0) {
            return fallback();
        }
        let mut e = Vec2::from_angle(t0);
        let mut prev = node(rho, inv_prev, e);
        kappa[0] = 1.0 / rho;
        let mut acc = Vec2::ZERO;
        let mut th_prev = t0;
        // Every 32nd sample from scratch; between them e^{iθ} by rotation and ρ by the ratio
        // (U_k/U_(k-1))^a = (1 + ε)^a, ε = c h / U_(k-1), as a binomial series of `terms`
        // terms while max(|a|, 1) |ε| <= `reach` (the remainder is below reach^(terms+1)
        // <= 1e-17); there U is far enough from 0 for its plain f64 value to do.
        let a_big = a.abs().max(1.0);
        let reach = (c.abs() * hmax * a_big / u_ends.max(1e-300)).clamp(1e-8, BINOMIAL_POW_REACH);
        let terms = ((-17.0 / reach.log10()).ceil() as usize)
            .saturating_sub(1)
            .clamp(2, 8);
        for (k, (p_out, k_out)) in pts.iter_mut().zip(kappa.iter_mut()).enumerate().skip(1) {
            let th = theta(k);
            let h = th - th_prev;
            let eps = c * h * inv_prev;
            let resync = k % 32 == 0 || k == n - 1;
            let uu;
            if !resync && eps.abs() * a_big <= reach {
                rho *= binomial_pow(a, eps, terms);
                e = if uniform {
                    cmul(e, turn)
                } else {
                    Vec2::from_angle(th)
                };
                uu = 1.0 + c * th;
            } else {
                let (u, ue) = u_of(th);
                rho = (a * (u.ln() + ue / u)).exp();
                e = Vec2::from_angle(th);
                uu = u + ue;
            }
            let kk = 1.0 / rho;
            if !(rho.is_finite() && rho > 0.0 && kk.is_finite() && uu > 0.0) {
                return fallback();
            }
            let inv_u = 1.0 / uu;
            let cur = node(rho, inv_u, e);
            if all_fine || hermite_ok(h, u_prev.min(uu)) {
                let h2 = h * h;
                acc += (prev[0] + cur[0]) * (0.5 * h)
                    + (prev[1] - cur[1]) * (h2 * 0.1)
                    + (prev[2] + cur[2]) * (h2 * h * (1.0 / 120.0));
            } else {
                acc += self.integral_step(th_prev, th, &mut cache)?.0;
            }
            *p_out = acc;
            *k_out = kk;
            prev = cur;
            u_prev = uu;
            inv_prev = inv_u;
            th_prev = th;
        }
        if pts.iter().any(|p| !p.is_finite()) {
            return Err(Error::invalid(
                "theta",
                "the curve at these theta is too large for f64",
            ));
        }
        Ok((pts, kappa))
    }

    /// [`Self::uniform_walk`] of the logarithmic spiral (α = 1) in closed form:
    /// `P(θ) - P(t0) = (z(θ) - z(t0))/(Λ + i)`, `z = e^{(Λ+i)θ}`, `κ = e^{-Λθ}`, with z
    /// advanced by the constant factor `e^{(Λ+i)h}` and recomputed every 16 samples.
    fn spiral_walk(
        &self,
        t0: f64,
        t1: f64,
        n: usize,
        theta: impl Fn(usize) -> f64,
    ) -> Result<(Vec<Vec2>, Vec<f64>)> {
        let l = self.lambda;
        let exact = |th: f64| Vec2::from_angle(th) * (l * th).exp();
        let h = (t1 - t0) / (n - 1) as f64;
        let step = exact(h);
        let z0 = exact(t0);
        let inv = Vec2::new(l, -1.0) / (l * l + 1.0); // 1/(Λ + i)
        let mut z = z0;
        let mut pts = vec![Vec2::ZERO; n];
        let mut kappa = vec![0.0; n];
        kappa[0] = (-l * t0).exp();
        for (k, (p_out, k_out)) in pts.iter_mut().zip(kappa.iter_mut()).enumerate().skip(1) {
            z = if k % 16 == 0 || k == n - 1 {
                exact(theta(k))
            } else {
                cmul(z, step)
            };
            *p_out = cmul(z - z0, inv);
            *k_out = 1.0 / z.hypot();
        }
        if !(z0.is_finite() && step.is_finite())
            || pts.iter().any(|p| !p.is_finite())
            || kappa.iter().any(|k| !(k.is_finite() && *k > 0.0))
        {
            return Err(Error::invalid(
                "theta",
                "the curve at these theta is too large for f64",
            ));
        }
        Ok((pts, kappa))
    }

    /// The logarithmic spiral's walk at any angles, each in closed form.
    fn spiral_at(&self, n: usize, theta: &dyn Fn(usize) -> f64) -> Result<(Vec<Vec2>, Vec<f64>)> {
        let l = self.lambda;
        let exact = |th: f64| Vec2::from_angle(th) * (l * th).exp();
        let inv = Vec2::new(l, -1.0) / (l * l + 1.0); // 1/(Λ + i)
        let z0 = exact(theta(0));
        let mut pts = vec![Vec2::ZERO; n];
        let mut kappa = vec![0.0; n];
        for (k, (p_out, k_out)) in pts.iter_mut().zip(kappa.iter_mut()).enumerate() {
            let z = exact(theta(k));
            *p_out = cmul(z - z0, inv);
            *k_out = 1.0 / z.hypot();
        }
        if pts.iter().any(|p| !p.is_finite()) || kappa.iter().any(|k| !(k.is_finite() && *k > 0.0))
        {
            return Err(Error::invalid(
                "theta",
                "the curve at these theta is too large for f64",
            ));
        }
        pts[0] = Vec2::ZERO;
        Ok((pts, kappa))
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
        if (t1 - t0).abs() > MAX_QUARTER_TURNS * std::f64::consts::FRAC_PI_2 {
            return Err(Error::invalid(
                "theta",
                format!(
                    "the curve from theta = {t0} to {t1} turns more than {} times",
                    MAX_QUARTER_TURNS / 4.0
                ),
            ));
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
            sum += w_integral(p1, c, w_prev, w, opts)?;
            w_prev = w;
        }
        Ok(sum / c)
    }
}

impl LacStandard {
    /// Where the domain ends on the side of `t0`'s sign... the finite end θ* = -1/((α-1)Λ)
    /// of the domain, when there is one.
    pub fn domain_end(&self) -> Option<f64> {
        let c = self.c();
        (self.alpha != 1.0 && c != 0.0).then(|| -1.0 / c)
    }

    /// `∫_{t0}^{θ*} ρ e^{iψ} dψ` up to the finite end θ* of the domain, where ρ → ∞ (α < 0)
    /// or ρ → 0 (α > 1); both integrable (for 0 <= α < 1 the integral diverges: error). In
    /// `w = ln u` the last stretch runs to -∞ with an exponentially decaying integrand:
    /// quadrature down to e^w = |c|/2, then a convergent series in closed form.
    pub fn integral_to_domain_end(&self, t0: f64) -> Result<Vec2> {
        let (a, c) = (self.alpha, self.c());
        let Some(t_end) = self.domain_end() else {
            return Err(Error::invalid("lambda", "the domain has no finite end"));
        };
        let p1 = a / (a - 1.0);
        if p1 <= 0.0 {
            return Err(Error::invalid(
                "alpha",
                "for 0 <= alpha <= 1 the curve is infinitely long at the end of its domain",
            ));
        }
        // Last quarter turn handled in w down to the truncation point.
        let q = std::f64::consts::FRAC_PI_2;
        let t_last = if (t_end - t0).abs() > q {
            t_end - q * (t_end - t0).signum()
        } else {
            t0
        };
        let head = self.integral(t0, t_last)?;
        let w0 = self.log_u(t_last);
        // Down to -∞: quadrature where e^w/|c| > 1/2, the series of `w_series` below.
        let len = self.arc_length(t_last)?.abs() + (p1 * w0).exp() / (p1 * c.abs());
        let opts = QuadOptions {
            accuracy: (1e-15 * len * c.abs()).max(f64::MIN_POSITIVE),
            max_panels: 4_000,
        };
        let w_s = w0.min(series_edge(c));
        let middle = w_integral(p1, c, w0, w_s, opts)?;
        let below = w_series(p1, c, f64::NEG_INFINITY, w_s);
        let tail = middle - below;
        Ok(head + tail / c)
    }
}

/// `((1 + ε)^a, (1 - ε)^a)`: the even and odd parts of the binomial series when it
/// converges fast (|ε| <= 1/4 and |a ε| <= 1/4: successive terms shrink by at least
/// max(|a|, 1) |ε| <= 1/4, so the tail is below the last term), else through logarithms.
fn binomial_pair(a: f64, eps: f64) -> (f64, f64) {
    if eps.abs() <= 0.25 && (a * eps).abs() <= 0.25 {
        let (mut even, mut odd) = (1.0, 0.0);
        let mut term = 1.0;
        let mut fi = 0.0;
        for inv in INV_INT.chunks_exact(2) {
            term *= (a - fi) * inv[0] * eps;
            odd += term;
            term *= (a - fi - 1.0) * inv[1] * eps;
            even += term;
            fi += 2.0;
            if term.abs() <= 1e-18 * even {
                break;
            }
        }
        (even + odd, even - odd)
    } else {
        ((a * eps.ln_1p()).exp(), (a * (-eps).ln_1p()).exp())
    }
}

/// Where [`binomial_pow`] applies: `max(|a|, 1) |ε| <= 0.005`.
const BINOMIAL_POW_REACH: f64 = 0.005;

/// `(1 + ε)^a` by the terms up to ε^`terms` (at most 8) of its binomial series, in Horner
/// form. For `max(|a|, 1) |ε| <=` [`BINOMIAL_POW_REACH`] successive terms shrink by at least
/// 200x, so with 8 terms the rest is below 0.005^9 < 2e-21. No data-dependent branches:
/// consecutive samples pipeline.
fn binomial_pow(a: f64, eps: f64, terms: usize) -> f64 {
    let mut acc = 1.0;
    for j in (0..terms.min(8)).rev() {
        acc = 1.0 + (a - j as f64) * INV_INT[j] * eps * acc;
    }
    acc
}

/// `D = Σ_k C(m,k) |a (a-1) ... (a-k+1)| r^k` (m = 6, 8 or 10): with ρ = U^a and
/// r = |c| / U_min, `|f^(m)| <= ρ_max D` for f = ρ e^{iψ} (Leibniz).
fn leibniz_bound(a: f64, r: f64, m: usize) -> f64 {
    let binom = &BINOM_ROWS[m / 2 - 3];
    let (mut d, mut prod) = (1.0, 1.0);
    for j in 0..m {
        prod *= (a - j as f64).abs() * r;
        d += binom[j + 1] * prod;
    }
    d
}

/// Rows 6, 8 and 10 of Pascal's triangle.
const BINOM_ROWS: [[f64; 11]; 3] = [
    [1., 6., 15., 20., 15., 6., 1., 0., 0., 0., 0.],
    [1., 8., 28., 56., 70., 56., 28., 8., 1., 0., 0.],
    [1., 10., 45., 120., 210., 252., 210., 120., 45., 10., 1.],
];

/// 1/(i+1) for the binomial series.
const INV_INT: [f64; 64] = {
    let mut t = [0.0; 64];
    let mut i = 0;
    while i < 64 {
        t[i] = 1.0 / (i as f64 + 1.0);
        i += 1;
    }
    t
};

/// For `gauss_step`: e^{iδ} for the positive Gauss nodes δ of the last step width, and
/// e^{i mid} of the last step (`uses` steps since it was computed exactly).
struct RotationCache {
    half: f64,
    nodes: usize,
    rot: [Vec2; 2],
    mid: f64,
    e_mid: Vec2,
    uses: u32,
}

impl Default for RotationCache {
    fn default() -> Self {
        RotationCache {
            half: f64::NAN,
            nodes: 0,
            rot: [Vec2::ZERO; 2],
            mid: f64::NAN,
            e_mid: Vec2::ZERO,
            uses: u32::MAX,
        }
    }
}

const GL3_X: [f64; 3] = [-0.774_596_669_241_483_4, 0.0, 0.774_596_669_241_483_4];
const GL3_W: [f64; 3] = [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0];
const GL4_X: [f64; 4] = [
    -0.861_136_311_594_052_6,
    -0.339_981_043_584_856_3,
    0.339_981_043_584_856_3,
    0.861_136_311_594_052_6,
];
const GL4_W: [f64; 4] = [
    0.347_854_845_137_453_8,
    0.652_145_154_862_546_1,
    0.652_145_154_862_546_1,
    0.347_854_845_137_453_8,
];
const GL5_X: [f64; 5] = [
    -0.906_179_845_938_664,
    -0.538_469_310_105_683_1,
    0.0,
    0.538_469_310_105_683_1,
    0.906_179_845_938_664,
];
const GL5_W: [f64; 5] = [
    0.236_926_885_056_189_1,
    0.478_628_670_499_366_5,
    0.568_888_888_888_888_9,
    0.478_628_670_499_366_5,
    0.236_926_885_056_189_1,
];

/// Below this w (e^w <= |c|/2) the w-integral is summed as a series ([`w_series`]).
fn series_edge(c: f64) -> f64 {
    (0.5 * c.abs()).ln()
}

/// `∫_{wa}^{wb}` of [`w_integrand`]: adaptive quadrature where e^w > |c|/2, the series
/// [`w_series`] below, where the integrand (near the singular end of the domain) is costly
/// to integrate numerically.
fn w_integral(p1: f64, c: f64, wa: f64, wb: f64, opts: QuadOptions) -> Result<Vec2> {
    let (lo, hi, sign) = if wa <= wb {
        (wa, wb, 1.0)
    } else {
        (wb, wa, -1.0)
    };
    let edge = series_edge(c);
    let mut v = Vec2::ZERO;
    if lo < edge {
        v += w_series(p1, c, lo, hi.min(edge));
    }
    if hi > edge {
        v += integrate(w_integrand(p1, c), lo.max(edge), hi, opts)?;
    }
    Ok(v * sign)
}

/// `∫_{lo}^{hi} e^{p1 w} e^{i expm1(w)/c} dw` for hi <= ln(|c|/2) (lo may be -∞ when
/// p1 > 0), in closed form: `e^{-i/c} Σ_k (i/c)^k/k! ∫ e^{(p1+k) w} dw`. Successive terms
/// shrink by e^w/|c| <= 1/2 over k, so 60 terms reach rounding.
fn w_series(p1: f64, c: f64, lo: f64, hi: f64) -> Vec2 {
    let delta = hi - lo;
    let mut sum = Vec2::ZERO;
    let mut coef = Vec2::new(1.0, 0.0); // (i/c)^k / k!
    for k in 0..80 {
        let x = p1 + k as f64;
        let ek = if x == 0.0 {
            delta
        } else {
            (x * hi).exp() * -(-x * delta).exp_m1() / x
        };
        let term = coef * ek;
        sum += term;
        if x > 0.0 && term.hypot() <= 1e-18 * sum.hypot() {
            break;
        }
        coef = cmul(coef, Vec2::new(0.0, 1.0 / c)) / (k as f64 + 1.0);
    }
    let (sn, cs) = (-1.0 / c).sin_cos();
    cmul(Vec2::new(cs, sn), sum)
}

/// The integrand in `w = ln u`: `e^{(p+1) w} e^{i expm1(w)/c}` (the integral is then divided
/// by c), with `p1 = p + 1 = α/(α-1)` and `c = (α-1) Λ`.
fn w_integrand(p1: f64, c: f64) -> impl Fn(f64) -> Vec2 {
    move |w| {
        let mag = (p1 * w).exp();
        let psi = w.exp_m1() / c;
        Vec2::new(mag * psi.cos(), mag * psi.sin())
    }
}

/// `Ok(v)` for a finite value, else the error that the curve overflows f64 at θ.
fn finite_or_err(theta: f64, v: f64) -> Result<f64> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Error::invalid(
            "theta",
            format!("the curve's curvature or length overflows f64 at theta = {theta}"),
        ))
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
    // Dekker's product with Veltkamp splitting: exact without a hardware FMA (the
    // portable build has none, and a software fma costs tens of nanoseconds).
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    let e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    if e.is_finite() {
        (p, e)
    } else {
        (p, a.mul_add(b, -p))
    }
}

fn split(a: f64) -> (f64, f64) {
    const SPLITTER: f64 = 134_217_729.0; // 2^27 + 1
    let t = SPLITTER * a;
    let hi = t - (t - a);
    (hi, a - hi)
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

/// A log-aesthetic segment fitted into a control triangle (docs/math.md §3.1; Yoshida & Saito
/// 2006): start, tangent intersection, end.
#[derive(Clone, Debug, PartialEq)]
pub struct LacSegment {
    /// The standard-form curve (Λ >= 0).
    pub standard: LacStandard,
    /// Turning angle θ_d in (0, π).
    pub theta_d: f64,
    /// The standard-form θ interval: [0, θ_d] for α <= 1, [-θ_d, 0] for α > 1 (a
    /// [`LacSegment::sub_segment`] keeps the parent's curve and takes a part of this).
    pub interval: (f64, f64),
    /// The three control points as given.
    pub control: [Point; 3],
    /// True when the standard start (high-curvature end) maps to `control[2]`.
    pub reversed: bool,
    /// From the standard form to the input.
    map: Similarity,
}

fn cmul(a: Vec2, b: Vec2) -> Vec2 {
    Vec2::new(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x)
}
fn cdiv(a: Vec2, b: Vec2) -> Vec2 {
    let d = b.hypot2();
    Vec2::new((a.x * b.x + a.y * b.y) / d, (a.y * b.x - a.x * b.y) / d)
}
fn conj(a: Vec2) -> Vec2 {
    Vec2::new(a.x, -a.y)
}

/// A similarity of the plane (possibly with a reflection): `z -> offset + factor z` in complex
/// numbers, after complex conjugation when `mirrored`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Similarity {
    offset: Vec2,
    factor: Vec2,
    mirrored: bool,
}

impl Similarity {
    /// The similarity taking `from[0] -> to[0]` and `from[1] -> to[1]`, with or without a
    /// reflection, whichever takes the corner `from[2]` closer to `to[2]`.
    fn fit(from: [Vec2; 3], to: [Point; 3]) -> Result<Similarity> {
        let (x, y, target) = (to[0].to_vec2(), to[1].to_vec2(), to[2]);
        let candidate = |mirrored: bool| {
            let [a, b, _] = if mirrored { from.map(conj) } else { from };
            let factor = cdiv(y - x, b - a);
            let map = Similarity {
                offset: x - cmul(a, factor),
                factor,
                mirrored,
            };
            ((map.apply(from[2]) - target).hypot(), map)
        };
        let (plain, mirror) = (candidate(false), candidate(true));
        let map = if mirror.0 < plain.0 {
            mirror.1
        } else {
            plain.1
        };
        if !(map.factor.is_finite() && map.scale() > 0.0) {
            return Err(Error::NoConvergence(
                "the segment for this triangle spans a range of sizes beyond f64".into(),
            ));
        }
        Ok(map)
    }

    fn apply(&self, z: Vec2) -> Point {
        let z = if self.mirrored { conj(z) } else { z };
        (self.offset + cmul(z, self.factor)).to_point()
    }

    fn scale(&self) -> f64 {
        self.factor.hypot()
    }
}

/// The angles of a control triangle [start, tangent intersection, end].
struct TriangleAngles {
    /// Turning angle between the end tangents, in (0, π).
    theta_d: f64,
    /// Base angle at the start.
    theta_e: f64,
    /// Base angle at the end.
    theta_f: f64,
}

/// Validate a control triangle (finite, no coincident points, not collinear) and measure it.
fn triangle_angles(control: &[Point; 3]) -> Result<TriangleAngles> {
    if control.iter().any(|p| !p.is_finite()) {
        return Err(Error::invalid("control", "control points must be finite"));
    }
    let (p0, p1, p2) = (control[0], control[1], control[2]);
    let (u, v, w) = (p1 - p0, p2 - p1, p2 - p0);
    let size = u.hypot().max(v.hypot());
    if !(size.is_finite() && w.hypot().is_finite()) {
        return Err(Error::invalid(
            "control",
            "the coordinates are too large: the triangle's sides overflow f64",
        ));
    }
    if size == 0.0 || u.hypot() <= 1e-12 * size || v.hypot() <= 1e-12 * size {
        return Err(Error::Degenerate(
            "coincident control points: the end tangents are undefined".into(),
        ));
    }
    let theta_d = angle_between(u, v);
    if theta_d <= 1e-9 || theta_d >= std::f64::consts::PI - 1e-9 {
        return Err(Error::Degenerate(format!(
            "collinear control points (turning angle {theta_d:.3e} rad): no segment turns \
             between these tangents"
        )));
    }
    Ok(TriangleAngles {
        theta_d,
        theta_e: angle_between(u, w),
        theta_f: angle_between(w, v),
    })
}

/// Angle between two vectors in [0, π].
fn angle_between(a: Vec2, b: Vec2) -> f64 {
    a.cross(b).abs().atan2(a.dot(b))
}

impl LacSegment {
    /// The standard interval and the chord's base angle at its start (the high-curvature
    /// end) for Λ; `at_limit` evaluates the limiting curve Λ = Λ_max (α < 0 or α > 1).
    fn base_angle(alpha: f64, lambda: f64, theta_d: f64, at_limit: bool) -> Result<f64> {
        let c = LacStandard::new(alpha, lambda)?;
        let (ta, tb) = if alpha <= 1.0 {
            (0.0, theta_d)
        } else {
            (-theta_d, 0.0)
        };
        let chord = if !at_limit {
            // Probes of the Λ solve often lie past the domain: refused here without the
            // formatted message of `integral`'s check (a fifth of a sketch fit's time).
            if !(c.in_domain(ta) && c.in_domain(tb)) {
                return Err(Error::NoConvergence(
                    "the interval leaves the curve's domain".into(),
                ));
            }
            c.integral(ta, tb)?
        } else if alpha <= 1.0 {
            // θ* = θ_d: from 0 to the end of the domain.
            c.integral_to_domain_end(ta)?
        } else {
            // θ* = -θ_d: the start is the singular end; integrate end -> start and negate.
            -c.integral_to_domain_end(tb)?
        };
        Ok(chord.y.atan2(chord.x) - ta)
    }

    /// `Λ_max = 1/(|α-1| θ_d)` (infinite for α = 1).
    pub fn lambda_max(alpha: f64, theta_d: f64) -> f64 {
        if alpha == 1.0 {
            f64::INFINITY
        } else {
            1.0 / ((alpha - 1.0).abs() * theta_d)
        }
    }

    /// θ_lim(α, θ_d): the supremum of the high-curvature end's base angle.
    pub fn theta_lim(alpha: f64, theta_d: f64) -> Result<f64> {
        if (0.0..=1.0).contains(&alpha) {
            return Ok(theta_d);
        }
        Self::base_angle(alpha, Self::lambda_max(alpha, theta_d), theta_d, true)
    }

    /// Solve Λ with base angle `phi` at the high-curvature end, `θ_d/2 <= phi < θ_lim`
    /// (φ increases strictly with Λ). Two starts: the second-order Taylor expansion of φ in
    /// Λ at the circle (ρ ≈ 1 + Λψ + (2-α)Λ²ψ²/2, good for small Λ) and the straight line
    /// between the ends of the bracket (good near the limit); then Brent's method
    /// ([`crate::roots::brent`]) to the resolution of Λ or until the residual is at the
    /// noise of the base angle (4 ulp). About 4 to 8 integrals instead of 10 to 18.
    pub fn solve_lambda(alpha: f64, theta_d: f64, phi: f64) -> Result<f64> {
        let half = 0.5 * theta_d;
        if (phi - half).abs() <= 1e-15 * theta_d {
            return Ok(0.0);
        }
        let lim = Self::theta_lim(alpha, theta_d)?;
        if !(phi > half && phi < lim) {
            return Err(Error::NoSegment(format!(
                "the base angle at the high-curvature end is {:.9} rad ({:.6} deg); for alpha = \
                 {alpha} and turning angle {:.6} deg it must lie in [{:.9}, {:.9}) rad \
                 ([{:.6}, {:.6}) deg)",
                phi,
                phi.to_degrees(),
                theta_d.to_degrees(),
                half,
                lim,
                half.to_degrees(),
                lim.to_degrees()
            )));
        }
        // A Λ whose curve overflows f64 lies beyond the solution (φ increases with Λ and
        // overflow comes with large Λ): such probes count as "above", with the limit as value
        // (no error message is built for them: probes fail often on extreme triangles). A
        // valid triangle whose curve overflows f64 is a limit of this library, not bad input.
        let f_at = |l: f64| -> Result<f64> {
            match Self::base_angle(alpha, l, theta_d, false) {
                Ok(v) => Ok(v - phi),
                Err(_) if l > 0.0 => Ok(lim - phi),
                Err(e) => Err(Error::NoConvergence(format!(
                    "the segment for this triangle is too extreme to evaluate (lambda = {l:.3e}): {e}"
                ))),
            }
        };
        let lmax = Self::lambda_max(alpha, theta_d);
        let p1 = alpha / (alpha - 1.0);
        // The base angle is computed to a few units of 1e-16 of itself: a residual below
        // this is noise, and the root is as good as the evaluation allows.
        let f_tol = 4.0 * f64::EPSILON * phi;
        // First-order guess: ρ ≈ 1 + Λψ near Λ = 0 gives φ ≈ θ_d/2 + Λ Im(C1/C0), C0 and C1
        // the moments ∫ e^{iψ} and ∫ ψ e^{iψ} over [0, θ_d].
        let guess = {
            let (s, c) = theta_d.sin_cos();
            let e = Vec2::new(c, s);
            let i = Vec2::new(0.0, 1.0);
            let c0 = Vec2::new(s, 1.0 - c);
            let c1 = cmul(i, c0 - e * theta_d);
            let c2 = cmul(i, c1 * 2.0 - e * (theta_d * theta_d));
            let r1 = cdiv(c1, c0);
            let s1 = r1.y;
            // α > 1 runs over [-θ_d, 0]: the mirror image, with the Λ² term's sign flipped.
            let side = if alpha <= 1.0 { 1.0 } else { -1.0 };
            let s2 = side * (cdiv(c2, c0) * (0.5 * (2.0 - alpha)) - cmul(r1, r1) * 0.5).y;
            let d = phi - half;
            // s2 Λ² + s1 Λ - d = 0, the root near d/s1.
            let disc = s1 * s1 + 4.0 * s2 * d;
            if disc > 0.0 {
                2.0 * d / (s1 + disc.sqrt())
            } else {
                d / s1
            }
        };
        if lmax.is_finite() && p1 > 0.0 {
            // α < 0 or α > 1: near Λ_max the base angle behaves like θ_lim - K δ^p1,
            // δ = 1 - Λ/Λ_max. Solve in z = δ^p1 ∈ [0, 1] (z = 1: Λ = 0, the circular arc;
            // z = 0: the limit), where it is close to linear, and carry z near 0 at full
            // relative precision.
            let lambda_of = |z: f64| lmax * -(z.ln() / p1).exp_m1();
            let mut f = |z: f64| {
                if z <= 0.0 {
                    return Ok(lim - phi);
                }
                f_at(lambda_of(z))
            };
            // Two starts: the Taylor guess (good for small Λ) and the straight line between
            // the ends in z (good near the limit), then the secant method between them.
            let z_taylor = if guess > 0.0 && guess < lmax {
                (1.0 - guess / lmax).powf(p1)
            } else {
                0.5
            };
            let z_line = ((lim - phi) / (lim - half)).clamp(1e-300, 1.0 - 1e-16);
            let (za, zb) = if (z_taylor - z_line).abs() > 1e-12 {
                (z_taylor, z_line)
            } else {
                (z_taylor, z_taylor * (1.0 - 1e-6))
            };
            let (fa, fb) = (f(za)?, f(zb)?);
            // z to the resolution of Λ: a step of z that moves Λ by less than a unit in the
            // last place changes nothing (near the limit dΛ/dz is small); estimated at the
            // better guess, so never coarser than 1e-12.
            let z_best = if fa.abs() < fb.abs() { za } else { zb };
            let dl_dz = lmax * (z_best.ln() * (1.0 / p1 - 1.0)).exp() / p1;
            let z_tol = (2.0 * f64::EPSILON * lambda_of(z_best) / dl_dz).clamp(1e-16, 1e-12);
            let z = brent(
                &mut f,
                (0.0, lim - phi),
                (1.0, half - phi),
                &[(za, fa), (zb, fb)],
                z_tol,
                f_tol,
                100,
            )?;
            return Ok(lambda_of(z));
        }
        let mut hi = lmax;
        if !hi.is_finite() {
            hi = 1.0;
            while f_at(hi)? < 0.0 {
                hi *= 2.0;
                if hi > 1e6 {
                    return Err(Error::NoConvergence(
                        "lambda bracket for alpha = 1 exceeded 1e6".into(),
                    ));
                }
            }
        }
        // f(0) = θ_d/2 - phi < 0; at a finite Λ_max, f is the limit θ_lim - phi > 0 (the
        // curve itself is not evaluated there).
        let fhi = if hi == Self::lambda_max(alpha, theta_d) {
            lim - phi
        } else {
            f_at(hi)?
        };
        // The Taylor guess and the straight line between the ends, then the secant method.
        let flo = half - phi;
        let x_line = hi * flo / (flo - fhi);
        let x_taylor = if guess > 0.0 && guess < hi {
            guess
        } else {
            x_line
        };
        let (xa, xb) = if (x_taylor - x_line).abs() > 1e-12 * hi {
            (x_taylor, x_line)
        } else {
            (x_taylor, x_taylor * (1.0 - 1e-6))
        };
        let (fa, fb) = (f_at(xa)?, f_at(xb)?);
        brent(
            f_at,
            (0.0, flo),
            (hi, fhi),
            &[(xa, fa), (xb, fb)],
            1e-15 * hi,
            f_tol,
            100,
        )
    }

    /// The turning angle θ_d and the larger base angle φ (the one at the high-curvature end)
    /// of a control triangle [start, tangent intersection, end]: a segment of shape α exists
    /// in it iff θ_d/2 <= φ < [`LacSegment::theta_lim`]`(α, θ_d)`. Errors for degenerate
    /// triangles, as in `new`.
    pub fn triangle_angles(control: [Point; 3]) -> Result<(f64, f64)> {
        let t = triangle_angles(&control)?;
        Ok((t.theta_d, t.theta_e.max(t.theta_f)))
    }

    /// Whether a segment of shape `alpha` exists in the triangle `control` = [start, tangent
    /// intersection, end], without building it: the base angle at the high-curvature end
    /// must be below θ_lim(α, θ_d) (always true for 0 <= α <= 1). One integral for α < 0 or
    /// α > 1, none otherwise; agrees with [`LacSegment::new`] succeeding, except that a
    /// triangle whose segment is too extreme to evaluate in f64 counts as existing here.
    /// Degenerate triangles and a bad `alpha` are errors, as in `new`.
    pub fn exists(alpha: f64, control: [Point; 3]) -> Result<bool> {
        if !alpha.is_finite() || alpha.abs() > MAX_ABS_ALPHA {
            return Err(Error::invalid("alpha", "must be a finite number"));
        }
        let (theta_d, phi) = Self::triangle_angles(control)?;
        Self::exists_for_angles(alpha, theta_d, phi)
    }

    /// [`LacSegment::exists`] for a triangle given by its turning angle θ_d and larger base
    /// angle φ ([`LacSegment::triangle_angles`]); `alpha` must be valid.
    pub fn exists_for_angles(alpha: f64, theta_d: f64, phi: f64) -> Result<bool> {
        if (0.0..=1.0).contains(&alpha) || (phi - 0.5 * theta_d).abs() <= 1e-15 * theta_d {
            return Ok(true);
        }
        Ok(phi < Self::theta_lim(alpha, theta_d)?)
    }

    /// The segment of shape `alpha` in the triangle `control` = [start, tangent
    /// intersection, end].
    pub fn new(alpha: f64, control: [Point; 3]) -> Result<Self> {
        if !alpha.is_finite() || alpha.abs() > MAX_ABS_ALPHA {
            return Err(Error::invalid("alpha", "must be a finite number"));
        }
        let TriangleAngles {
            theta_d,
            theta_e,
            theta_f,
        } = triangle_angles(&control)?;
        let (p0, p1, p2) = (control[0], control[1], control[2]);
        let reversed = theta_f > theta_e;
        let phi = theta_e.max(theta_f);
        let lambda = Self::solve_lambda(alpha, theta_d, phi)?;
        let standard = LacStandard::new(alpha, lambda)?;
        let interval = if alpha <= 1.0 {
            (0.0, theta_d)
        } else {
            (-theta_d, 0.0)
        };
        let extreme = |e: Error| {
            Error::NoConvergence(format!(
                "the segment for this triangle is too extreme to evaluate in f64 \
                 (lambda = {lambda:.3e}): {e}"
            ))
        };
        // One integral: the interval is [0, θ_d] or [-θ_d, 0], and P(0) = 0.
        let (a, b) = if interval.0 == 0.0 {
            let b = standard.integral(0.0, interval.1).map_err(extreme)?;
            (Vec2::ZERO, b)
        } else {
            let a = standard.integral(0.0, interval.0).map_err(extreme)?;
            (a, Vec2::ZERO)
        };
        // Tangent intersection of the standard segment.
        let da = Vec2::from_angle(interval.0);
        let db = Vec2::from_angle(interval.1);
        let t_std = a + da * ((b - a).cross(db) / da.cross(db));
        let (x, y) = if reversed { (p2, p0) } else { (p0, p2) };
        let map = Similarity::fit([a, b, t_std], [x, y, p1])?;
        Ok(LacSegment {
            standard,
            theta_d,
            interval,
            control,
            reversed,
            map,
        })
    }

    /// The tangent intersection of the fitted curve, mapped to the input: equals
    /// `control[1]` up to the accuracy of Λ (a check, not a copy).
    pub fn tangent_intersection(&self) -> Result<Point> {
        let (ta, tb) = self.interval;
        let a = self.standard.eval(ta)?.to_vec2();
        let b = a + self.standard.integral(ta, tb)?;
        let (da, db) = (Vec2::from_angle(ta), Vec2::from_angle(tb));
        Ok(self.map.apply(a + da * ((b - a).cross(db) / da.cross(db))))
    }

    /// Λ of the standard form.
    pub fn lambda(&self) -> f64 {
        self.standard.lambda()
    }

    /// Scale factor from the standard form to the input.
    pub fn scale(&self) -> f64 {
        self.map.scale()
    }

    /// +1 when the segment turns counter-clockwise from `control[0]` to `control[2]`.
    fn turn_sign(&self) -> f64 {
        let c = self.control;
        (c[1] - c[0]).cross(c[2] - c[1]).signum()
    }

    /// Arc length in input units.
    pub fn arc_length(&self) -> Result<f64> {
        let (a, b) = self.interval;
        Ok((self.standard.arc_length(b)? - self.standard.arc_length(a)?).abs() * self.scale())
    }

    /// Standard-form parameters of `n >= 2` samples from `control[0]` to `control[2]`, evenly
    /// spaced in tangent angle.
    fn sample_thetas(&self, n: usize) -> Vec<f64> {
        let (a, b) = if self.reversed {
            (self.interval.1, self.interval.0)
        } else {
            self.interval
        };
        (0..n)
            .map(|i| a + (b - a) * (i as f64 / (n - 1) as f64))
            .collect()
    }

    /// `n >= 2` points from `control[0]` to `control[2]` (ends exact) and their signed curvature.
    pub fn sample(&self, n: usize) -> Result<(Vec<Point>, Vec<f64>)> {
        if n < 2 {
            return Err(Error::invalid("samples", "need at least 2"));
        }
        // Walk the standard form upward over the interval, then orient.
        let (lo, hi) = self.interval;
        let start = if lo == 0.0 {
            Vec2::ZERO
        } else {
            self.standard.eval(lo)?.to_vec2()
        };
        let (rel, mut k) = self.standard.uniform_walk(lo, hi, n)?;
        let mut finite = true;
        // (In place: the same allocation.)
        let mut out: Vec<Point> = rel
            .into_iter()
            .map(|v| {
                let p = self.map.apply(start + v);
                finite &= p.is_finite();
                p
            })
            .collect();
        let f = self.turn_sign() / self.scale();
        for v in &mut k {
            *v *= f;
            finite &= v.is_finite();
        }
        if self.reversed {
            out.reverse();
            k.reverse();
        }
        out[0] = self.control[0];
        out[n - 1] = self.control[2];
        if !finite {
            return Err(Error::NoConvergence(
                "the segment's samples overflow f64 (triangle too extreme)".into(),
            ));
        }
        Ok((out, k))
    }

    /// The logarithmic curvature graph at the `n >= 2` sample points of [`Self::sample`],
    /// in this segment's units, from the closed form `log(rho ds/drho) = alpha log rho -
    /// log Lambda` of the standard form. A circular arc (Λ = 0) has none: [`Error::Degenerate`].
    pub fn lcg(&self, n: usize) -> Result<Vec<crate::lcg::LcgPoint>> {
        if n < 2 {
            return Err(Error::invalid("samples", "need at least 2"));
        }
        let lambda = self.lambda();
        if lambda <= 0.0 {
            return Err(Error::Degenerate(
                "a circular arc (isosceles triangle) has constant curvature: no LCG".into(),
            ));
        }
        let lc = self.scale().ln();
        let (a, ll) = (self.standard.alpha(), lambda.ln());
        self.sample_thetas(n)
            .iter()
            .map(|t| {
                let lr = self.standard.log_rho(*t)?;
                Ok(crate::lcg::LcgPoint {
                    log_rho: lr + lc,
                    log_rho_ds_drho: a * lr - ll + lc,
                })
            })
            .collect()
    }

    /// Standard-form θ at turning angle `tau` from `control[0]`.
    fn theta_at_turning(&self, tau: f64) -> f64 {
        if self.reversed {
            self.interval.1 - tau
        } else {
            self.interval.0 + tau
        }
    }

    /// Points and derivatives dP/dτ (length = radius of curvature, direction = tangent) at
    /// turning angles τ measured from `control[0]` (τ = 0) to `control[2]` (τ = θ_d); τ outside
    /// [0, θ_d] is clamped.
    pub fn eval_turning(&self, taus: &[f64]) -> Result<(Vec<Point>, Vec<Vec2>)> {
        if let Some(i) = taus.iter().position(|t| !t.is_finite()) {
            return Err(Error::invalid(format!("tau[{i}]"), "must be finite"));
        }
        let th: Vec<f64> = taus
            .iter()
            .map(|t| self.theta_at_turning(t.clamp(0.0, self.theta_d)))
            .collect();
        self.eval_thetas(&th)
    }

    /// Standard-form points and curvatures at `th`: a monotone sequence (the usual case:
    /// sorted turning angles) by one walk ([`LacStandard::walk_monotone`]) from the first
    /// point, anything else by [`LacStandard::eval_many_with_kappa`].
    fn standard_points(&self, th: &[f64]) -> Result<(Vec<Point>, Vec<f64>)> {
        let n = th.len();
        // A handful of points costs as little by quadrature; the walk pays from about 8.
        let monotone =
            n >= 8 && (th.windows(2).all(|w| w[1] >= w[0]) || th.windows(2).all(|w| w[1] <= w[0]));
        if monotone && th[n - 1] != th[0] {
            if let Ok((rel, kappa)) = self.standard.walk_monotone(th) {
                let start = if th[0] == 0.0 {
                    Vec2::ZERO
                } else {
                    self.standard.eval(th[0])?.to_vec2()
                };
                return Ok((rel.iter().map(|v| (start + *v).to_point()).collect(), kappa));
            }
        }
        self.standard.eval_many_with_kappa(th)
    }

    /// Points and dP/dτ at standard-form angles (no clamping).
    fn eval_thetas(&self, th: &[f64]) -> Result<(Vec<Point>, Vec<Vec2>)> {
        let (pts, kappa) = self.standard_points(th)?;
        let dir = if self.reversed { -1.0 } else { 1.0 };
        let o = self.map.apply(Vec2::ZERO);
        let points = pts.iter().map(|p| self.map.apply(p.to_vec2())).collect();
        let derivs = th
            .iter()
            .zip(&kappa)
            .map(|(t, k)| self.map.apply(Vec2::from_angle(*t) * (dir / k)) - o)
            .collect();
        Ok((points, derivs))
    }

    /// The turning angle (from `control[0]`, possibly outside `[0, θ_d]`: on the curve's
    /// extension) of the foot of the perpendicular from `q`, by Newton's method from `tau0`;
    /// `None` if it leaves the curve's domain or does not converge.
    pub fn project_turning(&self, q: Point, tau0: f64) -> Option<f64> {
        let (lo, hi) = self.standard.domain();
        let mut tau = tau0;
        for _ in 0..50 {
            let th = self.theta_at_turning(tau);
            if !(lo < th && th < hi) {
                return None;
            }
            let (p, d) = self.eval_thetas(&[th]).ok()?;
            let rho = d[0].hypot();
            let (u, n) = (d[0] / rho, Vec2::new(-d[0].y, d[0].x) / rho);
            // g(τ) = (q - P)·u, g'(τ) = -ρ + (q - P)·u' with u' = ±n (the tangent turns by
            // dτ towards the side the curve bends to).
            let sign = self.turn_sign();
            let r = q - p[0];
            let g = r.dot(u);
            let dg = -rho + sign * r.dot(n);
            if dg.is_nan() || dg >= 0.0 {
                return None;
            }
            let step = g / dg;
            let step = step.clamp(-0.5, 0.5);
            tau -= step;
            if step.abs() <= 1e-13 * (1.0 + tau.abs()) {
                return Some(tau);
            }
        }
        None
    }

    /// The part of this segment between turning angles `ta < tb` (from `control[0]`): the same
    /// curve (no new solve), with its own control triangle.
    pub fn sub_segment(&self, ta: f64, tb: f64) -> Result<LacSegment> {
        if !(ta.is_finite() && tb.is_finite() && 0.0 <= ta && ta < tb && tb <= self.theta_d) {
            return Err(Error::invalid(
                "turning",
                format!(
                    "need 0 <= ta < tb <= theta_d = {}, got {ta}, {tb}",
                    self.theta_d
                ),
            ));
        }
        self.between(ta, tb)
    }

    /// The same curve between turning angles `ta < tb` measured from `control[0]`, which may
    /// lie outside `[0, θ_d]`: the segment trimmed or extended along its own curve (no new
    /// solve). The extension must stay inside the curve's domain (α > 0 curves end where the
    /// radius of curvature reaches 0, α < 0 curves where it becomes infinite) and turn by
    /// less than π in all.
    pub fn extended(&self, ta: f64, tb: f64) -> Result<LacSegment> {
        if !(ta.is_finite() && tb.is_finite() && ta < tb && tb - ta < std::f64::consts::PI) {
            return Err(Error::invalid(
                "turning",
                format!("need ta < tb < ta + pi, got {ta}, {tb}"),
            ));
        }
        let (a, b) = (self.theta_at_turning(ta), self.theta_at_turning(tb));
        let (lo, hi) = self.standard.domain();
        if !(lo < a.min(b) && a.max(b) < hi) {
            return Err(Error::NoSegment(format!(
                "the curve ends inside the requested extension (turning {ta:.4}..{tb:.4} \
                 leaves its domain)"
            )));
        }
        self.between(ta, tb)
    }

    fn between(&self, ta: f64, tb: f64) -> Result<LacSegment> {
        let (a, b) = (self.theta_at_turning(ta), self.theta_at_turning(tb));
        let (pts, der) = self.eval_thetas(&[a, b])?;
        // The segment's own ends stay exact.
        let p0 = if ta == 0.0 { self.control[0] } else { pts[0] };
        let p2 = if tb == self.theta_d {
            self.control[2]
        } else {
            pts[1]
        };
        let denom = der[0].cross(der[1]);
        let x = p0 + der[0] * ((p2 - p0).cross(der[1]) / denom);
        let seg = LacSegment {
            standard: self.standard,
            theta_d: tb - ta,
            interval: (a.min(b), a.max(b)),
            control: [p0, x, p2],
            reversed: self.reversed,
            map: self.map,
        };
        if !x.is_finite() {
            return Err(Error::Degenerate(
                "the sub-segment's end tangents are parallel".into(),
            ));
        }
        Ok(seg)
    }

    /// Signed curvature at `control[0]` and `control[2]`.
    pub fn end_curvatures(&self) -> Result<(f64, f64)> {
        let th = self.sample_thetas(2);
        let s = self.turn_sign() / self.scale();
        let (a, b) = (
            s * self.standard.kappa(th[0])?,
            s * self.standard.kappa(th[1])?,
        );
        if !(a.is_finite() && b.is_finite()) {
            return Err(Error::NoConvergence(
                "the segment's end curvature overflows f64 (triangle too extreme)".into(),
            ));
        }
        Ok((a, b))
    }
}

/// A log-aesthetic segment with an inflection point at its start (docs/math.md §3.2; S4 §2.2):
/// `C(s) = ∫_0^s e^{i t^q} dt`, `q = (α-1)/α > 1` (α < 0), tangent angle `θ = s^q`,
/// curvature `q s^(q-1)`, zero at s = 0. Given the triangle, α follows from the base angle at
/// the inflection end, which runs from 0 (α → 0-) to θ_d/2 (α → -∞, a circle).
#[derive(Clone, Debug, PartialEq)]
pub struct LacInflectionSegment {
    /// The shape parameter (< 0).
    pub alpha: f64,
    /// Turning angle θ_d in (0, π).
    pub theta_d: f64,
    /// Control triangle; `control[0]` is the inflection end.
    pub control: [Point; 3],
    /// From the standard form to the input.
    map: Similarity,
}

/// `∫_0^θ u^(r-1) e^{iu} du` for `r` in (0, 1] and θ in [0, 3.5], by its power series
/// `θ^r Σ_k (iθ)^k / (k! (k + r))` (term by term from e^{iu} = Σ (iu)^k/k!). The terms
/// peak near k = θ below e^θ/√(2πθ) < 10 times the sum's leading term and fall as
/// θ^k/k! after it: 40 terms reach rounding, with a few units of 1e-16 of cancellation.
fn inflection_primitive(r: f64, theta: f64) -> Vec2 {
    if theta <= 0.0 {
        return Vec2::ZERO;
    }
    let (mut re, mut im) = (0.0f64, 0.0f64);
    // c = θ^k / k!, the sign pattern of i^k: 1, i, -1, -i.
    let mut c = 1.0f64;
    for k in 0..60 {
        let term = c / (k as f64 + r);
        match k % 4 {
            0 => re += term,
            1 => im += term,
            2 => re -= term,
            _ => im -= term,
        }
        c *= theta / (k as f64 + 1.0);
        if c < 1e-18 * (re.abs() + im.abs()) {
            break;
        }
    }
    Vec2::new(re, im) * theta.powf(r)
}

/// `∫_{θ0}^{θ1} u^(r-1) e^{iu} du` with `r = 1/q` in (0, 1] and 0 <= θ0 <= θ1 <= 3.5:
/// the difference of [`inflection_primitive`] (absolute error a few units of 1e-16 of
/// θ1^r/r, the accuracy the adaptive quadrature it replaced was asked for).
fn inflection_integral(r: f64, th0: f64, th1: f64) -> Result<Vec2> {
    let v = inflection_primitive(r, th1) - inflection_primitive(r, th0);
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Error::invalid(
            "alpha",
            "the inflection-end integral overflows f64",
        ))
    }
}

impl LacInflectionSegment {
    /// Base angle at the inflection end for `r = 1/q = α/(α-1)` in (0, 1).
    fn base_angle_r(r: f64, theta_d: f64) -> Result<f64> {
        let c = inflection_integral(r, 0.0, theta_d)?;
        Ok(c.y.atan2(c.x))
    }

    /// Base angle at the inflection end of the segment of shape `alpha` (< 0) turning `theta_d`.
    pub fn base_angle(alpha: f64, theta_d: f64) -> Result<f64> {
        if !(alpha < 0.0 && alpha.is_finite()) {
            return Err(Error::invalid(
                "alpha",
                "inflection-end segments need alpha < 0",
            ));
        }
        Self::base_angle_r(alpha / (alpha - 1.0), theta_d)
    }

    /// Whether an inflection-end segment exists in the triangle `control` (`control[0]` =
    /// inflection end): the base angle there must lie in (0, θ_d/2). No integral; agrees
    /// with [`LacInflectionSegment::new`] succeeding. Degenerate triangles are errors.
    pub fn exists(control: [Point; 3]) -> Result<bool> {
        let TriangleAngles {
            theta_d,
            theta_e: phi,
            ..
        } = triangle_angles(&control)?;
        Ok(phi > 0.0 && phi < 0.5 * theta_d)
    }

    /// The segment in the triangle `control` (`control[0]` = inflection end).
    pub fn new(control: [Point; 3]) -> Result<Self> {
        let TriangleAngles {
            theta_d,
            theta_e: phi,
            ..
        } = triangle_angles(&control)?;
        let half = 0.5 * theta_d;
        if !(phi > 0.0 && phi < half) {
            return Err(Error::NoSegment(format!(
                "the base angle at the inflection end is {:.6} deg; with turning angle {:.6} deg \
                 it must lie in (0, {:.6}) deg",
                phi.to_degrees(),
                theta_d.to_degrees(),
                half.to_degrees()
            )));
        }
        // r = 1/q in (0, 1): f(0+) = -phi, f(1) = θ_d/2 - phi.
        let r = illinois(
            |x| Ok(Self::base_angle_r(x, theta_d)? - phi),
            (0.0, -phi),
            (1.0, half - phi),
            1e-16,
            400,
        )?;
        let alpha = r / (r - 1.0);
        let (b, t) = Self::standard_end_and_corner(r, theta_d)?;
        let map = Similarity::fit([Vec2::ZERO, b, t], [control[0], control[2], control[1]])?;
        Ok(LacInflectionSegment {
            alpha,
            theta_d,
            control,
            map,
        })
    }

    fn r(&self) -> f64 {
        self.alpha / (self.alpha - 1.0)
    }

    /// Standard end point C(s1) and tangent intersection (start tangent is +x).
    fn standard_end_and_corner(r: f64, theta_d: f64) -> Result<(Vec2, Vec2)> {
        let b = inflection_integral(r, 0.0, theta_d)? * r;
        let db = Vec2::from_angle(theta_d);
        // Intersection of the x-axis with the line through b along db.
        let t = Vec2::new(b.x - b.y * db.x / db.y, 0.0);
        Ok((b, t))
    }

    /// Scale from the standard form to the input.
    pub fn scale(&self) -> f64 {
        self.map.scale()
    }

    /// The mapped tangent intersection (equals `control[1]` up to the accuracy of α).
    pub fn tangent_intersection(&self) -> Result<Point> {
        Ok(self
            .map
            .apply(Self::standard_end_and_corner(self.r(), self.theta_d)?.1))
    }

    /// Arc length `s1 = θ_d^(1/q)` in input units.
    pub fn arc_length(&self) -> f64 {
        self.theta_d.powf(self.r()) * self.scale()
    }

    /// Split at turning angle `tau` (0 < τ < θ_d, from the inflection end): the part
    /// [0, τ], an inflection-end segment of the same curve (no new solve), and the part
    /// [τ, θ_d], an ordinary LAC segment of the same α (its curvature never vanishes),
    /// solved from its own triangle: the same curve to the solver's accuracy (about 1e-13
    /// of its size; tested).
    pub fn split(&self, tau: f64) -> Result<(LacInflectionSegment, LacSegment)> {
        if !(tau.is_finite() && tau > 0.0 && tau < self.theta_d) {
            return Err(Error::invalid(
                "turning",
                format!("need 0 < tau < theta_d = {}, got {tau}", self.theta_d),
            ));
        }
        let (pts, tangents) = self.eval_turning(&[tau])?;
        let (p, t) = (pts[0], tangents[0]);
        let c = self.control;
        let meet = |a: Point, da: Vec2, b: Point, db: Vec2| -> Result<Point> {
            let x = a + da * ((b - a).cross(db) / da.cross(db));
            if x.is_finite() {
                Ok(x)
            } else {
                Err(Error::Degenerate(
                    "the split point's tangent is parallel to an end tangent".into(),
                ))
            }
        };
        let x0 = meet(c[0], c[1] - c[0], p, t)?;
        let x1 = meet(p, t, c[2], c[2] - c[1])?;
        let head = LacInflectionSegment {
            alpha: self.alpha,
            theta_d: tau,
            control: [c[0], x0, p],
            map: self.map,
        };
        let tail = LacSegment::new(self.alpha, [p, x1, c[2]])?;
        Ok((head, tail))
    }

    /// +1 when the segment turns counter-clockwise from `control[0]` to `control[2]`.
    fn turn_sign(&self) -> f64 {
        let c = self.control;
        (c[1] - c[0]).cross(c[2] - c[1]).signum()
    }

    /// Signed curvature at `control[2]` (the curvature at the inflection end `control[0]` is 0):
    /// `q θ_d^(1-1/q)` over the scale.
    pub fn end_curvature(&self) -> f64 {
        let r = self.r();
        self.turn_sign() * self.theta_d.powf(1.0 - r) / (r * self.scale())
    }

    /// Points at turning angles τ from the inflection end (τ = 0) to `control[2]` (τ = θ_d),
    /// and the unit tangents there; τ outside [0, θ_d] is clamped. Ascending τ are
    /// integrated incrementally.
    pub fn eval_turning(&self, taus: &[f64]) -> Result<(Vec<Point>, Vec<Vec2>)> {
        if let Some(i) = taus.iter().position(|t| !t.is_finite()) {
            return Err(Error::invalid(format!("tau[{i}]"), "must be finite"));
        }
        let r = self.r();
        let o = self.map.apply(Vec2::ZERO);
        let mut pts = Vec::with_capacity(taus.len());
        let mut tangents = Vec::with_capacity(taus.len());
        for t in taus {
            let th = t.clamp(0.0, self.theta_d);
            let acc = inflection_integral(r, 0.0, th)? * r;
            pts.push(if th == self.theta_d {
                self.control[2]
            } else if th == 0.0 {
                self.control[0]
            } else {
                self.map.apply(acc)
            });
            let d = self.map.apply(Vec2::from_angle(th)) - o;
            tangents.push(d / d.hypot());
        }
        Ok((pts, tangents))
    }

    /// `n >= 2` points from the inflection end to `control[2]`, evenly spaced in tangent angle,
    /// and their signed curvature (0 at the start).
    pub fn sample(&self, n: usize) -> Result<(Vec<Point>, Vec<f64>)> {
        if n < 2 {
            return Err(Error::invalid("samples", "need at least 2"));
        }
        let r = self.r();
        let q = 1.0 / r;
        let sign = (self.control[1] - self.control[0])
            .cross(self.control[2] - self.control[1])
            .signum();
        let mut pts = Vec::with_capacity(n);
        let mut k = Vec::with_capacity(n);
        for i in 0..n {
            let th = self.theta_d * (i as f64 / (n - 1) as f64);
            let acc = inflection_integral(r, 0.0, th)? * r;
            pts.push(self.map.apply(acc));
            // kappa(s) = q s^(q-1) with s = θ^(1/q): q θ^(1 - 1/q).
            k.push(sign * q * th.powf(1.0 - r) / self.scale());
        }
        pts[0] = self.control[0];
        pts[n - 1] = self.control[2];
        Ok((pts, k))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    fn rel(a: Point, re: f64, im: f64) -> f64 {
        ((a.x - re).powi(2) + (a.y - im).powi(2)).sqrt() / (re * re + im * im).sqrt()
    }

    #[test]
    fn inflection_series_matches_quadrature() {
        // The power series of the inflection-end integral against adaptive Gauss–Kronrod
        // quadrature in v = ln u (the singularity at 0 becomes exponential decay).
        let quad = |r: f64, th0: f64, th1: f64| {
            let f = |v: f64| {
                let (u, m) = (v.exp(), (r * v).exp());
                Vec2::new(m * u.cos(), m * u.sin())
            };
            let v0 = if th0 > 0.0 {
                th0.ln()
            } else {
                th1.ln().min(0.0) + (1e-18 * r).ln() / r
            };
            let opts = QuadOptions {
                accuracy: 1e-17 * th1.powf(r) / r,
                max_panels: 20000,
            };
            integrate(f, v0, th1.ln(), opts).unwrap()
        };
        let mut worst: f64 = 0.0;
        for &r in &[0.005, 0.05, 0.2, 0.5, 0.8, 0.999, 1.0] {
            for &th1 in &[
                1e-6,
                0.01,
                0.3,
                1.0,
                2.0,
                2.8,
                3.1,
                std::f64::consts::PI - 1e-3,
            ] {
                for &frac in &[0.0, 0.25, 0.9] {
                    let th0 = frac * th1;
                    let a = inflection_integral(r, th0, th1).unwrap();
                    let b = quad(r, th0, th1);
                    let scale = th1.powf(r) / r;
                    let e = (a - b).hypot() / scale;
                    worst = worst.max(e);
                    assert!(e < 2e-14, "r {r} [{th0}, {th1}]: {a:?} vs {b:?} ({e:e})");
                }
            }
        }
        println!("worst error / (theta^r / r): {worst:e}");
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
    fn math_md_segment_values() {
        let d = FRAC_PI_2;
        let lim = LacSegment::theta_lim(-1.0, d).unwrap().to_degrees();
        assert!((lim - 60.6663).abs() < 1e-4, "{lim}");
        let lim = LacSegment::theta_lim(2.0, d).unwrap().to_degrees();
        assert!((lim - 60.2824).abs() < 1e-4, "{lim}");
        let phi = 50f64.to_radians();
        let l = LacSegment::solve_lambda(-1.0, d, phi).unwrap();
        assert!((l - 0.233593243048).abs() < 1e-11, "{l}");
        let l = LacSegment::solve_lambda(1.0, d, phi).unwrap();
        assert!((l - 0.409925293631).abs() < 1e-11, "{l}");
    }

    #[test]
    fn segment_fits_its_triangle_and_refuses_outside() {
        let pts = [
            Point::new(0.0, 0.0),
            Point::new(10.0, 0.0),
            Point::new(16.0, 9.0),
        ];
        for alpha in [-1.0, 0.0, 0.5, 1.0, 2.0] {
            let seg = LacSegment::new(alpha, pts).unwrap();
            let (p, k) = seg.sample(65).unwrap();
            assert_eq!(p[0], pts[0]);
            assert_eq!(p[64], pts[2]);
            // The mapped end (before snapping) matches: check the next-to-last sample is close.
            assert!((p[63] - pts[2]).hypot() < 1.0);
            assert!(k.iter().all(|v| *v > 0.0), "counter-clockwise: {k:?}");
            let t = seg.tangent_intersection().unwrap();
            assert!((t - pts[1]).hypot() < 1e-10 * 16.0, "alpha {alpha}: {t:?}");
            // Mirrored triangle: same curve mirrored, negative curvature.
            let m = pts.map(|p| Point::new(p.x, -p.y));
            let sm = LacSegment::new(alpha, m).unwrap();
            let (pm, km) = sm.sample(65).unwrap();
            for i in 0..65 {
                assert!((pm[i] - Point::new(p[i].x, -p[i].y)).hypot() < 1e-10 * 16.0);
                assert!((km[i] + k[i]).abs() < 1e-10 * k[i].abs());
            }
            // Reversed triangle: same points in reverse order.
            let r = [pts[2], pts[1], pts[0]];
            let (pr, kr) = LacSegment::new(alpha, r).unwrap().sample(65).unwrap();
            for i in 0..65 {
                assert!((pr[i] - p[64 - i]).hypot() < 1e-10 * 16.0);
                assert!((kr[i] + k[64 - i]).abs() < 1e-10 * k[64 - i].abs());
            }
            // Tangent at the start points at P1.
            let d = p[1] - p[0];
            assert!(d.cross(pts[1] - pts[0]).abs() / (d.hypot() * 10.0) < 0.05);
        }
        // Base angle too large for alpha = -1 (theta_lim ~ 60.67 deg at 90 deg turning).
        let bad = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(1.0, 0.3),
        ];
        assert!(matches!(
            LacSegment::new(-1.0, bad),
            Err(Error::NoSegment(_))
        ));
        let line = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(2.0, 0.0),
        ];
        assert!(matches!(
            LacSegment::new(-1.0, line),
            Err(Error::Degenerate(_))
        ));
    }

    #[test]
    fn inflection_split_gives_the_same_curve() {
        let seg = LacInflectionSegment::new([
            Point::new(0.0, 0.0),
            Point::new(1.5, 0.0),
            Point::new(2.1, 1.3),
        ])
        .unwrap();
        let size = seg.arc_length();
        for frac in [1e-4, 0.05, 0.3, 0.9] {
            let tau = frac * seg.theta_d;
            let (head, tail) = seg.split(tau).unwrap();
            assert!((head.alpha - seg.alpha).abs() < 1e-15);
            // The head is the curve from 0 to τ; the tail from τ to θ_d.
            let taus: Vec<f64> = (0..=20).map(|k| tau * k as f64 / 20.0).collect();
            let (a, _) = head.eval_turning(&taus).unwrap();
            let (b, _) = seg.eval_turning(&taus).unwrap();
            for (x, y) in a.iter().zip(&b) {
                assert!((*x - *y).hypot() < 1e-13 * size, "head at {frac}");
            }
            let rest: Vec<f64> = (0..=20)
                .map(|k| (seg.theta_d - tau) * k as f64 / 20.0)
                .collect();
            let (c, _) = tail.eval_turning(&rest).unwrap();
            let (d, _) = seg
                .eval_turning(&rest.iter().map(|r| tau + r).collect::<Vec<_>>())
                .unwrap();
            let worst = c
                .iter()
                .zip(&d)
                .map(|(x, y)| (*x - *y).hypot())
                .fold(0.0, f64::max);
            assert!(worst < 1e-12 * size, "tail at {frac}: {worst:e}");
            // Curvature continuity at the split: head's end = tail's start.
            let (k0, _) = tail.end_curvatures().unwrap();
            let kh = head.end_curvature();
            assert!((k0 - kh).abs() < 1e-10 * kh.abs(), "{k0} {kh}");
        }
        assert!(seg.split(0.0).is_err());
        assert!(seg.split(seg.theta_d).is_err());
        assert!(seg.split(f64::NAN).is_err());
    }

    #[test]
    fn exists_agrees_with_new_on_a_grid_of_third_points() {
        // Third control points on a grid around P0 = (0, 0), P1 = (1, 0): `exists` must agree
        // with `new` succeeding (the region the editor shades), for every kind of alpha.
        let (p0, p1) = (Point::new(0.0, 0.0), Point::new(1.0, 0.0));
        for alpha in [-2.0, -1.0, -0.3, 0.0, 0.5, 1.0, 1.5, 3.0] {
            let (mut inside, mut outside) = (0, 0);
            for i in 0..23 {
                for k in 0..23 {
                    let p2 = Point::new(-0.9 + 0.13 * k as f64, -1.4 + 0.127 * i as f64);
                    let c = [p0, p1, p2];
                    match LacSegment::new(alpha, c) {
                        Err(Error::Degenerate(_)) => {
                            assert!(matches!(
                                LacSegment::exists(alpha, c),
                                Err(Error::Degenerate(_))
                            ))
                        }
                        r => {
                            let e = LacSegment::exists(alpha, c).unwrap();
                            // Too extreme for f64 (Λ at Λ_max to rounding) still exists.
                            let built = r.is_ok() || matches!(r, Err(Error::NoConvergence(_)));
                            assert_eq!(e, built, "alpha {alpha}, p2 {p2:?}: {r:?}");
                            if e {
                                inside += 1
                            } else {
                                outside += 1
                            }
                        }
                    }
                    let ri = LacInflectionSegment::new(c);
                    match LacInflectionSegment::exists(c) {
                        Ok(e) => assert_eq!(e, ri.is_ok(), "inflection, p2 {p2:?}: {ri:?}"),
                        Err(_) => assert!(matches!(ri, Err(Error::Degenerate(_)))),
                    }
                }
            }
            assert!(inside > 50, "alpha {alpha}: {inside} inside");
            if !(0.0..=1.0).contains(&alpha) {
                assert!(outside > 20, "alpha {alpha}: only {outside} outside");
            }
        }
        assert!(LacSegment::exists(f64::NAN, [p0, p1, Point::new(2.0, 1.0)]).is_err());
    }

    #[test]
    fn inflection_segment_values_and_identity() {
        let d = FRAC_PI_2;
        // docs/math.md §3.2: 90 deg turning, 30 deg at the inflection end: alpha = -1.066636984.
        // Build a triangle with base angles 30 (at P0) and 60 deg: P2 on the ray at 30 deg
        // from P0 and on the ray at 90 deg from P1.
        let p2 = Point::new(1.0, 30f64.to_radians().tan());
        let seg = LacInflectionSegment::new([Point::ZERO, Point::new(1.0, 0.0), p2]).unwrap();
        assert!((seg.alpha + 1.066636984).abs() < 1e-8, "{}", seg.alpha);
        let t = seg.tangent_intersection().unwrap();
        assert!((t - Point::new(1.0, 0.0)).hypot() < 1e-10, "{t:?}");
        let (p, k) = seg.sample(33).unwrap();
        assert_eq!(k[0], 0.0);
        assert!(k.windows(2).all(|w| w[1] > w[0]));
        assert!((p[16].y) > 0.0);
        // theta_lim(alpha) + inflection angle(alpha) = theta_d.
        for alpha in [-0.3, -1.0, -4.0] {
            let lim = LacSegment::theta_lim(alpha, d).unwrap();
            let inf = LacInflectionSegment::base_angle(alpha, d).unwrap();
            assert!((lim + inf - d).abs() < 1e-10, "{alpha}: {lim} + {inf}");
        }
        // Outside: base angle at the inflection end must be below theta_d / 2.
        let bad = [Point::ZERO, Point::new(1.0, 0.0), Point::new(1.0, 2.0)];
        assert!(matches!(
            LacInflectionSegment::new(bad),
            Err(Error::NoSegment(_))
        ));
    }

    #[test]
    fn extreme_triangles_give_finite_curves_or_a_clear_error() {
        for alpha in [-1.0, 0.5, 1.0, 3.0] {
            for turn in [0.012f64, 0.5, 3.0] {
                for split in [0.6f64, 0.99, 0.999999] {
                    let te = split * turn;
                    let t = te.sin() / (turn - te).sin();
                    let tri = [
                        Point::ZERO,
                        Point::new(1.0, 0.0),
                        Point::new(1.0 + t * turn.cos(), t * turn.sin()),
                    ];
                    match LacSegment::new(alpha, tri).and_then(|s| s.sample(33)) {
                        Ok((p, k)) => {
                            assert!(p.iter().all(|q| q.is_finite()));
                            assert!(k.iter().all(|v| v.is_finite() && *v != 0.0));
                        }
                        Err(Error::NoSegment(_)) | Err(Error::NoConvergence(_)) => {}
                        Err(e) => panic!("{alpha} {turn} {split}: {e}"),
                    }
                }
            }
        }
    }

    #[test]
    fn eval_many_with_kappa_matches_kappa() {
        for &(alpha, lambda) in &[(-1.0, 0.3), (0.5, 0.4), (2.0, 0.5), (1.0, 0.5), (5.0, 0.1)] {
            let c = LacStandard::new(alpha, lambda).unwrap();
            let (lo, hi) = c.domain();
            let (lo, hi) = (lo.max(-3.0) * 0.99, hi.min(3.0) * 0.99);
            let th: Vec<f64> = (0..500)
                .map(|i| lo + (hi - lo) * i as f64 / 499.0)
                .collect();
            let (p, k) = c.eval_many_with_kappa(&th).unwrap();
            assert_eq!(p, c.eval_many(&th).unwrap());
            for (t, kv) in th.iter().zip(&k) {
                let want = c.kappa(*t).unwrap();
                assert!(
                    (kv - want).abs() <= 1e-14 * want,
                    "{alpha} {t}: {kv} vs {want}"
                );
            }
        }
    }

    /// The polyline walk (Hermite steps) against adaptive quadrature from the walk's start
    /// to each sample, and the closed-form curvature: fine and coarse sampling, both signs
    /// of α - 1, and an interval that runs up to 1e-6 of the singular end (where the walk
    /// must switch to its fallback steps).
    #[test]
    fn uniform_walk_matches_quadrature() {
        let cases = [
            (-1.0, 0.3),
            (0.5, 0.4),
            (2.0, 0.5),
            (5.0, 0.1),
            (-8.0, 2.0),
            (1.0, 0.5),
            (1.0, 4.0),
            (0.5, 0.0),
            (1.0, 0.0),
        ];
        for &(alpha, lambda) in &cases {
            let c = LacStandard::new(alpha, lambda).unwrap();
            let (lo, hi) = c.domain();
            // Up to 1e-6 of the domain's finite end, or ±2.5.
            let (lo, hi) = ((lo + 1e-6).max(-2.5), (hi - 1e-6).min(2.5));
            let spans = [
                (0.0, hi * 0.9),
                (lo * 0.9, 0.0),
                (lo, hi),
                (0.5 * lo, hi),
                (lo, 0.5 * hi),
            ];
            for (t0, t1) in spans {
                for n in [2, 3, 17, 129, 1000, 4000] {
                    let (p, k) = c.uniform_walk(t0, t1, n).unwrap();
                    let len = (c.arc_length(t1).unwrap() - c.arc_length(t0).unwrap()).abs();
                    let mut worst: f64 = 0.0;
                    for (i, (pi, ki)) in p.iter().zip(&k).enumerate() {
                        let t = if i == n - 1 {
                            t1
                        } else {
                            t0 + (t1 - t0) * (i as f64 / (n - 1) as f64)
                        };
                        let want = c.integral(t0, t).unwrap();
                        worst = worst.max((*pi - want).hypot() / len);
                        let kw = c.kappa(t).unwrap();
                        assert!((ki - kw).abs() <= 1e-14 * kw, "{alpha} {t}: {ki} vs {kw}");
                    }
                    assert!(
                        worst < 2e-14,
                        "alpha {alpha} [{t0}, {t1}] n {n}: {worst:.2e}"
                    );
                }
            }
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

    /// Extending a segment and cutting the extension off again gives the segment back; the
    /// extension lies on the same curve (its sub-segment is the original), and the feet of
    /// perpendiculars land where the points were taken.
    #[test]
    fn extension_and_projection_stay_on_the_curve() {
        let tri = [
            Point::new(0.0, 0.0),
            Point::new(5.0, 0.5),
            Point::new(9.0, 4.0),
        ];
        for alpha in [-1.5, 0.0, 0.5, 2.0] {
            let seg = LacSegment::new(alpha, tri).unwrap();
            let td = seg.theta_d;
            let ext = seg.extended(-0.1 * td, 1.1 * td).unwrap();
            assert!((ext.theta_d - 1.2 * td).abs() < 1e-12);
            let back = ext.sub_segment(0.1 * td, 1.1 * td).unwrap();
            for (a, b) in back.control.iter().zip(&tri) {
                assert!((*a - *b).hypot() < 1e-9, "{alpha}: {a:?} vs {b:?}");
            }
            // A point of the extension, moved off the curve along its normal, projects back.
            let (p, d) = ext.eval_turning(&[0.03 * td]).unwrap();
            let n = Vec2::new(-d[0].y, d[0].x).normalize();
            let q = p[0] + n * 0.2;
            let tau = seg.project_turning(q, 0.0).unwrap();
            assert!(
                (tau - (-0.07 * td)).abs() < 1e-9,
                "{alpha}: {tau} vs {}",
                -0.07 * td
            );
            // Trimming works the same way.
            let t = seg.extended(0.2 * td, 0.7 * td).unwrap();
            let s = seg.sub_segment(0.2 * td, 0.7 * td).unwrap();
            for (a, b) in t.control.iter().zip(&s.control) {
                assert!((*a - *b).hypot() < 1e-12);
            }
        }
        // An alpha > 0 curve ends where its radius of curvature reaches 0.
        let seg = LacSegment::new(2.0, tri).unwrap();
        assert!(seg.extended(-3.0, 0.5).is_err() || seg.extended(0.0, 3.0).is_err());
        assert!(seg.extended(0.5, 0.2).is_err());
    }
}
