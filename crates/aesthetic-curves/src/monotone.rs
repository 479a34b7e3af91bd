//! Curvature monotonicity of Bézier curves (math.md §2; seeds S0 §4, S1 §3).
//!
//! ## The exact test
//!
//! The sign of dkappa/ds is the sign of a polynomial `K(t)`, written here in Bernstein form
//! from the control points directly (no power basis, no sampling):
//!
//! - **polynomial curve, degree n**: with `d_i = b_{i+1} - b_i`, `A = sum B_i^{n-2} d_i`,
//!   `B = sum B_i^{n-2} d_{i+1}` one has `det(x', x'') = G = n^2 (n-1) det(A, B)` (degree
//!   2n-4) and `K = G' |x'|^2 - 3 G (x'.x'')`, exactly the numerator of math.md §1 since
//!   `G' = det(x', x''')`. Its degree is **4n-7**: the top coefficient of the papers' nominal
//!   degree-(4n-6) form cancels and never gets computed.
//! - **rational curve, degree n**: with homogeneous points `H_i = w_i (b_i, 1)`,
//!   `D1 = W P' - P W' = n sum_{i,j} B_i^{n-1} B_j^{n-1} w_i w_{j+1} (b_{j+1} - b_i)`
//!   (degree 2n-2) and `det(H, H', H'') = G = n^2 (n-1) det(HAA, HAB, HBB)` (degree 3n-6, the
//!   three de Casteljau sub-polygons), curvature is `kappa = W^3 G / |D1|^3` and
//!   `dkappa/ds = W^4 K / |D1|^6` with `K = (3 W' G + W G') |D1|^2 - 3 W G (D1.D1')`.
//!   Nominal degree 8n-11; its top coefficient cancels analytically and is removed by exact
//!   degree reduction, giving degree **8n-12** (12 for a rational cubic, as in S0 and in Saito
//!   & Yoshida 2023).
//!
//! Every coefficient carries a rounding bound, obtained by running the same arithmetic on
//! absolute values; coefficients within it count as zero (so a circular arc, where K is
//! identically zero, is monotone, and a straight line too). The sign analysis is
//! [`crate::bernstein::analyze_signs`]: convex hull, one-variation certificates, subdivision.
//!
//! A curve whose first derivative vanishes somewhere on [0, 1] (coincident control points, a
//! cusp, a backtracking straight line) has no curvature there: that is an
//! [`Error::Degenerate`], not a verdict. The threshold is `|x'(t)| <= 1e-8 max_i |n d_i|`.
//!
//! ## The sampling test (S1 §3.1)
//!
//! Curvature at `N + 1` uniform parameters; monotone when consecutive differences keep one
//! sign (differences within `1e-12` of the curvature's size count as zero). It can miss
//! extrema between samples, and costs grow with N: it exists to reproduce S1's comparison.

use crate::bernstein::{analyze_signs, binomial, subdivide_coeffs, Bernstein, SignOptions};
use crate::bezier::{Bezier, Derivs, RationalBezier};
use crate::error::{Error, Result};
use kurbo::{Point, Vec2};
use smallvec::SmallVec;

/// Which way curvature runs along a monotone curve.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Trend {
    /// Signed curvature increases with t (dkappa/ds >= 0).
    Increasing,
    /// Signed curvature decreases with t (dkappa/ds <= 0).
    Decreasing,
    /// dkappa/ds is zero within rounding: a straight line or a circular arc.
    Constant,
}

impl Trend {
    /// `"increasing"`, `"decreasing"` or `"constant"`.
    pub fn as_str(&self) -> &'static str {
        match self {
            Trend::Increasing => "increasing",
            Trend::Decreasing => "decreasing",
            Trend::Constant => "constant",
        }
    }
}

/// Verdict of the exact test.
#[derive(Clone, Debug, PartialEq)]
pub struct MonotoneReport {
    /// dkappa/ds keeps one sign on [0, 1] (zero allowed).
    pub monotone: bool,
    /// The direction, when monotone.
    pub trend: Option<Trend>,
    /// Parameters in (0, 1) where dkappa/ds changes sign (curvature extrema), sorted.
    pub extrema: Vec<f64>,
    /// Degree of the Bernstein polynomial examined.
    pub test_degree: usize,
}

/// Verdict of the sampling test.
#[derive(Clone, Debug, PartialEq)]
pub struct SampledReport {
    /// Consecutive curvature differences keep one sign.
    pub monotone: bool,
    /// The direction, when monotone.
    pub trend: Option<Trend>,
    /// Number of divisions N (N + 1 curvature samples).
    pub samples: usize,
}

/// The numerator K(t) of dkappa/ds in Bernstein form, with per-coefficient rounding bounds,
/// and |x'|^2 (polynomial) or |D1|^2 (rational), whose zeros are the degenerate points.
#[derive(Clone, Debug)]
pub struct CurvatureVariation {
    /// K(t): same sign as dkappa/ds wherever the curve is regular.
    pub k: Bernstein,
    /// Rounding bound of each coefficient of `k`.
    pub k_noise: Vec<f64>,
    /// Squared speed, up to a positive factor: |x'|^2 or |W P' - P W'|^2.
    pub speed2: Bernstein,
    /// Rounding bound of each coefficient of `speed2`.
    pub speed2_noise: Vec<f64>,
    /// Largest squared length of the hodograph's control vectors (the speed's scale).
    pub speed2_scale: f64,
    /// Control vectors of the (scaled) hodograph: the tangent is a positive combination.
    pub hodograph: SmallVec<[Vec2; 24]>,
}

const EPS: f64 = f64::EPSILON;

fn noise_of(abs: &Bernstein) -> Vec<f64> {
    noise_slice(abs.coeffs())
}

/// Rounding bound from magnitude bounds: a few ulps per operation level of the products.
fn noise_slice(abs: &[f64]) -> Vec<f64> {
    let k = 16.0 + 4.0 * (abs.len() - 1) as f64;
    abs.iter().map(|v| k * EPS * v).collect()
}

/// `m (|c_{i+1}| + |c_i|)`: the magnitude bound of a derivative's coefficients.
fn deriv_abs(p: &Bernstein) -> Bernstein {
    let m = p.degree();
    if m == 0 {
        return Bernstein::constant(0.0);
    }
    let mf = m as f64;
    Bernstein::new(
        &p.coeffs()
            .windows(2)
            .map(|w| mf * (w[0].abs() + w[1].abs()))
            .collect::<Vec<_>>(),
    )
}

/// K(t) for a polynomial Bézier curve (degree 4n-7 for n >= 3; see the module docs).
///
/// Hot path: stack buffers only, products accumulated unnormalised and divided by the
/// binomial of the result once (the same Bernstein product formula as
/// [`Bernstein::mul`]), value and magnitude bound computed side by side.
pub fn curvature_variation(curve: &Bezier) -> CurvatureVariation {
    const N1: usize = crate::bezier::MAX_BEZIER_DEGREE;
    const NK: usize = 4 * N1;
    let b = curve.points();
    let n = b.len() - 1;
    let nf = n as f64;
    // Hodograph n d_i (values and magnitude bounds).
    let mut hx = [0.0; N1];
    let mut hy = [0.0; N1];
    let mut hxa = [0.0; N1];
    let mut hya = [0.0; N1];
    let mut hodograph: SmallVec<[Vec2; 24]> = SmallVec::new();
    let mut speed2_scale = 0.0f64;
    for i in 0..n {
        let (p, q) = (b[i + 1], b[i]);
        hx[i] = nf * (p.x - q.x);
        hy[i] = nf * (p.y - q.y);
        hxa[i] = nf * (p.x.abs() + q.x.abs());
        hya[i] = nf * (p.y.abs() + q.y.abs());
        hodograph.push(Vec2::new(hx[i], hy[i]));
        speed2_scale = speed2_scale.max(hx[i] * hx[i] + hy[i] * hy[i]);
    }
    // |x'|^2, degree 2n-2.
    let ds = 2 * (n - 1);
    let mut s = [0.0; NK];
    let mut sa = [0.0; NK];
    acc_mul(&hx[..n], &hx[..n], 1.0, &mut s);
    acc_mul(&hy[..n], &hy[..n], 1.0, &mut s);
    acc_mul(&hxa[..n], &hxa[..n], 1.0, &mut sa);
    acc_mul(&hya[..n], &hya[..n], 1.0, &mut sa);
    normalize(&mut s[..=ds]);
    normalize(&mut sa[..=ds]);
    let speed2 = Bernstein::new(&s[..=ds]);
    let speed2_noise = noise_slice(&sa[..=ds]);
    if n < 2 {
        return CurvatureVariation {
            k: Bernstein::constant(0.0),
            k_noise: vec![0.0],
            speed2,
            speed2_noise,
            speed2_scale,
            hodograph,
        };
    }
    // det(x', x'') = n^2 (n-1) det(A, B) with A = sum B^{n-2} d_i, B = sum B^{n-2} d_{i+1};
    // in terms of h = n d: (n-1) det(sum B^{n-2} h_i, sum B^{n-2} h_{i+1}). Degree 2n-4.
    let m = n - 2;
    let dg = 2 * m;
    let c2 = nf - 1.0;
    let mut g = [0.0; NK];
    let mut ga = [0.0; NK];
    acc_mul(&hx[..=m], &hy[1..=m + 1], c2, &mut g);
    acc_mul(&hy[..=m], &hx[1..=m + 1], -c2, &mut g);
    acc_mul(&hxa[..=m], &hya[1..=m + 1], c2, &mut ga);
    acc_mul(&hya[..=m], &hxa[1..=m + 1], c2, &mut ga);
    normalize(&mut g[..=dg]);
    normalize(&mut ga[..=dg]);
    // x'' = (n-1) (h_{i+1} - h_i), degree n-2.
    let mut x2 = [0.0; N1];
    let mut y2 = [0.0; N1];
    let mut x2a = [0.0; N1];
    let mut y2a = [0.0; N1];
    for i in 0..=m {
        x2[i] = (nf - 1.0) * (hx[i + 1] - hx[i]);
        y2[i] = (nf - 1.0) * (hy[i + 1] - hy[i]);
        x2a[i] = (nf - 1.0) * (hxa[i + 1] + hxa[i]);
        y2a[i] = (nf - 1.0) * (hya[i + 1] + hya[i]);
    }
    // Q = x'.x'', degree 2n-3.
    let dq = 2 * n - 3;
    let mut qv = [0.0; NK];
    let mut qa = [0.0; NK];
    acc_mul(&hx[..n], &x2[..=m], 1.0, &mut qv);
    acc_mul(&hy[..n], &y2[..=m], 1.0, &mut qv);
    acc_mul(&hxa[..n], &x2a[..=m], 1.0, &mut qa);
    acc_mul(&hya[..n], &y2a[..=m], 1.0, &mut qa);
    normalize(&mut qv[..=dq]);
    normalize(&mut qa[..=dq]);
    let mut k = [0.0; NK];
    let mut ka = [0.0; NK];
    let dk = if n == 2 {
        acc_mul(&g[..1], &qv[..=dq], -3.0, &mut k);
        acc_mul(&ga[..1], &qa[..=dq], 3.0, &mut ka);
        dq
    } else {
        // G' (degree 2m-1) and its bound.
        let mut gd = [0.0; NK];
        let mut gda = [0.0; NK];
        let mf = dg as f64;
        for i in 0..dg {
            gd[i] = mf * (g[i + 1] - g[i]);
            gda[i] = mf * (ga[i + 1] + ga[i]);
        }
        acc_mul(&gd[..dg], &s[..=ds], 1.0, &mut k);
        acc_mul(&g[..=dg], &qv[..=dq], -3.0, &mut k);
        acc_mul(&gda[..dg], &sa[..=ds], 1.0, &mut ka);
        acc_mul(&ga[..=dg], &qa[..=dq], 3.0, &mut ka);
        dg - 1 + ds
    };
    normalize(&mut k[..=dk]);
    normalize(&mut ka[..=dk]);
    CurvatureVariation {
        k: Bernstein::new(&k[..=dk]),
        k_noise: noise_slice(&ka[..=dk]),
        speed2,
        speed2_noise,
        speed2_scale,
        hodograph,
    }
}

/// `out[i + j] += s C(m, i) C(n, j) a_i b_j`: an unnormalised Bernstein product term.
#[inline]
fn acc_mul(a: &[f64], b: &[f64], s: f64, out: &mut [f64]) {
    let m = a.len() - 1;
    let n = b.len() - 1;
    for (i, &ai) in a.iter().enumerate() {
        let ai = s * ai * binomial(m, i);
        let row = &mut out[i..=i + n];
        for (j, (o, &bj)) in row.iter_mut().zip(b).enumerate() {
            *o += ai * binomial(n, j) * bj;
        }
    }
}

/// Divide by the binomials of the result's degree (completes [`acc_mul`]).
#[inline]
fn normalize(out: &mut [f64]) {
    let d = out.len() - 1;
    for (k, v) in out.iter_mut().enumerate() {
        *v /= binomial(d, k);
    }
}

/// K(t) for a rational Bézier curve (degree 8n-12 for n >= 2; see the module docs).
pub fn curvature_variation_rational(curve: &RationalBezier) -> CurvatureVariation {
    let b = curve.points();
    let w = curve.weights();
    let n = b.len() - 1;
    let nf = n as f64;
    // D1 = n sum_{i,j} B_i^{n-1} B_j^{n-1} w_i w_{j+1} (b_{j+1} - b_i), degree 2n-2.
    let m1 = n - 1;
    let deg_d = 2 * m1;
    let mut dx = vec![0.0; deg_d + 1];
    let mut dy = vec![0.0; deg_d + 1];
    let mut dxa = vec![0.0; deg_d + 1];
    let mut dya = vec![0.0; deg_d + 1];
    for i in 0..=m1 {
        for j in 0..=m1 {
            let c = binomial(m1, i) * binomial(m1, j) * w[i] * w[j + 1];
            let (p, q) = (b[j + 1], b[i]);
            dx[i + j] += c * (p.x - q.x);
            dy[i + j] += c * (p.y - q.y);
            dxa[i + j] += c * (p.x.abs() + q.x.abs());
            dya[i + j] += c * (p.y.abs() + q.y.abs());
        }
    }
    for l in 0..=deg_d {
        let s = nf / binomial(deg_d, l);
        dx[l] *= s;
        dy[l] *= s;
        dxa[l] *= s;
        dya[l] *= s;
    }
    let (dx, dy) = (Bernstein::new(&dx), Bernstein::new(&dy));
    let (dxa, dya) = (Bernstein::new(&dxa), Bernstein::new(&dya));
    let speed2 = dx.mul(&dx).add(&dy.mul(&dy));
    let speed2_abs = dxa.mul(&dxa).add(&dya.mul(&dya));
    let speed2_noise = noise_of(&speed2_abs);
    let speed2_scale = dx
        .coeffs()
        .iter()
        .zip(dy.coeffs())
        .map(|(a, b)| a * a + b * b)
        .fold(0.0, f64::max);
    let hodograph: SmallVec<[Vec2; 24]> = dx
        .coeffs()
        .iter()
        .zip(dy.coeffs())
        .map(|(a, b)| Vec2::new(*a, *b))
        .collect();
    if n < 2 {
        return CurvatureVariation {
            k: Bernstein::constant(0.0),
            k_noise: vec![0.0],
            speed2,
            speed2_noise,
            speed2_scale,
            hodograph,
        };
    }
    // G = n^2 (n-1) sum_{i,j,k} B_i B_j B_k (degree n-2 each) det3(H_i, H_{j+1}, H_{k+2}).
    let m2 = n - 2;
    let deg_g = 3 * m2;
    let mut g = vec![0.0; deg_g + 1];
    let mut ga = vec![0.0; deg_g + 1];
    for i in 0..=m2 {
        for j in 0..=m2 {
            for k in 0..=m2 {
                let c = binomial(m2, i)
                    * binomial(m2, j)
                    * binomial(m2, k)
                    * w[i]
                    * w[j + 1]
                    * w[k + 2];
                let (p0, p1, p2) = (b[i], b[j + 1], b[k + 2]);
                let (u, v) = (p1 - p0, p2 - p0);
                let (ua, va) = (abs_diff(p1, p0), abs_diff(p2, p0));
                g[i + j + k] += c * u.cross(v);
                ga[i + j + k] += c * (ua.0 * va.1 + ua.1 * va.0);
            }
        }
    }
    let c2 = nf * nf * (nf - 1.0);
    for l in 0..=deg_g {
        let s = c2 / binomial(deg_g, l);
        g[l] *= s;
        ga[l] *= s;
    }
    let (g, ga) = (Bernstein::new(&g), Bernstein::new(&ga));
    let wb = Bernstein::new(w);
    let wd = wb.deriv();
    let wda = deriv_abs(&wb);
    // E = 3 W' G + W G'
    let (e, ea) = if m2 == 0 {
        (wd.mul(&g).scale(3.0), wda.mul(&ga).scale(3.0))
    } else {
        (
            wd.mul(&g).scale(3.0).add(&wb.mul(&g.deriv())),
            wda.mul(&ga).scale(3.0).add(&wb.mul(&deriv_abs(&ga))),
        )
    };
    let dxd = dx.deriv();
    let dyd = dy.deriv();
    let q = dx.mul(&dxd).add(&dy.mul(&dyd));
    let qa = dxa.mul(&deriv_abs(&dxa)).add(&dya.mul(&deriv_abs(&dya)));
    let wg = wb.mul(&g);
    let wga = wb.mul(&ga);
    let k_full = e.mul(&speed2).sub(&wg.mul(&q).scale(3.0));
    let ka = ea.mul(&speed2_abs).add(&wga.mul(&qa).scale(3.0));
    let noise_full = Bernstein::new(&noise_of(&ka));
    // The top power coefficient cancels analytically (degree 8n-11 -> 8n-12).
    let (k, noise) = k_full.reduce_degree_exact(Some(&noise_full));
    let noise = noise.expect("noise requested");
    // The reduction recurrences amplify rounding at most by the factors already applied to
    // `noise`; double it for the residual of the cancelled top coefficient.
    let k_noise = noise.coeffs().iter().map(|v| 2.0 * v).collect();
    CurvatureVariation {
        k,
        k_noise,
        speed2,
        speed2_noise,
        speed2_scale,
        hodograph,
    }
}

fn abs_diff(p: Point, q: Point) -> (f64, f64) {
    (p.x.abs() + q.x.abs(), p.y.abs() + q.y.abs())
}

/// Relative speed below which a curve counts as degenerate (|x'| <= TOL * scale).
pub const DEGENERATE_SPEED_TOL: f64 = 1e-8;

/// Find a parameter where the squared speed falls to `target` or below, if any.
fn speed_vanishes(c: &[f64], target: f64, a: f64, b: f64, depth: u32) -> Option<f64> {
    let min = c.iter().copied().fold(f64::INFINITY, f64::min);
    if min > target {
        return None;
    }
    if c[0] <= target {
        return Some(a);
    }
    if c[c.len() - 1] <= target {
        return Some(b);
    }
    if depth >= 40 {
        let mid = 0.5 * (a + b);
        return (crate::bernstein::de_casteljau(c, 0.5) <= target).then_some(mid);
    }
    let (l, r) = subdivide_coeffs(c, 0.5);
    let mid = 0.5 * (a + b);
    speed_vanishes(&l, target, a, mid, depth + 1)
        .or_else(|| speed_vanishes(&r, target, mid, b, depth + 1))
}

impl CurvatureVariation {
    /// `Err(Degenerate)` when the speed vanishes (to the tolerance) somewhere on [0, 1].
    pub fn check_regular(&self) -> Result<()> {
        let noise = self.speed2_noise.iter().copied().fold(0.0, f64::max);
        let target = (DEGENERATE_SPEED_TOL * DEGENERATE_SPEED_TOL) * self.speed2_scale + noise;
        if self.speed2_scale == 0.0 {
            return Err(Error::Degenerate(
                "all control points coincide: the curve is a point".into(),
            ));
        }
        if self.tangent_cone_is_open(target.sqrt()) {
            return Ok(());
        }
        if let Some(t) = speed_vanishes(self.speed2.coeffs(), target, 0.0, 1.0, 0) {
            return Err(Error::Degenerate(format!(
                "the tangent vanishes at t = {t:.9} (coincident control points or a cusp): \
                 curvature is undefined there"
            )));
        }
        Ok(())
    }

    /// Sufficient condition for regularity: some direction v has `v . h_i >= margin` for every
    /// hodograph control vector, so `|x'(t)| >= margin` on [0, 1] (x' is their convex
    /// combination). The direction tried is the mean of the unit control vectors.
    fn tangent_cone_is_open(&self, margin: f64) -> bool {
        let mut s = Vec2::ZERO;
        for h in &self.hodograph {
            let l = h.hypot();
            if l <= margin {
                return false;
            }
            s += *h / l;
        }
        let l = s.hypot();
        if l < 1e-6 {
            return false;
        }
        let v = s / l;
        self.hodograph.iter().all(|h| v.dot(*h) > margin)
    }

    /// Run the sign analysis of K and turn it into a verdict.
    pub fn verdict(&self, full: bool) -> MonotoneReport {
        let test_degree = self.k.degree();
        let a = analyze_signs(
            self.k.coeffs(),
            &self.k_noise,
            SignOptions {
                stop_at_both_signs: !full,
                ..SignOptions::default()
            },
        );
        let (pos, neg) = (a.has_positive(), a.has_negative());
        let monotone = !(pos && neg);
        let trend = match (pos, neg) {
            (true, false) => Some(Trend::Increasing),
            (false, true) => Some(Trend::Decreasing),
            (false, false) => Some(Trend::Constant),
            _ => None,
        };
        MonotoneReport {
            monotone,
            trend,
            extrema: if monotone { Vec::new() } else { a.changes },
            test_degree,
        }
    }
}

/// Curves the monotonicity tests apply to.
pub trait CurvatureMonotone {
    /// The numerator of dkappa/ds in Bernstein form.
    fn curvature_variation(&self) -> CurvatureVariation;
    /// Point and derivatives at `t`.
    fn derivs_at(&self, t: f64) -> Derivs;

    /// The exact test with the curvature extrema located (to about 1e-15 in t).
    fn curvature_monotone(&self) -> Result<MonotoneReport> {
        let cv = self.curvature_variation();
        cv.check_regular()?;
        Ok(cv.verdict(true))
    }

    /// The exact test's verdict only (stops at the first proof of non-monotonicity).
    fn is_curvature_monotone(&self) -> Result<bool> {
        let cv = self.curvature_variation();
        cv.check_regular()?;
        Ok(cv.verdict(false).monotone)
    }

    /// The sampling test of S1 §3.1 with `samples` divisions (at least 1).
    fn curvature_monotone_sampled(&self, samples: usize) -> Result<SampledReport> {
        sampled(|t| self.derivs_at(t), samples)
    }
}

impl CurvatureMonotone for Bezier {
    fn curvature_variation(&self) -> CurvatureVariation {
        curvature_variation(self)
    }
    fn derivs_at(&self, t: f64) -> Derivs {
        self.derivs(t)
    }
}

impl CurvatureMonotone for RationalBezier {
    fn curvature_variation(&self) -> CurvatureVariation {
        curvature_variation_rational(self)
    }
    fn derivs_at(&self, t: f64) -> Derivs {
        self.derivs(t)
    }
}

fn sampled(f: impl Fn(f64) -> Derivs, samples: usize) -> Result<SampledReport> {
    if samples == 0 {
        return Err(Error::invalid("samples", "need at least 1 division"));
    }
    let inv = 1.0 / samples as f64;
    let mut prev = f(0.0).kappa();
    if !prev.is_finite() {
        return Err(Error::Degenerate(
            "curvature is undefined at t = 0 (vanishing tangent)".into(),
        ));
    }
    let (mut up, mut down) = (false, false);
    for i in 1..=samples {
        let t = i as f64 * inv;
        let k = f(t).kappa();
        if !k.is_finite() {
            return Err(Error::Degenerate(format!(
                "curvature is undefined at t = {t} (vanishing tangent)"
            )));
        }
        let d = k - prev;
        let tol = 1e-12 * k.abs().max(prev.abs());
        if d > tol {
            up = true;
        } else if d < -tol {
            down = true;
        }
        if up && down {
            return Ok(SampledReport {
                monotone: false,
                trend: None,
                samples,
            });
        }
        prev = k;
    }
    let trend = Some(match (up, down) {
        (true, _) => Trend::Increasing,
        (_, true) => Trend::Decreasing,
        _ => Trend::Constant,
    });
    Ok(SampledReport {
        monotone: true,
        trend,
        samples,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bez(v: &[(f64, f64)]) -> Bezier {
        Bezier::new(v.iter().map(|&(x, y)| Point::new(x, y)).collect()).unwrap()
    }

    #[test]
    fn k_has_the_sign_and_size_of_the_numerator() {
        let c = bez(&[(0.0, 0.0), (1.0, 2.0), (3.0, 3.5), (4.0, 0.0), (6.0, 1.0)]);
        let cv = curvature_variation(&c);
        assert_eq!(cv.k.degree(), 4 * 4 - 7);
        for i in 0..=20 {
            let t = i as f64 / 20.0;
            let d = c.derivs(t);
            let s2 = d.d1.hypot2();
            let num = d.d1.cross(d.d3) * s2 - 3.0 * d.d1.cross(d.d2) * d.d1.dot(d.d2);
            assert!(
                (cv.k.eval(t) - num).abs() < 1e-9 * num.abs().max(1.0),
                "t={t}"
            );
        }
    }

    #[test]
    fn rational_k_is_proportional_to_dkappa_ds() {
        let r = RationalBezier::new(
            [(0.0, 0.0), (1.0, 2.0), (3.0, 3.0), (4.0, 0.5)]
                .iter()
                .map(|&(x, y)| Point::new(x, y))
                .collect(),
            vec![1.0, 1.7, 0.6, 1.3],
        )
        .unwrap();
        let cv = curvature_variation_rational(&r);
        assert_eq!(cv.k.degree(), 12);
        let (_, _, w) = r.components();
        for i in 0..=20 {
            let t = i as f64 / 20.0;
            // dkappa/ds = W^4 K / |D1|^6
            let s2 = cv.speed2.eval(t);
            let expect = w.eval(t).powi(4) * cv.k.eval(t) / (s2 * s2 * s2);
            let got = r.dkappa_ds(t);
            assert!(
                (got - expect).abs() < 1e-9 * got.abs().max(1e-3),
                "t={t}: {got} vs {expect}"
            );
        }
    }

    #[test]
    fn lines_and_arcs_are_monotone() {
        let line = bez(&[(0.0, 0.0), (1.0, 1.0), (2.5, 2.5), (3.0, 3.0)]);
        let r = line.curvature_monotone().unwrap();
        assert!(r.monotone);
        assert_eq!(r.trend, Some(Trend::Constant));
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let arc = RationalBezier::new(
            vec![
                Point::new(1.0, 0.0),
                Point::new(1.0, 1.0),
                Point::new(0.0, 1.0),
            ],
            vec![1.0, h, 1.0],
        )
        .unwrap();
        let e = arc.elevate().unwrap().elevate().unwrap();
        for c in [arc, e] {
            let r = c.curvature_monotone().unwrap();
            assert!(r.monotone && r.trend == Some(Trend::Constant), "{r:?}");
        }
    }

    #[test]
    fn s_curve_has_an_extremum_and_spiral_is_monotone() {
        // Symmetric bump: curvature peaks at t = 1/2.
        let bump = bez(&[(0.0, 0.0), (1.0, 1.0), (2.0, 1.0), (3.0, 0.0)]);
        let r = bump.curvature_monotone().unwrap();
        assert!(!r.monotone);
        assert_eq!(r.extrema.len(), 1);
        assert!((r.extrema[0] - 0.5).abs() < 1e-12);
        let s = bump.curvature_monotone_sampled(100).unwrap();
        assert!(!s.monotone);
        // A "class A" control polygon: each edge is the previous one scaled by 0.6 and
        // rotated by 25 degrees; curvature grows monotonically.
        let (c, s) = (25f64.to_radians().cos(), 25f64.to_radians().sin());
        let mut pts = vec![(0.0, 0.0)];
        let mut e = (1.0, 0.0);
        for _ in 0..3 {
            let last = *pts.last().unwrap();
            pts.push((last.0 + e.0, last.1 + e.1));
            e = (0.6 * (c * e.0 - s * e.1), 0.6 * (s * e.0 + c * e.1));
        }
        let spiral = bez(&pts);
        let r = spiral.curvature_monotone().unwrap();
        assert!(r.monotone && r.trend == Some(Trend::Increasing), "{r:?}");
        assert!(spiral.curvature_monotone_sampled(2000).unwrap().monotone);
    }

    #[test]
    fn degenerate_curves_are_errors() {
        let coincident = bez(&[(0.0, 0.0), (0.0, 0.0), (1.0, 1.0), (2.0, 0.0)]);
        assert!(matches!(
            coincident.curvature_monotone(),
            Err(Error::Degenerate(_))
        ));
        // Cusp: x'(1/2) = 0.
        let cusp = bez(&[(0.0, 0.0), (2.0, 1.0), (0.0, 1.0), (2.0, 0.0)]);
        assert!(matches!(
            cusp.curvature_monotone(),
            Err(Error::Degenerate(_))
        ));
        // Backtracking line.
        let back = bez(&[(0.0, 0.0), (2.0, 0.0), (1.0, 0.0)]);
        assert!(matches!(
            back.curvature_monotone(),
            Err(Error::Degenerate(_))
        ));
        let point = bez(&[(1.0, 1.0), (1.0, 1.0)]);
        assert!(matches!(
            point.curvature_monotone(),
            Err(Error::Degenerate(_))
        ));
    }
}
