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

//! ## Rooms
//!
//! - `standard`: [`LacStandard`], the curve in standard form;
//! - `segment`: [`LacSegment`], a segment in a control triangle;
//! - `inflection`: [`LacInflectionSegment`], a segment with an inflection end;
//! - here: the complex arithmetic, the similarity and the triangle measure they share.

mod inflection;
mod segment;
mod standard;

pub use inflection::LacInflectionSegment;
pub use segment::LacSegment;

pub use standard::{LacStandard, MAX_ABS_ALPHA, MAX_QUARTER_TURNS};

/// The range of α a fit to data may return, in the whole library (`lac_fit`'s free α,
/// `sketch`'s pieces): beyond it the logarithmic curvature graph is so steep that points
/// cannot tell alphas apart, and a result on the bound says so (its
/// `alpha_at_bound`). [`MAX_ABS_ALPHA`] is what a curve can be built with, not what a fit
/// should conclude.
pub const ALPHA_RANGE: (f64, f64) = (-5.0, 5.0);

use crate::error::{Error, Result};
use kurbo::{Point, Vec2};

/// Samples of a segment with their signed curvature: what `sample` of [`LacSegment`] and
/// [`LacInflectionSegment`] returns, from `control[0]` to `control[2]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Polyline {
    /// The points, the ends exact.
    pub points: Vec<Point>,
    /// The signed curvature at each point (positive when the curve turns left), in inverse
    /// input units.
    pub kappa: Vec<f64>,
}

/// A point of a log-aesthetic segment at an arc length: what `at_arc_length` of
/// [`LacSegment`] and [`LacInflectionSegment`] returns. With the arc length as the
/// parameter, the first derivative is `tangent`, the second `kappa` times the tangent
/// turned by +90°, the third `dkappa_ds` times that less `kappa²` times the tangent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArcPoint {
    /// The point.
    pub p: Point,
    /// The unit tangent, in the direction from `control[0]` to `control[2]`.
    pub tangent: Vec2,
    /// Signed curvature (positive: turning counter-clockwise), in input units.
    pub kappa: f64,
    /// Its derivative in arc length, in input units.
    pub dkappa_ds: f64,
}

/// Points at given turning angles with their tangents: what `eval_turning` of
/// [`LacSegment`] and [`LacInflectionSegment`] returns.
#[derive(Clone, Debug, PartialEq)]
pub struct TurningSamples {
    /// The points.
    pub points: Vec<Point>,
    /// The unit tangents, in the direction from `control[0]` to `control[2]`.
    pub tangents: Vec<Vec2>,
    /// The radius of curvature at each point, in input units (infinite at an inflection
    /// end). `tangents[i] * radii[i]` is dP/dτ, the derivative in the turning angle.
    pub radii: Vec<f64>,
}

impl TurningSamples {
    /// dP/dτ at sample `i` (the tangent scaled by the radius of curvature).
    pub fn derivative(&self, i: usize) -> Vec2 {
        self.tangents[i] * self.radii[i]
    }
}

/// Complex product, quotient and conjugate of vectors taken as complex numbers (the
/// similarities here and the spline's chord frames).
pub(crate) fn cmul(a: Vec2, b: Vec2) -> Vec2 {
    Vec2::new(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x)
}
pub(crate) fn cdiv(a: Vec2, b: Vec2) -> Vec2 {
    let d = b.hypot2();
    Vec2::new((a.x * b.x + a.y * b.y) / d, (a.y * b.x - a.x * b.y) / d)
}
pub(crate) fn conj(a: Vec2) -> Vec2 {
    Vec2::new(a.x, -a.y)
}

/// Where the line through `a` along `da` meets the line through `b` along `db` (the apex of
/// a control triangle from its end tangents); `None` for parallel lines.
pub(crate) fn tangents_meet(a: Point, da: Vec2, b: Point, db: Vec2) -> Option<Point> {
    let x = a + da * ((b - a).cross(db) / da.cross(db));
    x.is_finite().then_some(x)
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

#[cfg(test)]
mod tests {
    use super::inflection::inflection_integral;
    use super::*;
    use crate::quadrature::{integrate, QuadOptions};
    use std::f64::consts::FRAC_PI_2;

    fn rel(a: Point, re: f64, im: f64) -> f64 {
        ((a.x - re).powi(2) + (a.y - im).powi(2)).sqrt() / (re * re + im * im).sqrt()
    }

    /// α = 1 is the logarithmic spiral ρ = e^{Λθ}: its chord over [0, θ_d] is
    /// (e^{(Λ+i)θ_d} - 1)/(Λ+i) in closed form, so the base angle at the high-curvature
    /// end is that chord's argument. The solve recovers Λ from it on pieces that turn
    /// nearly nothing (a sketch's sliver turned 1.2e-8 rad and needed Λ = 3e7: the old
    /// bracket stopped at 1e6) as on ordinary ones.
    #[test]
    fn the_alpha_one_solve_meets_the_spirals_closed_form_at_every_turning() {
        let base_angle = |lambda: f64, theta_d: f64| {
            // e^{(Λ+i)θ} - 1 = (e^{Λθ} - 1) + e^{Λθ}(e^{iθ} - 1), without cancellation.
            let g = (lambda * theta_d).exp_m1();
            let e = (lambda * theta_d).exp();
            let (s, c1) = (theta_d.sin(), -2.0 * (0.5 * theta_d).sin().powi(2));
            let (re, im) = (g + e * c1, e * s);
            // Divided by Λ + i: times (Λ - i).
            let (x, y) = (re * lambda + im, im * lambda - re);
            y.atan2(x)
        };
        for theta_d in [1.2e-8, 1e-5, 0.3, 2.0] {
            for log_ratio in [0.01, 0.3, 2.0, 30.0] {
                let lambda = log_ratio / theta_d;
                let phi = base_angle(lambda, theta_d);
                let got = LacSegment::solve_lambda(1.0, theta_d, phi).unwrap();
                // φ is flat in Λ near the limit: compare the log ratios, to the base angle's
                // resolution there.
                let tol = if log_ratio > 10.0 { 1e-6 } else { 1e-7 };
                assert!(
                    ((got - lambda) / lambda).abs() < tol,
                    "theta_d {theta_d:e}, ratio e^{log_ratio}: lambda {got:e} vs {lambda:e}"
                );
            }
        }
    }

    #[test]
    fn theta_at_arc_length_inverts_the_arc_length() {
        for alpha in [-3.0, -1.0, 0.0, 1e-9, 0.5, 1.0 - 1e-9, 1.0, 2.0, 5.0] {
            for lambda in [0.0, 0.3, 2.0] {
                let c = LacStandard::new(alpha, lambda).unwrap();
                for theta in [-1.0, -0.2, 0.0, 0.1, 0.7, 1.5] {
                    if !c.in_domain(theta) {
                        continue;
                    }
                    let Ok(s) = c.arc_length(theta) else { continue };
                    let back = c.theta_at_arc_length(s).unwrap();
                    assert!(
                        (back - theta).abs() <= 1e-12 * (1.0 + theta.abs()),
                        "alpha {alpha} lambda {lambda} theta {theta}: {back}"
                    );
                }
            }
        }
        // Beyond the end of the curve, and not a number.
        let c = LacStandard::new(-1.0, 1.0).unwrap();
        assert!(c.theta_at_arc_length(1.0).is_err() && c.theta_at_arc_length(f64::NAN).is_err());
    }

    /// Checks of `at_arc_length` against identities: the arc length from the start to the
    /// point's turning angle is `s` (the closed-form length of a sub-segment), dκ/ds is the
    /// derivative of κ (central differences), and the logarithmic curvature graph
    /// `ln(ρ ds/dρ)` against `ln ρ` is a line of slope α.
    fn check_arc_points(at: &dyn Fn(f64) -> ArcPoint, len: f64, alpha: f64) {
        let mut lcg: Vec<(f64, f64)> = Vec::new();
        for k in 1..20 {
            let s = len * k as f64 / 20.0;
            let q = at(s);
            let h = 1e-5 * len;
            let fd = (at(s + h).kappa - at(s - h).kappa) / (2.0 * h);
            assert!(
                (fd - q.dkappa_ds).abs() <= 1e-6 * q.dkappa_ds.abs().max(q.kappa.abs() / len),
                "s {s}: {fd:e} vs {:e}",
                q.dkappa_ds
            );
            assert!((q.tangent.hypot() - 1.0).abs() < 1e-14);
            let rho = 1.0 / q.kappa.abs();
            let drho = -q.dkappa_ds * q.kappa.signum() * rho * rho;
            lcg.push((rho.ln(), (rho / drho.abs()).ln()));
        }
        let c0 = lcg[0].1 - alpha * lcg[0].0;
        for (x, y) in &lcg {
            assert!(
                (y - alpha * x - c0).abs() < 1e-9,
                "alpha {alpha}: {x} {y} {c0}"
            );
        }
    }

    #[test]
    fn a_segment_at_an_arc_length() {
        let tri = [
            Point::new(0.0, 0.0),
            Point::new(10.0, 0.0),
            Point::new(16.0, 9.0),
        ];
        for alpha in [-2.0, 0.0, 0.5, 1.0, 3.0] {
            for control in [tri, [tri[2], tri[1], tri[0]]] {
                let seg = LacSegment::new(alpha, control).unwrap();
                let len = seg.arc_length().unwrap();
                let start = control[1] - control[0];
                let at = |s: f64| seg.at_arc_length(s).unwrap();
                check_arc_points(&at, len, alpha);
                // The length from the start to the point's turning angle is s.
                for s in [0.3 * len, 0.77 * len] {
                    let q = at(s);
                    let tau = start.cross(q.tangent).atan2(start.dot(q.tangent)).abs();
                    let part = seg.sub_segment(0.0, tau).unwrap().arc_length().unwrap();
                    assert!(
                        (part - s).abs() < 1e-11 * len,
                        "alpha {alpha}: {part} vs {s}"
                    );
                    let on = seg.eval_turning(&[tau]).unwrap().points[0];
                    assert!((on - q.p).hypot() < 1e-11 * len);
                }
                // The ends, and the clamp.
                let (k0, k1) = seg.end_curvatures().unwrap();
                assert!((at(0.0).kappa - k0).abs() < 1e-12 * k0.abs());
                assert!((at(len).kappa - k1).abs() < 1e-12 * k1.abs());
                assert_eq!(at(2.0 * len).p, at(len).p);
                assert!(seg.at_arc_length(f64::NAN).is_err());
                // Reversal: the same point, curvature of the other sign, the same dκ/ds.
                let rev = LacSegment::new(alpha, [control[2], control[1], control[0]]).unwrap();
                for s in [0.1 * len, 0.6 * len] {
                    let (a, b) = (at(s), rev.at_arc_length(len - s).unwrap());
                    assert!((a.p - b.p).hypot() < 1e-11 * len);
                    assert!((a.kappa + b.kappa).abs() < 1e-10 * a.kappa.abs());
                    assert!((a.dkappa_ds - b.dkappa_ds).abs() < 1e-9 * a.dkappa_ds.abs());
                }
            }
        }
    }

    #[test]
    fn an_inflection_segment_at_an_arc_length() {
        let tri = [
            Point::new(0.0, 0.0),
            Point::new(10.0, 0.0),
            Point::new(12.0, 3.0),
        ];
        let seg = LacInflectionSegment::new(tri).unwrap();
        let len = seg.arc_length();
        let at = |s: f64| seg.at_arc_length(s).unwrap();
        check_arc_points(&at, len, seg.alpha());
        assert_eq!(at(0.0).kappa, 0.0);
        assert_eq!(at(0.0).p, tri[0]);
        let k1 = seg.end_curvature();
        assert!((at(len).kappa - k1).abs() < 1e-12 * k1.abs());
        assert!((at(len).p - tri[2]).hypot() < 1e-12);
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
            let crate::Polyline {
                points: p,
                kappa: k,
            } = seg.sample(65).unwrap();
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
            let crate::Polyline {
                points: pm,
                kappa: km,
            } = sm.sample(65).unwrap();
            for i in 0..65 {
                assert!((pm[i] - Point::new(p[i].x, -p[i].y)).hypot() < 1e-10 * 16.0);
                assert!((km[i] + k[i]).abs() < 1e-10 * k[i].abs());
            }
            // Reversed triangle: same points in reverse order.
            let r = [pts[2], pts[1], pts[0]];
            let crate::Polyline {
                points: pr,
                kappa: kr,
            } = LacSegment::new(alpha, r).unwrap().sample(65).unwrap();
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
            let a = head.eval_turning(&taus).unwrap().points;
            let b = seg.eval_turning(&taus).unwrap().points;
            for (x, y) in a.iter().zip(&b) {
                assert!((*x - *y).hypot() < 1e-13 * size, "head at {frac}");
            }
            let rest: Vec<f64> = (0..=20)
                .map(|k| (seg.theta_d - tau) * k as f64 / 20.0)
                .collect();
            let c = tail.eval_turning(&rest).unwrap().points;
            let d = seg
                .eval_turning(&rest.iter().map(|r| tau + r).collect::<Vec<_>>())
                .unwrap()
                .points;
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
        let crate::Polyline {
            points: p,
            kappa: k,
        } = seg.sample(33).unwrap();
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
                        Ok(Polyline {
                            points: p,
                            kappa: k,
                        }) => {
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
    /// (α, Λ) of the walk tests: every regime of ρ = U^a, the spiral, and Λ = 0 (circles).
    const WALK_CASES: [(f64, f64); 9] = [
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

    #[test]
    fn monotone_walk_matches_quadrature() {
        // Uneven steps (rotation by each step's own angle, the third-derivative Hermite
        // rule where its bound allows, Gauss or adaptive steps elsewhere), both directions.
        let mut rng = crate::samples::SplitMix64::new(5);
        for &(alpha, lambda) in &WALK_CASES[..6] {
            let c = LacStandard::new(alpha, lambda).unwrap();
            let (lo, hi) = c.domain();
            let (lo, hi) = ((lo + 1e-6).max(-2.5), (hi - 1e-6).min(2.5));
            for n in [9, 40, 201, 1000] {
                let mut th: Vec<f64> = (0..n).map(|_| rng.range(lo, hi)).collect();
                th.sort_by(f64::total_cmp);
                if rng.range(0.0, 1.0) < 0.5 {
                    th.reverse();
                }
                let (p, k) = c.walk_monotone(&th).unwrap();
                let len = (c.arc_length(th[n - 1]).unwrap() - c.arc_length(th[0]).unwrap()).abs();
                for (i, t) in th.iter().enumerate() {
                    let want = c.integral(th[0], *t).unwrap();
                    let err = (p[i] - want).hypot() / len;
                    assert!(err < 2e-14, "alpha {alpha} n {n} theta {t}: {err:.2e}");
                    let kw = c.kappa(*t).unwrap();
                    assert!(
                        (k[i] - kw).abs() <= 1e-14 * kw,
                        "{alpha} {t}: {} vs {kw}",
                        k[i]
                    );
                }
            }
        }
    }

    #[test]
    fn uniform_walk_matches_quadrature() {
        for &(alpha, lambda) in &WALK_CASES {
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
            let at = ext.eval_turning(&[0.03 * td]).unwrap();
            let d = at.tangents[0];
            let n = Vec2::new(-d.y, d.x).normalize();
            let q = at.points[0] + n * 0.2;
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
