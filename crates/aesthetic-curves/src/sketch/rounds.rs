//! The rounds of the fit: α per piece, joint tangents, G2 fairing, cubics, deviation; a
//! round that misses the tolerance (or cannot build its pieces) splits a piece and the next
//! round starts, a round that meets it delivers the [`Sketch`].

use super::alpha::{alpha_range, fit_slot_alpha, points_in};
use super::constants::{BATCH_AFTER, MAX_JUMP_SPLITS, PIECES_OVER_POINTS};
use super::cubics::{CubicCache, Cubics};
use super::deviation::{measure, polyline_deviation, Deviation};
use super::fairing::fair;
use super::input::{Context, Noise};
use super::pieces::{settle_inflections, Built};
use super::segment::{
    initial_slots, split_at_mid_turn, split_at_peak, split_s_shapes, split_worst,
};
use super::slot::{triangle, Slot};
use super::types::{
    count_events, FairingReport, PieceKind, PieceShape, Sketch, SketchOptions, SketchPiece,
};
use crate::error::{Error, Result};
use kurbo::{Point, Vec2};
use rayon::prelude::*;

/// The fit at `opts.tolerance` (steps 1-7), the points checked and their noise estimated:
/// the context, the first pieces, then rounds until one delivers.
pub(super) fn fit_at(points: &[Point], opts: &SketchOptions, noise: &Noise) -> Result<Sketch> {
    let budget = opts.max_pieces.min(points.len() + PIECES_OVER_POINTS);
    let capped = SketchOptions {
        max_pieces: budget,
        ..opts.clone()
    };
    let cx = Context::with_noise(points, &capped, noise)?;
    let mut slots = initial_slots(&cx)?;
    let mut rounds = Rounds::default();
    loop {
        crate::deadline::check()?;
        match rounds.run(&cx, &mut slots) {
            Ok(Round::Done(sketch)) => return Ok(*sketch),
            Ok(Round::Again) => {}
            Err(e) if budget < opts.max_pieces && slots.len() >= budget => {
                return Err(Error::Degenerate(format!(
                    "these {} points need more than {budget} pieces as one G2 curve (last: \
                     {e}): the stroke turns back or wiggles between its points; a contour fit \
                     (`sketch.contour`) splits it at its corners, a looser tolerance smooths it",
                    points.len()
                )))
            }
            Err(e) => return Err(e),
        }
    }
}

/// How a round ended.
pub(super) enum Round {
    /// The pieces changed (a split): run another round.
    Again,
    /// The result.
    Done(Box<Sketch>),
}

/// What the rounds carry from one to the next.
#[derive(Default)]
pub(super) struct Rounds {
    /// Rounds that split pieces at a curvature peak because their inflection pieces could
    /// not be built.
    peak_splits: usize,
    /// Splits made because the curve missed the points.
    miss_splits: usize,
    /// Splits made because the fairing left a curvature jump.
    jump_splits: usize,
    /// The cubics fitted so far.
    cubics: CubicCache,
}

impl Rounds {
    /// One round on `slots`.
    pub(super) fn run(&mut self, cx: &Context, slots: &mut Vec<Slot>) -> Result<Round> {
        let opts = cx.opts;
        fit_alphas(cx, slots);
        let (mut pts, mut dirs) = joints(cx, slots);
        if self.split_unsettled(cx, slots, &pts, &mut dirs)? {
            return Ok(Round::Again);
        }
        keep_end_triangles(cx, slots, &mut pts, &mut dirs);
        let (built, fairing) = fair(slots, &pts, &mut dirs, opts)?;
        // A round whose fairing failed and whose LAC pieces miss a point by more than twice
        // the tolerance splits where they miss most, without fitting rational cubics to
        // pieces that will not be kept (those fits cost most of such a round).
        if !fairing.converged && slots.len() < opts.max_pieces {
            if let Some((worst, piece, u)) = lac_deviation(cx, &built) {
                if worst > 2.0 * opts.tolerance {
                    split_worst(&cx.track, slots, piece, u)?;
                    return Ok(Round::Again);
                }
            }
        }
        let pieces = match self
            .cubics
            .pieces(slots, built, &opts.approx, opts.max_pieces)?
        {
            Cubics::Pieces(p) => p,
            Cubics::Split(i) => {
                split_at_mid_turn(&cx.track, slots, i)?;
                return Ok(Round::Again);
            }
        };
        let dev = measure(&pieces, &cx.fit);
        if dev.worst > opts.tolerance && slots.len() < opts.max_pieces {
            self.split_misses(cx, slots, &dev)?;
            return Ok(Round::Again);
        }
        if !fairing.converged
            && dev.worst <= opts.tolerance
            && slots.len() < opts.max_pieces
            && self.jump_splits < MAX_JUMP_SPLITS
        {
            self.jump_splits += 1;
            let i = worst_jump_piece(&cx.track, slots, &pieces);
            split_at_mid_turn(&cx.track, slots, i)?;
            return Ok(Round::Again);
        }
        if dev.worst > opts.tolerance {
            return Err(Error::NoConvergence(format!(
                "{} pieces leave a deviation of {:.3e} above the tolerance {:.3e}",
                slots.len(),
                dev.worst,
                opts.tolerance
            )));
        }
        Ok(Round::Done(Box::new(deliver(cx, pieces, &dev, fairing))))
    }

    /// Inflection joints whose two pieces cannot both be inflection-end pieces at any
    /// nearby tangent: the pieces that cannot are split at their curvature peak (a maximum
    /// the segmentation dropped), at most twice `max_pieces` rounds. Returns whether any
    /// piece was split.
    fn split_unsettled(
        &mut self,
        cx: &Context,
        slots: &mut Vec<Slot>,
        pts: &[Point],
        dirs: &mut [Vec2],
    ) -> Result<bool> {
        let failed = settle_inflections(slots, pts, dirs);
        let max = cx.opts.max_pieces;
        if failed.is_empty() || self.peak_splits >= 2 * max || slots.len() >= max {
            return Ok(false);
        }
        // Later indices first, so earlier ones stay valid.
        let mut any = false;
        for &i in failed.iter().rev() {
            let at_line = slots[i].at_line();
            if split_at_peak(&cx.track, slots, i) {
                any = true;
            } else if at_line {
                // No peak to cut at: at half its turning, so the piece at the line turns
                // half as much.
                split_at_mid_turn(&cx.track, slots, i)?;
                any = true;
            }
        }
        if any {
            self.peak_splits += 1;
            split_s_shapes(&cx.track, slots)?;
        }
        Ok(any)
    }

    /// Split the piece that misses a point most, where it misses most (kept off the piece's
    /// ends); a piece with an inflection end at its mid-turn, so the inflection piece left
    /// keeps a proper triangle. A line that has needed [`BATCH_AFTER`] such splits needs
    /// many pieces: from then on every piece that misses a point is split in the same round
    /// (the rounds, not the pieces, cost the time). The worst pieces first within the piece
    /// budget, split from the last so the earlier indices stay valid.
    fn split_misses(&mut self, cx: &Context, slots: &mut Vec<Slot>, dev: &Deviation) -> Result<()> {
        let tol = cx.opts.tolerance;
        let pw = &dev.piece_worst;
        let mut over: Vec<usize> = (0..pw.len())
            .filter(|&i| pw[i].0 == dev.worst || (self.miss_splits >= BATCH_AFTER && pw[i].0 > tol))
            .collect();
        over.sort_by(|&a, &b| pw[b].0.total_cmp(&pw[a].0));
        over.truncate(cx.opts.max_pieces - slots.len());
        over.sort_unstable_by(|a, b| b.cmp(a));
        for i in over {
            split_worst(&cx.track, slots, i, pw[i].1)?;
            self.miss_splits += 1;
        }
        Ok(())
    }
}

/// Of the two pieces at the joint with the largest curvature jump, the one that turns
/// more: splitting it gives the fairing a tangent and a curvature of its own there.
fn worst_jump_piece(track: &super::track::Track, slots: &[Slot], pieces: &[SketchPiece]) -> usize {
    let jump = |j: usize| (pieces[j - 1].end_curvatures.1 - pieces[j].end_curvatures.0).abs();
    let Some(j) = (1..pieces.len()).max_by(|&a, &b| jump(a).total_cmp(&jump(b))) else {
        return 0;
    };
    let turn = |i: usize| track.angle_between(slots[i].ua, slots[i].ub).abs();
    if turn(j - 1) >= turn(j) {
        j - 1
    } else {
        j
    }
}

/// Stage 4 for the slots not fitted yet: each one's α on its own, in parallel (the same
/// results in any order). An open curve's end pieces fit their outer tangent with α.
fn fit_alphas(cx: &Context, slots: &mut [Slot]) {
    let last = slots.len() - 1;
    let closed = cx.opts.closed;
    slots
        .par_iter_mut()
        .enumerate()
        .filter(|(_, s)| !s.fitted)
        .for_each(|(i, s)| {
            let end = !closed && (i == 0 || i == last);
            fit_slot_alpha(&cx.track, &cx.fit, s, cx.ends, end);
        });
}

/// The joints' points and unit tangents (ends included): the fair spline's, the curve's
/// ends the input's, the end tangents fitted with the end pieces' α where they were; a
/// closed curve's two ends one point with one tangent (the two spline tangents averaged).
fn joints(cx: &Context, slots: &[Slot]) -> (Vec<Point>, Vec<Vec2>) {
    let track = &cx.track;
    let last = slots.last().unwrap();
    let mut pts: Vec<Point> = slots.iter().map(|s| track.point(s.ua)).collect();
    pts.push(track.point(last.ub));
    pts[0] = cx.ends.0;
    *pts.last_mut().unwrap() = cx.ends.1;
    let mut dirs: Vec<Vec2> = slots.iter().map(|s| track.direction(s.ua)).collect();
    dirs.push(track.direction(last.ub));
    if let Some(d) = slots[0].dir_a {
        dirs[0] = d;
    }
    if let Some(d) = last.dir_b {
        *dirs.last_mut().unwrap() = d;
    }
    // An end that joins a line leaves it along it.
    if let Some(d) = cx.line_ends[0] {
        dirs[0] = d;
    }
    if let Some(d) = cx.line_ends[1] {
        *dirs.last_mut().unwrap() = d;
    }
    if cx.opts.closed {
        let m = dirs.len() - 1;
        let both = dirs[0] + dirs[m];
        let l = both.hypot();
        if l > 0.0 {
            dirs[0] = both / l;
            dirs[m] = dirs[0];
        }
    }
    (pts, dirs)
}

/// An end piece whose end tangents form no triangle (the input's end point and a fitted
/// tangent can tip a shallow piece over) gets the fair spline's tangent there, then its end
/// point too.
fn keep_end_triangles(cx: &Context, slots: &[Slot], pts: &mut [Point], dirs: &mut [Vec2]) {
    let m = slots.len();
    let has = |pts: &[Point], dirs: &[Vec2], i: usize| {
        triangle(pts[i], dirs[i], pts[i + 1], dirs[i + 1]).is_some()
    };
    // An end that joins a line keeps its point and tangent.
    let [at_line_a, at_line_b] = cx.opts.line_ends.map(|d| d.is_some());
    if !at_line_a && !has(pts, dirs, 0) {
        dirs[0] = cx.track.direction(slots[0].ua);
        if !has(pts, dirs, 0) {
            pts[0] = cx.track.point(slots[0].ua);
        }
    }
    if !at_line_b && !has(pts, dirs, m - 1) {
        dirs[m] = cx.track.direction(slots[m - 1].ub);
        if !has(pts, dirs, m - 1) {
            pts[m] = cx.track.point(slots[m - 1].ub);
        }
    }
}

/// The input's largest distance to the LAC pieces' polylines (129 samples each), with its
/// piece and spline parameter; `None` where a piece cannot be sampled.
fn lac_deviation(cx: &Context, built: &[Built]) -> Option<(f64, usize, f64)> {
    let polys: Option<Vec<Vec<Point>>> = built.iter().map(|b| b.curve.polyline(129).ok()).collect();
    Some(polyline_deviation(&cx.fit.points, &cx.fit.params, &polys?))
}

/// The result of a round that met the tolerance: its joints' largest relative curvature
/// jump (a closed curve's seam included) and its inflections and curvature extrema.
fn deliver(
    cx: &Context,
    mut pieces: Vec<SketchPiece>,
    dev: &Deviation,
    fairing: FairingReport,
) -> Sketch {
    pieces.par_iter_mut().for_each(|p| {
        if p.kind == PieceKind::Lac {
            let pts = points_in(&cx.fit, p.u_range.0, p.u_range.1);
            p.alpha_range = Some(alpha_range(
                p.control,
                &pts,
                p.alpha,
                cx.noise,
                cx.opts.tolerance,
            ));
        }
    });
    let kmax = pieces
        .iter()
        .map(|p| {
            p.rational
                .kappa_start()
                .abs()
                .max(p.rational.kappa_end().abs())
        })
        .fold(0.0, f64::max);
    let seam = cx.opts.closed.then(|| {
        (pieces[pieces.len() - 1].rational.kappa_end() - pieces[0].rational.kappa_start()).abs()
    });
    let jump = pieces
        .windows(2)
        .map(|w| (w[0].rational.kappa_end() - w[1].rational.kappa_start()).abs())
        .chain(seam)
        .fold(0.0, f64::max)
        / kmax.max(f64::MIN_POSITIVE);
    let ends: Vec<(f64, f64)> = pieces
        .iter()
        .map(|p| (p.rational.kappa_start(), p.rational.kappa_end()))
        .collect();
    let (inflections, curvature_extrema) = count_events(&ends);
    Sketch {
        inflections,
        curvature_extrema,
        bspline: cx.fit.spline.clone(),
        bspline_deviation: cx.fit.max_deviation,
        all_monotone: pieces.iter().all(|p| p.monotone),
        pieces,
        max_deviation: dev.worst,
        rms_deviation: dev.rms,
        max_curvature_jump: jump,
        g2: jump < 1e-6,
        fairing,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sketch::segment::initial_slots;
    use crate::sketch::types::SketchOptions;

    #[test]
    fn a_closed_curve_has_one_point_and_one_tangent_at_its_seam() {
        let n = 120;
        let pts: Vec<Point> = (0..=n)
            .map(|i| {
                let a = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
                Point::new(100.0 * a.cos(), 60.0 * a.sin())
            })
            .collect();
        let opts = SketchOptions {
            closed: true,
            ..SketchOptions::with_tolerance(0.2)
        };
        let cx = Context::new(&pts, &opts).unwrap();
        let slots = initial_slots(&cx).unwrap();
        let (p, d) = joints(&cx, &slots);
        assert_eq!(p.len(), slots.len() + 1);
        assert_eq!(p[0], pts[0]);
        assert_eq!(*p.last().unwrap(), pts[n]);
        assert_eq!(d[0], *d.last().unwrap());
        assert!((d[0].hypot() - 1.0).abs() < 1e-12);
        // The seam's tangent is the ellipse's there (vertical), to the spline's accuracy.
        assert!(d[0].x.abs() < 1e-3, "{:?}", d[0]);
    }
}
