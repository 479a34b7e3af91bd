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
//!    moves to the nearest admissible value; α on its bound ([`ALPHA_RANGE`]) is reported;
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

pub mod contour;

use crate::approx::{
    fit_inflection_cubic_from, fit_rational_cubic, ApproxOptions, RationalCubicFit,
};
use crate::bernstein::sign_change_roots;
use crate::bezier::{Bezier, PlanarCurve, RationalBezier};
use crate::bspline::{self, BSpline, FitOptions};
use crate::error::{Error, Result};
use crate::lac::{LacInflectionSegment, LacSegment, ALPHA_RANGE};
use crate::lcg::{fit_line, lcg_point};
use kurbo::{Point, Vec2};
use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

/// Options of [`fit_sketch`].
#[derive(Clone, Debug)]
pub struct SketchOptions {
    /// Largest allowed distance from an input point to the result (input units, > 0).
    pub tolerance: f64,
    /// Most pieces before giving up on the tolerance.
    pub max_pieces: usize,
    /// Pieces turning more than this (radians) are split.
    pub max_turn: f64,
    /// Inflection pairs with less turning between them are noise (radians).
    pub min_turn: f64,
    /// Fairing target: largest curvature jump over the largest curvature.
    pub g2_tolerance: f64,
    /// Iteration limit of the fairing.
    pub max_fairing_iterations: usize,
    /// Options of the rational cubic per piece.
    pub approx: ApproxOptions,
    /// The points form a closed loop (the last is the first): the curve ends where it
    /// starts with the same tangent, and the seam is faired G2 like every joint.
    pub closed: bool,
}

impl SketchOptions {
    /// Defaults with the given tolerance.
    pub fn with_tolerance(tolerance: f64) -> Self {
        SketchOptions {
            tolerance,
            max_pieces: 64,
            max_turn: std::f64::consts::FRAC_PI_2,
            min_turn: 0.25f64.to_radians(),
            g2_tolerance: 1e-10,
            max_fairing_iterations: 60,
            approx: ApproxOptions::default(),
            closed: false,
        }
    }
}

/// Kind of a piece.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PieceKind {
    /// A LAC segment in its control triangle (docs/math.md §3.1).
    Lac,
    /// A segment with an inflection (zero curvature) at one end (docs/math.md §3.2).
    LacInflection,
}

impl PieceKind {
    /// `"lac"` or `"lac_inflection"` (the protocol's names).
    pub fn as_str(&self) -> &'static str {
        match self {
            PieceKind::Lac => "lac",
            PieceKind::LacInflection => "lac_inflection",
        }
    }
}

/// The curve of a piece.
#[derive(Clone, Debug)]
pub enum PieceCurve {
    /// A LAC segment; its `control[0]` is the piece's start.
    Lac(LacSegment),
    /// An inflection-end segment; its `control[0]` (the inflection) is the piece's start when
    /// `inflection_at_start`, else its end.
    Inflection {
        /// The segment.
        segment: LacInflectionSegment,
        /// Whether the inflection is at the piece's start.
        inflection_at_start: bool,
    },
}

/// One piece of the result, in curve order.
#[derive(Clone, Debug)]
pub struct SketchPiece {
    /// Which family.
    pub kind: PieceKind,
    /// Shape parameter of the segment.
    pub alpha: f64,
    /// α estimated from the piece's curvature graph (before any adaptation); `None` for
    /// inflection pieces and pieces of (nearly) constant curvature.
    pub alpha_estimate: Option<f64>,
    /// Control triangle in curve order: start, tangent intersection, end.
    pub control: [Point; 3],
    /// The segment itself.
    pub curve: PieceCurve,
    /// Signed curvature at the start and at the end.
    pub end_curvatures: (f64, f64),
    /// The rational cubic, in curve order.
    pub rational: RationalBezier,
    /// Largest distance of the rational cubic from the segment over its arc length.
    pub rational_error: f64,
    /// Curvature monotonicity of the rational cubic, proven by the exact test.
    pub monotone: bool,
    /// α sits on a bound of its least-squares fit ([`ALPHA_RANGE`]): the data do not pin
    /// it down (a shallow piece) or want a steeper curvature graph than allowed; for an
    /// inflection piece, whose α its control triangle fixes, α on or beyond the range (a
    /// known limit: such a piece is still returned).
    pub alpha_at_bound: bool,
    /// Parameter range on the intermediate B-spline.
    pub u_range: (f64, f64),
}

/// What the G2 fairing did.
#[derive(Clone, Debug, PartialEq)]
pub struct FairingReport {
    /// Newton iterations.
    pub iterations: usize,
    /// Largest relative curvature jump before.
    pub initial_jump: f64,
    /// Largest relative curvature jump after.
    pub final_jump: f64,
    /// Reached [`SketchOptions::g2_tolerance`].
    pub converged: bool,
}

/// The result of [`fit_sketch`].
#[derive(Clone, Debug)]
pub struct Sketch {
    /// The intermediate least-squares B-spline.
    pub bspline: BSpline,
    /// Its largest distance from the input points.
    pub bspline_deviation: f64,
    /// The pieces in order.
    pub pieces: Vec<SketchPiece>,
    /// Largest distance from an input point to the rational result.
    pub max_deviation: f64,
    /// Root mean square of those distances.
    pub rms_deviation: f64,
    /// Largest |κ_left - κ_right| at a joint of the rational cubics over their largest |κ|.
    pub max_curvature_jump: f64,
    /// `max_curvature_jump` below 1e-6.
    pub g2: bool,
    /// The fairing's report (of the last round).
    pub fairing: FairingReport,
    /// Every rational piece proven curvature-monotone.
    pub all_monotone: bool,
    /// Inflections of the result (sign changes of its curvature).
    pub inflections: usize,
    /// Interior curvature extrema of the result (the pieces are monotone, so these sit at
    /// joints where the curvature turns back).
    pub curvature_extrema: usize,
}

/// Inflections and interior curvature extrema of a curve made of curvature-monotone pieces
/// with signed end curvatures `ends` (curve order): the curvature between two ends is
/// monotone, so the sign changes and turns of the sequence of end values are all of them.
pub fn count_events(ends: &[(f64, f64)]) -> (usize, usize) {
    let mut ks: Vec<f64> = Vec::with_capacity(ends.len() + 1);
    for (i, e) in ends.iter().enumerate() {
        if i == 0 {
            ks.push(e.0);
        }
        ks.push(e.1);
    }
    let scale = ks.iter().fold(0.0f64, |m, k| m.max(k.abs()));
    let tiny = 1e-9 * scale;
    let signs: Vec<f64> = ks
        .iter()
        .filter(|k| k.abs() > tiny)
        .map(|k| k.signum())
        .collect();
    let inflections = signs.windows(2).filter(|w| w[0] != w[1]).count();
    let steps: Vec<f64> = ks
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|d| d.abs() > tiny)
        .map(|d| d.signum())
        .collect();
    let extrema = steps.windows(2).filter(|w| w[0] != w[1]).count();
    (inflections, extrema)
}

/// Share of the tolerance the fair spline of noisy input may use (the smoothest spline
/// within it shapes the pieces); the rest is left to the LAC pieces and their cubics.
const FAIR_SHARE: f64 = 0.75;

/// Share of the tolerance within which two neighbouring pieces merge into one LAC segment.
const MERGE_SHARE: f64 = 0.95;

/// The default tolerance of a sketch (the protocol's `sketch.fit` default): 0.5 % of the
/// diagonal of the points' bounding box, but never below 6 times the noise estimated from
/// the points themselves (per coordinate, from local cubic fits), so that a fair curve can
/// meet it: a hand's jitter of a few pixels is not a shape to follow.
pub fn default_tolerance(points: &[Point]) -> f64 {
    (0.005 * bbox_diagonal(points)).max(6.0 * noise_level(points))
}

impl Sketch {
    /// The joints in order: the start of every piece and the end of the last.
    pub fn joints(&self) -> Vec<Point> {
        self.pieces
            .iter()
            .map(|p| p.control[0])
            .chain(self.pieces.last().map(|p| p.control[2]))
            .collect()
    }

    /// A point of the rational result at `t` in [0, pieces] (piece index + local parameter).
    pub fn eval(&self, t: f64) -> Point {
        let n = self.pieces.len();
        let t = t.clamp(0.0, n as f64);
        let i = (t.floor() as usize).min(n - 1);
        self.pieces[i].rational.eval(t - i as f64)
    }
}

/// The B-spline as Bézier spans over its knot intervals, for derivatives at any u.
struct Track {
    spans: Vec<Bezier>,
    breaks: Vec<f64>,
}

impl Track {
    fn new(s: &BSpline) -> Result<Track> {
        let spans = s.to_beziers()?;
        let n = spans.len();
        let p = s.degree;
        let breaks = (0..=n).map(|i| s.knots[p + i]).collect();
        Ok(Track { spans, breaks })
    }

    fn locate(&self, u: f64) -> (usize, f64) {
        let n = self.spans.len();
        let mut i = 0;
        while i + 1 < n && self.breaks[i + 1] <= u {
            i += 1;
        }
        let (a, b) = (self.breaks[i], self.breaks[i + 1]);
        (i, ((u - a) / (b - a)).clamp(0.0, 1.0))
    }

    fn point(&self, u: f64) -> Point {
        let (i, t) = self.locate(u);
        self.spans[i].eval(t)
    }

    fn derivs(&self, u: f64) -> crate::bezier::Derivs {
        let (i, t) = self.locate(u);
        self.spans[i].derivs(t)
    }

    fn direction(&self, u: f64) -> Vec2 {
        let d = self.derivs(u).d1;
        d / d.hypot()
    }

    /// Inflection parameters and curvature-maximum (of |κ|) parameters, sorted.
    fn events(&self) -> (Vec<f64>, Vec<f64>) {
        let (mut infl, mut maxima) = (Vec::new(), Vec::new());
        for (i, b) in self.spans.iter().enumerate() {
            let (x, y) = b.components();
            let (x1, y1) = (x.deriv(), y.deriv());
            let (x2, y2) = (x1.deriv(), y1.deriv());
            let g = x1.mul(&y2).sub(&y1.mul(&x2));
            let f = x1.mul(&x1).add(&y1.mul(&y1));
            let h = g
                .deriv()
                .mul(&f)
                .scale(2.0)
                .sub(&g.mul(&f.deriv()).scale(3.0));
            let (a, w) = (self.breaks[i], self.breaks[i + 1] - self.breaks[i]);
            for t in sign_change_roots(&g) {
                infl.push(a + w * t);
            }
            for t in sign_change_roots(&h) {
                // A maximum of |κ|: d|κ|/ds goes from + to -; sign(h) = sign(dκ/ds).
                let e = 1e-6;
                let before = h.eval((t - e).max(0.0)) * g.eval(t).signum();
                let after = h.eval((t + e).min(1.0)) * g.eval(t).signum();
                if before > 0.0 && after < 0.0 {
                    maxima.push(a + w * t);
                }
            }
        }
        (infl, maxima)
    }

    /// Unwrapped tangent angle at `u`, continuing from `prev` at `u_prev` (steps small enough
    /// that the tangent turns less than π between them).
    fn angle_between(&self, ua: f64, ub: f64) -> f64 {
        // Signed turning from ua to ub, accumulated over small steps.
        let n = 64;
        let mut total = 0.0;
        let mut prev = self.direction(ua);
        for k in 1..=n {
            let u = ua + (ub - ua) * k as f64 / n as f64;
            let d = self.direction(u);
            total += prev.cross(d).atan2(prev.dot(d));
            prev = d;
        }
        total
    }

    /// |κ| at u.
    fn abs_kappa(&self, u: f64) -> f64 {
        self.derivs(u).kappa().abs()
    }
}

/// What ends a piece.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Cut {
    End,
    Inflection,
    Other,
}

/// A piece's place on the B-spline, with its end tangents (unit vectors).
#[derive(Clone, Debug)]
struct Slot {
    ua: f64,
    ub: f64,
    cut_a: Cut,
    cut_b: Cut,
    /// α of the piece: least squares against the input points, or the B-spline's LCG
    /// slope where that fit has not run or found no segment.
    alpha: Option<f64>,
    /// Whether the least-squares fit of α ran.
    fitted: bool,
    /// Tangent at the curve's start or end fitted with α (end slots only): replaces the
    /// spline's there.
    dir_a: Option<Vec2>,
    /// As `dir_a`, at the slot's end.
    dir_b: Option<Vec2>,
}

/// Parameters where the curve turns by `turn` (in [0, total]) from `ua`, by bisection.
fn u_at_turn(track: &Track, ua: f64, ub: f64, target: f64) -> f64 {
    let total = track.angle_between(ua, ub);
    let sgn = total.signum();
    let b = crate::solve::bisect_by(
        |mid| (sgn * track.angle_between(ua, mid) < target).then_some(()),
        ua,
        ub,
        |a, b| 0.5 * (a + b),
        |_, _| false,
        60,
    );
    0.5 * (b.inside + b.outside)
}

/// Step 2: the cuts of the B-spline.
fn segment(track: &Track, shape: &Track, opts: &SketchOptions) -> Result<Vec<Slot>> {
    let (u0, u1) = (track.breaks[0], *track.breaks.last().unwrap());
    let (mut infl, mut maxima) = shape.events();
    if !std::ptr::eq(track, shape) {
        // Move each event to the tight spline's own event nearby (its location is more
        // accurate), when there is one: the nearest inflection, the largest maximum.
        let (ti, tm) = track.events();
        let w = 0.05 * (u1 - u0);
        for u in infl.iter_mut() {
            if let Some(v) = ti
                .iter()
                .copied()
                .filter(|v| (v - *u).abs() < w)
                .min_by(|a, b| (a - *u).abs().total_cmp(&(b - *u).abs()))
            {
                *u = v;
            }
        }
        for u in maxima.iter_mut() {
            if let Some(v) = tm
                .iter()
                .copied()
                .filter(|v| (v - *u).abs() < w)
                .max_by(|a, b| track.abs_kappa(*a).total_cmp(&track.abs_kappa(*b)))
            {
                *u = v;
            }
        }
    }
    let turn = |a: f64, b: f64| track.angle_between(a, b).abs();
    // Drop inflections too close to an end, then inflection pairs with little turning between.
    loop {
        let before = infl.len();
        infl.retain(|&u| turn(u0, u) >= opts.min_turn && turn(u, u1) >= opts.min_turn);
        let mut i = 0;
        while i + 1 < infl.len() {
            if turn(infl[i], infl[i + 1]) < opts.min_turn {
                infl.drain(i..i + 2);
            } else {
                i += 1;
            }
        }
        if infl.len() == before {
            break;
        }
    }
    // An inflection pair (or an inflection and an end) with hardly any curvature between
    // them is a flat stretch crossed by noise, not an S: drop it (below a tenth of the
    // curve's largest |κ|).
    let kappa_max_on = |a: f64, b: f64| {
        (0..=16)
            .map(|k| track.abs_kappa(a + (b - a) * k as f64 / 16.0))
            .fold(0.0, f64::max)
    };
    let k_all = kappa_max_on(u0, u1);
    loop {
        let mut bounds = vec![u0];
        bounds.extend(&infl);
        bounds.push(u1);
        // The flattest stretch next to an inflection, if it is flat enough.
        let flat = (0..bounds.len() - 1)
            .map(|i| (i, kappa_max_on(bounds[i], bounds[i + 1])))
            .filter(|(_, k)| *k < 0.1 * k_all)
            .min_by(|x, y| x.1.total_cmp(&y.1));
        let Some((i, _)) = flat else { break };
        // Stretch i lies between bounds i and i + 1; inflections are bounds 1..=len.
        let (first, last) = (i == 0, i + 1 == bounds.len() - 1);
        match (first, last) {
            (true, true) => break,
            (true, false) => {
                infl.remove(0);
            }
            (false, true) => {
                infl.pop();
            }
            (false, false) => {
                infl.drain(i - 1..=i);
            }
        }
    }
    // Boundaries: ends and inflections; one |κ| maximum per interval.
    let mut bounds: Vec<(f64, Cut)> = vec![(u0, Cut::End)];
    bounds.extend(infl.iter().map(|&u| (u, Cut::Inflection)));
    bounds.push((u1, Cut::End));
    let mut cuts: Vec<(f64, Cut)> = vec![bounds[0]];
    for w in bounds.windows(2) {
        let ((a, ca), (b, cb)) = (w[0], w[1]);
        let inside: Vec<f64> = maxima
            .iter()
            .copied()
            .filter(|&u| {
                u > a
                    && u < b
                    && turn(a, u) >= 0.5 * opts.min_turn
                    && turn(u, b) >= 0.5 * opts.min_turn
            })
            .collect();
        let best = inside
            .iter()
            .copied()
            .max_by(|x, y| track.abs_kappa(*x).total_cmp(&track.abs_kappa(*y)));
        let pick = match best {
            Some(u) => {
                // Only a true interior maximum: above both ends of its interval.
                let k = track.abs_kappa(u);
                let need = ca == Cut::Inflection && cb == Cut::Inflection;
                if need || (k > track.abs_kappa(a) && k > track.abs_kappa(b)) {
                    Some(u)
                } else {
                    None
                }
            }
            None if ca == Cut::Inflection && cb == Cut::Inflection => {
                // Between two inflections there is a maximum; the root finder missed it
                // (flat): take the half-turning point.
                Some(u_at_turn(track, a, b, 0.5 * turn(a, b)))
            }
            None => None,
        };
        if let Some(u) = pick {
            cuts.push((u, Cut::Other));
        }
        cuts.push((b, cb));
    }
    // Split pieces turning more than max_turn.
    let mut slots = Vec::new();
    for w in cuts.windows(2) {
        let ((a, ca), (b, cb)) = (w[0], w[1]);
        let t = turn(a, b);
        let parts = ((t / opts.max_turn).ceil() as usize).max(1);
        let mut prev = (a, ca);
        for k in 1..parts {
            let u = u_at_turn(track, a, b, t * k as f64 / parts as f64);
            slots.push(slot(track, prev, (u, Cut::Other)));
            prev = (u, Cut::Other);
        }
        slots.push(slot(track, prev, (b, cb)));
    }
    Ok(slots)
}

fn slot(track: &Track, a: (f64, Cut), b: (f64, Cut)) -> Slot {
    Slot {
        ua: a.0,
        ub: b.0,
        cut_a: a.1,
        cut_b: b.1,
        alpha: lcg_alpha(track, a.0, b.0),
        fitted: false,
        dir_a: None,
        dir_b: None,
    }
}

/// α of the B-spline over [ua, ub] from the least-squares line of its LCG; `None` where the
/// curvature barely varies.
fn lcg_alpha(track: &Track, ua: f64, ub: f64) -> Option<f64> {
    let n = 64;
    let mut graph = Vec::with_capacity(n);
    let (mut kmin, mut kmax) = (f64::INFINITY, 0.0f64);
    for i in 0..n {
        let u = ua + (ub - ua) * (i as f64 + 0.5) / n as f64;
        let d = track.derivs(u);
        let k = d.kappa().abs();
        kmin = kmin.min(k);
        kmax = kmax.max(k);
        if let Some(p) = lcg_point(d.kappa(), d.dkappa_ds()) {
            graph.push(p);
        }
    }
    if kmax.is_nan() || kmax <= 0.0 || (kmax - kmin) < 0.01 * kmax {
        return None;
    }
    fit_line(graph).ok().map(|f| f.alpha.clamp(-5.0, 5.0))
}

/// The control triangle of a piece from its end points and unit end tangents; `None` when
/// the tangent lines do not meet ahead of the start and behind the end.
fn triangle(pa: Point, da: Vec2, pb: Point, db: Vec2) -> Option<[Point; 3]> {
    let den = da.cross(db);
    if den.abs() < 1e-12 {
        return None;
    }
    let s = (pb - pa).cross(db) / den;
    // Apex = pb + t' db with t' = (pb - pa) x da / den, which must be behind pb.
    let t = -(pb - pa).cross(da) / den;
    if !(s > 0.0 && t > 0.0) {
        return None;
    }
    Some([pa, pa + da * s, pb])
}

/// A built piece.
#[derive(Clone, Debug)]
struct Built {
    curve: PieceCurve,
    alpha: f64,
    /// Signed curvature at the start and at the end (curve order).
    kappa: (f64, f64),
}

/// The segment of a piece with end points and tangent angles given.
/// Split where the curve misses the points most (kept off the piece's ends); a piece with an
/// inflection end at its mid-turn, so the inflection piece left keeps a proper triangle.
fn split_worst(track: &Track, slots: &mut Vec<Slot>, piece: usize, u: f64) -> Result<()> {
    let s = &slots[piece];
    if s.cut_a == Cut::Inflection || s.cut_b == Cut::Inflection {
        split_at_mid_turn(track, slots, piece)
    } else {
        let u = u.clamp(s.ua + 0.25 * (s.ub - s.ua), s.ub - 0.25 * (s.ub - s.ua));
        split_at(track, slots, piece, u)
    }
}

/// The largest distance from `points` (spline parameters `params`) to polylines of the
/// pieces, with its piece and parameter: the nearest point over all pieces (the pieces'
/// polylines joined end to end, every chord a candidate: [`crate::lac_fit`]'s nearest
/// search).
fn polyline_deviation(points: &[Point], params: &[f64], polys: &[Vec<Point>]) -> (f64, usize, f64) {
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

/// An inflection-end piece's shape (α, θ_d) and the optimum (f0, ln w0) of its cubic.
type InflectionStart = ((f64, f64), (f64, f64));

/// Splits for missed points made one per round before they are made all at once.
const BATCH_AFTER: usize = 4;

/// The memo key of a piece: its kind, alpha and control points, bit for bit.
fn memo_key(kind: u64, alpha: u64, c: &[Point; 3]) -> [u64; 8] {
    [
        kind,
        alpha,
        c[0].x.to_bits(),
        c[0].y.to_bits(),
        c[1].x.to_bits(),
        c[1].y.to_bits(),
        c[2].x.to_bits(),
        c[2].y.to_bits(),
    ]
}

fn build_piece(slot: &Slot, pa: Point, da: Vec2, pb: Point, db: Vec2) -> Result<Built> {
    let tri = triangle(pa, da, pb, db).ok_or_else(|| {
        Error::Degenerate("the end tangents of a piece do not form a triangle".into())
    })?;
    let infl_a = slot.cut_a == Cut::Inflection;
    let infl_b = slot.cut_b == Cut::Inflection;
    if infl_a != infl_b {
        let ctrl = if infl_a {
            tri
        } else {
            [tri[2], tri[1], tri[0]]
        };
        if let Ok(segment) = LacInflectionSegment::new(ctrl) {
            let k = segment.end_curvature();
            let alpha = segment.alpha;
            // In curve order; a reversed segment's signed curvature changes sign.
            let ends = if infl_a { (0.0, k) } else { (-k, 0.0) };
            return Ok(Built {
                curve: PieceCurve::Inflection {
                    segment,
                    inflection_at_start: infl_a,
                },
                alpha,
                kappa: ends,
            });
        }
    }
    let target = slot.alpha.unwrap_or(1.0);
    let seg = match LacSegment::new(target, tri) {
        Ok(s) => s,
        Err(Error::NoSegment(_)) => {
            // Nearest admissible α towards 0.5 (0 <= α <= 1 always admits a triangle):
            // bisection on the existence test (no Λ solve), then the solve just inside the
            // boundary, where it can still refuse (the curve overflows f64 right at it);
            // failing that, bisection on the solve itself.
            let (mut bad, mut good) = (target, 0.5);
            for _ in 0..40 {
                let mid = 0.5 * (bad + good);
                if LacSegment::exists(mid, tri).unwrap_or(false) {
                    good = mid;
                } else {
                    bad = mid;
                }
            }
            let inside = [0.0, 1e-9, 1e-6, 1e-3]
                .iter()
                .find_map(|f| LacSegment::new(good + (0.5 - good) * f, tri).ok());
            match inside {
                Some(s) => s,
                None => {
                    let (mut bad, mut good) = (target, 0.5);
                    for _ in 0..40 {
                        let mid = 0.5 * (bad + good);
                        if LacSegment::new(mid, tri).is_ok() {
                            good = mid;
                        } else {
                            bad = mid;
                        }
                    }
                    LacSegment::new(good, tri)?
                }
            }
        }
        Err(e) => return Err(e),
    };
    let ends = seg.end_curvatures()?;
    let alpha = seg.standard.alpha();
    Ok(Built {
        curve: PieceCurve::Lac(seg),
        alpha,
        kappa: ends,
    })
}

/// The pieces for joint tangents `dirs` (one unit vector per joint, ends included).
fn build_all(slots: &[Slot], pts: &[Point], dirs: &[Vec2]) -> Result<Vec<Built>> {
    slots
        .iter()
        .enumerate()
        .map(|(i, s)| build_piece(s, pts[i], dirs[i], pts[i + 1], dirs[i + 1]))
        .collect()
}

/// At each inflection joint, turn the tangent (least first, within ±0.5 rad) until both
/// adjacent inflection-end pieces exist: the B-spline's tangent there can leave one
/// triangle with the inflection end's base angle above half its turning.
/// Returns the slots that cannot be inflection pieces at any such tangent.
fn settle_inflections(slots: &[Slot], pts: &[Point], dirs: &mut [Vec2]) -> Vec<usize> {
    let mut failed = Vec::new();
    let both = |j: usize, d: Vec2, before: Vec2, after: Vec2| {
        let l = build_piece(&slots[j - 1], pts[j - 1], before, pts[j], d);
        let r = build_piece(&slots[j], pts[j], d, pts[j + 1], after);
        matches!(
            (l, r),
            (
                Ok(Built {
                    curve: PieceCurve::Inflection { .. },
                    ..
                }),
                Ok(Built {
                    curve: PieceCurve::Inflection { .. },
                    ..
                })
            )
        )
    };
    for j in 1..slots.len() {
        if !(slots[j - 1].cut_b == Cut::Inflection && slots[j].cut_a == Cut::Inflection) {
            continue;
        }
        let (before, here, after) = (dirs[j - 1], dirs[j], dirs[j + 1]);
        if both(j, here, before, after) {
            continue;
        }
        let found = (1..=200).find_map(|k| {
            let a = 0.0025 * k as f64;
            [a, -a]
                .into_iter()
                .map(|x| rotate(here, x))
                .find(|d| both(j, *d, before, after))
        });
        if let Some(d) = found {
            dirs[j] = d;
        } else {
            let is_infl = |r: Result<Built>| {
                matches!(
                    r,
                    Ok(Built {
                        curve: PieceCurve::Inflection { .. },
                        ..
                    })
                )
            };
            if !is_infl(build_piece(&slots[j - 1], pts[j - 1], before, pts[j], here)) {
                failed.push(j - 1);
            }
            if !is_infl(build_piece(&slots[j], pts[j], here, pts[j + 1], after)) {
                failed.push(j);
            }
        }
    }
    failed.dedup();
    failed
}

/// Split `slots[i]` at its largest |κ| (sampled) when that lies inside it: an inflection
/// piece whose curvature peaks near the inflection (a maximum the simplification dropped)
/// becomes a short inflection piece and a monotone rest. Returns whether it split.
fn split_at_peak(track: &Track, slots: &mut Vec<Slot>, i: usize) -> bool {
    let s = slots[i].clone();
    let n = 64;
    let us: Vec<f64> = (1..n)
        .map(|k| s.ua + (s.ub - s.ua) * k as f64 / n as f64)
        .collect();
    let k = (0..us.len())
        .max_by(|&a, &b| track.abs_kappa(us[a]).total_cmp(&track.abs_kappa(us[b])))
        .unwrap();
    let u = us[k];
    let inner =
        track.abs_kappa(u) > track.abs_kappa(s.ua) && track.abs_kappa(u) > track.abs_kappa(s.ub);
    if !(inner && k > 0 && k + 1 < us.len()) {
        return false;
    }
    let left = slot(track, (s.ua, s.cut_a), (u, Cut::Other));
    let right = slot(track, (u, Cut::Other), (s.ub, s.cut_b));
    slots.splice(i..=i, [left, right]);
    true
}

/// The largest end curvature of the pieces.
fn curvature_scale(built: &[Built]) -> f64 {
    built
        .iter()
        .map(|b| b.kappa.0.abs().max(b.kappa.1.abs()))
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE)
}

/// The pieces before and after joint `j` of `m` pieces: joint j (1 to m - 1) starts piece
/// j; joint 0 is a closed curve's seam, from the last piece to the first.
fn sides(j: usize, m: usize) -> (usize, usize) {
    if j == 0 {
        (m - 1, 0)
    } else {
        (j - 1, j)
    }
}

/// Joint `j`'s tangent turned by `h` (the seam's at both ends of the curve, which share it).
fn turn_joint(dirs: &mut [Vec2], j: usize, h: f64) {
    dirs[j] = rotate(dirs[j], h);
    if j == 0 {
        let m = dirs.len() - 1;
        dirs[m] = dirs[0];
    }
}

/// The pieces on both sides of joint `j` rebuilt in `built` with the tangents `dirs`.
fn rebuild_joint(
    built: &mut [Built],
    (slots, pts, dirs): (&[Slot], &[Point], &[Vec2]),
    j: usize,
) -> Option<()> {
    let (a, b) = sides(j, slots.len());
    for i in [a, b] {
        built[i] = build_piece(&slots[i], pts[i], dirs[i], pts[i + 1], dirs[i + 1]).ok()?;
    }
    Some(())
}

/// The curvature mismatch at each active joint over `scale`.
fn mismatches(built: &[Built], active: &[usize], scale: f64) -> Vec<f64> {
    active
        .iter()
        .map(|&j| {
            let (a, b) = sides(j, built.len());
            (built[b].kappa.0 - built[a].kappa.1) / scale
        })
        .collect()
}

fn rotate(v: Vec2, a: f64) -> Vec2 {
    let (s, c) = a.sin_cos();
    Vec2::new(c * v.x - s * v.y, s * v.x + c * v.y)
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// One Jacobian column by finite differences of the mismatches: central from the values at
/// `+h` and `-h`, one-sided (against `d`, the values at 0) where one side cannot be built,
/// `None` where neither can.
fn difference_column(
    plus: Option<Vec<f64>>,
    minus: Option<Vec<f64>>,
    d: &[f64],
    h: f64,
) -> Option<Vec<f64>> {
    let n = d.len();
    match (plus, minus) {
        (Some(p), Some(m)) => Some((0..n).map(|r| (p[r] - m[r]) / (2.0 * h)).collect()),
        (Some(p), None) => Some((0..n).map(|r| (p[r] - d[r]) / h).collect()),
        (None, Some(m)) => Some((0..n).map(|r| (d[r] - m[r]) / h).collect()),
        (None, None) => None,
    }
}

/// Step 4: G2 fairing by Newton on the active joints' tangent angles.
fn fair(
    slots: &[Slot],
    pts: &[Point],
    dirs: &mut [Vec2],
    opts: &SketchOptions,
) -> Result<(Vec<Built>, FairingReport)> {
    let m = slots.len();
    let built = build_all(slots, pts, dirs)?;
    // Joints where both sides are inflection ends have zero curvature on both sides; every
    // other joint (an inflection cut whose piece could not be an inflection piece too) is
    // faired.
    let zero_both = |built: &[Built], j: usize| {
        let (a, b) = sides(j, m);
        matches!(
            built[a].curve,
            PieceCurve::Inflection {
                inflection_at_start: false,
                ..
            }
        ) && matches!(
            built[b].curve,
            PieceCurve::Inflection {
                inflection_at_start: true,
                ..
            }
        )
    };
    // A closed curve's seam (joint 0) is faired too.
    let first = usize::from(!opts.closed);
    let faired =
        |built: &[Built]| -> Vec<usize> { (first..m).filter(|&j| !zero_both(built, j)).collect() };
    let active = faired(&built);
    // The merit's scale stays that of the first build: measured against the trial's own
    // largest curvature, a step that blows one free end up into a hook (a triangle at the
    // edge of its existence region) would shrink every relative mismatch and be accepted.
    let scale = curvature_scale(&built);
    let d = mismatches(&built, &active, scale);
    let initial = max_abs(&d);
    let na = active.len();
    let tol = opts.g2_tolerance;
    // Newton on the active joints' tangent angles (the solver layer's damped Newton); the
    // state is the tangent directions and the pieces built on them.
    let direction = |(dirs, built): &(Vec<Vec2>, Vec<Built>), d: &[f64]| {
        // Finite-difference Jacobian: joint k's angle moves pieces active[k]-1 and active[k].
        // Central difference; one-sided where a side leaves the admissible set. The columns
        // are independent: computed in parallel (the same numbers in any order).
        let column = |j: usize| -> Option<Vec<f64>> {
            let at = |h: f64| -> Option<Vec<f64>> {
                let mut trial = dirs.to_vec();
                turn_joint(&mut trial, j, h);
                let mut b2 = built.clone();
                rebuild_joint(&mut b2, (slots, pts, &trial), j)?;
                Some(mismatches(&b2, &active, scale))
            };
            let h = 1e-6;
            difference_column(at(h), at(-h), d, h)
        };
        let columns: Vec<Option<Vec<f64>>> = if na >= 4 {
            active.par_iter().map(|&j| column(j)).collect()
        } else {
            active.iter().map(|&j| column(j)).collect()
        };
        let mut jac = DMatrix::<f64>::zeros(na, na);
        for (k, c) in columns.into_iter().enumerate() {
            for (r, v) in c?.into_iter().enumerate() {
                jac[(r, k)] = v;
            }
        }
        let step = jac
            .lu()
            .solve(&DVector::from_iterator(na, d.iter().map(|v| -v)))?;
        let big = step.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let lam = if big > 0.3 { 0.3 / big } else { 1.0 };
        Some((step.iter().copied().collect::<Vec<f64>>(), lam))
    };
    let trial = |(dirs, _): &(Vec<Vec2>, Vec<Built>), step: &[f64], lam: f64| {
        let mut trial = dirs.to_vec();
        for (k, &j) in active.iter().enumerate() {
            turn_joint(&mut trial, j, lam * step[k]);
        }
        let b2 = build_all(slots, pts, &trial).ok()?;
        let d2 = mismatches(&b2, &active, scale);
        Some(((trial, b2), d2))
    };
    // Converged by the measure of the final report: over the build's own curvature.
    let own = |built: &[Built]| max_abs(&mismatches(built, &active, curvature_scale(built)));
    let converged = |(_, built): &(Vec<Vec2>, Vec<Built>), _: &[f64]| own(built) <= tol;
    let newton = crate::solve::DampedNewton {
        max_iterations: opts.max_fairing_iterations,
        halvings: 30,
    };
    let run = crate::solve::damped_newton(
        (dirs.to_vec(), built),
        d,
        direction,
        trial,
        converged,
        &newton,
    )?;
    let (new_dirs, mut built) = run.state;
    dirs.copy_from_slice(&new_dirs);
    let final_jump = own(&built);
    let mut report = FairingReport {
        iterations: run.iterations,
        initial_jump: initial,
        final_jump,
        converged: final_jump <= tol,
    };
    if !report.converged {
        free_alphas(
            slots,
            pts,
            dirs,
            opts,
            &active,
            scale,
            &mut built,
            &mut report,
        )?;
    }
    // The report covers every joint of the result: a step can turn a piece next to a joint
    // left out (zero curvature on both sides) into an ordinary one, whose end curvature
    // there is not zero.
    report.final_jump = max_abs(&mismatches(
        &built,
        &faired(&built),
        curvature_scale(&built),
    ));
    report.converged = report.final_jump <= opts.g2_tolerance;
    Ok((built, report))
}

/// The fairing's second stage, when the joint tangents alone leave a jump: the α of every
/// LAC piece next to a joint that still jumps joins the unknowns (a joint between an
/// inflection-end piece, whose end curvature its triangle fixes, and a short piece whose
/// least-squares α sits on its bound can have no tangent that matches). More unknowns than
/// equations: the minimum-norm Gauss–Newton step (α weighted by [`ALPHA_WEIGHT`]), α kept
/// within [`ALPHA_RANGE`], the same merit and line search as the first stage.
#[allow(clippy::too_many_arguments)]
fn free_alphas(
    slots: &[Slot],
    pts: &[Point],
    dirs: &mut [Vec2],
    opts: &SketchOptions,
    active: &[usize],
    scale: f64,
    built: &mut Vec<Built>,
    report: &mut FairingReport,
) -> Result<()> {
    let na = active.len();
    let tol = opts.g2_tolerance;
    let mut d0 = mismatches(built, active, scale);
    let mut free: Vec<usize> = Vec::new();
    for (k, &j) in active.iter().enumerate() {
        if d0[k].abs() > tol {
            let (a, b) = sides(j, built.len());
            for i in [a, b] {
                if matches!(built[i].curve, PieceCurve::Lac(_)) && !free.contains(&i) {
                    free.push(i);
                }
            }
        }
    }
    if free.is_empty() {
        return Ok(());
    }
    free.sort_unstable();
    // α as built; an α that was outside its triangle's existence region and moved onto its
    // edge (where an end curvature goes to 0 or infinity and no derivative helps) starts a
    // tenth of the way from there to 0.5, which every triangle admits.
    let mut local: Vec<Slot> = slots.to_vec();
    for &i in &free {
        let a = built[i].alpha;
        let snapped = slots[i].alpha.is_some_and(|s| (s - a).abs() > 1e-9);
        local[i].alpha = Some(if snapped { a + 0.1 * (0.5 - a) } else { a });
    }
    if free.iter().any(|&i| local[i].alpha != Some(built[i].alpha)) {
        if let Ok(b2) = build_all(&local, pts, dirs) {
            *built = b2;
            d0 = mismatches(built, active, scale);
        }
    }
    let nx = na + free.len();
    type State = (Vec<Vec2>, Vec<Slot>, Vec<Built>);
    let direction = |(dirs, local, built): &State, d: &[f64]| {
        // Columns: the active joints' tangent angles, then the free pieces' α.
        let column = |c: usize| -> Vec<f64> {
            let at = |h: f64| -> Option<Vec<f64>> {
                let mut b2 = built.clone();
                if c < na {
                    let j = active[c];
                    let mut trial = dirs.to_vec();
                    turn_joint(&mut trial, j, h);
                    rebuild_joint(&mut b2, (local, pts, &trial), j)?;
                } else {
                    let i = free[c - na];
                    let mut sl = local[i].clone();
                    let a = sl.alpha? + h;
                    if !(ALPHA_RANGE.0..=ALPHA_RANGE.1).contains(&a) {
                        return None;
                    }
                    sl.alpha = Some(a);
                    b2[i] = build_piece(&sl, pts[i], dirs[i], pts[i + 1], dirs[i + 1]).ok()?;
                    if (b2[i].alpha - a).abs() > 1e-12 {
                        return None; // moved back inside the existence region: no derivative
                    }
                }
                Some(mismatches(&b2, active, scale))
            };
            let h = if c < na { 1e-6 } else { 1e-5 };
            // An unknown that can move neither way does not move.
            difference_column(at(h), at(-h), d, h).unwrap_or_else(|| vec![0.0; na])
        };
        let columns: Vec<Vec<f64>> = (0..nx).into_par_iter().map(column).collect();
        let mut jac = DMatrix::<f64>::zeros(na, nx);
        for (c, col) in columns.into_iter().enumerate() {
            let w = if c < na { 1.0 } else { ALPHA_WEIGHT.sqrt() };
            for (r, v) in col.into_iter().enumerate() {
                jac[(r, c)] = v * w;
            }
        }
        // Minimum-norm step in the weighted unknowns: x = Jᵀ (J Jᵀ + μ I)⁻¹ (-d).
        let jjt = &jac * jac.transpose();
        let mu = 1e-12 * jjt.trace().max(f64::MIN_POSITIVE);
        let y = (jjt + DMatrix::identity(na, na) * mu)
            .lu()
            .solve(&DVector::from_iterator(na, d.iter().map(|v| -v)))?;
        let mut step = jac.transpose() * y;
        for c in na..nx {
            step[c] *= ALPHA_WEIGHT.sqrt();
        }
        let big_angle = (0..na).fold(0.0f64, |m, c| m.max(step[c].abs()));
        let big_alpha = (na..nx).fold(0.0f64, |m, c| m.max(step[c].abs()));
        let lam = 1.0f64
            .min(0.3 / big_angle.max(1e-300))
            .min(1.0 / big_alpha.max(1e-300));
        Some((step.iter().copied().collect::<Vec<f64>>(), lam))
    };
    let trial = |(dirs, local, _): &State, step: &[f64], lam: f64| {
        let mut trial = dirs.to_vec();
        for (k, &j) in active.iter().enumerate() {
            turn_joint(&mut trial, j, lam * step[k]);
        }
        let mut tl = local.clone();
        for (k, &i) in free.iter().enumerate() {
            let a = tl[i].alpha.unwrap_or(1.0) + lam * step[na + k];
            tl[i].alpha = Some(a.clamp(ALPHA_RANGE.0, ALPHA_RANGE.1));
        }
        let b2 = build_all(&tl, pts, &trial).ok()?;
        let d2 = mismatches(&b2, active, scale);
        Some(((trial, tl, b2), d2))
    };
    let own = |built: &[Built]| max_abs(&mismatches(built, active, curvature_scale(built)));
    let converged = |(_, _, built): &State, _: &[f64]| own(built) <= tol;
    let newton = crate::solve::DampedNewton {
        max_iterations: opts.max_fairing_iterations,
        halvings: 30,
    };
    let run = crate::solve::damped_newton(
        (dirs.to_vec(), local, std::mem::take(built)),
        d0,
        direction,
        trial,
        converged,
        &newton,
    )?;
    // The final jump and verdict are [`fair`]'s, over every joint of the result.
    report.iterations += run.iterations;
    let (new_dirs, _, new_built) = run.state;
    dirs.copy_from_slice(&new_dirs);
    *built = new_built;
    Ok(())
}

/// Distance from `q` to a rational cubic and the foot's parameter: the nearest of `n`
/// samples, then safeguarded Newton.
fn project(c: &RationalBezier, q: Point, samples: &[(f64, Point)]) -> (f64, f64) {
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
    let opts = crate::solve::NewtonMin1d {
        max_iterations: 20,
        max_halvings: 1,
        x_tol: 0.0,
        min_move: 0.0,
        bounds: (0.0, 1.0),
    };
    let m = crate::solve::newton_min_1d(step, |t| (c.eval(t) - q).hypot(), t0, &opts);
    (m.value, m.x)
}

/// Fit a G2 curve of LAC pieces (as rational cubics) to an ordered point sequence (see the
/// module documentation).
///
/// Errors: [`Error::InvalidInput`] for fewer than 4 distinct points, non-finite values or a
/// bad tolerance; [`Error::Degenerate`] for points on a straight line (no LAC turns) or
/// tangents that do not form triangles; [`Error::NoConvergence`] when `max_pieces` are not
/// enough for the tolerance.
pub fn fit_sketch(points: &[Point], opts: &SketchOptions) -> Result<Sketch> {
    // The points first: a tolerance derived from unusable points is not the cause.
    check_points(points)?;
    Error::check_positive("tolerance", opts.tolerance)?;
    if !(opts.max_turn > 0.1 && opts.max_turn < 3.0) {
        return Err(Error::invalid("max_turn", "must lie in (0.1, 3) radians"));
    }
    // Precise input: the B-spline follows the data as closely as its noise allows
    // (tangents and curvature graphs come out accurate), never looser than half the
    // tolerance; noisy input: the smoothest spline within FAIR_SHARE of it.
    let size = bbox_diagonal(points);
    let sigma = noise_level(points);
    // Precise data (noise below 1e-6 of the size) get a tight fit, whose tangents and
    // curvature graphs are accurate; noisy data the smoothest fit within FAIR_SHARE of the
    // tolerance.
    let noisy = 4.0 * sigma > 1e-6 * size;
    let fit_tol = if noisy {
        FAIR_SHARE * opts.tolerance
    } else {
        (4.0 * sigma).max(1e-5 * size).min(0.5 * opts.tolerance)
    };
    // Noisy data (measured lines, pen strokes): fair first. The smoothest spline within
    // FAIR_SHARE of the tolerance carries no hooks or wiggles the tolerance does not demand;
    // its few events cut the pieces. Precise data: the tight fit, whose tangents and curvature are
    // accurate. Outliers the noise estimate ignores can keep the tight fit from converging:
    // then half the tolerance.
    let fit = if noisy {
        bspline::smoothing_fit(points, fit_tol)
    } else {
        bspline::fit(
            points,
            FitOptions {
                tolerance: fit_tol,
                max_segments: 200,
            },
        )
    };
    let (fit, fit_tol) = match fit {
        Err(Error::NoConvergence(_)) if fit_tol < 0.5 * opts.tolerance => (
            bspline::fit(
                points,
                FitOptions {
                    tolerance: 0.5 * opts.tolerance,
                    max_segments: 200,
                },
            )?,
            0.5 * opts.tolerance,
        ),
        other => (other?, fit_tol),
    };
    let track = Track::new(&fit.spline)?;
    let total_turn = track.angle_between(track.breaks[0], *track.breaks.last().unwrap());
    let mut turns = 0.0;
    let nb = 256;
    let (u0, u1) = (track.breaks[0], *track.breaks.last().unwrap());
    for k in 0..nb {
        let a = u0 + (u1 - u0) * k as f64 / nb as f64;
        let b = u0 + (u1 - u0) * (k + 1) as f64 / nb as f64;
        turns += track.angle_between(a, b).abs();
    }
    if turns < opts.min_turn {
        return Err(Error::Degenerate(format!(
            "the points lie on a straight line (total turning {:.3e} rad, total {:.3e}): \
             no log-aesthetic curve turns along them",
            turns, total_turn
        )));
    }
    // On noisy data (noise above 1e-4 of the size), inflections and curvature maxima come
    // from a smoother spline (a quarter of the tolerance): noise-induced wiggles of the
    // tight fit's curvature are not features. Both are parametrised by chord length (corrected),
    // so a parameter carries over.
    let shape_tol = 0.25 * opts.tolerance;
    let shape_fit;
    let shape = if !noisy && shape_tol > 2.0 * fit_tol {
        let f = bspline::fit(
            points,
            FitOptions {
                tolerance: shape_tol,
                max_segments: 200,
            },
        )?;
        shape_fit = Track::new(&f.spline)?;
        &shape_fit
    } else {
        &track
    };
    let mut slots = segment(&track, shape, opts)?;
    split_s_shapes(&track, &mut slots)?;
    // The curve runs from the first input point to the last (their end tangents are fitted
    // with the end pieces' α, so an artefact in the last few points bends nothing).
    let ends: EndPoints = (fit.points[0], *fit.points.last().unwrap());
    merge_slots(
        &track,
        &fit,
        &mut slots,
        ends,
        MERGE_SHARE * opts.tolerance,
        opts.max_turn,
    );
    // The pieces at the curve's ends fit their outer tangent with α (in the loop).
    slots[0].fitted = false;
    if let Some(s) = slots.last_mut() {
        s.fitted = false;
    }
    let mut peak_splits = 0;
    // Splits made because the curve missed the points.
    let mut miss_splits = 0;
    // Optima of the inflection-end cubic fits so far, by shape (α, θ_d): warm starts for
    // the next rounds, whose pieces differ only a little.
    let mut inflection_starts: Vec<InflectionStart> = Vec::new();
    // The rational cubic of every piece fitted so far, by its exact segment: a piece that
    // no round changed is not fitted again.
    let mut memo: std::collections::HashMap<[u64; 8], RationalCubicFit> =
        std::collections::HashMap::new();
    loop {
        crate::deadline::check()?;
        let last = slots.len() - 1;
        // Each new slot's alpha on its own: in parallel (the same results in any order).
        slots
            .par_iter_mut()
            .enumerate()
            .filter(|(_, s)| !s.fitted)
            .for_each(|(i, s)| {
                let end = !opts.closed && (i == 0 || i == last);
                fit_slot_alpha(&track, &fit, s, ends, end);
            });
        let pts: Vec<Point> = slots
            .iter()
            .map(|s| track.point(s.ua))
            .chain(std::iter::once(track.point(slots.last().unwrap().ub)))
            .collect();
        let mut pts = pts;
        // The curve's ends are the input's ends.
        pts[0] = ends.0;
        *pts.last_mut().unwrap() = ends.1;
        let mut dirs: Vec<Vec2> = slots
            .iter()
            .map(|s| track.direction(s.ua))
            .chain(std::iter::once(track.direction(slots.last().unwrap().ub)))
            .collect();
        // Fitted end tangents replace the spline's.
        if let Some(d) = slots[0].dir_a {
            dirs[0] = d;
        }
        if let Some(d) = slots.last().unwrap().dir_b {
            *dirs.last_mut().unwrap() = d;
        }
        // A closed curve's two ends are one point with one tangent: the two ends' spline
        // tangents averaged.
        if opts.closed {
            let m = dirs.len() - 1;
            let both = dirs[0] + dirs[m];
            let l = both.hypot();
            if l > 0.0 {
                dirs[0] = both / l;
                dirs[m] = dirs[0];
            }
        }
        let failed = settle_inflections(&slots, &pts, &mut dirs);
        if !failed.is_empty() && peak_splits < 2 * opts.max_pieces && slots.len() < opts.max_pieces
        {
            // Later indices first, so earlier ones stay valid.
            let mut any = false;
            for &i in failed.iter().rev() {
                any |= split_at_peak(&track, &mut slots, i);
            }
            if any {
                peak_splits += 1;
                split_s_shapes(&track, &mut slots)?;
                continue;
            }
        }
        // An end piece whose end tangents form no triangle (the input's end point and a
        // fitted tangent can tip a shallow piece over): the fair spline's tangent there,
        // then its end point too.
        let m = slots.len();
        let has = |pts: &[Point], dirs: &[Vec2], i: usize| {
            triangle(pts[i], dirs[i], pts[i + 1], dirs[i + 1]).is_some()
        };
        if !has(&pts, &dirs, 0) {
            dirs[0] = track.direction(slots[0].ua);
            if !has(&pts, &dirs, 0) {
                pts[0] = track.point(slots[0].ua);
            }
        }
        if !has(&pts, &dirs, m - 1) {
            dirs[m] = track.direction(slots[m - 1].ub);
            if !has(&pts, &dirs, m - 1) {
                pts[m] = track.point(slots[m - 1].ub);
            }
        }
        let (built, fairing) = fair(&slots, &pts, &mut dirs, opts)?;
        // A round whose fairing failed and whose LAC pieces miss a point by more than twice
        // the tolerance splits where they miss most, without fitting rational cubics to
        // pieces that will not be kept (those fits cost most of such a round).
        if !fairing.converged && slots.len() < opts.max_pieces {
            let polys: Option<Vec<Vec<Point>>> = built
                .iter()
                .map(|b| match &b.curve {
                    PieceCurve::Lac(seg) => seg.sample(129).ok().map(|x| x.points),
                    PieceCurve::Inflection { segment, .. } => {
                        segment.sample(129).ok().map(|x| x.points)
                    }
                })
                .collect();
            if let Some(polys) = polys {
                let (worst, piece, u) = polyline_deviation(&fit.points, &fit.params, &polys);
                if worst > 2.0 * opts.tolerance {
                    split_worst(&track, &mut slots, piece, u)?;
                    continue;
                }
            }
        }
        // The rational cubic of every piece, fitted in parallel (each fit is pure work on
        // its own piece); the memo and the warm starts are read here and updated in curve
        // order below.
        type Fitted = (RationalCubicFit, Option<InflectionStart>);
        let fits: Vec<Result<Fitted>> = built
            .par_iter()
            .map(|b| match &b.curve {
                PieceCurve::Lac(seg) => {
                    let key = memo_key(0, seg.standard.alpha().to_bits(), &seg.control);
                    match memo.get(&key) {
                        Some(f) => Ok((f.clone(), None)),
                        None => fit_rational_cubic(seg, &opts.approx).map(|f| (f, None)),
                    }
                }
                PieceCurve::Inflection { segment, .. } => {
                    let key = memo_key(1, segment.alpha.to_bits(), &segment.control);
                    if let Some(f) = memo.get(&key) {
                        return Ok((f.clone(), None));
                    }
                    // A warm start from the optimum of the nearest shape (α, θ_d) fitted
                    // so far; the same shape has the same optimum.
                    let shape = (segment.alpha, segment.theta_d);
                    let warm = inflection_starts
                        .iter()
                        .filter(|(k, _)| {
                            (k.0 - shape.0).abs() <= 0.25 && (k.1 - shape.1).abs() <= 0.1 * shape.1
                        })
                        .min_by(|a, b| {
                            let d = |k: (f64, f64)| (k.0 - shape.0).abs() + (k.1 - shape.1).abs();
                            d(a.0).total_cmp(&d(b.0))
                        })
                        .map(|e| e.1);
                    let same = inflection_starts.iter().any(|(k, _)| {
                        k.0.to_bits() == shape.0.to_bits() && k.1.to_bits() == shape.1.to_bits()
                    });
                    fit_inflection_cubic_from(segment, &opts.approx, warm, !same)
                        .map(|(f, x)| (f, (!same).then_some((shape, x))))
                }
            })
            .collect();
        let mut pieces = Vec::with_capacity(slots.len());
        let mut split_here: Option<usize> = None;
        for ((s, b), fitted) in slots.iter().zip(built).zip(fits) {
            let Built {
                curve,
                alpha,
                kappa: ends,
            } = b;
            let (kind, control, rat) = match &curve {
                PieceCurve::Lac(seg) => match fitted {
                    Ok((f, _)) => {
                        memo.insert(
                            memo_key(0, seg.standard.alpha().to_bits(), &seg.control),
                            f.clone(),
                        );
                        (PieceKind::Lac, seg.control, f)
                    }
                    // No monotone cubic for this segment (it turns too far for its
                    // curvature range): split the piece and start the round again.
                    Err(Error::NoSegment(_)) if slots.len() < opts.max_pieces => {
                        split_here = Some(pieces.len());
                        break;
                    }
                    Err(e) => return Err(e),
                },
                PieceCurve::Inflection {
                    segment,
                    inflection_at_start,
                } => {
                    let f = match fitted {
                        Ok((f, start)) => {
                            if let Some(st) = start.filter(|st| st.1 .0.is_finite()) {
                                inflection_starts.push(st);
                            }
                            memo.insert(
                                memo_key(1, segment.alpha.to_bits(), &segment.control),
                                f.clone(),
                            );
                            f
                        }
                        // No curvature-monotone cubic of the family: the G2 cubic of the
                        // family's centre, reported as not monotone.
                        Err(Error::NoSegment(_)) => inflection_fallback(segment)?,
                        Err(e) => return Err(e),
                    };
                    let c = segment.control;
                    if *inflection_at_start {
                        (PieceKind::LacInflection, c, f)
                    } else {
                        let mut f = f;
                        f.curve = reverse(&f.curve);
                        (PieceKind::LacInflection, [c[2], c[1], c[0]], f)
                    }
                }
            };
            pieces.push(SketchPiece {
                kind,
                alpha,
                alpha_estimate: if kind == PieceKind::Lac {
                    s.alpha
                } else {
                    None
                },
                control,
                curve,
                end_curvatures: ends,
                rational: rat.curve,
                rational_error: rat.max_error,
                monotone: rat.monotone,
                alpha_at_bound: alpha <= ALPHA_RANGE.0 + 1e-9 || alpha >= ALPHA_RANGE.1 - 1e-9,
                u_range: (s.ua, s.ub),
            });
        }
        if let Some(i) = split_here {
            split_at_mid_turn(&track, &mut slots, i)?;
            continue;
        }
        // Deviation of the input from the rational result.
        let samples: Vec<Vec<(f64, Point)>> = pieces
            .iter()
            .map(|p| {
                (0..=64)
                    .map(|i| {
                        let t = i as f64 / 64.0;
                        (t, p.rational.eval(t))
                    })
                    .collect()
            })
            .collect();
        // Each piece's box, grown by its longest sample step: a piece whose box lies
        // farther from a point than the nearest distance found so far cannot hold a nearer
        // point, so it is skipped (the distance stays the true nearest one; the piece
        // around the point's parameter is tried first).
        let boxes: Vec<(kurbo::Rect, f64)> = samples
            .iter()
            .map(|sm| {
                let r = sm
                    .iter()
                    .fold(kurbo::Rect::from_points(sm[0].1, sm[0].1), |r, s| {
                        r.union_pt(s.1)
                    });
                let step = sm
                    .windows(2)
                    .map(|w| (w[1].1 - w[0].1).hypot())
                    .fold(0.0, f64::max);
                (r, step)
            })
            .collect();
        let box_distance = |r: &kurbo::Rect, q: Point| {
            let dx = (r.x0 - q.x).max(q.x - r.x1).max(0.0);
            let dy = (r.y0 - q.y).max(q.y - r.y1).max(0.0);
            dx.hypot(dy)
        };
        let (mut worst, mut sum) = (0.0f64, 0.0);
        // Each piece's largest deviation and its parameter.
        let mut piece_worst = vec![(0.0f64, 0.0f64); pieces.len()];
        for (q, &u) in fit.points.iter().zip(&fit.params) {
            let home = pieces
                .iter()
                .position(|p| u <= p.u_range.1)
                .unwrap_or(pieces.len() - 1);
            let mut best = (project(&pieces[home].rational, *q, &samples[home]).0, home);
            for (i, p) in pieces.iter().enumerate() {
                if i == home || box_distance(&boxes[i].0, *q) > best.0 + boxes[i].1 {
                    continue;
                }
                let d = project(&p.rational, *q, &samples[i]).0;
                if d < best.0 {
                    best = (d, i);
                }
            }
            let (d, i) = best;
            sum += d * d;
            worst = worst.max(d);
            if d > piece_worst[i].0 {
                piece_worst[i] = (d, u);
            }
        }
        let rms = (sum / fit.points.len() as f64).sqrt();
        if worst > opts.tolerance && slots.len() < opts.max_pieces {
            // Split the piece that misses a point most, where it misses most (kept off the
            // piece's ends); a piece with an inflection end at its mid-turn, so the
            // inflection piece left keeps a proper triangle. A line that has needed
            // BATCH_AFTER such splits needs many pieces: from then on every piece that misses
            // a point is split in the same round (the rounds, not the pieces, cost the time).
            // Later pieces first, so the earlier indices stay valid; the worst pieces first
            // within the piece budget.
            let mut over: Vec<usize> = (0..pieces.len())
                .filter(|&i| {
                    piece_worst[i].0 == worst
                        || (miss_splits >= BATCH_AFTER && piece_worst[i].0 > opts.tolerance)
                })
                .collect();
            over.sort_by(|&a, &b| piece_worst[b].0.total_cmp(&piece_worst[a].0));
            over.truncate(opts.max_pieces - slots.len());
            over.sort_unstable_by(|a, b| b.cmp(a));
            for i in over {
                split_worst(&track, &mut slots, i, piece_worst[i].1)?;
                miss_splits += 1;
            }
            continue;
        }
        if worst > opts.tolerance {
            return Err(Error::NoConvergence(format!(
                "{} pieces leave a deviation of {worst:.3e} above the tolerance {:.3e}",
                slots.len(),
                opts.tolerance
            )));
        }
        let kmax = pieces
            .iter()
            .map(|p| {
                p.rational
                    .kappa_start()
                    .abs()
                    .max(p.rational.kappa_end().abs())
            })
            .fold(0.0, f64::max);
        // Every joint, and a closed curve's seam.
        let seam = opts.closed.then(|| {
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
        return Ok(Sketch {
            inflections,
            curvature_extrema,
            bspline: fit.spline.clone(),
            bspline_deviation: fit.max_deviation,
            all_monotone: pieces.iter().all(|p| p.monotone),
            pieces,
            max_deviation: worst,
            rms_deviation: rms,
            max_curvature_jump: jump,
            g2: jump < 1e-6,
            fairing,
        });
    }
}

/// Split every piece whose end tangents do not form a control triangle (an S shape: an
/// inflection dropped as noise, or too flat to be found) at its smallest |κ|, an inflection
/// when κ changes sign there.
fn split_s_shapes(track: &Track, slots: &mut Vec<Slot>) -> Result<()> {
    let mut i = 0;
    let mut guard = 0;
    while i < slots.len() {
        let s = &slots[i];
        let ok = triangle(
            track.point(s.ua),
            track.direction(s.ua),
            track.point(s.ub),
            track.direction(s.ub),
        )
        .is_some();
        if ok {
            i += 1;
            continue;
        }
        guard += 1;
        if guard > 200 || (s.ub - s.ua) < 1e-9 {
            return Err(Error::Degenerate(
                "a piece of the curve has end tangents that form no triangle".into(),
            ));
        }
        let n = 64;
        let us: Vec<f64> = (1..n)
            .map(|k| s.ua + (s.ub - s.ua) * k as f64 / n as f64)
            .collect();
        let ks: Vec<f64> = us.iter().map(|&u| track.derivs(u).kappa()).collect();
        let k = (0..us.len())
            .min_by(|&a, &b| ks[a].abs().total_cmp(&ks[b].abs()))
            .unwrap();
        let changes =
            (k > 0 && ks[k - 1] * ks[k] <= 0.0) || (k + 1 < ks.len() && ks[k] * ks[k + 1] <= 0.0);
        let cut = if changes { Cut::Inflection } else { Cut::Other };
        let s = s.clone();
        let left = slot(track, (s.ua, s.cut_a), (us[k], cut));
        let right = slot(track, (us[k], cut), (s.ub, s.cut_b));
        slots.splice(i..=i, [left, right]);
    }
    Ok(())
}

/// The inflection-family cubic at (f0, w0) = (0.5, 1), measured like a fit.
fn inflection_fallback(seg: &LacInflectionSegment) -> Result<crate::approx::RationalCubicFit> {
    use crate::monotone::CurvatureMonotone;
    let curve = crate::approx::inflection_cubic(seg, 0.5, 1.0)
        .ok_or_else(|| Error::NoConvergence("no G2 cubic for an inflection piece".into()))?;
    let monotone = curve.is_curvature_monotone().unwrap_or(false);
    Ok(crate::approx::RationalCubicFit {
        curve,
        f0: 0.5,
        f1: 1.0,
        rms: f64::NAN,
        max_error: f64::NAN,
        monotone,
        evaluations: 1,
        // A fixed cubic, not an optimum.
        converged: false,
    })
}

/// Split `slots[i]` at parameter `u`, then any S-shaped results.
fn split_at(track: &Track, slots: &mut Vec<Slot>, i: usize, u: f64) -> Result<()> {
    let s = slots[i].clone();
    let left = slot(track, (s.ua, s.cut_a), (u, Cut::Other));
    let right = slot(track, (u, Cut::Other), (s.ub, s.cut_b));
    slots.splice(i..=i, [left, right]);
    split_s_shapes(track, slots)
}

/// Split `slots[i]` where it has turned half its turning, then any S-shaped results.
fn split_at_mid_turn(track: &Track, slots: &mut Vec<Slot>, i: usize) -> Result<()> {
    let (ua, ub) = (slots[i].ua, slots[i].ub);
    let mid = u_at_turn(track, ua, ub, 0.5 * track.angle_between(ua, ub).abs());
    split_at(track, slots, i, mid)
}

/// Diagonal of the bounding box.
/// The points of a stroke checked: finite, their extent within f64, and (two or more) not
/// all one point; their bounding box's diagonal (0 for fewer than two).
fn check_points(points: &[Point]) -> Result<f64> {
    if points.iter().any(|q| !q.is_finite()) {
        return Err(Error::invalid("points", "must be finite"));
    }
    if points.len() < 2 {
        return Ok(0.0);
    }
    let diagonal = bbox_diagonal(points);
    if !diagonal.is_finite() {
        return Err(Error::invalid(
            "points",
            "the coordinates are too large: their extent overflows f64",
        ));
    }
    if diagonal == 0.0 {
        return Err(Error::Degenerate(format!(
            "all {} points coincide: no curve runs through them",
            points.len()
        )));
    }
    Ok(diagonal)
}

fn bbox_diagonal(points: &[Point]) -> f64 {
    let (mut lo, mut hi) = (
        Point::new(f64::MAX, f64::MAX),
        Point::new(f64::MIN, f64::MIN),
    );
    for q in points {
        lo = Point::new(lo.x.min(q.x), lo.y.min(q.y));
        hi = Point::new(hi.x.max(q.x), hi.y.max(q.y));
    }
    (hi - lo).hypot()
}

/// Robust estimate of the standard deviation of the noise per coordinate: residuals at
/// each point of a local least-squares cubic in chord length over its 15 neighbours (the
/// spacing may be irregular), median absolute value over 0.6745, corrected for the fit's
/// own share of the noise (the centre's leverage, about 0.4 for 15 points and a cubic).
fn noise_level(points: &[Point]) -> f64 {
    let n = points.len();
    let half = 7;
    if n < 2 * half + 1 {
        return 0.0;
    }
    let mut s = vec![0.0; n];
    for i in 1..n {
        s[i] = s[i - 1] + (points[i] - points[i - 1]).hypot();
    }
    let mut res = Vec::with_capacity(2 * n);
    for k in half..n - half {
        let w = (s[k + half] - s[k - half]).max(f64::MIN_POSITIVE);
        let mut m = nalgebra::Matrix4::<f64>::zeros();
        let mut bx = nalgebra::Vector4::<f64>::zeros();
        let mut by = nalgebra::Vector4::<f64>::zeros();
        for j in k - half..=k + half {
            let t = (s[j] - s[k]) / w;
            let v = nalgebra::Vector4::new(1.0, t, t * t, t * t * t);
            m += v * v.transpose();
            bx += v * points[j].x;
            by += v * points[j].y;
        }
        if let Some(ch) = m.cholesky() {
            let (cx, cy) = (ch.solve(&bx), ch.solve(&by));
            res.push((points[k].x - cx[0]).abs());
            res.push((points[k].y - cy[0]).abs());
        }
    }
    if res.is_empty() {
        return 0.0;
    }
    let mid = res.len() / 2;
    let (_, m, _) = res.select_nth_unstable_by(mid, f64::total_cmp);
    *m / 0.6745 / (1.0f64 - 0.4).sqrt()
}

/// The same curve traversed the other way.
fn reverse(c: &RationalBezier) -> RationalBezier {
    let mut p = c.points().to_vec();
    let mut w = c.weights().to_vec();
    p.reverse();
    w.reverse();
    RationalBezier::new(p, w).expect("reversal keeps a valid curve")
}

/// Distance from `q` to a curve sampled at an odd number of points: each pair of
/// neighbouring chords is read as the parabola through its three points (chord plus the
/// bulge of its middle sample), which removes the chord's sagitta from the distance; the
/// nearest of all of them (no assumption that the points advance along the curve).
fn curve_distance(samples: &[Point], q: Point) -> f64 {
    let mut best = f64::INFINITY;
    let mut k = 0;
    while k + 2 < samples.len() {
        let (p0, p1, p2) = (samples[k], samples[k + 1], samples[k + 2]);
        let d = p2 - p0;
        let l2 = d.hypot2();
        let t = if l2 > 0.0 {
            ((q - p0).dot(d) / l2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let bulge = p1 - p0.midpoint(p2);
        let c = p0 + d * t + bulge * (4.0 * t * (1.0 - t));
        best = best.min((c - q).hypot2());
        k += 2;
    }
    best.sqrt()
}

/// Sum of squared and largest distance of `pts` to the LAC segment of shape `alpha` in
/// `tri`; `None` where the segment does not exist.
fn lac_cost(alpha: f64, tri: [Point; 3], pts: &[Point], cap: f64) -> Option<(f64, f64)> {
    let seg = LacSegment::new(alpha, tri).ok()?;
    let (k0, k1) = seg.end_curvatures().ok()?;
    if k0.abs().max(k1.abs()) > cap {
        return None;
    }
    let poly = seg.sample(129).ok()?.points;
    let (mut sum, mut max) = (0.0, 0.0f64);
    // The nearest sample by descent from the previous point's (either way: points may step
    // back), then the parabolic arcs around it.
    let mut j = 0usize;
    for q in pts {
        while j + 1 < poly.len() && (poly[j + 1] - *q).hypot2() <= (poly[j] - *q).hypot2() {
            j += 1;
        }
        while j > 0 && (poly[j - 1] - *q).hypot2() < (poly[j] - *q).hypot2() {
            j -= 1;
        }
        // Arcs start at even samples: the ones holding j and its neighbours.
        let lo = (j.saturating_sub(2)) & !1;
        let hi = (j + 4).min(poly.len());
        let d = curve_distance(&poly[lo..hi], *q);
        sum += d * d;
        max = max.max(d);
    }
    Some((sum, max))
}

/// How far a piece's end curvature may exceed the fair spline's largest curvature over
/// the piece in the fit of its α.
const HOOK_FACTOR: f64 = 4.0;

/// Weight of α against the joint tangent angles (radians) in the fairing's minimum-norm
/// step, which minimises Σ Δangle² + Σ Δα²/ALPHA_WEIGHT: with 1, a change of α by 1 costs as
/// much as a turn of 1 rad.
const ALPHA_WEIGHT: f64 = 1.0;

/// α of the LAC segment in `tri` closest to `pts` in the least-squares sense (point-to-curve
/// distances), and the largest distance of all `pts`: a scan over [`ALPHA_RANGE`] then
/// golden-section refinement to 1e-4, on at most 64 of the points (evenly spread; the
/// largest distance is measured on all). `None` when no α of the range gives a segment.
fn fit_alpha(tri: [Point; 3], all: &[Point], cap: f64) -> Option<(f64, f64)> {
    let sub = spread(all, 64);
    let pts = &sub[..];
    let (lo, hi) = ALPHA_RANGE;
    let steps = 20;
    let grid: Vec<(f64, f64)> = (0..=steps)
        .filter_map(|k| {
            let a = lo + (hi - lo) * k as f64 / steps as f64;
            lac_cost(a, tri, pts, cap).map(|c| (a, c.0))
        })
        .collect();
    let &(a0, _) = grid.iter().min_by(|x, y| x.1.total_cmp(&y.1))?;
    let h = (hi - lo) / steps as f64;
    let f = |a: f64| lac_cost(a, tri, pts, cap).map_or(f64::INFINITY, |c| c.0);
    let (mut a, mut b) = ((a0 - h).max(lo), (a0 + h).min(hi));
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..40 {
        if b - a < 1e-4 {
            break;
        }
        if fc <= fd {
            b = d;
            d = c;
            fd = fc;
            c = b - g * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + g * (b - a);
            fd = f(d);
        }
    }
    // The best of the refined point and the grid's (the refinement never loses it).
    let cand = [(0.5 * (a + b)), a0];
    let best = cand
        .iter()
        .copied()
        .filter(|&x| f(x).is_finite())
        .min_by(|x, y| f(*x).total_cmp(&f(*y)))?;
    lac_cost(best, tri, all, cap).map(|c| (best, c.1))
}

/// At most `n` of `pts`, evenly spread (every k-th), for the searches; results are measured
/// on all of them.
fn spread(pts: &[Point], n: usize) -> Vec<Point> {
    pts.iter()
        .step_by(pts.len().div_ceil(n).max(1))
        .copied()
        .collect()
}

/// The input points whose foot parameters lie in [ua, ub].
fn points_in(fit: &bspline::BSplineFit, ua: f64, ub: f64) -> Vec<Point> {
    fit.points
        .iter()
        .zip(&fit.params)
        .filter(|(_, u)| **u >= ua && **u <= ub)
        .map(|(q, _)| *q)
        .collect()
}

/// The curve's end points: the first and last input points.
type EndPoints = (Point, Point);

/// Where slot `s` starts and ends: on the track, or at the curve's end points.
fn slot_ends(track: &Track, s: &Slot, ends: EndPoints) -> (Point, Point) {
    let a = if s.cut_a == Cut::End {
        ends.0
    } else {
        track.point(s.ua)
    };
    let b = if s.cut_b == Cut::End {
        ends.1
    } else {
        track.point(s.ub)
    };
    (a, b)
}

/// The LAC piece of slot `s` (not an inflection piece) fitted to its input points: α by
/// least squares in the triangle of its end points and the track's tangents; with
/// `free_ends`, the tangent at an end of the whole curve is fitted too (Nelder–Mead over α
/// and the tangent angles, from the α of the fixed triangle). Returns the largest distance,
/// or `None` when the slot has no triangle or no segment.
fn fit_slot_alpha(
    track: &Track,
    fit: &bspline::BSplineFit,
    s: &mut Slot,
    ends: EndPoints,
    free_ends: bool,
) -> Option<f64> {
    if s.cut_a == Cut::Inflection || s.cut_b == Cut::Inflection {
        return None;
    }
    let (pa, pb) = slot_ends(track, s, ends);
    let (da, db) = (track.direction(s.ua), track.direction(s.ub));
    let tri = triangle(pa, da, pb, db)?;
    let pts = points_in(fit, s.ua, s.ub);
    if pts.len() < 3 {
        return None;
    }
    s.fitted = true;
    // No hooks: the segment's end curvatures stay within HOOK_FACTOR of the fair spline's
    // largest over the piece (near the edge of its existence region a segment's end
    // curvature grows without bound while its shape, and the distances, barely change).
    let cap = HOOK_FACTOR
        * (0..=32)
            .map(|k| track.abs_kappa(s.ua + (s.ub - s.ua) * k as f64 / 32.0))
            .fold(0.0, f64::max);
    let (alpha, max) = fit_alpha(tri, &pts, cap)?;
    s.alpha = Some(alpha);
    let (free_a, free_b) = (
        free_ends && s.cut_a == Cut::End,
        free_ends && s.cut_b == Cut::End,
    );
    if !(free_a || free_b) {
        return Some(max);
    }
    let sub = spread(&pts, 64);
    // Unknowns: α, then the turn of each free end tangent (only those).
    let ib = if free_a { 2 } else { 1 };
    let make = |x: &[f64]| {
        let a = if free_a { rotate(da, x[1]) } else { da };
        let b = if free_b { rotate(db, x[ib]) } else { db };
        (a, b)
    };
    let mut cost = |x: &[f64]| -> f64 {
        let (a, b) = make(x);
        triangle(pa, a, pb, b)
            .and_then(|t| lac_cost(x[0].clamp(ALPHA_RANGE.0, ALPHA_RANGE.1), t, &sub, cap))
            .map_or(f64::INFINITY, |c| c.0)
    };
    let n = 1 + usize::from(free_a) + usize::from(free_b);
    let start = [alpha, 0.0, 0.0];
    let step = [0.25, 0.01, 0.01];
    let scale = cost(&start[..n]);
    let m = crate::solve::nelder_mead(
        &mut cost,
        &start[..n],
        &step[..n],
        crate::solve::Options {
            f_tol: 1e-8 * scale,
            x_tol: 1e-4,
            max_evaluations: 150,
            ..Default::default()
        },
    );
    if m.value.partial_cmp(&scale) != Some(std::cmp::Ordering::Less) {
        return Some(max);
    }
    let (a, b) = make(&m.x);
    let alpha = m.x[0].clamp(ALPHA_RANGE.0, ALPHA_RANGE.1);
    let tri = triangle(pa, a, pb, b)?;
    let (_, max) = lac_cost(alpha, tri, &pts, cap)?;
    s.alpha = Some(alpha);
    s.dir_a = free_a.then_some(a);
    s.dir_b = free_b.then_some(b);
    Some(max)
}

/// Merge neighbouring pieces (across curvature-extremum cuts, never across inflections or
/// the curve's ends) while one LAC segment, α fitted by least squares, stays within
/// `limit` of the input points and turns less than `max_turn`: as few pieces as the
/// tolerance allows. Each remaining LAC slot gets its least-squares α.
fn merge_slots(
    track: &Track,
    fit: &bspline::BSplineFit,
    slots: &mut Vec<Slot>,
    ends: EndPoints,
    limit: f64,
    max_turn: f64,
) {
    for s in slots.iter_mut() {
        fit_slot_alpha(track, fit, s, ends, false);
    }
    // The merged slot of each neighbouring pair and its deviation (None: no merge),
    // recomputed only next to a merge.
    let pair = |a: &Slot, b: &Slot| -> Option<(Slot, f64)> {
        if a.cut_b != Cut::Other || track.angle_between(a.ua, b.ub).abs() > max_turn {
            return None;
        }
        let mut m = Slot {
            ua: a.ua,
            ub: b.ub,
            cut_a: a.cut_a,
            cut_b: b.cut_b,
            alpha: None,
            fitted: false,
            dir_a: None,
            dir_b: None,
        };
        // A merge with an inflection at one end is an inflection-end segment: its α comes
        // from its triangle; it merges when that segment fits the points.
        let infl_a = a.cut_a == Cut::Inflection;
        let infl_b = b.cut_b == Cut::Inflection;
        if infl_a || infl_b {
            if infl_a && infl_b {
                return None;
            }
            m.fitted = true;
            let (pa, pb) = slot_ends(track, &m, ends);
            let tri = triangle(pa, track.direction(m.ua), pb, track.direction(m.ub))?;
            let ctrl = if infl_a {
                tri
            } else {
                [tri[2], tri[1], tri[0]]
            };
            let seg = LacInflectionSegment::new(ctrl).ok()?;
            let poly = seg.sample(129).ok()?.points;
            let d = points_in(fit, m.ua, m.ub)
                .iter()
                .map(|q| curve_distance(&poly, *q))
                .fold(0.0, f64::max);
            return (d <= limit).then_some((m, d));
        }
        // A merge that reaches an end of the curve fits the tangent there too, when the
        // spline's tangent alone comes close.
        let d = fit_slot_alpha(track, fit, &mut m, ends, false)?;
        let touches_end = m.cut_a == Cut::End || m.cut_b == Cut::End;
        let d = if d > limit && d < 3.0 * limit && touches_end {
            fit_slot_alpha(track, fit, &mut m, ends, true)?
        } else {
            d
        };
        (d <= limit).then_some((m, d))
    };
    let mut pairs: Vec<Option<(Slot, f64)>> =
        slots.windows(2).map(|w| pair(&w[0], &w[1])).collect();
    loop {
        // The merge that leaves the smallest deviation first.
        let best = pairs
            .iter()
            .enumerate()
            .filter_map(|(i, p)| p.as_ref().map(|(_, d)| (i, *d)))
            .min_by(|x, y| x.1.total_cmp(&y.1));
        let Some((i, _)) = best else { break };
        let (m, _) = pairs[i].take().expect("chosen pair");
        slots.splice(i..=i + 1, [m]);
        pairs.remove(i);
        if i > 0 {
            pairs[i - 1] = pair(&slots[i - 1], &slots[i]);
        }
        if i < pairs.len() {
            pairs[i] = pair(&slots[i], &slots[i + 1]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn events_of_monotone_pieces() {
        // One bump: up then down, one sign: one extremum, no inflection.
        assert_eq!(count_events(&[(0.1, 0.3), (0.3, 0.2)]), (0, 1));
        // An S through an inflection joint (zero at the joint), monotone across it.
        assert_eq!(count_events(&[(0.2, 0.0), (0.0, -0.3)]), (1, 0));
        // A piece crossing zero inside, then turning back.
        assert_eq!(count_events(&[(0.2, -0.1), (-0.1, 0.05)]), (2, 1));
        // Constant curvature: nothing.
        assert_eq!(count_events(&[(0.5, 0.5), (0.5, 0.5)]), (0, 0));
    }

    #[test]
    fn curve_distance_removes_the_sagitta() {
        // Unit circle sampled coarsely: points on it are at distance ~0, the centre at 1.
        let samples: Vec<Point> = (0..=8)
            .map(|k| {
                let a = k as f64 * std::f64::consts::FRAC_PI_2 / 8.0;
                Point::new(a.cos(), a.sin())
            })
            .collect();
        let on = Point::new(0.3f64.cos(), 0.3f64.sin());
        let chord_only = polyline_like(&samples, on);
        assert!(curve_distance(&samples, on) < 0.05 * chord_only);
        assert!((curve_distance(&samples, Point::ZERO) - 1.0).abs() < 1e-3);
    }

    #[test]
    fn a_triangle_needs_tangents_that_meet_ahead() {
        let (a, b) = (Point::new(0.0, 0.0), Point::new(10.0, 0.0));
        let up = Vec2::from_angle(0.5);
        let down = Vec2::from_angle(-0.5);
        let t = triangle(a, up, b, down).expect("the tangents meet above the chord");
        assert!(
            (t[1] - Point::new(5.0, 5.0 * 0.5f64.tan())).hypot() < 1e-12,
            "{t:?}"
        );
        assert!(triangle(a, up, b, up).is_none(), "parallel tangents");
        assert!(triangle(a, up, b, -down).is_none(), "apex behind the end");
    }

    /// Two LAC pieces through (0, 0), (10, 3), (20, 0) (α 1 and -1) with the tangents given
    /// by their angles at the three points.
    fn two_pieces(angles: [f64; 3]) -> (Vec<Slot>, Vec<Point>, Vec<Vec2>) {
        let slot = |alpha: f64, cut_a: Cut, cut_b: Cut| Slot {
            ua: 0.0,
            ub: 1.0,
            cut_a,
            cut_b,
            alpha: Some(alpha),
            fitted: true,
            dir_a: None,
            dir_b: None,
        };
        let slots = vec![
            slot(1.0, Cut::End, Cut::Other),
            slot(-1.0, Cut::Other, Cut::End),
        ];
        let pts = vec![
            Point::new(0.0, 0.0),
            Point::new(10.0, 3.0),
            Point::new(20.0, 0.0),
        ];
        (
            slots,
            pts,
            angles.iter().map(|a| Vec2::from_angle(*a)).collect(),
        )
    }

    #[test]
    fn fairing_matches_the_curvature_at_a_joint_and_keeps_the_ends() {
        let (slots, pts, mut dirs) = two_pieces([0.5, 0.15, -0.6]);
        let ends = (dirs[0], dirs[2]);
        let opts = SketchOptions::with_tolerance(0.1);
        let before = build_all(&slots, &pts, &dirs).unwrap();
        let jump = |b: &[Built]| (b[1].kappa.0 - b[0].kappa.1).abs() / curvature_scale(b);
        assert!(
            jump(&before) > 0.01,
            "the start is not G2: {}",
            jump(&before)
        );
        let (built, report) = fair(&slots, &pts, &mut dirs, &opts).unwrap();
        assert!(report.converged && report.iterations >= 1, "{report:?}");
        assert!(report.final_jump <= opts.g2_tolerance, "{report:?}");
        assert!((report.initial_jump - jump(&before)).abs() < 1e-12);
        // The report is the built pieces' own mismatch; only the joint's tangent moved.
        assert!((jump(&built) - report.final_jump).abs() < 1e-15);
        assert_eq!((dirs[0], dirs[2]), ends);
        assert!(dirs[1].cross(Vec2::from_angle(0.15)).abs() > 1e-6);
    }

    #[test]
    fn fairing_that_cannot_move_says_so() {
        // No iteration allowed: the report says the jump is still there.
        let (slots, pts, mut dirs) = two_pieces([0.5, 0.15, -0.6]);
        let opts = SketchOptions {
            max_fairing_iterations: 0,
            ..SketchOptions::with_tolerance(0.1)
        };
        let start = dirs.clone();
        let (_, report) = fair(&slots, &pts, &mut dirs, &opts).unwrap();
        assert!(!report.converged && report.final_jump > 0.01, "{report:?}");
        assert_eq!(dirs[1], start[1]);
    }

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

    /// Distance to the chords alone, for comparison.
    fn polyline_like(poly: &[Point], q: Point) -> f64 {
        poly.windows(2)
            .map(|w| {
                let d = w[1] - w[0];
                let t = ((q - w[0]).dot(d) / d.hypot2()).clamp(0.0, 1.0);
                (w[0] + d * t - q).hypot()
            })
            .fold(f64::INFINITY, f64::min)
    }
}
