//! A log-aesthetic segment in a control triangle: the Λ solve, evaluation by turning angle,
//! sub-segments, projection.

use super::{cdiv, cmul, triangle_angles, Similarity, TriangleAngles};
use super::{ArcPoint, LacStandard, Polyline, TurningSamples, MAX_ABS_ALPHA};
use crate::error::{Error, Result};
use crate::solve::roots::brent;
use kurbo::{Point, Vec2};

/// A log-aesthetic segment fitted into a control triangle (docs/math.md §3.1; Yoshida & Saito
/// 2006): start, tangent intersection, end.
#[derive(Clone, Debug, PartialEq)]
///
/// Its fields are private (they hold the solved Λ, the similarity and the orientation
/// together); read them through the accessors of the same names.
pub struct LacSegment {
    /// The standard-form curve (Λ >= 0).
    pub(crate) standard: LacStandard,
    /// Turning angle θ_d in (0, π).
    pub(crate) theta_d: f64,
    /// The standard-form θ interval: [0, θ_d] for α <= 1, [-θ_d, 0] for α > 1 (a
    /// [`LacSegment::sub_segment`] keeps the parent's curve and takes a part of this).
    pub(crate) interval: (f64, f64),
    /// The three control points as given.
    pub(crate) control: [Point; 3],
    /// True when the standard start (high-curvature end) maps to `control[2]`.
    pub(crate) reversed: bool,
    /// From the standard form to the input.
    map: Similarity,
}

/// A segment's standard curve, its parameter interval and its chord there.
pub(crate) type SolvedStandard = (LacStandard, (f64, f64), Vec2);

/// The largest log curvature ratio (Λ θ_d) the α = 1 solve brackets: far past e^700, where
/// the curve overflows f64 and its probes count as above the root.
const ALPHA_ONE_LOG_RATIO: f64 = 1e4;

impl LacSegment {
    /// The standard-form curve (α and Λ >= 0).
    pub fn standard(&self) -> &LacStandard {
        &self.standard
    }
    /// α.
    pub fn alpha(&self) -> f64 {
        self.standard.alpha()
    }
    /// The turning angle θ_d in (0, π).
    pub fn theta_d(&self) -> f64 {
        self.theta_d
    }
    /// The standard-form θ interval: [0, θ_d] for α <= 1, [-θ_d, 0] for α > 1 (a
    /// [`LacSegment::sub_segment`] keeps the parent's curve and takes a part of this).
    pub fn interval(&self) -> (f64, f64) {
        self.interval
    }
    /// The control triangle: start, tangent intersection, end.
    pub fn control(&self) -> [Point; 3] {
        self.control
    }
    /// True when the standard start (the high-curvature end) is `control()[2]`.
    pub fn reversed(&self) -> bool {
        self.reversed
    }
}

/// The second-order Taylor guess of Λ for base angle `phi`: ρ ≈ 1 + Λψ + (2-α)Λ²ψ²/2 near the
/// circle, with the moments ∫ ψ^k e^{iψ} over [0, θ_d].
/// Where [`LacSegment::newton_lambda`] starts: a guess of Λ, or the fraction
/// `(θ_lim - φ)/(θ_lim - θ_d/2)` of the way from the limit back to the circle.
#[derive(Clone, Copy, Debug)]
enum NewtonStart {
    Lambda(f64),
    Line(f64),
}

fn taylor_guess(alpha: f64, theta_d: f64, phi: f64) -> f64 {
    let half = 0.5 * theta_d;
    // To first order φ ≈ θ_d/2 + Λ Im(C1/C0), C0 and C1 the moments ∫ e^{iψ} and
    // ∫ ψ e^{iψ} over [0, θ_d].
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
}

impl LacSegment {
    /// The standard interval and the chord's base angle at its start (the high-curvature
    /// end) for Λ; `at_limit` evaluates the limiting curve Λ = Λ_max (α < 0 or α > 1).
    fn base_angle(alpha: f64, lambda: f64, theta_d: f64, at_limit: bool) -> Result<f64> {
        let c = LacStandard::new(alpha, lambda)?;
        let (ta, tb) = Self::standard_interval(alpha, theta_d);
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
        // In [0, 2π): the base angle lies in (0, θ_d), past π only when a spline's span turns
        // by more than a half turn (below π it is what atan2 gives).
        Ok((chord.y.atan2(chord.x) - ta).rem_euclid(std::f64::consts::TAU))
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
    /// (φ increases strictly with Λ), to the resolution of Λ or until the residual is at the
    /// noise of the base angle (4 ulp).
    ///
    /// 1. Far from the limit (the second-order Taylor guess below 0.7 Λ_max): Newton's
    ///    method from that guess, the derivative riding on the chord's quadrature; no θ_lim
    ///    needed. Typically 3 chords.
    /// 2. Otherwise, for α < 0 or α > 1: θ_lim (one integral, and the existence check), then
    ///    Newton from the straight line between the circle and the limit in a variable in
    ///    which φ is nearly linear there. 2 to 5 chords.
    /// 3. If Newton does not converge in its budget (α in [0, 1) near θ_d, extreme shapes):
    ///    Brent's method ([`crate::solve::roots::brent`]) from the Taylor guess and the line.
    pub fn solve_lambda(alpha: f64, theta_d: f64, phi: f64) -> Result<f64> {
        Ok(Self::solve_lambda_chord(alpha, theta_d, phi)?.0)
    }

    /// [`Self::solve_lambda`], with the standard chord over the segment's interval at the
    /// solution when the solve produced it (the Newton path).
    fn solve_lambda_chord(alpha: f64, theta_d: f64, phi: f64) -> Result<(f64, Option<Vec2>)> {
        match Self::lambda_chord_in_region(alpha, theta_d, phi)? {
            Some(found) => Ok(found),
            None => Err(Self::outside_region(alpha, theta_d, phi)),
        }
    }

    /// The error of a triangle outside the existence region, with the region's bounds.
    fn outside_region(alpha: f64, theta_d: f64, phi: f64) -> Error {
        let half = 0.5 * theta_d;
        let lim = match Self::theta_lim(alpha, theta_d) {
            Ok(lim) => lim,
            Err(e) => return e,
        };
        Error::NoSegment(format!(
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
        ))
    }

    /// [`Self::solve_lambda_chord`], `None` outside the existence region (no message is
    /// built: a spline's solve probes outside it often).
    fn lambda_chord_in_region(
        alpha: f64,
        theta_d: f64,
        phi: f64,
    ) -> Result<Option<(f64, Option<Vec2>)>> {
        let half = 0.5 * theta_d;
        if (phi - half).abs() <= 1e-15 * theta_d {
            return Ok(Some((0.0, None)));
        }
        let guess = taylor_guess(alpha, theta_d, phi);
        let lmax = Self::lambda_max(alpha, theta_d);
        let newton = |start| Self::newton_lambda(alpha, theta_d, phi, start, 6);
        if phi > half && alpha != 1.0 && guess > 0.0 && guess < 0.7 * lmax {
            if let Some((l, chord, _)) = newton(NewtonStart::Lambda(guess)) {
                return Ok(Some((l, Some(chord))));
            }
        }
        let lim = Self::theta_lim(alpha, theta_d)?;
        if !(phi > half && phi < lim) {
            return Ok(None);
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
        let p1 = alpha / (alpha - 1.0);
        if lmax.is_finite() && p1 > 0.0 {
            if let Some((l, chord, _)) = newton(NewtonStart::Line((lim - phi) / (lim - half))) {
                return Ok(Some((l, Some(chord))));
            }
        }
        // The base angle is computed to a few units of 1e-16 of itself: a residual below
        // this is noise, and the root is as good as the evaluation allows.
        let f_tol = 4.0 * f64::EPSILON * phi;
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
            return Ok(Some((lambda_of(z), None)));
        }
        let mut hi = lmax;
        if !hi.is_finite() {
            // α = 1: Λ θ_d is the log of the curvature ratio between the ends, so the
            // bracket grows in that, not in Λ (a piece turning 1e-8 rad needs Λ = 3e7 for a
            // ratio of 1.35). A ratio past e^700 overflows and counts as above the root.
            hi = 1.0 / theta_d;
            while f_at(hi)? < 0.0 {
                hi *= 2.0;
                if hi * theta_d > ALPHA_ONE_LOG_RATIO {
                    return Err(Error::NoConvergence(format!(
                        "the alpha = 1 segment for this triangle (base angle {phi:.6e} rad, \
                         {:.3e} below its limit {lim:.6e}) has a curvature ratio beyond \
                         e^{ALPHA_ONE_LOG_RATIO}: too extreme to evaluate",
                        lim - phi
                    )));
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
        let l = brent(
            f_at,
            (0.0, flo),
            (hi, fhi),
            &[(xa, fa), (xb, fb)],
            1e-15 * hi,
            f_tol,
            100,
        )?;
        Ok(Some((l, None)))
    }

    /// The fast path of the Λ solve: Newton's method ([`crate::solve::roots::newton`]) on the base
    /// angle, its Λ derivative riding on the chord's quadrature
    /// ([`LacStandard::integral_dlambda`]), from the Taylor guess, in z = (1 - Λ/Λ_max)^p1
    /// for α < 0 or α > 1 (where φ is nearly linear up to the limit) and in Λ for
    /// 0 <= α < 1; θ_lim is not needed, since a root below Λ_max proves the segment exists.
    /// Typically 2 or 3 chords instead of 6 plus θ_lim's. `None` when it does not converge
    /// within 8 chords or a chord fails (the caller's bracketed solve then decides);
    /// otherwise Λ and the chord at Λ (extrapolated along the derivative over the last
    /// step, below 1e-7 relative).
    fn newton_lambda(
        alpha: f64,
        theta_d: f64,
        phi: f64,
        start: NewtonStart,
        max_evals: usize,
    ) -> Option<(f64, Vec2, usize)> {
        let lmax = Self::lambda_max(alpha, theta_d);
        if !lmax.is_finite() {
            return None;
        }
        let (ta, tb) = Self::standard_interval(alpha, theta_d);
        let p1 = alpha / (alpha - 1.0);
        // The Newton variable: z = δ^q, δ = 1 - Λ/Λ_max, q = min(p1, 1) for α < 0 or α > 1
        // (θ_lim - φ ~ δ^q near the limit); Λ itself for 0 <= α < 1.
        let q = p1.min(1.0);
        let in_z = p1 > 0.0;
        let lambda_of = |x: f64| -> (f64, f64) {
            if in_z {
                let e = x.ln() / q;
                (lmax * -e.exp_m1(), -lmax * (e - x.ln()).exp() / q)
            } else {
                (x, 1.0)
            }
        };
        let x0 = match start {
            NewtonStart::Lambda(g) if in_z => (1.0 - g / lmax).max(0.0).powf(q),
            NewtonStart::Lambda(g) => g.min(lmax),
            NewtonStart::Line(s) if in_z => s,
            NewtonStart::Line(s) => lmax * (1.0 - s),
        };
        if x0.is_nan() || x0 <= 0.0 {
            return None;
        }
        let (lo, hi) = if in_z { (0.0, 1.0) } else { (0.0, lmax) };
        let x_tol = if in_z {
            let (l0, dl) = lambda_of(x0);
            (2.0 * f64::EPSILON * l0 / dl.abs()).clamp(1e-16, 1e-12)
        } else {
            1e-15 * lmax
        };
        let f = |x: f64| -> Result<(f64, f64, (f64, Vec2, Vec2))> {
            let (l, dl) = lambda_of(x);
            let c = LacStandard::new(alpha, l)?;
            if !(c.in_domain(ta) && c.in_domain(tb)) {
                return Err(Error::NoConvergence("outside the domain".into()));
            }
            let (chord, d) = c.integral_dlambda(ta, tb)?;
            let slope = chord.cross(d) / chord.hypot2();
            Ok((chord.y.atan2(chord.x) - ta - phi, slope * dl, (l, chord, d)))
        };
        let root = crate::solve::roots::newton(
            f,
            x0,
            (lo, hi),
            !in_z,
            x_tol,
            4.0 * f64::EPSILON * phi,
            max_evals,
        )
        .ok()?;
        if !root.converged {
            return None;
        }
        let (l_at, chord, d) = root.payload;
        let l = lambda_of(root.x).0;
        (l > 0.0 && l < lmax).then(|| (l, chord + d * (l - l_at), root.evaluations))
    }

    /// The standard interval of a segment turning `theta_d`: [0, θ_d] for α <= 1 (the
    /// radius grows from 1), [-θ_d, 0] above; its start is the high-curvature end.
    pub(crate) fn standard_interval(alpha: f64, theta_d: f64) -> (f64, f64) {
        if alpha <= 1.0 {
            (0.0, theta_d)
        } else {
            (-theta_d, 0.0)
        }
    }

    /// The curve of the Λ solve for (α, θ_d, φ): its standard form, its standard interval
    /// and the chord over it (from the solve when it has it, else one integral; P(0) = 0).
    pub(crate) fn solved_standard(alpha: f64, theta_d: f64, phi: f64) -> Result<SolvedStandard> {
        Self::solved_standard_in_region(alpha, theta_d, phi)?
            .ok_or_else(|| Self::outside_region(alpha, theta_d, phi))
    }

    /// [`Self::solved_standard`], `None` outside the existence region.
    fn solved_standard_in_region(
        alpha: f64,
        theta_d: f64,
        phi: f64,
    ) -> Result<Option<SolvedStandard>> {
        let Some((lambda, chord)) = Self::lambda_chord_in_region(alpha, theta_d, phi)? else {
            return Ok(None);
        };
        let standard = LacStandard::new(alpha, lambda)?;
        let interval = Self::standard_interval(alpha, theta_d);
        let chord = match chord {
            Some(c) => c,
            None => standard.integral(interval.0, interval.1).map_err(|e| {
                Error::NoConvergence(format!(
                    "the segment for this triangle is too extreme to evaluate in f64 \
                     (lambda = {lambda:.3e}): {e}"
                ))
            })?,
        };
        Ok(Some((standard, interval, chord)))
    }

    /// The curvatures at the high- and the low-curvature end of the segment of shape
    /// `alpha` turning `theta_d` with base angle `phi` at its high-curvature end, for a chord
    /// of length 1, without building it (a spline's solve needs only these): the Λ solve,
    /// the standard chord and two closed-form curvatures. Errors as [`LacSegment::new`]
    /// (`None` outside the existence region).
    pub(crate) fn unit_chord_curvatures(
        alpha: f64,
        theta_d: f64,
        phi: f64,
    ) -> Result<Option<(f64, f64)>> {
        let Some((standard, (t0, t1), chord)) =
            Self::solved_standard_in_region(alpha, theta_d, phi)?
        else {
            return Ok(None);
        };
        let len = chord.hypot();
        let (k0, k1) = (standard.kappa(t0)? * len, standard.kappa(t1)? * len);
        if !(k0.is_finite() && k1.is_finite()) {
            return Err(Error::NoConvergence(
                "the segment's end curvature overflows f64 (triangle too extreme)".into(),
            ));
        }
        Ok(Some((k0, k1)))
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
        let (standard, interval, chord) = Self::solved_standard(alpha, theta_d, phi)?;
        let (a, b) = if interval.0 == 0.0 {
            (Vec2::ZERO, chord)
        } else {
            (-chord, Vec2::ZERO)
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
    pub(crate) fn sample_thetas(&self, n: usize) -> Vec<f64> {
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
    pub fn sample(&self, n: usize) -> Result<Polyline> {
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
        Ok(Polyline {
            points: out,
            kappa: k,
        })
    }

    /// Standard-form θ at turning angle `tau` from `control[0]`.
    fn theta_at_turning(&self, tau: f64) -> f64 {
        if self.reversed {
            self.interval.1 - tau
        } else {
            self.interval.0 + tau
        }
    }

    /// The segment at arc length `s` from `control[0]` (clamped into [0, length]): point,
    /// unit tangent, signed curvature and dκ/ds, the last in closed form from the standard
    /// form's `dρ/ds = Λ ρ^(1-α)` (the straight logarithmic curvature graph), the point at
    /// the standard θ of that length ([`LacStandard::theta_at_arc_length`]).
    pub fn at_arc_length(&self, s: f64) -> Result<ArcPoint> {
        if !s.is_finite() {
            return Err(Error::invalid("s", "must be finite"));
        }
        let c = self.scale();
        let (a, b) = self.interval;
        let (sa, sb) = (self.standard.arc_length(a)?, self.standard.arc_length(b)?);
        let s = s.clamp(0.0, (sb - sa) * c);
        let target = if self.reversed {
            sb - s / c
        } else {
            sa + s / c
        };
        let theta = self.standard.theta_at_arc_length(target)?.clamp(a, b);
        let tau = if self.reversed { b - theta } else { theta - a };
        let at = self.eval_turning(&[tau])?;
        let (p, tangent, radius) = (at.points[0], at.tangents[0], at.radii[0]);
        let sign = self.turn_sign();
        // dρ/ds along the segment: ρ grows away from the standard start (high curvature).
        let rho_std = self.standard.rho(theta)?;
        let alpha = self.standard.alpha();
        let drho = self.standard.lambda() * rho_std.powf(1.0 - alpha);
        let drho = if self.reversed { -drho } else { drho };
        Ok(ArcPoint {
            p,
            tangent,
            kappa: sign / radius,
            dkappa_ds: -sign * drho / (radius * radius),
        })
    }

    /// Points, unit tangents and radii of curvature at turning angles τ measured from
    /// `control[0]` (τ = 0) to `control[2]` (τ = θ_d); τ outside [0, θ_d] is clamped.
    pub fn eval_turning(&self, taus: &[f64]) -> Result<TurningSamples> {
        self.eval_thetas(&self.thetas_at_turning(taus)?)
    }

    /// The standard-form θ of turning angles τ (finite; clamped to [0, θ_d]).
    fn thetas_at_turning(&self, taus: &[f64]) -> Result<Vec<f64>> {
        if let Some(i) = taus.iter().position(|t| !t.is_finite()) {
            return Err(Error::invalid(format!("tau[{i}]"), "must be finite"));
        }
        Ok(taus
            .iter()
            .map(|t| self.theta_at_turning(t.clamp(0.0, self.theta_d)))
            .collect())
    }

    /// The points of [`Self::eval_turning`] alone (no tangents: no sine and cosine per
    /// point).
    pub(crate) fn points_at_turning(&self, taus: &[f64]) -> Result<Vec<Point>> {
        let (pts, _) = self.standard_points(&self.thetas_at_turning(taus)?)?;
        Ok(pts.iter().map(|p| self.map.apply(p.to_vec2())).collect())
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

    /// Points, unit tangents and radii at standard-form angles (no clamping).
    fn eval_thetas(&self, th: &[f64]) -> Result<TurningSamples> {
        let (pts, kappa) = self.standard_points(th)?;
        let dir = if self.reversed { -1.0 } else { 1.0 };
        let o = self.map.apply(Vec2::ZERO);
        let points = pts.iter().map(|p| self.map.apply(p.to_vec2())).collect();
        // e^{iθ} by the rotation of each step (sorted angles, steps up to 0.05 rad),
        // from scratch every 32 points.
        // The map is a similarity: it scales lengths by `scale` and turns every tangent alike.
        let mut e = Vec2::ZERO;
        let mut prev = f64::NAN;
        let scale = self.scale();
        let mut tangents = Vec::with_capacity(th.len());
        let mut radii = Vec::with_capacity(th.len());
        for (i, (t, k)) in th.iter().zip(&kappa).enumerate() {
            let h = t - prev;
            e = if i % 32 != 0 && h.abs() <= 0.05 {
                super::cmul(e, super::standard::rotation(h))
            } else {
                Vec2::from_angle(*t)
            };
            prev = *t;
            tangents.push((self.map.apply(e * dir) - o) / scale);
            radii.push(scale / k);
        }
        Ok(TurningSamples {
            points,
            tangents,
            radii,
        })
    }

    /// The turning angle (from `control[0]`, possibly outside `[0, θ_d]`: on the curve's
    /// extension) of the foot of the perpendicular from `q`, by Newton's method from `tau0`;
    /// `None` if it leaves the curve's domain or does not converge.
    pub fn project_turning(&self, q: Point, tau0: f64) -> Option<f64> {
        let (lo, hi) = self.standard.domain();
        let sign = self.turn_sign();
        // g(τ) = (q - P)·u, g'(τ) = -ρ + (q - P)·u' with u' = ±n (the tangent turns by dτ
        // towards the side the curve bends to); g' < 0 at a nearest point.
        let update = |tau: f64| {
            let th = self.theta_at_turning(tau);
            if !(lo < th && th < hi) {
                return None;
            }
            let at = self.eval_thetas(&[th]).ok()?;
            let (rho, u) = (at.radii[0], at.tangents[0]);
            let n = Vec2::new(-u.y, u.x);
            let r = q - at.points[0];
            let dg = -rho + sign * r.dot(n);
            (dg < 0.0).then(|| -r.dot(u) / dg)
        };
        let opts = crate::solve::roots::Newton1d {
            max_iterations: 50,
            max_step: 0.5,
            abs_tol: 1e-13,
            rel_tol: 1e-13,
            bounds: (f64::NEG_INFINITY, f64::INFINITY),
            clamp: false,
        };
        let root = crate::solve::roots::newton_1d(update, tau0, &opts);
        root.converged().then_some(root.x)
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
        let crate::lac::TurningSamples {
            points: pts,
            tangents: der,
            ..
        } = self.eval_thetas(&[a, b])?;
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
