//! Where a polynomial changes sign on (0, 1), certified: a floating-point filter that knows
//! when it cannot decide, and the exact answer when it cannot.
//!
//! The filter works on Bernstein coefficients with rigorous error bounds
//! ([`super::Bounded`]). A coefficient whose value is within its bound of zero has an
//! *unknown* sign, never a zero one. A piece of [0, 1] is settled when its coefficients
//! prove one sign (all of one strict sign or exactly zero), or exactly one sign change (the
//! strict signs form one run of each sign, unknown ones only between the two runs: Descartes'
//! rule then counts one variation whatever the unknown signs are). Anything else is split in
//! two (de Casteljau at 33/64, the bounds carried along), up to a depth and a number of pieces. A
//! located change is certified by the signs of the polynomial, with bounds, on both sides of
//! it, `2^-43` away. Whatever the filter leaves open goes to [`super::poly::sign_changes`] on
//! the exact integer coefficients.

use super::poly;
use super::ring::{Bounded, Ring};
use num_bigint::BigInt;
use smallvec::SmallVec;

/// What a caller needs from the analysis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Want {
    /// Which signs occur (stops once both strict signs are seen; changes not located).
    Signs,
    /// Every sign change, located within about 1e-13.
    Changes,
}

/// The sign structure of a polynomial on (0, 1).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Signs {
    /// Identically zero.
    pub zero: bool,
    /// Strictly positive somewhere in (0, 1).
    pub positive: bool,
    /// Strictly negative somewhere in (0, 1).
    pub negative: bool,
    /// Where it changes sign, sorted (only with [`Want::Changes`]).
    pub changes: Vec<f64>,
    /// Decided by exact arithmetic (the filter could not decide).
    pub exact: bool,
    /// Not decided: the exact arithmetic would need more than [`EXACT_BUDGET`] (a
    /// polynomial of high degree with huge integers, from coordinates spanning hundreds of
    /// orders of magnitude); the other fields mean nothing then.
    pub over_budget: bool,
}

/// The most work the exact stage takes on, in a cost model of its gcd and Sturm sequence:
/// about `d³` products of numbers of `d × bits` bits (d the degree), each `(d bits / 64)^1.58`
/// word operations (Karatsuba), the isolation's evaluations on top. 4·10^8 admits every
/// degree up to 12 with ordinary coordinates (a degree-41 numerator with 300-bit
/// coefficients), a rational cubic whose coordinates span 100 orders of magnitude, and a
/// font's cubics many times over; it refuses at once what would take many seconds to minutes
/// (a degree-29 numerator with 10,000-bit coefficients: a degree-8 curve whose coordinates
/// span 300 orders of magnitude took 20 s), and a degree-20 curve's degree-73 numerator
/// from about 200-bit coefficients on.
pub const EXACT_BUDGET: f64 = 4e8;

/// The exact stage's cost in the model of [`EXACT_BUDGET`].
pub fn exact_cost(degree: usize, bits: u64) -> f64 {
    let d = degree.max(1) as f64;
    d * d * d * (d * bits.max(64) as f64 / 64.0).powf(1.58)
}

/// The filter's limits: at most `MAX_DEPTH` splits deep, at most `MAX_PIECES` visited.
const MAX_DEPTH: u32 = 24;
const MAX_PIECES: usize = 400;

type Co = SmallVec<[Bounded; 24]>;

/// The sign structure of the polynomial with scaled Bernstein coefficients `scaled` (with
/// error bounds); `exact` gives the same coefficients exactly, and is called only when the
/// filter cannot decide.
pub fn certified_signs(
    scaled: &[Bounded],
    exact: impl FnOnce() -> Vec<BigInt>,
    want: Want,
) -> Signs {
    if let Some(s) = filter(scaled, want) {
        return s;
    }
    let c = exact();
    let bits = c.iter().map(|v| v.bits()).max().unwrap_or(0);
    // An empty answer: the caller knew beforehand that it was over the budget.
    if c.is_empty() || exact_cost(c.len().saturating_sub(1), bits) > EXACT_BUDGET {
        return Signs {
            exact: true,
            over_budget: true,
            ..Signs::default()
        };
    }
    let e = poly::sign_changes(&c, want == Want::Changes);
    Signs {
        zero: e.zero,
        positive: e.positive,
        negative: e.negative,
        changes: e.changes,
        exact: true,
        over_budget: false,
    }
}

/// C(d, i) and whether it is exact in f64.
fn binomial(d: usize, i: usize) -> f64 {
    let i = i.min(d - i);
    let mut b = 1.0f64;
    for j in 0..i {
        b = b * (d - j) as f64 / (j + 1) as f64;
    }
    b.round()
}

/// Ordinary Bernstein coefficients from scaled ones, bounds included.
fn unscale(scaled: &[Bounded]) -> Co {
    let d = scaled.len() - 1;
    // Binomials beyond C(56, 28) are not all exact in f64: their relative error (at most
    // d units in the last place from the product formula) joins the bound.
    let rel = if d > 56 {
        4.0 * d as f64 * f64::EPSILON
    } else {
        0.0
    };
    scaled
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let mut b = c.div_int(binomial(d, i));
            b.e += rel * b.v.abs();
            b
        })
        .collect()
}

enum Piece {
    /// One sign (1, -1) or exactly zero (0).
    Settled(i32),
    /// Exactly one sign change; the sign at the piece's start.
    OneChange(i32),
    Split,
}

fn classify(c: &[Bounded]) -> Piece {
    let signs: SmallVec<[Option<i32>; 24]> = c.iter().map(Bounded::sign).collect();
    let first_unknown = signs.iter().position(Option::is_none);
    let Some(fu) = first_unknown else {
        // Every sign known: count the variations.
        let mut strict = signs.iter().flatten().filter(|s| **s != 0);
        let Some(&s0) = strict.next() else {
            return Piece::Settled(0);
        };
        let mut variations = 0;
        let mut last = s0;
        for &s in strict {
            if s != last {
                variations += 1;
                last = s;
            }
        }
        return match variations {
            0 => Piece::Settled(s0),
            1 => Piece::OneChange(s0),
            _ => Piece::Split,
        };
    };
    let lu = signs
        .iter()
        .rposition(Option::is_none)
        .expect("one unknown");
    let run = |part: &[Option<i32>]| -> Option<i32> {
        let mut s = None;
        for v in part.iter().flatten().filter(|v| **v != 0) {
            match s {
                None => s = Some(*v),
                Some(x) if x != *v => return None,
                _ => {}
            }
        }
        s
    };
    let middle_strict = signs[fu..=lu].iter().flatten().any(|v| *v != 0);
    match (run(&signs[..fu]), run(&signs[lu + 1..])) {
        (Some(a), Some(b)) if a != b && !middle_strict => Piece::OneChange(a),
        _ => Piece::Split,
    }
}

/// Pieces are split at this fraction, not at 1/2: symmetric designs (a font's circles and
/// bowls) have curvature extrema exactly at t = 1/2, where no certificate could ever be found
/// on a split at 1/2. `1 - SPLIT` is exact.
const SPLIT: f64 = 33.0 / 64.0;

fn split(c: &[Bounded]) -> (Co, Co) {
    let n = c.len();
    let mut w: Co = SmallVec::from_slice(c);
    let mut left: Co = SmallVec::with_capacity(n);
    let mut right: Co = SmallVec::from_elem(Bounded::exact(0.0), n);
    let (s, t) = (Bounded::exact(1.0 - SPLIT), Bounded::exact(SPLIT));
    left.push(w[0]);
    right[n - 1] = w[n - 1];
    for k in 1..n {
        for i in 0..n - k {
            w[i] = s.mul(&w[i]).add(&t.mul(&w[i + 1]));
        }
        left.push(w[0]);
        right[n - 1 - k] = w[n - 1 - k];
    }
    (left, right)
}

fn values_at(c: &[Bounded], x: f64) -> f64 {
    let mut b: SmallVec<[f64; 24]> = c.iter().map(|v| v.v).collect();
    let s = 1.0 - x;
    for k in 1..b.len() {
        for i in 0..b.len() - k {
            b[i] = s * b[i] + x * b[i + 1];
        }
    }
    b[0]
}

/// The value at `x` in [0, 1] with a bound (1 - x is exact for x >= 1/2 and carries its
/// rounding otherwise).
fn bounded_at(c: &[Bounded], x: f64) -> Bounded {
    let mut b: Co = SmallVec::from_slice(c);
    let (s, xb) = (Bounded::diff(1.0, x), Bounded::exact(x));
    for k in 1..b.len() {
        for i in 0..b.len() - k {
            b[i] = s.mul(&b[i]).add(&xb.mul(&b[i + 1]));
        }
    }
    b[0]
}

struct Walk {
    want: Want,
    pieces: usize,
    positive: bool,
    negative: bool,
    /// The sign of the last settled stretch (for changes at piece boundaries).
    last: i32,
    changes: Vec<f64>,
    failed: bool,
}

impl Walk {
    fn done(&self) -> bool {
        self.failed || (self.want == Want::Signs && self.positive && self.negative)
    }

    fn note(&mut self, sign: i32, at: f64) {
        if sign == 0 {
            return;
        }
        if self.last != 0 && sign != self.last && self.want == Want::Changes {
            self.changes.push(at);
        }
        self.last = sign;
        if sign > 0 {
            self.positive = true;
        } else {
            self.negative = true;
        }
    }

    fn visit(&mut self, c: &[Bounded], a: f64, w: f64, depth: u32) {
        if self.done() {
            return;
        }
        self.pieces += 1;
        match classify(c) {
            Piece::Settled(s) => self.note(s, a),
            Piece::OneChange(s0) => {
                self.note(s0, a);
                if self.want == Want::Changes {
                    match self.locate(c, s0, w) {
                        Some(r) => self.changes.push(a + w * r),
                        None => self.failed = true,
                    }
                }
                // The far side's sign, without a second change at the piece's end.
                self.last = -s0;
                if s0 > 0 {
                    self.negative = true;
                } else {
                    self.positive = true;
                }
            }
            Piece::Split => {
                if depth >= MAX_DEPTH || self.pieces >= MAX_PIECES {
                    self.failed = true;
                    return;
                }
                let (l, r) = split(c);
                self.visit(&l, a, SPLIT * w, depth + 1);
                self.visit(&r, a + SPLIT * w, (1.0 - SPLIT) * w, depth + 1);
            }
        }
    }

    /// The one sign change of the piece (local parameter), certified within `2^-43` in t.
    fn locate(&self, c: &[Bounded], s0: i32, w: f64) -> Option<f64> {
        let f = |x: f64| values_at(c, x);
        let mut lo = 0.0f64;
        let mut hi = 1.0f64;
        for _ in 0..200 {
            let m = 0.5 * (lo + hi);
            if m <= lo || m >= hi {
                break;
            }
            let v = f(m);
            if v == 0.0 {
                lo = m;
                hi = m;
                break;
            }
            if (v > 0.0) == (s0 > 0) {
                lo = m;
            } else {
                hi = m;
            }
        }
        let r = 0.5 * (lo + hi);
        let d = (-43f64).exp2() / w;
        let (x1, x2) = ((r - d).max(0.0), (r + d).min(1.0));
        let (v1, v2) = (bounded_at(c, x1).sign(), bounded_at(c, x2).sign());
        (v1 == Some(s0) && v2 == Some(-s0)).then_some(r)
    }
}

/// The filter on scaled coefficients: `None` when it cannot decide.
fn filter(scaled: &[Bounded], want: Want) -> Option<Signs> {
    if scaled.is_empty() {
        return Some(Signs {
            zero: true,
            ..Signs::default()
        });
    }
    if scaled.iter().all(|c| c.v == 0.0 && c.e == 0.0) {
        return Some(Signs {
            zero: true,
            ..Signs::default()
        });
    }
    filter_plain(&unscale(scaled), want)
}

/// The filter on ordinary Bernstein coefficients with their bounds: `None` when it cannot
/// decide.
pub fn filter_plain(c: &[Bounded], want: Want) -> Option<Signs> {
    if c.iter().all(|c| c.v == 0.0 && c.e == 0.0) {
        return Some(Signs {
            zero: true,
            ..Signs::default()
        });
    }
    let mut walk = Walk {
        want,
        pieces: 0,
        positive: false,
        negative: false,
        last: 0,
        changes: Vec::new(),
        failed: false,
    };
    walk.visit(c, 0.0, 1.0, 0);
    if walk.failed {
        return None;
    }
    if want == Want::Changes {
        walk.changes.sort_by(f64::total_cmp);
    }
    Some(Signs {
        zero: false,
        positive: walk.positive,
        negative: walk.negative,
        changes: walk.changes,
        exact: false,
        over_budget: false,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_traits::Zero;

    /// Scaled coefficients of Π (t - r) for dyadic roots, exactly (in u = t/(1-t), each factor
    /// (t - r)(1 + u) = (1 - r) u - r).
    fn from_roots(roots: &[f64]) -> (Vec<Bounded>, Vec<BigInt>) {
        let mut c = vec![1.0f64];
        for &r in roots {
            let mut n = vec![0.0; c.len() + 1];
            for (i, ci) in c.iter().enumerate() {
                n[i] += -r * ci;
                n[i + 1] += (1.0 - r) * ci;
            }
            c = n;
        }
        let ints = super::super::dyadic_integers(&c).0;
        (
            c.iter()
                .map(|v| Bounded {
                    v: *v,
                    e: 1e-15 * v.abs(),
                })
                .collect(),
            ints,
        )
    }

    #[test]
    fn the_filter_decides_clear_cases_and_defers_near_ones() {
        let (c, _) = from_roots(&[0.25, 0.625]);
        let s = certified_signs(&c, || panic!("the filter decides this"), Want::Changes);
        assert!(!s.exact && s.positive && s.negative);
        assert_eq!(s.changes.len(), 2);
        assert!(
            (s.changes[0] - 0.25).abs() < 2e-13 && (s.changes[1] - 0.625).abs() < 2e-13,
            "{s:?}"
        );
        // A double root: the filter cannot tell a touch from two close roots.
        let (c, ints) = from_roots(&[0.5, 0.5]);
        let s = certified_signs(&c, || ints, Want::Changes);
        assert!(
            s.exact && s.positive && !s.negative && s.changes.is_empty(),
            "{s:?}"
        );
        // Unknown is never zero: tiny coefficients with bounds bigger than they are.
        let c = [Bounded { v: 1e-20, e: 1e-18 }; 4];
        let s = certified_signs(
            &c,
            || {
                vec![
                    BigInt::from(-1),
                    <BigInt as Zero>::zero(),
                    BigInt::from(1),
                    BigInt::from(1),
                ]
            },
            Want::Signs,
        );
        assert!(s.exact && s.positive && s.negative);
    }
}
