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
//! it, `2^-43` away (up to `2^-40` where the bounds are wide). A change the filter proved
//! but could not place that closely is placed on the exact integer coefficients, by their
//! exact signs `2^-42` on either side of it (or exact bisection): a few evaluations, not a
//! gcd. Whatever else the filter leaves open goes to [`super::poly::sign_changes`] on the
//! exact integer coefficients.

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

impl Signs {
    /// The answer when the exact stage would be over [`EXACT_BUDGET`].
    fn over_budget() -> Self {
        Signs {
            exact: true,
            over_budget: true,
            ..Signs::default()
        }
    }

    /// Identically zero.
    fn zero() -> Self {
        Signs {
            zero: true,
            ..Signs::default()
        }
    }
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
    let unplaced = match filter(scaled, want) {
        Filtered::Decided(s) => return s,
        Filtered::Unplaced(p) => Some(p),
        Filtered::Undecided => None,
    };
    let c = exact();
    // An empty answer: the caller knew beforehand that it was over the budget.
    if c.is_empty() {
        return Signs::over_budget();
    }
    // The filter proved every sign change and only could not place some: place those on
    // the exact polynomial (a few evaluations, no gcd or Sturm sequence).
    if let Some(s) = unplaced.and_then(|partial| place_exactly(partial, &c)) {
        return s;
    }
    let bits = c.iter().map(|v| v.bits()).max().unwrap_or(0);
    if exact_cost(c.len().saturating_sub(1), bits) > EXACT_BUDGET {
        return Signs::over_budget();
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
            let mut b = c.div_int(super::binomial(d, i));
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

/// A number with the sign of the polynomial's value at `x` in (0, 1), in plain floating
/// point (for the search only; certificates use [`bounded_at`]): `Σ C(d,i) c_i r^i` with
/// `r = x / (1 - x)` by Horner (the value divided by `(1 - x)^d`), or from the other end in
/// `(1 - x) / x` when x > 1/2, so the ratio stays at most 1.
fn sign_value_at(c: &[Bounded], x: f64) -> f64 {
    let d = c.len() - 1;
    let s = 1.0 - x;
    let mut acc = 0.0;
    // The binomials C(d, i) step by step (exact up to far beyond the degrees met here; a
    // rounded one would only perturb the search, never a certificate).
    let mut b = 1.0;
    if x <= 0.5 {
        let r = x / s;
        for (i, ci) in c.iter().enumerate().rev() {
            acc = acc * r + b * ci.v;
            b = b * i as f64 / (d - i + 1) as f64;
        }
    } else {
        let r = s / x;
        for (i, ci) in c.iter().enumerate() {
            acc = acc * r + b * ci.v;
            b = b * (d - i) as f64 / (i + 1) as f64;
        }
    }
    acc
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
    /// Changes the filter proved (exactly one in their piece) but could not place within
    /// `2^-40`: their piece `(a, w)`, the sign at its start, and the float estimate.
    pending: Vec<Pending>,
    failed: bool,
}

/// A proven sign change still to be located (exactly).
#[derive(Clone, Copy, Debug)]
struct Pending {
    a: f64,
    w: f64,
    s0: i32,
    guess: f64,
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
                        Ok(r) => self.changes.push(a + w * r),
                        Err(r) => self.pending.push(Pending {
                            a,
                            w,
                            s0,
                            guess: a + w * r,
                        }),
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

    /// Where the piece's one change is, in plain floating point (local parameter, within
    /// about `2^-47` in t), by [`crate::solve::roots::illinois`] on the bracket [0, 1].
    fn search(&self, c: &[Bounded], s0: i32, w: f64) -> f64 {
        let f = |x: f64| Ok(sign_value_at(c, x) * s0 as f64);
        // The end coefficients' signs are known: s0 (or an exact zero) at the start, -s0 (or
        // an exact zero) at the end; a zero end stands in as the smallest value of its sign,
        // so the bracket is one and the search moves off that end.
        let flo = (c[0].v * s0 as f64).max(f64::MIN_POSITIVE);
        let fhi = (c[c.len() - 1].v * s0 as f64).min(-f64::MIN_POSITIVE);
        // 200 steps, every fourth a bisection, always reach the tolerance; were they not to,
        // the certificate below would fail and the change go to exact placement.
        crate::solve::roots::illinois(f, (0.0, flo), (1.0, fhi), (-47f64).exp2() / w, 200)
            .unwrap_or(0.5)
    }

    /// The one sign change of the piece (local parameter), certified within `2^-40` in t;
    /// `Err(estimate)` when the bounds are too wide to certify it there.
    fn locate(&self, c: &[Bounded], s0: i32, w: f64) -> Result<f64, f64> {
        let r = self.search(c, s0, w);
        // Certified as close as the bounds allow, at most 2^-40 (9.1e-13) away in t.
        for bits in [43, 41, 40] {
            let d = (-(bits as f64)).exp2() / w;
            let (x1, x2) = ((r - d).max(0.0), (r + d).min(1.0));
            let (v1, v2) = (bounded_at(c, x1).sign(), bounded_at(c, x2).sign());
            if v1 == Some(s0) && v2 == Some(-s0) {
                return Ok(r);
            }
        }
        Err(r)
    }
}

/// The filter's answer with some proven changes not yet placed.
struct Partial {
    signs: Signs,
    pending: Vec<Pending>,
}

/// Separation below which two placed changes might be one root seen twice.
const PLACED: f64 = 1.0 / (1u64 << 42) as f64;

/// Places the filter's pending changes on the exact polynomial `c`. Each is placed at `x`
/// once the exact signs at `x ∓ 2^-42` are the piece's start sign and its opposite: a
/// change lies within `2^-42` of `x`. Such an interval, from floating-point ends, may reach
/// past its piece, so the placed changes must also lie more than `2^-41` apart: then the
/// filter's count (one change per piece) and the placements match one to one. `None` (the
/// full exact analysis decides) when a bracket's exact signs disagree with the filter's.
fn place_exactly(partial: Partial, c: &[BigInt]) -> Option<Signs> {
    let p = poly::IntPoly::new(c.to_vec());
    let sign = |t: f64| poly::sign_at_f64(&p, t);
    let mut signs = partial.signs;
    for q in partial.pending {
        let brackets = |x: f64| sign(x - PLACED) == q.s0 && sign(x + PLACED) == -q.s0;
        if brackets(q.guess) {
            signs.changes.push(q.guess);
            continue;
        }
        // Bisection on the exact sign over the whole piece.
        let (mut lo, mut hi) = (q.a, q.a + q.w);
        if sign(lo) != q.s0 || sign(hi) != -q.s0 {
            return None;
        }
        while hi - lo > PLACED {
            let m = 0.5 * (lo + hi);
            if m <= lo || m >= hi {
                break;
            }
            match sign(m) {
                0 => {
                    lo = m;
                    hi = m;
                }
                v if v == q.s0 => lo = m,
                _ => hi = m,
            }
        }
        signs.changes.push(0.5 * (lo + hi));
    }
    signs.changes.sort_by(f64::total_cmp);
    if signs
        .changes
        .windows(2)
        .any(|w| w[1] - w[0] <= 2.0 * PLACED)
    {
        return None;
    }
    signs.exact = true;
    Some(signs)
}

/// What the filter made of a polynomial.
enum Filtered {
    Decided(Signs),
    /// Every sign change proven, some not placed closely enough.
    Unplaced(Partial),
    Undecided,
}

/// The filter on scaled coefficients.
fn filter(scaled: &[Bounded], want: Want) -> Filtered {
    if scaled.is_empty() {
        return Filtered::Decided(Signs::zero());
    }
    walk_plain(&unscale(scaled), want)
}

/// The filter on ordinary Bernstein coefficients with their bounds: `None` when it cannot
/// decide.
pub fn filter_plain(c: &[Bounded], want: Want) -> Option<Signs> {
    match walk_plain(c, want) {
        Filtered::Decided(s) => Some(s),
        Filtered::Unplaced(_) | Filtered::Undecided => None,
    }
}

fn walk_plain(c: &[Bounded], want: Want) -> Filtered {
    if c.iter().all(|c| c.v == 0.0 && c.e == 0.0) {
        return Filtered::Decided(Signs::zero());
    }
    let mut walk = Walk {
        want,
        pieces: 0,
        positive: false,
        negative: false,
        last: 0,
        changes: Vec::new(),
        pending: Vec::new(),
        failed: false,
    };
    walk.visit(c, 0.0, 1.0, 0);
    if walk.failed {
        return Filtered::Undecided;
    }
    if want == Want::Changes {
        walk.changes.sort_by(f64::total_cmp);
    }
    let signs = Signs {
        zero: false,
        positive: walk.positive,
        negative: walk.negative,
        changes: walk.changes,
        exact: false,
        over_budget: false,
    };
    if walk.pending.is_empty() {
        Filtered::Decided(signs)
    } else {
        Filtered::Unplaced(Partial {
            signs,
            pending: walk.pending,
        })
    }
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

    /// Bounds too wide to certify a change within 2^-40 (1e-9 of each coefficient): the
    /// filter still proves how many changes there are, and the exact signs place them.
    #[test]
    fn proven_changes_are_placed_exactly_when_the_bounds_are_wide() {
        for roots in [
            vec![0.25, 0.625],
            // Dyadic roots with few bits, so that the coefficients are exact.
            vec![0.0078125, 0.296875, 0.296875 + 2f64.powi(-20), 0.9990234375],
        ] {
            let (mut c, ints) = from_roots(&roots);
            for v in &mut c {
                v.e = 1e-9 * v.v.abs().max(1e-300);
            }
            let s = certified_signs(&c, || ints.clone(), Want::Changes);
            assert!(s.exact && !s.over_budget, "{roots:?}: {s:?}");
            assert_eq!(s.changes.len(), roots.len(), "{roots:?}: {s:?}");
            for (got, want) in s.changes.iter().zip(&roots) {
                assert!((got - want).abs() <= 2.3e-13, "{roots:?}: {s:?}");
            }
        }
    }
}
