//! A tolerance typed inside the stroke's noise: below the default tolerance of noisy input
//! ([`super::default_tolerance`]), where the smoothest spline within the tolerance has to
//! follow the noise's extremes and the fit at that tolerance alone returns dozens of pieces
//! with false inflections, or no curve at all.
//!
//! The fit at the default tolerance is the reference: its inflections and curvature extrema
//! are the stroke's, since the default is the noise's scale. Fits at a ladder of tolerances
//! are tried, the loosest first ([`NOISE_RUNGS_ABOVE`] times the default, the default, then
//! down in steps of [`NOISE_RUNG_STEP`] to the typed tolerance), and the first that is G2, has
//! no event the reference does not have, and stays within the *typed* tolerance of every
//! point is the result: a fair curve fitted at a looser tolerance often stays well inside
//! it (the fit keeps a share for its pieces). Below the default, a rung that is not fair
//! ends the descent (tighter only follows the noise more) and may use at most twice the
//! reference's pieces and [`NOISE_EXTRA_PIECES`] more. None meets it: a typed
//! [`Error::InvalidInput`] naming the noise and the closest a fair curve came.

use super::constants::{NOISE_EXTRA_PIECES, NOISE_RUNGS_ABOVE, NOISE_RUNG_STEP};
use super::input::Noise;
use super::rounds::fit_at;
use super::types::{Sketch, SketchOptions};
use crate::error::{Error, Result};
use kurbo::Point;

/// The fit of `points` at `opts.tolerance`, which lies below `default`, their default
/// tolerance (noisy input only).
pub(super) fn fit(
    points: &[Point],
    opts: &SketchOptions,
    noise: &Noise,
    default: f64,
) -> Result<Sketch> {
    let at = |tolerance: f64, max_pieces: usize| {
        let o = SketchOptions {
            tolerance,
            max_pieces,
            ..opts.clone()
        };
        fit_at(points, &o, noise)
    };
    let typed = opts.tolerance;
    let Ok(reference) = at(default, opts.max_pieces) else {
        // No reference to judge by: the fit at the typed tolerance, as it comes.
        return fit_at(points, opts, noise);
    };
    let fair = |s: &Sketch| {
        s.g2 && s.inflections <= reference.inflections
            && s.curvature_extrema <= reference.curvature_extrema
    };
    let mut closest = reference.max_deviation;
    if reference.max_deviation <= typed {
        return Ok(reference);
    }
    for factor in NOISE_RUNGS_ABOVE {
        if let Ok(s) = at(factor * default, opts.max_pieces) {
            if fair(&s) {
                if s.max_deviation <= typed {
                    return Ok(s);
                }
                closest = closest.min(s.max_deviation);
            }
        }
    }
    let cap = (2 * reference.pieces.len() + NOISE_EXTRA_PIECES).min(opts.max_pieces);
    for tolerance in rungs_below(default, typed) {
        match at(tolerance, cap) {
            Ok(s) if fair(&s) => {
                if s.max_deviation <= typed {
                    return Ok(s);
                }
                closest = closest.min(s.max_deviation);
            }
            _ => break,
        }
    }
    Err(Error::invalid(
        "tolerance",
        format!(
            "{typed:.4} lies inside the stroke's noise (estimated σ {:.4}, its largest \
             deviation {:.4}): a curve that close follows the noise, with inflections or \
             curvature extrema that the default tolerance {default:.4} does not have; the \
             fairest curve found misses a point by {closest:.4}: a tolerance of at least {} \
             gets it",
            noise.sigma,
            noise.extreme,
            round_up(closest)
        ),
    ))
}

/// The tolerances below `default` down to `typed`: `default` times powers of
/// [`NOISE_RUNG_STEP`] above `typed`, then `typed`. The powers do not depend on `typed`, so
/// the closest deviation an error reports is met when typed: the rung that came that close
/// lies above it and is tried again.
fn rungs_below(default: f64, typed: f64) -> impl Iterator<Item = f64> {
    (1..)
        .map(move |k| default * NOISE_RUNG_STEP.powi(k))
        .take_while(move |&t| t > typed)
        .chain(std::iter::once(typed))
}

/// `x > 0` rounded up to 4 significant digits: a tolerance to type that is not below it.
fn round_up(x: f64) -> f64 {
    let scale = 10f64.powi(3 - x.log10().floor() as i32);
    let up = (x * scale).ceil() / scale;
    // The division may round below `x`: one more step then.
    if up < x {
        (x * scale + 1.0).ceil() / scale
    } else {
        up
    }
}
