//! A G2 log-aesthetic spline through points (docs/math.md §7): the curve passes through
//! every point exactly, is G2 at every smooth point, and each span between two points is
//! made of log-aesthetic pieces of the requested α whose curvature is monotone (an S-shaped
//! span gets an inflection inside: two inflection-end halves). Corners and the open ends
//! are free: the span next to one leaves it as a circular arc, so points on a circle give
//! the circle. Every piece comes with its rational cubic (G2 to the piece at both ends,
//! curvature proven monotone by the exact test), so the spline exports like the sketch.
//!
//! With α = -1 the pieces are clothoid arcs: the spline of Euler spirals that Spiro
//! draws, solved here with an exact inflection inside every S-span.
//!
//! ## Rooms
//!
//! - `span`: one span from its tangents (a line, one segment, or an inflection pair);
//! - `system`: the G2 equations in the tangent angles and their Newton solve;
//! - `continuation`: where Newton stops short, the walk from an easy version of the
//!   problem (points on a line or a circle) to the points;
//! - `pieces`: the solved spans as segments in input coordinates and their cubics;
//! - `joins`: the cubics' end curvatures as their f64 coordinates read them, repaired
//!   where rounding moved them (short pieces far from the origin);
//! - `relax`: where the requested α fails, the walk from the clothoid spline (α = -1) to
//!   the nearest α each span can hold;
//! - here: the options, the result and the driver.

mod clothoid;
mod continuation;
mod joins;
mod pieces;
mod relax;
mod span;
mod system;

use crate::approx::ApproxOptions;
use crate::bezier::RationalBezier;
use crate::error::{Error, Result};
use crate::lac::MAX_ABS_ALPHA;
use kurbo::Point;

pub use pieces::{SplinePiece, SplinePieceKind};

/// The largest relative curvature jump a result may have (the spline's G2: 1e-10 of the
/// largest curvature); the solve aims at [`LacSplineOptions::g2_tolerance`].
pub const ACCEPTED_JUMP: f64 = 1e-10;

/// Newton steps of the direct solve at the requested α where the spline with the
/// inflection spans held ([`relax::held`]) has answered already: on 770 point sets (the α
/// sweep's kinds and 20 wavy points), 10 leave 4 more spans at another α than 60 do, in
/// half the time at α >= 0.
const HELD_DIRECT_ITERATIONS: usize = 10;

/// Options of [`lac_spline`].
#[derive(Clone, Debug)]
pub struct LacSplineOptions {
    /// α of every span (used where `span_alphas` is `None`).
    pub alpha: f64,
    /// α per span (one per span, in order), overriding `alpha`.
    pub span_alphas: Option<Vec<f64>>,
    /// The last point joins the first (a closed curve; the points do not repeat the first).
    pub closed: bool,
    /// Indices of the points that are corners (no tangent or curvature condition there).
    pub corners: Vec<usize>,
    /// Largest curvature jump at a smooth point over the largest curvature, the solve's
    /// target.
    pub g2_tolerance: f64,
    /// Newton steps at most.
    pub max_iterations: usize,
    /// Options of the rational cubic per piece.
    pub approx: ApproxOptions,
}

impl Default for LacSplineOptions {
    fn default() -> Self {
        LacSplineOptions {
            alpha: -1.0,
            span_alphas: None,
            closed: false,
            corners: Vec::new(),
            g2_tolerance: 1e-12,
            max_iterations: 60,
            approx: ApproxOptions::default(),
        }
    }
}

/// The result of [`lac_spline`].
#[derive(Clone, Debug)]
pub struct LacSpline {
    /// The pieces in curve order (a span gives one or more).
    pub pieces: Vec<SplinePiece>,
    /// The tangent direction (unit vector) at each point; at a corner, the outgoing one (the
    /// incoming is the previous piece's end tangent); at an open end, the curve's.
    pub tangents: Vec<kurbo::Vec2>,
    /// Newton steps taken.
    pub iterations: usize,
    /// The G2 target was met.
    pub converged: bool,
    /// Largest |κ in - κ out| at a smooth point over the largest |κ| of the segments.
    pub max_curvature_jump: f64,
    /// The same measured on the delivered rational cubics, at every join of two pieces
    /// but the corners (what a user's tool sees; an arc's cubic is tilted above rounding,
    /// see [`SplinePiece::monotone`]).
    pub max_cubic_jump: f64,
    /// Largest angle (radians) between the cubics' tangents at those joins.
    pub max_cubic_angle: f64,
    /// Every piece's rational cubic proven curvature-monotone.
    pub all_monotone: bool,
    /// Largest distance of a rational cubic from its segment.
    pub max_rational_error: f64,
    /// Inflections (sign changes of the curvature along the curve).
    pub inflections: usize,
    /// Curvature extrema at the points and joins (the pieces are monotone).
    pub curvature_extrema: usize,
    /// The curve is closed.
    pub closed: bool,
    /// The α each span was solved with: the requested one, or the nearest one it could
    /// hold (an S-span's halves of α ≥ 0 are clothoid-like whatever this says: see the
    /// pieces' own α).
    pub span_alphas: Vec<f64>,
    /// The spans whose α is not the requested one (the requested α had no G2 solution
    /// through the points, or none the solve found).
    pub relaxed_spans: Vec<usize>,
}

impl LacSpline {
    /// G2 as delivered: the solve converged and the cubics' curvature jumps at smooth
    /// points are below 1e-8 of the largest curvature.
    pub fn g2(&self) -> bool {
        self.converged && self.max_cubic_jump <= 1e-8
    }

    /// The rational cubics in curve order.
    pub fn rationals(&self) -> crate::Pieces<RationalBezier> {
        crate::Pieces(self.pieces.iter().map(|p| p.rational.clone()).collect())
    }
}

/// The G2 log-aesthetic spline through `points` (module documentation). Where the
/// requested α cannot be held by every span (no solution, or none found), the spans take
/// the nearest α that can (the walk from α = -1 of the room `relax`): the result's
/// `span_alphas` and `relaxed_spans` say which. Errors: fewer than 2 points (3 closed),
/// repeated consecutive points, a bad α or corner index ([`Error::InvalidInput`]); a span
/// no log-aesthetic curve can take ([`Error::NoSegment`]); the solve not reaching G2 at
/// any α ([`Error::NoConvergence`], naming the jump it reached at the requested one).
pub fn lac_spline(points: &[Point], opts: &LacSplineOptions) -> Result<LacSpline> {
    let problem = problem_of(points, opts)?;
    let requested = problem.alphas.clone();
    // α >= 0: the spans that need an inflection held in the clothoid family first (one
    // Newton run from the clothoid spline); where every span then has its α, that is the
    // answer.
    let held = relax::held(points, opts, &requested);
    if let Some((alphas, sol)) = held.as_ref().filter(|(a, _)| *a == requested) {
        let o = LacSplineOptions {
            span_alphas: Some(alphas.clone()),
            ..opts.clone()
        };
        if let Ok(s) = built(&problem_of(points, &o)?, sol, opts, &requested) {
            return Ok(s);
        }
    }
    // The solve's rescues (the wider family, continuation) only for the clothoid spline:
    // at other α the walk from it is the rescue, and a failing rescue costs tens of
    // Newton runs.
    let rescue = requested.iter().all(|&a| a == relax::ANCHOR);
    // Where the held spline answered, the direct solve only looks for a spline with every
    // span at its α, briefly: it converges in a few steps where it converges at all.
    let most = if held.is_some() {
        opts.max_iterations.min(HELD_DIRECT_ITERATIONS)
    } else {
        opts.max_iterations
    };
    let first = system::solve_in(&problem, opts.g2_tolerance, most, rescue).and_then(|sol| {
        if !relax::accepted(&sol) {
            return Err(Error::NoConvergence(format!(
                "the G2 solve stopped ({:?}) after {} steps with a curvature jump of \
                     {:.3e} of the largest curvature",
                sol.stop, sol.iterations, sol.jump
            )));
        }
        built(&problem, &sol, opts, &requested)
    });
    match first {
        Err(e @ (Error::NoConvergence(_) | Error::NoSegment(_))) => {
            let Some((alphas, sol)) = relax::walk(points, opts, &requested, held) else {
                return Err(e);
            };
            let o = LacSplineOptions {
                span_alphas: Some(alphas),
                ..opts.clone()
            };
            built(&problem_of(points, &o)?, &sol, opts, &requested).map_err(|_| e)
        }
        other => other,
    }
}

/// The spline of a solved problem: its pieces and cubics, and which spans hold another α
/// than `requested`.
fn built(
    problem: &system::Problem,
    sol: &system::Solution,
    opts: &LacSplineOptions,
    requested: &[f64],
) -> Result<LacSpline> {
    let problem = problem.solved_as(sol);
    let pieces = pieces::build(&problem, &sol.theta, &opts.approx)?;
    let mut spline = pieces::result(pieces, &problem, sol, opts.closed);
    // A span of α > 1 outside its existence region holds the nearest α that has a segment
    // (its pieces say which): that is its α too.
    spline.span_alphas = problem.alphas.clone();
    for p in &spline.pieces {
        if let (SplinePieceKind::Lac, Some(a)) = (p.kind, p.alpha) {
            spline.span_alphas[p.span] = a;
        }
    }
    spline.relaxed_spans = (0..requested.len())
        .filter(|&k| spline.span_alphas[k] != requested[k])
        .collect();
    Ok(spline)
}

/// The G2 solve alone, without the pieces' cubics: the tangent angle at every point
/// (radians; `None` at a free point: an open end or a corner), the Newton steps and the
/// curvature jump reached. What libspiro's `run_spiro` computes for its clothoids; the
/// benchmark against it (`benches/spiro_compare.rs`) times this and the whole spline.
pub fn lac_spline_tangents(points: &[Point], opts: &LacSplineOptions) -> Result<SplineTangents> {
    let problem = problem_of(points, opts)?;
    let sol = system::solve(&problem, opts.g2_tolerance, opts.max_iterations)?;
    Ok(SplineTangents {
        angles: problem
            .unknown
            .iter()
            .map(|u| u.map(|u| sol.theta[u]))
            .collect(),
        iterations: sol.iterations,
        max_curvature_jump: sol.jump,
    })
}

/// What [`lac_spline_tangents`] returns.
#[derive(Clone, Debug, PartialEq)]
pub struct SplineTangents {
    /// The tangent angle at each point, `None` at a free point.
    pub angles: Vec<Option<f64>>,
    /// Newton steps.
    pub iterations: usize,
    /// Largest relative curvature jump at a smooth point.
    pub max_curvature_jump: f64,
}

/// Validate the input and lay out the unknowns.
fn problem_of<'a>(points: &'a [Point], opts: &LacSplineOptions) -> Result<system::Problem<'a>> {
    let n = points.len();
    let least = if opts.closed { 3 } else { 2 };
    if n < least {
        return Err(Error::invalid(
            "points",
            format!(
                "need at least {least} points for an {} curve",
                kind(opts.closed)
            ),
        ));
    }
    if let Some(i) = points.iter().position(|p| !p.is_finite()) {
        return Err(Error::invalid("points", format!("point {i} is not finite")));
    }
    let spans = if opts.closed { n } else { n - 1 };
    let ends: Vec<(usize, usize)> = (0..spans).map(|k| (k, (k + 1) % n)).collect();
    let size = points
        .iter()
        .map(|p| (*p - points[0]).hypot())
        .fold(0.0f64, f64::max);
    if let Some(k) = ends
        .iter()
        .position(|&(i, j)| (points[j] - points[i]).hypot() <= 1e-12 * size)
    {
        return Err(Error::Degenerate(format!(
            "points {} and {} coincide: a span needs two distinct points",
            ends[k].0, ends[k].1
        )));
    }
    let alphas = span_alphas(opts, spans)?;
    let mut free = vec![false; n];
    for &c in &opts.corners {
        *free.get_mut(c).ok_or_else(|| {
            Error::invalid(
                "corners",
                format!("corner index {c} is not a point (0..{n})"),
            )
        })? = true;
    }
    if !opts.closed {
        free[0] = true;
        free[n - 1] = true;
    }
    let smooth: Vec<usize> = (0..n).filter(|&i| !free[i]).collect();
    let mut unknown = vec![None; n];
    for (u, &p) in smooth.iter().enumerate() {
        unknown[p] = Some(u);
    }
    Ok(system::Problem {
        points,
        alphas,
        half: span::HALF_TURN,
        roots: (0..spans)
            .map(|_| std::sync::atomic::AtomicU64::new(f64::NAN.to_bits()))
            .collect(),
        chords: system::chords_of(points, &ends),
        ends,
        unknown,
        smooth,
        branch: None,
    })
}

fn kind(closed: bool) -> &'static str {
    if closed {
        "closed"
    } else {
        "open"
    }
}

/// α of each span, checked.
fn span_alphas(opts: &LacSplineOptions, spans: usize) -> Result<Vec<f64>> {
    let alphas = match &opts.span_alphas {
        Some(a) if a.len() != spans => {
            return Err(Error::invalid(
                "alphas",
                format!("need one alpha per span ({spans}), got {}", a.len()),
            ))
        }
        Some(a) => a.clone(),
        None => vec![opts.alpha; spans],
    };
    if let Some(a) = alphas
        .iter()
        .find(|a| !(a.is_finite() && a.abs() <= MAX_ABS_ALPHA))
    {
        return Err(Error::invalid(
            "alpha",
            format!("{a} is not a finite number within ±{MAX_ABS_ALPHA}"),
        ));
    }
    Ok(alphas)
}
