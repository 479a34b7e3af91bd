//! Integer polynomials and their real roots in (0, 1), decided exactly.
//!
//! A polynomial is held in the variable `u = t / (1 - t)`: `p(u) = Σ c_i u^i`. For
//! `t ∈ (0, 1)`, `u ∈ (0, ∞)`, and `(1 - t)^d p(u) = Σ c_i t^i (1 - t)^{d-i}`: the `c_i` are
//! the *scaled* Bernstein coefficients `C(d, i) b_i` of the same polynomial on [0, 1]. So the
//! roots of a Bernstein polynomial in (0, 1) are the positive roots of `p`, and Descartes'
//! rule of signs on the `c_i` is the Bernstein basis's variation-diminishing property.
//!
//! [`sign_changes`] finds where such a polynomial changes sign in (0, 1) (its roots of odd
//! multiplicity), with no rounding anywhere:
//! 1. no sign variation among the coefficients: one sign throughout; one variation: exactly
//!    one simple root (Descartes);
//! 2. otherwise the square-free part `s = p / gcd(p, p')` (primitive pseudo-remainder
//!    sequences) and its Sturm sequence count the distinct roots; bisection on dyadic `t`
//!    isolates each one; `p`'s signs at the two ends of its isolating interval tell whether it
//!    changes sign there (odd multiplicity) or only touches zero;
//! 3. each sign change is refined by bisection on the sign of `s` to an interval of width
//!    `2^-41` in t, whose middle is reported (within `2^-42 ≈ 2.3e-13` of the root).

use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed, Zero};
use std::cmp::Ordering;

/// Refined sign changes are located within `2^-(REFINE_BITS + 1)` in t.
const REFINE_BITS: u32 = 41;

/// An integer polynomial `Σ c_i u^i` (no trailing zero coefficients; empty is zero).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct IntPoly {
    c: Vec<BigInt>,
}

impl IntPoly {
    /// From coefficients, lowest power first.
    pub fn new(mut c: Vec<BigInt>) -> Self {
        while c.last().is_some_and(|v| v.is_zero()) {
            c.pop();
        }
        IntPoly { c }
    }

    /// The coefficients, lowest power first.
    pub fn coeffs(&self) -> &[BigInt] {
        &self.c
    }

    /// Whether this is the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.c.is_empty()
    }

    /// The degree (0 for constants and for zero).
    pub fn degree(&self) -> usize {
        self.c.len().saturating_sub(1)
    }

    fn lead(&self) -> &BigInt {
        self.c.last().expect("nonzero polynomial")
    }

    /// The derivative.
    pub fn deriv(&self) -> IntPoly {
        IntPoly::new(
            self.c
                .iter()
                .enumerate()
                .skip(1)
                .map(|(i, v)| v * BigInt::from(i))
                .collect(),
        )
    }

    /// The primitive part with a positive leading coefficient (zero stays zero).
    pub fn primitive(&self) -> IntPoly {
        let p = self.content_free();
        if !p.is_zero() && p.lead().is_negative() {
            return IntPoly::new(p.c.iter().map(|v| -v).collect());
        }
        p
    }

    /// Divided by the (positive) gcd of the coefficients: the same signs everywhere.
    pub fn content_free(&self) -> IntPoly {
        if self.is_zero() {
            return self.clone();
        }
        let g = content(&self.c);
        if g.is_one() {
            return self.clone();
        }
        IntPoly::new(self.c.iter().map(|v| v / &g).collect())
    }

    /// A positive multiple of the remainder of `self` by `b` (`b` nonzero): each step of
    /// the long division is multiplied by `|lc(b)|`, so signs are those of the true remainder.
    fn pos_prem(&self, b: &IntPoly) -> IntPoly {
        let db = b.degree();
        let lc = b.lead();
        let (lc_abs, lc_neg) = (lc.abs(), lc.is_negative());
        let mut r = self.c.clone();
        while !r.is_empty() && r.len() > db {
            let k = r.len() - 1 - db;
            let top = r.last().expect("nonempty").clone();
            let f = if lc_neg { -top } else { top };
            for v in r.iter_mut() {
                *v *= &lc_abs;
            }
            for (j, bj) in b.c.iter().enumerate() {
                r[j + k] -= &f * bj;
            }
            debug_assert!(r.last().is_some_and(|v| v.is_zero()));
            r.pop();
            while r.last().is_some_and(|v| v.is_zero()) {
                r.pop();
            }
        }
        IntPoly::new(r)
    }

    /// The greatest common divisor, primitive with positive leading coefficient.
    pub fn gcd(&self, other: &IntPoly) -> IntPoly {
        let (mut a, mut b) = (self.primitive(), other.primitive());
        if a.degree() < b.degree() {
            std::mem::swap(&mut a, &mut b);
        }
        while !b.is_zero() {
            let r = a.pos_prem(&b).primitive();
            a = b;
            b = r;
        }
        a.primitive()
    }

    /// `self / d` for a divisor `d` that divides `self` exactly over the rationals and is
    /// primitive (then the quotient has integer coefficients, by Gauss's lemma).
    pub fn div_exact(&self, d: &IntPoly) -> IntPoly {
        let dd = d.degree();
        if self.degree() < dd {
            return IntPoly::new(vec![]);
        }
        let mut r = self.c.clone();
        let mut q = vec![BigInt::zero(); self.degree() - dd + 1];
        let lc = d.lead();
        for k in (0..q.len()).rev() {
            let top = &r[k + dd];
            let (qk, rem) = top.div_rem(lc);
            debug_assert!(rem.is_zero(), "inexact polynomial division");
            for (j, dj) in d.c.iter().enumerate() {
                r[j + k] -= &qk * dj;
            }
            q[k] = qk;
        }
        IntPoly::new(q)
    }

    /// `sign(p(t))` at the dyadic `t = a / 2^k`, `0 < a < 2^k`: the sign of the homogeneous
    /// form `Σ c_i a^i (2^k - a)^{d-i}` (a positive multiple of `p(u)`).
    pub fn sign_at(&self, t: &Dyadic) -> i32 {
        if self.is_zero() {
            return 0;
        }
        let q = (BigInt::one() << t.k) - &t.a;
        let mut acc = self.lead().clone();
        let mut qp = BigInt::one();
        for ci in self.c.iter().rev().skip(1) {
            qp *= &q;
            acc = acc * &t.a + ci * &qp;
        }
        sign_of(&acc)
    }

    /// Sign just right of t = 0 (u → 0+): the lowest nonzero coefficient.
    fn sign_at_zero(&self) -> i32 {
        self.c.iter().find(|v| !v.is_zero()).map_or(0, sign_of)
    }

    /// Sign just left of t = 1 (u → ∞): the leading coefficient.
    fn sign_at_one(&self) -> i32 {
        self.c.last().map_or(0, sign_of)
    }
}

/// The gcd of the coefficients' absolute values (not all zero). The smallest first, and
/// each one reduced modulo the gcd so far: the running gcd is soon small, and each step with
/// it cheap.
fn content(c: &[BigInt]) -> BigInt {
    let mut by_size: Vec<&BigInt> = c.iter().filter(|v| !v.is_zero()).collect();
    by_size.sort_by_key(|v| v.bits());
    let mut g = BigInt::zero();
    for v in by_size {
        g = if g.is_zero() {
            v.abs()
        } else {
            gcd(&g, &(v % &g))
        };
        if g.is_one() {
            break;
        }
    }
    g
}

/// The gcd of two integers. num-bigint's binary gcd removes about a bit a step: fine on a
/// few words, but the sequences of a curve whose coordinates span 1e-300 to 1e300 have
/// 21,000-bit coefficients (3.5 ms a gcd); dashu's Lehmer gcd takes 0.3 ms there.
fn gcd(a: &BigInt, b: &BigInt) -> BigInt {
    if a.bits().max(b.bits()) <= 1024 {
        return a.gcd(b);
    }
    use dashu_int::{ops::Gcd, UBig};
    let big = |v: &BigInt| UBig::from_le_bytes(&v.magnitude().to_bytes_le());
    let g = big(a).gcd(big(b));
    BigInt::from_biguint(
        num_bigint::Sign::Plus,
        num_bigint::BigUint::from_bytes_le(&g.to_le_bytes()),
    )
}

/// The exact sign of `Σ c_i u^i` at the f64 parameter `t`: at `t <= 0` the sign just right
/// of 0, at `t >= 1` the sign just left of 1 (0 only for an exact root inside).
pub fn sign_at_f64(p: &IntPoly, t: f64) -> i32 {
    if t <= 0.0 {
        return p.sign_at_zero();
    }
    if t >= 1.0 {
        return p.sign_at_one();
    }
    let (m, e) = super::decompose(t);
    // t = m 2^e with 0 < t < 1, so e < 0.
    p.sign_at(&Dyadic::new(BigInt::from(m), (-e) as u32))
}

/// The sign of an integer: -1, 0 or 1.
pub fn sign_of(v: &BigInt) -> i32 {
    match v.sign() {
        num_bigint::Sign::Minus => -1,
        num_bigint::Sign::NoSign => 0,
        num_bigint::Sign::Plus => 1,
    }
}

/// A dyadic number `a / 2^k` in [0, 1].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Dyadic {
    a: BigInt,
    k: u32,
}

impl Dyadic {
    fn new(a: BigInt, k: u32) -> Self {
        Dyadic { a, k }
    }

    fn at_k(&self, k: u32) -> BigInt {
        &self.a << (k - self.k)
    }

    /// `lo + (hi - lo) num / 2^bits`.
    fn between(lo: &Dyadic, hi: &Dyadic, num: u64, bits: u32) -> Dyadic {
        let k = lo.k.max(hi.k) + bits;
        let (l, h) = (lo.at_k(k - bits), hi.at_k(k - bits));
        Dyadic::new((l.clone() << bits) + (h - l) * BigInt::from(num), k)
    }

    /// The nearest f64.
    pub fn to_f64(&self) -> f64 {
        // a < 2^k: shift both down to 60 bits of a.
        let bits = self.a.bits() as i64;
        let drop = (bits - 60).max(0);
        let a = (&self.a >> drop as usize)
            .to_string()
            .parse::<f64>()
            .unwrap_or(0.0);
        a * 2f64.powi((drop - self.k as i64) as i32)
    }
}

/// Sign changes (odd-multiplicity roots) of `Σ c_i u^i` with `u = t/(1-t)`, t in (0, 1).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ExactSigns {
    /// The polynomial is identically zero.
    pub zero: bool,
    /// It is strictly positive somewhere in (0, 1).
    pub positive: bool,
    /// It is strictly negative somewhere in (0, 1).
    pub negative: bool,
    /// Where it changes sign, sorted, each within `2.3e-13` of the root.
    pub changes: Vec<f64>,
}

/// Sturm sequence of a square-free polynomial.
struct Sturm(Vec<IntPoly>);

impl Sturm {
    fn new(s: &IntPoly) -> Self {
        let mut seq = vec![s.content_free(), s.deriv().content_free()];
        loop {
            let n = seq.len();
            if seq[n - 1].is_zero() {
                seq.pop();
                break;
            }
            if seq[n - 1].degree() == 0 {
                break;
            }
            let r = seq[n - 2].pos_prem(&seq[n - 1]);
            // -r, divided by its positive content.
            seq.push(IntPoly::new(r.c.iter().map(|v| -v).collect()).content_free());
        }
        Sturm(seq)
    }

    fn variations(signs: impl Iterator<Item = i32>) -> usize {
        let mut last = 0;
        let mut v = 0;
        for s in signs.filter(|s| *s != 0) {
            if last != 0 && s != last {
                v += 1;
            }
            last = s;
        }
        v
    }

    fn at(&self, t: &Dyadic) -> usize {
        Self::variations(self.0.iter().map(|p| p.sign_at(t)))
    }
    fn at_zero(&self) -> usize {
        Self::variations(self.0.iter().map(|p| p.sign_at_zero()))
    }
    fn at_one(&self) -> usize {
        Self::variations(self.0.iter().map(|p| p.sign_at_one()))
    }
}

/// Where `Σ c_i u^i` changes sign for t in (0, 1); see the module docs. Without `locate`
/// the changes are only counted (each reported at the middle of its isolating interval).
pub fn sign_changes(c: &[BigInt], locate: bool) -> ExactSigns {
    let lo = c.iter().position(|v| !v.is_zero());
    let Some(lo) = lo else {
        return ExactSigns {
            zero: true,
            ..ExactSigns::default()
        };
    };
    // Dividing by a power of u (roots at t = 0) changes no sign in (0, 1).
    let p = IntPoly::new(c[lo..].to_vec());
    let first = p.sign_at_zero();
    let last = p.sign_at_one();
    let mut out = ExactSigns::default();
    let note = |s: i32, out: &mut ExactSigns| match s.cmp(&0) {
        Ordering::Greater => out.positive = true,
        Ordering::Less => out.negative = true,
        Ordering::Equal => {}
    };
    note(first, &mut out);
    note(last, &mut out);
    let variations = Sturm::variations(p.c.iter().map(sign_of));
    if variations == 0 {
        return out;
    }
    let zero = Dyadic::new(BigInt::zero(), 0);
    let one = Dyadic::new(BigInt::one(), 0);
    if variations == 1 {
        out.changes.push(if locate {
            refine(&p, zero, one, first)
        } else {
            0.5
        });
        return out;
    }
    let g = p.gcd(&p.deriv());
    let s = if g.degree() > 0 {
        p.div_exact(&g)
    } else {
        p.clone()
    };
    let sturm = Sturm::new(&s);
    let (v0, v1) = (sturm.at_zero(), sturm.at_one());
    let mut intervals = Vec::new();
    isolate(&s, &sturm, (zero, v0), (one, v1), &mut intervals);
    for (a, b) in intervals {
        let (pa, pb) = (
            if a.a.is_zero() { first } else { p.sign_at(&a) },
            if a_is_one(&b) { last } else { p.sign_at(&b) },
        );
        note(pa, &mut out);
        note(pb, &mut out);
        if pa != pb {
            let sa = if a.a.is_zero() {
                s.sign_at_zero()
            } else {
                s.sign_at(&a)
            };
            out.changes.push(if locate {
                refine(&s, a, b, sa)
            } else {
                Dyadic::between(&a, &b, 1, 1).to_f64()
            });
        }
    }
    out
}

/// The distinct real roots of `Σ c_i u^i` for t in (0, 1) (of any multiplicity), each
/// within `2.3e-13`, sorted.
pub fn roots(c: &[BigInt]) -> Vec<f64> {
    let Some(lo) = c.iter().position(|v| !v.is_zero()) else {
        return Vec::new();
    };
    let p = IntPoly::new(c[lo..].to_vec());
    if p.degree() == 0 || Sturm::variations(p.c.iter().map(sign_of)) == 0 {
        return Vec::new();
    }
    let g = p.gcd(&p.deriv());
    let s = if g.degree() > 0 { p.div_exact(&g) } else { p };
    let sturm = Sturm::new(&s);
    let (zero, one) = (
        Dyadic::new(BigInt::zero(), 0),
        Dyadic::new(BigInt::one(), 0),
    );
    let (v0, v1) = (sturm.at_zero(), sturm.at_one());
    let mut intervals = Vec::new();
    isolate(&s, &sturm, (zero, v0), (one, v1), &mut intervals);
    intervals
        .into_iter()
        .map(|(a, b)| {
            let sa = if a.a.is_zero() {
                s.sign_at_zero()
            } else {
                s.sign_at(&a)
            };
            refine(&s, a, b, sa)
        })
        .collect()
}

fn a_is_one(d: &Dyadic) -> bool {
    d.a == (BigInt::one() << d.k)
}

/// Isolating intervals (one distinct root each) of the square-free `s` in (lo, hi), given the
/// Sturm variations at both ends; ends are never roots.
fn isolate(
    s: &IntPoly,
    sturm: &Sturm,
    lo: (Dyadic, usize),
    hi: (Dyadic, usize),
    out: &mut Vec<(Dyadic, Dyadic)>,
) {
    let count = lo.1.saturating_sub(hi.1);
    if count == 0 {
        return;
    }
    if count == 1 {
        out.push((lo.0, hi.0));
        return;
    }
    // A split point that is not a root of s: the middle, else points near it (s has finitely
    // many roots, so one of the first deg + 1 candidates works).
    let mut mid = Dyadic::between(&lo.0, &hi.0, 1, 1);
    let mut j = 1u64;
    while s.sign_at(&mid) == 0 {
        mid = Dyadic::between(&lo.0, &hi.0, 64 + j, 7);
        j += 1;
    }
    let vm = sturm.at(&mid);
    isolate(s, sturm, lo, (mid.clone(), vm), out);
    isolate(s, sturm, (mid, vm), hi, out);
}

/// The one sign change of `s` in (a, b) (`s`'s sign just right of `a` is `sa`), by bisection
/// to width `2^-REFINE_BITS`; an exact root met on the way is returned as it is.
fn refine(s: &IntPoly, mut a: Dyadic, mut b: Dyadic, sa: i32) -> f64 {
    loop {
        let k = a.k.max(b.k);
        // Width (b - a) at most 2^-REFINE_BITS.
        if (b.at_k(k) - a.at_k(k)) << REFINE_BITS as usize <= BigInt::one() << k as usize {
            return Dyadic::between(&a, &b, 1, 1).to_f64();
        }
        let mid = Dyadic::between(&a, &b, 1, 1);
        match s.sign_at(&mid) {
            0 => return mid.to_f64(),
            v if v == sa => a = mid,
            _ => b = mid,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn poly_from_t_roots(roots: &[(i64, i64, usize)]) -> Vec<BigInt> {
        // Π (q t - p)^m in t, written in u: t = u/(1+u), times (1+u)^deg:
        // (q t - p) (1 + u) = q u - p (1 + u) = (q - p) u - p.
        let mut c = vec![BigInt::one()];
        for &(p, q, m) in roots {
            for _ in 0..m {
                let f = [BigInt::from(-p), BigInt::from(q - p)];
                let mut n = vec![BigInt::zero(); c.len() + 1];
                for (i, ci) in c.iter().enumerate() {
                    n[i] += ci * &f[0];
                    n[i + 1] += ci * &f[1];
                }
                c = n;
            }
        }
        c
    }

    #[test]
    fn simple_double_triple_and_end_roots() {
        // roots at t = 1/3 (simple), 1/2 (double), 3/4 (triple), 0 (simple).
        let mut c = poly_from_t_roots(&[(1, 3, 1), (1, 2, 2), (3, 4, 3)]);
        c.insert(0, BigInt::zero());
        let r = sign_changes(&c, true);
        assert!(!r.zero && r.positive && r.negative);
        assert_eq!(r.changes.len(), 2, "{r:?}");
        assert!((r.changes[0] - 1.0 / 3.0).abs() < 3e-13);
        assert!((r.changes[1] - 0.75).abs() < 3e-13);
        // A double root only: touches zero, no change.
        let c = poly_from_t_roots(&[(2, 5, 2)]);
        let r = sign_changes(&c, true);
        assert!(r.changes.is_empty() && r.positive && !r.negative, "{r:?}");
        // Two roots closer than 1e-12: (t - 1/2)(t - (1/2 + 2^-45)).
        let big = 1i64 << 46;
        let c = poly_from_t_roots(&[(big / 2, big, 1), (big / 2 + 2, big, 1)]);
        let r = sign_changes(&c, true);
        assert_eq!(r.changes.len(), 2, "{r:?}");
        assert!(r.changes[0] < r.changes[1]);
        assert!(sign_changes(&[BigInt::zero(), BigInt::zero()], true).zero);
    }

    #[test]
    fn gcd_and_division() {
        let a = IntPoly::new(poly_from_t_roots(&[(1, 3, 2), (1, 5, 1)]));
        let b = IntPoly::new(poly_from_t_roots(&[(1, 3, 1), (2, 7, 1)]));
        let g = a.gcd(&b);
        assert_eq!(g.degree(), 1);
        let q = a.div_exact(&g);
        assert_eq!(q.degree(), 2);
        // a = (3t-1)^2 (5t-1) and g = (3t-1): the quotient still has the factor (3t-1).
        assert_eq!(q.gcd(&g).degree(), 1);
        let t = Dyadic::new(BigInt::from(3), 3);
        assert_eq!(q.sign_at(&t) * g.sign_at(&t), a.sign_at(&t));
    }
}
