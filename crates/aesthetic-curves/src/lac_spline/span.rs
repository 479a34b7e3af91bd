//! One span of the spline: the log-aesthetic curve between two points with given tangent
//! directions (G1 Hermite data), and its end curvatures. Worked in the chord frame: the
//! start at 0, the end at 1, so only the tangents' deviations from the chord matter.
//!
//! - Both deviations (nearly) zero: a line.
//! - Deviations of opposite signs and equal size: a circular arc (every α has it), of any
//!   turning below a full turn.
//! - Deviations of opposite signs (the span bends one way) in the existence region of α:
//!   one [`LacSegment`] in the triangle the tangents make.
//! - Otherwise (an S, or for α < 0 a bend too lopsided for one segment): two
//!   inflection-end halves of the same curve mirrored about their common inflection point
//!   (same α, same scale), the inflection's tangent found by a one-variable root. At the edge
//!   of the existence region the short half vanishes and the pair is the one segment, so the
//!   end curvatures are continuous across the edge (α < 0).
//! - α >= 0 has no inflection-end segment (its curvature reaches zero only at infinite
//!   length): an S-shaped span's halves are clothoid-like (α = -1), and for α > 1 a bend
//!   outside the existence region takes the α nearest the requested one that has a segment.

use crate::error::{Error, Result};
use crate::lac::{LacInflectionSegment, LacSegment};
use crate::solve::roots::{illinois, illinois_bracket, newton};
use kurbo::Vec2;
use std::f64::consts::PI;

/// The most one segment of a span may turn (radians): past a half turn it is built in two
/// halves of its turning (pieces.rs).
pub(super) const MAX_TURN: f64 = 1.8 * PI;

/// The most one segment may turn in the wider family.
pub(super) const WIDE_TURN: f64 = 1.95 * PI;

/// The most each inflection-end half of an S-span may turn (radians): a half turn in the
/// spline's own family (where the pair is unique), up to [`WIDE_HALF`] in the wider family
/// the solve falls back on (`system::solve`).
pub(super) const HALF_TURN: f64 = PI;

/// The most a half may turn in the wider family: libspiro's clothoid splines through sharp
/// turns have S-spans whose one side winds past a half turn (the harsh sets of
/// `tests/spiro_oracle.rs`: 130 of the 138 it solved and the narrow family did not), which a half
/// of this family holds as an inflection-end piece and a segment (pieces.rs).
pub(super) const WIDE_HALF: f64 = 1.8 * PI;

/// A pair's mismatch (radians) within this of zero at an end of its range is a root there
/// (rounding of the halves' chords, which are integrals, is far below it).
const EDGE_MISMATCH: f64 = 1e-12;

/// Deviations below this (radians, summed) make a span a line.
const LINE_TURN: f64 = 2e-9;

/// The shape α of an S-span's halves for a requested α.
pub(super) fn pair_alpha(alpha: f64) -> f64 {
    if alpha < 0.0 {
        alpha
    } else {
        -1.0
    }
}

/// The span's curve in the chord frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Shape {
    /// A straight line.
    Line,
    /// A circular arc turning by `turn` (signed, counter-clockwise positive, |turn| < 2π).
    Arc { turn: f64 },
    /// One segment of shape `alpha` (the requested one, or the nearest that exists).
    Lac { alpha: f64 },
    /// Two inflection-end halves of shape `alpha` and scale `scale` (chord lengths) meeting
    /// at the inflection with tangent angle `psi`; `side` is +1 when the second half turns
    /// counter-clockwise.
    Pair {
        alpha: f64,
        psi: f64,
        side: f64,
        scale: f64,
        inflection: Vec2,
    },
}

/// A solved span: its shape and its signed curvatures at the start and the end, in units
/// of one over the chord length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Solved {
    pub(super) shape: Shape,
    pub(super) kappa: (f64, f64),
}

/// The span whose tangents leave the chord by `a` at the start and `b` at the end (radians,
/// counter-clockwise positive), for the requested `alpha`, an S-span's halves turning less
/// than `half` each ([`HALF_TURN`] or [`WIDE_HALF`]).
pub(super) fn solve(alpha: f64, a: f64, b: f64, half: f64) -> Result<Solved> {
    // The wider family: a deviation past a half turn (a span that winds), one segment up
    // to [`WIDE_TURN`].
    let wide = half > HALF_TURN;
    let most = if wide { 2.0 * PI } else { PI };
    if !(a.abs() < most && b.abs() < most) {
        return Err(Error::NoSegment(format!(
            "a span's tangent turns {:.1} deg from its chord: no fair curve between them",
            a.abs().max(b.abs()).to_degrees()
        )));
    }
    if a.abs() + b.abs() <= LINE_TURN {
        return Ok(Solved {
            shape: Shape::Line,
            kappa: (0.0, 0.0),
        });
    }
    if a * b < 0.0 && (a + b).abs() <= 1e-12 * (a.abs() + b.abs()) && b.abs() < PI {
        // A circular arc (every α): its curvature 2 sin(b) over the chord, whatever its
        // turning 2|b| (up to a full turn; the pieces split it).
        let k = 2.0 * b.sin();
        return Ok(Solved {
            shape: Shape::Arc { turn: 2.0 * b },
            kappa: (k, k),
        });
    }
    let most_turn = if wide { WIDE_TURN } else { MAX_TURN };
    if a * b < 0.0 && a.abs() + b.abs() < most_turn {
        if let Some(s) = one_segment(alpha, a, b)? {
            return Ok(s);
        }
    }
    pair(pair_alpha(alpha), a, b, half)
}

/// The control triangle of the chord frame for deviations `a`, `b` of opposite signs.
pub(super) fn triangle(a: f64, b: f64) -> [kurbo::Point; 3] {
    // Apex where the start tangent (angle a) meets the end tangent (angle b) through 1.
    let (ta, tb) = (Vec2::from_angle(a), Vec2::from_angle(b));
    let s = (Vec2::new(1.0, 0.0)).cross(tb) / ta.cross(tb);
    [
        kurbo::Point::ZERO,
        (ta * s).to_point(),
        kurbo::Point::new(1.0, 0.0),
    ]
}

/// One segment for a bend, or `None` when α < 0 and the bend lies outside the existence
/// region (the pair continues it). Only its end curvatures are computed here.
fn one_segment(alpha: f64, a: f64, b: f64) -> Result<Option<Solved>> {
    let theta_d = a.abs() + b.abs();
    let phi = a.abs().max(b.abs());
    // At the high-curvature end first; the sign of the turn (b > 0: counter-clockwise);
    // `None` outside the existence region.
    let kappa = |alpha: f64| -> Result<Option<(f64, f64)>> {
        let found = match LacSegment::unit_chord_curvatures(alpha, theta_d, phi) {
            // Λ solved onto the existence region's edge, where the low-curvature end lands
            // on the standard form's zero curvature within rounding and the integral
            // refuses it: for α < 0 that is the pair's inflection-end segment, which the
            // pair builds (a half of no turning), not a refusal.
            Err(Error::NoConvergence(_)) if alpha < 0.0 => None,
            other => other?,
        };
        let s = b.signum();
        Ok(found.map(|(hi, lo)| {
            if a.abs() >= b.abs() {
                (s * hi, s * lo)
            } else {
                (s * lo, s * hi)
            }
        }))
    };
    let lac = |alpha: f64, kappa: (f64, f64)| {
        Some(Solved {
            shape: Shape::Lac { alpha },
            kappa,
        })
    };
    if let Some(k) = kappa(alpha)? {
        return Ok(lac(alpha, k));
    }
    if phi - 0.5 * theta_d <= 1e-12 * theta_d {
        // Within rounding of the circle (a rounding below θ_d/2): the circle.
        let k = 2.0 * (0.5 * theta_d).sin() * b.signum();
        return Ok(lac(alpha, (k, k)));
    }
    let none = |alpha: f64| {
        Error::NoSegment(format!(
            "no segment of alpha {alpha} in a triangle turning {:.1} deg",
            theta_d.to_degrees()
        ))
    };
    if alpha < 0.0 {
        return Ok(None);
    }
    if alpha <= 1.0 {
        // Every triangle has a segment for α in [0, 1]: only rounding at the region's edge.
        return Err(none(alpha));
    }
    // α > 1: the nearest α that has one.
    let alpha = nearest_existing(alpha, theta_d, phi)?;
    match kappa(alpha)? {
        Some(k) => Ok(lac(alpha, k)),
        None => Err(none(alpha)),
    }
}

/// How far below the limit [`nearest_existing`] stays, relative to α: at the limit itself
/// the segment degenerates (Λ at its largest, the curvature ratio unbounded), and a span
/// solved there stalled the G2 solve's Newton runs. 1e-4 of α is below what a designer
/// reads (α 2.9997 for 3); on 770 point sets (the α sweep's kinds and 20 wavy points),
/// the margin at 1e-12 left 866 spans at another α and 8 sets unanswered, at 1e-4 697 and
/// 4, in half the time.
const NEAREST_MARGIN: f64 = 1e-4;

/// For α > 1 outside its region: the α' in [1, α) nearest it whose segment exists (α = 1,
/// the logarithmic spiral, exists in every triangle), [`NEAREST_MARGIN`] below the limit:
/// the sign change of θ_lim(α') - φ (positive at α' = 1, where θ_lim = θ_d > φ) by regula
/// falsi (some ten limits θ_lim where bisection took forty).
fn nearest_existing(alpha: f64, theta_d: f64, phi: f64) -> Result<f64> {
    let g = |a: f64| LacSegment::theta_lim(a, theta_d).map(|lim| lim - phi);
    let tol = 1e-12 * alpha.abs().max(1.0);
    // The limit at α itself may not evaluate (a curve too extreme for f64): no segment
    // there, and the bracket's end value a plain negative one.
    let at_alpha = g(alpha).unwrap_or(-(theta_d - phi));
    if at_alpha > 0.0 {
        // The limit says α itself has a segment where the Λ solve found none (rounding at
        // the region's edge): the α just below it.
        return Ok((alpha - NEAREST_MARGIN * alpha).max(1.0));
    }
    let b = illinois_bracket(g, (1.0, theta_d - phi), (alpha, at_alpha), tol, 200)?;
    // The end of positive value (a zero is no segment: φ must lie below the limit).
    let root = if b.lo.1 > 0.0 {
        b.lo.0
    } else if b.hi.1 > 0.0 {
        b.hi.0
    } else {
        b.lo.0 - tol
    };
    Ok(1.0f64.max(root - NEAREST_MARGIN * alpha))
}

/// The chord of both halves per unit scale for inflection tangent `psi`, family `side`:
/// `W(t1) + W(t2)` (mirrored for side -1), with `t1 = side (a - ψ)`, `t2 = side (b - ψ)`.
struct PairGeometry {
    alpha: f64,
    a: f64,
    b: f64,
    side: f64,
    /// The most a half may turn.
    half: f64,
}

impl PairGeometry {
    fn turns(&self, psi: f64) -> (f64, f64) {
        (self.side * (self.a - psi), self.side * (self.b - psi))
    }

    fn chords(&self, psi: f64) -> Result<(Vec2, Vec2)> {
        let (t1, t2) = self.turns(psi);
        let w = |t: f64| -> Result<Vec2> {
            let c = LacInflectionSegment::standard_chord(self.alpha, t.max(0.0))?;
            Ok(Vec2::new(c.x, self.side * c.y))
        };
        Ok((w(t1)?, w(t2)?))
    }

    /// The angle of the pair's chord from the x axis, less zero: a root puts B at 1.
    fn mismatch(&self, psi: f64) -> Result<f64> {
        let (w1, w2) = self.chords(psi)?;
        let v = w1 + w2;
        Ok(psi + v.y.atan2(v.x))
    }

    /// [`Self::mismatch`] and its derivative in ψ. A half's chord moves with its turning t
    /// as the standard segment's end does: `dW/dt = e^{it} / κ(t)` (its tangent over its
    /// curvature there), and `t` moves by `-side` per unit of ψ.
    fn mismatch_slope(&self, psi: f64) -> Result<(f64, f64)> {
        let (t1, t2) = self.turns(psi);
        let (w1, w2) = self.chords(psi)?;
        let v = w1 + w2;
        let moved = |t: f64| {
            let k = LacInflectionSegment::standard_end_kappa(self.alpha, t);
            Vec2::new(-self.side * t.cos(), -t.sin()) / k
        };
        let dv = moved(t1) + moved(t2);
        Ok((psi + v.y.atan2(v.x), 1.0 + v.cross(dv) / v.hypot2()))
    }

    /// A start for the root: the inflection tangent of the S-shaped clothoid span of small
    /// deviations (curvature linear in arc length, `κ₀ = -4a - 2b`, `κ₁ = 2a + 4b` over the
    /// chord, zero at `s = (2a + b) / 3(a + b)`): `ψ = a - (2a + b)² / 3(a + b)`, where
    /// that lies in `range`.
    fn start(&self, (lo, hi): (f64, f64)) -> Option<f64> {
        let (a, b) = (self.a, self.b);
        let psi = a - (2.0 * a + b).powi(2) / (3.0 * (a + b));
        (psi > lo && psi < hi).then_some(psi)
    }

    /// The range of ψ where both halves turn by (0, `half`]: below both deviations for
    /// side +1, above both for side -1.
    fn range(&self) -> Option<(f64, f64)> {
        let (lo, hi) = (self.a.min(self.b), self.a.max(self.b));
        if hi - lo >= self.half {
            return None;
        }
        Some(if self.side > 0.0 {
            (hi - self.half, lo)
        } else {
            (hi, lo + self.half)
        })
    }

    /// The root of the mismatch over the range, if any: the mismatch increases with ψ
    /// (the chord's angle moves slower than ψ, the base angle of a half turning t staying
    /// below t/2; checked at 401 points of 4000 random families by a unit test), so there is
    /// at most one. Where the small-angle start ([`Self::start`]) lies in the range, Newton's
    /// method with the exact slope from there (2 or 3 evaluations near the root, where the
    /// halves turn little and their chords are cheap); a step that converges inside the
    /// range is the root (a monotone function's Newton steps shrink only at its root).
    /// Otherwise, or if that fails, a sign change between the range's ends (where a half
    /// turns by π) brackets the root, found by Newton's method from the middle, by
    /// Illinois' where that does not converge.
    fn root(&self) -> Result<Option<f64>> {
        let Some((lo, hi)) = self.range() else {
            return Ok(None);
        };
        let slope = |x: f64| self.mismatch_slope(x).map(|(f, d)| (f, d, ()));
        if let Some(x0) = self.start((lo, hi)) {
            if let Ok(r) = newton(slope, x0, (lo, hi), true, 1e-15, 0.0, 12) {
                let margin = 1e-9 * (hi - lo);
                if r.converged && r.x > lo + margin && r.x < hi - margin {
                    return Ok(Some(r.x));
                }
            }
        }
        let (f0, f1) = (self.mismatch(lo)?, self.mismatch(hi)?);
        // A root within rounding of an end (a half of no turning: the one segment at the
        // existence region's edge, where its own solve refuses by rounding) is that end.
        if f0.abs() <= EDGE_MISMATCH {
            return Ok(Some(lo));
        }
        if f0 * f1 >= 0.0 {
            return Ok((f1.abs() <= EDGE_MISMATCH).then_some(hi));
        }
        let r = newton(slope, 0.5 * (lo + hi), (lo, hi), true, 1e-15, 0.0, 40)?;
        if r.converged {
            return Ok(Some(r.x));
        }
        illinois(|x| self.mismatch(x), (lo, f0), (hi, f1), 1e-15, 200).map(Some)
    }

    /// The solved pair at root `psi`: both halves must turn (a half of zero turning is the
    /// one segment at the region's edge, which `solve` builds instead).
    fn solved(&self, psi: f64) -> Result<Option<Solved>> {
        let (t1, t2) = self.turns(psi);
        // A half may turn by nothing within rounding: at the existence region's edge the
        // pair is the one inflection-end segment of the other half (which the one-segment
        // solve may refuse there by rounding).
        let edge = 1e-12 * (t1.abs() + t2.abs());
        if !(t1 > -edge && t2 > -edge && t1.max(t2) > 0.0 && t1 < self.half && t2 < self.half) {
            return Ok(None);
        }
        let (t1, t2) = (t1.max(0.0), t2.max(0.0));
        let (w1, w2) = self.chords(psi)?;
        let scale = 1.0 / (w1 + w2).hypot();
        let k = |t: f64| LacInflectionSegment::standard_end_kappa(self.alpha, t) / scale;
        let inflection = Vec2::from_angle(psi);
        let m = kurbo::Vec2::new(
            inflection.x * w1.x - inflection.y * w1.y,
            inflection.x * w1.y + inflection.y * w1.x,
        ) * scale;
        Ok(Some(Solved {
            shape: Shape::Pair {
                alpha: self.alpha,
                psi,
                side: self.side,
                scale,
                inflection: m,
            },
            kappa: (-self.side * k(t1), self.side * k(t2)),
        }))
    }
}

/// The S-span (or the continuation of a lopsided bend): of the roots of both families, the
/// pair that turns least in all.
fn pair(alpha: f64, a: f64, b: f64, half: f64) -> Result<Solved> {
    let mut best: Option<(f64, Solved)> = None;
    for side in [1.0, -1.0] {
        let g = PairGeometry {
            alpha,
            a,
            b,
            side,
            half,
        };
        if let Some(psi) = g.root()? {
            if let Some(s) = g.solved(psi)? {
                let (t1, t2) = g.turns(psi);
                if best.as_ref().is_none_or(|(t, _)| t1 + t2 < *t) {
                    best = Some((t1 + t2, s));
                }
            }
        }
    }
    best.map(|b| b.1).ok_or_else(|| {
        Error::NoSegment(format!(
            "no log-aesthetic curve of alpha {alpha} between tangents {:.3} and {:.3} deg \
             from the chord",
            a.to_degrees(),
            b.to_degrees()
        ))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_symmetric_bend_is_a_circle_and_a_straight_span_a_line() {
        // Deviations -φ and φ: an arc of radius 1/(2 sin φ) through 0 and 1.
        for alpha in [-2.0, -1.0, 0.0, 1.0, 2.0] {
            let s = solve(alpha, -0.4, 0.4, HALF_TURN).unwrap();
            let k = 2.0 * 0.4f64.sin();
            assert!((s.kappa.0 - k).abs() < 1e-12 && (s.kappa.1 - k).abs() < 1e-12);
            // The same from the segment of a triangle a rounding away from isosceles.
            let s = solve(alpha, -0.4 * (1.0 + 1e-11), 0.4, HALF_TURN).unwrap();
            assert!((s.kappa.0 - k).abs() < 1e-9 && (s.kappa.1 - k).abs() < 1e-9);
        }
        assert_eq!(solve(-1.0, 0.0, 0.0, HALF_TURN).unwrap().shape, Shape::Line);
    }

    #[test]
    fn an_s_span_is_a_point_symmetric_pair_when_its_deviations_are_equal() {
        // a = b: the S is symmetric about the chord's midpoint; the inflection sits there.
        let s = solve(-1.0, 0.3, 0.3, HALF_TURN).unwrap();
        let Shape::Pair { inflection, .. } = s.shape else {
            panic!("{s:?}")
        };
        assert!(
            (inflection - Vec2::new(0.5, 0.0)).hypot() < 1e-12,
            "{inflection:?}"
        );
        assert!((s.kappa.0 + s.kappa.1).abs() < 1e-12 && s.kappa.0 < 0.0);
    }

    #[test]
    fn the_pair_continues_the_segment_across_the_edge_of_the_region() {
        // α = -1: along a = -ε (one segment) to a = +ε (a pair), b fixed, the end
        // curvatures move continuously through the region's edge.
        let b = 0.6;
        let mut last: Option<(f64, f64)> = None;
        let mut kinds = Vec::new();
        for k in 0..=400 {
            let a = -0.3 + 0.6 * k as f64 / 400.0;
            let s = solve(-1.0, a, b, HALF_TURN).unwrap();
            kinds.push(matches!(s.shape, Shape::Lac { .. }));
            if let Some(l) = last {
                assert!(
                    (s.kappa.0 - l.0).abs() < 0.05 && (s.kappa.1 - l.1).abs() < 0.05,
                    "a = {a}: {:?} after {l:?}",
                    s.kappa
                );
            }
            last = Some(s.kappa);
        }
        assert!(kinds.first() == Some(&true) && kinds.last() == Some(&false));
    }

    #[test]
    fn the_mismatch_increases_with_the_inflection_tangent() {
        // What `root` relies on: one root per family at most.
        let mut rng = crate::samples::SplitMix64::new(1);
        for _ in 0..2000 {
            let alpha = rng.range(-5.0, -0.01);
            let (a, b) = (rng.range(-3.0, 3.0), rng.range(-3.0, 3.0));
            for side in [1.0, -1.0] {
                let g = PairGeometry {
                    alpha,
                    a,
                    b,
                    side,
                    half: PI,
                };
                let Some((lo, hi)) = g.range() else { continue };
                let mut last = f64::NEG_INFINITY;
                for k in 0..=400 {
                    let v = g.mismatch(lo + (hi - lo) * k as f64 / 400.0).unwrap();
                    assert!(
                        v >= last - 1e-12,
                        "alpha {alpha}, a {a}, b {b}, side {side}"
                    );
                    last = v;
                }
            }
        }
    }

    /// The root's exact slope against central differences of the mismatch (an oracle that
    /// does not use the slope's formula), over random families inside their ranges; and the
    /// root found by Newton's method equal to Illinois' on the whole range.
    #[test]
    fn the_mismatch_slope_is_the_mismatch_derivative() {
        let mut rng = crate::samples::SplitMix64::new(5);
        let (mut checked, mut roots) = (0, 0);
        for _ in 0..1500 {
            let alpha = rng.range(-5.0, -0.05);
            let (a, b) = (rng.range(-2.5, 2.5), rng.range(-2.5, 2.5));
            for side in [1.0, -1.0] {
                let g = PairGeometry {
                    alpha,
                    a,
                    b,
                    side,
                    half: PI,
                };
                let Some((lo, hi)) = g.range() else { continue };
                for k in 1..8 {
                    let x = lo + (hi - lo) * k as f64 / 8.0;
                    let h = 1e-6 * (hi - lo);
                    let (Ok(p), Ok(m), Ok((_, d))) =
                        (g.mismatch(x + h), g.mismatch(x - h), g.mismatch_slope(x))
                    else {
                        continue;
                    };
                    let fd = (p - m) / (2.0 * h);
                    assert!(
                        (fd - d).abs() <= 1e-5 * d.abs().max(1.0),
                        "alpha {alpha}, a {a}, b {b}, side {side}, psi {x}: {d} vs {fd}"
                    );
                    checked += 1;
                }
                let (Ok(f0), Ok(f1)) = (g.mismatch(lo), g.mismatch(hi)) else {
                    continue;
                };
                if f0 * f1 < 0.0 {
                    let want = illinois(|x| g.mismatch(x), (lo, f0), (hi, f1), 1e-15, 200).unwrap();
                    let got = g.root().unwrap().unwrap();
                    assert!((got - want).abs() <= 1e-12, "{got} vs {want}");
                    roots += 1;
                }
            }
        }
        assert!(checked > 10_000 && roots > 500, "{checked} {roots}");
    }
}
