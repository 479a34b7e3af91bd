//! Space curves: Bézier curves in three dimensions, their curvature and torsion decided
//! exactly for the given f64 control points.
//!
//! A car's key line is a space curve: a curvature that is not monotone puts a wobble into
//! the reflections on the surface, and so does a torsion that turns back. For a polynomial
//! curve `r(t)` of degree `n` the hodograph is `r' = n z` with `z` of degree `m = n - 1`, and
//! with `C = z × z'`, `D = det(z, z', z'') = C · z''`:
//!
//! - `κ = |C| / (n |z|³)`, so `dκ²/dt` has the sign of
//!   `N = (|C|²)' |z|² - 6 |C|² (z · z')` (degree `6n - 11`);
//! - `τ = D / (n |C|²)`, so `dτ/dt` has the sign of `T = D' |C|² - D (|C|²)'` (degree
//!   `7n - 16` as written here).
//!
//! Arc length grows with `t`, so these are the signs along the curve. `C` is computed from
//! `z`'s two sub-polygons (`Ã_i = (m - i) z_i`, `B̃_i = (i + 1) z_{i+1}`: `m z = (1 - t) Ã +
//! t B̃`, `z' = B̃ - Ã`, so `Ã × B̃ = m (z × z')` at degree `2m - 2`), all in scaled Bernstein
//! form ([`crate::exact::ring`]): one formula, run on bounded floats first and on big
//! integers where those cannot decide ([`crate::exact::certified_signs`]). The verdicts are
//! those of the curve the numbers describe: no sign is guessed from a rounded value. A
//! rational curve's numerators (`rational_numerators`) follow the same pattern from its
//! homogeneous form (docs/math.md §2.5).
//!
//! The curvature of a space curve is not signed: where `C` vanishes (a straight stretch's
//! point, a planar curve's inflection) it touches zero, which is a minimum, and `N` changes
//! sign there. Such extrema are reported apart ([`SpaceReport::zero_curvature`]), so that a
//! planar curve's other extrema are those of its signed curvature in the plane. The torsion
//! is undefined where the curvature is zero, and identically zero on a planar curve (decided
//! exactly: `D ≡ 0`).

use crate::error::{Error, Result};
use crate::exact::ring::{self, Scaled};
use crate::exact::{certified_signs, dyadic_integers, Bounded, Ring, Signs, Want};
use num_bigint::BigInt;

/// The most control points of a space curve (degree 20).
pub const MAX_POINTS: usize = 21;

/// A Bézier curve in three dimensions, polynomial or rational.
#[derive(Clone, Debug, PartialEq)]
pub struct SpaceBezier {
    points: Vec<[f64; 3]>,
    /// The weights of a rational curve (positive); `None` for a polynomial one.
    weights: Option<Vec<f64>>,
}

impl SpaceBezier {
    /// A curve from its control points: 2 to [`MAX_POINTS`] finite points.
    pub fn new(points: Vec<[f64; 3]>) -> Result<Self> {
        if !(2..=MAX_POINTS).contains(&points.len()) {
            return Err(Error::invalid(
                "points",
                format!(
                    "a space Bézier curve needs 2 to {MAX_POINTS} control points, got {}",
                    points.len()
                ),
            ));
        }
        if let Some(i) = points.iter().position(|p| p.iter().any(|v| !v.is_finite())) {
            return Err(Error::invalid(
                "points",
                format!("control point {i} is not finite"),
            ));
        }
        Ok(SpaceBezier {
            points,
            weights: None,
        })
    }

    /// A rational curve: its control points and one positive finite weight each (weights
    /// all equal make it the polynomial curve).
    pub fn rational(points: Vec<[f64; 3]>, weights: Vec<f64>) -> Result<Self> {
        let mut c = SpaceBezier::new(points)?;
        if weights.len() != c.points.len() {
            return Err(Error::invalid(
                "weights",
                format!(
                    "one weight per control point: {} points, {} weights",
                    c.points.len(),
                    weights.len()
                ),
            ));
        }
        if let Some(i) = weights.iter().position(|w| !(w.is_finite() && *w > 0.0)) {
            return Err(Error::invalid(
                "weights",
                format!("weight {i} is not a positive finite number"),
            ));
        }
        if weights.iter().any(|w| *w != weights[0]) {
            c.weights = Some(weights);
        }
        Ok(c)
    }

    /// The weights of a rational curve, `None` for a polynomial one.
    pub fn weights(&self) -> Option<&[f64]> {
        self.weights.as_deref()
    }

    /// The degree n (control points minus one).
    pub fn degree(&self) -> usize {
        self.points.len() - 1
    }

    /// The control points.
    pub fn points(&self) -> &[[f64; 3]] {
        &self.points
    }

    /// The point and its first three derivatives at `t`, in f64 (a rational curve's from
    /// its homogeneous form by the quotient rule).
    pub fn derivatives(&self, t: f64) -> [[f64; 3]; 4] {
        let Some(w) = &self.weights else {
            return polynomial_derivatives(&self.points, t);
        };
        let weighted: Vec<[f64; 3]> = (self.points.iter().zip(w))
            .map(|(p, w)| p.map(|x| x * w))
            .collect();
        let ws: Vec<[f64; 3]> = w.iter().map(|w| [*w, 0.0, 0.0]).collect();
        let (p, ww) = (
            polynomial_derivatives(&weighted, t),
            polynomial_derivatives(&ws, t).map(|v| v[0]),
        );
        // r = P / W: r^(k) = (P^(k) - Σ_{j<k} C(k, j) W^(k-j) r^(j)) / W.
        let mut r = [[0.0; 3]; 4];
        for k in 0..4 {
            let binom = [
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [1.0, 2.0, 1.0],
                [1.0, 3.0, 3.0],
            ];
            r[k] = std::array::from_fn(|c| {
                let rest: f64 = (0..k).map(|j| binom[k][j] * ww[k - j] * r[j][c]).sum();
                (p[k][c] - rest) / ww[0]
            });
        }
        r
    }
}

/// A polynomial Bézier curve's point and first three derivatives at `t` (de Casteljau on
/// the control points and their differences).
fn polynomial_derivatives(points: &[[f64; 3]], t: f64) -> [[f64; 3]; 4] {
    let mut out = [[0.0; 3]; 4];
    let mut pts: Vec<[f64; 3]> = points.to_vec();
    let mut factor = 1.0;
    for (k, slot) in out.iter_mut().enumerate() {
        if pts.is_empty() {
            break;
        }
        let p = casteljau(&pts, t);
        *slot = [factor * p[0], factor * p[1], factor * p[2]];
        let d = pts.len() as f64 - 1.0;
        factor *= d;
        pts = pts
            .windows(2)
            .map(|w| [w[1][0] - w[0][0], w[1][1] - w[0][1], w[1][2] - w[0][2]])
            .collect();
        if k == 3 {
            break;
        }
    }
    out
}

impl SpaceBezier {
    /// The curvature at `t` in f64 (0 where the speed vanishes).
    pub fn curvature(&self, t: f64) -> f64 {
        let [_, d1, d2, _] = self.derivatives(t);
        let (c, s) = (cross(d1, d2), norm(d1));
        if s == 0.0 {
            0.0
        } else {
            norm(c) / (s * s * s)
        }
    }

    /// The torsion at `t` in f64 (NaN where the curvature vanishes: undefined there).
    pub fn torsion(&self, t: f64) -> f64 {
        let [_, d1, d2, d3] = self.derivatives(t);
        let c = cross(d1, d2);
        let c2 = dot(c, c);
        if c2 == 0.0 {
            f64::NAN
        } else {
            dot(c, d3) / c2
        }
    }

    /// The exact verdicts on its curvature and torsion (see the module documentation).
    pub fn check(&self) -> SpaceReport {
        check(self)
    }
}

/// How a space curve lies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpaceShape {
    /// Its curvature is zero everywhere: a straight line (or a point).
    Straight,
    /// It lies in a plane: its torsion is zero everywhere.
    Planar,
    /// It leaves every plane.
    Twisted,
}

/// How a quantity varies along a curve, decided exactly.
#[derive(Clone, Debug, PartialEq)]
pub struct Variation {
    /// It does not turn back on (0, 1): its derivative keeps one sign (zero allowed).
    pub monotone: bool,
    /// It increases (`Some(true)`) or decreases (`Some(false)`) when monotone and not
    /// constant.
    pub increasing: Option<bool>,
    /// It is constant.
    pub constant: bool,
    /// Where its derivative changes sign in (0, 1): its extrema, sorted, each within
    /// about 1e-13 of the exact one.
    pub extrema: Vec<f64>,
    /// The degree of the Bernstein polynomial whose signs decided it.
    pub test_degree: usize,
    /// The floating-point filter could not decide: big-integer arithmetic did.
    pub exact: bool,
    /// The exact stage would have been over its budget (coordinates spanning hundreds of
    /// orders of magnitude): nothing above is decided.
    pub undecided: bool,
}

impl Variation {
    fn of(signs: Signs, test_degree: usize) -> Self {
        if signs.over_budget {
            return Variation {
                monotone: false,
                increasing: None,
                constant: false,
                extrema: Vec::new(),
                test_degree,
                exact: true,
                undecided: true,
            };
        }
        let both = signs.positive && signs.negative;
        Variation {
            monotone: !both,
            increasing: (!both && !signs.zero).then_some(signs.positive),
            constant: signs.zero,
            extrema: signs.changes,
            test_degree,
            exact: signs.exact,
            undecided: false,
        }
    }

    fn constant() -> Self {
        Variation {
            monotone: true,
            increasing: None,
            constant: true,
            extrema: Vec::new(),
            test_degree: 0,
            exact: false,
            undecided: false,
        }
    }
}

/// The verdicts on a space curve.
#[derive(Clone, Debug, PartialEq)]
pub struct SpaceReport {
    /// Straight, planar or twisted (exact).
    pub shape: SpaceShape,
    /// The curvature (unsigned): monotone or not, its extrema (exact).
    pub curvature: Variation,
    /// Those of the curvature's extrema where the curvature is zero (a planar curve's
    /// inflections, a point where the curve is momentarily straight), judged in f64: the
    /// curvature there below 1e-3 of its value 1e-6 away. The torsion is undefined there.
    pub zero_curvature: Vec<f64>,
    /// The torsion: `None` for a straight or planar curve (identically zero there).
    pub torsion: Option<Variation>,
}

fn check(curve: &SpaceBezier) -> SpaceReport {
    let n = curve.degree();
    if n < 2 {
        return SpaceReport {
            shape: SpaceShape::Straight,
            curvature: Variation::constant(),
            zero_curvature: Vec::new(),
            torsion: None,
        };
    }
    let bounded = match curve.weights() {
        None => numerators(&bounded_differences(curve.points()), n),
        Some(w) => {
            let (from_first, ws) = bounded_rational(curve.points(), w);
            rational_numerators(&from_first, &ws)
        }
    };
    let exact = std::cell::OnceCell::new();
    let exact_numerators = || match curve.weights() {
        None => numerators(&exact_differences(curve.points()), n),
        Some(w) => {
            let (from_first, ws) = exact_rational(curve.points(), w);
            rational_numerators(&from_first, &ws)
        }
    };
    let exact_of = |pick: fn(&Numerators<BigInt>) -> &Scaled<BigInt>| -> Vec<BigInt> {
        pick(exact.get_or_init(exact_numerators)).to_vec()
    };
    let square = certified_signs(&bounded.square, || exact_of(|e| &e.square), Want::Signs);
    if square.zero {
        return SpaceReport {
            shape: SpaceShape::Straight,
            curvature: Variation::constant(),
            zero_curvature: Vec::new(),
            torsion: None,
        };
    }
    let signs = certified_signs(
        &bounded.curvature,
        || exact_of(|e| &e.curvature),
        Want::Changes,
    );
    let curvature = Variation::of(signs, bounded.curvature.len() - 1);
    let zero_curvature = (curvature.extrema.iter())
        .copied()
        .filter(|&t| touches_zero(curve, t))
        .collect();
    let planar =
        n < 3 || certified_signs(&bounded.twist, || exact_of(|e| &e.twist), Want::Signs).zero;
    let torsion = (!planar).then(|| {
        let signs = certified_signs(&bounded.torsion, || exact_of(|e| &e.torsion), Want::Changes);
        Variation::of(signs, bounded.torsion.len() - 1)
    });
    SpaceReport {
        shape: if planar {
            SpaceShape::Planar
        } else {
            SpaceShape::Twisted
        },
        curvature,
        zero_curvature,
        torsion,
    }
}

/// Whether the curvature at the extremum `t` is zero: below 1e-3 of its value 1e-6 away
/// on either side. A located extremum is within about 1e-13 of the exact one, so at a zero
/// of the curvature (a simple zero of `C`) the value there is some 1e-7 of its neighbours';
/// at a nonzero minimum or maximum they differ by about 1e-12 of it.
fn touches_zero(curve: &SpaceBezier, t: f64) -> bool {
    let h = 1e-6;
    let here = curve.curvature(t);
    let near = curve
        .curvature((t - h).max(0.0))
        .max(curve.curvature((t + h).min(1.0)));
    here < 1e-3 * near
}

/// The polynomials whose signs decide a curve (scaled Bernstein form).
struct Numerators<R> {
    /// `|Ã × B̃|² = m² |C|²`: zero only where the curvature is.
    square: Scaled<R>,
    /// `N`, the sign of `dκ/dt`.
    curvature: Scaled<R>,
    /// `Ã × B̃ · z'' = m D`: the torsion's sign (identically zero on a planar curve).
    twist: Scaled<R>,
    /// `T`, the sign of `dτ/dt` (degree 0 and zero for a curve of degree below 3).
    torsion: Scaled<R>,
}

/// The control points' differences `b_{i+1} - b_i`, per coordinate.
type Differences<R> = Vec<[R; 3]>;

fn numerators<R: Ring>(d: &Differences<R>, n: usize) -> Numerators<R> {
    let m = n - 1;
    // z_i = C(m, i) (b_{i+1} - b_i), per coordinate.
    let z: [Scaled<R>; 3] = std::array::from_fn(|k| {
        (0..=m)
            .map(|i| d[i][k].mul_int(crate::exact::binomial(m, i) as i64))
            .collect()
    });
    let (c, zp) = cross_with_derivative(&z);
    let square = dot3(&c, &c);
    let speed2 = dot3(&z, &z);
    let along = dot3(&z, &zp);
    let curvature = if square.len() > 1 {
        ring::sub(
            &ring::conv(&ring::deriv(&square), &speed2),
            &ring::scale(&ring::conv(&square, &along), 6),
        )
    } else {
        // |C|² constant (a quadratic): N = -6 |C|² (z · z').
        ring::scale(&ring::conv(&square, &along), -6)
    };
    if m < 2 {
        let zero: Scaled<R> = smallvec::smallvec![R::zero()];
        return Numerators {
            square,
            curvature,
            twist: zero.clone(),
            torsion: zero,
        };
    }
    let zpp: [Scaled<R>; 3] = std::array::from_fn(|k| ring::deriv(&zp[k]));
    let twist = dot3(&c, &zpp);
    let torsion = ring::sub(
        &ring::conv(&ring::deriv(&twist), &square),
        &ring::conv(&twist, &ring::deriv(&square)),
    );
    Numerators {
        square,
        curvature,
        twist,
        torsion,
    }
}

/// The numerators of a rational curve from its control points less the first, `c_i = b_i -
/// b_0` (the verdicts do not depend on where the curve lies, and the products stay small),
/// and its weights. With `P = Σ w_i c_i` and `W` in scaled Bernstein form and the
/// hodograph's numerator `D1 = W P' - P W'` (`r' = D1 / W²`), `E = D1 × D1'` (`r' × r'' =
/// E / W⁴`, computed from D1's sub-polygons as `q E`, `q` its degree), and
/// `Δ = det(H, H', H'', H''')` of the homogeneous `H = (P, W)` (`det(r', r'', r''') =
/// -Δ / W⁴`):
/// - `κ² = W⁴ |E|² / |D1|⁶`, so `dκ/dt` has the sign of
///   `(4 W' |E|² + W (|E|²)') |D1|² - 6 W |E|² (D1 · D1')`;
/// - `τ = -W⁴ Δ / |E|²`, so `dτ/dt` has the sign of `-((4 W' Δ + W Δ') |E|² - W Δ (|E|²)')`.
fn rational_numerators<R: Ring>(c: &[[R; 3]], w: &[R]) -> Numerators<R> {
    let n = c.len() - 1;
    let binom = |n: usize, k: usize| crate::exact::binomial(n, k) as i64;
    // D1 = n Σ_{i,j} C(n-1, i) C(n-1, j) w_i w_{j+1} (c_{j+1} - c_i) t^{i+j} (1-t)^{..}.
    let q = 2 * n - 2;
    let d1: [Scaled<R>; 3] = std::array::from_fn(|k| {
        let mut out: Scaled<R> = (0..=q).map(|_| R::zero()).collect();
        for i in 0..n {
            for j in 0..n {
                let f = w[i]
                    .mul(&w[j + 1])
                    .mul_int(binom(n - 1, i) * binom(n - 1, j));
                out[i + j] = out[i + j].add(&f.mul(&c[j + 1][k].sub(&c[i][k])));
            }
        }
        out
    });
    let h: [Scaled<R>; 4] = std::array::from_fn(|k| {
        (0..=n)
            .map(|i| {
                let v = if k < 3 {
                    w[i].mul(&c[i][k])
                } else {
                    w[i].clone()
                };
                v.mul_int(binom(n, i))
            })
            .collect()
    });
    let weight = &h[3];
    let (e, d1p) = cross_with_derivative(&d1);
    let square = dot3(&e, &e);
    let dsquare = ring::deriv(&square);
    let wp = ring::deriv(weight);
    let lead = ring::add(
        &ring::scale(&ring::conv(&wp, &square), 4),
        &ring::conv(weight, &dsquare),
    );
    let w_square = ring::conv(weight, &square);
    let curvature = ring::sub(
        &ring::conv(&lead, &dot3(&d1, &d1)),
        &ring::scale(&ring::conv(&w_square, &dot3(&d1, &d1p)), 6),
    );
    let twist = det4(&h);
    let tlead = ring::add(
        &ring::scale(&ring::conv(&wp, &twist), 4),
        &ring::conv(weight, &ring::deriv(&twist)),
    );
    let torsion = ring::sub(
        &ring::conv(&ring::conv(weight, &twist), &dsquare),
        &ring::conv(&tlead, &square),
    );
    Numerators {
        square,
        curvature,
        twist,
        torsion,
    }
}

/// `q (z × z')` at its true degree `2q - 2` and `z'`, for `z` of degree `q` (at least 1),
/// from z's two sub-polygons `Ã_i = (q - i) z_i`, `B̃_i = (i + 1) z_{i+1}`: `q z = (1 - t) Ã
/// + t B̃` and `z' = B̃ - Ã`, so `Ã × B̃ = q (z × z')`.
fn cross_with_derivative<R: Ring>(z: &[Scaled<R>; 3]) -> ([Scaled<R>; 3], [Scaled<R>; 3]) {
    let q = z[0].len() - 1;
    let a: [Scaled<R>; 3] =
        std::array::from_fn(|k| (0..q).map(|i| z[k][i].mul_int((q - i) as i64)).collect());
    let b: [Scaled<R>; 3] =
        std::array::from_fn(|k| (0..q).map(|i| z[k][i + 1].mul_int(i as i64 + 1)).collect());
    let cross = std::array::from_fn(|k| {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        ring::sub(&ring::conv(&a[i], &b[j]), &ring::conv(&a[j], &b[i]))
    });
    (cross, std::array::from_fn(|k| ring::sub(&b[k], &a[k])))
}

/// The dot product of two polynomial vectors.
fn dot3<R: Ring>(u: &[Scaled<R>; 3], v: &[Scaled<R>; 3]) -> Scaled<R> {
    let t = |k: usize| ring::conv(&u[k], &v[k]);
    ring::add(&ring::add(&t(0), &t(1)), &t(2))
}

/// `det(H, H', H'', H''')` of four polynomials (rows: the derivatives), by its 24 terms.
fn det4<R: Ring>(h: &[Scaled<R>; 4]) -> Scaled<R> {
    let mut rows: Vec<[Scaled<R>; 4]> = vec![h.clone()];
    for _ in 0..3 {
        let last = rows.last().expect("one row at least");
        let next: [Scaled<R>; 4] = std::array::from_fn(|k| ring::deriv(&last[k]));
        rows.push(next);
    }
    let mut out: Option<Scaled<R>> = None;
    for perm in permutations4() {
        let (cols, odd) = perm;
        let term = ring::conv(
            &ring::conv(&rows[0][cols[0]], &rows[1][cols[1]]),
            &ring::conv(&rows[2][cols[2]], &rows[3][cols[3]]),
        );
        out = Some(match out {
            None if odd => ring::scale(&term, -1),
            None => term,
            Some(acc) if odd => ring::sub(&acc, &term),
            Some(acc) => ring::add(&acc, &term),
        });
    }
    out.expect("24 terms")
}

/// The 24 permutations of 0..4, each with whether it is odd.
fn permutations4() -> Vec<([usize; 4], bool)> {
    let mut out = Vec::with_capacity(24);
    for a in 0..4 {
        for b in 0..4 {
            for c in 0..4 {
                let d = 6 - a - b - c;
                let p = [a, b, c, d];
                if a == b || a == c || b == c || d > 3 || [a, b, c].contains(&d) {
                    continue;
                }
                let inversions = (0..4)
                    .flat_map(|i| (i + 1..4).map(move |j| (i, j)))
                    .filter(|&(i, j)| p[i] > p[j])
                    .count();
                out.push((p, inversions % 2 == 1));
            }
        }
    }
    out
}

/// A rational curve's control points less the first and its weights as bounded floats,
/// each scaled by one power of two (exact, as for [`bounded_differences`]).
fn bounded_rational(p: &[[f64; 3]], w: &[f64]) -> (Vec<[Bounded; 3]>, Vec<Bounded>) {
    let raw: Vec<[Bounded; 3]> = (p.iter())
        .map(|q| std::array::from_fn(|k| Bounded::diff(q[k], p[0][k])))
        .collect();
    let ws: Vec<Bounded> = w.iter().map(|v| Bounded::exact(*v)).collect();
    (
        scaled_bounded(raw),
        scaled_bounded(ws.into_iter().map(|b| [b]).collect())
            .into_iter()
            .map(|[b]| b)
            .collect(),
    )
}

/// A rational curve's control points less the first and its weights as exact integers
/// (each over its own power of two: the verdicts do not depend on either scale).
fn exact_rational(p: &[[f64; 3]], w: &[f64]) -> (Vec<[BigInt; 3]>, Vec<BigInt>) {
    let flat: Vec<f64> = p.iter().flat_map(|q| q.iter().copied()).collect();
    let (ints, _) = dyadic_integers(&flat);
    let c = (0..p.len())
        .map(|i| std::array::from_fn(|k| &ints[3 * i + k] - &ints[k]))
        .collect();
    (c, dyadic_integers(w).0)
}

/// The differences as bounded floats, scaled by one power of two so that the largest is
/// near 1 (the numerators are products of up to eight of them: nothing overflows or
/// underflows on the way for ordinary coordinates; where it would, the bounds say so and
/// the exact stage decides).
fn bounded_differences(p: &[[f64; 3]]) -> Differences<Bounded> {
    scaled_bounded(
        p.windows(2)
            .map(|w| std::array::from_fn(|k| Bounded::diff(w[1][k], w[0][k])))
            .collect(),
    )
}

/// Bounded values scaled by one power of two so that the largest is near 1.
fn scaled_bounded<const K: usize>(raw: Vec<[Bounded; K]>) -> Vec<[Bounded; K]> {
    let big = raw
        .iter()
        .flat_map(|d| d.iter().map(|b| b.v.abs()))
        .fold(0.0f64, f64::max);
    let k = if big > 0.0 && big.is_finite() {
        -(big.log2().floor() as i32)
    } else {
        0
    };
    let f = 2f64.powi(k.clamp(-1000, 1000));
    raw.into_iter()
        .map(|d| {
            d.map(|b| {
                let (v, e) = (b.v * f, b.e * f);
                // A value pushed below the normal range is rounded there (to zero
                // included): its bound grows by the rounding.
                let lost = (b.v != 0.0 && v.abs() < f64::MIN_POSITIVE)
                    || (b.e != 0.0 && e.abs() < f64::MIN_POSITIVE);
                Bounded {
                    v,
                    e: if lost { e + 2.0 * f64::from_bits(1) } else { e },
                }
            })
        })
        .collect()
}

/// The differences as exact integers (all coordinates over one power of two).
fn exact_differences(p: &[[f64; 3]]) -> Differences<BigInt> {
    let flat: Vec<f64> = p.iter().flat_map(|q| q.iter().copied()).collect();
    let (ints, _) = dyadic_integers(&flat);
    (0..p.len() - 1)
        .map(|i| std::array::from_fn(|k| &ints[3 * (i + 1) + k] - &ints[3 * i + k]))
        .collect()
}

fn casteljau(pts: &[[f64; 3]], t: f64) -> [f64; 3] {
    let mut w = pts.to_vec();
    for n in (1..w.len()).rev() {
        for i in 0..n {
            let next = w[i + 1];
            w[i] = std::array::from_fn(|k| w[i][k] * (1.0 - t) + next[k] * t);
        }
    }
    w[0]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: [f64; 3]) -> f64 {
    a[0].hypot(a[1]).hypot(a[2])
}
