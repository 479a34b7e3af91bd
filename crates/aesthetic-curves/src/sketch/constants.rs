//! The sketch fit's constants, in one place (the α range is the library's:
//! [`crate::lac::ALPHA_RANGE`]).

/// Input whose noise (4σ, [`super::input::noise_level`]) is below this share of its size is
/// precise (sampled from a curve): it gets the tight spline, not the smoothest one.
pub(super) const PRECISE_NOISE: f64 = 1e-6;

/// The default tolerance's share of the bounding box's diagonal.
pub(super) const DEFAULT_SIZE_SHARE: f64 = 0.005;

/// The default tolerance is never below this many times the estimated noise.
pub(super) const DEFAULT_NOISE_FACTOR: f64 = 6.0;

/// Share of the tolerance the fair spline of noisy input may use (the smoothest spline
/// within it shapes the pieces); the rest is left to the LAC pieces and their cubics.
pub(super) const FAIR_SHARE: f64 = 0.75;

/// Share of the tolerance within which two neighbouring pieces merge into one LAC segment.
pub(super) const MERGE_SHARE: f64 = 0.95;

/// Splits for missed points made one per round before they are made all at once.
pub(super) const BATCH_AFTER: usize = 4;

/// How far a piece's end curvature may exceed the fair spline's largest curvature over
/// the piece in the fit of its α.
pub(super) const HOOK_FACTOR: f64 = 4.0;

/// Weight of α against the joint tangent angles (radians) in the fairing's minimum-norm
/// step, which minimises Σ Δangle² + Σ Δα²/ALPHA_WEIGHT: with 1, a change of α by 1 costs as
/// much as a turn of 1 rad.
pub(super) const ALPHA_WEIGHT: f64 = 1.0;
