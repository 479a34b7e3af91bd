//! One arithmetic interface for two number types: floating point with a rigorous error bound
//! ([`Bounded`]) and exact integers (`BigInt`), and polynomials in scaled Bernstein form over
//! either.
//!
//! A formula written once over [`Ring`] runs first as a filter on [`Bounded`] numbers (fast;
//! each result knows how far from the exact value it can be) and, where that cannot decide
//! a sign, again on `BigInt`s (exact). This is the habit of CGAL's filtered kernels.
//!
//! Scaled Bernstein form: `p(t) = Σ a_i t^i (1 - t)^{d - i}` (`a_i = C(d, i)` times the
//! ordinary Bernstein coefficient, so signs agree). Products are convolutions and the
//! derivative has integer factors, `a'_j = (j + 1) a_{j+1} - (d - j) a_j`: no division, so
//! the same code is exact on integers.

use num_bigint::BigInt;
use num_traits::Zero;
use smallvec::SmallVec;

/// Numbers a formula can run on.
pub trait Ring: Clone {
    /// Zero.
    fn zero() -> Self;
    /// `self + o`.
    fn add(&self, o: &Self) -> Self;
    /// `self - o`.
    fn sub(&self, o: &Self) -> Self;
    /// `self * o`.
    fn mul(&self, o: &Self) -> Self;
    /// `self * k` for a small integer k (|k| < 2^53).
    fn mul_int(&self, k: i64) -> Self;
}

impl Ring for BigInt {
    fn zero() -> Self {
        Zero::zero()
    }
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    fn sub(&self, o: &Self) -> Self {
        self - o
    }
    fn mul(&self, o: &Self) -> Self {
        self * o
    }
    fn mul_int(&self, k: i64) -> Self {
        self * BigInt::from(k)
    }
}

const U: f64 = f64::EPSILON * 0.5;
/// Covers the rounding of the bound's own few operations (each rounds by at most U).
const INFLATE: f64 = 1.0 + 16.0 * f64::EPSILON;
/// The absolute rounding error of a product in the subnormal range is at most 2^-1075.
const ETA: f64 = f64::from_bits(1);

/// A floating-point value `v` and a bound `e` with `|v - exact| <= e`, where `exact` is what
/// the same formula gives in exact arithmetic on the exact inputs. Overflow gives an
/// infinite or NaN bound: every sign is then unknown.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounded {
    /// The computed value.
    pub v: f64,
    /// Its error bound.
    pub e: f64,
}

impl Bounded {
    /// An exact input.
    pub fn exact(v: f64) -> Self {
        Bounded { v, e: 0.0 }
    }

    /// `a - b` for exact inputs, with the bound 0 when the subtraction was exact (Knuth's
    /// TwoSum finds its rounding error exactly).
    pub fn diff(a: f64, b: f64) -> Self {
        let nb = -b;
        let s = a + nb;
        let bb = s - a;
        let err = (a - (s - bb)) + (nb - bb);
        Bounded {
            v: s,
            e: if err == 0.0 { 0.0 } else { U * s.abs() },
        }
    }

    /// The sign, when the bound settles it: `Some(1)`, `Some(-1)`, `Some(0)` for an exact
    /// zero, `None` when the value is within its bound of zero (or not finite).
    #[inline]
    pub fn sign(&self) -> Option<i32> {
        if self.v > self.e {
            Some(1)
        } else if -self.v > self.e {
            Some(-1)
        } else if self.v == 0.0 && self.e == 0.0 {
            Some(0)
        } else {
            None
        }
    }

    /// `self / k` for a positive integer k; the bound stays 0 when the input was exact and
    /// the quotient is (a fused multiply-add gives `v k - self` exactly for a normal or zero
    /// quotient), so an exact zero stays a known zero.
    pub fn div_int(&self, k: f64) -> Self {
        let v = self.v / k;
        let exact = self.e == 0.0
            && (v == 0.0 || v.abs() >= f64::MIN_POSITIVE)
            && v.is_finite()
            && v.mul_add(k, -self.v) == 0.0;
        Bounded {
            v,
            e: if exact {
                0.0
            } else {
                (self.e / k + U * v.abs() + ETA) * INFLATE
            },
        }
    }

    /// The average `(self + o) / 2`.
    pub fn mid(&self, o: &Self) -> Self {
        let v = 0.5 * (self.v + o.v);
        Bounded {
            v,
            e: (0.5 * (self.e + o.e) + U * v.abs() + ETA) * INFLATE,
        }
    }
}

/// Whether `a + b` (computed as `v`) was exact: Knuth's TwoSum gives the rounding error
/// exactly (exact inputs only, so the result's bound can be 0 and a computed zero of exact
/// data, a font's, is known to be zero).
#[inline]
fn sum_is_exact(a: f64, b: f64, v: f64) -> bool {
    let bb = v - a;
    (a - (v - bb)) + (b - bb) == 0.0 && v.is_finite()
}

/// Whether the product `a b` (computed as `v`) was exact: a fused multiply-add gives its
/// rounding error exactly, when the product is a normal number (in the subnormal range the
/// error itself may round to zero) or a factor is zero.
#[inline]
fn product_is_exact(a: f64, b: f64, v: f64) -> bool {
    if a == 0.0 || b == 0.0 {
        return true;
    }
    v.is_finite() && v.abs() >= f64::MIN_POSITIVE && a.mul_add(b, -v) == 0.0
}

impl Ring for Bounded {
    fn zero() -> Self {
        Bounded::exact(0.0)
    }
    #[inline]
    fn add(&self, o: &Self) -> Self {
        let v = self.v + o.v;
        if self.e == 0.0 && o.e == 0.0 && sum_is_exact(self.v, o.v, v) {
            return Bounded::exact(v);
        }
        Bounded {
            v,
            e: (self.e + o.e + U * v.abs()) * INFLATE,
        }
    }
    #[inline]
    fn sub(&self, o: &Self) -> Self {
        let v = self.v - o.v;
        if self.e == 0.0 && o.e == 0.0 && sum_is_exact(self.v, -o.v, v) {
            return Bounded::exact(v);
        }
        Bounded {
            v,
            e: (self.e + o.e + U * v.abs()) * INFLATE,
        }
    }
    #[inline]
    fn mul(&self, o: &Self) -> Self {
        let v = self.v * o.v;
        if self.e == 0.0 && o.e == 0.0 && product_is_exact(self.v, o.v, v) {
            return Bounded::exact(v);
        }
        // Each of the bound's three products may underflow (to zero included) where both
        // its factors are nonzero: ETA each then, or a tiny uncertain value times another
        // would come out as a known zero.
        let lost = |a: f64, b: f64| if a != 0.0 && b != 0.0 { ETA } else { 0.0 };
        let e = self.v.abs() * o.e
            + o.v.abs() * self.e
            + self.e * o.e
            + lost(self.v, o.e)
            + lost(o.v, self.e)
            + lost(self.e, o.e);
        let round = if v == 0.0 && (self.v == 0.0 || o.v == 0.0) {
            0.0
        } else {
            U * v.abs() + ETA
        };
        Bounded {
            v,
            e: (e + round) * INFLATE,
        }
    }
    #[inline]
    fn mul_int(&self, k: i64) -> Self {
        let kf = k as f64;
        let v = self.v * kf;
        if self.e == 0.0 && product_is_exact(self.v, kf, v) {
            return Bounded::exact(v);
        }
        let round = if self.v == 0.0 {
            0.0
        } else {
            U * v.abs() + ETA
        };
        // The bound's product may underflow too.
        let lost = if self.e != 0.0 && k != 0 { ETA } else { 0.0 };
        Bounded {
            v,
            e: (kf.abs() * self.e + lost + round) * INFLATE,
        }
    }
}

/// Coefficients of a polynomial in scaled Bernstein form (see the module docs).
pub type Scaled<R> = SmallVec<[R; 24]>;

/// The product (degree adds).
pub fn conv<R: Ring>(a: &[R], b: &[R]) -> Scaled<R> {
    let mut out: Scaled<R> = (0..a.len() + b.len() - 1).map(|_| R::zero()).collect();
    for (i, ai) in a.iter().enumerate() {
        for (j, bj) in b.iter().enumerate() {
            out[i + j] = out[i + j].add(&ai.mul(bj));
        }
    }
    out
}

/// `a + b` of one degree.
pub fn add<R: Ring>(a: &[R], b: &[R]) -> Scaled<R> {
    debug_assert_eq!(a.len(), b.len());
    a.iter().zip(b).map(|(x, y)| x.add(y)).collect()
}

/// `a - b` of one degree.
pub fn sub<R: Ring>(a: &[R], b: &[R]) -> Scaled<R> {
    debug_assert_eq!(a.len(), b.len());
    a.iter().zip(b).map(|(x, y)| x.sub(y)).collect()
}

/// `k a`.
pub fn scale<R: Ring>(a: &[R], k: i64) -> Scaled<R> {
    a.iter().map(|x| x.mul_int(k)).collect()
}

/// The derivative (degree d - 1; a constant's derivative is the zero constant).
pub fn deriv<R: Ring>(a: &[R]) -> Scaled<R> {
    let d = a.len() - 1;
    if d == 0 {
        return smallvec::smallvec![R::zero()];
    }
    (0..d)
        .map(|j| {
            a[j + 1]
                .mul_int(j as i64 + 1)
                .sub(&a[j].mul_int((d - j) as i64))
        })
        .collect()
}

/// `(α (1 - t) + β t) a`: degree d + 1.
pub fn times_linear<R: Ring>(a: &[R], alpha: i64, beta: i64) -> Scaled<R> {
    let d = a.len() - 1;
    (0..=d + 1)
        .map(|i| {
            let from_one_minus = if i <= d {
                a[i].mul_int(alpha)
            } else {
                R::zero()
            };
            if i >= 1 && beta != 0 {
                from_one_minus.add(&a[i - 1].mul_int(beta))
            } else {
                from_one_minus
            }
        })
        .collect()
}

/// The same polynomial at degree d + 1 (times `(1 - t) + t`).
pub fn elevate<R: Ring>(a: &[R]) -> Scaled<R> {
    times_linear(a, 1, 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eval(a: &[f64], t: f64) -> f64 {
        let d = a.len() - 1;
        a.iter()
            .enumerate()
            .map(|(i, c)| c * t.powi(i as i32) * (1.0 - t).powi((d - i) as i32))
            .sum()
    }

    #[test]
    fn scaled_operations_agree_with_values() {
        let p: Vec<Bounded> = [1.0, -3.0, 2.0, 5.0].map(Bounded::exact).to_vec();
        let q: Vec<Bounded> = [0.5, 4.0, -1.0].map(Bounded::exact).to_vec();
        let v = |a: &[Bounded]| a.iter().map(|x| x.v).collect::<Vec<_>>();
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            let (pv, qv) = (eval(&v(&p), t), eval(&v(&q), t));
            assert!((eval(&v(&conv(&p, &q)), t) - pv * qv).abs() < 1e-12);
            assert!((eval(&v(&elevate(&p)), t) - pv).abs() < 1e-12);
            assert!(
                (eval(&v(&times_linear(&p, 2, -3)), t) - (2.0 * (1.0 - t) - 3.0 * t) * pv).abs()
                    < 1e-12
            );
            let h = 1e-6;
            let fd = (eval(&v(&p), t + h) - eval(&v(&p), t - h)) / (2.0 * h);
            assert!((eval(&v(&deriv(&p)), t) - fd).abs() < 1e-6);
        }
    }

    #[test]
    fn bounds_hold_against_exact_integers() {
        // A long product chain on values with a rounding error each: the bound covers the
        // exact result computed in big integers.
        let xs = [3.0e15 + 1.0, -7.0e14 - 3.0, 1.0e15 + 7.0, 123456789.0];
        let mut b = Bounded::exact(1.0);
        let mut x = BigInt::from(1);
        for (i, v) in xs.iter().enumerate() {
            let bv = Bounded::exact(*v);
            b = b.mul(&bv).add(&bv.mul_int(i as i64 + 3));
            x = x
                .mul(&BigInt::from(*v as i64))
                .add(&BigInt::from(*v as i64 * (i as i64 + 3)));
        }
        let exact: f64 = x.to_string().parse().unwrap();
        assert!((b.v - exact).abs() <= b.e, "{b:?} vs {exact}");
        assert!(b.e > 0.0);
        assert_eq!(Bounded::diff(5.0, 3.0).e, 0.0);
        assert!(Bounded::diff(1.0, 1e-30).e > 0.0);
    }

    /// Products near the bottom of the range: a value known only to within a subnormal
    /// bound, times another, is not a known zero (its bound's products underflowed to 0 and
    /// the filter once proved a curve monotone that is not); a known zero times anything
    /// stays a known zero.
    #[test]
    fn underflowing_bounds_are_never_a_known_zero() {
        let tiny = Bounded { v: 0.0, e: 1e-323 };
        let small = Bounded {
            v: 1e-300,
            e: 4e-315,
        };
        for (a, b) in [(tiny, tiny), (tiny, small), (small, small)] {
            let p = a.mul(&b);
            assert_eq!(p.sign(), None, "{a:?} * {b:?} = {p:?}");
        }
        assert_eq!(tiny.mul_int(3).sign(), None);
        assert_eq!(Bounded::exact(0.0).mul(&tiny).sign(), Some(0));
        assert_eq!(Bounded::exact(0.0).mul_int(5).sign(), Some(0));
        // Ordinary bounds are not widened: a product of exact normal values stays exact.
        assert_eq!(Bounded::exact(3.0).mul(&Bounded::exact(0.25)).e, 0.0);
    }
}
