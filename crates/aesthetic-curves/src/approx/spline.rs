//! Rational cubic B-splines of G2 pieces for a LAC segment (or one with an inflection end)
//! within a tolerance.

use super::{fit_inflection_cubic, fit_rational_cubic, ApproxOptions, RationalCubicFit};
use crate::bezier::RationalBezier;
use crate::error::{Error, Result};
use crate::lac::{LacInflectionSegment, LacSegment};
use crate::nurbs::Nurbs;
use kurbo::Point;

/// A LAC segment as rational cubic pieces joined with G2 continuity, as one rational
/// B-spline (degree 3, every interior knot of multiplicity 3: the pieces meet with the
/// LAC's point, tangent and curvature, so the spline is G2 although only C0 in its
/// parameter).
#[derive(Clone, Debug)]
pub struct RationalSpline {
    /// The spline: degree 3, knots 0,0,0,0, u1,u1,u1, ..., 1,1,1,1 (interior knots at the
    /// pieces' joints, proportional to arc length), 3 k + 1 control points for k pieces,
    /// each piece's weights scaled to share its first weight with the previous piece's last.
    pub nurbs: Nurbs,
    /// The pieces, in order, each with its own fit report.
    pub pieces: Vec<RationalCubicFit>,
    /// Largest distance to the LAC over all pieces, in input units.
    pub max_error: f64,
}

impl RationalSpline {
    /// The point at knot parameter `u` in [0, 1], by de Boor's algorithm on homogeneous
    /// coordinates (independent of the pieces: a check of the assembled spline).
    pub fn eval(&self, u: f64) -> Point {
        self.nurbs.eval(u)
    }
}

/// The fewest rational cubic pieces (greedy from the start: each piece as long as it can be
/// while its maximum error stays within `tolerance`, input units) approximating `seg`, as
/// one [`RationalSpline`]. Errors: [`Error::NoSegment`] when `max_pieces` are not enough.
pub fn fit_rational_spline(
    seg: &LacSegment,
    tolerance: f64,
    max_pieces: usize,
    opts: &ApproxOptions,
) -> Result<RationalSpline> {
    Error::check_positive("tolerance", tolerance)?;
    if max_pieces == 0 || max_pieces > 1000 {
        return Err(Error::invalid("max_pieces", "must be 1 to 1000"));
    }
    let td = seg.theta_d;
    // A piece [a, b] of turning angle: its fit, when it exists and is within tolerance.
    let try_piece = |a: f64, b: f64| -> Option<RationalCubicFit> {
        let sub = seg.sub_segment(a, b).ok()?;
        let fit = fit_rational_cubic(&sub, opts).ok()?;
        let len = sub.arc_length().ok()?;
        (fit.max_error * len <= tolerance).then_some(fit)
    };
    let mut pieces: Vec<(f64, RationalCubicFit)> = Vec::new();
    let mut a = 0.0;
    while a < td {
        if pieces.len() >= max_pieces {
            return Err(Error::NoSegment(format!(
                "{max_pieces} rational cubic pieces are not enough for tolerance {tolerance:e}"
            )));
        }
        if let Some(f) = try_piece(a, td) {
            pieces.push((td, f));
            break;
        }
        // Longest feasible end by bisection on the turning angle (feasibility shrinks with
        // length), down to 1e-3 of the remaining turn.
        let found = crate::solve::roots::bisect_by(
            |mid| try_piece(a, mid),
            a,
            td,
            |x, y| 0.5 * (x + y),
            |x, y| y - x <= 1e-3 * (td - a),
            64,
        );
        let Some((b, f)) = found.value.map(|f| (found.inside, f)) else {
            return Err(Error::NoSegment(format!(
                "no rational cubic piece from turning angle {a:.6} meets tolerance {tolerance:e}"
            )));
        };
        pieces.push((b, f));
        a = b;
    }
    let mut with_lengths = Vec::with_capacity(pieces.len());
    let mut start = 0.0;
    for (end, fit) in pieces {
        with_lengths.push((fit, seg.sub_segment(start, end)?.arc_length()?));
        start = end;
    }
    assemble(with_lengths)
}

/// G2 rational cubic pieces, each with its arc length (input units), as one
/// [`RationalSpline`]: shared joint points, each piece's weights scaled to meet the previous
/// piece's last weight, interior knots of multiplicity 3 at the arc-length fractions.
fn assemble(pieces: Vec<(RationalCubicFit, f64)>) -> Result<RationalSpline> {
    let total: f64 = pieces.iter().map(|(_, l)| l).sum();
    let mut breaks = vec![0.0];
    let mut acc = 0.0;
    for (_, l) in &pieces[..pieces.len() - 1] {
        acc += l / total;
        breaks.push(acc);
    }
    breaks.push(1.0);
    let curves: Vec<RationalBezier> = pieces.iter().map(|(f, _)| f.curve.clone()).collect();
    let nurbs = Nurbs::from_beziers_at(&curves, &breaks)?;
    let max_error = pieces
        .iter()
        .map(|(f, l)| f.max_error * l)
        .fold(0.0, f64::max);
    Ok(RationalSpline {
        nurbs,
        pieces: pieces.into_iter().map(|(f, _)| f).collect(),
        max_error,
    })
}

/// An inflection-end segment as rational cubic pieces within `tolerance` (input units), as
/// one [`RationalSpline`]: the head [0, τ] next to the inflection is one proven-monotone
/// cubic of [`fit_inflection_cubic`] (zero curvature at the inflection), with τ the largest
/// (to a factor 1.25) that keeps it within the tolerance; the rest, an ordinary LAC segment
/// of the same α ([`LacInflectionSegment::split`]), is [`fit_rational_spline`]. Each joint
/// matches point, tangent and curvature of the segment, so the spline is G2. Errors:
/// [`Error::NoSegment`] when `max_pieces` are not enough or no head cubic meets the
/// tolerance down to τ = 1e-9 θ_d.
pub fn fit_inflection_spline(
    seg: &LacInflectionSegment,
    tolerance: f64,
    max_pieces: usize,
    opts: &ApproxOptions,
) -> Result<RationalSpline> {
    Error::check_positive("tolerance", tolerance)?;
    if !(2..=1000).contains(&max_pieces) {
        return Err(Error::invalid("max_pieces", "must be 2 to 1000"));
    }
    let whole = fit_inflection_cubic(seg, opts)?;
    let len = seg.arc_length();
    if whole.max_error * len <= tolerance {
        return assemble(vec![(whole, len)]);
    }
    // The head's error falls fast with its turning: search τ geometrically.
    let try_head = |tau: f64| -> Option<(LacInflectionSegment, LacSegment, RationalCubicFit)> {
        let (head, tail) = seg.split(tau).ok()?;
        let fit = fit_inflection_cubic(&head, opts).ok()?;
        (fit.max_error * head.arc_length() <= tolerance).then_some((head, tail, fit))
    };
    // The whole turn fails; descend by factors of 8, then bisect in ln τ between the last
    // failure and the first success.
    let mut hi = seg.theta_d;
    let (lo, first) = loop {
        let tau = hi / 8.0;
        if tau < 1e-9 * seg.theta_d {
            return Err(Error::NoSegment(format!(
                "no rational cubic next to the inflection meets tolerance {tolerance:e}"
            )));
        }
        if let Some(f) = try_head(tau) {
            break (tau, f);
        }
        hi = tau;
    };
    let found = crate::solve::roots::bisect_by(
        try_head,
        lo,
        hi,
        |x, y| (x * y).sqrt(),
        |x, y| y / x <= 1.25,
        64,
    );
    let (head, tail, head_fit) = found.value.unwrap_or(first);
    let rest = fit_rational_spline(&tail, tolerance, max_pieces - 1, opts)?;
    // The tail's pieces with their lengths (its knots are arc-length fractions).
    let lt = tail.arc_length()?;
    let mut pieces = vec![(head_fit, head.arc_length())];
    for (i, f) in rest.pieces.into_iter().enumerate() {
        pieces.push((
            f,
            (rest.nurbs.knots[4 + 3 * i] - rest.nurbs.knots[3 + 3 * i]) * lt,
        ));
    }
    assemble(pieces)
}
