//! The certified verdict: dκ/ds's sign on (0, 1) decided for the exact f64 inputs.
//!
//! One formula, written once over [`Ring`], runs on [`Bounded`] floats (the filter) and,
//! where those cannot decide, on big integers (the inputs are dyadic, so exactly). It works
//! on `z`, the hodograph with its vanishing ends divided out:
//!
//! - the hodograph `D1` is `x'` (polynomial) or `W P' - P W'` (rational, `= W² x'`), and
//!   `D1 = φ z` with `φ = t^r (1 - t)^s`, where `r` (`s`) counts the control points that
//!   coincide with the first (last) one beyond it: a retracted handle. In scaled Bernstein
//!   form dividing by `t` or `1 - t` is dropping an exact zero end coefficient;
//! - `δ = det(z, z')`, `K_z = (2 W' δ + W δ') |z|² - 3 W δ (z·z')` (W = 1 for a polynomial
//!   curve), and
//!   `K̃ = t^[r>0] (1-t)^[s>0] K_z - (r (1 - t) - s t)/(...) W δ |z|²` (docs/math.md §2.4):
//!   `dκ/ds = φ⁴ K̃ / (t^[r>0] (1-t)^[s>0] W³ |D1|⁶)` up to a positive constant, so K̃ has the
//!   sign of dκ/ds on (0, 1). With `r = s = 0` it is the usual numerator (degree 4n - 7 for
//!   a polynomial curve of degree n; for a rational one `W K`, from
//!   `det(D1, D1') = W det(H, H', H'')`).
//!
//! The curvature is `κ = W² δ / (m n φ |z|³)` (`m` the degree of z): at a retracted end it
//! is unbounded when δ vanishes there to a lower order than φ, finite otherwise.

use super::{EndCurvature, MonotoneReport, Trend};
use crate::error::{Error, Result};
use crate::exact::ring::{self, Scaled};
use crate::exact::{certified_signs, dyadic_integers, poly, Bounded, Ring, Want};
use kurbo::Point;
use num_bigint::BigInt;

/// The curve as the formula sees it: control points, optional weights, retracted ends.
pub(super) struct Input<'a> {
    points: &'a [Point],
    weights: Option<&'a [f64]>,
    /// Control points after the first that coincide with it (`b_0 = ... = b_r`).
    r: usize,
    /// The same at the end.
    s: usize,
}

impl<'a> Input<'a> {
    /// `Err(Degenerate)` for a curve that is a single point.
    pub(super) fn new(points: &'a [Point], weights: Option<&'a [f64]>) -> Result<Self> {
        let n = points.len() - 1;
        let r = points[1..].iter().take_while(|p| **p == points[0]).count();
        if r == n {
            return Err(Error::Degenerate(
                "all control points coincide: the curve is a point".into(),
            ));
        }
        let s = points[..n]
            .iter()
            .rev()
            .take_while(|p| **p == points[n])
            .count();
        // Weights all equal: the polynomial curve itself.
        let weights = weights.filter(|w| w.iter().any(|v| *v != w[0]));
        Ok(Input {
            points,
            weights,
            r,
            s,
        })
    }

    fn degree(&self) -> usize {
        self.points.len() - 1
    }

    /// The weights, None for a polynomial curve (or one whose weights are all equal).
    pub(super) fn weights(&self) -> Option<&'a [f64]> {
        self.weights
    }

    /// The degree of K̃ (see the module docs).
    pub(super) fn test_degree(&self) -> usize {
        k_degree(self.degree(), self.weights.is_some(), (self.r, self.s))
    }

    /// Whether an end's speed vanishes.
    pub(super) fn retracted(&self) -> bool {
        self.r > 0 || self.s > 0
    }
}

/// The degree of K̃ for a curve of degree `n` (rational or not) whose ends have `r` and `s`
/// retracted handles.
pub(super) fn k_degree(n: usize, rational: bool, (r, s): (usize, usize)) -> usize {
    let (m, w) = if rational {
        (2 * n - 2 - r - s, n)
    } else {
        (n - 1 - r - s, 0)
    };
    if m == 0 {
        return 0;
    }
    w + 4 * m - 3 + usize::from(r > 0) + usize::from(s > 0)
}

/// z and W over a ring, from the control points' differences `diff(j, i) = b_j - b_i` and
/// the weights.
struct Lifted<R> {
    zx: Scaled<R>,
    zy: Scaled<R>,
    w: Option<Scaled<R>>,
    /// The factor the coordinates were scaled by (a power of two; 1 for exact integers,
    /// whose scale does not matter): curvatures computed from these are the true ones
    /// divided by it.
    length_scale: f64,
}

/// C(n, k) for the small n here (at most twice a curve's degree, so exact).
fn binom(n: usize, k: usize) -> i64 {
    crate::exact::binomial(n, k) as i64
}

fn lift<R: Ring>(inp: &Input, diff: impl Fn(usize, usize) -> (R, R), w: Option<&[R]>) -> Lifted<R> {
    let n = inp.degree();
    let (r, s) = (inp.r, inp.s);
    match w {
        None => {
            // x' = n Σ C(n-1, i) (b_{i+1} - b_i) t^i (1-t)^{n-1-i}; z drops n and φ.
            let (zx, zy) = (r..n - s)
                .map(|i| {
                    let (dx, dy) = diff(i + 1, i);
                    let c = binom(n - 1, i);
                    (dx.mul_int(c), dy.mul_int(c))
                })
                .unzip();
            Lifted {
                zx,
                zy,
                w: None,
                length_scale: 1.0,
            }
        }
        Some(w) => {
            // D1 = n Σ_{i,j} C(n-1,i) C(n-1,j) w_i w_{j+1} (b_{j+1} - b_i) t^{i+j} (1-t)^{..}.
            let deg = 2 * (n - 1);
            let mut x: Scaled<R> = (0..=deg).map(|_| R::zero()).collect();
            let mut y = x.clone();
            for i in 0..n {
                for j in 0..n {
                    let (dx, dy) = diff(j + 1, i);
                    let c = w[i]
                        .mul(&w[j + 1])
                        .mul_int(binom(n - 1, i) * binom(n - 1, j));
                    x[i + j] = x[i + j].add(&c.mul(&dx));
                    y[i + j] = y[i + j].add(&c.mul(&dy));
                }
            }
            let ws = w
                .iter()
                .enumerate()
                .map(|(i, v)| v.mul_int(binom(n, i)))
                .collect();
            Lifted {
                zx: x[r..=deg - s].iter().cloned().collect(),
                zy: y[r..=deg - s].iter().cloned().collect(),
                w: Some(ws),
                length_scale: 1.0,
            }
        }
    }
}

/// `δ̃ = m det(z, z')` from z's two sub-polygons (degree 2m - 2), and `z' = B̃ - Ã`.
fn delta<R: Ring>(l: &Lifted<R>) -> (Scaled<R>, Scaled<R>, Scaled<R>) {
    let m = l.zx.len() - 1;
    let sub = |z: &[R]| -> (Scaled<R>, Scaled<R>) {
        (
            (0..m).map(|i| z[i].mul_int((m - i) as i64)).collect(),
            (0..m).map(|i| z[i + 1].mul_int(i as i64 + 1)).collect(),
        )
    };
    let (ax, bx) = sub(&l.zx);
    let (ay, by) = sub(&l.zy);
    let d = ring::sub(&ring::conv(&ax, &by), &ring::conv(&ay, &bx));
    (d, ring::sub(&bx, &ax), ring::sub(&by, &ay))
}

/// K̃ (see the module docs); the zero constant for a straight segment (z constant).
fn k_tilde<R: Ring>(inp: &Input, l: &Lifted<R>) -> Scaled<R> {
    let m = l.zx.len() - 1;
    if m == 0 {
        return smallvec::smallvec![R::zero()];
    }
    let (d, zpx, zpy) = delta(l);
    let speed2 = ring::add(&ring::conv(&l.zx, &l.zx), &ring::conv(&l.zy, &l.zy));
    let q = ring::add(&ring::conv(&l.zx, &zpx), &ring::conv(&l.zy, &zpy));
    // (2 W' δ + W δ') (or δ'), then times |z|², minus 3 W δ (z·z').
    let (lead, wd) = match &l.w {
        None => ((m > 1).then(|| ring::deriv(&d)), d.clone()),
        Some(w) => {
            let wp = ring::scale(&ring::conv(&ring::deriv(w), &d), 2);
            let lead = if m > 1 {
                ring::add(&wp, &ring::conv(w, &ring::deriv(&d)))
            } else {
                wp
            };
            (Some(lead), ring::conv(w, &d))
        }
    };
    let tail = ring::scale(&ring::conv(&wd, &q), 3);
    let kz = match lead {
        Some(lead) => ring::sub(&ring::conv(&lead, &speed2), &tail),
        None => tail.iter().map(|v| R::zero().sub(v)).collect(),
    };
    let (r, s) = (inp.r as i64, inp.s as i64);
    if r == 0 && s == 0 {
        return kz;
    }
    let wds = ring::conv(&wd, &speed2);
    match (r > 0, s > 0) {
        (true, false) => ring::sub(&ring::times_linear(&kz, 0, 1), &ring::scale(&wds, r)),
        (false, true) => ring::add(&ring::times_linear(&kz, 1, 0), &ring::scale(&wds, s)),
        _ => ring::sub(
            &ring::times_linear(&ring::times_linear(&kz, 0, 1), 1, 0),
            &ring::times_linear(&wds, r, -s),
        ),
    }
}

/// The inputs as bounded floats, scaled by powers of two so that nothing overflows or
/// underflows on the way (exact, apart from values that become subnormal: their bound says so).
fn bounded(inp: &Input) -> Lifted<Bounded> {
    let p = inp.points;
    let n = p.len();
    let mut d = vec![(Bounded::exact(0.0), Bounded::exact(0.0)); n * n];
    let mut big = 0.0f64;
    // Coordinates near the top of the range are halved first, so that their differences do
    // not overflow (halving is exact, apart from a subnormal's last bit: its bound says so).
    let huge = p
        .iter()
        .any(|q| q.x.abs().max(q.y.abs()) >= 2f64.powi(1022));
    let half = if huge { 0.5 } else { 1.0 };
    let halved_diff = |a: f64, b: f64| {
        let (ha, hb) = (a * half, b * half);
        let mut d = Bounded::diff(ha, hb);
        if ha / half != a || hb / half != b {
            d.e += 2.0 * f64::from_bits(1);
        }
        d
    };
    for j in 0..n {
        for i in 0..n {
            let v = (halved_diff(p[j].x, p[i].x), halved_diff(p[j].y, p[i].y));
            big = big.max(v.0.v.abs()).max(v.1.v.abs());
            d[j * n + i] = v;
        }
    }
    let k = pow2_normaliser(big);
    let diff = |j: usize, i: usize| {
        let (x, y) = d[j * n + i];
        (times_pow2(x, k), times_pow2(y, k))
    };
    let w: Option<Vec<Bounded>> = inp.weights.map(|w| {
        let kw = pow2_normaliser(w.iter().fold(0.0f64, |m, v| m.max(*v)));
        w.iter()
            .map(|v| times_pow2(Bounded::exact(*v), kw))
            .collect()
    });
    Lifted {
        length_scale: 2f64.powi(k.clamp(-1000, 1000)) * half,
        ..lift(inp, diff, w.as_deref())
    }
}

/// Whether a bounded coefficient carries the digits of a curvature reported to about
/// 1e-12: a normal value whose bound is that small beside it.
fn accurate(c: &Bounded) -> bool {
    c.v.abs() >= f64::MIN_POSITIVE && c.e <= 1e-13 * c.v.abs()
}

/// The curvature at a regular end from the closed form
/// `κ(0) = (n-1)/n · w0 w2 / w1² · (b1 - b0) × (b2 - b1) / |b1 - b0|³` (at t = 1 the same
/// with the last three points, `(b_{n-1} - b_{n-2}) × (b_n - b_{n-1})`), the cross product
/// and the squared length in exact integers, rounded to f64 once each.
fn regular_end_exactly(inp: &Input, start: bool) -> f64 {
    let (p, n) = (inp.points, inp.points.len() - 1);
    let idx = if start { [0, 1, 2] } else { [n - 2, n - 1, n] };
    let coords: Vec<f64> = idx.iter().flat_map(|&i| [p[i].x, p[i].y]).collect();
    let (c, e) = crate::exact::dyadic_integers(&coords);
    let (ux, uy) = (&c[2] - &c[0], &c[3] - &c[1]);
    let (vx, vy) = (&c[4] - &c[2], &c[5] - &c[3]);
    let cross = &ux * &vy - &uy * &vx;
    // The end's handle: b1 - b0 at the start, b_n - b_{n-1} at the end.
    let len2 = if start {
        &ux * &ux + &uy * &uy
    } else {
        &vx * &vx + &vy * &vy
    };
    let (cm, ce) = big_split_pow2(&cross);
    let (mut lm, mut le) = big_split_pow2(&len2);
    if le % 2 != 0 {
        lm *= 2.0;
        le -= 1;
    }
    let w = inp
        .weights
        .map_or([1.0; 3], |w| [w[idx[0]], w[idx[1]], w[idx[2]]]);
    let mut mant = (n - 1) as f64 / n as f64 * cm / (lm * lm.sqrt());
    // cross and len2 are in units of 2^(2e): κ is in units of 2^(-e).
    let mut exp = ce - 3 * le / 2 - e as i64;
    for (f, sign) in [(w[0], 1), (w[2], 1), (w[1], -2)] {
        let (m, x) = split_pow2(f);
        mant *= if sign > 0 { m } else { 1.0 / (m * m) };
        exp += sign * x;
    }
    times_pow2_wide(mant, exp)
}

/// A big integer as `m · 2^e` with `1 <= |m| < 2`, `m` rounded to 53 bits (0 as (0, 0)).
fn big_split_pow2(v: &BigInt) -> (f64, i64) {
    use num_traits::ToPrimitive;
    let bits = v.bits() as i64;
    if bits == 0 {
        return (0.0, 0);
    }
    let drop = (bits - 64).max(0);
    let top = (v >> drop as usize).to_f64().unwrap_or(0.0);
    let (m, e) = split_pow2(top);
    (m, e + drop)
}

/// `x = m · 2^e` with `1 <= |m| < 2` (subnormals included); zero and non-finite `x` as
/// they are, with `e = 0`.
fn split_pow2(x: f64) -> (f64, i64) {
    if x == 0.0 || !x.is_finite() {
        return (x, 0);
    }
    let bits = x.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i64;
    if biased == 0 {
        let (m, e) = split_pow2(x * 2f64.powi(64));
        return (m, e - 64);
    }
    let m = f64::from_bits((bits & !(0x7ff << 52)) | (1023 << 52));
    (m, biased - 1023)
}

/// `x · 2^e` for any `e`, rounded once: ±inf or 0 only where the true value is out of range.
fn times_pow2_wide(mut x: f64, mut e: i64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    while e > 1000 && x.is_finite() && x != 0.0 {
        x *= 2f64.powi(1000);
        e -= 1000;
    }
    while e < -1000 && x != 0.0 {
        // Down to the smallest normal first, then the rest in one rounding.
        let step = e.max(-1000);
        let normal = split_pow2(x).1 + step >= -1022;
        if !normal {
            break;
        }
        x *= 2f64.powi(step as i32);
        e -= step;
    }
    x * 2f64.powi(e.clamp(-1100, 1100) as i32)
}

/// The power of two that brings `big` near 1 when it is far from it (0 between 2^-20 and
/// 2^40, where nothing can overflow or underflow; 0 for zero or non-finite values).
fn pow2_normaliser(big: f64) -> i32 {
    if big > 0.0 && big.is_finite() && !(2f64.powi(-20)..=2f64.powi(40)).contains(&big) {
        -(big.log2().floor() as i32)
    } else {
        0
    }
}

fn times_pow2(b: Bounded, k: i32) -> Bounded {
    let f = 2f64.powi(k.clamp(-1000, 1000));
    let (v, e) = (b.v * f, b.e * f);
    // Exact unless a result lands below the normal range: rounded there by at most 2^-1075,
    // to zero included (a nonzero value that underflows to 0 is not a known zero).
    let rounded = |x: f64, was: f64| was != 0.0 && x.abs() < f64::MIN_POSITIVE;
    let tiny = if rounded(v, b.v) || rounded(e, b.e) {
        2.0 * f64::from_bits(1)
    } else {
        0.0
    };
    Bounded { v, e: e + tiny }
}

/// The inputs as exact integers (all coordinates share one power of two, the weights
/// another: positive factors that change no sign).
fn exact(inp: &Input) -> Lifted<BigInt> {
    let p = inp.points;
    let coords: Vec<f64> = p.iter().flat_map(|q| [q.x, q.y]).collect();
    let (ints, _) = dyadic_integers(&coords);
    let diff = |j: usize, i: usize| {
        (
            &ints[2 * j] - &ints[2 * i],
            &ints[2 * j + 1] - &ints[2 * i + 1],
        )
    };
    let w = inp.weights.map(|w| dyadic_integers(w).0);
    lift(inp, diff, w.as_deref())
}

/// Whether the floating-point filter proves z nonzero on [0, 1]: its control vectors
/// known well within the margin, and no zero of the hodograph within it.
fn regular_by_filter(b: &Lifted<Bounded>) -> bool {
    let m = b.zx.len() - 1;
    let h: Vec<kurbo::Vec2> = (0..=m)
        .map(|i| {
            let c = binom(m, i) as f64;
            kurbo::Vec2::new(b.zx[i].v / c, b.zy[i].v / c)
        })
        .collect();
    let scale = h.iter().map(|v| v.hypot2()).fold(0.0, f64::max);
    let err = (0..=m)
        .map(|i| (b.zx[i].e + b.zy[i].e) / binom(m, i) as f64)
        .fold(0.0, f64::max);
    let margin = super::DEGENERATE_SPEED_TOL * scale.sqrt();
    scale.is_finite()
        && scale > 0.0
        && err * 1e3 < margin
        && super::hodograph_vanishes(&h, margin).is_none()
}

/// `Err(Degenerate)` when z vanishes inside (0, 1): a cusp or a curve that turns back.
fn check_regular(inp: &Input, b: &Lifted<Bounded>) -> Result<()> {
    if regular_by_filter(b) {
        return Ok(());
    }
    let m = b.zx.len() - 1;
    // Exactly: a common root of z's components in (0, 1) (z's ends are not zero).
    over_budget(
        predicted_cost(inp, 3 * m) > crate::exact::signs::EXACT_BUDGET,
        m,
    )?;
    let e = exact(inp);
    let bits =
        e.zx.iter()
            .chain(&e.zy)
            .map(|v| v.bits())
            .max()
            .unwrap_or(0) as f64;
    let d = e.zx.len() as f64;
    over_budget(
        d * d * d * bits > crate::exact::signs::EXACT_BUDGET,
        e.zx.len() - 1,
    )?;
    let g = poly::IntPoly::new(e.zx.to_vec()).gcd(&poly::IntPoly::new(e.zy.to_vec()));
    match poly::roots(g.coeffs()).first() {
        Some(t) => Err(Error::Degenerate(format!(
            "the tangent vanishes at t = {t:.9}, inside the segment (a cusp, or the curve \
             turns back on itself): curvature is undefined there"
        ))),
        None => Ok(()),
    }
}

/// The end behaviour of the curvature at t = 0 (`start`) or t = 1.
fn end_curvatures(inp: &Input, b: &Lifted<Bounded>) -> [EndCurvature; 2] {
    let m = b.zx.len() - 1;
    let d = if m > 0 { delta(b).0 } else { Scaled::new() };
    // Exact zero test of δ's coefficients (the filter's signs, else exact).
    let signs: Vec<i32> = if m == 0 {
        Vec::new()
    } else if d.iter().all(|c| c.sign().is_some()) {
        d.iter().map(|c| c.sign().unwrap_or(0)).collect()
    } else {
        delta(&exact(inp)).0.iter().map(poly::sign_of).collect()
    };
    [
        end_curvature(inp, b, (&d, &signs), true),
        end_curvature(inp, b, (&d, &signs), false),
    ]
}

/// One end's curvature from δ (with bounds) and the exact signs of its coefficients.
fn end_curvature(
    inp: &Input,
    b: &Lifted<Bounded>,
    (d, signs): (&[Bounded], &[i32]),
    start: bool,
) -> EndCurvature {
    let order = if start { inp.r } else { inp.s };
    let m = b.zx.len() - 1;
    let n = inp.degree();
    // W at the end, as scaled with the rest (W(0) = w_0, W(1) = w_n).
    let w_end =
        b.w.as_ref()
            .map_or(1.0, |w| if start { w[0].v } else { w[n].v });
    let z_end = if start { 0 } else { m };
    let z2 = b.zx[z_end].v.hypot(b.zy[z_end].v);
    let ordered: Vec<usize> = if start {
        (0..signs.len()).collect()
    } else {
        (0..signs.len()).rev().collect()
    };
    let first = ordered.iter().position(|&i| signs[i] != 0);
    // κ from the scaled inputs is the true one divided by the length scale.
    // In mantissas and binary exponents: on a curve spanning hundreds of orders of
    // magnitude, z2³ alone over- or underflows where κ does not.
    let value = |i: usize| {
        let parts = [
            w_end,
            w_end,
            d[i].v,
            b.length_scale,
            1.0 / (m as f64 * n as f64),
        ];
        let (mut mant, mut exp) = (1.0, 0i64);
        for (f, e) in parts.into_iter().map(split_pow2) {
            mant *= f;
            exp += e;
        }
        let (z, ze) = split_pow2(z2);
        times_pow2_wide(mant / (z * z * z), exp - 3 * ze)
    };
    match first {
        None => {
            if order == 0 {
                EndCurvature::Regular(0.0)
            } else {
                EndCurvature::Finite {
                    curvature: 0.0,
                    order,
                }
            }
        }
        Some(o) if order == 0 => EndCurvature::Regular(match o {
            0 if accurate(&d[ordered[0]]) => value(ordered[0]),
            // The scaled δ lost this coefficient or most of its digits (coordinates spanning
            // hundreds of orders of magnitude): from the exact control points instead.
            0 => regular_end_exactly(inp, start),
            _ => 0.0,
        }),
        Some(o) if o < order => EndCurvature::Unbounded {
            positive: signs[ordered[o]] > 0,
            order,
            rate: order - o,
        },
        Some(o) => EndCurvature::Finite {
            curvature: if o == order { value(ordered[o]) } else { 0.0 },
            order,
        },
    }
}

/// The sign structure of K̃ on (0, 1), certified; the curve checked for regularity first.
fn signs(inp: &Input, b: &Lifted<Bounded>, want: Want) -> Result<(crate::exact::Signs, usize)> {
    check_regular(inp, b)?;
    let k = k_tilde(inp, b);
    let s = decide(inp, &k, || k_tilde(inp, &exact(inp)), want)?;
    Ok((s, k.len() - 1))
}

/// The certified signs of `p` (with bounds); `exact_p` gives the same polynomial exactly,
/// built only when the filter cannot decide and the exact stage is within its budget.
fn decide(
    inp: &Input,
    p: &[Bounded],
    exact_p: impl FnOnce() -> Scaled<BigInt>,
    want: Want,
) -> Result<crate::exact::Signs> {
    let degree = p.len() - 1;
    let cost = predicted_cost(inp, degree);
    let affordable = cost <= crate::exact::signs::EXACT_BUDGET;
    let mut refused = false;
    let s = certified_signs(
        p,
        || {
            // Spent only when the filter cannot decide; a search's budget may refuse it.
            refused = affordable && !super::budget::spend(cost);
            if affordable && !refused {
                exact_p().to_vec()
            } else {
                Vec::new()
            }
        },
        want,
    );
    if s.exact {
        super::note_exact_fallback();
    }
    if refused {
        return Err(Error::NoConvergence(
            "the floating-point filter could not decide this curve and the search it belongs \
             to has spent its budget for exact arithmetic"
                .into(),
        ));
    }
    over_budget(s.over_budget, degree)?;
    Ok(s)
}

/// Where the curvature changes sign in (0, 1) (inflections), certified: the sign changes of
/// δ, which has the sign of κ there.
pub(super) fn inflections(inp: &Input) -> Result<Vec<f64>> {
    let b = bounded(inp);
    check_regular(inp, &b)?;
    if b.zx.len() < 2 {
        return Ok(Vec::new());
    }
    let d = delta(&b).0;
    Ok(decide(inp, &d, || delta(&exact(inp)).0, Want::Changes)?.changes)
}

/// The exact stage's cost (`exact::signs::exact_cost`) predicted from the inputs before any
/// big integer is made: the coordinates' binary exponents span `span` bits (plus 53 of
/// mantissa), K̃ is of degree 4 in them (8 for a rational curve, with 9 weight factors).
pub(super) fn predicted_cost(inp: &Input, degree: usize) -> f64 {
    let span = |v: &mut dyn Iterator<Item = f64>| {
        let (mut lo, mut hi) = (i32::MAX, i32::MIN);
        for x in v.filter(|x| *x != 0.0 && x.is_finite()) {
            let e = x.abs().log2().floor() as i32;
            lo = lo.min(e);
            hi = hi.max(e);
        }
        if lo > hi {
            53
        } else {
            (hi - lo + 53) as u64
        }
    };
    let c = span(&mut inp.points.iter().flat_map(|p| [p.x, p.y]));
    let bits = match inp.weights {
        None => 4 * c + 32,
        Some(w) => 8 * c + 10 * span(&mut w.iter().copied()) + 64,
    };
    crate::exact::signs::exact_cost(degree, bits)
}

/// `Err(NoConvergence)` when the exact stage is over its budget: said, never guessed.
fn over_budget(over: bool, degree: usize) -> Result<()> {
    if over {
        return Err(Error::NoConvergence(format!(
            "the floating-point filter could not decide this curve and the exact test (a \
             polynomial of degree {degree}) would need more than its work budget: its \
             coordinates or weights span too many orders of magnitude for big-integer \
             arithmetic in reasonable time; rescale or round them"
        )));
    }
    Ok(())
}

/// The certified verdict only.
pub(super) fn verdict(inp: &Input) -> Result<bool> {
    let b = bounded(inp);
    let (s, _) = signs(inp, &b, Want::Signs)?;
    Ok(!(s.positive && s.negative))
}

/// The verdict of the floating-point filter alone: `Some` only where its bounds prove it,
/// `None` where only exact arithmetic could decide (never a guess).
pub(super) fn filtered_verdict(inp: &Input) -> Result<Option<bool>> {
    let b = bounded(inp);
    // Regularity the filter cannot prove is not decided either: the exact gcd of z's
    // components would cost what the filter is there to save.
    if !regular_by_filter(&b) {
        return Ok(None);
    }
    let k = k_tilde(inp, &b);
    let s = crate::exact::signs::certified_signs(&k, Vec::new, Want::Signs);
    Ok((!s.over_budget).then_some(!(s.positive && s.negative)))
}

/// The certified verdict with the extrema located and the end curvatures.
pub(super) fn report(inp: &Input) -> Result<MonotoneReport> {
    let b = bounded(inp);
    let (signs, test_degree) = signs(inp, &b, Want::Changes)?;
    let monotone = !(signs.positive && signs.negative);
    let trend = monotone.then_some(match (signs.positive, signs.negative) {
        (true, _) => Trend::Increasing,
        (_, true) => Trend::Decreasing,
        _ => Trend::Constant,
    });
    Ok(MonotoneReport {
        monotone,
        trend,
        extrema: if monotone { Vec::new() } else { signs.changes },
        test_degree,
        exact: signs.exact,
        ends: end_curvatures(inp, &b),
    })
}
