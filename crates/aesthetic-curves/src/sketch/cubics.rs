//! Stage 6: each piece's rational cubic ([`crate::approx`]), G2 to its LAC at both ends and
//! proven curvature-monotone by the exact test, with a memo of the pieces fitted so far and
//! warm starts for inflection-end pieces of a nearby shape.

use super::pieces::Built;
use super::slot::Slot;

use super::types::{PieceCurve, PieceKind, PieceShape, SketchPiece};
use crate::approx::{
    fit_inflection_cubic_from, fit_rational_cubic, ApproxOptions, RationalCubicFit,
};
use crate::error::{Error, Result};
use crate::lac::{LacInflectionSegment, ALPHA_RANGE};
use kurbo::Point;
use rayon::prelude::*;
use std::collections::HashMap;

/// What the cubic stage hands back.
pub(super) enum Cubics {
    /// Every piece with its cubic, in curve order.
    Pieces(Vec<SketchPiece>),
    /// Piece `i` has no curvature-monotone cubic (a LAC segment turning too far for its
    /// curvature range, an inflection piece of α near 0): it is to be split and the round
    /// repeated.
    Split(usize),
}

/// The cubics of the rounds so far: fits by exact segment, and the optima of the
/// inflection-end fits by shape (α, θ_d), the warm starts of later rounds, whose pieces
/// differ only a little.
#[derive(Default)]
pub(super) struct CubicCache {
    memo: HashMap<[u64; 8], RationalCubicFit>,
    inflection_starts: Vec<InflectionStart>,
}

/// A cubic fit and, for an inflection-end piece of a new shape, its optimum.
type Fitted = (RationalCubicFit, Option<InflectionStart>);

impl CubicCache {
    /// The cubics of `built` (pieces of `slots`): fitted in parallel (each fit is pure work
    /// on its own piece; the memo and the warm starts are read there and updated here in
    /// curve order). A piece without a monotone cubic asks for a split while `max_pieces`
    /// allows one (an inflection piece's halves re-solve their α: one whose α is near 0⁻
    /// has a curvature that reaches zero over so long a run that no cubic of its family
    /// is proven monotone); past that, an inflection piece without one gets the G2 cubic of
    /// its family's centre, reported as not monotone.
    pub(super) fn pieces(
        &mut self,
        slots: &[Slot],
        built: Vec<Built>,
        approx: &ApproxOptions,
        max_pieces: usize,
    ) -> Result<Cubics> {
        let fits: Vec<Result<Fitted>> = built.par_iter().map(|b| self.fit(b, approx)).collect();
        let mut pieces = Vec::with_capacity(slots.len());
        for ((s, b), fitted) in slots.iter().zip(built).zip(fits) {
            let (control, rat) = match (&b.curve, fitted) {
                (PieceCurve::Lac(seg), Ok((f, _))) => {
                    self.memo.insert(lac_key(seg), f.clone());
                    (seg.control, f)
                }
                (PieceCurve::Lac(_), Err(Error::NoSegment(_))) if slots.len() < max_pieces => {
                    return Ok(Cubics::Split(pieces.len()));
                }
                (
                    PieceCurve::Inflection {
                        segment,
                        inflection_at_start,
                    },
                    fitted,
                ) => {
                    let f = match fitted {
                        Ok((f, start)) => {
                            if let Some(st) = start.filter(|st| st.1 .0.is_finite()) {
                                self.inflection_starts.push(st);
                            }
                            self.memo.insert(inflection_key(segment), f.clone());
                            f
                        }
                        Err(Error::NoSegment(_)) => inflection_fallback(segment)?,
                        Err(e) => return Err(e),
                    };
                    if !f.monotone && slots.len() < max_pieces {
                        return Ok(Cubics::Split(pieces.len()));
                    }
                    in_curve_order(segment.control, f, *inflection_at_start)
                }
                (PieceCurve::Lac(_), Err(e)) => return Err(e),
            };
            pieces.push(piece(s, b, control, rat));
        }
        Ok(Cubics::Pieces(pieces))
    }

    /// One piece's cubic: from the memo, or fitted (an inflection-end piece warm-started
    /// from the optimum of the nearest shape fitted so far; the same shape has the same
    /// optimum).
    fn fit(&self, b: &Built, approx: &ApproxOptions) -> Result<Fitted> {
        match &b.curve {
            PieceCurve::Lac(seg) => match self.memo.get(&lac_key(seg)) {
                Some(f) => Ok((f.clone(), None)),
                None => fit_rational_cubic(seg, approx).map(|f| (f, None)),
            },
            PieceCurve::Inflection { segment, .. } => {
                if let Some(f) = self.memo.get(&inflection_key(segment)) {
                    return Ok((f.clone(), None));
                }
                let shape = (segment.alpha, segment.theta_d);
                let same = self.inflection_starts.iter().any(|(k, _)| {
                    k.0.to_bits() == shape.0.to_bits() && k.1.to_bits() == shape.1.to_bits()
                });
                fit_inflection_cubic_from(segment, approx, self.warm_start(shape), !same)
                    .map(|(f, x)| (f, (!same).then_some((shape, x))))
            }
        }
    }

    /// The optimum of the nearest shape within 0.25 in α and 10 % in θ_d.
    fn warm_start(&self, shape: (f64, f64)) -> Option<(f64, f64)> {
        let d = |k: (f64, f64)| (k.0 - shape.0).abs() + (k.1 - shape.1).abs();
        self.inflection_starts
            .iter()
            .filter(|(k, _)| {
                (k.0 - shape.0).abs() <= 0.25 && (k.1 - shape.1).abs() <= 0.1 * shape.1
            })
            .min_by(|a, b| d(a.0).total_cmp(&d(b.0)))
            .map(|e| e.1)
    }
}

fn lac_key(seg: &crate::lac::LacSegment) -> [u64; 8] {
    memo_key(0, seg.standard.alpha().to_bits(), &seg.control)
}

fn inflection_key(seg: &LacInflectionSegment) -> [u64; 8] {
    memo_key(1, seg.alpha.to_bits(), &seg.control)
}

/// An inflection-end segment's control triangle and cubic in curve order (the segment's
/// own order starts at the inflection).
fn in_curve_order(
    c: [Point; 3],
    mut f: RationalCubicFit,
    inflection_at_start: bool,
) -> ([Point; 3], RationalCubicFit) {
    if inflection_at_start {
        (c, f)
    } else {
        f.curve = f.curve.reversed();
        ([c[2], c[1], c[0]], f)
    }
}

/// The delivered piece of a slot.
fn piece(s: &Slot, b: Built, control: [Point; 3], rat: RationalCubicFit) -> SketchPiece {
    let kind = b.curve.kind();
    SketchPiece {
        kind,
        alpha: b.alpha,
        alpha_estimate: if kind == PieceKind::Lac {
            s.alpha
        } else {
            None
        },
        control,
        curve: b.curve,
        end_curvatures: b.kappa,
        rational: rat.curve,
        rational_error: rat.max_error,
        monotone: rat.monotone,
        alpha_at_bound: b.alpha <= ALPHA_RANGE.0 + 1e-9 || b.alpha >= ALPHA_RANGE.1 - 1e-9,
        alpha_range: None,
        u_range: (s.ua, s.ub),
    }
}

/// An inflection-end piece's shape (α, θ_d) and the optimum (f0, ln w0) of its cubic.
type InflectionStart = ((f64, f64), (f64, f64));

/// The memo key of a piece: its kind, alpha and control points, bit for bit.
fn memo_key(kind: u64, alpha: u64, c: &[Point; 3]) -> [u64; 8] {
    [
        kind,
        alpha,
        c[0].x.to_bits(),
        c[0].y.to_bits(),
        c[1].x.to_bits(),
        c[1].y.to_bits(),
        c[2].x.to_bits(),
        c[2].y.to_bits(),
    ]
}

/// Points of an inflection piece its fallback cubic is measured against.
const FALLBACK_SAMPLES: usize = 2000;

/// The inflection-family cubic at (f0, w0) = (0.5, 1), measured like a fit: its distance
/// from the segment over the segment's arc length (the fit's measure), here to a polyline
/// of [`FALLBACK_SAMPLES`] of the segment's points.
fn inflection_fallback(seg: &LacInflectionSegment) -> Result<crate::approx::RationalCubicFit> {
    use crate::bezier::PlanarCurve;
    use crate::monotone::CurvatureMonotone;
    let curve = crate::approx::inflection_cubic(seg, 0.5, 1.0)
        .ok_or_else(|| Error::NoConvergence("no G2 cubic for an inflection piece".into()))?;
    let monotone = curve.is_curvature_monotone().unwrap_or(false);
    let exact = seg.sample(FALLBACK_SAMPLES)?.points;
    let m = FALLBACK_SAMPLES / 4;
    let on_cubic: Vec<Point> = (0..=m).map(|i| curve.eval(i as f64 / m as f64)).collect();
    let len = seg.arc_length();
    let d: Vec<f64> = crate::lac_fit::nearest_distances(&exact, &on_cubic)
        .into_iter()
        .map(|x| x / len)
        .collect();
    Ok(crate::approx::RationalCubicFit {
        curve,
        f0: 0.5,
        f1: 1.0,
        rms: (d.iter().map(|x| x * x).sum::<f64>() / d.len() as f64).sqrt(),
        max_error: d.iter().copied().fold(0.0, f64::max),
        monotone,
        evaluations: 1,
        // A fixed cubic, not an optimum.
        converged: false,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bezier::PlanarCurve;
    use crate::sketch::pieces::build_piece;
    use crate::sketch::slot::Cut;
    use kurbo::Vec2;

    fn slot(cut_a: Cut, cut_b: Cut) -> Slot {
        Slot {
            ua: 0.0,
            ub: 1.0,
            cut_a,
            cut_b,
            alpha: Some(1.0),
            fitted: true,
            dir_a: None,
            dir_b: None,
        }
    }

    fn only(c: Cubics) -> SketchPiece {
        match c {
            Cubics::Pieces(mut p) if p.len() == 1 => p.remove(0),
            _ => panic!("one piece expected"),
        }
    }

    #[test]
    fn a_piece_fitted_before_comes_back_from_the_memo_unchanged() {
        let s = slot(Cut::End, Cut::End);
        let (pa, pb) = (Point::new(0.0, 0.0), Point::new(10.0, 0.0));
        let (da, db) = (Vec2::from_angle(0.5), Vec2::from_angle(-0.3));
        let built = build_piece(&s, pa, da, pb, db).unwrap();
        let approx = ApproxOptions::default();
        let mut cache = CubicCache::default();
        let first = only(
            cache
                .pieces(std::slice::from_ref(&s), vec![built.clone()], &approx, 64)
                .unwrap(),
        );
        assert_eq!(cache.memo.len(), 1);
        let again = only(cache.pieces(&[s], vec![built], &approx, 64).unwrap());
        assert_eq!(cache.memo.len(), 1);
        assert_eq!(first.rational, again.rational);
        assert_eq!(first.kind, PieceKind::Lac);
        assert!(first.monotone);
        assert!((first.rational.eval(0.0) - pa).hypot() < 1e-12);
        assert!((first.rational.eval(1.0) - pb).hypot() < 1e-12);
    }

    #[test]
    fn an_inflection_at_the_end_is_delivered_in_curve_order() {
        // The segment of [(0,0), (5,0), (7,3)] with its inflection at (0,0), run backwards.
        let s = slot(Cut::Other, Cut::Inflection);
        let (pa, pb) = (Point::new(7.0, 3.0), Point::new(0.0, 0.0));
        let da = -Vec2::new(2.0, 3.0) / Vec2::new(2.0, 3.0).hypot();
        let db = Vec2::new(-1.0, 0.0);
        let built = build_piece(&s, pa, da, pb, db).unwrap();
        let mut cache = CubicCache::default();
        let p = only(
            cache
                .pieces(&[s], vec![built], &ApproxOptions::default(), 64)
                .unwrap(),
        );
        assert_eq!(p.kind, PieceKind::LacInflection);
        assert_eq!(p.control[0], pa);
        assert_eq!(p.control[2], pb);
        assert!((p.rational.eval(0.0) - pa).hypot() < 1e-12);
        let k0 = p.rational.kappa_start().abs();
        assert!(
            p.rational.kappa_end().abs() < 1e-9 * k0,
            "{}",
            p.rational.kappa_end()
        );
    }
}
