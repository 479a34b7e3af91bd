//! Pen strokes as contours: corners, straight runs and closed loops.
//!
//! A designer's stroke is not always one fair curve: an L has a corner, a rectangle four,
//! a straight stroke none and no curvature, a loop ends where it began. [`fit_contour`]
//! takes the stroke in stages, each a function of its own:
//!
//! 1. **open or closed** ([`closes`]): as the caller says, else closed when the stroke ends
//!    near its start (within 3 tolerances or 5 % of its size) after going around (its
//!    length at least twice its size); an overshoot past the start is trimmed;
//! 2. **corners** ([`corners`]): at each point, the directions of the stroke over the
//!    stretches of arc length `w` before and after it (least-squares lines: the noise of a
//!    hand averages out over a few dozen points) turn by θ_w. A corner is a turn above
//!    [`ContourOptions::corner_angle`] that happens in a short stretch: over windows a third
//!    as long the turn is nearly as large (θ_w/3 ≥ [`SHORT_SHARE`] θ_w), over windows twice
//!    as long hardly larger (θ_2w < [`CONCENTRATION`] θ_w); on an arc of radius R,
//!    θ_w ≈ w / R at every scale. `w` is [`WINDOW_TOLERANCES`] tolerances (at most a sixth
//!    of the stroke) and at least [`WINDOW_NOISE`] times the noise. The largest turns are
//!    kept first, none within `w` of another, each then put where it splits the stroke
//!    into the two straightest stretches around it. At a point of a sparse stroke (both
//!    steps longer than `w` and [`SPARSE_STEP`] of its size) the chords alone turn, and a
//!    turn of [`SPARSE_CORNER`] or more is a corner;
//! 3. **runs**: the points from one corner to the next (both included, so the runs meet at
//!    the corner exactly; a run of fewer than 4 points that is not straight is a polygon,
//!    its inner points corners too); a closed contour with corners starts at its first corner, one
//!    without is one run from its first point around to it again;
//! 4. **straight runs** (`line_ends`): a run whose points lie within the tolerance of
//!    their least-squares line is a line (a straight stroke is the limit of every LAC:
//!    zero curvature); two straight runs meet where their lines cross, not at the noisy
//!    sample between them, and an open stroke's straight end is its last point's foot on
//!    the line;
//! 5. **each run**: that line where every point lies within the tolerance of it, else a
//!    line along the chord where they lie within the tolerance of that, else its straight
//!    stretches (`super::straight`: between bends in the same direction) as lines and the
//!    curves between them as G2 sketches of [`super::fit_sketch`] that leave the lines along
//!    them with zero curvature ([`SketchOptions::line_ends`]; the joins are
//!    [`SmoothJoin`]s), else the run as one G2 sketch.
//!
//! A closed contour without corners is one run whose seam is faired like every joint of the
//! sketch ([`SketchOptions::closed`]: one tangent at both ends, the curvature jump across the
//! seam among the fairing's equations); [`Seam`] reports what is left there.
//!
//! Known limit: a straight stretch between bends in opposite directions (the middle of a Z
//! with rounded turns) or next to an open end is fitted with the run's pieces, not as a
//! line: the flank of an S or a wave looks the same.

pub use super::constants::SPARSE_STEP;
use super::input::{arc_lengths, bbox_diagonal, check_points, noise_level, sparse, Noise};
use super::slot::segment_distance;
use super::straight;
use super::thinning;
use super::types::{Sketch, SketchOptions};
use super::{default_tolerance_of, fit_sketch};
use crate::error::{Error, Result};
use kurbo::{Point, Vec2};

/// The least turn of a corner at a point of a sparse stroke (both its steps longer than
/// the corner window and [`SPARSE_STEP`] of its size: a stroke of some 50 points or
/// fewer): such points turn at every point of a sampled arc, as a polygon's
/// do, so the turn alone decides: 80° (a rectangle's 90° and a triangle's corners are
/// corners; a regular pentagon's 72°, a wave sampled at 13 points turning up to 76°, are
/// smooth).
pub const SPARSE_CORNER: f64 = 80.0 * std::f64::consts::PI / 180.0;

/// Points closer than this share of a stroke's size are one point (rounding).
const COINCIDENT: f64 = 1e-9;

/// Window length of the corner test, in tolerances...
pub const WINDOW_TOLERANCES: f64 = 6.0;

/// ... and at least this many times the estimated noise ([`super::estimated_noise`]), so
/// that a tight tolerance does not shrink the windows to a few points, whose directions
/// turn with the jitter (the default tolerance is 3 times the noise).
pub const WINDOW_NOISE: f64 = 30.0;

/// A corner's turn over windows of `2w` is less than this times its turn over `w` (on a
/// smooth arc it is about twice).
pub const CONCENTRATION: f64 = 1.35;

/// A corner's turn over windows of `w / 3` is at least this share of its turn over `w` (on
/// a smooth arc about a third).
pub const SHORT_SHARE: f64 = 0.7;

/// The most pieces a run of the contour may take at a rung of the default tolerance's
/// ladder other than the last (an S takes 2 to 4, a loop 4 to 8).
const RUNG_PIECES: usize = 24;

/// The most pieces of a curve between two straight stretches (a rounded corner takes 2 to
/// 4): one that needs more does not fit between those lines, and the next setback, or the
/// run as one curve, is tried at once instead of after splitting up to the run's limit.
const PART_PIECES: usize = 8;

/// The root-mean-square bow of a hand's straight stretch, in tolerances (a drawn side
/// that the hand's drift bows by up to about half the tolerance is still straight).
const HAND_BOW: f64 = 0.3;

/// What the fit of a run may use: the tolerance and the most pieces.
#[derive(Clone, Copy, Debug)]
struct Fit {
    tolerance: f64,
    max_pieces: usize,
    /// The root-mean-square bow a straight stretch may have ([`straight::Test::allowing_bow`]).
    bow: f64,
}

impl Fit {
    /// At `tolerance`, with [`SketchOptions`]'s default for the pieces.
    fn at(tolerance: f64) -> Fit {
        Fit {
            tolerance,
            max_pieces: SketchOptions::with_tolerance(tolerance).max_pieces,
            bow: 0.0,
        }
    }
}

/// What [`fit_contour`] may do.
#[derive(Clone, Debug, PartialEq)]
pub struct ContourOptions {
    /// Largest distance from an input point to the result; `None`: [`default_tolerance`](super::default_tolerance).
    pub tolerance: Option<f64>,
    /// Closed or open; `None`: decided from the stroke ([`closes`]).
    pub closed: Option<bool>,
    /// The least turn of a corner (radians).
    pub corner_angle: f64,
    /// The size of one device pixel in the points' units (the editor sends its view's), or
    /// `None` to read it from the points (whole steps of a mouse: `resolution::quantum`).
    /// The default tolerance is at least three of them: a stroke drawn on a screen is never
    /// taken as more precise than the screen shows it.
    pub resolution: Option<f64>,
}

impl Default for ContourOptions {
    fn default() -> Self {
        ContourOptions {
            tolerance: None,
            closed: None,
            corner_angle: 35f64.to_radians(),
            resolution: None,
        }
    }
}

/// One run of a contour: a line, or a G2 curve of LAC pieces.
#[derive(Clone, Debug)]
pub enum Run {
    /// A straight run from `start` to `end` (zero curvature).
    Line {
        /// The first point.
        start: Point,
        /// The last point.
        end: Point,
    },
    /// A fair run ([`super::fit_sketch`]).
    Curve(Box<Sketch>),
}

impl Run {
    /// `"line"` or `"curve"` (the protocol's names).
    pub fn kind(&self) -> &'static str {
        match self {
            Run::Line { .. } => "line",
            Run::Curve(_) => "curve",
        }
    }

    /// A line, or a curve that is G2 at every joint.
    pub fn is_g2(&self) -> bool {
        match self {
            Run::Line { .. } => true,
            Run::Curve(s) => s.g2,
        }
    }

    /// Its first and last points.
    pub fn ends(&self) -> (Point, Point) {
        match self {
            Run::Line { start, end } => (*start, *end),
            Run::Curve(s) => {
                let j = s.joints();
                (j[0], j[j.len() - 1])
            }
        }
    }

    /// Unit tangents at its start and end (curve order).
    fn tangents(&self) -> (Vec2, Vec2) {
        match self {
            Run::Line { start, end } => {
                let d = unit(*end - *start);
                (d, d)
            }
            Run::Curve(s) => {
                let (first, last) = (
                    &s.pieces[0].rational,
                    &s.pieces[s.pieces.len() - 1].rational,
                );
                let (p, q) = (first.points(), last.points());
                (unit(p[1] - p[0]), unit(q[q.len() - 1] - q[q.len() - 2]))
            }
        }
    }

    /// Its largest |curvature| (0 for a line).
    fn largest_curvature(&self) -> f64 {
        match self {
            Run::Line { .. } => 0.0,
            Run::Curve(s) => s
                .pieces
                .iter()
                .map(|p| p.end_curvatures.0.abs().max(p.end_curvatures.1.abs()))
                .fold(0.0, f64::max),
        }
    }

    /// Signed curvatures at its start and end.
    fn end_curvatures(&self) -> (f64, f64) {
        match self {
            Run::Line { .. } => (0.0, 0.0),
            Run::Curve(s) => (
                s.pieces[0].end_curvatures.0,
                s.pieces[s.pieces.len() - 1].end_curvatures.1,
            ),
        }
    }
}

/// A corner of the contour: where one run ends and the next begins.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Corner {
    /// The input point where the stroke is split there.
    pub index: usize,
    /// Its place, where the runs meet: between two straight runs where their lines cross
    /// (the noisy sample is within 3 tolerances of it), else the input point.
    pub point: Point,
    /// How far the stroke turns there (radians, the window test's θ_w).
    pub angle: f64,
    /// The run it follows (`runs[run]` ends there, the next run starts there).
    pub run: usize,
}

/// A smooth join between a straight run and a curved one inside a stroke (no corner): the
/// curve leaves the line along it with zero curvature, so the join is G2.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SmoothJoin {
    /// The run it follows (closed: the last run's join with the first is the last one).
    pub run: usize,
    /// Where the runs meet.
    pub point: Point,
    /// The angle between their tangents there (radians; rounding).
    pub angle: f64,
    /// The curvature jump there over the larger of the two runs' largest curvatures.
    pub curvature_jump: f64,
}

/// The seam of a closed contour without corners: where the one run ends at its start.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Seam {
    /// The angle between the tangents there (radians).
    pub angle: f64,
    /// The relative curvature jump there.
    pub curvature_jump: f64,
}

/// The result of [`fit_contour`].
#[derive(Clone, Debug)]
pub struct SketchContour {
    /// The runs in order (for a closed contour the last ends where the first starts).
    pub runs: Vec<Run>,
    /// The corners in order, each after its run ([`Corner::run`]; closed: the last may
    /// follow the last run and come before the first).
    pub corners: Vec<Corner>,
    /// The smooth joins in order: where a straight stretch inside a curved part of the
    /// stroke meets the curves next to it ([`SmoothJoin::run`]).
    pub smooth_joins: Vec<SmoothJoin>,
    /// Closed.
    pub closed: bool,
    /// The seam of a closed contour that is one curve (no corners, no straight stretch).
    pub seam: Option<Seam>,
    /// The tolerance used.
    pub tolerance: f64,
    /// Largest distance from an input point (of the stroke as kept: an overshoot past the
    /// start of a closed one trimmed) to the result.
    pub max_deviation: f64,
    /// Input points trimmed from the end of a closed stroke (its overshoot).
    pub trimmed: usize,
}

impl SketchContour {
    /// How many pieces: one per line run, a curve run's pieces.
    pub fn pieces(&self) -> usize {
        self.runs
            .iter()
            .map(|r| match r {
                Run::Line { .. } => 1,
                Run::Curve(s) => s.pieces.len(),
            })
            .sum()
    }
}

/// A pen stroke as a contour of runs joined at corners (see the module documentation).
pub fn fit_contour(points: &[Point], opts: &ContourOptions) -> Result<SketchContour> {
    if points.len() < 2 {
        return Err(Error::invalid("points", "a stroke needs at least 2 points"));
    }
    check_points(points)?;
    if !(opts.corner_angle > 0.0 && opts.corner_angle < std::f64::consts::PI) {
        return Err(Error::invalid("corner_angle", "must lie in (0, π) radians"));
    }
    // Estimated once for the stroke: the default tolerance, the corners' windows and the
    // straight stretches' test all read it (a closed stroke's overlapping tail, dropped
    // below, is a few points of hundreds).
    if let Some(r) = opts.resolution {
        Error::check_positive("resolution", r)?;
    }
    let noise = Noise::of(points).with_resolution(opts.resolution);
    // The default read from the raw points (it grows with their number).
    let default = default_tolerance_of(points, &noise);
    if let Some(c) = thinned_fit(points, opts, &noise, default) {
        return Ok(c);
    }
    contour_with_noise(points, opts, &noise, default)
}

/// [`fit_contour`] of a dense stroke on its points averaged over bins of half the (first)
/// tolerance ([`thinning`]), the noise and the default read from the raw points: its
/// corners' and trimmed count's indices the raw points', its deviation measured on the raw
/// points.
/// `None` where the stroke is not dense, the thinned fit fails, or it misses a raw point
/// by more than its tolerance: the raw points are fitted then.
fn thinned_fit(
    points: &[Point],
    opts: &ContourOptions,
    noise: &Noise,
    default: f64,
) -> Option<SketchContour> {
    let first = opts.tolerance.unwrap_or(default);
    let thin = thinning::thin(points, thinning::THIN_SHARE * first)?;
    let mut c = contour_with_noise(&thin.points, opts, noise, default).ok()?;
    let kept = thin.raw_kept(thin.points.len() - c.trimmed);
    let deviation = thinning::worst_distance(&points[..kept], &c.runs);
    if deviation > c.tolerance {
        return None;
    }
    for corner in &mut c.corners {
        corner.index = thin.raw_index(corner.index);
    }
    c.trimmed = points.len() - kept;
    c.max_deviation = deviation;
    Some(c)
}

/// [`fit_contour`] with the stroke's noise and default tolerance estimated.
fn contour_with_noise(
    points: &[Point],
    opts: &ContourOptions,
    noise: &Noise,
    default: f64,
) -> Result<SketchContour> {
    let size = bbox_diagonal(points);
    match opts.tolerance {
        Some(t) => {
            Error::check_positive("tolerance", t)?;
            contour_at(points, opts, Fit::at(t), noise)
        }
        None if points.len() >= 4 => {
            let ladder = super::escalation(noise);
            let last = default * ladder[ladder.len() - 1];
            // Every rung but the last with at most RUNG_PIECES pieces a run: a rung that
            // needs more follows the hand's wobble, slowly, and the next, looser one is
            // fairer.
            let fit = |t: f64| {
                let base = Fit::at(t);
                Fit {
                    max_pieces: if t < last {
                        RUNG_PIECES
                    } else {
                        base.max_pieces
                    },
                    ..base
                }
            };
            super::at_default(
                default,
                ladder,
                |t| contour_at(points, opts, fit(t), noise),
                |c| {
                    let curves = c.runs.iter().filter_map(|r| match r {
                        Run::Curve(s) => Some(s),
                        Run::Line { .. } => None,
                    });
                    c.runs
                        .iter()
                        .all(Run::is_g2)
                        .then(|| curves.map(|s| s.inflections + s.curvature_extrema).sum())
                },
            )
            .map(|(c, _)| c)
        }
        None => contour_at(points, opts, Fit::at(0.005 * size), noise),
    }
}

/// [`fit_contour`] at `tolerance`, the stroke's noise estimated.
fn contour_at(
    points: &[Point],
    opts: &ContourOptions,
    fit: Fit,
    noise: &Noise,
) -> Result<SketchContour> {
    let tolerance = fit.tolerance;
    // A hand's stroke (a device's step seen or given): its slow wobble bows a drawn side
    // by a pixel or two, which a designer does not mean.
    let fit = Fit {
        bow: if noise.quantum > 0.0 {
            HAND_BOW * tolerance
        } else {
            0.0
        },
        ..fit
    };
    let (closed, kept) = closes(points, tolerance, opts.closed);
    let stroke = &points[..kept];
    let found = corners_at(stroke, closed, tolerance, opts.corner_angle, noise.sigma);
    let mut corners = with_polygon_corners(stroke, closed, found, tolerance);
    let size = bbox_diagonal(stroke);
    // A run no G2 curve can follow within the tolerance gets a corner at its sharpest
    // point, and the contour is fitted again, until every run fits: a run that turns back
    // and forth ("these N points need more than M pieces"); a sparse run (clicks, each
    // point meant) whose zigzag its own noise estimate reads as noise (which named a
    // tolerance the user never typed); and once the stroke has turned out to zigzag, a
    // sparse run that no curve fits. Other runs that fail are left to a looser tolerance
    // (the default's ladder): a few noisy points of an arc are not corners.
    let mut zigzag = false;
    let (mut out, one_loop) = loop {
        let (k, err) = match assemble(stroke, closed, &corners, fit, noise.sigma) {
            Ok(done) => break done,
            Err(e) => e,
        };
        let sparse_run = || sparse(&runs_of(stroke, closed, &corners)[k]);
        let split = match &err {
            Error::Degenerate(_) => true,
            Error::InvalidInput { field, .. } if field == "tolerance" => sparse_run(),
            Error::NoConvergence(_) | Error::NoSegment(_) => zigzag && sparse_run(),
            _ => false,
        };
        match split
            .then(|| sharpest_inside(stroke, closed, &corners, k))
            .flatten()
        {
            Some(c) => {
                zigzag = true;
                corners.insert(corners.partition_point(|x| x.0 < c.0), c);
                // Runs of fewer than 4 points left by the cut are polygons.
                corners = with_polygon_corners(stroke, closed, corners, tolerance);
            }
            None => return Err(in_run(k, err)),
        }
    };
    if closed {
        let start = out.runs[0].ends().0;
        out.bridge(start, size);
    }
    let looped = one_loop && out.runs.len() == 1;
    let seam = looped.then(|| seam(&out.runs[0]));
    if one_loop && !looped {
        // The last part ends where the first starts, along it.
        out.smooth_after(out.runs.len() - 1);
    }
    // Each corner follows the last part of its run: a closed contour's runs start at its
    // first corner, so that one follows the last run.
    let mut corner_list = corners;
    if closed && !corner_list.is_empty() {
        corner_list.rotate_left(1);
    }
    let corners = corner_list
        .iter()
        .zip(&out.run_ends)
        .map(|(&(index, angle), &run)| Corner {
            index,
            point: out.runs[run].ends().1,
            angle,
            run,
        })
        .collect();
    Ok(SketchContour {
        runs: out.runs,
        corners,
        smooth_joins: out.smooth,
        closed,
        seam,
        tolerance,
        max_deviation: out.deviation,
        trimmed: points.len() - kept,
    })
}

/// The runs of `stroke` cut at `corners`, each fitted ([`fit_parts`]) and assembled, and
/// whether it is one closed loop; or the first run that fails, with its error.
fn assemble(
    stroke: &[Point],
    closed: bool,
    corners: &[(usize, f64)],
    fit: Fit,
    sigma: f64,
) -> std::result::Result<(Assembly, bool), (usize, Error)> {
    let tolerance = fit.tolerance;
    let runs = runs_of(stroke, closed, corners);
    // A closed contour without corners is one run whose seam is faired G2, unless it has
    // straight stretches: then it starts with the first and every join is smooth.
    let one_loop = closed && corners.is_empty();
    let lines = line_ends(&runs, closed && !one_loop, tolerance);
    let size = bbox_diagonal(stroke);
    let mut out = Assembly::default();
    for (k, (r, line)) in runs.iter().zip(&lines).enumerate() {
        let parts = fit_parts(r, *line, fit, one_loop, sigma).map_err(|e| (k, e))?;
        out.push_run(parts, size);
    }
    Ok((out, one_loop))
}

/// An error of run `k`, saying so.
fn in_run(k: usize, e: Error) -> Error {
    match e {
        Error::NoSegment(m) => Error::NoSegment(format!("run {k}: {m}")),
        Error::NoConvergence(m) => Error::NoConvergence(format!("run {k}: {m}")),
        Error::Degenerate(m) => Error::Degenerate(format!("run {k}: {m}")),
        Error::InvalidInput { field, message } if field == "tolerance" => {
            Error::invalid(field, format!("run {k}: {message}"))
        }
        other => other,
    }
}

/// The point inside run `k` (cut at `corners`) where its chords turn most, with that turn:
/// the corner a run that no curve follows gets; `None` for a run without inner points.
fn sharpest_inside(
    stroke: &[Point],
    closed: bool,
    corners: &[(usize, f64)],
    k: usize,
) -> Option<(usize, f64)> {
    let n = stroke.len();
    let (a, b) = *run_bounds(n, closed, corners).get(k)?;
    let turn = |j: usize| {
        let (u, v) = (
            stroke[j % n] - stroke[(j - 1) % n],
            stroke[(j + 1) % n] - stroke[j % n],
        );
        u.cross(v).atan2(u.dot(v)).abs()
    };
    (a + 1..b)
        .map(|j| (j % n, turn(j)))
        .max_by(|x, y| x.1.total_cmp(&y.1))
}

/// The contour's runs as they are fitted: the parts of each run, the smooth joins between
/// parts, the index of each run's last part, the largest deviation.
#[derive(Default)]
struct Assembly {
    runs: Vec<Run>,
    smooth: Vec<SmoothJoin>,
    run_ends: Vec<usize>,
    deviation: f64,
}

impl Assembly {
    /// The parts of one run (with their deviations), smooth joins between them.
    fn push_run(&mut self, parts: Vec<(Run, f64)>, size: f64) {
        if let Some((run, _)) = parts.first() {
            self.bridge(run.ends().0, size);
        }
        let first = self.runs.len();
        for (i, (run, dev)) in parts.into_iter().enumerate() {
            self.deviation = self.deviation.max(dev);
            self.runs.push(run);
            if i > 0 {
                self.smooth_after(first + i - 1);
            }
        }
        self.run_ends.push(self.runs.len() - 1);
    }

    /// A straight bridge where the previous part ends short of where the next starts
    /// (by more than [`COINCIDENT`] of the stroke's `size`), as the previous run's last part: a
    /// curve's end piece whose end tangents form no triangle at the corner's point ends on
    /// the fair spline instead, within the tolerance of that point (a wave's crest read as
    /// a corner at ±3 px of jitter left 2.96 px between its runs, and no drawing or export
    /// could join them).
    fn bridge(&mut self, to: Point, size: f64) {
        let Some(last) = self.runs.last() else {
            return;
        };
        let from = last.ends().1;
        if (to - from).hypot() > COINCIDENT * size {
            self.runs.push(Run::Line {
                start: from,
                end: to,
            });
            if let Some(e) = self.run_ends.last_mut() {
                *e += 1;
            }
        }
    }

    /// A smooth join after run `k` (the next run, or the first after the last).
    fn smooth_after(&mut self, k: usize) {
        let next = (k + 1) % self.runs.len();
        let (a, b) = (&self.runs[k], &self.runs[next]);
        let (ta, tb) = (a.tangents().1, b.tangents().0);
        let (ka, kb) = (a.end_curvatures().1, b.end_curvatures().0);
        let scale = [a, b]
            .iter()
            .map(|r| r.largest_curvature())
            .fold(0.0, f64::max);
        self.smooth.push(SmoothJoin {
            run: k,
            point: a.ends().1,
            angle: ta.cross(tb).atan2(ta.dot(tb)).abs(),
            curvature_jump: if scale > 0.0 {
                (ka - kb).abs() / scale
            } else {
                0.0
            },
        });
    }
}

/// One run fitted as its parts: split at its straight stretches ([`super::straight`]) into
/// lines and curves that join them G2, when it has any and every curve between them fits;
/// else as one ([`fit_run`]). Each part with its largest distance from its points. Where
/// a line stops before its curve is tried at [`SETBACKS`] radii of that curve in turn: the
/// first whose curves are fair (G2, monotone, one curvature extremum at most each) is kept,
/// else the fairest that fits.
fn fit_parts(
    run: &[Point],
    line: Option<(Point, Point)>,
    fit: Fit,
    one_loop: bool,
    sigma: f64,
) -> Result<Vec<(Run, f64)>> {
    let tolerance = fit.tolerance;
    let whole = || -> Result<Vec<(Run, f64)>> {
        let fitted = fit_run(run, line, fit, one_loop)?;
        let dev = deviation(run, &fitted);
        Ok(vec![(fitted, dev)])
    };
    if line.is_some() || run.len() < straight::MIN_POINTS {
        return whole();
    }
    // A loop starts at its sharpest point (inside a curve, so no straight stretch is cut
    // where it starts).
    let from_sharpest;
    let points = if one_loop {
        let Some(sharpest) = straight::sharpest(run, tolerance) else {
            return whole();
        };
        from_sharpest = turn_loop(run, sharpest);
        &from_sharpest[..]
    } else {
        run
    };
    let Some(test) = straight::Test::of(points, tolerance, sigma, one_loop) else {
        return whole();
    };
    let test = test.allowing_bow(fit.bow);
    let mut best: Option<(usize, Vec<(Run, f64)>)> = None;
    for setback in SETBACKS {
        let Some(parts) = split_run(&test, setback) else {
            return whole();
        };
        let Ok(fitted) = parts
            .into_iter()
            .map(|part| fit_part(part, fit))
            .collect::<Result<Vec<(Run, f64)>>>()
        else {
            continue;
        };
        let unfair = unfairness(&fitted);
        if unfair == 0 {
            return Ok(fitted);
        }
        if best.as_ref().is_none_or(|b| unfair < b.0) {
            best = Some((unfair, fitted));
        }
    }
    // No setback gives curves that fit between the lines: the run as one, as before.
    best.map_or_else(whole, |b| Ok(b.1))
}

/// Where a line ends before its curve, in radii of that curve: tried in this order. The
/// widest first: on 24 hand-drawn rounded rectangles a curve between lines ending 0.3
/// radii before it fits G2 in one try where 0.15 or 0 fail (a line that ends where a hand's
/// corner already turns leaves its inflection-end piece no triangle); each failed try costs
/// a fit of up to 8 pieces.
const SETBACKS: [f64; 3] = [0.3, 0.5, 0.15];

/// The parts of a run (a loop: starting at its first straight stretch) with lines ending
/// `setback` radii before their curves; `None` where it has no straight stretch.
fn split_run(test: &straight::Test, setback: f64) -> Option<Vec<straight::Part>> {
    let (points, one_loop) = (test.points, test.closed_loop);
    let found = test.stretches(setback);
    let a0 = found.first()?.a;
    if !one_loop {
        return Some(straight::parts(points, &found, false));
    }
    let turned = turn_loop(points, a0);
    let shifted: Vec<straight::Stretch> = found
        .into_iter()
        .map(|s| straight::Stretch {
            a: s.a - a0,
            b: s.b - a0,
            ..s
        })
        .collect();
    Some(straight::parts(&turned, &shifted, true))
}

/// How far fitted parts are from fair: per curve, its curvature extrema beyond one, and ten
/// for one that is not G2 or not proven monotone.
fn unfairness(parts: &[(Run, f64)]) -> usize {
    parts
        .iter()
        .map(|(run, _)| match run {
            Run::Line { .. } => 0,
            Run::Curve(s) => {
                let broken = !(s.g2 && s.all_monotone);
                s.curvature_extrema.saturating_sub(1) + 10 * usize::from(broken)
            }
        })
        .sum()
}

/// A closed loop (its last point its first) started at its point `k` instead.
fn turn_loop(run: &[Point], k: usize) -> Vec<Point> {
    let n = run.len() - 1;
    let mut out = run[k..n].to_vec();
    out.extend_from_slice(&run[..=k]);
    out
}

/// A part fitted: a line as it is, a curve by the sketch with its line ends.
fn fit_part(part: straight::Part, fit: Fit) -> Result<(Run, f64)> {
    let tolerance = fit.tolerance;
    match part {
        straight::Part::Line { start, end, points } => {
            let line = Run::Line { start, end };
            let dev = deviation(&points, &line);
            // Its ends set back along the curves next to it, a line may leave its points
            // (random clicks read as a closed loop: 465 from them at a tolerance of 437).
            if dev > tolerance {
                return Err(Error::NoConvergence(format!(
                    "a straight stretch's line lies {dev:.3e} from its points, beyond the \
                     tolerance {tolerance:.3e}"
                )));
            }
            Ok((line, dev))
        }
        straight::Part::Curve { points, line_ends } => {
            if points.len() < 4 {
                return Err(Error::Degenerate(
                    "a curve between lines needs points".into(),
                ));
            }
            let opts = SketchOptions {
                line_ends,
                max_pieces: fit.max_pieces.min(PART_PIECES),
                ..SketchOptions::with_tolerance(tolerance)
            };
            let s = fit_sketch(&points, &opts)?;
            let dev = s.max_deviation;
            Ok((Run::Curve(Box::new(s)), dev))
        }
    }
}

/// Whether the stroke is closed (`given`, else: it ends within 3 tolerances or 5 % of its
/// size of its start, and is at least twice as long as its size), and how many of its
/// points to keep: a closed stroke's overshoot past its start (the points after the one
/// nearest the start in its last tenth) is trimmed, and a last point on the first (to
/// rounding) dropped.
pub fn closes(points: &[Point], tolerance: f64, given: Option<bool>) -> (bool, usize) {
    let n = points.len();
    let size = bbox_diagonal(points);
    let length: f64 = points.windows(2).map(|w| (w[1] - w[0]).hypot()).sum();
    let near = (3.0 * tolerance).max(0.05 * size);
    let start = points[0];
    // The point of the last tenth nearest the start: where the pen came back.
    let tail = (n - n / 10).min(n - 1).max(1);
    let back = (tail..n)
        .min_by(|&a, &b| {
            (points[a] - start)
                .hypot()
                .total_cmp(&(points[b] - start).hypot())
        })
        .unwrap_or(n - 1);
    let auto = n >= 4 && (points[back] - start).hypot() <= near && length >= 2.0 * size;
    let closed = given.unwrap_or(auto);
    if !closed || n < 4 {
        return (closed, n);
    }
    let mut keep = if auto { back + 1 } else { n };
    // A last point on the first, to rounding (points computed around a circle end at
    // (100, -2.4e-14)), is the first: kept, it would be a step of nothing at the seam.
    while keep > 3 && (points[keep - 1] - start).hypot() <= COINCIDENT * size {
        keep -= 1;
    }
    (true, keep)
}

/// The corners of a stroke: (index, turn) in stroke order (see the module documentation).
pub fn corners(
    points: &[Point],
    closed: bool,
    tolerance: f64,
    min_angle: f64,
) -> Vec<(usize, f64)> {
    corners_at(points, closed, tolerance, min_angle, noise_level(points))
}

/// [`corners`] of a stroke whose noise is `sigma`.
fn corners_at(
    points: &[Point],
    closed: bool,
    tolerance: f64,
    min_angle: f64,
    sigma: f64,
) -> Vec<(usize, f64)> {
    let n = points.len();
    if n < 3 {
        return Vec::new();
    }
    let arc = ArcLength::of(points, closed);
    let w = (WINDOW_TOLERANCES * tolerance)
        .max(WINDOW_NOISE * sigma)
        .min(arc.total / 6.0);
    // A step is sparse beyond the window and a share of the stroke's size: a dense
    // measured line whose samples step back and forth (the Prius lines, 3 mm back in 900
    // at a 0.3 mm tolerance) turns by 180° between steps longer than its window.
    let sparse_step = w.max(SPARSE_STEP * bbox_diagonal(points));
    let mut found: Vec<(usize, f64)> = (0..n)
        .filter_map(|i| {
            // Whole windows: a turn nearer an open stroke's end than w is its end's own
            // business (a pen's flick), not a corner between two runs.
            let corner = if arc.sparse_at(i, sparse_step) {
                let near = arc.turn(points, i, (w, 2), 0.9)?;
                (near >= min_angle.max(SPARSE_CORNER)).then_some(near)
            } else {
                let near = arc.turn(points, i, (w, 3), 0.9)?;
                (near >= min_angle && arc.concentrated(points, i, w, near)).then_some(near)
            };
            corner.map(|near| (i, near))
        })
        .collect();
    found.sort_by(|a, b| b.1.total_cmp(&a.1));
    let mut kept: Vec<(usize, f64)> = Vec::new();
    for (i, a) in found {
        if kept.iter().all(|&(k, _)| arc.between(i, k) > w) {
            kept.push((i, a));
        }
    }
    let mut out: Vec<(usize, f64)> = kept
        .into_iter()
        .map(|(i, a)| (arc.apex(points, i, w), a))
        .collect();
    out.sort_by_key(|c| c.0);
    out.dedup_by_key(|c| c.0);
    out
}

/// Arc length along a stroke (closed: around, the closing step included).
struct ArcLength {
    s: Vec<f64>,
    total: f64,
    closed: bool,
}

impl ArcLength {
    fn of(points: &[Point], closed: bool) -> ArcLength {
        let s = arc_lengths(points);
        let last = *s.last().unwrap_or(&0.0);
        let total = if closed {
            last + (points[0] - points[points.len() - 1]).hypot()
        } else {
            last
        };
        ArcLength { s, total, closed }
    }

    /// Arc length between points `i` and `k` (closed: the shorter way around).
    fn between(&self, i: usize, k: usize) -> f64 {
        let d = (self.s[i] - self.s[k]).abs();
        if self.closed {
            d.min(self.total - d)
        } else {
            d
        }
    }

    /// The points within arc length `w` before (`dir` -1) or after (+1) point `i`, `i`
    /// included, in stroke order (at least `least`, 2 or 3), and their arc length; None
    /// where the stroke ends (or comes round) before `fill` of `w`.
    fn window(
        &self,
        i: usize,
        w: f64,
        (dir, least): (i64, usize),
        fill: f64,
    ) -> Option<(Vec<usize>, f64)> {
        let n = self.s.len() as i64;
        let mut out = vec![i];
        let mut k = i as i64;
        let mut run = 0.0;
        let mut ended = false;
        loop {
            let next = k + dir;
            let j = if self.closed {
                next.rem_euclid(n)
            } else if next < 0 || next >= n {
                ended = true;
                break;
            } else {
                next
            };
            if j as usize == i {
                ended = true;
                break;
            }
            // At least `least` points however sparse the stroke.
            let step = self.between(k as usize, j as usize);
            if run + step > w && out.len() >= least {
                break;
            }
            run += step;
            out.push(j as usize);
            k = j;
        }
        if (ended && run < fill * w) || out.len() < least {
            return None;
        }
        if dir < 0 {
            out.reverse();
        }
        Some((out, run))
    }

    /// Whether the steps on both sides of point `i` are longer than `w` (a sparse stroke
    /// where `w` is at least the corner window: its windows there are the chords alone).
    fn sparse_at(&self, i: usize, w: f64) -> bool {
        let step = |j: Option<usize>| j.is_none_or(|j| self.between(i, j) > w);
        let (prev, next) = neighbours(i, self.s.len(), self.closed);
        step(prev) && step(next)
    }

    /// Whether the turn `near` over windows `w` at point `i` happens in a short stretch:
    /// over windows a third as long it is nearly as large (on an arc a third), and over
    /// windows twice as long hardly larger (on an arc twice); a window that does not fit
    /// (the stroke's end, too few points) leaves the decision to the others. Each window
    /// holds at least three points (two steps).
    fn concentrated(&self, points: &[Point], i: usize, w: f64, near: f64) -> bool {
        let short = self
            .turn(points, i, (w / 3.0, 3), 0.9)
            .is_none_or(|t| t >= SHORT_SHARE * near);
        let long = self
            .turn(points, i, (2.0 * w, 3), 0.5)
            .is_none_or(|t| t < CONCENTRATION * near);
        short && long
    }

    /// Where exactly the corner found at `i` is: the stretch of the stroke within `1.5 w`
    /// of it split into the two straightest pieces (least sum of the squared distances
    /// from their least-squares lines, each piece at least three points).
    fn apex(&self, points: &[Point], i: usize, w: f64) -> usize {
        let (Some((before, _)), Some((after, _))) = (
            self.window(i, 1.5 * w, (-1, 3), 0.0),
            self.window(i, 1.5 * w, (1, 3), 0.0),
        ) else {
            return i;
        };
        let stretch: Vec<usize> = before.iter().chain(&after[1..]).copied().collect();
        let m = stretch.len();
        (2..m - 2)
            .map(|k| {
                let cost =
                    line_residual(points, &stretch[..=k]) + line_residual(points, &stretch[k..]);
                (cost, stretch[k])
            })
            .min_by(|x, y| x.0.total_cmp(&y.0))
            .map_or(i, |x| x.1)
    }

    /// The turn at point `i` between the least-squares directions of the stretches of
    /// length `w` before and after it (each at least `fill` of `w` long: near an open
    /// stroke's ends they are cut short, and at least `least` points: 2 where one step of
    /// a sparse stroke is longer than `w`, its chord then the stretch); None where one does
    /// not fit.
    fn turn(&self, points: &[Point], i: usize, (w, least): (f64, usize), fill: f64) -> Option<f64> {
        let (a, b) = (
            self.window(i, w, (-1, least), fill)?,
            self.window(i, w, (1, least), fill)?,
        );
        // A stretch that goes back and forth (samples out of order, a scribble) has no
        // direction to turn from.
        let goes = |(idx, along): &(Vec<usize>, f64)| {
            let (first, last) = (idx[0], idx[idx.len() - 1]);
            (points[last] - points[first]).hypot() >= 0.5 * along
        };
        if !goes(&a) || !goes(&b) {
            return None;
        }
        let before = direction(points, &a.0)?;
        let after = direction(points, &b.0)?;
        Some(before.cross(after).atan2(before.dot(after)).abs())
    }
}

/// The points `idx` of `points`, one by one.
fn picked<'a>(points: &'a [Point], idx: &'a [usize]) -> impl Iterator<Item = Point> + Clone + 'a {
    idx.iter().map(|&i| points[i])
}

/// The sum of the squared distances of the points `idx` from their least-squares line (the
/// scatter's smaller eigenvalue).
fn line_residual(points: &[Point], idx: &[usize]) -> f64 {
    let (_, sxx, sxy, syy) = straight::scatter(picked(points, idx));
    let half = 0.5 * (sxx + syy);
    let root = (0.25 * (sxx - syy) * (sxx - syy) + sxy * sxy).sqrt();
    (half - root).max(0.0)
}

/// The least-squares direction of the points `idx` (the principal axis of their scatter),
/// pointing from the first towards the last.
fn direction(points: &[Point], idx: &[usize]) -> Option<Vec2> {
    straight::line_through(picked(points, idx)).map(|(_, d)| d)
}

/// `corners` and the points inside every run of fewer than 4 points (too few for a curve:
/// a sparse stroke) that is not straight within the tolerance, each with its turn: such a
/// run is a polygon, its every point a corner. A closed stroke without corners is one run.
fn with_polygon_corners(
    points: &[Point],
    closed: bool,
    mut corners: Vec<(usize, f64)>,
    tolerance: f64,
) -> Vec<(usize, f64)> {
    let n = points.len();
    let bounds = run_bounds(n, closed, &corners);
    let turn = |i: usize| -> Option<f64> {
        let (prev, next) = (points[(i + n - 1) % n], points[(i + 1) % n]);
        let (a, b) = (points[i] - prev, next - points[i]);
        (a.hypot() > 0.0 && b.hypot() > 0.0).then(|| a.cross(b).atan2(a.dot(b)).abs())
    };
    for &(a, b) in &bounds {
        let run: Vec<Point> = (a..=b).map(|j| points[j % n]).collect();
        if run.len() >= 4 || chord_deviation(&run) <= tolerance {
            continue;
        }
        let inside = (a + 1..b).map(|j| j % n);
        corners.extend(inside.filter_map(|j| Some((j, turn(j)?))));
    }
    if closed && bounds == [(0, n)] && n < 4 {
        // A closed stroke of three points: a triangle.
        corners = (0..n).filter_map(|j| Some((j, turn(j)?))).collect();
    }
    corners.sort_by_key(|c| c.0);
    corners.dedup_by_key(|c| c.0);
    corners
}

/// The indices before and after `k` of `n` in order (closed: around; open: none past
/// an end).
fn neighbours(k: usize, n: usize, closed: bool) -> (Option<usize>, Option<usize>) {
    if closed {
        (Some((k + n - 1) % n), Some((k + 1) % n))
    } else {
        (k.checked_sub(1), (k + 1 < n).then_some(k + 1))
    }
}

/// The runs' points: from corner to corner, both included (closed with corners: from the
/// first corner around to it; closed without: from the first point around to it).
fn runs_of(points: &[Point], closed: bool, corners: &[(usize, f64)]) -> Vec<Vec<Point>> {
    let n = points.len();
    run_bounds(n, closed, corners)
        .into_iter()
        .map(|(a, b)| (a..=b).map(|j| points[j % n]).collect())
        .collect()
}

/// Each run's first and last point index, both included, for `n` points cut at the
/// `corners` (in order): a closed stroke's last run counts on past `n` (index `j` is point
/// `j % n`), one without corners is `(0, n)`, its first point again at its end.
fn run_bounds(n: usize, closed: bool, corners: &[(usize, f64)]) -> Vec<(usize, usize)> {
    let mut cuts: Vec<usize> = corners.iter().map(|c| c.0).collect();
    if !closed {
        cuts.retain(|&c| c > 0 && c < n - 1);
        cuts.insert(0, 0);
        cuts.push(n - 1);
    } else if cuts.is_empty() {
        cuts = vec![0, n];
    } else {
        cuts.push(cuts[0] + n);
    }
    cuts.windows(2).map(|w| (w[0], w[1])).collect()
}

/// Where each straight run's line starts and ends (None for a run that is not straight:
/// its points farther than the tolerance from their least-squares line). A corner between
/// two straight runs is where their lines meet (a designer's corner, not the noisy sample
/// nearest it), if that is within 3 tolerances of the sample; an open stroke's end is the
/// sample's foot on the line; a corner next to a curved run is the sample itself, where
/// that run starts or ends.
fn line_ends(runs: &[Vec<Point>], closed: bool, tolerance: f64) -> Vec<Option<(Point, Point)>> {
    let fits: Vec<Option<(Point, Vec2)>> = runs
        .iter()
        .map(|r| {
            let (c, d) = straight::line_of(r)?;
            let off = r
                .iter()
                .map(|q| (*q - c).cross(d).abs())
                .fold(0.0, f64::max);
            (r.len() >= 2 && off <= tolerance).then_some((c, d))
        })
        .collect();
    let n = runs.len();
    let foot = |(c, d): (Point, Vec2), q: Point| c + d * (q - c).dot(d);
    // The place of the corner after run k (between it and the next), seen from run k.
    let meet = |k: usize, line: (Point, Vec2), sample: Point| -> Point {
        match neighbours(k, n, closed).1.map(|j| fits[j]) {
            Some(Some(other)) => intersection(line, other)
                .filter(|x| (*x - sample).hypot() <= 3.0 * tolerance)
                .unwrap_or(sample),
            Some(None) => sample,
            None => foot(line, sample),
        }
    };
    let ends: Vec<Option<(Point, Point)>> = (0..n)
        .map(|k| {
            let line = fits[k]?;
            let r = &runs[k];
            let start = match neighbours(k, n, closed).0.map(|j| (j, fits[j])) {
                Some((j, Some(other))) => meet(j, other, r[0]),
                Some((_, None)) => r[0],
                None => foot(line, r[0]),
            };
            Some((start, meet(k, line, r[r.len() - 1])))
        })
        .collect();
    held_together(runs, closed, tolerance, ends)
}

/// The line ends with every run's ends moved back to its samples where its line between
/// the moved ends is farther than the tolerance from its points (a coarse stroke: lines
/// that meet far from its samples) or has no length, and its neighbours' ends there with them, until every
/// line holds: the runs then still meet (that run is fitted from its samples).
fn held_together(
    runs: &[Vec<Point>],
    closed: bool,
    tolerance: f64,
    mut ends: Vec<Option<(Point, Point)>>,
) -> Vec<Option<(Point, Point)>> {
    let n = runs.len();
    // A line of no length does not hold either (a closed contour of two lines: both
    // corners where the same two lines meet).
    let holds = |r: &[Point], (a, b): (Point, Point)| {
        let chord = (r[r.len() - 1] - r[0]).hypot().max(tolerance);
        (b - a).hypot() > COINCIDENT * chord
            && r.iter().all(|&q| segment_distance(q, a, b) <= tolerance)
    };
    loop {
        let Some(k) = (0..n).find(|&k| {
            let r = &runs[k];
            ends[k].is_some_and(|e| !holds(r, e) && e != (r[0], r[r.len() - 1]))
        }) else {
            return ends;
        };
        let r = &runs[k];
        ends[k] = Some((r[0], r[r.len() - 1]));
        let (prev, next) = neighbours(k, n, closed);
        if let Some(e) = prev.and_then(|j| ends[j].as_mut()) {
            e.1 = r[0];
        }
        if let Some(e) = next.and_then(|j| ends[j].as_mut()) {
            e.0 = r[r.len() - 1];
        }
    }
}

/// Where the lines through `a.0` along `a.1` and through `b.0` along `b.1` meet; None for
/// (nearly) parallel ones.
fn intersection(a: (Point, Vec2), b: (Point, Vec2)) -> Option<Point> {
    let den = a.1.cross(b.1);
    if den.abs() < 1e-9 {
        return None;
    }
    Some(a.0 + a.1 * ((b.0 - a.0).cross(b.1) / den))
}

/// One run fitted: a line where every point lies within the tolerance of its line's ends
/// ([`line_ends`]) or of its chord, else the G2 sketch (`closed`: a loop, G2 across its
/// seam).
fn fit_run(points: &[Point], line: Option<(Point, Point)>, fit: Fit, closed: bool) -> Result<Run> {
    let tolerance = fit.tolerance;
    // A line has a length: a closed stroke's one corner starts and ends its one run (a
    // teardrop), which no line is, however loose the tolerance.
    let size = bbox_diagonal(points);
    let long = |a: Point, b: Point| (b - a).hypot() > COINCIDENT * size;
    if let Some((start, end)) = line.filter(|(a, b)| !closed && long(*a, *b)) {
        let l = Run::Line { start, end };
        if deviation(points, &l) <= tolerance {
            return Ok(l);
        }
    }
    let (start, end) = (points[0], points[points.len() - 1]);
    let line = Run::Line { start, end };
    if !closed && long(start, end) && (points.len() < 4 || chord_deviation(points) <= tolerance) {
        return Ok(line);
    }
    let opts = SketchOptions {
        closed,
        max_pieces: fit.max_pieces,
        ..SketchOptions::with_tolerance(tolerance)
    };
    match fit_sketch(points, &opts) {
        Ok(s) => Ok(Run::Curve(Box::new(s))),
        Err(Error::Degenerate(m)) => Err(Error::Degenerate(format!(
            "a run of {} points that is not straight within the tolerance: {m}",
            points.len()
        ))),
        Err(e) => Err(e),
    }
}

/// The largest distance of the points from the segment between the first and the last.
fn chord_deviation(points: &[Point]) -> f64 {
    let (a, b) = (points[0], points[points.len() - 1]);
    points
        .iter()
        .map(|&q| segment_distance(q, a, b))
        .fold(0.0, f64::max)
}

/// A run's largest distance from its points.
fn deviation(points: &[Point], run: &Run) -> f64 {
    match run {
        Run::Line { start, end } => points
            .iter()
            .map(|&q| segment_distance(q, *start, *end))
            .fold(0.0, f64::max),
        Run::Curve(s) => s.max_deviation,
    }
}

/// The seam of a closed run: its end against its start.
fn seam(run: &Run) -> Seam {
    let (t0, t1) = run.tangents();
    let (k0, k1) = run.end_curvatures();
    let scale = k0.abs().max(k1.abs());
    Seam {
        angle: t1.cross(t0).atan2(t1.dot(t0)).abs(),
        curvature_jump: if scale > 0.0 {
            (k0 - k1).abs() / scale
        } else {
            0.0
        },
    }
}

fn unit(v: Vec2) -> Vec2 {
    let l = v.hypot();
    if l > 0.0 {
        v / l
    } else {
        v
    }
}
