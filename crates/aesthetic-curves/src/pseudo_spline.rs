//! The pseudo-elastic spline of S2 (math.md §5), exact mode: interpolation through points by
//! cubic Hermite segments whose tangent lengths minimise the pseudo-energy J = E L².
//!
//! One segment on the unit chord (P0 = (0,0), P1 = (1,0)) with end tangent angles θ0, θ1 and
//! lengths r0, r1: `P(t) = b(t) P1 + c(t) r0 e^{iθ0} + d(t) r1 e^{iθ1}`. The strain energy
//! `E = ∫ κ² ds` has no minimum over (r0, r1) in general (it falls as r grows); `J = E L²`
//! always has one. Here:
//! - [`segment_energy`]: E, L and the signed area S under the segment (adaptive
//!   Gauss–Kronrod, relative accuracy about 1e-12; S is a polynomial integral, exact);
//! - [`optimal_segment`]: J(θ0, θ1) = min over r0, r1 > 0, by Nelder–Mead in (ln r0, ln r1)
//!   from several starts, polished to 1e-10 in J;
//! - [`single_angle`]: J(θ0) = min over θ1 and its minimiser θ1(θ0) (a scan of the circle
//!   and golden-section refinement; J(θ0, θ1) = J(θ1, θ0) by the half-turn symmetry of the
//!   unit chord);
//! - [`pseudo_elastic`]: tangents by S2 eq. 11 (each interior tangent minimises the
//!   pseudo-energy of the elastic rod through its two neighbours) and eq. 12 (end tangents),
//!   open or closed, with length (eq. 15-16), area (eq. 18-20) and energy Σ l_i J_i.
//!
//! This is the exact mode: every J is a minimisation, so a curve through n points costs
//! about n x 10⁵ segment evaluations. The table mode of S2 (tabulated J, r0, r1, L, S) is not
//! built yet.

use crate::error::{Error, Result};
use crate::quadrature::{integrate, QuadOptions};
use kurbo::{Point, Vec2};
use std::f64::consts::PI;

/// Energy, length and area of one unit-chord Hermite segment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SegmentEnergy {
    /// `E = ∫ κ² ds`.
    pub energy: f64,
    /// Arc length L.
    pub length: f64,
    /// Signed area between the segment and the chord (x axis): `∫ y dx`, below negative.
    pub area: f64,
}

fn hermite(theta0: f64, theta1: f64, r0: f64, r1: f64) -> (Vec2, Vec2) {
    (Vec2::from_angle(theta0) * r0, Vec2::from_angle(theta1) * r1)
}

/// P'(t) and P''(t) of the unit-chord segment.
fn derivs(t: f64, d0: Vec2, d1: Vec2) -> (Vec2, Vec2) {
    // b' = 6t - 6t², c' = 3t² - 4t + 1, d' = 3t² - 2t; b'' = 6 - 12t, c'' = 6t - 4, d'' = 6t - 2.
    let p1 = Vec2::new(1.0, 0.0);
    let d = p1 * (6.0 * t - 6.0 * t * t)
        + d0 * (3.0 * t * t - 4.0 * t + 1.0)
        + d1 * (3.0 * t * t - 2.0 * t);
    let dd = p1 * (6.0 - 12.0 * t) + d0 * (6.0 * t - 4.0) + d1 * (6.0 * t - 2.0);
    (d, dd)
}

/// E, L and S of the unit-chord segment (θ0, θ1, r0, r1). E is infinite when the speed
/// vanishes (a cusp).
pub fn segment_energy(theta0: f64, theta1: f64, r0: f64, r1: f64) -> SegmentEnergy {
    let (d0, d1) = hermite(theta0, theta1, r0, r1);
    let f = |t: f64| {
        let (d, dd) = derivs(t, d0, d1);
        let s2 = d.hypot2();
        let c = d.cross(dd);
        // κ² ds/dt = c² / |P'|^5
        Vec2::new(c * c / (s2 * s2 * s2.sqrt()), s2.sqrt())
    };
    let opts = QuadOptions {
        accuracy: 1e-13,
        max_panels: 400,
    };
    let (energy, length) = match integrate(f, 0.0, 1.0, opts) {
        Ok(v) if v.is_finite() => (v.x, v.y),
        _ => (f64::INFINITY, f64::INFINITY),
    };
    // Area ∫ y x' dt: degree 5 polynomial, exact with 3 Gauss points.
    let (xs, ws) = crate::quadrature::gauss_legendre_01(4);
    let area = xs
        .iter()
        .zip(&ws)
        .map(|(t, w)| {
            let t = *t;
            let p = Vec2::new(1.0, 0.0) * (-2.0 * t * t * t + 3.0 * t * t)
                + d0 * (t * t * t - 2.0 * t * t + t)
                + d1 * (t * t * t - t * t);
            let (d, _) = derivs(t, d0, d1);
            w * p.y * d.x
        })
        .sum();
    SegmentEnergy {
        energy,
        length,
        area,
    }
}

/// The segment minimising J for given end angles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SegmentOptimum {
    /// Pseudo-energy J = E L² at the optimum.
    pub j: f64,
    /// Optimal tangent lengths.
    pub r0: f64,
    /// Optimal tangent lengths.
    pub r1: f64,
    /// E, L, S of the optimal segment.
    pub shape: SegmentEnergy,
}

/// J on a fixed 32-point Gauss rule (the search; the optimum is re-measured adaptively).
fn j_fast(theta0: f64, theta1: f64, u: f64, v: f64, nodes: &(Vec<f64>, Vec<f64>)) -> f64 {
    let (d0, d1) = hermite(theta0, theta1, u.exp(), v.exp());
    let (mut e, mut l) = (0.0, 0.0);
    for (t, w) in nodes.0.iter().zip(&nodes.1) {
        let (d, dd) = derivs(*t, d0, d1);
        let s2 = d.hypot2();
        let c = d.cross(dd);
        e += w * c * c / (s2 * s2 * s2.sqrt());
        l += w * s2.sqrt();
    }
    let j = e * l * l;
    if j.is_finite() {
        j
    } else {
        f64::INFINITY
    }
}

fn j_of(theta0: f64, theta1: f64, u: f64, v: f64) -> f64 {
    let e = segment_energy(theta0, theta1, u.exp(), v.exp());
    let j = e.energy * e.length * e.length;
    if j.is_finite() {
        j
    } else {
        f64::INFINITY
    }
}

/// Nelder–Mead in two variables; returns (point, value).
fn nelder_mead(
    f: &dyn Fn(f64, f64) -> f64,
    start: (f64, f64),
    step: f64,
    tol: f64,
) -> ((f64, f64), f64) {
    let mut s = [
        (start, f(start.0, start.1)),
        ((start.0 + step, start.1), f(start.0 + step, start.1)),
        ((start.0, start.1 + step), f(start.0, start.1 + step)),
    ];
    for _ in 0..400 {
        s.sort_by(|a, b| a.1.total_cmp(&b.1));
        let spread = (s[0].0 .0 - s[2].0 .0)
            .abs()
            .max((s[0].0 .1 - s[2].0 .1).abs());
        if spread < tol && (s[2].1 - s[0].1).abs() <= 1e-14 * s[0].1.abs() + 1e-300 {
            break;
        }
        if spread < 1e-13 {
            break;
        }
        let c = ((s[0].0 .0 + s[1].0 .0) / 2.0, (s[0].0 .1 + s[1].0 .1) / 2.0);
        let w = s[2].0;
        let pt = |a: f64| (c.0 + a * (w.0 - c.0), c.1 + a * (w.1 - c.1));
        let r = pt(-1.0);
        let fr = f(r.0, r.1);
        if fr < s[0].1 {
            let e = pt(-2.0);
            let fe = f(e.0, e.1);
            s[2] = if fe < fr { (e, fe) } else { (r, fr) };
        } else if fr < s[1].1 {
            s[2] = (r, fr);
        } else {
            let k = if fr < s[2].1 { pt(-0.5) } else { pt(0.5) };
            let fk = f(k.0, k.1);
            if fk < s[2].1.min(fr) {
                s[2] = (k, fk);
            } else {
                // Shrink towards the best.
                let b = s[0].0;
                for item in s.iter_mut().skip(1) {
                    let q = ((item.0 .0 + b.0) / 2.0, (item.0 .1 + b.1) / 2.0);
                    *item = (q, f(q.0, q.1));
                }
            }
        }
    }
    s.sort_by(|a, b| a.1.total_cmp(&b.1));
    s[0]
}

/// J(θ0, θ1) and the optimal (r0, r1) (angles in radians, any real value). The straight
/// segment (θ0 = θ1 = 0) has J = 0 for every (r0, r1); it is returned with r0 = r1 = 1.
pub fn optimal_segment(theta0: f64, theta1: f64) -> Result<SegmentOptimum> {
    if !(theta0.is_finite() && theta1.is_finite()) {
        return Err(Error::invalid("theta", "angles must be finite"));
    }
    let (a, b) = (wrap(theta0), wrap(theta1));
    if a == 0.0 && b == 0.0 {
        let shape = segment_energy(0.0, 0.0, 1.0, 1.0);
        return Ok(SegmentOptimum {
            j: 0.0,
            r0: 1.0,
            r1: 1.0,
            shape,
        });
    }
    let nodes = crate::quadrature::gauss_legendre_01(32);
    let fast = |u: f64, v: f64| j_fast(a, b, u, v, &nodes);
    let mut best: Option<((f64, f64), f64)> = None;
    for start in [(0.0, 0.0), (-1.2, -1.2), (0.8, 0.8)] {
        let r = nelder_mead(&fast, start, 0.4, 1e-6);
        if best.is_none_or(|b| r.1 < b.1) {
            best = Some(r);
        }
    }
    // Polish on the adaptive quadrature (accurate also near tight turns).
    let f = |u: f64, v: f64| j_of(a, b, u, v);
    let ((u, v), j) = nelder_mead(&f, best.expect("starts").0, 0.02, 1e-8);
    if !j.is_finite() {
        return Err(Error::NoConvergence(format!(
            "no finite pseudo-energy found for end angles ({theta0}, {theta1})"
        )));
    }
    let (r0, r1) = (u.exp(), v.exp());
    Ok(SegmentOptimum {
        j,
        r0,
        r1,
        shape: segment_energy(a, b, r0, r1),
    })
}

/// Angle in (-π, π].
pub fn wrap(a: f64) -> f64 {
    let mut x = a.rem_euclid(2.0 * PI);
    if x > PI {
        x -= 2.0 * PI;
    }
    x
}

/// Brent's minimisation of `f` on [lo, hi] to `tol` (golden sections with parabolic
/// steps; Brent 1973, "Algorithms for minimization without derivatives", ch. 5).
fn golden(f: &mut dyn FnMut(f64) -> f64, lo: f64, hi: f64, tol: f64) -> (f64, f64) {
    const CG: f64 = 0.381_966_011_250_105_1;
    let (mut a, mut b) = (lo, hi);
    let mut x = a + CG * (b - a);
    let (mut w, mut v) = (x, x);
    let mut fx = f(x);
    let (mut fw, mut fv) = (fx, fx);
    let (mut d, mut e): (f64, f64) = (0.0, 0.0);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        let tol1 = tol * 0.5 + 1e-12 * x.abs();
        let tol2 = 2.0 * tol1;
        if (x - m).abs() <= tol2 - 0.5 * (b - a) {
            break;
        }
        let mut golden_step = true;
        if e.abs() > tol1 {
            let r = (x - w) * (fx - fv);
            let q0 = (x - v) * (fx - fw);
            let mut p = (x - v) * q0 - (x - w) * r;
            let mut q = 2.0 * (q0 - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            if p.abs() < (0.5 * q * e).abs() && p > q * (a - x) && p < q * (b - x) {
                e = d;
                d = p / q;
                let u = x + d;
                if u - a < tol2 || b - u < tol2 {
                    d = if x < m { tol1 } else { -tol1 };
                }
                golden_step = false;
            }
        }
        if golden_step {
            e = if x < m { b - x } else { a - x };
            d = CG * e;
        }
        let u = if d.abs() >= tol1 {
            x + d
        } else if d > 0.0 {
            x + tol1
        } else {
            x - tol1
        };
        let fu = f(u);
        if fu <= fx {
            if u < x {
                b = x;
            } else {
                a = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    (x, fx)
}

/// Global minimum of a function of an angle on the circle: a scan of `n` points, then
/// golden-section refinement around the best to `tol`.
fn circle_min(f: &mut dyn FnMut(f64) -> f64, n: usize, tol: f64) -> (f64, f64) {
    let h = 2.0 * PI / n as f64;
    let mut best = (0.0, f64::INFINITY);
    for k in 0..n {
        let x = -PI + h * (k as f64 + 0.5);
        let v = f(x);
        if v < best.1 {
            best = (x, v);
        }
    }
    let (x, v) = golden(f, best.0 - h, best.0 + h, tol);
    if v < best.1 {
        (wrap(x), v)
    } else {
        (wrap(best.0), best.1)
    }
}

/// J(θ0) = min over θ1 of J(θ0, θ1), and the minimiser θ1(θ0).
pub fn single_angle(theta0: f64) -> Result<(f64, f64)> {
    if !theta0.is_finite() {
        return Err(Error::invalid("theta", "must be finite"));
    }
    let mut f = |t1: f64| {
        optimal_segment(theta0, t1)
            .map(|o| o.j)
            .unwrap_or(f64::INFINITY)
    };
    let (t1, j) = circle_min(&mut f, 16, 1e-7);
    Ok((j, t1))
}

/// One span of the spline in input coordinates: x(t) = h00 p0 + h10 d0 + h01 p1 + h11 d1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HermiteSpan {
    /// Start point.
    pub p0: Point,
    /// End point.
    pub p1: Point,
    /// Start derivative.
    pub d0: Vec2,
    /// End derivative.
    pub d1: Vec2,
}

impl HermiteSpan {
    /// The point at t in [0, 1].
    pub fn eval(&self, t: f64) -> Point {
        let (t2, t3) = (t * t, t * t * t);
        let h00 = 2.0 * t3 - 3.0 * t2 + 1.0;
        let h10 = t3 - 2.0 * t2 + t;
        let h01 = -2.0 * t3 + 3.0 * t2;
        let h11 = t3 - t2;
        (self.p0.to_vec2() * h00 + self.d0 * h10 + self.p1.to_vec2() * h01 + self.d1 * h11)
            .to_point()
    }
}

impl HermiteSpan {
    /// The span as a cubic Bézier curve.
    pub fn to_bezier(&self) -> Result<crate::Bezier> {
        crate::Bezier::new(vec![
            self.p0,
            self.p0 + self.d0 / 3.0,
            self.p1 - self.d1 / 3.0,
            self.p1,
        ])
    }
}

/// Fairness numbers of a piecewise curve (S2's comparison).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fairness {
    /// Bending energy ∫ κ² ds.
    pub bending_energy: f64,
    /// ∫ (dκ/ds)² ds.
    pub kappa_variation: f64,
    /// Curvature extrema: inside the spans by the exact test, plus joints where dκ/ds
    /// changes sign from one span to the next.
    pub curvature_extrema: usize,
    /// Largest |κ|.
    pub max_abs_kappa: f64,
}

/// [`Fairness`] of consecutive cubic spans.
pub fn fairness(spans: &[HermiteSpan]) -> Result<Fairness> {
    use crate::monotone::CurvatureMonotone;
    use crate::PlanarCurve;
    let mut out = Fairness {
        bending_energy: 0.0,
        kappa_variation: 0.0,
        curvature_extrema: 0,
        max_abs_kappa: 0.0,
    };
    let opts = QuadOptions {
        accuracy: 1e-12,
        max_panels: 2000,
    };
    let mut prev_end_slope: Option<f64> = None;
    for sp in spans {
        let b = sp.to_bezier()?;
        let v = integrate(
            |t| {
                let d = b.derivs(t);
                let speed = d.d1.hypot();
                let k = d.kappa();
                let dk = d.dkappa_ds();
                Vec2::new(k * k * speed, dk * dk * speed)
            },
            0.0,
            1.0,
            opts,
        )?;
        out.bending_energy += v.x;
        out.kappa_variation += v.y;
        let r = b.curvature_monotone()?;
        out.curvature_extrema += r.extrema.len();
        for i in 0..=64 {
            out.max_abs_kappa = out.max_abs_kappa.max(b.kappa(i as f64 / 64.0).abs());
        }
        for t in &r.extrema {
            out.max_abs_kappa = out.max_abs_kappa.max(b.kappa(*t).abs());
        }
        let start_slope = b.dkappa_ds(0.0);
        if let Some(e) = prev_end_slope {
            if e * start_slope < 0.0 {
                out.curvature_extrema += 1;
            }
        }
        prev_end_slope = Some(b.dkappa_ds(1.0));
    }
    Ok(out)
}

/// A pseudo-elastic spline through points.
#[derive(Clone, Debug, PartialEq)]
pub struct PseudoSpline {
    /// Absolute tangent direction at each input point (radians).
    pub tangent_angles: Vec<f64>,
    /// One span per pair of consecutive points (and the closing pair when closed).
    pub segments: Vec<HermiteSpan>,
    /// Total length (eq. 15/16, from the optimal segments' own lengths).
    pub length: f64,
    /// Closed: enclosed area; open: area between the curve and the chord of its ends (eq. 18-20).
    pub area: f64,
    /// Σ l_i J_i.
    pub energy: f64,
}

/// The pseudo-elastic spline through `points` (exact mode). Errors: fewer than 2 points
/// (3 when closed) `invalid_input`; coincident consecutive points `degenerate`.
pub fn pseudo_elastic(points: &[Point], closed: bool) -> Result<PseudoSpline> {
    let need = if closed { 3 } else { 2 };
    if points.len() < need {
        return Err(Error::invalid(
            "points",
            format!("need at least {need} points, got {}", points.len()),
        ));
    }
    if let Some(i) = points.iter().position(|p| !p.is_finite()) {
        return Err(Error::invalid(format!("points[{i}]"), "must be finite"));
    }
    let n = points.len();
    let spans = if closed { n } else { n - 1 };
    let next = |i: usize| (i + 1) % n;
    let mut l = Vec::with_capacity(spans);
    let mut phi = Vec::with_capacity(spans);
    for i in 0..spans {
        let d = points[next(i)] - points[i];
        let len = d.hypot();
        if len == 0.0 {
            return Err(Error::Degenerate(format!(
                "points {i} and {} coincide",
                next(i)
            )));
        }
        l.push(len);
        phi.push(d.y.atan2(d.x));
    }
    // α_i relative to chord i; interior (or every point when closed) by eq. 11.
    let mut dir = vec![0.0; n];
    let interior: Vec<usize> = if closed {
        (0..n).collect()
    } else {
        (1..n - 1).collect()
    };
    for &i in &interior {
        let prev = if i == 0 { spans - 1 } else { i - 1 };
        let turn = wrap(phi[i] - phi[prev]);
        let (lp, li) = (l[prev], l[i]);
        let mut w = |a: f64| -> f64 {
            let j1 = single_angle(a + turn).map(|v| v.0).unwrap_or(f64::INFINITY);
            let j2 = single_angle(a).map(|v| v.0).unwrap_or(f64::INFINITY);
            lp * j1 + li * j2
        };
        // The tangent lies near the bisector of the two chords: scan a window around it.
        let guess = -0.5 * turn;
        let (a, _) = golden(&mut w, guess - 0.6, guess + 0.6, 1e-7);
        dir[i] = phi[i] + a;
    }
    if !closed {
        if n == 2 {
            dir[0] = phi[0];
            dir[1] = phi[0];
        } else {
            // Eq. 12: the rods through the first and last three points.
            let a1 = wrap(dir[1] - phi[1]);
            let (_, t0) = single_angle(a1 + wrap(phi[1] - phi[0]))?;
            dir[0] = phi[0] + t0;
            let an = wrap(dir[n - 2] - phi[n - 2]);
            let (_, t1) = single_angle(an)?;
            dir[n - 1] = phi[n - 2] + t1;
        }
    }
    let mut segments = Vec::with_capacity(spans);
    let (mut length, mut energy, mut s_sum) = (0.0, 0.0, 0.0);
    for i in 0..spans {
        let t0 = wrap(dir[i] - phi[i]);
        let t1 = wrap(dir[next(i)] - phi[i]);
        let o = optimal_segment(t0, t1)?;
        let rot = Vec2::from_angle(phi[i]) * l[i];
        let rotate = |v: Vec2| Vec2::new(v.x * rot.x - v.y * rot.y, v.x * rot.y + v.y * rot.x);
        segments.push(HermiteSpan {
            p0: points[i],
            p1: points[next(i)],
            d0: rotate(Vec2::from_angle(t0) * o.r0),
            d1: rotate(Vec2::from_angle(t1) * o.r1),
        });
        length += l[i] * o.shape.length;
        energy += l[i] * o.j;
        s_sum += l[i] * l[i] * o.shape.area;
    }
    // Shoelace area of the polygon (closed back to the first point), eq. 20.
    let mut s0 = 0.0;
    for i in 0..n {
        let (a, b) = (points[i], points[(i + 1) % n]);
        s0 += 0.5 * (a.x * b.y - a.y * b.x);
    }
    Ok(PseudoSpline {
        tangent_angles: dir.iter().map(|d| wrap(*d)).collect(),
        segments,
        length,
        area: (s0 - s_sum).abs(),
        energy,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn straight_and_symmetric_segments() {
        let o = optimal_segment(0.0, 0.0).unwrap();
        assert_eq!(o.j, 0.0);
        assert!((o.shape.length - 1.0).abs() < 1e-12);
        // Half-turn symmetry: J(a, b) = J(b, a).
        let (a, b) = (0.4, -0.9);
        let x = optimal_segment(a, b).unwrap();
        let y = optimal_segment(b, a).unwrap();
        assert!((x.j - y.j).abs() < 1e-9 * x.j);
        assert!((x.r0 - y.r1).abs() < 1e-5 && (x.r1 - y.r0).abs() < 1e-5);
        // Mirror symmetry: J(a, b) = J(-a, -b).
        let z = optimal_segment(-a, -b).unwrap();
        assert!((x.j - z.j).abs() < 1e-9 * x.j);
    }

    #[test]
    fn energy_of_a_circular_arc_like_segment() {
        // θ0 = -θ1 = 30°: close to a 60° arc of radius 1 on the unit chord, E ≈ θ/R, L ≈ Rθ.
        let t = 30f64.to_radians();
        let radius = 1.0 / (2.0 * t.sin());
        let r = 4.0 * (t / 2.0).tan() * radius; // Hermite tangent of the Bézier arc
        let e = segment_energy(t, -t, r, r);
        let arc = 2.0 * t * radius;
        assert!((e.length - arc).abs() < 1e-3, "{e:?}");
        assert!((e.energy - arc / (radius * radius)).abs() < 2e-2, "{e:?}");
        // Circular segment area R²/2 (2t - sin 2t), above the chord: positive.
        let seg_area = 0.5 * radius * radius * (2.0 * t - (2.0 * t).sin());
        assert!((e.area - seg_area).abs() < 1e-3, "{e:?} vs {seg_area}");
    }

    #[test]
    fn bad_input_is_reported() {
        let p = |x: f64, y: f64| Point::new(x, y);
        assert!(matches!(
            pseudo_elastic(&[p(0.0, 0.0)], false),
            Err(Error::InvalidInput { .. })
        ));
        assert!(matches!(
            pseudo_elastic(&[p(0.0, 0.0), p(1.0, 0.0), p(1.0, 0.0)], false),
            Err(Error::Degenerate(_))
        ));
        assert!(matches!(
            pseudo_elastic(&[p(0.0, 0.0), p(1.0, 0.0)], true),
            Err(Error::InvalidInput { .. })
        ));
    }

    #[test]
    fn collinear_points_give_a_line() {
        let pts: Vec<Point> = (0..4)
            .map(|i| Point::new(i as f64, 2.0 * i as f64))
            .collect();
        let s = pseudo_elastic(&pts, false).unwrap();
        let dir = 2f64.atan2(1.0);
        for a in &s.tangent_angles {
            assert!((a - dir).abs() < 1e-6, "{a}");
        }
        assert!(s.energy < 1e-10);
        assert!((s.length - 3.0 * 5f64.sqrt()).abs() < 1e-9);
    }
}
