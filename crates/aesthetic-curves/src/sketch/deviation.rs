//! Stage 7: how far the input points lie from the delivered curve: the true nearest-point
//! distance to the rational cubics (the fit's measure), and a quick one to the LAC
//! pieces' polylines (to split a hopeless round before its cubics are fitted).

use super::types::SketchPiece;
use crate::bezier::{PlanarCurve, RationalBezier};
use crate::bspline::BSplineFit;
use kurbo::{Point, Rect};
use rayon::prelude::*;

/// The input's distances to the delivered cubics.
pub(super) struct Deviation {
    /// The largest.
    pub(super) worst: f64,
    /// Their root mean square.
    pub(super) rms: f64,
    /// Per piece, the largest distance of a point nearest to it and that point's spline
    /// parameter.
    pub(super) piece_worst: Vec<(f64, f64)>,
}

/// Each input point's distance to the nearest point of the pieces' rational cubics.
/// Each piece's box, grown by its longest sample step, bounds it: a piece whose box lies
/// farther from a point than the nearest distance found so far cannot hold a nearer point,
/// so it is skipped (the distance stays the true nearest one; the piece around the point's
/// parameter is tried first).
pub(super) fn measure(pieces: &[SketchPiece], fit: &BSplineFit) -> Deviation {
    let sampled: Vec<Sampled> = pieces.iter().map(Sampled::new).collect();
    // Each point's nearest distance and piece, in parallel (in order: the sums below are
    // the same in any run).
    let nearest: Vec<(f64, usize)> = fit
        .points
        .par_iter()
        .zip(&fit.params)
        .with_min_len(32)
        .map(|(q, &u)| nearest_piece(pieces, &sampled, *q, u))
        .collect();
    let (mut worst, mut sum) = (0.0f64, 0.0);
    let mut piece_worst = vec![(0.0f64, 0.0f64); pieces.len()];
    for (&(d, i), &u) in nearest.iter().zip(&fit.params) {
        sum += d * d;
        worst = worst.max(d);
        if d > piece_worst[i].0 {
            piece_worst[i] = (d, u);
        }
    }
    Deviation {
        worst,
        rms: (sum / fit.points.len() as f64).sqrt(),
        piece_worst,
    }
}

/// A piece's rational cubic at 65 even parameters, their box and its longest step.
pub(super) struct Sampled {
    pub(super) samples: Vec<(f64, Point)>,
    bounds: (Rect, f64),
}

impl Sampled {
    pub(super) fn new(p: &SketchPiece) -> Sampled {
        let samples: Vec<(f64, Point)> = (0..=64)
            .map(|i| {
                let t = i as f64 / 64.0;
                (t, p.rational.eval(t))
            })
            .collect();
        let bounds = grown_box(&samples);
        Sampled { samples, bounds }
    }

    /// Whether the cubic may hold a point nearer `q` than `best`: its samples' box, grown
    /// by their longest step, lies within `best` of `q`.
    pub(super) fn may_be_nearer(&self, q: Point, best: f64) -> bool {
        let (bx, step) = self.bounds;
        box_distance(&bx, q) <= best + step
    }
}

/// The distance from `q` (spline parameter `u`) to the nearest piece, and that piece: the
/// piece around `u` first, then every piece whose box, grown by its longest sample step,
/// lies nearer than the best distance so far.
fn nearest_piece(pieces: &[SketchPiece], sampled: &[Sampled], q: Point, u: f64) -> (f64, usize) {
    let home = pieces
        .iter()
        .position(|p| u <= p.u_range.1)
        .unwrap_or(pieces.len() - 1);
    let mut best = (
        project(&pieces[home].rational, q, &sampled[home].samples).0,
        home,
    );
    for (i, (p, sm)) in pieces.iter().zip(sampled).enumerate() {
        if i == home || !sm.may_be_nearer(q, best.0) {
            continue;
        }
        let d = project(&p.rational, q, &sm.samples).0;
        if d < best.0 {
            best = (d, i);
        }
    }
    best
}

/// The box of a piece's samples and its longest sample step.
fn grown_box(sm: &[(f64, Point)]) -> (Rect, f64) {
    let r = sm
        .iter()
        .fold(Rect::from_points(sm[0].1, sm[0].1), |r, s| r.union_pt(s.1));
    let step = sm
        .windows(2)
        .map(|w| (w[1].1 - w[0].1).hypot())
        .fold(0.0, f64::max);
    (r, step)
}

/// Distance from `q` to the rectangle `r` (0 inside).
fn box_distance(r: &Rect, q: Point) -> f64 {
    let dx = (r.x0 - q.x).max(q.x - r.x1).max(0.0);
    let dy = (r.y0 - q.y).max(q.y - r.y1).max(0.0);
    dx.hypot(dy)
}

/// The largest distance from `points` (spline parameters `params`) to polylines of the
/// pieces, with its piece and parameter: the nearest point over all pieces (the pieces'
/// polylines joined end to end, every chord a candidate: [`crate::lac_fit`]'s nearest
/// search).
pub(super) fn polyline_deviation(
    points: &[Point],
    params: &[f64],
    polys: &[Vec<Point>],
) -> (f64, usize, f64) {
    let mut joined: Vec<Point> = Vec::new();
    let mut piece_of_chord: Vec<usize> = Vec::new();
    for (i, p) in polys.iter().enumerate() {
        if !joined.is_empty() {
            piece_of_chord.push(i);
        }
        joined.extend_from_slice(p);
        piece_of_chord.extend(std::iter::repeat_n(i, p.len().saturating_sub(1)));
    }
    let near = crate::lac_fit::nearest_chords(&joined, points);
    let (mut worst, mut piece, mut at) = (0.0f64, 0usize, 0.0);
    for ((d, k), &u) in near.into_iter().zip(params) {
        if d > worst {
            (worst, piece, at) = (d, piece_of_chord.get(k).copied().unwrap_or(0), u);
        }
    }
    (worst, piece, at)
}

/// Distance from `q` to a rational cubic and the foot's parameter: the nearest of `n`
/// samples, then safeguarded Newton.
pub(super) fn project(c: &RationalBezier, q: Point, samples: &[(f64, Point)]) -> (f64, f64) {
    let (t0, _) = samples
        .iter()
        .map(|(t, p)| (*t, (*p - q).hypot()))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((0.5, f64::INFINITY));
    // Newton on the squared distance, a step kept only where the distance falls (no
    // halving: from the nearest sample the first step that does not help ends it).
    let step = |t: f64| {
        let d = c.derivs(t);
        let r = c.eval(t) - q;
        let gg = d.d1.hypot2() + r.dot(d.d2);
        (gg > 0.0).then(|| -r.dot(d.d1) / gg)
    };
    let opts = crate::solve::line_search::NewtonMin1d {
        max_iterations: 20,
        max_halvings: 1,
        x_tol: 0.0,
        min_move: 0.0,
        bounds: (0.0, 1.0),
    };
    let m = crate::solve::line_search::newton_min_1d(step, |t| (c.eval(t) - q).hypot(), t0, &opts);
    (m.value, m.x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn projection_onto_a_rational_cubic_finds_the_foot() {
        // A quarter circle of radius 2 as a rational cubic (degree-elevated conic).
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let conic = RationalBezier::new(
            vec![
                Point::new(2.0, 0.0),
                Point::new(2.0, 2.0),
                Point::new(0.0, 2.0),
            ],
            vec![1.0, s, 1.0],
        )
        .unwrap();
        let c = conic.elevate().unwrap();
        let samples: Vec<(f64, Point)> = (0..=8)
            .map(|i| {
                let t = i as f64 / 8.0;
                (t, c.eval(t))
            })
            .collect();
        for angle in [0.2f64, 0.7, 1.3] {
            let q = Point::new(3.0 * angle.cos(), 3.0 * angle.sin());
            let (d, t) = project(&c, q, &samples);
            assert!((d - 1.0).abs() < 1e-12, "{angle}: {d}");
            let foot = c.eval(t);
            assert!((foot.y.atan2(foot.x) - angle).abs() < 1e-9, "{angle}: {t}");
        }
    }
}
