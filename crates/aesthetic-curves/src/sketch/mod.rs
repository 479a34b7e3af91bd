//! Pen input to a G2 aesthetic curve (docs/math.md §6; S4 §3): fair first, then segment.
//!
//! The pipeline of [`fit_sketch`]:
//! 1. a fair spline: for noisy input (measured lines, pen strokes) the smoothest cubic
//!    B-spline within 3/4 of the tolerance (85 % for a tolerance within 4σ of the noise;
//!    [`crate::bspline::smoothing_fit`]), so the pieces inherit no noise and no end hook;
//!    for precise input the tight least-squares B-spline ([`crate::bspline::fit`]), whose
//!    tangents and curvature are accurate;
//! 2. its inflections (sign changes of `g = x'y'' - y'x''`) and curvature extrema (of
//!    `h = 2 g' f - 3 g f'`, `f = |x'|²`), isolated exactly on each Bézier span's Bernstein
//!    form; simplified as in S4 (one curvature maximum between two inflections, pieces
//!    turning more than [`SketchOptions::max_turn`] split) and without inflection pairs
//!    across a flat stretch (noise; a free end of such a stretch takes the tangent of its
//!    last sign change, `Track::with_flat_ends`). For precise input a peak that sits on a
//!    knot (dκ/ds changes sign from one span to the next without a root, as on symmetric
//!    data) is found by sampling and cut as a peak that no merge crosses;
//! 3. neighbouring pieces merge while one LAC segment still fits their input points;
//! 4. per piece, α by least squares against its input points (point-to-curve distances) in
//!    the triangle of its end points and tangents, up to the edge of the segment's
//!    existence, the tangent at the curve's ends fitted with it; a piece with an inflection at one end becomes an inflection-end segment
//!    (docs/math.md §3.2, α from its triangle). α outside the triangle's existence region
//!    moves to the nearest admissible value; α on its bound ([`crate::lac::ALPHA_RANGE`]) is reported;
//!    α keeps the segment's end curvatures within `HOOK_FACTOR` times the fair spline's
//!    largest over the piece (no hooks from triangles at the edge of their existence region)
//!    and within `MAX_CURVATURE_RATIO` of each other (no end flattened to zero curvature);
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
//!    steps 4-7 repeat; while the fairing leaves a curvature jump (at most
//!    `MAX_JUMP_SPLITS` times), the piece that turns more at the largest jump is split.
//!
//! The result reports its inflections and curvature extrema ([`count_events`]).
//!
//! A tolerance typed inside the noise of noisy input (below 0.9 times
//! [`default_tolerance`]) would make the fair spline of step 1 follow the noise's extremes:
//! `inside_noise` then runs steps 1-7 at a ladder of tolerances and delivers the first fair
//! curve (G2, no event the fit at the default lacks) within the typed tolerance, or a typed
//! error naming the closest one found.
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
//! - `rounds`: steps 4-7 as one round, repeated by [`fit_sketch`] until the tolerance is met;
//! - `inside_noise`: a tolerance typed inside the noise, a ladder of whole fits.

mod alpha;
mod constants;
pub mod contour;
mod cubics;
mod deviation;
mod fairing;
mod input;
mod inside_noise;
mod pieces;
mod resolution;
mod rounds;
mod segment;
mod slot;
mod straight;
mod thinning;
mod track;
mod types;

pub use types::{
    count_events, FairingReport, PieceCurve, PieceKind, PieceShape, Sketch, SketchOptions,
    SketchPiece, ALPHA_DETERMINED_WIDTH,
};

use constants::{
    DEFAULT_ESCALATION, DEFAULT_NOISE_FACTOR, EXTREME_FACTOR, NOISE_FACTOR_POINTS, NOISE_RUNG_STEP,
    NOISY_SIZE_SHARE, PRECISE_SIZE_SHARE, UNKNOWN_NOISE_ESCALATION, WOBBLE_FACTOR,
};
use input::{bbox_diagonal, check_points, noise_level, Noise};
use rounds::fit_at;

use crate::error::{Error, Result};
use kurbo::Point;

/// The default tolerance of a sketch (the protocol's `sketch.fit` default). For noisy
/// input (a pen's stroke, a measured line) 3 times the noise estimated from the points
/// ([`estimated_noise`]): about twice a hand's jitter (±1.5 px gives about 3 px), so the
/// curve stays on the drawn shape and a fair curve still meets it; more beyond 1,000
/// points (`noise_factor`); at least 1.35 times the noise's largest deviation, so that the
/// fair spline need not follow noise without a bound (Gaussian-like: a few of a few hundred
/// points lie 3σ off); never below 0.02 % of the diagonal of the points' bounding box. For points sampled from a curve (noise below 1e-6 of that diagonal at the finer of
/// two scales, or residuals that shrink with the window as a curve's own do) 0.5 % of the
/// diagonal.
pub fn default_tolerance(points: &[Point]) -> f64 {
    default_tolerance_of(points, &Noise::of(points))
}

/// [`default_tolerance`] with the points' noise already estimated.
fn default_tolerance_of(points: &[Point], noise: &Noise) -> f64 {
    let size = bbox_diagonal(points);
    if noise.sampled(size) {
        PRECISE_SIZE_SHARE * size
    } else {
        (noise_factor(points.len()) * noise.sigma)
            .max(EXTREME_FACTOR * noise.extreme)
            .max(NOISY_SIZE_SHARE * size)
            .max(WOBBLE_FACTOR * noise.wobble)
            .max(resolution::QUANTUM_TOLERANCE * noise.quantum)
    }
}

/// [`fit_sketch`] with default options within `tolerance`, or, for `None`, at the points'
/// [`default_tolerance`]: an estimate, which a stroke can defeat (a hand's tremor, regular
/// enough to read as noise, with a fair curve only a little further out: the fit there
/// fails or is not G2); then at 1.25, 1.5 and 2 times it, the first G2 result, or a looser
/// one with fewer inflections and curvature extrema (`at_default`). Returns the sketch and
/// the tolerance it was fitted to (its `max_deviation` is within it). The protocol's
/// `sketch.fit`, the CLI and Python.
pub fn fit_sketch_within(points: &[Point], tolerance: Option<f64>) -> Result<(Sketch, f64)> {
    if let Some(t) = tolerance {
        return Ok((fit_sketch(points, &SketchOptions::with_tolerance(t))?, t));
    }
    check_points(points)?;
    let noise = Noise::of(points);
    // Every rung is at least the default: no ladder inside the noise, the rounds directly.
    at_default(
        default_tolerance_of(points, &noise),
        escalation(&noise),
        |t| fit_at(points, &SketchOptions::with_tolerance(t), &noise),
        |s| s.g2.then_some(s.inflections + s.curvature_extrema),
    )
}

/// The multiples of the default tolerance [`at_default`] tries for a stroke of this noise.
fn escalation(noise: &Noise) -> &'static [f64] {
    if noise.known {
        &DEFAULT_ESCALATION
    } else {
        &UNKNOWN_NOISE_ESCALATION
    }
}

/// `fit` at `default`, then at the `ladder`'s multiples of it where it fails or its result
/// is not fair (`events` is `None`: not G2). Once a looser tolerance was needed, the next
/// ones are tried while they are fair with fewer events (inflections and curvature
/// extrema): events that a slightly looser fit does not have follow the noise. Rungs
/// beyond [`DEFAULT_ESCALATION`]'s are tried only while nothing was fair and the last rung
/// did not fail as degenerate (a stroke that turns back, which fails the same way at most
/// tolerances: each failed rung of a 12-point scribble costs seconds). None fair: the
/// first result (which says what it is), else the first error.
fn at_default<T>(
    default: f64,
    ladder: &[f64],
    fit: impl Fn(f64) -> Result<T>,
    events: impl Fn(&T) -> Option<usize>,
) -> Result<(T, f64)> {
    let mut first: Option<Result<(T, f64)>> = None;
    let mut best: Option<(T, f64, usize)> = None;
    let mut turned_back = false;
    for (k, &factor) in ladder.iter().enumerate() {
        if k >= DEFAULT_ESCALATION.len() && (best.is_some() || turned_back) {
            break;
        }
        let tolerance = factor * default;
        let got = fit(tolerance);
        turned_back = matches!(got, Err(Error::Degenerate(_)));
        let fair = got.as_ref().ok().and_then(&events);
        match (got, fair, &best) {
            (Ok(s), Some(_), None) if k == 0 => return Ok((s, tolerance)),
            (Ok(s), Some(n), None) => best = Some((s, tolerance, n)),
            (Ok(s), Some(n), Some((_, _, m))) if n < *m => best = Some((s, tolerance, n)),
            (_, _, Some(_)) => break,
            (Ok(s), None, None) if !matches!(first, Some(Ok(_))) => {
                first = Some(Ok((s, tolerance)))
            }
            (Err(e), _, None) if first.is_none() => first = Some(Err(e)),
            _ => {}
        }
    }
    match best {
        Some((s, tolerance, _)) => Ok((s, tolerance)),
        None => first.expect("the ladder is not empty"),
    }
}

/// [`DEFAULT_NOISE_FACTOR`] for up to [`NOISE_FACTOR_POINTS`] points; beyond, growing as
/// the expected largest of `n` Gaussian deviations does (as `√(2 ln n)`): the more points,
/// the further the noise's extremes, which the curve must still meet (200,000 points get
/// 4σ).
fn noise_factor(n: usize) -> f64 {
    let grow = (n as f64).ln() / (NOISE_FACTOR_POINTS as f64).ln();
    DEFAULT_NOISE_FACTOR * grow.max(1.0).sqrt()
}

/// The noise of a stroke as estimated from its points: the standard deviation across the
/// stroke of the residuals of local least-squares cubics over 15 neighbours (robust: the
/// root mean square of the smallest 90 %), corrected for each fit's own share. 0 for fewer
/// than 15 points.
pub fn estimated_noise(points: &[Point]) -> f64 {
    noise_level(points)
}

/// Fit a G2 curve of LAC pieces (as rational cubics) to an ordered point sequence (see the
/// module documentation).
///
/// Errors: [`crate::Error::InvalidInput`] for fewer than 4 distinct points, non-finite values or a
/// bad tolerance; [`crate::Error::Degenerate`] for points on a straight line (no LAC turns) or
/// tangents that do not form triangles; [`crate::Error::NoConvergence`] when `max_pieces` are not
/// enough for the tolerance.
pub fn fit_sketch(points: &[Point], opts: &SketchOptions) -> Result<Sketch> {
    // The points first: a tolerance derived from unusable points is not the cause.
    let size = check_points(points)?;
    Error::check_positive("tolerance", opts.tolerance)?;
    let noise = Noise::of(points);
    let default = default_tolerance_of(points, &noise);
    if noise.sampled(size) || opts.tolerance >= NOISE_RUNG_STEP * default {
        fit_at(points, opts, &noise)
    } else {
        inside_noise::fit(points, opts, &noise, default)
    }
}
