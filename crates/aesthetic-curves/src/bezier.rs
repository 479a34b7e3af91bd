//! Bézier curves of degree 1 to 20, polynomial ([`Bezier`]) and rational ([`RationalBezier`]).
//!
//! Naming follows one scheme for every curve of the library: `eval` (point), `eval_d`,
//! `eval_dd`, `eval_ddd` (derivatives in the curve's parameter), `derivs` (all of them at once),
//! `kappa` (signed curvature, positive for counter-clockwise turning) and `dkappa_ds`
//! (derivative of curvature by arc length).
//!
//! Evaluation is by de Casteljau's algorithm throughout (convex combinations, stable on
//! [0, 1]); derivatives come from the last levels of the same triangle, so one pass gives the
//! point and three derivatives. Rational curves are evaluated in homogeneous coordinates and
//! their derivatives follow from the quotient rule.

use crate::bernstein::Bernstein;
use crate::error::{Error, Result};
use kurbo::{Point, Vec2};

/// The largest supported degree.
pub const MAX_BEZIER_DEGREE: usize = 20;

/// Point and first three derivatives at one parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Derivs {
    /// The point.
    pub p: Point,
    /// First derivative.
    pub d1: Vec2,
    /// Second derivative.
    pub d2: Vec2,
    /// Third derivative.
    pub d3: Vec2,
}

impl Derivs {
    /// Signed curvature `det(x', x'') / |x'|^3` (NaN-free: 0/0 gives an infinite or NaN value
    /// only at a cusp, which callers check with [`Derivs::is_regular`]).
    pub fn kappa(&self) -> f64 {
        let s = self.d1.hypot();
        self.d1.cross(self.d2) / (s * s * s)
    }

    /// `dkappa/ds = (det(x',x''') |x'|^2 - 3 det(x',x'') (x'.x'')) / |x'|^6` (docs/math.md §1).
    pub fn dkappa_ds(&self) -> f64 {
        let s2 = self.d1.hypot2();
        (self.d1.cross(self.d3) * s2 - 3.0 * self.d1.cross(self.d2) * self.d1.dot(self.d2))
            / (s2 * s2 * s2)
    }

    /// Whether the first derivative is non-zero (curvature defined).
    pub fn is_regular(&self) -> bool {
        self.d1.hypot2() > 0.0
    }
}

fn check_points(points: &[Point]) -> Result<()> {
    if points.len() < 2 || points.len() > MAX_BEZIER_DEGREE + 1 {
        return Err(Error::invalid(
            "control_points",
            format!(
                "need 2 to {} control points (degree 1 to {}), got {}",
                MAX_BEZIER_DEGREE + 1,
                MAX_BEZIER_DEGREE,
                points.len()
            ),
        ));
    }
    if let Some(i) = points.iter().position(|p| !p.is_finite()) {
        return Err(Error::invalid(
            "control_points",
            format!("control point {i} is not finite"),
        ));
    }
    Ok(())
}

/// de Casteljau on 3-vectors (homogeneous or xy + dummy), keeping the last four levels:
/// returns `[q0..q3]` at level n-3 reduced to the value and derivative combinations.
fn casteljau_derivs<const D: usize>(pts: &[[f64; D]], t: f64) -> [[f64; D]; 4] {
    // Returns [value, d1, d2, d3] (derivatives with the n, n(n-1), ... factors applied).
    let n = pts.len() - 1;
    let mut buf: smallvec::SmallVec<[[f64; D]; 24]> = smallvec::SmallVec::from_slice(pts);
    let s = 1.0 - t;
    // Reduce to level n-3 (4 points) when n >= 3.
    let stop = n.saturating_sub(3);
    for k in 0..stop {
        for i in 0..n - k {
            for c in 0..D {
                buf[i][c] = s * buf[i][c] + t * buf[i + 1][c];
            }
        }
    }
    let m = n - stop; // remaining degree: min(n, 3)
    let q = &buf[..=m];
    let nf = n as f64;
    let mut out = [[0.0; D]; 4];
    match m {
        0 => out[0] = q[0],
        1 => {
            for c in 0..D {
                out[0][c] = s * q[0][c] + t * q[1][c];
                out[1][c] = nf * (q[1][c] - q[0][c]);
            }
        }
        2 => {
            for c in 0..D {
                let r0 = s * q[0][c] + t * q[1][c];
                let r1 = s * q[1][c] + t * q[2][c];
                out[0][c] = s * r0 + t * r1;
                out[1][c] = nf * (r1 - r0);
                out[2][c] = nf * (nf - 1.0) * (q[2][c] - 2.0 * q[1][c] + q[0][c]);
            }
        }
        _ => {
            for c in 0..D {
                let (a, b, cc, d) = (q[0][c], q[1][c], q[2][c], q[3][c]);
                let r0 = s * a + t * b;
                let r1 = s * b + t * cc;
                let r2 = s * cc + t * d;
                let u0 = s * r0 + t * r1;
                let u1 = s * r1 + t * r2;
                out[0][c] = s * u0 + t * u1;
                out[1][c] = nf * (u1 - u0);
                out[2][c] = nf * (nf - 1.0) * (r2 - 2.0 * r1 + r0);
                out[3][c] = nf * (nf - 1.0) * (nf - 2.0) * (d - 3.0 * cc + 3.0 * b - a);
            }
        }
    }
    out
}

/// How far the outline moved from Bézier `a` to Bézier `b` (the same degree): an upper
/// bound of `max_t |b(t) - a(t)|`, so of the distance between the two curves, within
/// 1e-4 of the exact maximum (relative). The difference `b(t) - a(t)` is the Bézier curve
/// of the differences of the control points; the largest of its control points bounds it
/// (the convex hull), and that bound is split at t = 1/2 until it is within 1e-4 of the
/// values at the pieces' ends (a lower bound), at most 12 levels deep. A handle alone moving
/// by `d` moves its cubic by at most 4/9 d (`max 3t(1-t)²`), both handles by `d` each at
/// most 3/4 d.
pub fn outline_move(a: &[Point], b: &[Point]) -> f64 {
    move_bound(a, b, 0.0)
}

/// The most control points [`move_bound`] keeps on the stack (a cubic's four).
const MOVE_POINTS: usize = 4;

/// [`outline_move`], refined only as far as a caller comparing it with `enough` needs
/// (`enough > 0`): a piece whose hull lies within `enough` is not split, and once a point of
/// the difference lies further than `enough` the bound so far is returned (more than
/// `enough`). Squared norms throughout; a cubic or lower on the stack, any other degree
/// through [`split_points`].
fn move_bound(a: &[Point], b: &[Point], enough: f64) -> f64 {
    let n = a.len().min(b.len());
    if n == 0 {
        return 0.0;
    }
    if n > MOVE_POINTS {
        return move_bound_any(a, b, enough);
    }
    let mut d = [[0.0f64; 2]; MOVE_POINTS];
    for (k, (p, q)) in a.iter().zip(b).enumerate() {
        d[k] = [q.x - p.x, q.y - p.y];
    }
    // Squares of coordinates beyond this range overflow or lose their digits: hypot there.
    let size = d[..n]
        .iter()
        .map(|v| v[0].abs().max(v[1].abs()))
        .fold(0.0, f64::max);
    if size == 0.0 {
        return 0.0;
    }
    if !(1e-140..=1e140).contains(&size) {
        return move_bound_any(a, b, enough);
    }
    let norm2 = |v: &[f64; 2]| v[0] * v[0] + v[1] * v[1];
    let ends = |c: &[[f64; 2]; MOVE_POINTS]| norm2(&c[0]).max(norm2(&c[n - 1]));
    let (close, enough2) = ((1.0 + 1e-4f64).powi(2), enough * enough);
    let mut lower = ends(&d);
    let mut upper = 0.0f64;
    let mut stack = Vec::with_capacity(2 * 13);
    stack.push((d, 0u8));
    while let Some((c, depth)) = stack.pop() {
        if enough > 0.0 && lower > enough2 {
            // Further than `enough` for certain: the largest hull still open bounds the rest.
            upper = stack
                .iter()
                .map(|(c, _)| hull2(c, n))
                .fold(upper.max(hull2(&c, n)), f64::max);
            break;
        }
        let hull = hull2(&c, n);
        if hull <= lower * close || hull <= enough2 || depth >= 12 {
            upper = upper.max(hull);
            continue;
        }
        let (l, r) = halves(&c, n);
        lower = lower.max(ends(&l)).max(ends(&r));
        stack.push((l, depth + 1));
        stack.push((r, depth + 1));
    }
    // The float rounding of the splits and of the squares, far below any tolerance that
    // matters.
    upper.max(lower).sqrt() * (1.0 + 1e-12)
}

/// The largest squared norm of the first `n` control points.
fn hull2(c: &[[f64; 2]; MOVE_POINTS], n: usize) -> f64 {
    c[..n]
        .iter()
        .map(|v| v[0] * v[0] + v[1] * v[1])
        .fold(0.0, f64::max)
}

/// The first `n` control points split at t = 1/2 (de Casteljau), on the stack.
fn halves(
    c: &[[f64; 2]; MOVE_POINTS],
    n: usize,
) -> ([[f64; 2]; MOVE_POINTS], [[f64; 2]; MOVE_POINTS]) {
    let mut work = *c;
    let (mut left, mut right) = ([[0.0; 2]; MOVE_POINTS], [[0.0; 2]; MOVE_POINTS]);
    left[0] = work[0];
    right[n - 1] = work[n - 1];
    for k in 1..n {
        for i in 0..n - k {
            let next = work[i + 1];
            work[i] = [0.5 * (work[i][0] + next[0]), 0.5 * (work[i][1] + next[1])];
        }
        left[k] = work[0];
        right[n - 1 - k] = work[n - 1 - k];
    }
    (left, right)
}

/// [`move_bound`] for any degree, on the heap.
fn move_bound_any(a: &[Point], b: &[Point], enough: f64) -> f64 {
    let d: Vec<[f64; 2]> = a
        .iter()
        .zip(b)
        .map(|(p, q)| [q.x - p.x, q.y - p.y])
        .collect();
    let norm = |v: &[f64; 2]| v[0].hypot(v[1]);
    let ends = |c: &[[f64; 2]]| norm(&c[0]).max(norm(&c[c.len() - 1]));
    let mut lower = ends(&d);
    let mut upper = 0.0f64;
    let mut stack = vec![(d, 0u8)];
    while let Some((c, depth)) = stack.pop() {
        let hull = c.iter().map(norm).fold(0.0, f64::max);
        if enough > 0.0 && lower > enough {
            let open = stack.iter().flat_map(|(c, _)| c.iter().map(norm));
            upper = open.fold(upper.max(hull), f64::max);
            break;
        }
        if hull <= lower * (1.0 + 1e-4) || hull <= enough || depth >= 12 {
            upper = upper.max(hull);
            continue;
        }
        let (l, r) = split_points(&c, 0.5);
        lower = lower.max(ends(&l)).max(ends(&r));
        stack.push((l, depth + 1));
        stack.push((r, depth + 1));
    }
    // The float rounding of the splits, far below any tolerance that matters.
    upper.max(lower) * (1.0 + 1e-12)
}

/// How far the outline of cubic `b` lies from that of cubic `a`, as a shape: a sound upper
/// bound of their Fréchet distance (so of the Hausdorff distance, both ways), never more
/// than [`outline_move`]. A handle slid along its tangent moves its cubic's points along the
/// curve as much as off it; at equal parameters that counts in full, as a shape it does not.
///
/// `b` is cut at even parameters `t_i`, `a` at the parameters `s_i` nearest to `b(t_i)`
/// (Newton on `(a(s) - b(t_i))·a'(s)` from `t_i`, then made non-decreasing, `s_0 = 0`,
/// `s_k = 1`), and each pair of pieces compared at equal local parameters with
/// [`outline_move`]; a piece whose bound stands above the distances at the cuts is halved. The pieces' parameters joined end to end are a
/// monotone map of `[0, 1]` onto itself, so the largest piece bound is the length of a
/// matching of the two curves: whatever `s_i` the search finds, the bound holds. Any
/// degree other than 3, or a pair of different degrees: [`outline_move`].
pub fn outline_distance(a: &[Point], b: &[Point]) -> f64 {
    shape_bound(a, b, 0.0)
}

/// Whether cubic `b`'s outline lies within `tolerance` of `a`'s ([`outline_distance`]),
/// asking the cheaper bound at equal parameters first.
pub fn outline_within(a: &[Point], b: &[Point], tolerance: f64) -> bool {
    shape_bound(a, b, tolerance) <= tolerance
}

/// [`outline_distance`], refined only as far as a caller comparing it with `enough` needs
/// ([`matched_distance`]); the bound at equal parameters where that is within `enough`.
fn shape_bound(a: &[Point], b: &[Point], enough: f64) -> f64 {
    let equal_parameters = move_bound(a, b, enough);
    if equal_parameters <= enough || a.len() != 4 || b.len() != 4 {
        return equal_parameters;
    }
    let cubic = |p: &[Point]| kurbo::CubicBez::new(p[0], p[1], p[2], p[3]);
    matched_distance(&cubic(a), &cubic(b), enough).min(equal_parameters)
}

/// How many pieces [`outline_distance`] starts from, and how many halvings it may add.
const MATCHED_PIECES: usize = 8;
const MATCHED_DEPTH: u8 = 5;

/// The parameter of `a` nearest to `q`, from `s` (Newton on `(a(s) - q)·a'(s)`), kept in
/// `range`.
fn nearest_from(a: &kurbo::CubicBez, q: Point, s: f64, range: (f64, f64)) -> f64 {
    use kurbo::{ParamCurve, ParamCurveDeriv};
    let (da, dda) = (a.deriv(), a.deriv().deriv());
    let mut x = s;
    for _ in 0..6 {
        let (d, v, w) = (a.eval(x) - q, da.eval(x).to_vec2(), dda.eval(x).to_vec2());
        let (f, df) = (d.dot(v), v.dot(v) + d.dot(w));
        if df.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            break;
        }
        x = (x - f / df).clamp(range.0, range.1);
    }
    if x.is_finite() {
        x
    } else {
        s.clamp(range.0, range.1)
    }
}

/// The matched pieces' bound ([`outline_distance`]): pieces whose bound stands more than
/// 10⁻³ above the distances at the matched points are halved (a point of `b` and its
/// nearest on `a` in the middle), at most [`MATCHED_DEPTH`] times; a piece within `enough`
/// is not halved, and once a matched point is further than `enough` the bound so far is
/// returned (more than `enough`: all a caller asking whether it is within needs).
fn matched_distance(a: &kurbo::CubicBez, b: &kurbo::CubicBez, enough: f64) -> f64 {
    use kurbo::ParamCurve;
    let k = MATCHED_PIECES;
    let mut s = vec![0.0; k + 1];
    s[k] = 1.0;
    for i in 1..k {
        let t = i as f64 / k as f64;
        s[i] = nearest_from(a, b.eval(t), t, (0.0, 1.0)).max(s[i - 1]);
    }
    let points = |c: kurbo::CubicBez| [c.p0, c.p1, c.p2, c.p3];
    let gap = |t: f64, s: f64| (b.eval(t) - a.eval(s)).hypot();
    let mut lower = (0..=k)
        .map(|i| gap(i as f64 / k as f64, s[i]))
        .fold(0.0, f64::max);
    // Pieces to bound: b's parameter range, a's, and how often halved.
    type Piece = ((f64, f64), (f64, f64), u8);
    let mut stack: Vec<Piece> = (0..k)
        .map(|i| {
            (
                (i as f64 / k as f64, (i + 1) as f64 / k as f64),
                (s[i], s[i + 1]),
                0,
            )
        })
        .collect();
    let mut worst = 0.0f64;
    while let Some((t, s, depth)) = stack.pop() {
        if lower > enough && enough > 0.0 {
            break;
        }
        let piece = move_bound(
            &points(a.subsegment(s.0..s.1)),
            &points(b.subsegment(t.0..t.1)),
            enough,
        );
        if piece <= worst
            || piece <= enough
            || piece <= lower * (1.0 + 1e-3)
            || depth >= MATCHED_DEPTH
        {
            worst = worst.max(piece);
            continue;
        }
        let tm = 0.5 * (t.0 + t.1);
        let sm = nearest_from(a, b.eval(tm), 0.5 * (s.0 + s.1), s);
        lower = lower.max(gap(tm, sm));
        stack.push(((t.0, tm), (s.0, sm), depth + 1));
        stack.push(((tm, t.1), (sm, s.1), depth + 1));
    }
    // The pieces' own rounding: a few units in the last place of the coordinates.
    let size = [a.p0, a.p1, a.p2, a.p3, b.p0, b.p1, b.p2, b.p3]
        .iter()
        .map(|p| p.x.abs().max(p.y.abs()))
        .fold(0.0, f64::max);
    worst.max(lower) + 64.0 * f64::EPSILON * size
}

fn split_points<const D: usize>(pts: &[[f64; D]], t: f64) -> (Vec<[f64; D]>, Vec<[f64; D]>) {
    let n = pts.len();
    let mut work = pts.to_vec();
    let mut left = Vec::with_capacity(n);
    let mut right = vec![[0.0; D]; n];
    let s = 1.0 - t;
    left.push(work[0]);
    right[n - 1] = work[n - 1];
    for k in 1..n {
        for i in 0..n - k {
            let next = work[i + 1];
            for (c, v) in work[i].iter_mut().enumerate() {
                *v = s * *v + t * next[c];
            }
        }
        left.push(work[0]);
        right[n - 1 - k] = work[n - 1 - k];
    }
    (left, right)
}

fn elevate_points<const D: usize>(pts: &[[f64; D]]) -> Vec<[f64; D]> {
    let n = pts.len() - 1;
    let nf = (n + 1) as f64;
    (0..=n + 1)
        .map(|i| {
            let a = i as f64 / nf;
            let mut v = [0.0; D];
            for (c, vc) in v.iter_mut().enumerate() {
                let prev = if i > 0 { pts[i - 1][c] } else { 0.0 };
                let cur = if i <= n { pts[i][c] } else { 0.0 };
                *vc = a * prev + (1.0 - a) * cur;
            }
            v
        })
        .collect()
}

/// A polynomial Bézier curve `x(t) = sum B_i^n(t) b_i`, t in [0, 1], degree 1 to 20.
#[derive(Clone, Debug, PartialEq)]
pub struct Bezier {
    points: Vec<Point>,
}

impl Bezier {
    /// A curve from its control points (2 to 21 finite points).
    pub fn new(points: Vec<Point>) -> Result<Self> {
        check_points(&points)?;
        Ok(Bezier { points })
    }

    /// The degree n (control points minus one).
    pub fn degree(&self) -> usize {
        self.points.len() - 1
    }

    /// The control points.
    pub fn points(&self) -> &[Point] {
        &self.points
    }

    fn xy(&self) -> smallvec::SmallVec<[[f64; 2]; 24]> {
        self.points.iter().map(|p| [p.x, p.y]).collect()
    }

    fn derivs_impl(&self, t: f64) -> Derivs {
        let o = casteljau_derivs(&self.xy(), t);
        Derivs {
            p: Point::new(o[0][0], o[0][1]),
            d1: Vec2::new(o[1][0], o[1][1]),
            d2: Vec2::new(o[2][0], o[2][1]),
            d3: Vec2::new(o[3][0], o[3][1]),
        }
    }

    /// The hodograph control vectors `n (b_{i+1} - b_i)` (a curve of degree n-1).
    pub fn hodograph(&self) -> Vec<Vec2> {
        let n = self.degree() as f64;
        self.points.windows(2).map(|w| n * (w[1] - w[0])).collect()
    }

    /// Split at `t` into the curves on [0, t] and [t, 1].
    pub fn subdivide(&self, t: f64) -> (Bezier, Bezier) {
        let (l, r) = split_points(&self.xy(), t);
        let mk = |v: Vec<[f64; 2]>| Bezier {
            points: v.into_iter().map(|p| Point::new(p[0], p[1])).collect(),
        };
        (mk(l), mk(r))
    }

    /// The same curve with degree n+1 (fails past degree 20).
    pub fn elevate(&self) -> Result<Bezier> {
        let e = elevate_points(&self.xy());
        Bezier::new(e.into_iter().map(|p| Point::new(p[0], p[1])).collect())
    }

    /// The coordinate functions in Bernstein form.
    pub fn components(&self) -> (Bernstein, Bernstein) {
        let x: Vec<f64> = self.points.iter().map(|p| p.x).collect();
        let y: Vec<f64> = self.points.iter().map(|p| p.y).collect();
        (Bernstein::new(&x), Bernstein::new(&y))
    }

    /// Power-basis coefficients: `x(t) = sum a_k t^k`.
    pub fn to_power(&self) -> Vec<Vec2> {
        let (x, y) = self.components();
        x.to_power()
            .into_iter()
            .zip(y.to_power())
            .map(|(a, b)| Vec2::new(a, b))
            .collect()
    }

    /// The curve with power-basis coefficients `a` (`x(t) = sum a_k t^k`).
    pub fn from_power(a: &[Vec2]) -> Result<Bezier> {
        let x = Bernstein::from_power(&a.iter().map(|v| v.x).collect::<Vec<_>>());
        let y = Bernstein::from_power(&a.iter().map(|v| v.y).collect::<Vec<_>>());
        Bezier::new(
            x.coeffs()
                .iter()
                .zip(y.coeffs())
                .map(|(a, b)| Point::new(*a, *b))
                .collect(),
        )
    }

    /// This curve as a rational curve with unit weights.
    pub fn to_rational(&self) -> RationalBezier {
        RationalBezier {
            points: self.points.clone(),
            weights: vec![1.0; self.points.len()],
        }
    }
}

/// A rational Bézier curve `x(t) = sum B_i^n w_i b_i / sum B_i^n w_i`, degree 1 to 20,
/// all weights positive.
#[derive(Clone, Debug, PartialEq)]
pub struct RationalBezier {
    points: Vec<Point>,
    weights: Vec<f64>,
}

impl RationalBezier {
    /// A curve from control points and weights (same count, weights finite and > 0).
    pub fn new(points: Vec<Point>, weights: Vec<f64>) -> Result<Self> {
        check_points(&points)?;
        if weights.len() != points.len() {
            return Err(Error::invalid(
                "weights",
                format!(
                    "need one weight per control point ({}), got {}",
                    points.len(),
                    weights.len()
                ),
            ));
        }
        if let Some(i) = weights.iter().position(|w| !(w.is_finite() && *w > 0.0)) {
            return Err(Error::invalid(
                "weights",
                format!(
                    "weight {i} is {}: weights must be finite and > 0",
                    weights[i]
                ),
            ));
        }
        Ok(RationalBezier { points, weights })
    }

    /// The degree n.
    pub fn degree(&self) -> usize {
        self.points.len() - 1
    }
    /// The control points.
    pub fn points(&self) -> &[Point] {
        &self.points
    }
    /// The weights.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// Homogeneous control points `(w x, w y, w)`.
    pub fn homogeneous(&self) -> smallvec::SmallVec<[[f64; 3]; 24]> {
        self.points
            .iter()
            .zip(&self.weights)
            .map(|(p, w)| [w * p.x, w * p.y, *w])
            .collect()
    }

    fn derivs_impl(&self, t: f64) -> Derivs {
        let h = casteljau_derivs(&self.homogeneous(), t);
        let v = |k: usize| Vec2::new(h[k][0], h[k][1]);
        let (w, w1, w2, w3) = (h[0][2], h[1][2], h[2][2], h[3][2]);
        let x = v(0) / w;
        let x1 = (v(1) - x * w1) / w;
        let x2 = (v(2) - 2.0 * w1 * x1 - w2 * x) / w;
        let x3 = (v(3) - 3.0 * w1 * x2 - 3.0 * w2 * x1 - w3 * x) / w;
        Derivs {
            p: x.to_point(),
            d1: x1,
            d2: x2,
            d3: x3,
        }
    }

    fn eval_impl(&self, t: f64) -> Point {
        let h = casteljau_derivs(&self.homogeneous(), t);
        Point::new(h[0][0] / h[0][2], h[0][1] / h[0][2])
    }

    /// Curvature at t = 0 by the closed form of docs/math.md §1:
    /// `((n-1)/n) (w0 w2 / w1^2) det(b1-b0, b2-b1) / |b1-b0|^3`.
    pub fn kappa_start(&self) -> f64 {
        end_curvature(&self.points, &self.weights)
    }

    /// Curvature at t = 1 (the closed form applied to the reversed curve, sign restored).
    pub fn kappa_end(&self) -> f64 {
        let p: Vec<Point> = self.points.iter().rev().copied().collect();
        let w: Vec<f64> = self.weights.iter().rev().copied().collect();
        -end_curvature(&p, &w)
    }

    fn from_homogeneous(h: Vec<[f64; 3]>) -> RationalBezier {
        RationalBezier {
            points: h
                .iter()
                .map(|v| Point::new(v[0] / v[2], v[1] / v[2]))
                .collect(),
            weights: h.iter().map(|v| v[2]).collect(),
        }
    }

    /// Split at `t` into the curves on [0, t] and [t, 1].
    pub fn subdivide(&self, t: f64) -> (RationalBezier, RationalBezier) {
        let (l, r) = split_points(&self.homogeneous(), t);
        (Self::from_homogeneous(l), Self::from_homogeneous(r))
    }

    /// The same curve with degree n+1 (fails past degree 20).
    pub fn elevate(&self) -> Result<RationalBezier> {
        if self.degree() >= MAX_BEZIER_DEGREE {
            return Err(Error::invalid(
                "degree",
                format!("cannot elevate past degree {MAX_BEZIER_DEGREE}"),
            ));
        }
        Ok(Self::from_homogeneous(elevate_points(&self.homogeneous())))
    }

    /// Reparametrise by the standard Möbius map so that the end weights become 1 (the same
    /// curve; weights `w_i * c^i` scaled). Fails never for positive weights.
    pub fn normalized(&self) -> RationalBezier {
        let n = self.degree();
        let w0 = self.weights[0];
        let wn = self.weights[n];
        let c = (w0 / wn).powf(1.0 / n as f64);
        let weights = self
            .weights
            .iter()
            .enumerate()
            .map(|(i, w)| w * c.powi(i as i32) / w0)
            .collect();
        RationalBezier {
            points: self.points.clone(),
            weights,
        }
    }

    /// Numerator components and the weight function in Bernstein form: `(X, Y, W)`.
    pub fn components(&self) -> (Bernstein, Bernstein, Bernstein) {
        let h = self.homogeneous();
        let col = |c: usize| Bernstein::new(&h.iter().map(|v| v[c]).collect::<Vec<_>>());
        (col(0), col(1), col(2))
    }
}

/// The one evaluation interface of the library's parametric curves (`eval`, `eval_d`,
/// `eval_dd`, `eval_ddd`, `kappa`, `dkappa_ds`), all derived from [`PlanarCurve::derivs`].
pub trait PlanarCurve {
    /// Point and derivatives up to third order at `t`.
    fn derivs(&self, t: f64) -> Derivs;
    /// The point at `t`.
    fn eval(&self, t: f64) -> Point {
        self.derivs(t).p
    }
    /// First derivative at `t`.
    fn eval_d(&self, t: f64) -> Vec2 {
        self.derivs(t).d1
    }
    /// Second derivative at `t`.
    fn eval_dd(&self, t: f64) -> Vec2 {
        self.derivs(t).d2
    }
    /// Third derivative at `t`.
    fn eval_ddd(&self, t: f64) -> Vec2 {
        self.derivs(t).d3
    }
    /// Signed curvature at `t`.
    fn kappa(&self, t: f64) -> f64 {
        self.derivs(t).kappa()
    }
    /// dkappa/ds at `t`.
    fn dkappa_ds(&self, t: f64) -> f64 {
        self.derivs(t).dkappa_ds()
    }
}

impl PlanarCurve for Bezier {
    /// One de Casteljau pass.
    fn derivs(&self, t: f64) -> Derivs {
        self.derivs_impl(t)
    }
}

impl PlanarCurve for RationalBezier {
    /// Homogeneous de Casteljau and the quotient rule.
    fn derivs(&self, t: f64) -> Derivs {
        self.derivs_impl(t)
    }
    fn eval(&self, t: f64) -> Point {
        self.eval_impl(t)
    }
}

fn end_curvature(p: &[Point], w: &[f64]) -> f64 {
    let n = p.len() - 1;
    if n < 2 {
        return 0.0;
    }
    let d0 = p[1] - p[0];
    let d1 = p[2] - p[1];
    let l = d0.hypot();
    ((n as f64 - 1.0) / n as f64) * (w[0] * w[2] / (w[1] * w[1])) * d0.cross(d1) / (l * l * l)
}

// kurbo interop. kurbo's curves are polynomial Béziers of degree 1 to 3 in the same
// coordinates; its `ParamCurveCurvature::curvature` has the opposite sign of this
// library's (here positive where the curve turns counter-clockwise), which the tests check.

impl TryFrom<kurbo::Line> for Bezier {
    type Error = Error;
    /// Fails only for non-finite points.
    fn try_from(l: kurbo::Line) -> Result<Self> {
        Bezier::new(vec![l.p0, l.p1])
    }
}

impl TryFrom<kurbo::QuadBez> for Bezier {
    type Error = Error;
    /// Fails only for non-finite points.
    fn try_from(q: kurbo::QuadBez) -> Result<Self> {
        Bezier::new(vec![q.p0, q.p1, q.p2])
    }
}

impl TryFrom<kurbo::CubicBez> for Bezier {
    type Error = Error;
    /// Fails only for non-finite points.
    fn try_from(c: kurbo::CubicBez) -> Result<Self> {
        Bezier::new(vec![c.p0, c.p1, c.p2, c.p3])
    }
}

impl TryFrom<kurbo::PathSeg> for Bezier {
    type Error = Error;
    /// Fails only for non-finite points.
    fn try_from(s: kurbo::PathSeg) -> Result<Self> {
        match s {
            kurbo::PathSeg::Line(l) => l.try_into(),
            kurbo::PathSeg::Quad(q) => q.try_into(),
            kurbo::PathSeg::Cubic(c) => c.try_into(),
        }
    }
}

impl TryFrom<&Bezier> for kurbo::PathSeg {
    type Error = Error;
    /// Degree 1 to 3 exactly; higher degrees have no kurbo form ([`Error::InvalidInput`]).
    fn try_from(b: &Bezier) -> Result<Self> {
        let p = &b.points;
        match p.len() {
            2 => Ok(kurbo::PathSeg::Line(kurbo::Line::new(p[0], p[1]))),
            3 => Ok(kurbo::PathSeg::Quad(kurbo::QuadBez::new(p[0], p[1], p[2]))),
            4 => Ok(kurbo::PathSeg::Cubic(kurbo::CubicBez::new(
                p[0], p[1], p[2], p[3],
            ))),
            n => Err(Error::invalid(
                "degree",
                format!(
                    "kurbo holds Béziers of degree 1 to 3, this one has degree {}",
                    n - 1
                ),
            )),
        }
    }
}

impl Bezier {
    /// The segments of a kurbo path, in order (a closed subpath's closing line included).
    pub fn from_bezpath(path: &kurbo::BezPath) -> Result<Vec<Bezier>> {
        path.segments().map(Bezier::try_from).collect()
    }

    /// Curves of degree 1 to 3 as one kurbo path: a new subpath starts wherever a curve
    /// does not begin at the previous one's end.
    pub fn to_bezpath(curves: &[Bezier]) -> Result<kurbo::BezPath> {
        let mut path = kurbo::BezPath::new();
        let mut end: Option<Point> = None;
        for c in curves {
            let seg = kurbo::PathSeg::try_from(c)?;
            let start = c.points[0];
            if end != Some(start) {
                path.move_to(start);
            }
            match seg {
                kurbo::PathSeg::Line(l) => path.line_to(l.p1),
                kurbo::PathSeg::Quad(q) => path.quad_to(q.p1, q.p2),
                kurbo::PathSeg::Cubic(k) => path.curve_to(k.p1, k.p2, k.p3),
            }
            end = c.points.last().copied();
        }
        Ok(path)
    }

    /// The image under an affine map (exact: Bézier curves are affinely invariant).
    /// Fails only if the map sends a point to infinity or NaN.
    pub fn transform(&self, map: kurbo::Affine) -> Result<Bezier> {
        Bezier::new(self.points.iter().map(|p| map * *p).collect())
    }

    /// The bounding box of the control points, which contains the curve.
    pub fn control_box(&self) -> kurbo::Rect {
        control_box(&self.points)
    }
}

impl RationalBezier {
    /// The image under an affine map (exact: the weights are unchanged).
    pub fn transform(&self, map: kurbo::Affine) -> Result<RationalBezier> {
        RationalBezier::new(
            self.points.iter().map(|p| map * *p).collect(),
            self.weights.clone(),
        )
    }

    /// The bounding box of the control points, which contains the curve (positive weights).
    pub fn control_box(&self) -> kurbo::Rect {
        control_box(&self.points)
    }

    /// The same curve traversed the other way (points and weights in reverse order; its
    /// signed curvature changes sign).
    pub fn reversed(&self) -> RationalBezier {
        RationalBezier {
            points: self.points.iter().rev().copied().collect(),
            weights: self.weights.iter().rev().copied().collect(),
        }
    }
}

fn control_box(points: &[Point]) -> kurbo::Rect {
    let first = kurbo::Rect::from_points(points[0], points[0]);
    points.iter().fold(first, |r, p| r.union_pt(*p))
}

/// Test oracle: the Hausdorff distance of two cubics, one way: the largest, over 401 points
/// of `b`, of the distance to `a` (its nearest of 1001 samples, then golden sections on the
/// two intervals beside it). Power-form sums, not kurbo's or this module's evaluation.
#[cfg(test)]
pub(crate) fn sampled_hausdorff(a: &[Point], b: &[Point]) -> f64 {
    let at = |p: &[Point], t: f64| {
        let m = 1.0 - t;
        let w = [m * m * m, 3.0 * t * m * m, 3.0 * t * t * m, t * t * t];
        p.iter()
            .zip(w)
            .fold(Vec2::ZERO, |c, (q, w)| c + q.to_vec2() * w)
    };
    let dist = |q: Vec2, s: f64| (at(a, s) - q).hypot();
    let n = 1000;
    (0..=400)
        .map(|k| at(b, k as f64 / 400.0))
        .map(|q| {
            let best = (0..=n)
                .min_by(|&i, &j| {
                    dist(q, i as f64 / n as f64).total_cmp(&dist(q, j as f64 / n as f64))
                })
                .unwrap();
            let (mut lo, mut hi) = (
                (best.max(1) - 1) as f64 / n as f64,
                ((best + 1).min(n)) as f64 / n as f64,
            );
            for _ in 0..60 {
                let (x1, x2) = (lo + (hi - lo) * 0.382, lo + (hi - lo) * 0.618);
                if dist(q, x1) < dist(q, x2) {
                    hi = x2;
                } else {
                    lo = x1;
                }
            }
            dist(q, (lo + hi) / 2.0).min(dist(q, best as f64 / n as f64))
        })
        .fold(0.0, f64::max)
}

/// Test oracle: the Hausdorff distance of two cubics both ways ([`sampled_hausdorff`]).
#[cfg(test)]
pub(crate) fn sampled_shape_distance(a: &[Point], b: &[Point]) -> f64 {
    sampled_hausdorff(a, b).max(sampled_hausdorff(b, a))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pts(v: &[(f64, f64)]) -> Vec<Point> {
        v.iter().map(|&(x, y)| Point::new(x, y)).collect()
    }

    /// outline_distance bounds the Hausdorff distance both ways (the oracle above), is never
    /// more than outline_move, and is close to the truth where a handle slides along its
    /// tangent: at equal parameters that move counts in full.
    #[test]
    fn the_move_at_equal_parameters_is_bounded_and_asked_only_as_far_as_needed() {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut random = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for k in 0..300 {
            // Scales from 1e-160 to 1e160: squares of the widest overflow, of the narrowest
            // vanish; both go through hypot.
            let scale = 10f64.powi((k % 33) * 10 - 160);
            let degree = 1 + k as usize % 3;
            let mut r = || (random() - 0.5) * scale;
            let a: Vec<Point> = (0..=degree).map(|_| Point::new(r(), r())).collect();
            let b: Vec<Point> = a.iter().map(|q| *q + Vec2::new(r(), r()) * 0.1).collect();
            let bound = outline_move(&a, &b);
            assert!(bound.is_finite() && bound > 0.0, "{a:?} {b:?}");
            // Sound: no sampled parameter moves further.
            let at = |p: &[Point], t: f64| {
                let mut w: Vec<Vec2> = p.iter().map(|q| q.to_vec2()).collect();
                for n in (1..w.len()).rev() {
                    for i in 0..n {
                        w[i] = w[i] * (1.0 - t) + w[i + 1] * t;
                    }
                }
                w[0]
            };
            let truth = (0..=400)
                .map(|i| {
                    let t = i as f64 / 400.0;
                    let d = at(&b, t) - at(&a, t);
                    d.x.hypot(d.y)
                })
                .fold(0.0, f64::max);
            assert!(truth <= bound * (1.0 + 1e-9), "{truth} > {bound}");
            assert!(
                bound <= truth * (1.0 + 2e-4) + 1e-300,
                "{bound} far above {truth}"
            );
            // Asked against `enough`, it answers the same question.
            for share in [0.5, 0.99, 1.01, 2.0] {
                let enough = share * bound;
                assert_eq!(
                    move_bound(&a, &b, enough) <= enough,
                    share >= 1.0,
                    "{a:?} {b:?} {share}"
                );
            }
        }
    }

    #[test]
    fn outline_distance_bounds_the_shape_distance() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut random = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut slides, mut ratio_sum, mut worst_ratio) = (0, 0.0, 0.0f64);
        for k in 0..120 {
            let scale = 10f64.powi(k % 8 - 2);
            let origin = if k % 3 == 0 { 1e4 * scale } else { 0.0 };
            let mut r = || (random() - 0.5) * scale;
            let a: Vec<Point> = (0..4).map(|_| Point::new(origin + r(), r())).collect();
            let slide = k % 2 == 0;
            let b: Vec<Point> = if slide {
                let (f0, f1) = (0.6 + 0.8 * random(), 0.6 + 0.8 * random());
                vec![
                    a[0],
                    a[0] + (a[1] - a[0]) * f0,
                    a[3] + (a[2] - a[3]) * f1,
                    a[3],
                ]
            } else {
                let mut r = || (random() - 0.5) * scale * 0.1;
                a.iter().map(|q| *q + Vec2::new(r(), r())).collect()
            };
            let bound = outline_distance(&a, &b);
            let truth = sampled_shape_distance(&a, &b);
            let tiny = 1e-12 * (scale + origin);
            assert!(
                truth <= bound + tiny,
                "{a:?} {b:?}: bound {bound} < {truth}"
            );
            assert!(bound <= outline_move(&a, &b), "{a:?} {b:?}");
            // The question "within T?" refines only what it needs, and agrees.
            for share in [0.5, 0.9, 0.99, 1.01, 1.1, 2.0] {
                let within = outline_within(&a, &b, share * bound);
                assert!(
                    !within || truth <= share * bound + tiny,
                    "{a:?} {b:?} {share}"
                );
                assert!(share < 1.01 || within, "{a:?} {b:?} {share}");
            }
            if slide && truth > 1e-3 * scale {
                slides += 1;
                let ratio = bound / truth;
                ratio_sum += ratio;
                worst_ratio = worst_ratio.max(ratio);
            }
        }
        eprintln!(
            "{slides} slides: bound / truth mean {:.3}, worst {worst_ratio:.3}",
            ratio_sum / slides as f64
        );
        assert!(
            slides >= 30 && ratio_sum / (slides as f64) < 1.2,
            "{slides} {ratio_sum}"
        );
        // A straight cubic's handles slid along it (inside the chord): the same segment.
        let a = pts(&[(0.0, 0.0), (10.0, 0.0), (20.0, 0.0), (30.0, 0.0)]);
        let b = pts(&[(0.0, 0.0), (4.0, 0.0), (27.0, 0.0), (30.0, 0.0)]);
        let (d, m) = (outline_distance(&a, &b), outline_move(&a, &b));
        assert!(d < 0.05 && m > 2.0, "{d} {m}");
    }

    #[test]
    fn cubic_derivatives_match_power_form() {
        let b = Bezier::new(pts(&[(0.0, 0.0), (1.0, 2.0), (3.0, 3.0), (4.0, 0.0)])).unwrap();
        let a = b.to_power();
        for i in 0..=8 {
            let t = i as f64 / 8.0;
            let d = b.derivs(t);
            let p = a[0] + a[1] * t + a[2] * t * t + a[3] * t * t * t;
            let d1 = a[1] + 2.0 * a[2] * t + 3.0 * a[3] * t * t;
            let d2 = 2.0 * a[2] + 6.0 * a[3] * t;
            let d3 = 6.0 * a[3];
            assert!((d.p.to_vec2() - p).hypot() < 1e-13);
            assert!((d.d1 - d1).hypot() < 1e-12);
            assert!((d.d2 - d2).hypot() < 1e-12);
            assert!((d.d3 - d3).hypot() < 1e-12);
        }
    }

    #[test]
    fn rational_quadratic_circle_has_constant_curvature() {
        // Quarter circle of radius 2: weights 1, cos(45deg), 1.
        let r = RationalBezier::new(
            pts(&[(2.0, 0.0), (2.0, 2.0), (0.0, 2.0)]),
            vec![1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0],
        )
        .unwrap();
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            assert!((r.eval(t).to_vec2().hypot() - 2.0).abs() < 1e-14);
            assert!((r.kappa(t) - 0.5).abs() < 1e-13);
            assert!(r.dkappa_ds(t).abs() < 1e-12);
        }
        assert!((r.kappa_start() - 0.5).abs() < 1e-14);
        assert!((r.kappa_end() - 0.5).abs() < 1e-14);
        // Backwards: the same points in reverse, the curvature of the other sign.
        let b = r.reversed();
        assert_eq!(b.eval(0.25), r.eval(0.75));
        assert_eq!(b.kappa_start(), -r.kappa_end());
    }

    #[test]
    fn subdivision_elevation_and_normalisation_keep_the_curve() {
        let r = RationalBezier::new(
            pts(&[(0.0, 0.0), (1.0, 2.0), (3.0, 3.0), (4.0, 0.0)]),
            vec![1.0, 2.0, 0.5, 3.0],
        )
        .unwrap();
        let (l, rr) = r.subdivide(0.4);
        let e = r.elevate().unwrap();
        let nrm = r.normalized();
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            assert!((l.eval(t) - r.eval(0.4 * t)).hypot() < 1e-13);
            assert!((rr.eval(t) - r.eval(0.4 + 0.6 * t)).hypot() < 1e-13);
            assert!((e.eval(t) - r.eval(t)).hypot() < 1e-13);
            assert!((e.kappa(t) - r.kappa(t)).abs() < 1e-10 * r.kappa(t).abs().max(1.0));
        }
        // The normalised curve is a reparametrisation: same points at other parameters,
        // same curvature at the ends.
        assert!((nrm.weights()[0] - 1.0).abs() < 1e-15 && (nrm.weights()[3] - 1.0).abs() < 1e-14);
        assert!((nrm.kappa_start() - r.kappa_start()).abs() < 1e-12);
        assert!((r.kappa_start() - r.kappa(0.0)).abs() < 1e-12 * r.kappa(0.0).abs());
        assert!((r.kappa_end() - r.kappa(1.0)).abs() < 1e-12 * r.kappa(1.0).abs());
    }

    #[test]
    fn rejects_bad_input() {
        assert!(Bezier::new(pts(&[(0.0, 0.0)])).is_err());
        assert!(Bezier::new(pts(&[(0.0, f64::NAN), (1.0, 0.0)])).is_err());
        assert!(Bezier::new(vec![Point::ZERO; 22]).is_err());
        assert!(RationalBezier::new(pts(&[(0.0, 0.0), (1.0, 0.0)]), vec![1.0, 0.0]).is_err());
        assert!(RationalBezier::new(pts(&[(0.0, 0.0), (1.0, 0.0)]), vec![1.0]).is_err());
    }

    #[test]
    fn kurbo_round_trip_and_curvature_sign() {
        use kurbo::{ParamCurve, ParamCurveCurvature};
        let c = kurbo::CubicBez::new((0.0, 0.0), (1.0, 2.0), (3.0, 2.5), (4.0, 0.5));
        let b = Bezier::try_from(c).unwrap();
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            let d = b.derivs(t);
            assert!((d.p - c.eval(t)).hypot() < 1e-14);
            // kurbo's curvature has the opposite sign.
            let k = c.curvature(t);
            assert!(
                (d.kappa() + k).abs() <= 1e-12 * k.abs().max(1e-300),
                "{t}: {} vs {k}",
                d.kappa()
            );
        }
        let q = kurbo::QuadBez::new((0.0, 0.0), (1.0, 1.0), (2.0, 0.0));
        let bq = Bezier::try_from(q).unwrap();
        assert!(bq.derivs(0.5).kappa() < 0.0 && q.curvature(0.5) > 0.0);
        // A path with a closing line, and back.
        let mut path = kurbo::BezPath::new();
        path.move_to((0.0, 0.0));
        path.curve_to((1.0, 2.0), (3.0, 2.5), (4.0, 0.5));
        path.quad_to((2.0, -1.0), (0.5, -0.5));
        path.close_path();
        let segs = Bezier::from_bezpath(&path).unwrap();
        assert_eq!(
            segs.iter().map(|s| s.degree()).collect::<Vec<_>>(),
            vec![3, 2, 1]
        );
        let back = Bezier::to_bezpath(&segs).unwrap();
        assert_eq!(back.segments().count(), 3);
        assert!(back.segments().zip(path.segments()).all(|(a, b)| a == b));
        // Degree 4 has no kurbo form; NaN points are refused.
        let quartic = b.elevate().unwrap();
        assert!(Bezier::to_bezpath(&[quartic]).is_err());
        let bad = kurbo::Line::new((0.0, 0.0), (f64::NAN, 1.0));
        assert!(Bezier::try_from(bad).is_err());
        // Affine maps act on the control points; a rotation keeps the curvature, a
        // reflection flips its sign, a uniform scale by s divides it by s.
        let rot = kurbo::Affine::rotate(0.7);
        let flip = kurbo::Affine::FLIP_Y;
        let grow = kurbo::Affine::scale(2.0);
        let k0 = b.derivs(0.3).kappa();
        assert!((b.transform(rot).unwrap().derivs(0.3).kappa() - k0).abs() < 1e-12);
        assert!((b.transform(flip).unwrap().derivs(0.3).kappa() + k0).abs() < 1e-12);
        assert!((b.transform(grow).unwrap().derivs(0.3).kappa() - 0.5 * k0).abs() < 1e-12);
        let r = b.to_rational().transform(rot).unwrap();
        assert!((r.derivs(0.3).kappa() - k0).abs() < 1e-12);
        // The control box holds the curve.
        let bx = b.control_box();
        assert_eq!((bx.x0, bx.y0, bx.x1, bx.y1), (0.0, 0.0, 4.0, 2.5));
        // (kurbo's `Rect::contains` is half-open: the closed box is checked here.)
        assert!((0..=20).all(|i| {
            let p = b.derivs(i as f64 / 20.0).p;
            p.x >= bx.x0 && p.x <= bx.x1 && p.y >= bx.y0 && p.y <= bx.y1
        }));
    }
}
