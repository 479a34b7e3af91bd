//! The exact curvature check of outlines people already have (fonts, SVG, DXF): per segment
//! and per join, and the places most worth a look.
//!
//! An outline is contours of polynomial or rational Bézier segments (lines, TrueType
//! quadratics, CFF and SVG cubics, DXF rational splines), each segment starting where the
//! previous one ends. For every segment:
//! - whether its curvature is monotone, by the exact test of [`crate::monotone`], and where
//!   it has curvature extrema (t and point);
//! - its inflections: the sign changes of `det(H, H', H'')` (H = (wx, wy, w), the
//!   homogeneous curve; for a polynomial curve `x'y'' - y'x''`), isolated exactly on its
//!   Bernstein form;
//! - its largest |curvature|, exact: |κ| is largest at an end or at an interior extremum.
//!
//! For every join (between consecutive segments, and last to first on a closed contour): the
//! tangent angle break (0: G1), and at G1 joins (break at most [`OutlineOptions::g1_angle`])
//! the relative curvature jump `|κ₁ - κ₂| / max(|κ₁|, |κ₂|)` (G2 when below
//! [`OutlineOptions::g2_jump`]). A break that is not G1 but under
//! [`OutlineOptions::near_break`] (a few degrees) is almost always unintended: it is
//! flagged.
//!
//! Every verdict, extremum and inflection is exact for the file's f64 coordinates
//! ([`crate::monotone`]). A handle retracted onto its end point is an ordinary segment: the
//! verdict is the exact one on the open segment, and the end's curvature is what it is (a
//! finite limit, 0 on a straight stretch, or unbounded like 1/t, said in the segment's
//! `notes`); a join next to an unbounded end gets no curvature jump. Only a segment that does
//! not move (all control points equal) or whose tangent vanishes inside (a cusp) is flagged,
//! never an error or a NaN; findings are placed on the segment, never at (0, 0).

use crate::bezier::{PlanarCurve, RationalBezier};
use crate::monotone::{CurvatureMonotone, EndCurvature, Trend};
use kurbo::{Point, Vec2};

/// Thresholds of the join checks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OutlineOptions {
    /// A join whose tangent directions differ by at most this (radians) counts as G1.
    pub g1_angle: f64,
    /// A G1 join whose relative curvature jump is below this counts as G2.
    pub g2_jump: f64,
    /// Breaks above `g1_angle` and below this (radians) are flagged as probably unintended.
    pub near_break: f64,
    /// The coordinate grid of the file (1 for a font's integer units, 0 for exact
    /// coordinates): a join also counts as G1 when its break is what rounding the handles
    /// to this grid can make, `√2/2 grid (1/|h₁| + 1/|h₂|)` for handle legs h₁, h₂.
    pub grid: f64,
    /// With a tolerance (file units): for every polynomial cubic whose curvature is not
    /// monotone, the handle lengths nearest to its own that make it monotone, moving the curve
    /// by at most this ([`suggest_handles`]).
    pub suggest: Option<f64>,
    /// Non-monotone segments whose curvature bump ([`SegmentCheck::bump`]) is below this
    /// are not findings (a cubic standing for a circular arc varies by a few per cent; a
    /// single smooth extremum is often the design).
    pub min_bump: f64,
    /// An extremum within this fraction of the parameter of an end is a hook at that end.
    pub hook_zone: f64,
}

impl Default for OutlineOptions {
    /// G1 within 0.05°, G2 within 5 %, near-breaks up to 3°, exact coordinates, bumps from
    /// 5 %, hooks within 5 % of an end.
    fn default() -> Self {
        OutlineOptions {
            g1_angle: 0.05f64.to_radians(),
            g2_jump: 0.05,
            near_break: 3f64.to_radians(),
            grid: 0.0,
            suggest: None,
            min_bump: 0.05,
            hook_zone: 0.05,
        }
    }
}

/// The thresholds as a user states them: angles in degrees, the rest as fractions; what
/// `aecurve check --g1-angle ...` and Python's `check_outline` take.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Thresholds {
    /// [`OutlineOptions::g1_angle`], in degrees.
    pub g1_angle_degrees: f64,
    /// [`OutlineOptions::g2_jump`].
    pub g2_jump: f64,
    /// [`OutlineOptions::near_break`], in degrees.
    pub near_break_degrees: f64,
    /// [`OutlineOptions::min_bump`].
    pub min_bump: f64,
}

impl Thresholds {
    /// The check's options with these thresholds on `grid`; an invalid-input error naming
    /// the first one (or the grid) that is not a finite number >= 0.
    pub fn options(&self, grid: f64) -> crate::Result<OutlineOptions> {
        for (name, v) in [
            ("g1_angle", self.g1_angle_degrees),
            ("g2_jump", self.g2_jump),
            ("near_break", self.near_break_degrees),
            ("min_bump", self.min_bump),
            ("grid", grid),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(crate::Error::invalid(name, "must be a number >= 0"));
            }
        }
        Ok(OutlineOptions {
            g1_angle: self.g1_angle_degrees.to_radians(),
            g2_jump: self.g2_jump,
            near_break: self.near_break_degrees.to_radians(),
            grid,
            min_bump: self.min_bump,
            ..OutlineOptions::default()
        })
    }
}

/// What the check found on one segment.
#[derive(Clone, Debug, PartialEq)]
pub struct SegmentCheck {
    /// Polynomial degree (1: a line).
    pub degree: usize,
    /// The segment's first point (where findings without a better place are put).
    pub start: Point,
    /// Whether any weight differs from the others (a truly rational segment).
    pub rational: bool,
    /// The exact verdict: curvature monotone along the segment (None: the segment does not
    /// move, or the test could not run; see `flag`).
    pub monotone: Option<bool>,
    /// Increasing, decreasing or constant, when monotone.
    pub trend: Option<Trend>,
    /// Interior curvature extrema: parameter and point.
    pub extrema: Vec<(f64, Point)>,
    /// Interior inflections: parameter and point.
    pub inflections: Vec<(f64, Point)>,
    /// Signed curvature at the start and at the end, the limit at a retracted handle
    /// (±infinity where it grows without bound: see `ends`); None for a segment that does
    /// not move or could not be checked.
    pub end_curvatures: Option<(f64, f64)>,
    /// What the curvature does at each end (None when the segment could not be checked).
    pub ends: Option<[EndCurvature; 2]>,
    /// Largest |curvature| on the segment, over its ends and its extrema (infinite when an
    /// end's curvature grows without bound).
    pub max_abs_curvature: f64,
    /// How large the curvature's detour is, relative to the segment's largest curvature:
    /// the total variation of the signed curvature over its ends and extrema less what a
    /// monotone curvature between the same end values would vary, halved
    /// (`(Σ|Δκ| - |κ₁ - κ₀|) / (2 max|κ|)`): 0 for a monotone segment, 0.03 for a cubic
    /// circle whose curvature rises 3 % in its middle (0 where an end is unbounded).
    pub bump: f64,
    /// Why the segment could not be checked (a point, a cusp), if so.
    pub flag: Option<String>,
    /// Facts worth knowing that are not defects (retracted handles and what the curvature
    /// does there).
    pub notes: Vec<String>,
    /// The verdict needed exact arithmetic (the floating-point filter could not decide).
    pub exact: bool,
    /// With [`OutlineOptions::suggest`]: monotone handle lengths within the tolerance.
    pub suggestion: Option<HandleSuggestion>,
}

/// New handle lengths for a cubic whose curvature is not monotone: the end points and the
/// tangent directions stay (so G1 joins stay G1), the handles scale by `scale`.
#[derive(Clone, Debug, PartialEq)]
pub struct HandleSuggestion {
    /// The factors of the first and the second handle's length.
    pub scale: (f64, f64),
    /// The suggested cubic (its curvature is monotone: the exact test says so).
    pub curve: crate::Bezier,
    /// How far it moves the curve: `max_t |new(t) - old(t)|` (an upper bound of the distance
    /// between the two curves).
    pub deviation: f64,
}

/// The monotone handle lengths nearest to those of the cubic `c` (degree 3), moving it by at
/// most `tolerance`, if any: a search of the factors (a, b) of the two handle lengths over
/// 0.2 to 5 (log-spaced, 33 × 33), then bisection between the current handles and the best
/// monotone point found towards the boundary of the monotone region, so that the curve
/// moves as little as it must. The change of the curve is
/// `3(1-t)²t (a-1) h₁ + 3(1-t)t² (b-1) h₂`, its largest length bounded from above by
/// [`crate::bezier::outline_move`] (within 10⁻⁴ of the true maximum).
/// None for a curve already monotone, not a cubic, with a zero handle, or with nothing
/// monotone within the tolerance; or with nothing proven monotone before the search's budget
/// for exact arithmetic ran out ([`crate::monotone::with_exact_budget`]; only where the
/// coordinates span hundreds of orders of magnitude).
pub fn suggest_handles(c: &crate::Bezier, tolerance: f64) -> Option<HandleSuggestion> {
    let p = c.points();
    if p.len() != 4 || tolerance.is_nan() || tolerance <= 0.0 {
        return None;
    }
    let (h1, h2) = (p[1] - p[0], p[2] - p[3]);
    if h1.hypot() == 0.0 || h2.hypot() == 0.0 {
        return None;
    }
    let scaled = Scaled { p, h1, h2 };
    if scaled.monotone(1.0, 1.0) {
        return None;
    }
    // The search's verdicts under one budget for exact work (a caller's, if smaller).
    crate::monotone::with_exact_budget(crate::monotone::SEARCH_EXACT_BUDGET, || {
        search_handles(&scaled, tolerance)
    })
    .0
}

/// A cubic `p` with its handles `h1`, `h2` scaled by factors (a, b), its ends and tangent
/// directions kept.
struct Scaled<'a> {
    p: &'a [Point],
    h1: Vec2,
    h2: Vec2,
}

impl Scaled<'_> {
    fn points(&self, a: f64, b: f64) -> [Point; 4] {
        let p = self.p;
        [p[0], p[0] + self.h1 * a, p[3] + self.h2 * b, p[3]]
    }
    fn curve(&self, a: f64, b: f64) -> Option<crate::Bezier> {
        crate::Bezier::new(self.points(a, b).to_vec()).ok()
    }
    /// Proven monotone by the exact test (false where it gives no verdict).
    fn monotone(&self, a: f64, b: f64) -> bool {
        self.curve(a, b)
            .is_some_and(|c| c.is_curvature_monotone().unwrap_or(false))
    }
    /// The sound bound of the move (convex hull, split until tight), not samples of it.
    fn deviation(&self, a: f64, b: f64) -> f64 {
        crate::bezier::outline_move(self.p, &self.points(a, b))
    }
}

/// [`suggest_handles`]' search, for a cubic that is not monotone.
fn search_handles(s: &Scaled, tolerance: f64) -> Option<HandleSuggestion> {
    let n = 33;
    let (lo, hi) = (0.2f64.ln(), 5f64.ln());
    let at = |i: usize| (lo + (hi - lo) * i as f64 / (n - 1) as f64).exp();
    // The candidates within the tolerance by their move, smallest first (ties in grid
    // order): the first monotone one is the best, and no larger move is proven.
    let mut candidates: Vec<(f64, f64, f64)> = (0..n * n)
        .map(|k| (at(k / n), at(k % n)))
        .map(|(a, b)| (a, b, s.deviation(a, b)))
        .filter(|c| c.2 <= tolerance)
        .collect();
    candidates.sort_by(|x, y| x.2.total_cmp(&y.2));
    let best = candidates.into_iter().find(|c| s.monotone(c.0, c.1));
    let (a, b, _) = best?;
    // Towards the current handles in (ln a, ln b) while it stays monotone.
    // (`inside`: the fraction of the way from (1, 1).)
    let inside = crate::solve::roots::bisect_by(
        |m| s.monotone(a.powf(m), b.powf(m)).then_some(()),
        1.0,
        0.0,
        |x, y| 0.5 * (x + y),
        |_, _| false,
        30,
    )
    .inside;
    let (a, b) = (a.powf(inside), b.powf(inside));
    let curve = s.curve(a, b)?;
    if !curve.is_curvature_monotone().unwrap_or(false) {
        return None;
    }
    Some(HandleSuggestion {
        scale: (a, b),
        curve,
        deviation: s.deviation(a, b),
    })
}

/// What the check found at one join.
#[derive(Clone, Debug, PartialEq)]
pub struct JoinCheck {
    /// The segment before the join (the one after is the next, cyclically).
    pub after_segment: usize,
    /// Where.
    pub point: Point,
    /// Angle between the end tangent before and the start tangent after (radians, 0 to π).
    pub angle_break: f64,
    /// At G1 joins: `|κ₁ - κ₂| / max(|κ₁|, |κ₂|)` (0 when both are 0).
    pub curvature_jump: Option<f64>,
    /// G1 (break at most `g1_angle`).
    pub g1: bool,
    /// G2 (G1 and jump below `g2_jump`).
    pub g2: bool,
    /// Break above `g1_angle` and below `near_break`: probably unintended.
    pub near_break: bool,
    /// At least one side's curvature grows without bound at the join (a retracted handle):
    /// no jump is measured.
    pub unbounded_curvature: bool,
    /// Whether the source marks the join's point smooth (a UFO's `smooth="yes"`); None
    /// where the source marks no points (binary fonts, SVG, DXF). [`check_contour`] leaves
    /// it None; a reader that has the marks sets them ([`ContourCheck::mark_smooth`]).
    pub smooth_mark: Option<bool>,
}

/// A non-monotone segment's finding, if its bump is at least `min_bump`: a hook (an
/// extremum within `hook_zone` of an end: a defect at the join, scored twice its bump),
/// several extrema (one and a half times), or one smooth extremum inside (half its bump:
/// often the design, listed for its size).
fn not_monotone_finding(
    contour: usize,
    segment: usize,
    s: &SegmentCheck,
    opts: &OutlineOptions,
) -> Option<Finding> {
    if s.monotone != Some(false) || s.bump < opts.min_bump {
        return None;
    }
    let z = opts.hook_zone;
    let hook = s.extrema.iter().find(|e| e.0 < z || e.0 > 1.0 - z);
    let (kind, weight, at) = match (hook, s.extrema.len()) {
        (Some(h), _) => ("hook", 2.0, h.1),
        (None, 1) => ("curvature-extremum", 0.5, s.extrema[0].1),
        (None, _) => (
            "not-monotone",
            1.5,
            s.extrema.first().map_or(s.start, |e| e.1),
        ),
    };
    let n = s.extrema.len();
    let what = match kind {
        "hook" => format!(
            "curvature hook at the {} (an extremum within {:.0} % of it)",
            if hook.is_some_and(|h| h.0 < z) {
                "start"
            } else {
                "end"
            },
            100.0 * z
        ),
        "curvature-extremum" => "one curvature extremum inside (often the design)".to_string(),
        _ => format!("curvature not monotone: {n} extrema"),
    };
    Some(Finding {
        contour,
        kind,
        segment,
        point: at,
        score: weight * s.bump,
        message: format!(
            "{what}; the curvature's detour is {:.0} % of its largest",
            100.0 * s.bump
        ),
    })
}

/// A place worth a look, for the ranked list.
#[derive(Clone, Debug, PartialEq)]
pub struct Finding {
    /// Contour index.
    pub contour: usize,
    /// What: "hook", "not-monotone" (several extrema), "curvature-extremum" (one, inside),
    /// "near-break", "curvature-jump", "degenerate".
    pub kind: &'static str,
    /// Segment index (for a join, the segment before it).
    pub segment: usize,
    /// Where.
    pub point: Point,
    /// How bad, for the ranking, on one scale for every kind: half a near-break's angle over
    /// the near-break threshold, a relative curvature jump (a quarter next to a line or a flat
    /// end, a half where the curvature changes sign), a curvature bump (twice for a hook, one
    /// and a half times for several extrema, half for one extremum inside); degenerate
    /// segments 0.5.
    pub score: f64,
    /// For a person.
    pub message: String,
}

/// The check of one contour.
#[derive(Clone, Debug, PartialEq)]
pub struct ContourCheck {
    /// Per segment, in order.
    pub segments: Vec<SegmentCheck>,
    /// Per join, in order (n - 1 for an open contour, n for a closed one).
    pub joins: Vec<JoinCheck>,
    /// Whether the last segment joins the first.
    pub closed: bool,
}

impl ContourCheck {
    /// Sets the joins' smooth marks from the source's: `marks[i]` for the join after
    /// segment `i` (missing entries leave a join unmarked).
    pub fn mark_smooth(&mut self, marks: &[bool]) {
        for j in &mut self.joins {
            j.smooth_mark = marks.get(j.after_segment).copied();
        }
    }

    /// Whether a line is on either side of the join `j` (one of this contour's).
    pub fn at_line(&self, j: &JoinCheck) -> bool {
        let n = self.segments.len();
        [j.after_segment, (j.after_segment + 1) % n]
            .iter()
            .any(|&i| self.segments.get(i).is_some_and(|s| s.degree == 1))
    }

    /// Whether `j` is the curvature step of a line running tangentially into a curve at a
    /// point the source does not mark smooth: the design, left out of [`findings`].
    pub fn unlisted_line_step(&self, j: &JoinCheck) -> bool {
        j.g1 && !j.g2
            && j.curvature_jump.is_some()
            && j.smooth_mark != Some(true)
            && self.at_line(j)
    }

    /// Segments whose curvature is monotone.
    pub fn monotone_count(&self) -> usize {
        self.segments
            .iter()
            .filter(|s| s.monotone == Some(true))
            .count()
    }
}

/// The parameter values in (0, 1) where the curvature of `c` changes sign, exact for its
/// f64 inputs ([`CurvatureMonotone::inflections`]); none for a line or a segment that
/// cannot be checked.
pub fn inflections(c: &RationalBezier) -> Vec<f64> {
    if c.degree() < 2 {
        return Vec::new();
    }
    c.inflections().unwrap_or_default()
}

/// The unit tangent at t = 0 (`start`) or t = 1: along the first control point that differs
/// from the end point (the limit of the tangent at a retracted handle); None for a point.
fn end_tangent(c: &RationalBezier, start: bool) -> Option<Vec2> {
    let p = c.points();
    let (end, mut others): (Point, Box<dyn Iterator<Item = &Point>>) = if start {
        (p[0], Box::new(p.iter().skip(1)))
    } else {
        (p[p.len() - 1], Box::new(p.iter().rev().skip(1)))
    };
    let q = others.find(|q| **q != end)?;
    // Halved first: the difference of two finite coordinates near ±1.8e308 overflows, and
    // a segment of such points is not a point. The direction is the same.
    let (a, b) = (q.to_vec2() * 0.5, end.to_vec2() * 0.5);
    let v = if start { a - b } else { b - a };
    // Scaled to its largest component before the length (whose square would overflow or
    // underflow near the ends of the range); v is not zero: q != end.
    let m = v.x.abs().max(v.y.abs());
    let u = v / m;
    let l = u.hypot();
    (m > 0.0 && l.is_finite()).then(|| u / l)
}

/// A signed end curvature as a number: ±infinity where it is unbounded.
fn end_value(e: &EndCurvature) -> f64 {
    match e {
        EndCurvature::Unbounded { positive, .. } => {
            if *positive {
                f64::INFINITY
            } else {
                f64::NEG_INFINITY
            }
        }
        _ => e.value().unwrap_or(0.0),
    }
}

/// Check one segment (no suggestion: [`check_segment_with`]).
pub fn check_segment(c: &RationalBezier) -> SegmentCheck {
    check_segment_with(c, &OutlineOptions::default())
}

/// Check one segment, with a handle suggestion when [`OutlineOptions::suggest`] asks.
pub fn check_segment_with(c: &RationalBezier, opts: &OutlineOptions) -> SegmentCheck {
    let w = c.weights();
    let rational = w.iter().any(|v| (v - w[0]).abs() > 1e-12 * w[0].abs());
    let mut out = SegmentCheck {
        degree: c.degree(),
        start: c.points()[0],
        rational,
        monotone: None,
        trend: None,
        extrema: Vec::new(),
        inflections: Vec::new(),
        end_curvatures: None,
        ends: None,
        max_abs_curvature: 0.0,
        bump: 0.0,
        flag: None,
        notes: Vec::new(),
        exact: false,
        suggestion: None,
    };
    if end_tangent(c, true).is_none() {
        out.flag = Some("the segment is a point (all control points coincide)".into());
        return out;
    }
    // Cooperative cancellation: once the caller's deadline has passed, the rest of an outline
    // is flagged instead of checked (and the caller, seeing the deadline, answers timeout).
    if crate::deadline::expired() {
        out.flag = Some("not checked: the work ran past its deadline".into());
        return out;
    }
    let r = match c.curvature_monotone() {
        Ok(r) => r,
        Err(e) => {
            out.flag = Some(e.to_string());
            return out;
        }
    };
    let (k0, k1) = (end_value(&r.ends[0]), end_value(&r.ends[1]));
    out.end_curvatures = Some((k0, k1));
    out.ends = Some(r.ends);
    out.max_abs_curvature = k0.abs().max(k1.abs());
    out.exact = r.exact;
    for (e, at) in r.ends.iter().zip(["start", "end"]) {
        if let Some(d) = e.describe() {
            out.notes.push(format!("{at}: {d}"));
        }
    }
    out.monotone = Some(r.monotone);
    out.trend = r.trend;
    if c.degree() >= 2 {
        out.inflections = inflections(c).into_iter().map(|t| (t, c.eval(t))).collect();
    }
    let mut along = vec![k0];
    for &t in &r.extrema {
        let k = c.kappa(t);
        if k.is_finite() {
            out.max_abs_curvature = out.max_abs_curvature.max(k.abs());
        }
        along.push(k);
        out.extrema.push((t, c.eval(t)));
    }
    along.push(k1);
    out.bump = bump(&along, out.max_abs_curvature);
    if let (Some(tol), Some(false), false) = (opts.suggest, out.monotone, rational) {
        if c.degree() == 3 {
            if let Ok(b) = crate::Bezier::new(c.points().to_vec()) {
                out.suggestion = suggest_handles(&b, tol);
            }
        }
    }
    out
}

/// The relative detour of the curvature values `k` (ends and extrema in order): see
/// [`SegmentCheck::bump`].
fn bump(k: &[f64], max_abs: f64) -> f64 {
    if k.iter().any(|v| !v.is_finite()) || max_abs <= 0.0 || !max_abs.is_finite() {
        return 0.0;
    }
    let variation: f64 = k.windows(2).map(|w| (w[1] - w[0]).abs()).sum();
    let direct = (k[k.len() - 1] - k[0]).abs();
    ((variation - direct) / (2.0 * max_abs)).max(0.0)
}

/// How far rounding to `grid` can turn the tangents at a join whose handle legs (from the
/// on-curve point to the next control point on either side) have lengths `legs`: half a
/// cell's diagonal over each leg, summed (radians); 0 where a leg is 0 (no tangent from
/// it) or there is no grid. A join whose break is within this of the G1 angle is G1.
pub fn g1_slack(grid: f64, legs: (f64, f64)) -> f64 {
    let slack = std::f64::consts::FRAC_1_SQRT_2 * grid * (1.0 / legs.0 + 1.0 / legs.1);
    if slack.is_finite() {
        slack
    } else {
        0.0
    }
}

/// Check a contour of consecutive segments.
pub fn check_contour(
    segments: &[RationalBezier],
    closed: bool,
    opts: &OutlineOptions,
) -> ContourCheck {
    let checks: Vec<SegmentCheck> = segments
        .iter()
        .map(|c| check_segment_with(c, opts))
        .collect();
    let n = segments.len();
    let join_count = if closed { n } else { n.saturating_sub(1) };
    let mut joins = Vec::with_capacity(join_count);
    for i in 0..join_count {
        let (a, b) = (&segments[i], &segments[(i + 1) % n]);
        let (Some(ta), Some(tb)) = (end_tangent(a, false), end_tangent(b, true)) else {
            continue; // a point segment: flagged on the segment
        };
        // Curvatures on both sides (from the checks; a segment that could not be checked
        // gives no jump).
        let side = |s: &SegmentCheck, end: bool| {
            s.end_curvatures.map(|(k0, k1)| if end { k1 } else { k0 })
        };
        let (ka, kb) = (side(&checks[i], true), side(&checks[(i + 1) % n], false));
        let angle = ta.cross(tb).atan2(ta.dot(tb)).abs();
        // The handle legs at the join: what rounding to the grid can turn them by.
        let leg = |c: &RationalBezier, end: bool| {
            let p = c.points();
            let n = p.len();
            let l = if end {
                p[n - 1] - p[n - 2]
            } else {
                p[1] - p[0]
            };
            l.hypot()
        };
        let g1 = angle <= opts.g1_angle + g1_slack(opts.grid, (leg(a, true), leg(b, false)));
        let unbounded = [ka, kb].iter().any(|k| k.is_some_and(|v| v.is_infinite()));
        let jump = match (ka, kb) {
            (Some(ka), Some(kb)) if g1 && !unbounded => {
                let m = ka.abs().max(kb.abs());
                Some(if m > 0.0 { (ka - kb).abs() / m } else { 0.0 })
            }
            _ => None,
        };
        joins.push(JoinCheck {
            after_segment: i,
            point: a.points()[a.points().len() - 1],
            angle_break: angle,
            curvature_jump: jump,
            g1,
            g2: jump.is_some_and(|j| j < opts.g2_jump),
            near_break: !g1 && angle < opts.near_break,
            unbounded_curvature: unbounded,
            smooth_mark: None,
        });
    }
    ContourCheck {
        segments: checks,
        joins,
        closed,
    }
}

/// The places of `contours` most worth a look, worst first: near-breaks (by angle), then
/// segments whose curvature is not monotone (by their number of extrema), then curvature
/// jumps at G1 joins (by size), then degenerate segments. A line meeting a curve
/// tangentially has a curvature step unless the curve ends flat: that is the design of a
/// stem running into a bowl, and is listed only where the source marks the join smooth.
pub fn findings(contours: &[ContourCheck], opts: &OutlineOptions) -> Vec<Finding> {
    let mut out = Vec::new();
    for (ci, c) in contours.iter().enumerate() {
        for j in &c.joins {
            if j.near_break {
                out.push(Finding {
                    contour: ci,
                    kind: "near-break",
                    segment: j.after_segment,
                    point: j.point,
                    // Half at the near-break threshold: the larger the break the more visible,
                    // and the likelier it was meant (a font stores no smooth flags).
                    score: 0.5 * j.angle_break / opts.near_break,
                    message: format!(
                        "tangent break of {:.3}° (under {:.1}°: probably meant smooth)",
                        j.angle_break.to_degrees(),
                        opts.near_break.to_degrees()
                    ),
                });
            }
            if let Some(jump) = j.curvature_jump.filter(|v| *v >= opts.g2_jump) {
                // Next to a line (or a flat end: a 90 to 100 % jump) only a zero end
                // curvature is G2, and a sign change (over 100 %) is an inflection on the node: both
                // common and mostly meant, so they rank at a quarter and a half.
                let at_line = c.at_line(j);
                if c.unlisted_line_step(j) {
                    continue;
                }
                // A flat end: one side's curvature under a tenth of the other's, same sign.
                let flat = (0.9..=1.0).contains(&jump);
                let (weight, why) = if at_line || flat {
                    (
                        0.25,
                        " (next to a line or a flat end: G2 only with zero curvature)",
                    )
                } else if jump > 1.0 {
                    (
                        0.5,
                        " (the curvature changes sign: an inflection on the node)",
                    )
                } else {
                    (1.0, "")
                };
                out.push(Finding {
                    contour: ci,
                    kind: "curvature-jump",
                    segment: j.after_segment,
                    point: j.point,
                    score: jump.min(1.0) * weight,
                    message: format!("smooth join, curvature jumps by {:.0} %{why}", 100.0 * jump),
                });
            }
        }
        for (si, s) in c.segments.iter().enumerate() {
            if let Some(f) = not_monotone_finding(ci, si, s, opts) {
                out.push(f);
            }
            if let Some(f) = &s.flag {
                out.push(Finding {
                    contour: ci,
                    kind: "degenerate",
                    segment: si,
                    point: s.start,
                    score: 0.5,
                    message: f.clone(),
                });
            }
        }
    }
    out.sort_by(|a, b| b.score.total_cmp(&a.score));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thresholds_in_degrees_become_options_and_bad_ones_are_named() {
        let t = Thresholds {
            g1_angle_degrees: 0.1,
            g2_jump: 0.02,
            near_break_degrees: 2.0,
            min_bump: 0.1,
        };
        let o = t.options(1.0).unwrap();
        assert!((o.g1_angle - 0.1f64.to_radians()).abs() < 1e-15 && o.grid == 1.0);
        for bad in [
            Thresholds { g2_jump: -0.1, ..t },
            Thresholds {
                near_break_degrees: f64::NAN,
                ..t
            },
        ] {
            let e = bad.options(0.0).unwrap_err().to_string();
            assert!(e.contains("g2_jump") || e.contains("near_break"), "{e}");
        }
        assert!(t
            .options(f64::INFINITY)
            .unwrap_err()
            .to_string()
            .contains("grid"));
    }
    use crate::Bezier;

    /// A four-cubic circle (handles 0.5523 of the radius) varies in curvature by a few per
    /// cent: not monotone, but no finding by default; listed when every bump is asked
    /// for. A cubic whose extremum sits next to its end is a hook.
    #[test]
    fn findings_have_sizes_and_kinds() {
        let k = 0.5523;
        let q = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0), (1.0, 0.0)];
        let circle: Vec<RationalBezier> = (0..4)
            .map(|i| {
                let ((ax, ay), (bx, by)) = (q[i], q[i + 1]);
                cubic([
                    ax,
                    ay,
                    ax - k * ay,
                    ay + k * ax,
                    bx + k * by,
                    by - k * bx,
                    bx,
                    by,
                ])
            })
            .collect();
        let opts = OutlineOptions::default();
        let c = check_contour(&circle, true, &opts);
        assert_eq!(c.monotone_count(), 0, "a cubic is no circular arc");
        for s in &c.segments {
            assert!(s.bump > 0.0 && s.bump < 0.05, "{}", s.bump);
        }
        assert!(findings(std::slice::from_ref(&c), &opts).is_empty());
        let all = OutlineOptions {
            min_bump: 0.0,
            ..opts
        };
        let f = findings(&[c], &all);
        assert_eq!(f.len(), 4);
        // Three extrema each (two minima around a middle maximum), a 4 % detour.
        assert!(f.iter().all(|f| f.kind == "not-monotone"), "{f:?}");
        // One extremum, at t ≈ 0.04: a hook at the start.
        let hooked = cubic([0.0, 0.0, 0.5, 2.0, 6.0, 1.0, 10.0, 0.0]);
        let s = check_segment_with(&hooked, &opts);
        assert!(s.extrema.iter().any(|e| e.0 < 0.05), "{:?}", s.extrema);
        let c = check_contour(&[hooked], false, &opts);
        let f = findings(&[c], &opts);
        assert_eq!(f[0].kind, "hook", "{f:?}");
        assert!(f[0].message.contains("start"), "{}", f[0].message);
    }

    /// A contour from -1e308 to 1.6e308 is checked like the same contour at unit scale
    /// (its segments were flagged "a point", their tangents' differences overflowing), with
    /// the same join angle and the end curvatures divided by the scale.
    #[test]
    fn a_contour_across_the_whole_range_is_checked_as_at_unit_scale() {
        let unit = [
            cubic([-1.0, 0.0, -0.5, 0.1, 0.5, 0.1, 1.0, 0.0]),
            cubic([1.0, 0.0, 1.2, -0.1, 1.5, -0.5, 1.6, -1.0]),
        ];
        let big: Vec<RationalBezier> = unit
            .iter()
            .map(|c| {
                let q = c
                    .points()
                    .iter()
                    .map(|p| Point::new(p.x * 1e308, p.y * 1e308));
                Bezier::new(q.collect()).unwrap().to_rational()
            })
            .collect();
        let opts = OutlineOptions::default();
        let (a, b) = (
            check_contour(&unit, false, &opts),
            check_contour(&big, false, &opts),
        );
        for (s, t) in a.segments.iter().zip(&b.segments) {
            assert_eq!(t.flag, None);
            assert_eq!(s.monotone, t.monotone);
            let ((k0, k1), (m0, m1)) = (s.end_curvatures.unwrap(), t.end_curvatures.unwrap());
            for (k, m) in [(k0, m0), (k1, m1)] {
                assert!((m * 1e308 - k).abs() < 1e-6 * k.abs(), "{k} vs {m}");
            }
        }
        let (j, k) = (&a.joins[0], &b.joins[0]);
        assert!((j.angle_break - k.angle_break).abs() < 1e-12);
    }

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }
    fn cubic(a: [f64; 8]) -> RationalBezier {
        Bezier::new(vec![
            p(a[0], a[1]),
            p(a[2], a[3]),
            p(a[4], a[5]),
            p(a[6], a[7]),
        ])
        .unwrap()
        .to_rational()
    }

    #[test]
    fn a_circle_of_four_cubics_is_g2_with_near_constant_curvature() {
        // The usual four-cubic circle (handle 0.5523 of the radius): curvature within 3e-4 of
        // constant, every join G1 and G2.
        let k = 0.552_284_749_8;
        let segs = [
            cubic([1.0, 0.0, 1.0, k, k, 1.0, 0.0, 1.0]),
            cubic([0.0, 1.0, -k, 1.0, -1.0, k, -1.0, 0.0]),
            cubic([-1.0, 0.0, -1.0, -k, -k, -1.0, 0.0, -1.0]),
            cubic([0.0, -1.0, k, -1.0, 1.0, -k, 1.0, 0.0]),
        ];
        let c = check_contour(&segs, true, &OutlineOptions::default());
        assert_eq!(c.joins.len(), 4);
        for j in &c.joins {
            assert!(j.g1 && j.g2 && j.angle_break < 1e-12, "{j:?}");
        }
        for (s, seg) in c.segments.iter().zip(&segs) {
            assert!(s.inflections.is_empty());
            // The exact largest |κ| bounds the sampled one, within 1 % of 1.
            let sampled = (0..=1000)
                .map(|i| seg.kappa(i as f64 / 1000.0).abs())
                .fold(0.0, f64::max);
            assert!(s.max_abs_curvature >= sampled - 1e-12);
            assert!(
                s.max_abs_curvature - sampled < 1e-6,
                "{} {sampled}",
                s.max_abs_curvature
            );
            assert!((s.max_abs_curvature - 1.0).abs() < 1e-2);
            for i in 0..=100 {
                let r = seg.eval(i as f64 / 100.0).to_vec2().hypot();
                assert!((r - 1.0).abs() < 3e-4, "{r}");
            }
        }
        assert!(findings(&[c], &OutlineOptions::default())
            .iter()
            .all(|f| f.kind == "not-monotone"));
    }

    #[test]
    fn inflections_breaks_and_degenerate_segments_are_found() {
        // An S-curve: one inflection at t = 1/2 by symmetry.
        let s = cubic([0.0, 0.0, 1.0, 1.0, 2.0, -1.0, 3.0, 0.0]);
        let c = check_segment(&s);
        assert_eq!(c.inflections.len(), 1);
        assert!((c.inflections[0].0 - 0.5).abs() < 1e-12);
        // Two lines meeting at 1°: a near-break, found first.
        let l1 = Bezier::new(vec![p(0.0, 0.0), p(1.0, 0.0)])
            .unwrap()
            .to_rational();
        let a = 1f64.to_radians();
        let l2 = Bezier::new(vec![p(1.0, 0.0), p(1.0 + a.cos(), a.sin())])
            .unwrap()
            .to_rational();
        let opts = OutlineOptions::default();
        let c = check_contour(&[l1.clone(), l2], false, &opts);
        assert!(c.joins[0].near_break && !c.joins[0].g1);
        assert!((c.joins[0].angle_break.to_degrees() - 1.0).abs() < 1e-9);
        let f = findings(&[c], &opts);
        assert_eq!(f[0].kind, "near-break");
        // A point segment: flagged, no NaN. A cubic with a retracted handle: a verdict, the
        // end's unbounded curvature said in its notes (±infinity as a number, never NaN).
        let point = Bezier::new(vec![p(1.0, 1.0), p(1.0, 1.0), p(1.0, 1.0)])
            .unwrap()
            .to_rational();
        let c = check_segment(&point);
        assert!(c.flag.is_some() && c.monotone.is_none() && c.end_curvatures.is_none());
        let hooked = cubic([0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 1.0]);
        let c = check_segment(&hooked);
        assert!(c.flag.is_none() && c.monotone.is_some(), "{c:?}");
        assert!(c.notes[0].contains("without bound"), "{c:?}");
        let (k0, k1) = c.end_curvatures.unwrap();
        assert!(k0.is_infinite() && k1.is_finite() && c.max_abs_curvature.is_infinite());
        let c = check_contour(&[l1, point], false, &opts);
        assert!(c.joins.is_empty());
    }

    #[test]
    fn handle_suggestions_make_the_cubic_monotone_and_move_it_little() {
        // The classic bump: curvature peaks in the middle.
        let c =
            crate::Bezier::new(vec![p(0.0, 0.0), p(1.0, 1.0), p(2.0, 1.0), p(3.0, 0.0)]).unwrap();
        assert!(!c.is_curvature_monotone().unwrap());
        // A symmetric arch cannot be made monotone by its handle lengths within a small
        // tolerance ...
        assert!(suggest_handles(&c, 1e-3).is_none());
        // ... a lopsided one can: ends and tangent directions kept, curvature monotone, the
        // deviation within the tolerance.
        let c =
            crate::Bezier::new(vec![p(0.0, 0.0), p(2.0, 0.0), p(3.0, 0.5), p(3.2, 2.0)]).unwrap();
        assert!(!c.is_curvature_monotone().unwrap());
        let s = suggest_handles(&c, 0.5).expect("a suggestion");
        let q = s.curve.points();
        assert_eq!(q[0], c.points()[0]);
        assert_eq!(q[3], c.points()[3]);
        assert!((q[1] - q[0]).cross(c.points()[1] - c.points()[0]).abs() < 1e-12);
        assert!((q[2] - q[3]).cross(c.points()[2] - c.points()[3]).abs() < 1e-12);
        assert!(s.curve.is_curvature_monotone().unwrap());
        assert!(s.deviation <= 0.5 && s.deviation > 0.0, "{}", s.deviation);
        // An upper bound of the move, and a tight one: against 10,001 samples of the two
        // curves at equal parameters (de Casteljau's evaluation, not the bound's splits).
        let sampled = (0..=10_000)
            .map(|i| {
                let t = i as f64 / 10_000.0;
                (s.curve.eval(t) - c.eval(t)).hypot()
            })
            .fold(0.0, f64::max);
        assert!(
            s.deviation >= sampled && s.deviation <= sampled * (1.0 + 2e-4),
            "{} vs sampled {sampled}",
            s.deviation
        );
        // Through the options: only not-monotone polynomial cubics get one.
        let opts = OutlineOptions {
            suggest: Some(0.5),
            ..OutlineOptions::default()
        };
        let r = check_segment_with(&c.to_rational(), &opts);
        assert_eq!(r.suggestion.as_ref().map(|s| s.scale), Some(s.scale));
    }

    #[test]
    fn verdicts_never_contradict_dense_sampling() {
        // Random cubics: a "monotone" verdict is never contradicted by 20,000 samples of κ.
        let mut rng = crate::samples::SplitMix64::new(19);
        for _ in 0..200 {
            let mut v = [0.0; 8];
            for x in v.iter_mut() {
                *x = rng.next_f64() * 10.0;
            }
            let c = cubic(v);
            let s = check_segment(&c);
            if s.monotone != Some(true) {
                continue;
            }
            let ks: Vec<f64> = (0..20_000).map(|i| c.kappa(i as f64 / 19_999.0)).collect();
            let up = ks
                .windows(2)
                .all(|w| w[1] >= w[0] - 1e-9 * w[0].abs().max(1.0));
            let down = ks
                .windows(2)
                .all(|w| w[1] <= w[0] + 1e-9 * w[0].abs().max(1.0));
            assert!(up || down, "{v:?}");
        }
    }
}
