//! Pen input to a G2 aesthetic curve (docs/math.md §6; S4 §3): fair first, then segment.
//!
//! The pipeline of [`fit_sketch`]:
//! 1. a fair spline: for noisy input (measured lines, pen strokes) the smoothest cubic
//!    B-spline within 3/4 of the tolerance ([`crate::bspline::smoothing_fit`]), so the
//!    pieces inherit no noise and no end hook; for precise input the tight least-squares
//!    B-spline ([`crate::bspline::fit`]), whose tangents and curvature are accurate;
//! 2. its inflections (sign changes of `g = x'y'' - y'x''`) and curvature extrema (of
//!    `h = 2 g' f - 3 g f'`, `f = |x'|²`), isolated exactly on each Bézier span's Bernstein
//!    form; simplified as in S4 (one curvature maximum between two inflections, pieces
//!    turning more than [`SketchOptions::max_turn`] split) and without inflection pairs
//!    across a flat stretch (noise). Known limit: a maximum that sits on a knot (dκ/ds
//!    changes sign from one span to the next, as on symmetric data) is not found, so such
//!    a peak is not cut (issue 35; counting them changed the noisy Prius lines' pieces);
//! 3. neighbouring pieces merge while one LAC segment still fits their input points;
//! 4. per piece, α by least squares against its input points (point-to-curve distances) in
//!    the triangle of its end points and tangents, the tangent at the curve's ends fitted
//!    with it; a piece with an inflection at one end becomes an inflection-end segment
//!    (docs/math.md §3.2, α from its triangle). α outside the triangle's existence region
//!    moves to the nearest admissible value; α on its bound ([`crate::lac::ALPHA_RANGE`]) is reported;
//!    α keeps the segment's end curvatures within `HOOK_FACTOR` times the fair spline's
//!    largest over the piece (no hooks from triangles at the edge of their existence region);
//! 5. **G2 fairing**: the tangent directions at the joints are the unknowns, the curvature
//!    mismatches at the joints the equations; Newton's method with a finite-difference
//!    Jacobian (tridiagonal: a joint's tangent moves its two pieces) and a backtracking line
//!    search (its merit over the first build's largest curvature, held fixed), until the
//!    largest jump is below [`SketchOptions::g2_tolerance`] of the largest curvature; if the
//!    tangents alone cannot get there, the α of the LAC pieces next to the joints that still
//!    jump join the unknowns (minimum-norm steps). Joints where both sides are inflection
//!    ends have zero curvature on both sides by construction and keep their tangent;
//! 6. each piece becomes one rational cubic ([`crate::approx`]): G2 to its LAC at both ends,
//!    so G2 at every joint, with curvature monotonicity proven by the exact test;
//! 7. the input points' true nearest-point distance to the delivered cubics is measured;
//!    while it exceeds the tolerance, the piece holding the worst point is split there and
//!    steps 4-7 repeat.
//!
//! The result reports its inflections and curvature extrema ([`count_events`]).
//!
//! ## The stages, one file each
//!
//! - `types`: the public options, pieces and result; `constants`: the fit's constants;
//! - `input`: step 1, the `Context` built once (the input checked, the noise, the fair
//!   spline and its `track`, the shape track, the ends);
//! - `track`: the spline as Bézier spans (points, tangents, events, turning);
//! - `slot`: a piece's place on the spline and its control triangle;
//! - `segment`: steps 2-3 (cuts, S shapes, merging) and the splits of later rounds;
//! - `alpha`: step 4, α of a piece by least squares; `pieces`: the LAC or inflection-end
//!   segment of a piece for given joint tangents;
//! - `fairing`: step 5; `cubics`: step 6, with its memo and warm starts; `deviation`: step 7;
//! - `rounds`: steps 4-7 as one round, repeated by [`fit_sketch`] until the tolerance is met.

mod alpha;
mod constants;
pub mod contour;
mod cubics;
mod deviation;
mod fairing;
mod input;
mod pieces;
mod rounds;
mod segment;
mod slot;
mod track;
mod types;

pub use types::{
    count_events, FairingReport, PieceCurve, PieceKind, Sketch, SketchOptions, SketchPiece,
};

use constants::{DEFAULT_NOISE_FACTOR, DEFAULT_SIZE_SHARE};
use input::{bbox_diagonal, noise_level, Context};
use rounds::{Round, Rounds};
use segment::initial_slots;

use crate::error::Result;
use kurbo::Point;

/// The default tolerance of a sketch (the protocol's `sketch.fit` default): 0.5 % of the
/// diagonal of the points' bounding box, but never below 6 times the noise estimated from
/// the points themselves (per coordinate, from local cubic fits), so that a fair curve can
/// meet it: a hand's jitter of a few pixels is not a shape to follow.
pub fn default_tolerance(points: &[Point]) -> f64 {
    (DEFAULT_SIZE_SHARE * bbox_diagonal(points)).max(DEFAULT_NOISE_FACTOR * noise_level(points))
}

/// Fit a G2 curve of LAC pieces (as rational cubics) to an ordered point sequence (see the
/// module documentation).
///
/// Errors: [`crate::Error::InvalidInput`] for fewer than 4 distinct points, non-finite values or a
/// bad tolerance; [`crate::Error::Degenerate`] for points on a straight line (no LAC turns) or
/// tangents that do not form triangles; [`crate::Error::NoConvergence`] when `max_pieces` are not
/// enough for the tolerance.
pub fn fit_sketch(points: &[Point], opts: &SketchOptions) -> Result<Sketch> {
    let cx = Context::new(points, opts)?;
    let mut slots = initial_slots(&cx)?;
    let mut rounds = Rounds::default();
    loop {
        crate::deadline::check()?;
        if let Round::Done(sketch) = rounds.run(&cx, &mut slots)? {
            return Ok(*sketch);
        }
    }
}
