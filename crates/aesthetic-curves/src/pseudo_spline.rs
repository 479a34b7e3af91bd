//! The pseudo-elastic spline of S2 (docs/math.md §5): interpolation through points by cubic
//! Hermite segments whose tangent lengths minimise the pseudo-energy J = E L².
//!
//! Each span is the optimal segment of [`crate::pseudo_segment`] for its end tangent
//! angles, scaled onto its chord. Here:
//! - [`pseudo_elastic`]: tangents by S2 eq. 11 (each interior tangent minimises the
//!   pseudo-energy of the elastic rod through its two neighbours) and eq. 12 (end tangents),
//!   open or closed, with length (eq. 15-16), area (eq. 18-20) and energy Σ l_i J_i, in
//!   [`Mode::Table`] (the shipped tables of [`crate::pseudo_table`]; a 1000-point curve in
//!   about 0.5 ms) or [`Mode::Exact`] (a minimisation per span, about a second per point);
//! - [`comparison_curve`]: the cubic splines and Hermite curves S2 compares with, and
//!   [`fairness`] numbers for any of them.

use crate::error::{Error, Result};
use crate::pseudo_segment::{optimal_segment, single_angle, wrap};
use crate::quadrature::{integrate, QuadOptions};
use kurbo::{Point, Vec2};

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

/// How the segment values J, r0, r1, L and S are obtained.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Mode {
    /// Interpolated from the shipped tables ([`crate::pseudo_table`]): microseconds per point.
    #[default]
    Table,
    /// Direct minimisation at every segment: about a second per point.
    Exact,
}

impl Mode {
    /// The protocol's name: `table` or `exact`.
    pub fn as_str(self) -> &'static str {
        match self {
            Mode::Table => "table",
            Mode::Exact => "exact",
        }
    }

    /// The mode of a protocol name (`table` or `exact`).
    pub fn from_name(name: &str) -> Result<Self> {
        [Mode::Table, Mode::Exact]
            .into_iter()
            .find(|m| m.as_str() == name)
            .ok_or_else(|| crate::Error::invalid("mode", "must be table or exact"))
    }
}

/// Segment values used by the spline: (J, r0, r1, L, S).
fn segment_values(mode: Mode, t0: f64, t1: f64) -> Result<(f64, f64, f64, f64, f64)> {
    match mode {
        Mode::Exact => {
            let o = optimal_segment(t0, t1)?;
            Ok((o.j, o.r0, o.r1, o.shape.length, o.shape.area))
        }
        Mode::Table => {
            let o = crate::pseudo_table::tables().segment(t0, t1)?;
            Ok((o.j, o.r0, o.r1, o.length, o.area))
        }
    }
}

/// J(θ) and θ1(θ) in the given mode.
fn single_values(mode: Mode, theta: f64) -> Result<(f64, f64)> {
    match mode {
        Mode::Exact => single_angle(theta),
        Mode::Table => crate::pseudo_table::tables().single(theta),
    }
}

/// Eq. 11 on the tables: Newton's method on the derivative of
/// `lp J(a + turn) + li J(a)` from the small-angle minimiser, kept within 0.6 of the bisector
/// `guess`; None when it does not settle (the caller then searches that window).
fn table_tangent(lp: f64, li: f64, turn: f64, guess: f64) -> Option<f64> {
    let t = crate::pseudo_table::tables();
    // Start from the minimiser of the small-angle energy lp (a + turn)² + li a² (J ~ θ²);
    // `guess` (the bisector) stays the centre of the window.
    let a0 = (-turn * lp / (lp + li)).clamp(guess - 0.5, guess + 0.5);
    let update = |a: f64| {
        let (d1p, d2p) = t.single_slope_curvature(a + turn);
        let (d1, d2) = t.single_slope_curvature(a);
        let (g, h) = (lp * d1p + li * d1, lp * d2p + li * d2);
        (h > 0.0 && h.is_finite()).then(|| -g / h)
    };
    // Newton converges quadratically here: a step below 1e-6 leaves an error of order its
    // square (1e-12 rad), far below the accuracy of the tables themselves. The window:
    // within 0.6 of `guess`.
    let opts = crate::solve::roots::Newton1d {
        max_iterations: 30,
        max_step: 0.1,
        abs_tol: 1e-6,
        rel_tol: 0.0,
        bounds: (guess - 0.6, guess + 0.6),
        clamp: false,
    };
    let root = crate::solve::roots::newton_1d(update, a0, &opts);
    root.converged().then_some(root.x)
}

/// The pseudo-elastic spline through `points`. Errors: fewer than 2 points (3 when closed)
/// or non-finite coordinates `invalid_input`; coincident consecutive points `degenerate`.
pub fn pseudo_elastic(points: &[Point], closed: bool, mode: Mode) -> Result<PseudoSpline> {
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
    // Work on the points moved to the first one and scaled to unit size (similarity
    // invariance; no overflow or underflow for huge or tiny coordinates), then scale back.
    let origin = points[0];
    let scale = points
        .iter()
        .map(|p| (*p - origin).hypot())
        .fold(0.0, f64::max);
    if !scale.is_finite() {
        return Err(Error::invalid(
            "points",
            "coordinates too large: their differences overflow",
        ));
    }
    let unit: Vec<Point> = if scale > 0.0 {
        points
            .iter()
            .map(|p| ((*p - origin) / scale).to_point())
            .collect()
    } else {
        points.to_vec()
    };
    let mut s = pseudo_elastic_unit(&unit, closed, mode)?;
    let scale = if scale > 0.0 { scale } else { 1.0 };
    let n = points.len();
    for (i, sp) in s.segments.iter_mut().enumerate() {
        sp.p0 = points[i];
        sp.p1 = points[(i + 1) % n];
        sp.d0 *= scale;
        sp.d1 *= scale;
    }
    s.length *= scale;
    s.energy *= scale;
    s.area *= scale * scale;
    let finite = s.length.is_finite()
        && s.area.is_finite()
        && s.energy.is_finite()
        && s.segments
            .iter()
            .all(|g| g.d0.is_finite() && g.d1.is_finite());
    if !finite {
        return Err(Error::invalid(
            "points",
            "the curve's length, area or tangents overflow f64",
        ));
    }
    Ok(s)
}

/// [`pseudo_elastic`] on points already checked and scaled to unit size.
fn pseudo_elastic_unit(points: &[Point], closed: bool, mode: Mode) -> Result<PseudoSpline> {
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
        crate::deadline::check()?;
        let prev = if i == 0 { spans - 1 } else { i - 1 };
        let turn = wrap(phi[i] - phi[prev]);
        let (lp, li) = (l[prev], l[i]);
        let single = |a: f64| single_values(mode, a).map(|v| v.0).unwrap_or(f64::INFINITY);
        let mut w = |a: f64| -> f64 { lp * single(a + turn) + li * single(a) };
        // The tangent lies near the bisector of the two chords: search a window around it.
        let guess = -0.5 * turn;
        let newton = match mode {
            Mode::Table => table_tangent(lp, li, turn, guess),
            Mode::Exact => None,
        };
        let a = match newton {
            Some(a) => a,
            None => {
                let tol = if mode == Mode::Exact { 1e-7 } else { 1e-9 };
                crate::solve::line_search::brent(&mut w, guess - 0.6, guess + 0.6, tol).0
            }
        };
        dir[i] = phi[i] + a;
    }
    if !closed {
        if n == 2 {
            dir[0] = phi[0];
            dir[1] = phi[0];
        } else {
            // Eq. 12: the rods through the first and last three points.
            let a1 = wrap(dir[1] - phi[1]);
            let (_, t0) = single_values(mode, a1 + wrap(phi[1] - phi[0]))?;
            dir[0] = phi[0] + t0;
            let an = wrap(dir[n - 2] - phi[n - 2]);
            let (_, t1) = single_values(mode, an)?;
            dir[n - 1] = phi[n - 2] + t1;
        }
    }
    let mut segments = Vec::with_capacity(spans);
    let (mut length, mut energy, mut s_sum) = (0.0, 0.0, 0.0);
    // The span's end tangents are r l e^{i t} rotated by the chord's angle φ, t = dir - φ:
    // r l e^{i dir}, one unit vector per point.
    let unit: Vec<Vec2> = dir.iter().map(|d| Vec2::from_angle(*d)).collect();
    for i in 0..spans {
        let t0 = wrap(dir[i] - phi[i]);
        let t1 = wrap(dir[next(i)] - phi[i]);
        let (j, r0, r1, len, area) = match mode {
            Mode::Table => {
                // (cos t, sin t) from the unit vectors: the tangent's relative to the chord's.
                let c = (points[next(i)] - points[i]) / l[i];
                let rel = |u: Vec2| Vec2::new(u.dot(c), c.cross(u));
                let q = crate::pseudo_table::q2_from_unit(rel(unit[i]), rel(unit[next(i)]));
                let o = crate::pseudo_table::tables().segment_with_q(t0, t1, q)?;
                (o.j, o.r0, o.r1, o.length, o.area)
            }
            Mode::Exact => segment_values(mode, t0, t1)?,
        };
        segments.push(HermiteSpan {
            p0: points[i],
            p1: points[next(i)],
            d0: unit[i] * (r0 * l[i]),
            d1: unit[next(i)] * (r1 * l[i]),
        });
        length += l[i] * len;
        energy += l[i] * j;
        s_sum += l[i] * l[i] * area;
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

/// The interpolants S2 compares the pseudo-elastic spline with (§4, Fig. 8-17).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Comparison {
    /// Cubic spline A: interpolating cubic spline with uniform parameters t_i = i (natural
    /// end conditions: zero second derivative at both ends).
    CubicSplineUniform,
    /// Cubic spline B: parameters spaced by chord length (natural ends).
    CubicSplineChord,
    /// Hermite A: tangent at P_i parallel to P_{i+1} - P_{i-1}, along the end chords at the
    /// ends; tangent length the span's chord length.
    HermiteChord,
    /// Hermite B: tangent of the circle through P_{i-1}, P_i, P_{i+1} (through the first or
    /// last three points at the ends); tangent length the span's chord length.
    HermiteCircle,
}

impl Comparison {
    /// All four, in S2's order.
    pub const ALL: [Comparison; 4] = [
        Comparison::CubicSplineUniform,
        Comparison::CubicSplineChord,
        Comparison::HermiteChord,
        Comparison::HermiteCircle,
    ];

    /// S2's name of the curve.
    pub fn name(self) -> &'static str {
        match self {
            Comparison::CubicSplineUniform => "cubic spline A",
            Comparison::CubicSplineChord => "cubic spline B",
            Comparison::HermiteChord => "Hermite A",
            Comparison::HermiteCircle => "Hermite B",
        }
    }
}

/// The open curve of a [`Comparison`] method through `points`, as one Hermite span per pair
/// of consecutive points. Errors: fewer than 3 points or non-finite coordinates
/// `invalid_input`; coincident consecutive points `degenerate`.
pub fn comparison_curve(points: &[Point], method: Comparison) -> Result<Vec<HermiteSpan>> {
    if points.len() < 3 {
        return Err(Error::invalid(
            "points",
            format!("need at least 3 points, got {}", points.len()),
        ));
    }
    if let Some(i) = points.iter().position(|p| !p.is_finite()) {
        return Err(Error::invalid(format!("points[{i}]"), "must be finite"));
    }
    let n = points.len();
    let chords: Vec<f64> = points.windows(2).map(|w| (w[1] - w[0]).hypot()).collect();
    if let Some(i) = chords.iter().position(|c| *c == 0.0) {
        return Err(Error::Degenerate(format!(
            "points {i} and {} coincide",
            i + 1
        )));
    }
    let spans = |dirs: &[Vec2], scale: &dyn Fn(usize) -> (f64, f64)| -> Vec<HermiteSpan> {
        (0..n - 1)
            .map(|i| {
                let (s0, s1) = scale(i);
                HermiteSpan {
                    p0: points[i],
                    p1: points[i + 1],
                    d0: dirs[i] * s0,
                    d1: dirs[i + 1] * s1,
                }
            })
            .collect()
    };
    match method {
        Comparison::CubicSplineUniform | Comparison::CubicSplineChord => {
            let h: Vec<f64> = if method == Comparison::CubicSplineUniform {
                vec![1.0; n - 1]
            } else {
                chords.clone()
            };
            let m = natural_spline_slopes(points, &h);
            // dP/dt at the knots; a span's Hermite derivatives in its own [0, 1] are h_i m.
            let out = spans(&m, &|i| (h[i], h[i]));
            if out.iter().any(|g| !(g.d0.is_finite() && g.d1.is_finite())) {
                return Err(Error::invalid(
                    "points",
                    "the spline's tangents overflow f64",
                ));
            }
            Ok(out)
        }
        Comparison::HermiteChord | Comparison::HermiteCircle => {
            let unit = |v: Vec2| v / v.hypot();
            let mut dirs = Vec::with_capacity(n);
            for i in 0..n {
                let d = if method == Comparison::HermiteChord {
                    if i == 0 {
                        points[1] - points[0]
                    } else if i == n - 1 {
                        points[n - 1] - points[n - 2]
                    } else {
                        points[i + 1] - points[i - 1]
                    }
                } else if i == 0 {
                    // Circle through P0, P1, P2, tangent at P0 (travelling towards P1).
                    circle_tangent(points[0], points[2], points[1])
                } else if i == n - 1 {
                    circle_tangent(points[n - 1], points[n - 2], points[n - 3])
                } else {
                    circle_tangent(points[i], points[i - 1], points[i + 1])
                };
                if d.hypot() == 0.0 || !d.is_finite() {
                    return Err(Error::Degenerate(format!(
                        "no tangent direction at point {i}"
                    )));
                }
                dirs.push(unit(d));
            }
            Ok(spans(&dirs, &|i| (chords[i], chords[i])))
        }
    }
}

/// Tangent at `x` of the circle through `prev`, `x`, `next`, pointing from `prev`'s side to
/// `next`'s: `(next - x) |prev - x|² - (prev - x) |next - x|²` (along the chord when the three
/// points are collinear).
fn circle_tangent(x: Point, prev: Point, next: Point) -> Vec2 {
    let (a, c) = (prev - x, next - x);
    c * a.hypot2() - a * c.hypot2()
}

/// First derivatives at the knots of the natural interpolating cubic spline with parameter
/// steps `h` (tridiagonal system, Thomas algorithm; diagonally dominant).
fn natural_spline_slopes(p: &[Point], h: &[f64]) -> Vec<Vec2> {
    let n = p.len();
    let d = |i: usize| (p[i + 1] - p[i]) / h[i];
    let (mut a, mut b, mut c, mut r) = (
        vec![0.0; n],
        vec![0.0; n],
        vec![0.0; n],
        vec![Vec2::ZERO; n],
    );
    b[0] = 2.0;
    c[0] = 1.0;
    r[0] = d(0) * 3.0;
    for i in 1..n - 1 {
        a[i] = h[i];
        b[i] = 2.0 * (h[i - 1] + h[i]);
        c[i] = h[i - 1];
        r[i] = (d(i - 1) * h[i] + d(i) * h[i - 1]) * 3.0;
    }
    a[n - 1] = 1.0;
    b[n - 1] = 2.0;
    r[n - 1] = d(n - 2) * 3.0;
    for i in 1..n {
        let w = a[i] / b[i - 1];
        b[i] -= w * c[i - 1];
        let prev = r[i - 1];
        r[i] -= prev * w;
    }
    let mut m = vec![Vec2::ZERO; n];
    m[n - 1] = r[n - 1] / b[n - 1];
    for i in (0..n - 1).rev() {
        m[i] = (r[i] - m[i + 1] * c[i]) / b[i];
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn bad_input_is_reported() {
        let p = |x: f64, y: f64| Point::new(x, y);
        assert!(matches!(
            pseudo_elastic(&[p(0.0, 0.0)], false, Mode::Exact),
            Err(Error::InvalidInput { .. })
        ));
        assert!(matches!(
            pseudo_elastic(&[p(0.0, 0.0), p(1.0, 0.0), p(1.0, 0.0)], false, Mode::Exact),
            Err(Error::Degenerate(_))
        ));
        assert!(matches!(
            pseudo_elastic(&[p(0.0, 0.0), p(1.0, 0.0)], true, Mode::Exact),
            Err(Error::InvalidInput { .. })
        ));
    }

    #[test]
    fn comparison_curves_interpolate_and_match_their_definitions() {
        let pts: Vec<Point> = [(0.0, 0.0), (1.0, 0.3), (2.5, 0.2), (3.0, -1.0), (4.2, -1.1)]
            .iter()
            .map(|p| Point::new(p.0, p.1))
            .collect();
        for m in Comparison::ALL {
            let c = comparison_curve(&pts, m).unwrap();
            assert_eq!(c.len(), 4);
            for (i, sp) in c.iter().enumerate() {
                assert!((sp.eval(0.0) - pts[i]).hypot() < 1e-14, "{m:?}");
                assert!((sp.eval(1.0) - pts[i + 1]).hypot() < 1e-14, "{m:?}");
                if i > 0 {
                    let prev = &c[i - 1];
                    assert!(
                        prev.d1.cross(sp.d0).abs() < 1e-12 * prev.d1.hypot2(),
                        "{m:?}"
                    );
                }
            }
        }
        // Natural splines: C2 in their parameter (second derivatives agree at the knots, in
        // t units: x'' / h²) and zero second derivative at the ends.
        for m in [Comparison::CubicSplineUniform, Comparison::CubicSplineChord] {
            let c = comparison_curve(&pts, m).unwrap();
            let h: Vec<f64> = if m == Comparison::CubicSplineUniform {
                vec![1.0; 4]
            } else {
                pts.windows(2).map(|w| (w[1] - w[0]).hypot()).collect()
            };
            let dd = |sp: &HermiteSpan, t: f64| {
                // Hermite second derivative: h00'' = 12t - 6, h10'' = 6t - 4, h01'' = 6 - 12t, h11'' = 6t - 2.
                sp.p0.to_vec2() * (12.0 * t - 6.0)
                    + sp.d0 * (6.0 * t - 4.0)
                    + sp.p1.to_vec2() * (6.0 - 12.0 * t)
                    + sp.d1 * (6.0 * t - 2.0)
            };
            assert!(dd(&c[0], 0.0).hypot() < 1e-12, "{m:?}");
            assert!(dd(&c[3], 1.0).hypot() < 1e-12, "{m:?}");
            for i in 1..4 {
                let l = dd(&c[i - 1], 1.0) / (h[i - 1] * h[i - 1]);
                let r = dd(&c[i], 0.0) / (h[i] * h[i]);
                assert!((l - r).hypot() < 1e-12, "{m:?} knot {i}: {l:?} {r:?}");
            }
        }
        // Hermite B on points of a circle: every tangent is the circle's.
        let circle: Vec<Point> = (0..5)
            .map(|k| Vec2::from_angle(0.4 * k as f64).to_point())
            .collect();
        let c = comparison_curve(&circle, Comparison::HermiteCircle).unwrap();
        for (k, sp) in c.iter().enumerate() {
            let want = Vec2::from_angle(0.4 * k as f64 + PI / 2.0);
            assert!(sp.d0.cross(want).abs() < 1e-12 * sp.d0.hypot() && sp.d0.dot(want) > 0.0);
        }
        let last = Vec2::from_angle(0.4 * 4.0 + PI / 2.0);
        assert!(c[3].d1.cross(last).abs() < 1e-12 * c[3].d1.hypot() && c[3].d1.dot(last) > 0.0);
        assert!(matches!(
            comparison_curve(&pts[..2], Comparison::HermiteChord),
            Err(Error::InvalidInput { .. })
        ));
    }

    #[test]
    fn collinear_points_give_a_line() {
        let pts: Vec<Point> = (0..4)
            .map(|i| Point::new(i as f64, 2.0 * i as f64))
            .collect();
        let s = pseudo_elastic(&pts, false, Mode::Exact).unwrap();
        let dir = 2f64.atan2(1.0);
        for a in &s.tangent_angles {
            assert!((a - dir).abs() < 1e-6, "{a}");
        }
        assert!(s.energy < 1e-10);
        assert!((s.length - 3.0 * 5f64.sqrt()).abs() < 1e-9);
    }
}
