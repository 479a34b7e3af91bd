//! A log-aesthetic segment with an inflection point at its start.

use super::{
    triangle_angles, ArcPoint, LacSegment, Polyline, Similarity, TriangleAngles, TurningSamples,
};
use crate::error::{Error, Result};
use crate::solve::roots::illinois;
use kurbo::{Point, Vec2};
use std::f64::consts::PI;

/// A log-aesthetic segment with an inflection point at its start (docs/math.md §3.2; S4 §2.2):
/// `C(s) = ∫_0^s e^{i t^q} dt`, `q = (α-1)/α > 1` (α < 0), tangent angle `θ = s^q`,
/// curvature `q s^(q-1)`, zero at s = 0. Given the triangle, α follows from the base angle at
/// the inflection end, which runs from 0 (α → 0-) to θ_d/2 (α → -∞, a circle).
#[derive(Clone, Debug, PartialEq)]
pub struct LacInflectionSegment {
    /// The shape parameter (< 0).
    pub(crate) alpha: f64,
    /// Turning angle θ_d in (0, π).
    pub(crate) theta_d: f64,
    /// Control triangle; `control[0]` is the inflection end.
    pub(crate) control: [Point; 3],
    /// From the standard form to the input.
    map: Similarity,
}

impl LacInflectionSegment {
    /// α (< 0).
    pub fn alpha(&self) -> f64 {
        self.alpha
    }
    /// The turning angle θ_d in (0, π).
    pub fn theta_d(&self) -> f64 {
        self.theta_d
    }
    /// The control triangle; `control()[0]` is the inflection end.
    pub fn control(&self) -> [Point; 3] {
        self.control
    }
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
pub(super) fn inflection_integral(r: f64, th0: f64, th1: f64) -> Result<Vec2> {
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

    /// The end point of the standard inflection-end segment of shape `alpha` (< 0) at unit
    /// scale, turning `theta` in [0, 3.5] counter-clockwise from +x at its inflection end
    /// (the origin): its angle is the base angle at the inflection end, its length the chord
    /// per unit of scale. With [`Self::standard_end_kappa`], what a solver that places an
    /// inflection between two given tangents needs without building the segment.
    pub(crate) fn standard_chord(alpha: f64, theta: f64) -> Result<Vec2> {
        let r = alpha / (alpha - 1.0);
        Ok(inflection_integral(r, 0.0, theta)? * r)
    }

    /// The curvature at the far end of that standard segment (unit scale): `θ^(1-r) / r`.
    pub(crate) fn standard_end_kappa(alpha: f64, theta: f64) -> f64 {
        let r = alpha / (alpha - 1.0);
        theta.powf(1.0 - r) / r
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
        Self::with_shape(r / (r - 1.0), theta_d, control)
    }

    /// The segment of shape `alpha` (< 0) turning `theta_d` in the triangle `control`
    /// (`control[0]` = the inflection end) where the caller knows both: a solver that
    /// placed the triangle from α's own standard segment (the G2 spline's inflection
    /// halves). Neither is solved again from the triangle, which a thin one (a half that
    /// turns little) leaves ill-conditioned: α recovered there moved a half's end
    /// curvature by 3 %, and its turning read from the apex moved it by 1e-7 of the
    /// spline's largest curvature. The similarity sends the standard segment's ends onto
    /// the triangle's.
    pub(crate) fn with_shape(alpha: f64, theta_d: f64, control: [Point; 3]) -> Result<Self> {
        if !(alpha < 0.0 && alpha.is_finite()) {
            return Err(Error::invalid(
                "alpha",
                "inflection-end segments need alpha < 0",
            ));
        }
        if !(theta_d > 0.0 && theta_d < PI) {
            return Err(Error::NoSegment(format!(
                "an inflection-end segment turning {:.6} deg",
                theta_d.to_degrees()
            )));
        }
        let r = alpha / (alpha - 1.0);
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
        let at = self.eval_turning(&[tau])?;
        let (p, t) = (at.points[0], at.tangents[0]);
        let c = self.control;
        let meet = |a: Point, da: Vec2, b: Point, db: Vec2| -> Result<Point> {
            super::tangents_meet(a, da, b, db).ok_or_else(|| {
                Error::Degenerate("the split point's tangent is parallel to an end tangent".into())
            })
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

    /// The segment at arc length `s` from the inflection end (clamped into [0, length]):
    /// in standard form the tangent angle is `θ = s^q`, the curvature `q s^(q-1)` and its
    /// derivative `q (q-1) s^(q-2)`, which is infinite at the inflection for α < -1 (q < 2:
    /// the curvature rises there faster than linearly).
    pub fn at_arc_length(&self, s: f64) -> Result<ArcPoint> {
        if !s.is_finite() {
            return Err(Error::invalid("s", "must be finite"));
        }
        let c = self.scale();
        let q = 1.0 / self.r();
        let s_std = (s / c).clamp(0.0, self.theta_d.powf(self.r()));
        let theta = s_std.powf(q).min(self.theta_d);
        let at = self.eval_turning(&[theta])?;
        let sign = self.turn_sign();
        Ok(ArcPoint {
            p: at.points[0],
            tangent: at.tangents[0],
            kappa: sign * q * s_std.powf(q - 1.0) / c,
            dkappa_ds: sign * q * (q - 1.0) * s_std.powf(q - 2.0) / (c * c),
        })
    }

    /// Points, unit tangents and radii of curvature (infinite at τ = 0) at turning angles τ
    /// from the inflection end (τ = 0) to `control[2]` (τ = θ_d); τ outside [0, θ_d] is
    /// clamped.
    pub fn eval_turning(&self, taus: &[f64]) -> Result<TurningSamples> {
        if let Some(i) = taus.iter().position(|t| !t.is_finite()) {
            return Err(Error::invalid(format!("tau[{i}]"), "must be finite"));
        }
        let r = self.r();
        let o = self.map.apply(Vec2::ZERO);
        let mut pts = Vec::with_capacity(taus.len());
        let mut tangents = Vec::with_capacity(taus.len());
        let mut radii = Vec::with_capacity(taus.len());
        // kappa(θ) = q θ^(1 - r) in standard form ([`Self::sample`]).
        let q = 1.0 / r;
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
            radii.push(self.scale() / (q * th.powf(1.0 - r)));
        }
        Ok(TurningSamples {
            points: pts,
            tangents,
            radii,
        })
    }

    /// `n >= 2` points from the inflection end to `control[2]`, evenly spaced in tangent angle,
    /// and their signed curvature (0 at the start).
    pub fn sample(&self, n: usize) -> Result<Polyline> {
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
        Ok(Polyline {
            points: pts,
            kappa: k,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The standard half of shape α turning θ at unit scale, as a triangle: inflection at
    /// the origin along +x, its end where the standard chord puts it.
    fn standard_triangle(alpha: f64, theta: f64) -> [Point; 3] {
        let b = LacInflectionSegment::standard_chord(alpha, theta).unwrap();
        let t = Vec2::from_angle(theta);
        // The end tangent's line meets the x axis at the apex.
        let apex = Point::new(b.x - b.y * t.x / t.y, 0.0);
        [Point::ZERO, apex, b.to_point()]
    }

    #[test]
    fn a_known_shape_gives_the_solved_segment() {
        for (alpha, theta) in [(-1.0, 0.8), (-0.4, 2.0), (-3.0, 0.3)] {
            let c = standard_triangle(alpha, theta);
            let solved = LacInflectionSegment::new(c).unwrap();
            let known = LacInflectionSegment::with_shape(alpha, theta, c).unwrap();
            let k = LacInflectionSegment::standard_end_kappa(alpha, theta);
            assert!((solved.alpha - alpha).abs() < 1e-9, "{}", solved.alpha);
            assert!(
                (known.end_curvature() - k).abs() <= 1e-13 * k,
                "{alpha} {theta}"
            );
            assert!(
                (solved.end_curvature() - k).abs() <= 1e-9 * k,
                "{alpha} {theta}"
            );
        }
    }

    /// A half that turns 1e-6 rad, placed as the spline places one (turned, scaled, moved
    /// off the origin): α and the turning read back from the rounded triangle are off, and
    /// the end curvature with them (by 1.1e-4, measured); with α and θ_d known it is the
    /// standard one, `θ^(1-r)/r` over the scale, to the rounding of the triangle's ends.
    #[test]
    fn a_thin_half_keeps_its_curvature_when_its_shape_is_known() {
        let (alpha, theta) = (-1.0, 1e-6);
        let (f, o) = (Vec2::new(0.006, 0.008), Vec2::new(3.7, -2.1));
        let c = standard_triangle(alpha, theta)
            .map(|p| (o + crate::lac::cmul(p.to_vec2(), f)).to_point());
        let k = LacInflectionSegment::standard_end_kappa(alpha, theta) / f.hypot();
        let known = LacInflectionSegment::with_shape(alpha, theta, c).unwrap();
        assert!(
            (known.end_curvature() - k).abs() <= 1e-9 * k,
            "{:e}",
            known.end_curvature() / k - 1.0
        );
        assert!(LacInflectionSegment::with_shape(1.0, theta, c).is_err());
        assert!(LacInflectionSegment::with_shape(alpha, PI, c).is_err());
    }
}
