//! The log-aesthetic curve in standard form: P(θ), curvature, arc length, the polyline walk.

use super::{cmul, conj};
use crate::error::{Error, Result};
use crate::quadrature::{integrate, QuadOptions, QuadValue, Riding};
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

    /// The θ at signed arc length `s` from θ = 0: the inverse of [`Self::arc_length`] in
    /// closed form, `θ = L · expm1(x)/x` with `L = ln(1 + αΛs)/(αΛ)` and `x = (α-1)Λ L`
    /// (every special case, α = 0, α = 1, Λ = 0, is a limit of it, taken without
    /// cancellation). Errors: `s` not finite, or beyond the end of the curve
    /// (`1 + αΛs <= 0`: the length to an inflection or to infinite curvature).
    pub fn theta_at_arc_length(&self, s: f64) -> Result<f64> {
        let (a, l) = (self.alpha, self.lambda);
        let y = a * l * s;
        if !s.is_finite() || y <= -1.0 {
            return Err(Error::invalid(
                "s",
                format!("arc length {s} is not on the curve (1 + alpha lambda s must be > 0)"),
            ));
        }
        let big_l = if y == 0.0 { s } else { y.ln_1p() / y * s };
        let x = (a - 1.0) * l * big_l;
        let theta = if x == 0.0 {
            big_l
        } else {
            big_l * (x.exp_m1() / x)
        };
        finite_or_err(theta, theta)
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
    /// Each sample is evaluated once (ρ and its derivatives in closed form from U = 1 + cθ,
    /// e^{iθ} by rotation, recomputed every 32 samples) and consecutive samples are joined
    /// by a two-point Hermite rule: with second derivatives,
    /// `∫_0^h f = h/2 (f0 + f1) + h²/10 (f0' - f1') + h³/120 (f0'' + f1'') - h⁷/100800 f⁽⁶⁾(ξ)`,
    /// when the bound of [`Self::integral_step`] (m = 6) puts that error below 2e-17 of every
    /// step's arc length (dense walks), else with third derivatives,
    /// `h/2 (f0 + f1) + 3h²/28 (f0' - f1') + h³/84 (f0'' + f1'') + h⁴/1680 (f0''' - f1''')`,
    /// error `h⁹/25401600 f⁽⁸⁾(ξ)`, at each step where that bound (m = 8) passes; other steps (near the singular end, coarse sampling) go
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

    /// [`Self::uniform_walk`] at any monotone sequence of angles (at least 2): e^{iθ} by
    /// the rotation of each step's own angle (its Taylor series, steps up to 0.05 rad;
    /// larger ones from scratch); the same error bound per step.
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
        // f = ρ e^{iθ}, f' = (ρ' + iρ) e^{iθ}, f'' = (ρ'' - ρ + 2iρ') e^{iθ},
        // f''' = (ρ''' - 3ρ' + i(3ρ'' - ρ)) e^{iθ}, with ρ^(k) = ρ a (a-1)...(a-k+1) (c/U)^k.
        // (f''' only when the walk needs the higher rule: `low_order` below.)
        let node = |rho: f64, inv_u: f64, e: Vec2, third: bool| -> [Vec2; 4] {
            let r1 = a * c * rho * inv_u;
            let r2 = (a - 1.0) * c * r1 * inv_u;
            let f3 = if third {
                let r3 = (a - 2.0) * c * r2 * inv_u;
                cmul(e, Vec2::new(r3 - 3.0 * r1, 3.0 * r2 - rho))
            } else {
                Vec2::ZERO
            };
            [
                e * rho,
                cmul(e, Vec2::new(r1, rho)),
                cmul(e, Vec2::new(r2 - rho, 2.0 * r1)),
                f3,
            ]
        };
        // The Hermite rules' error bounds for a step of width `h` where U >= `umin`: with
        // r = |c|/U_min, D_m = Σ_j C(m,j) |a (a-1) ... (a-j+1)| r^j bounds |f⁽ᵐ⁾| / ρ_max
        // and ρ_max/ρ_min <= e^{|a| r h} <= 1 + 2 |a| r h; m = 6 for the rule with second
        // derivatives (error h⁷/100800 f⁽⁶⁾), m = 8 with third (h⁹/25401600 f⁽⁸⁾).
        let hermite_ok = |h: f64, umin: f64, m: usize| {
            let r = c.abs() / umin;
            let spread = a.abs() * r * h.abs();
            if !(umin > 0.0 && spread <= 1.0) {
                return false;
            }
            let d = leibniz_bound(a, r, m);
            let h2 = h * h;
            let (hm, k) = if m == 6 {
                (h2 * h2 * h2, 1.0 / 100_800.0)
            } else {
                ((h2 * h2) * (h2 * h2), 1.0 / 25_401_600.0)
            };
            1.5 * hm * d * (1.0 + 2.0 * spread) * k <= 2e-17
        };
        // U is linear in θ: its minimum over the walk is at an end. When the widest step
        // passes at that minimum, every step does.
        let u_ends = (1.0 + c * t0).min(1.0 + c * t1) * (1.0 - 1e-12);
        // Dense walks (the usual polyline) take the cheaper rule at every step; others the
        // higher one, step by step where its bound allows.
        let low_order = hermite_ok(hmax * (1.0 + 1e-9), u_ends, 6);
        let all_fine = low_order || hermite_ok(hmax * (1.0 + 1e-9), u_ends, 8);
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
        let mut prev = node(rho, inv_prev, e, !low_order);
        kappa[0] = 1.0 / rho;
        let mut acc = Vec2::ZERO;
        let mut th_prev = t0;
        let mut bad = false;
        // Every 32nd sample from scratch; between them e^{iθ} by rotation and ρ by the ratio
        // (U_k/U_(k-1))^a = (1 + ε)^a, ε = c h / U_(k-1), as a binomial series of `terms`
        // terms while max(|a|, 1) |ε| <= `reach` (the remainder is below reach^(terms+1)
        // <= 1e-17); there U is far enough from 0 for its plain f64 value to do.
        let a_big = a.abs().max(1.0);
        let reach = (c.abs() * hmax * a_big / u_ends.max(1e-300)).clamp(1e-8, BINOMIAL_POW_REACH);
        let terms = ((-17.0 / reach.log10()).ceil() as usize)
            .saturating_sub(1)
            .clamp(2, 8);
        let ratios = binomial_ratios(a);
        // The loop twice (by macro): once per rule, so that the dense walk's cheaper rule
        // pays nothing for the other.
        macro_rules! steps {
            ($third:literal) => {
                for (k, (p_out, k_out)) in pts.iter_mut().zip(kappa.iter_mut()).enumerate().skip(1)
                {
                    let th = theta(k);
                    let h = th - th_prev;
                    let eps = c * h * inv_prev;
                    let resync = k % 32 == 0 || k == n - 1;
                    let uu;
                    if !resync && eps.abs() * a_big <= reach {
                        rho *= binomial_pow(&ratios, eps, terms);
                        e = if uniform {
                            cmul(e, turn)
                        } else if h.abs() <= 0.05 {
                            cmul(e, rotation(h))
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
                    // Checked once after the loop (no branch per sample): a bad value only spoils
                    // what the fallback recomputes anyway.
                    bad |= !(rho.is_finite() && rho > 0.0 && kk.is_finite() && uu > 0.0);
                    let inv_u = 1.0 / uu;
                    let cur = node(rho, inv_u, e, $third);
                    if !$third {
                        let h2 = h * h;
                        acc += (prev[0] + cur[0]) * (0.5 * h)
                            + (prev[1] - cur[1]) * (h2 * 0.1)
                            + (prev[2] + cur[2]) * (h2 * h * (1.0 / 120.0));
                    } else if all_fine || (!bad && hermite_ok(h, u_prev.min(uu), 8)) {
                        let h2 = h * h;
                        acc += (prev[0] + cur[0]) * (0.5 * h)
                            + (prev[1] - cur[1]) * (h2 * (3.0 / 28.0))
                            + (prev[2] + cur[2]) * (h2 * h * (1.0 / 84.0))
                            + (prev[3] - cur[3]) * (h2 * h2 * (1.0 / 1680.0));
                    } else if !bad {
                        acc += self.integral_step(th_prev, th, &mut cache)?.0;
                    }
                    *p_out = acc;
                    *k_out = kk;
                    prev = cur;
                    u_prev = uu;
                    inv_prev = inv_u;
                    th_prev = th;
                }
            };
        }
        if low_order {
            steps!(false);
        } else {
            steps!(true);
        }
        if bad {
            return fallback();
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
        let sum: Vec2 = self.w_pieces(t0, t1, |wa, wb, opts| w_integral(p1, c, wa, wb, opts))?;
        Ok(sum / c)
    }

    /// The chord `∫_{t0}^{t1} ρ e^{iψ} dψ` of [`Self::integral`] and its derivative in Λ at
    /// fixed ends, `∫ ψ ρ/U e^{iψ} dψ` (∂ρ/∂Λ = ψ ρ/U), from the same quadrature nodes (the
    /// accuracy is controlled on the chord; the derivative is as smooth and comes out about
    /// as accurate). For α ≠ 1 and Λ ≠ 0 (the Λ solve's Newton steps), else an error.
    pub(crate) fn integral_dlambda(&self, t0: f64, t1: f64) -> Result<(Vec2, Vec2)> {
        self.check(t0)?;
        self.check(t1)?;
        let (a, l) = (self.alpha, self.lambda);
        if a == 1.0 || l == 0.0 {
            return Err(Error::invalid(
                "lambda",
                "the Λ derivative is computed for alpha != 1 and lambda != 0 only",
            ));
        }
        let c = self.c();
        let p1 = a / (a - 1.0);
        let sum: Riding = self.w_pieces(t0, t1, |wa, wb, opts| {
            w_integral_riding(p1, c, wa, wb, opts)
        })?;
        let (v, d) = (sum.value / c, sum.rider / (c * c));
        if !(v.is_finite() && d.is_finite()) {
            return Err(Error::invalid(
                "theta",
                format!("the curve between theta = {t0} and {t1} is too large for f64"),
            ));
        }
        Ok((v, d))
    }

    /// `Σ piece(w_k, w_{k+1})` over the pieces of [t0, t1] (at most a quarter turn each, so
    /// adaptive quadrature is never fooled by an oscillation it did not sample), in
    /// `w = ln U`, with the accuracy of each piece's quadrature scaled to the arc length
    /// (times |c|, the factor the w-integrals carry). α ≠ 1, Λ ≠ 0, both ends in the domain.
    fn w_pieces<V: QuadValue>(
        &self,
        t0: f64,
        t1: f64,
        mut piece: impl FnMut(f64, f64, QuadOptions) -> Result<V>,
    ) -> Result<V> {
        let c = self.c();
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
        let opts = QuadOptions {
            accuracy: (1e-15 * len * c.abs() / pieces).max(f64::MIN_POSITIVE),
            max_panels: 2_000,
        };
        let n = pieces as usize;
        let mut sum = V::ZERO;
        let mut w_prev = self.log_u(t0);
        for k in 1..=n {
            let t = if k == n {
                t1
            } else {
                t0 + (t1 - t0) * (k as f64 / n as f64)
            };
            let w = self.log_u(t);
            sum = sum + piece(w_prev, w, opts)?;
            w_prev = w;
        }
        Ok(sum)
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
/// form, from the ratios `coefs[j] = (a - j)/(j + 1)` of successive coefficients
/// ([`binomial_ratios`]). For `max(|a|, 1) |ε| <=` [`BINOMIAL_POW_REACH`] successive terms
/// shrink by at least 200x, so with 8 terms the rest is below 0.005^9 < 2e-21. No
/// data-dependent branches: consecutive samples pipeline.
fn binomial_pow(coefs: &[f64; 8], eps: f64, terms: usize) -> f64 {
    let mut acc = 1.0;
    for &b in coefs[..terms.min(8)].iter().rev() {
        acc = 1.0 + b * eps * acc;
    }
    acc
}

/// The ratios `(a - j)/(j + 1)`, j < 8, of [`binomial_pow`].
fn binomial_ratios(a: f64) -> [f64; 8] {
    std::array::from_fn(|j| (a - j as f64) * INV_INT[j])
}

/// `D = Σ_k C(m,k) |a (a-1) ... (a-k+1)| r^k` (m = 6, 8 or 10): with ρ = U^a and
/// r = |c| / U_min, `|f^(m)| <= ρ_max D` for f = ρ e^{iψ} (Leibniz).
/// e^{ih} for |h| <= 0.05 by its Taylor series to h^9 (truncation below 3e-20).
#[inline]
pub(super) fn rotation(h: f64) -> Vec2 {
    let h2 = h * h;
    let re = 1.0 - h2 * (0.5 - h2 * (1.0 / 24.0 - h2 * (1.0 / 720.0 - h2 * (1.0 / 40320.0))));
    let im = h
        * (1.0
            - h2 * (1.0 / 6.0 - h2 * (1.0 / 120.0 - h2 * (1.0 / 5040.0 - h2 * (1.0 / 362_880.0)))));
    Vec2::new(re, im)
}

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

/// [`w_integral`] with the Λ derivative riding along: the rider's integrand is the chord's
/// times `expm1(w) e^{-w}` (= ψ c/U), so below the series edge it is the difference of two
/// series, in `p1` and in `p1 - 1` (finite `lo`).
fn w_integral_riding(p1: f64, c: f64, wa: f64, wb: f64, opts: QuadOptions) -> Result<Riding> {
    let (lo, hi, sign) = if wa <= wb {
        (wa, wb, 1.0)
    } else {
        (wb, wa, -1.0)
    };
    let edge = series_edge(c);
    let mut v = Riding::ZERO;
    if lo < edge {
        let top = hi.min(edge);
        let (value, lower) = w_series_pair(p1, c, lo, top, true);
        let rider = value - lower;
        v = v + Riding { value, rider };
    }
    if hi > edge {
        let f = move |w: f64| {
            let mag = (p1 * w).exp();
            let psi = w.exp_m1() / c;
            let (sn, cs) = psi.sin_cos();
            let value = Vec2::new(mag * cs, mag * sn);
            Riding {
                value,
                rider: value * -(-w).exp_m1(),
            }
        };
        v = v + integrate(f, lo.max(edge), hi, opts)?;
    }
    Ok(v * sign)
}

/// `∫_{lo}^{hi} e^{p1 w} e^{i expm1(w)/c} dw` for hi <= ln(|c|/2) (lo may be -∞ when
/// p1 > 0), in closed form: `e^{-i/c} Σ_k (i/c)^k/k! ∫ e^{(p1+k) w} dw`. Successive terms
/// shrink by e^w/|c| <= 1/2 over k, so 60 terms reach rounding.
fn w_series(p1: f64, c: f64, lo: f64, hi: f64) -> Vec2 {
    w_series_pair(p1, c, lo, hi, false).0
}

/// [`w_series`] for `p1` and, when `both`, for `p1 - 1` too (the Λ derivative's second
/// series), from the same coefficients. The exponentials of the k-th term come from those
/// of the previous one (one multiplication each; `1 - e^{-xδ}` directly when e^{-xδ} < 1/2,
/// else by `expm1`, so there is no cancellation).
fn w_series_pair(p1: f64, c: f64, lo: f64, hi: f64, both: bool) -> (Vec2, Vec2) {
    let delta = hi - lo;
    let (e_hi, s) = (hi.exp(), (-delta).exp());
    // ∫_{lo}^{hi} e^{x w} dw = e^{x hi} (1 - e^{-x δ}) / x, x = p + k, for p = p1 and p1 - 1;
    // mag = e^{x hi} and f = e^{-x δ} carried along k.
    let term = |x: f64, mag: f64, f: f64| -> f64 {
        if x == 0.0 {
            delta
        } else if f < 0.5 {
            mag * (1.0 - f) / x
        } else {
            mag * -(-x * delta).exp_m1() / x
        }
    };
    let mut mag = [(p1 * hi).exp(), ((p1 - 1.0) * hi).exp()];
    let mut f = [(-p1 * delta).exp(), (-(p1 - 1.0) * delta).exp()];
    let (mut sum, mut sum2) = (Vec2::ZERO, Vec2::ZERO);
    let mut coef = Vec2::new(1.0, 0.0); // (i/c)^k / k!
    for k in 0..80 {
        let x = p1 + k as f64;
        let t = coef * term(x, mag[0], f[0]);
        sum += t;
        let mut small = x > 0.0 && t.hypot() <= 1e-18 * sum.hypot();
        if both {
            let t2 = coef * term(x - 1.0, mag[1], f[1]);
            sum2 += t2;
            small &= x > 1.0 && t2.hypot() <= 1e-18 * sum2.hypot();
        }
        if small {
            break;
        }
        coef = cmul(coef, Vec2::new(0.0, 1.0 / c)) / (k as f64 + 1.0);
        for j in 0..2 {
            mag[j] *= e_hi;
            f[j] *= s;
        }
    }
    let (sn, cs) = (-1.0 / c).sin_cos();
    let rot = Vec2::new(cs, sn);
    (cmul(rot, sum), cmul(rot, sum2))
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
