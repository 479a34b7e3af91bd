//! The sketch fit's constants, in one place (the α range is the library's:
//! [`crate::lac::ALPHA_RANGE`]).

/// Input whose noise (4σ, [`super::input::noise_level`]) is below this share of its size is
/// precise (sampled from a curve): it gets the tight spline, not the smoothest one.
pub(super) const PRECISE_NOISE: f64 = 1e-6;

/// Input whose residuals over 5 points are below this share of those over 15 is precise
/// too: noise leaves both alike (the ratio is 1 ± 0.3), a sampled curve's own residuals
/// fall as the window's fourth power (to 0.012).
pub(super) const PRECISE_SCALING: f64 = 0.1;

/// The window scaling below which points are a curve's samples for the choice of spline
/// (the tight one): 1,200 coarse and dense samples of log-aesthetic curves measured at most
/// 0.0146 (a polynomial's (5/15)⁴ = 0.012); a regular tremor 0.076, a hand's sparse stroke
/// 0.029.
pub(super) const CURVE_SAMPLES_SCALING: f64 = 0.02;

/// A stroke whose steps at a point are longer than this share of its size (the diagonal
/// of its bounding box: some 50 points or fewer along it) is sparse there: clicked
/// points, or a pen sampled far apart ([`super::contour`]'s corners).
pub const SPARSE_STEP: f64 = 0.02;

/// The tight spline of precise input stays within this share of the size (or 4 times the
/// noise, if more): the joints and tangents the pieces take from it are that accurate.
/// Points close to a circle barely tell the alphas apart (a shallow bump's α = -1.86 fits
/// α = -2's samples within 1.4e-5 of the size): at 1e-5 a joint at a shallow peak sat
/// 1.3e-4 of the size off and its pieces' α 0.15 off; at 1e-6, 0.015.
pub(super) const TIGHT_SHARE: f64 = 1e-6;

/// The default tolerance of precise input: this share of the bounding box's diagonal.
pub(super) const PRECISE_SIZE_SHARE: f64 = 0.005;

/// The default tolerance of noisy input: this many times the estimated noise (σ across the
/// stroke, [`super::estimated_noise`]). A hand's jitter uniform in ±a per coordinate is
/// estimated at 0.61a (stroke at 45°) to 0.74a (along an axis), so this is about 2a,
/// twice its amplitude; for Gaussian noise, its 99.7 % band...
pub(super) const DEFAULT_NOISE_FACTOR: f64 = 3.0;

/// ... and at least this many times the noise's largest deviation ([`EXTREME_CUT`]), so
/// that the fair spline, within [`NEAR_NOISE_SHARE`] of the tolerance, keeps 15 % of room
/// above every point's noise and need not follow it (a tolerance of 1.06 times the largest
/// deviation left a stroke's smoothest spline with 2 false inflections, 0.9 times with 16).
pub(super) const EXTREME_FACTOR: f64 = 1.35;

/// Residuals above this many times σ are not noise (the noise's largest deviation among 10⁶
/// Gaussian points is about 5σ; a hand's jitter stays under 3σ) but a local cubic that
/// misses a sharp bend or a corner.
pub(super) const EXTREME_CUT: f64 = 4.5;

/// The default tolerance is an estimate: where the fit at it fails or is not G2, these
/// multiples of it are tried in turn (a hand's tremor of a 6-point period and 0.7 px,
/// which the noise estimate reads as noise: the fit failed at the default, 0.72, and met
/// 0.9 and 1.0 G2).
pub(super) const DEFAULT_ESCALATION: [f64; 4] = [1.0, 1.25, 1.5, 2.0];

/// The multiples of the default tolerance tried for a stroke too short for a noise estimate
/// (fewer than 15 points), whose default takes it as precise: where that fails, its points
/// carry noise the default does not know of, and the ladder goes on to 8 times it, 4 % of
/// the size (13 points of an arc of radius 12 with noise of σ 0.12 failed at every rung of
/// [`DEFAULT_ESCALATION`] and met 3 times the default; 9 points of arcs with noise of 2 to
/// 3 % of the radius failed up to 4 times and met 6 or 8).
pub(super) const UNKNOWN_NOISE_ESCALATION: [f64; 8] = [1.0, 1.25, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0];

/// Strokes of more points get a larger factor than [`DEFAULT_NOISE_FACTOR`] (their noise's
/// extremes lie further out).
pub(super) const NOISE_FACTOR_POINTS: usize = 1000;

/// ... but never below this share of the bounding box's diagonal (near-precise input: the
/// rounding of coordinates to a grid), which a fair curve of a few pieces meets.
pub(super) const NOISY_SIZE_SHARE: f64 = 0.0002;

/// Share of the tolerance the fair spline of noisy input may use (the smoothest spline
/// within it shapes the pieces); the rest is left to the LAC pieces and their cubics.
pub(super) const FAIR_SHARE: f64 = 0.75;

/// A tolerance below this many times the estimated noise σ is near the noise's extremes
/// (about 2.5σ for a hand's jitter, 3σ for a few hundred Gaussian deviations)...
pub(super) const NEAR_NOISE: f64 = 4.0;

/// ... and its fair spline gets this share: at 3σ the spline 3/4 of it away followed the
/// noise's extremes (a jittery spiral: 15 pieces, 2 false inflections; 8 and none at 85 %).
pub(super) const NEAR_NOISE_SHARE: f64 = 0.85;

/// The fair spline's share where no spline meets [`FAIR_SHARE`]: a tolerance close to the
/// noise's largest deviations (3σ over 200,000 points of uniform jitter left even the
/// least-squares spline 0.78 of the tolerance away), leaving the pieces less room.
pub(super) const FAIR_SHARE_LAST: f64 = 0.95;

/// Share of the tolerance within which two neighbouring pieces merge into one LAC segment.
pub(super) const MERGE_SHARE: f64 = 0.95;

/// A merge may cross a curvature peak of precise input when the merged segment's largest
/// deviation is within this many times the larger of the two pieces' own: the peak is then
/// the spline's (a wave of the tight spline near a free end), not the data's. A true peak
/// (a segment and its mirror image) leaves one segment across it hundreds of times further
/// off than its two halves.
pub(super) const PEAK_MERGE_FACTOR: f64 = 4.0;

/// The least share of a piece's parameter range left on either side of a split at its half
/// turning (a piece with an inflection end that misses the points): over 240 jittery
/// strokes 0.2 gave 8 % fewer pieces, 17 % fewer on their α bound and the same fairness as
/// the unclamped half turning.
pub(super) const MID_TURN_ROOM: f64 = 0.2;

/// Where a piece from a curvature peak to an inflection is split when its turning gathers
/// at the peak: where the curvature has fallen to this share of the peak's. The jittery S
/// drawn in the editor: the piece after its peak fell 3.17 → 0.48 with α -2.11 at the
/// clamped half turning, 3.30 → 0.47 with α -0.93 here; over 240 jittery strokes 7
/// unfair (9 at the half turning), 1647 pieces (1684) and 460 on their α bound (457); the
/// wave of the default-tolerance test 5 curvature extrema (7). A fifth split that wave
/// into 28 pieces (19 here and before).
pub(super) const PEAK_FALL_SPLIT: f64 = 0.25;

/// Splits for missed points made one per round before they are made all at once.
pub(super) const BATCH_AFTER: usize = 4;

/// How far a piece's end curvature may exceed the fair spline's largest curvature over
/// the piece in the fit of its α.
pub(super) const HOOK_FACTOR: f64 = 4.0;

/// Weight of α against the joint tangent angles (radians) in the fairing's minimum-norm
/// step, which minimises Σ Δangle² + Σ Δα²/ALPHA_WEIGHT: with 1, a change of α by 1 costs as
/// much as a turn of 1 rad.
pub(super) const ALPHA_WEIGHT: f64 = 1.0;

/// Rounds that split a piece at the joint the fairing left with a curvature jump, before a
/// result that is not G2 is delivered as it is (and says so).
pub(super) const MAX_JUMP_SPLITS: usize = 4;

/// An inflection of the fair spline closer to a line's end than this share of the curve's
/// turning is noise about the zero curvature there ([`super::SketchOptions::line_ends`]).
pub(super) const LINE_END_SHARE: f64 = 0.2;

/// A stretch whose |κ| stays below this share of the curve's largest is flat: an inflection
/// pair across it (or an inflection and an end) is noise, which the segmentation drops, and
/// a free end in one takes the tangent of its last sign change (`Track::with_flat_ends`).
pub(super) const FLAT_STRETCH_SHARE: f64 = 0.1;

/// The largest ratio of a piece's end curvatures: a control triangle near the edge of its
/// existence region puts one end's curvature towards 0 or ∞, a shape that one rational
/// cubic cannot follow (its piece would be split for want of a monotone cubic). The α fit
/// and the admissible α of a moved triangle stop there (measured: 100 gave the jittery S
/// strokes invented inflections, 1000 none; the pieces of the Prius lines and the exact
/// samples stay far below it).
pub(super) const MAX_CURVATURE_RATIO: f64 = 1000.0;

/// Whether end curvatures `k0`, `k1` are within [`MAX_CURVATURE_RATIO`] of each other.
pub(super) fn tame_curvatures(k0: f64, k1: f64) -> bool {
    k0.abs().max(k1.abs()) <= MAX_CURVATURE_RATIO * k0.abs().min(k1.abs())
}

/// A curvature peak of precise input that the root finder missed (on a knot) counts when
/// its |κ| stands this share above the ends of its interval (or above the maximum found
/// there): a feature of the data, not the tight spline's rounding.
pub(super) const PEAK_PROMINENCE: f64 = 0.02;

/// A tolerance typed inside the noise (`inside_noise`): the fit also tries these multiples
/// of the default tolerance, loosest first; a fair curve fitted there may still stay within
/// the typed tolerance...
pub(super) const NOISE_RUNGS_ABOVE: [f64; 2] = [1.5, 1.25];

/// ... then the default, then the default times the powers of this step down to the typed
/// tolerance...
pub(super) const NOISE_RUNG_STEP: f64 = 0.9;

/// ... each allowed twice the pieces of the fit at the default and this many more (a fit
/// that follows the noise splits piece after piece: the cap ends it early).
pub(super) const NOISE_EXTRA_PIECES: usize = 4;

/// A curve through `n` points gets at most `n` plus this many pieces (and never more than
/// its `max_pieces`): a stroke that needs more turns back or wiggles between its points,
/// and the rounds that split it piece by piece only delay the error (a random walk of 13
/// points went from 11 to 41 pieces in 30 rounds, and failed after 12 s over the default
/// tolerance's rungs; sparse smooth strokes need fewer).
pub(super) const PIECES_OVER_POINTS: usize = 4;

/// The default tolerance is at least this many times the hand's slow wobble
/// (`resolution::wobble`): about twice its amplitude.
pub(super) const WOBBLE_FACTOR: f64 = 2.5;
