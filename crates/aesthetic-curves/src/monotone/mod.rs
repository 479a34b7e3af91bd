//! Curvature monotonicity of Bézier curves (docs/math.md §2; seeds S0 §4, S1 §3).
//!
//! ## The exact test
//!
//! The sign of dkappa/ds is the sign of a polynomial `K(t)`, written here in Bernstein form
//! from the control points directly (no power basis, no sampling):
//!
//! - **polynomial curve, degree n**: with `d_i = b_{i+1} - b_i`, `A = sum B_i^{n-2} d_i`,
//!   `B = sum B_i^{n-2} d_{i+1}` one has `det(x', x'') = G = n^2 (n-1) det(A, B)` (degree
//!   2n-4) and `K = G' |x'|^2 - 3 G (x'.x'')`, exactly the numerator of docs/math.md §1 since
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
//! ## Every verdict is exact for the given f64 control points and weights
//!
//! f64 numbers are dyadic rationals, so the verdict has one right answer for every finite
//! input, and it is the one given (docs/math.md §2.4). Three stages, each knowing when it
//! cannot decide:
//!
//! 1. **fast paths** (regular curves): K as above in plain floating point, against a
//!    rigorous bound on its rounding (`loose_k_bound`, `rational_cubic_bounds`): all
//!    coefficients beyond it and of one sign prove monotonicity; values of both strict signs
//!    prove a change. A coefficient within the bound has an unknown sign, never a zero one;
//! 2. **the certified filter** (`monotone/certified.rs`): K̃, the numerator with the vanishing ends of
//!    the hodograph divided out, computed on [`crate::exact::Bounded`] numbers (every value
//!    with a rigorous error bound, the inputs scaled by powers of two so that nothing
//!    overflows), and its signs by subdivision ([`crate::exact::signs`]);
//! 3. **exact arithmetic**, where the filter cannot decide: the same formula on big
//!    integers, and the sign changes of the integer polynomial by Descartes' rule, square-free
//!    parts and Sturm sequences ([`crate::exact::poly`]). [`MonotoneReport::exact`] says it
//!    ran, [`exact_fallbacks`] counts it.
//!
//! Extrema are located within 1e-12 in t (certified by the signs on both sides).
//!
//! **Retracted handles** (control points coinciding with an end point, the commonest
//! construction in fonts): the speed vanishes at that end like `t^r`. The common power of t
//! (or 1 - t) is divided out of the hodograph and of K, and the verdict is the exact one on
//! the open segment; [`MonotoneReport::ends`] says what the curvature does there (tends to a
//! finite limit, to 0 on a straight stretch, or grows without bound like `1/t`). Only a
//! speed that vanishes *inside* (0, 1) (a cusp, a straight line that turns back) is an
//! [`Error::Degenerate`], decided exactly too (a common root of the hodograph's components).
//!
//! ## The sampling test (S1 §3.1)
//!
//! Curvature at `N + 1` uniform parameters; monotone when consecutive differences keep one
//! sign (differences within `1e-12` of the curvature's size count as zero). As in S1, all
//! `N + 1` samples are evaluated before the check (S1 Fig. 4: time linear in N and in the
//! degree), so a non-monotone curve costs as much as a monotone one. It can miss extrema
//! between samples: it exists to reproduce S1's comparison.

mod budget;
mod certified;

use crate::bernstein::{binomial, Bernstein, Coeffs};
use crate::bezier::{Bezier, PlanarCurve, RationalBezier};
use crate::error::{Error, Result};
use crate::exact::{Bounded, Want};
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
    /// dkappa/ds keeps one sign on (0, 1) (zero allowed): exact for the given f64 control
    /// points and weights.
    pub monotone: bool,
    /// The direction, when monotone.
    pub trend: Option<Trend>,
    /// Parameters in (0, 1) where dkappa/ds changes sign (curvature extrema), sorted, each
    /// within 1e-12 of the exact one.
    pub extrema: Vec<f64>,
    /// Degree of the Bernstein polynomial examined.
    pub test_degree: usize,
    /// The floating-point filter could not decide: big-integer arithmetic did.
    pub exact: bool,
    /// How the curvature behaves at t = 0 and at t = 1.
    pub ends: [EndCurvature; 2],
}

/// The curvature at an end of a curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum EndCurvature {
    /// The speed does not vanish there: the curvature at the end.
    Regular(f64),
    /// A retracted handle (`order` control points coincide with the end point, so the speed
    /// vanishes like t^order), and the curvature tends to a finite limit (0 on a straight
    /// stretch).
    Finite {
        /// The limit.
        curvature: f64,
        /// How many handles are retracted onto the end point.
        order: usize,
    },
    /// A retracted handle, and the curvature grows without bound towards the end, like
    /// `1/t^rate` (t the distance in parameter from the end).
    Unbounded {
        /// The sign of the curvature near the end.
        positive: bool,
        /// How many handles are retracted onto the end point.
        order: usize,
        /// The growth's power of 1/t.
        rate: usize,
    },
}

impl EndCurvature {
    /// The curvature at the end (the limit at a retracted one), None where it is unbounded.
    pub fn value(&self) -> Option<f64> {
        match self {
            EndCurvature::Regular(k) | EndCurvature::Finite { curvature: k, .. } => Some(*k),
            EndCurvature::Unbounded { .. } => None,
        }
    }

    /// How an unbounded curvature grows: `1/t`, `1/t^2`, ... (None where it is bounded).
    pub fn growth(&self) -> Option<String> {
        match self {
            EndCurvature::Unbounded { rate: 1, .. } => Some("1/t".into()),
            EndCurvature::Unbounded { rate, .. } => Some(format!("1/t^{rate}")),
            _ => None,
        }
    }

    /// For a person: None at a regular end.
    pub fn describe(&self) -> Option<String> {
        match self {
            EndCurvature::Regular(_) => None,
            EndCurvature::Finite { curvature, .. } if *curvature == 0.0 => {
                Some("retracted handle: the curvature tends to 0 towards this end".into())
            }
            EndCurvature::Finite { curvature, .. } => Some(format!(
                "retracted handle: the curvature tends to {curvature:.6} towards this end"
            )),
            EndCurvature::Unbounded { .. } => Some(format!(
                "retracted handle: the curvature grows without bound towards this end (like {})",
                self.growth().unwrap_or_default()
            )),
        }
    }
}

pub use budget::{with_exact_budget, SEARCH_EXACT_BUDGET};

static EXACT_FALLBACKS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

/// The degree of the polynomial whose sign the exact test decides (K̃ of the module docs) for
/// a Bézier curve of `degree`, rational or not, with no handle retracted onto its end point:
/// the largest it can be for that curve, and what the test's cost grows with (about its
/// power 1.5: the editor's work budget for a region of control-point positions).
pub fn exact_test_degree(degree: usize, rational: bool) -> usize {
    certified::k_degree(degree, rational, (0, 0))
}

fn note_exact_fallback() {
    EXACT_FALLBACKS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
}

/// How many verdicts so far (in this process) needed exact arithmetic because the
/// floating-point filter could not decide: for statistics (`aecurve bench monotone`, the
/// check summary).
pub fn exact_fallbacks() -> u64 {
    EXACT_FALLBACKS.load(std::sync::atomic::Ordering::Relaxed)
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
    pub k_noise: Coeffs,
    /// Squared speed, up to a positive factor: |x'|^2 or |W P' - P W'|^2.
    pub speed2: Bernstein,
    /// Largest squared length of the hodograph's control vectors (the speed's scale).
    pub speed2_scale: f64,
    /// Control vectors of the (scaled) hodograph: the tangent is a positive combination.
    pub hodograph: SmallVec<[Vec2; 24]>,
}

const EPS: f64 = f64::EPSILON;

fn noise_of(abs: &Bernstein) -> Coeffs {
    noise_slice(abs.coeffs())
}

/// Rounding bound from magnitude bounds: a few ulps per operation level of the products.
fn noise_slice(abs: &[f64]) -> Coeffs {
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
pub fn curvature_variation(curve: &Bezier) -> CurvatureVariation {
    if curve.degree() <= SMALL_DEGREE {
        poly_k::<SMALL_CAP>(curve.points(), true).to_variation()
    } else {
        poly_k::<LARGE_CAP>(curve.points(), true).to_variation()
    }
}

/// Degrees up to this use the small stack buffers.
const SMALL_DEGREE: usize = 5;
const SMALL_CAP: usize = 4 * SMALL_DEGREE - 5;
/// Buffers for cubics and below, the commonest curves (K of degree 5, |x'|² of degree 4).
const CUBIC_CAP: usize = 8;
const LARGE_CAP: usize = 4 * crate::bezier::MAX_BEZIER_DEGREE;

/// K, its magnitude bounds, |x'|^2 and the hodograph of a polynomial curve, on the stack.
///
/// `k`, `ka` and `s` are in *scaled* Bernstein form (`C(d, i) c_i`): products are then plain
/// convolutions, and signs (with their bounds) are the same as in the unscaled form.
struct PolyK<const C: usize> {
    n: usize,
    k: [f64; C],
    ka: [f64; C],
    dk: usize,
    s: [f64; C],
    ds: usize,
    h: [Vec2; C],
    scale: f64,
}

impl<const C: usize> PolyK<C> {
    fn noise(&self) -> [f64; C] {
        let mut out = [0.0; C];
        let f = 16.0 + 4.0 * self.dk as f64;
        for (o, a) in out.iter_mut().zip(&self.ka[..=self.dk]) {
            *o = f * EPS * a;
        }
        out
    }

    fn to_variation(&self) -> CurvatureVariation {
        let mut noise = self.noise();
        let mut k = self.k;
        let mut s = self.s;
        unscale(&mut k[..=self.dk]);
        unscale(&mut noise[..=self.dk]);
        unscale(&mut s[..=self.ds]);
        CurvatureVariation {
            k: Bernstein::new(&k[..=self.dk]),
            k_noise: Coeffs::from_slice(&noise[..=self.dk]),
            speed2: Bernstein::new(&s[..=self.ds]),
            speed2_scale: self.scale,
            hodograph: SmallVec::from_slice(&self.h[..self.n]),
        }
    }

    /// A proof of regularity by subdivision of the hodograph: every piece's control vectors
    /// in an open cone by a margin of 1e-8 of their size (the hodograph's rounding is a few
    /// ulps of it, as the differences are correctly rounded).
    fn hodograph_is_clearly_regular(&self) -> bool {
        let margin = DEGENERATE_SPEED_TOL * self.scale.sqrt();
        margin > 0.0
            && margin.is_finite()
            && hodograph_vanishes(&self.h[..self.n], margin).is_none()
    }

    /// A quick proof of regularity: every Bernstein coefficient of |x'|^2 is positive by far
    /// more than its rounding (which is a few ulps of `scale` times the binomials).
    #[inline(always)]
    fn speed_is_clearly_positive(&self) -> bool {
        let margin = 1e-12 * self.scale;
        self.scale > 0.0
            && self.scale.is_finite()
            && self.s[..=self.ds]
                .iter()
                .enumerate()
                .all(|(i, v)| *v > margin * binomial(self.ds, i))
    }
}

/// From scaled (`C(d, i) c_i`) to plain Bernstein coefficients.
#[inline]
fn unscale(c: &mut [f64]) {
    let d = c.len() - 1;
    for (i, v) in c.iter_mut().enumerate() {
        *v /= binomial(d, i);
    }
}

/// From plain to scaled Bernstein coefficients.
#[inline]
fn rescale(c: &mut [f64]) {
    let d = c.len() - 1;
    for (i, v) in c.iter_mut().enumerate() {
        *v *= binomial(d, i);
    }
}

/// `out[i + j] += s a_i b_j`: the product of scaled Bernstein forms is a convolution.
#[inline(always)]
fn conv(a: &[f64], b: &[f64], s: f64, out: &mut [f64]) {
    for (i, &ai) in a.iter().enumerate() {
        let ai = s * ai;
        for (o, &bj) in out[i..i + b.len()].iter_mut().zip(b) {
            *o += ai * bj;
        }
    }
}

/// Stack buffers only, scaled Bernstein forms (products are convolutions), values and
/// magnitude bounds side by side. Needs `4n - 6 <= C` and `n <= C`.
#[inline(always)]
fn poly_k<const C: usize>(b: &[Point], bounds: bool) -> PolyK<C> {
    let n = b.len() - 1;
    let nf = n as f64;
    let m1 = n - 1;
    // Hodograph n d_i, plain (for regularity) and scaled by C(n-1, i).
    let mut h = [Vec2::ZERO; C];
    let (mut hx, mut hy, mut hxa, mut hya) = ([0.0; C], [0.0; C], [0.0; C], [0.0; C]);
    let mut scale = 0.0f64;
    for i in 0..n {
        let (p, q) = (b[i + 1], b[i]);
        hx[i] = nf * (p.x - q.x);
        hy[i] = nf * (p.y - q.y);
        hxa[i] = nf * (p.x.abs() + q.x.abs());
        hya[i] = nf * (p.y.abs() + q.y.abs());
        h[i] = Vec2::new(hx[i], hy[i]);
        scale = scale.max(hx[i] * hx[i] + hy[i] * hy[i]);
    }
    let sc = |v: &[f64; C], off: usize, d: usize| {
        let mut o = [0.0; C];
        for i in 0..=d {
            o[i] = v[i + off] * binomial(d, i);
        }
        o
    };
    let (hxs, hys, hxas, hyas) = (
        sc(&hx, 0, m1),
        sc(&hy, 0, m1),
        sc(&hxa, 0, m1),
        sc(&hya, 0, m1),
    );
    // |x'|^2, degree 2n-2.
    let ds = 2 * m1;
    let mut s = [0.0; C];
    let mut sa = [0.0; C];
    conv(&hxs[..n], &hxs[..n], 1.0, &mut s);
    conv(&hys[..n], &hys[..n], 1.0, &mut s);
    if bounds {
        conv(&hxas[..n], &hxas[..n], 1.0, &mut sa);
        conv(&hyas[..n], &hyas[..n], 1.0, &mut sa);
    }
    let mut out = PolyK {
        n,
        k: [0.0; C],
        ka: [0.0; C],
        dk: 0,
        s,
        ds,
        h,
        scale,
    };
    if n < 2 {
        return out;
    }
    // det(x', x'') = (n-1) det(sum B^{n-2} h_i, sum B^{n-2} h_{i+1}), degree 2n-4.
    let m = n - 2;
    let dg = 2 * m;
    let c2 = nf - 1.0;
    let (ax, ay, aax, aay) = (sc(&hx, 0, m), sc(&hy, 0, m), sc(&hxa, 0, m), sc(&hya, 0, m));
    let (bx, by, bax, bay) = (sc(&hx, 1, m), sc(&hy, 1, m), sc(&hxa, 1, m), sc(&hya, 1, m));
    let mut g = [0.0; C];
    let mut ga = [0.0; C];
    conv(&ax[..=m], &by[..=m], c2, &mut g);
    conv(&ay[..=m], &bx[..=m], -c2, &mut g);
    if bounds {
        conv(&aax[..=m], &bay[..=m], c2, &mut ga);
        conv(&aay[..=m], &bax[..=m], c2, &mut ga);
    }
    // x'' = (n-1) (h_{i+1} - h_i), degree n-2, scaled: (n-1) (B - A).
    let (mut x2, mut y2, mut x2a, mut y2a) = ([0.0; C], [0.0; C], [0.0; C], [0.0; C]);
    for i in 0..=m {
        x2[i] = c2 * (bx[i] - ax[i]);
        y2[i] = c2 * (by[i] - ay[i]);
        x2a[i] = c2 * (bax[i] + aax[i]);
        y2a[i] = c2 * (bay[i] + aay[i]);
    }
    // Q = x'.x'', degree 2n-3.
    let mut qv = [0.0; C];
    let mut qa = [0.0; C];
    conv(&hxs[..n], &x2[..=m], 1.0, &mut qv);
    conv(&hys[..n], &y2[..=m], 1.0, &mut qv);
    if bounds {
        conv(&hxas[..n], &x2a[..=m], 1.0, &mut qa);
        conv(&hyas[..n], &y2a[..=m], 1.0, &mut qa);
    }
    let dq = 2 * n - 3;
    let (k, ka) = (&mut out.k, &mut out.ka);
    out.dk = if n == 2 {
        conv(&g[..1], &qv[..=dq], -3.0, k);
        if bounds {
            conv(&ga[..1], &qa[..=dq], 3.0, ka);
        }
        dq
    } else {
        // G' (degree 2n-5) and its bound: unscale, differentiate, rescale.
        unscale(&mut g[..=dg]);
        unscale(&mut ga[..=dg]);
        let (mut gd, mut gda) = ([0.0; C], [0.0; C]);
        let mf = dg as f64;
        for i in 0..dg {
            gd[i] = mf * (g[i + 1] - g[i]);
            gda[i] = mf * (ga[i + 1] + ga[i]);
        }
        rescale(&mut gd[..dg]);
        rescale(&mut gda[..dg]);
        rescale(&mut g[..=dg]);
        rescale(&mut ga[..=dg]);
        conv(&gd[..dg], &out.s[..=ds], 1.0, k);
        conv(&g[..=dg], &qv[..=dq], -3.0, k);
        if bounds {
            conv(&gda[..dg], &sa[..=ds], 1.0, ka);
            conv(&ga[..=dg], &qa[..=dq], 3.0, ka);
        }
        dg - 1 + ds
    };
    out
}

/// What a fast path proved (None from it: undecided, the certified test decides).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Fast {
    /// Monotone; the sign of dkappa/ds.
    Monotone(i32),
    /// Not monotone.
    NotMonotone,
}

/// The unit roundoff.
const U: f64 = f64::EPSILON * 0.5;

/// The fast verdict for polynomial curves (stack buffers sized for the degree).
fn poly_fast(b: &[Point]) -> Option<Fast> {
    let n = b.len() - 1;
    if n <= 3 {
        poly_fast_cap::<CUBIC_CAP>(b)
    } else if n <= SMALL_DEGREE {
        poly_fast_cap::<SMALL_CAP>(b)
    } else {
        poly_fast_cap::<LARGE_CAP>(b)
    }
}

/// A rigorous bound on the rounding error of every *plain* Bernstein coefficient of K as
/// [`poly_k`] computes it. Each coefficient is a sum of products of four hodograph
/// components with small integer factors; running the same arithmetic on absolute values,
/// with every component replaced by the largest one, bounds the sum of the terms' magnitudes
/// (the arithmetic is monotone in them), and on constant inputs every plain coefficient of
/// that magnitude polynomial is the same number, `2 dg GA SA + 3 GA QA`. The rounding error is
/// at most `γ_D` times it, where D (the longest chain of roundings: the difference, the
/// scalings, the products and the sums of the convolutions) is far below the `16 + 4 dk` used
/// here; a factor 8 covers the rounding of the bound itself and the inputs' own rounding.
fn loose_k_bound(b: &[Point], dk: usize) -> f64 {
    let n = b.len() - 1;
    let nf = n as f64;
    let (mut hxa, mut hya) = (0.0f64, 0.0f64);
    for w in b.windows(2) {
        hxa = hxa.max(nf * (w[1].x - w[0].x).abs());
        hya = hya.max(nf * (w[1].y - w[0].y).abs());
    }
    let c2 = nf - 1.0;
    let dg = 2.0 * (nf - 2.0).max(0.0);
    let h = hxa.max(hya) * (1.0 + 4.0 * f64::EPSILON);
    let sa = 2.0 * h * h;
    let ga = 2.0 * c2 * h * h;
    let qa = 2.0 * c2 * sa;
    let bound = 2.0 * dg * ga * sa + 3.0 * ga * qa;
    (16.0 + 4.0 * dk as f64) * 8.0 * f64::EPSILON * bound
}

/// K of a quickly proven regular curve with [`loose_k_bound`]; None when regularity is not
/// quickly proven or the bound is out of range (underflow, overflow).
#[inline(always)]
fn poly_fast_k<const C: usize>(b: &[Point]) -> Option<(PolyK<C>, f64)> {
    let pk = poly_k::<C>(b, false);
    if pk.n < 2 || !(pk.speed_is_clearly_positive() || pk.hodograph_is_clearly_regular()) {
        return None;
    }
    let loose = loose_k_bound(b, pk.dk);
    (loose > 1e-280 && loose < 1e280).then_some((pk, loose))
}

/// The fast paths' last resort: the filter's subdivision of the plain coefficients, the one
/// bound carried along; None when it cannot decide.
#[inline(always)]
fn subdivided(plain: &[f64], bound: f64) -> Option<Fast> {
    let s = crate::exact::signs::filter_plain(&plain_with_bound(plain, bound), Want::Signs)?;
    Some(if s.positive && s.negative {
        Fast::NotMonotone
    } else if s.positive {
        Fast::Monotone(1)
    } else if s.negative {
        Fast::Monotone(-1)
    } else {
        return None;
    })
}

/// Plain Bernstein coefficients with one common bound as [`Bounded`] numbers (the
/// division by the binomials adds its rounding).
fn plain_with_bound(plain: &[f64], bound: f64) -> SmallVec<[Bounded; 24]> {
    plain
        .iter()
        .map(|v| Bounded {
            v: *v,
            e: bound + 2.0 * U * v.abs(),
        })
        .collect()
}

/// One instance per buffer size, kept out of line so that the small case does not pay for
/// the large case's stack frame.
#[inline(never)]
fn poly_fast_cap<const C: usize>(b: &[Point]) -> Option<Fast> {
    let (pk, loose) = poly_fast_k::<C>(b)?;
    let dk = pk.dk;
    let k = &pk.k[..=dk];
    // Scaled coefficients: the plain bound times the binomials (plus the scaling's rounding).
    let strict = |i: usize| {
        let bound = loose * binomial(dk, i) * (1.0 + 4.0 * f64::EPSILON);
        if k[i] > bound {
            1
        } else if k[i] < -bound {
            -1
        } else {
            0
        }
    };
    let s0 = strict(0);
    if s0 != 0 && (1..=dk).all(|i| strict(i) == s0) {
        return Some(Fast::Monotone(s0));
    }
    let sm = strict(dk);
    if s0 * sm < 0 {
        return Some(Fast::NotMonotone);
    }
    // Values of both strict signs at a few parameters prove a change. A value is a convex
    // combination of the plain coefficients (de Casteljau), so its error is at most the
    // bound plus the evaluation's rounding, `dk` ulps of the largest coefficient.
    let mut ku = [0.0f64; C];
    for i in 0..=dk {
        ku[i] = k[i] / binomial(dk, i);
    }
    let big = ku[..=dk].iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let margin = 2.0 * loose + 4.0 * (dk as f64 + 2.0) * U * big;
    let (mut pos, mut neg) = (k[0] > 0.0 && s0 != 0, k[0] < 0.0 && s0 != 0);
    // The middle first: with both ends of one sign, the other sign is most often there.
    for j in [4, 2, 6, 1, 3, 5, 7] {
        let v = crate::bernstein::de_casteljau(&ku[..=dk], j as f64 / 8.0);
        pos |= v > margin;
        neg |= v < -margin;
        if pos && neg {
            return Some(Fast::NotMonotone);
        }
    }
    subdivided(&ku[..=dk], loose)
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
            k_noise: Coeffs::from_elem(0.0, 1),
            speed2,
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
    let k_noise: Coeffs = noise.coeffs().iter().map(|v| 2.0 * v).collect();
    CurvatureVariation {
        k,
        k_noise,
        speed2,
        speed2_scale,
        hodograph,
    }
}

/// Product of two Bernstein polynomials given by their coefficients, into `out` (length
/// `a.len() + b.len() - 1`): `(ab)_k = Σ C(m,i) C(n,j) / C(m+n,k) a_i b_j`.
#[inline(always)]
fn bernstein_mul(a: &[f64], b: &[f64], out: &mut [f64]) {
    let (m, n) = (a.len() - 1, b.len() - 1);
    out[..=m + n].fill(0.0);
    for (i, ai) in a.iter().enumerate() {
        let ci = binomial(m, i) * ai;
        for (j, bj) in b.iter().enumerate() {
            out[i + j] += ci * binomial(n, j) * bj;
        }
    }
    for (k, v) in out[..=m + n].iter_mut().enumerate() {
        *v /= binomial(m + n, k);
    }
}

/// Derivative of a Bernstein polynomial (degree n, n >= 1) into `out` (degree n - 1).
fn bernstein_deriv(a: &[f64], out: &mut [f64]) {
    let n = a.len() - 1;
    for i in 0..n {
        out[i] = n as f64 * (a[i + 1] - a[i]);
    }
}

/// A degree-13 Bernstein polynomial at `t` in [0, 1]: `s^13 Σ C(13,i) c_i (t/s)^i`,
/// `s = 1 - t`, by Horner in `t/s` (or in `s/t` from the other end when t > 1/2, so the
/// ratio stays at most 1).
fn bernstein_eval13(c: &[f64; 14], t: f64) -> f64 {
    let s = 1.0 - t;
    if t <= 0.5 {
        let r = t / s;
        let mut acc = 0.0;
        for (i, ci) in c.iter().enumerate().rev() {
            acc = acc * r + binomial(13, i) * ci;
        }
        acc * s.powi(13)
    } else {
        let r = s / t;
        let mut acc = 0.0;
        for (i, ci) in c.iter().enumerate() {
            acc = acc * r + binomial(13, i) * ci;
        }
        acc * t.powi(13)
    }
}

/// A rigorous bound on the rounding error of every plain Bernstein coefficient of the
/// rational cubic's K as [`rational_cubic_fast`] computes it, from the largest weight and
/// coordinate difference (as for [`loose_k_bound`]: the magnitude computation on constant
/// inputs gives 3 for each component of D1, 36 for G, 864 for E, 18 for |D1|², 144 for Q, 36
/// for W G and so `864·18 + 3·36·144 = 31104` for K, times `w^8 d^4`; 64 roundings in a chain
/// at most, and a factor 2 for the rest). Also the bound on D1's coefficients, `18 w² d`.
fn rational_cubic_bounds(b: &[Point], w: &[f64]) -> (f64, f64) {
    let wmax = w.iter().fold(0.0f64, |m, v| m.max(*v));
    let mut d = 0.0f64;
    for j in 0..4 {
        for i in 0..j {
            d = d.max((b[j].x - b[i].x).abs()).max((b[j].y - b[i].y).abs());
        }
    }
    let d = d * (1.0 + 4.0 * f64::EPSILON);
    let w2 = wmax * wmax;
    let w8 = w2 * w2 * w2 * w2;
    (
        2.0 * 64.0 * U * 31104.0 * w8 * d * d * d * d,
        2.0 * 64.0 * U * 18.0 * w2 * d,
    )
}

/// The fast verdict for a rational cubic: K (degree 13, the nominal form) from stack arrays,
/// values only, against the rigorous bound of [`rational_cubic_bounds`]: all coefficients
/// beyond it and of one sign prove monotonicity; two values at sample points beyond it (and
/// beyond the evaluation's rounding) of opposite signs prove a sign change. `None`: the
/// certified test decides (also when regularity is not quickly proven).
#[inline(never)]
fn rational_cubic_fast(b: &[Point], w: &[f64]) -> Option<Fast> {
    let rk = rational_cubic_k(b, w)?;
    let (k, k_bound) = (&rk.k, rk.k_bound);
    if k.iter().all(|v| *v > k_bound) {
        return Some(Fast::Monotone(1));
    }
    if k.iter().all(|v| *v < -k_bound) {
        return Some(Fast::Monotone(-1));
    }
    if rk.samples_change_sign() {
        return Some(Fast::NotMonotone);
    }
    subdivided(k, k_bound)
}

/// A rational cubic's K (degree 13, plain Bernstein coefficients), its rigorous bound and
/// the parts it is made of.
struct RationalCubicK {
    k: [f64; 14],
    k_bound: f64,
    e: [f64; 6],
    speed2: [f64; 9],
    wg: [f64; 7],
    q: [f64; 8],
}

/// K of a rational cubic whose regularity is quickly proven (None otherwise, or when the
/// bound is out of range).
#[inline(always)]
fn rational_cubic_k(b: &[Point], w: &[f64]) -> Option<RationalCubicK> {
    let (k_bound, d_bound) = rational_cubic_bounds(b, w);
    if !(k_bound > 1e-280 && k_bound < 1e280) {
        return None;
    }
    // D1 = 3 Σ_{i,j<=2} B_i^2 B_j^2 w_i w_{j+1} (b_{j+1} - b_i), degree 4.
    let (mut dx, mut dy) = ([0.0f64; 5], [0.0f64; 5]);
    for i in 0..3 {
        for j in 0..3 {
            let c = binomial(2, i) * binomial(2, j) * w[i] * w[j + 1];
            let d = b[j + 1] - b[i];
            dx[i + j] += c * d.x;
            dy[i + j] += c * d.y;
        }
    }
    for l in 0..5 {
        let s = 3.0 / binomial(4, l);
        dx[l] *= s;
        dy[l] *= s;
    }
    // G = 18 Σ_{i,j,k<=1} B_i^1 B_j^1 B_k^1 w_i w_{j+1} w_{k+2} det(b_{j+1} - b_i, b_{k+2} - b_i).
    let mut g = [0.0f64; 4];
    for i in 0..2 {
        for j in 0..2 {
            for k in 0..2 {
                let c = w[i] * w[j + 1] * w[k + 2];
                let (u, v) = (b[j + 1] - b[i], b[k + 2] - b[i]);
                g[i + j + k] += c * u.cross(v);
            }
        }
    }
    for (l, v) in g.iter_mut().enumerate() {
        *v *= 18.0 / binomial(3, l);
    }
    let (mut wd, mut gd) = ([0.0f64; 3], [0.0f64; 3]);
    bernstein_deriv(w, &mut wd);
    bernstein_deriv(&g, &mut gd);
    // E = 3 W' G + W G' (degree 5), S = |D1|² (8), Q = D1 . D1' (7).
    let (mut e, mut t5) = ([0.0f64; 6], [0.0f64; 6]);
    bernstein_mul(&wd, &g, &mut e);
    bernstein_mul(w, &gd, &mut t5);
    for (a, b) in e.iter_mut().zip(&t5) {
        *a = 3.0 * *a + b;
    }
    let (mut speed2, mut t9) = ([0.0f64; 9], [0.0f64; 9]);
    bernstein_mul(&dx, &dx, &mut speed2);
    bernstein_mul(&dy, &dy, &mut t9);
    for (a, b) in speed2.iter_mut().zip(&t9) {
        *a += b;
    }
    let (mut dxd, mut dyd) = ([0.0f64; 4], [0.0f64; 4]);
    bernstein_deriv(&dx, &mut dxd);
    bernstein_deriv(&dy, &mut dyd);
    let (mut q, mut t8) = ([0.0f64; 8], [0.0f64; 8]);
    bernstein_mul(&dx, &dxd, &mut q);
    bernstein_mul(&dy, &dyd, &mut t8);
    for (a, b) in q.iter_mut().zip(&t8) {
        *a += b;
    }
    let mut wg = [0.0f64; 7];
    bernstein_mul(w, &g, &mut wg);
    // K = E S - 3 W G Q (degree 13).
    let (mut k, mut t14) = ([0.0f64; 14], [0.0f64; 14]);
    bernstein_mul(&e, &speed2, &mut k);
    bernstein_mul(&wg, &q, &mut t14);
    for (a, b) in k.iter_mut().zip(&t14) {
        *a -= 3.0 * b;
    }
    // Regularity, proven quickly or left to the certified test (D1 must not vanish).
    let hodograph: [Vec2; 5] = std::array::from_fn(|i| Vec2::new(dx[i], dy[i]));
    let scale = hodograph.iter().map(|h| h.hypot2()).fold(0.0, f64::max);
    let margin = DEGENERATE_SPEED_TOL * scale.sqrt();
    // Written so that a NaN margin fails too.
    let margin_ok = margin > 1e3 * d_bound;
    if !margin_ok || hodograph_vanishes(&hodograph, margin).is_some() {
        return None;
    }
    Some(RationalCubicK {
        k,
        k_bound,
        e,
        speed2,
        wg,
        q,
    })
}

impl RationalCubicK {
    /// K at 15 evenly spaced t (ends included): two values of strictly opposite signs, each
    /// beyond its rounding, prove a sign change. A value's error is at most the
    /// coefficients' bound (the value is a convex combination of them) plus the
    /// evaluation's rounding, a few ulps of the terms' magnitudes: 1e-8 of the size of the
    /// terms K is made of at that t, bounded by the Bernstein polynomial of their absolute
    /// coefficients, |E S| + 3 |W G Q| <= (|e| x |s| + 3 |wg| x |q|)(t), is far above that.
    fn samples_change_sign(&self) -> bool {
        let abs = |v: &[f64], out: &mut [f64]| {
            for (o, x) in out.iter_mut().zip(v) {
                *o = x.abs();
            }
        };
        let (mut ea, mut sa, mut wga, mut qa) =
            ([0.0f64; 6], [0.0f64; 9], [0.0f64; 7], [0.0f64; 8]);
        abs(&self.e, &mut ea);
        abs(&self.speed2, &mut sa);
        abs(&self.wg, &mut wga);
        abs(&self.q, &mut qa);
        let (mut size, mut t14) = ([0.0f64; 14], [0.0f64; 14]);
        bernstein_mul(&ea, &sa, &mut size);
        bernstein_mul(&wga, &qa, &mut t14);
        for (a, b) in size.iter_mut().zip(&t14) {
            *a += 3.0 * b;
        }
        let kmax = self.k.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let (mut pos, mut neg) = (false, false);
        for j in 0..=14 {
            let t = j as f64 / 14.0;
            let (v, sz) = (bernstein_eval13(&self.k, t), bernstein_eval13(&size, t));
            if v.abs() > 1e-8 * sz + 2.0 * self.k_bound + 64.0 * U * kmax {
                pos |= v > 0.0;
                neg |= v < 0.0;
            }
            if pos && neg {
                return true;
            }
        }
        false
    }
}

fn abs_diff(p: Point, q: Point) -> (f64, f64) {
    (p.x.abs() + q.x.abs(), p.y.abs() + q.y.abs())
}

/// Relative speed below which a curve counts as degenerate (|x'| <= TOL * scale).
pub const DEGENERATE_SPEED_TOL: f64 = 1e-8;

/// Whether some direction v has `v . h_i > margin` for all control vectors (then the
/// hodograph, their convex combination, stays at least `margin` long). The direction tried
/// is the mean of the unit control vectors.
fn cone_is_open(h: &[Vec2], margin: f64) -> bool {
    let mut s = Vec2::ZERO;
    for v in h {
        let l = v.hypot();
        if l <= margin {
            return false;
        }
        s += *v / l;
    }
    let l = s.hypot();
    if l < 1e-9 {
        return false;
    }
    let dir = s / l;
    h.iter().all(|v| dir.dot(*v) > margin)
}

/// A parameter where the hodograph (control vectors `h` on [a, b]) is at most `margin` long,
/// if any: subdivide until every piece's control vectors lie in an open cone.
fn hodograph_vanishes(h: &[Vec2], margin: f64) -> Option<f64> {
    if h.len() <= 8 {
        hodograph_vanishes_in::<8>(h, margin, 0.0, 1.0, 0)
    } else {
        hodograph_vanishes_in::<{ 2 * crate::bezier::MAX_BEZIER_DEGREE }>(h, margin, 0.0, 1.0, 0)
    }
}

fn hodograph_vanishes_in<const C: usize>(
    h: &[Vec2],
    margin: f64,
    a: f64,
    b: f64,
    depth: u32,
) -> Option<f64> {
    if h[0].hypot() <= margin {
        return Some(a);
    }
    if h[h.len() - 1].hypot() <= margin {
        return Some(b);
    }
    // Cheapest proofs first: one coordinate of the hodograph keeps a strict sign.
    if h.iter().all(|v| v.x > margin)
        || h.iter().all(|v| v.x < -margin)
        || h.iter().all(|v| v.y > margin)
        || h.iter().all(|v| v.y < -margin)
        || cone_is_open(h, margin)
    {
        return None;
    }
    let n = h.len();
    let (mut left, mut right, mut work) = ([Vec2::ZERO; C], [Vec2::ZERO; C], [Vec2::ZERO; C]);
    work[..n].copy_from_slice(h);
    left[0] = work[0];
    right[n - 1] = work[n - 1];
    for k in 1..n {
        for i in 0..n - k {
            work[i] = (work[i] + work[i + 1]) * 0.5;
        }
        left[k] = work[0];
        right[n - 1 - k] = work[n - 1 - k];
    }
    let mid = 0.5 * (a + b);
    if depth >= 44 {
        // A piece of width 2^-44 whose control vectors still span a half-plane: the value in
        // its middle decides.
        return (right[0].hypot() <= margin.max(1e-300)).then_some(mid);
    }
    hodograph_vanishes_in::<C>(&left[..n], margin, a, mid, depth + 1)
        .or_else(|| hodograph_vanishes_in::<C>(&right[..n], margin, mid, b, depth + 1))
}

/// The verdict: fast paths first (regular curves), then the certified test.
fn verdict(points: &[Point], weights: Option<&[f64]>) -> Result<bool> {
    let inp = certified::Input::new(points, weights)?;
    match fast_verdict(points, &inp) {
        Some(v) => Ok(v),
        None => certified::verdict(&inp),
    }
}

/// The fast paths' verdict, for curves whose handles are not retracted; None where they
/// cannot tell.
fn fast_verdict(points: &[Point], inp: &certified::Input) -> Option<bool> {
    if inp.retracted() {
        return None;
    }
    match fast(points, inp.weights())? {
        Fast::Monotone(_) => Some(true),
        Fast::NotMonotone => Some(false),
    }
}

/// The verdict where floating point proves it, `None` where only exact arithmetic could
/// decide: for searches that probe many candidates near the boundary of the monotone set
/// and may treat an undecided one as outside it (what they accept is still proven).
pub(crate) fn filtered_verdict(points: &[Point], weights: Option<&[f64]>) -> Result<Option<bool>> {
    let inp = certified::Input::new(points, weights)?;
    match fast_verdict(points, &inp) {
        Some(v) => Ok(Some(v)),
        None => certified::filtered_verdict(&inp),
    }
}

fn fast(points: &[Point], weights: Option<&[f64]>) -> Option<Fast> {
    match weights {
        None => poly_fast(points),
        Some(w) if points.len() == 4 => rational_cubic_fast(points, w),
        Some(_) => None,
    }
}

/// The full report: a fast proof of monotonicity needs no extrema; anything else is located
/// by the certified test.
fn report(
    points: &[Point],
    weights: Option<&[f64]>,
    kappa: impl Fn(f64) -> f64,
) -> Result<MonotoneReport> {
    let inp = certified::Input::new(points, weights)?;
    if !inp.retracted() {
        if let Some(Fast::Monotone(sign)) = fast(points, inp.weights()) {
            return Ok(MonotoneReport {
                monotone: true,
                trend: Some(if sign > 0 {
                    Trend::Increasing
                } else {
                    Trend::Decreasing
                }),
                extrema: Vec::new(),
                test_degree: inp.test_degree(),
                exact: false,
                ends: [
                    EndCurvature::Regular(kappa(0.0)),
                    EndCurvature::Regular(kappa(1.0)),
                ],
            });
        }
    }
    // The certified test locates the extrema (the fast path's one loose bound is too wide
    // to place them).
    certified::report(&inp)
}

/// Curves the monotonicity tests apply to.
pub trait CurvatureMonotone: PlanarCurve {
    /// The numerator of dkappa/ds in Bernstein form, in floating point with rounding bounds
    /// (for plots and inspection; the verdicts come from the certified test).
    fn curvature_variation(&self) -> CurvatureVariation;

    /// The exact test with the curvature extrema located (within 1e-12 in t) and the end
    /// curvatures: exact for the given f64 control points (and weights).
    fn curvature_monotone(&self) -> Result<MonotoneReport>;

    /// The exact test's verdict only (stops at the first proof of non-monotonicity).
    fn is_curvature_monotone(&self) -> Result<bool>;

    /// The sampling test of S1 §3.1 with `samples` divisions (at least 1).
    fn curvature_monotone_sampled(&self, samples: usize) -> Result<SampledReport> {
        sampled(|t| self.kappa(t), samples)
    }

    /// The parameters in (0, 1) where the curvature changes sign (inflections), sorted, each
    /// within 1e-12: exact for the given f64 inputs, as the verdict is.
    fn inflections(&self) -> Result<Vec<f64>>;
}

impl CurvatureMonotone for Bezier {
    fn curvature_variation(&self) -> CurvatureVariation {
        curvature_variation(self)
    }
    fn curvature_monotone(&self) -> Result<MonotoneReport> {
        report(self.points(), None, |t| self.kappa(t))
    }
    fn is_curvature_monotone(&self) -> Result<bool> {
        verdict(self.points(), None)
    }
    fn inflections(&self) -> Result<Vec<f64>> {
        certified::inflections(&certified::Input::new(self.points(), None)?)
    }
    fn curvature_monotone_sampled(&self, samples: usize) -> Result<SampledReport> {
        let k = KappaSampler::new(self);
        sampled(|t| k.kappa(t), samples)
    }
}

impl CurvatureMonotone for RationalBezier {
    fn curvature_variation(&self) -> CurvatureVariation {
        curvature_variation_rational(self)
    }
    fn curvature_monotone(&self) -> Result<MonotoneReport> {
        report(self.points(), Some(self.weights()), |t| self.kappa(t))
    }
    fn is_curvature_monotone(&self) -> Result<bool> {
        verdict(self.points(), Some(self.weights()))
    }
    fn inflections(&self) -> Result<Vec<f64>> {
        certified::inflections(&certified::Input::new(self.points(), Some(self.weights()))?)
    }
}

/// Curvature of a polynomial curve from its precomputed first and second hodographs: what
/// the sampling test evaluates N + 1 times (no allocation, no third derivative).
struct KappaSampler {
    n: usize,
    h1: [Vec2; crate::bezier::MAX_BEZIER_DEGREE],
    h2: [Vec2; crate::bezier::MAX_BEZIER_DEGREE],
}

impl KappaSampler {
    fn new(curve: &Bezier) -> Self {
        let b = curve.points();
        let n = b.len() - 1;
        let mut h1 = [Vec2::ZERO; crate::bezier::MAX_BEZIER_DEGREE];
        let mut h2 = [Vec2::ZERO; crate::bezier::MAX_BEZIER_DEGREE];
        for i in 0..n {
            h1[i] = (b[i + 1] - b[i]) * n as f64;
        }
        for i in 0..n.saturating_sub(1) {
            h2[i] = (h1[i + 1] - h1[i]) * (n - 1) as f64;
        }
        KappaSampler { n, h1, h2 }
    }

    #[inline]
    fn casteljau(mut v: [Vec2; crate::bezier::MAX_BEZIER_DEGREE], len: usize, t: f64) -> Vec2 {
        if len == 0 {
            return Vec2::ZERO;
        }
        let s = 1.0 - t;
        for k in 1..len {
            for i in 0..len - k {
                v[i] = v[i] * s + v[i + 1] * t;
            }
        }
        v[0]
    }

    #[inline]
    fn kappa(&self, t: f64) -> f64 {
        let d1 = Self::casteljau(self.h1, self.n, t);
        let d2 = Self::casteljau(self.h2, self.n.saturating_sub(1), t);
        let s = d1.hypot();
        d1.cross(d2) / (s * s * s)
    }
}

fn sampled(f: impl Fn(f64) -> f64, samples: usize) -> Result<SampledReport> {
    if samples == 0 {
        return Err(Error::invalid("samples", "need at least 1 division"));
    }
    let inv = 1.0 / samples as f64;
    let mut prev = f(0.0);
    if !prev.is_finite() {
        return Err(Error::Degenerate(
            "curvature is undefined at t = 0 (vanishing tangent)".into(),
        ));
    }
    let (mut up, mut down) = (false, false);
    for i in 1..=samples {
        let t = i as f64 * inv;
        let k = f(t);
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
        prev = k;
    }
    let trend = match (up, down) {
        (true, true) => None,
        (true, false) => Some(Trend::Increasing),
        (false, true) => Some(Trend::Decreasing),
        (false, false) => Some(Trend::Constant),
    };
    Ok(SampledReport {
        monotone: trend.is_some(),
        trend,
        samples,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_test_degree_is_the_degree_the_test_runs() {
        // Generic curves (no retracted handle, distinct weights) of degrees 2 to 7: the
        // report's degree of K̃ is the one the editor's work budget assumes.
        for n in 2..=7usize {
            let pts: Vec<Point> = (0..=n)
                .map(|i| {
                    let t = i as f64;
                    Point::new(
                        t * 10.0 + (t * 1.3).sin(),
                        (t * 0.7).cos() * 7.0 + t * t * 0.3,
                    )
                })
                .collect();
            let poly = Bezier::new(pts.clone())
                .unwrap()
                .curvature_monotone()
                .unwrap();
            assert_eq!(poly.test_degree, exact_test_degree(n, false), "degree {n}");
            let w: Vec<f64> = (0..=n).map(|i| 1.0 + 0.25 * (i % 3) as f64).collect();
            let rat = RationalBezier::new(pts, w)
                .unwrap()
                .curvature_monotone()
                .unwrap();
            assert_eq!(
                rat.test_degree,
                exact_test_degree(n, true),
                "rational degree {n}"
            );
        }
    }

    fn bez(v: &[(f64, f64)]) -> Bezier {
        Bezier::new(v.iter().map(|&(x, y)| Point::new(x, y)).collect()).unwrap()
    }

    #[test]
    fn rational_cubic_fast_path_agrees_with_the_full_test() {
        // Random rational cubics (weights 0.1 to 10) and ones near the monotone boundary
        // (the LAC family, where the optimiser probes): the fast verdict, when it gives
        // one, is the full test's.
        let mut curves = crate::samples::random_rational_curves(3, 20000, 77);
        let seg = crate::lac::LacSegment::new(
            -1.0,
            [
                Point::new(0.0, 0.0),
                Point::new(10.0, 0.0),
                Point::new(16.0, 9.0),
            ],
        )
        .unwrap();
        for i in 1..100 {
            for j in 1..100 {
                if let Ok(c) = crate::approx::construct(&seg, i as f64 / 100.0, j as f64 / 100.0) {
                    curves.push(c);
                }
            }
        }
        let mut fast = 0;
        for c in &curves {
            let full = certified::Input::new(c.points(), Some(c.weights()))
                .and_then(|inp| certified::verdict(&inp));
            if let Some(v) = rational_cubic_fast(c.points(), c.weights()) {
                fast += 1;
                match (v, &full) {
                    (Fast::Monotone(_), Ok(true)) | (Fast::NotMonotone, Ok(false)) => {}
                    (a, b) => panic!("{c:?}: fast {a:?}, full {b:?}"),
                }
            }
            assert_eq!(
                c.is_curvature_monotone().ok(),
                full.as_ref().ok().copied(),
                "{c:?}"
            );
        }
        let monotone = curves
            .iter()
            .filter(|c| c.is_curvature_monotone().unwrap_or(false))
            .count();
        println!(
            "fast verdicts: {fast} of {} ({monotone} monotone)",
            curves.len()
        );
        assert!(fast > curves.len() / 2, "{fast} of {}", curves.len());
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
    fn lines_are_constant_and_f64_arcs_are_what_they_are() {
        let line = bez(&[(0.0, 0.0), (1.0, 1.0), (2.5, 2.5), (3.0, 3.0)]);
        let r = line.curvature_monotone().unwrap();
        assert!(r.monotone);
        assert_eq!(r.trend, Some(Trend::Constant));
        // The f64 weight 0.7071067811865476 is not 1/√2: the symmetric conic is an ellipse
        // arc, whose curvature has its extremum at the middle (by a relative 1e-16). The
        // exact test says so, and says the same after degree elevation (exact: the weights
        // and points of an elevation by 1/2 and 1/3 are not exact in f64, so the elevated
        // curve is another curve, decided on its own).
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
        let r = arc.curvature_monotone().unwrap();
        assert!(!r.monotone && r.extrema.len() == 1, "{r:?}");
        assert!((r.extrema[0] - 0.5).abs() < 1e-12, "{r:?}");
        let k = arc.kappa(0.5);
        assert!((k - arc.kappa(0.0)).abs() < 1e-15);
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

    /// A cubic spanning 600 orders of magnitude: its start curvature (6e298) was reported
    /// as null, from z2³ overflowing in the scaled frame. Against the end formula
    /// `κ(0) = (2/3) (p1 - p0) × (p2 - p1) / |p1 - p0|³`, in f64 with no overflow at this
    /// size; and a unit cubic scaled by 2^±1000 has its end curvatures scaled by 2^∓1000.
    #[test]
    fn end_curvatures_of_curves_spanning_hundreds_of_orders_are_finite() {
        let c = bez(&[
            (-1.0, 1e-300),
            (1.0, -1.0),
            (1e300, 0.33530130125527186),
            (1e-300, -1e300),
        ]);
        let r = c.curvature_monotone().unwrap();
        let p = c.points();
        let (a, b) = (p[1] - p[0], p[2] - p[1]);
        let want = 2.0 / 3.0 * a.cross(b) / a.hypot().powi(3);
        let got = r.ends[0].value().unwrap();
        assert!((got - want).abs() <= 1e-12 * want.abs(), "{got} vs {want}");
        assert!(r.ends[1].value().unwrap().is_finite());
        // Found by the protocol's fuzz: δ's first coefficient underflows in the scaled frame
        // (κ(0) = 2.2e-303) and came back null; κ(1) = 3e-898 is 0 in f64.
        let c = bez(&[
            (0.0, 0.0),
            (29.85647403695823, 0.0),
            (0.0, 1e-300),
            (1e300, -11.21044018764352),
        ]);
        let r = c.curvature_monotone().unwrap();
        let p = c.points();
        let (a, b) = (p[1] - p[0], p[2] - p[1]);
        let want = 2.0 / 3.0 * (a.x * b.y) / a.hypot().powi(3);
        let got = r.ends[0].value().unwrap();
        assert!((got - want).abs() <= 1e-12 * want.abs(), "{got} vs {want}");
        assert_eq!(r.ends[1].value(), Some(0.0));
        // δ(0) = 1e-320 in the scaled frame, a subnormal with a known sign and a few digits:
        // κ(0) = (2/3) b.y / a.x² = 6.7e159, to 1e-12.
        let c = bez(&[(0.0, 0.0), (1e-160, 0.0), (1.0, 1e-160), (2.0, 1.0)]);
        let r = c.curvature_monotone().unwrap();
        let want = 2.0 / 3.0 * (1e-160 / 1e-160) / 1e-160;
        let got = r.ends[0].value().unwrap();
        assert!((got - want).abs() <= 1e-12 * want, "{got} vs {want}");
        let unit = bez(&[(0.0, 0.0), (1.0, 0.2), (2.0, 1.5), (2.5, 3.0)]);
        let ends = |c: &Bezier| {
            let r = c.curvature_monotone().unwrap();
            [r.ends[0].value().unwrap(), r.ends[1].value().unwrap()]
        };
        let base = ends(&unit);
        for k in [1000, -1000] {
            let s = 2f64.powi(k);
            let scaled = Bezier::new(
                unit.points()
                    .iter()
                    .map(|q| Point::new(q.x * s, q.y * s))
                    .collect(),
            )
            .unwrap();
            for (got, b) in ends(&scaled).into_iter().zip(base) {
                let want = b / s;
                assert!(
                    got.is_finite() && (got - want).abs() <= 1e-12 * want.abs(),
                    "2^{k}: {got} vs {want}"
                );
            }
        }
    }

    #[test]
    fn certified_end_curvatures_are_the_curvatures_at_the_ends() {
        // Regular ends: the certified report's value is κ(0) and κ(1), at any scale and
        // weights; a retracted end's finite limit is the limit of κ.
        let mut curves = crate::samples::random_rational_curves(3, 200, 5);
        for c in &mut curves {
            let s = 1e3;
            let p: Vec<Point> = c
                .points()
                .iter()
                .map(|q| Point::new(q.x * s + 7.0, q.y * s))
                .collect();
            *c = RationalBezier::new(p, c.weights().iter().map(|w| w * 3.0).collect()).unwrap();
        }
        for c in &curves {
            let inp = certified::Input::new(c.points(), Some(c.weights())).unwrap();
            let Ok(r) = certified::report(&inp) else {
                continue;
            };
            for (e, t) in r.ends.iter().zip([0.0, 1.0]) {
                let (k, want) = (e.value().unwrap(), c.kappa(t));
                assert!(
                    (k - want).abs() <= 1e-9 * want.abs().max(1e-12),
                    "{c:?}: {k} vs {want}"
                );
            }
        }
        // A cubic with a retracted handle has unbounded curvature there unless it is
        // straight; a quartic whose next two control points continue the end's tangent has a
        // finite nonzero limit (δ vanishes there as fast as the speed).
        let c = bez(&[(0.0, 0.0), (0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (3.0, 1.0)]);
        let r = c.curvature_monotone().unwrap();
        assert!(matches!(r.ends[0], EndCurvature::Finite { .. }), "{r:?}");
        let lim = r.ends[0].value().unwrap();
        assert!(
            (lim - c.kappa(1e-7)).abs() < 1e-5 * lim.abs().max(1.0),
            "{lim} {}",
            c.kappa(1e-7)
        );
    }

    /// Integer control points whose K has exact zero coefficients (a parabola's vertex, a
    /// circle's identically zero K): the filter knows those zeros are zeros, so these common
    /// shapes never pay for the exact stage (a division by a binomial that is exact keeps
    /// its bound at 0).
    #[test]
    fn exact_zeros_are_decided_by_the_filter() {
        let parabola = bez(&[(0.0, 0.0), (1.0, 0.0), (2.0, 1.0), (3.0, 3.0)]);
        let r = parabola.curvature_monotone().unwrap();
        assert!(
            r.monotone && r.trend == Some(Trend::Decreasing) && !r.exact,
            "{r:?}"
        );
        let circle = RationalBezier::new(
            bez(&[(0.0, 0.0), (3.0, 4.0), (6.0, 0.0)]).points().to_vec(),
            vec![5.0, 3.0, 5.0],
        )
        .unwrap();
        let r = circle.curvature_monotone().unwrap();
        assert!(
            r.monotone && r.trend == Some(Trend::Constant) && !r.exact,
            "{r:?}"
        );
    }

    #[test]
    fn retracted_handles_get_a_verdict_and_cusps_are_errors() {
        // One handle on its point: the speed vanishes like t, the curvature like 1/t.
        let retracted = bez(&[(0.0, 0.0), (0.0, 0.0), (1.0, 1.0), (2.0, 0.0)]);
        let r = retracted.curvature_monotone().unwrap();
        assert!(
            matches!(r.ends[0], EndCurvature::Unbounded { rate: 1, .. }),
            "{r:?}"
        );
        assert!(matches!(r.ends[1], EndCurvature::Regular(_)), "{r:?}");
        // A straight line with retracted handles: curvature 0 throughout.
        let line = bez(&[(0.0, 0.0), (0.0, 0.0), (1.0, 0.0), (2.0, 0.0)]);
        let r = line.curvature_monotone().unwrap();
        assert!(r.monotone && r.trend == Some(Trend::Constant), "{r:?}");
        assert_eq!(
            r.ends[0],
            EndCurvature::Finite {
                curvature: 0.0,
                order: 1
            }
        );
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
#[cfg(test)]
mod fast_path {
    /// The fast path decides every generic random curve (the certified test is for the
    /// near-degenerate ones): it is what keeps the verdict at its old speed.
    #[test]
    fn decides_generic_curves() {
        for d in [3, 5] {
            let cs = crate::samples::random_curves(d, 2000, 2024);
            let (mut m, mut n, mut none) = (0, 0, 0);
            for c in &cs {
                match super::poly_fast(c.points()) {
                    Some(super::Fast::Monotone(_)) => m += 1,
                    Some(super::Fast::NotMonotone) => n += 1,
                    None => none += 1,
                }
            }
            println!("degree {d}: monotone {m}, not {n}, undecided {none}");
            assert_eq!(none, 0, "degree {d}");
        }
    }
}
