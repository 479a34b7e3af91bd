use crate::bernstein::sign_change_roots;
use crate::bezier::{Bezier, PlanarCurve};
use crate::bspline::BSpline;
use crate::error::Result;
use kurbo::{Point, Vec2};

/// The B-spline as Bézier spans over its knot intervals, for derivatives at any u.
pub(super) struct Track {
    pub(super) spans: Vec<Bezier>,
    pub(super) breaks: Vec<f64>,
}

impl Track {
    pub(super) fn new(s: &BSpline) -> Result<Track> {
        let spans = s.to_beziers()?;
        let n = spans.len();
        let p = s.degree;
        let breaks = (0..=n).map(|i| s.knots[p + i]).collect();
        Ok(Track { spans, breaks })
    }

    pub(super) fn locate(&self, u: f64) -> (usize, f64) {
        let n = self.spans.len();
        let mut i = 0;
        while i + 1 < n && self.breaks[i + 1] <= u {
            i += 1;
        }
        let (a, b) = (self.breaks[i], self.breaks[i + 1]);
        (i, ((u - a) / (b - a)).clamp(0.0, 1.0))
    }

    pub(super) fn point(&self, u: f64) -> Point {
        let (i, t) = self.locate(u);
        self.spans[i].eval(t)
    }

    pub(super) fn derivs(&self, u: f64) -> crate::bezier::Derivs {
        let (i, t) = self.locate(u);
        self.spans[i].derivs(t)
    }

    pub(super) fn direction(&self, u: f64) -> Vec2 {
        let d = self.derivs(u).d1;
        d / d.hypot()
    }

    /// Inflection parameters and curvature-maximum (of |κ|) parameters, sorted.
    pub(super) fn events(&self) -> (Vec<f64>, Vec<f64>) {
        let (mut infl, mut maxima) = (Vec::new(), Vec::new());
        for (i, b) in self.spans.iter().enumerate() {
            let (x, y) = b.components();
            let (x1, y1) = (x.deriv(), y.deriv());
            let (x2, y2) = (x1.deriv(), y1.deriv());
            let g = x1.mul(&y2).sub(&y1.mul(&x2));
            let f = x1.mul(&x1).add(&y1.mul(&y1));
            let h = g
                .deriv()
                .mul(&f)
                .scale(2.0)
                .sub(&g.mul(&f.deriv()).scale(3.0));
            let (a, w) = (self.breaks[i], self.breaks[i + 1] - self.breaks[i]);
            for t in sign_change_roots(&g) {
                infl.push(a + w * t);
            }
            for t in sign_change_roots(&h) {
                // A maximum of |κ|: d|κ|/ds goes from + to -; sign(h) = sign(dκ/ds).
                let e = 1e-6;
                let before = h.eval((t - e).max(0.0)) * g.eval(t).signum();
                let after = h.eval((t + e).min(1.0)) * g.eval(t).signum();
                if before > 0.0 && after < 0.0 {
                    maxima.push(a + w * t);
                }
            }
        }
        (infl, maxima)
    }

    /// Unwrapped tangent angle at `u`, continuing from `prev` at `u_prev` (steps small enough
    /// that the tangent turns less than π between them).
    pub(super) fn angle_between(&self, ua: f64, ub: f64) -> f64 {
        // Signed turning from ua to ub, accumulated over small steps.
        let n = 64;
        let mut total = 0.0;
        let mut prev = self.direction(ua);
        for k in 1..=n {
            let u = ua + (ub - ua) * k as f64 / n as f64;
            let d = self.direction(u);
            total += prev.cross(d).atan2(prev.dot(d));
            prev = d;
        }
        total
    }

    /// |κ| at u.
    pub(super) fn abs_kappa(&self, u: f64) -> f64 {
        self.derivs(u).kappa().abs()
    }
}

/// Parameters where the curve turns by `turn` (in [0, total]) from `ua`, by bisection.
pub(super) fn u_at_turn(track: &Track, ua: f64, ub: f64, target: f64) -> f64 {
    let total = track.angle_between(ua, ub);
    let sgn = total.signum();
    let b = crate::solve::roots::bisect_by(
        |mid| (sgn * track.angle_between(ua, mid) < target).then_some(()),
        ua,
        ub,
        |a, b| 0.5 * (a + b),
        |_, _| false,
        60,
    );
    0.5 * (b.inside + b.outside)
}
