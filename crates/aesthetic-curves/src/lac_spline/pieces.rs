//! The solved spans as segments in input coordinates, each with its rational cubic. A
//! segment without a curvature-monotone cubic (it turns too far for one) is split in two
//! halves of its turning, the same curve, until each half has one.

use super::span::{triangle, Shape};
use super::system::{Problem, Solution};
use super::LacSpline;
use crate::approx::{
    fit_inflection_cubic, fit_rational_cubic, fit_rational_cubic_from_table, ApproxOptions,
    RationalCubicFit,
};
use crate::bezier::RationalBezier;
use crate::error::{Error, Result};
use crate::lac::{cdiv, cmul, conj, tangents_meet, LacInflectionSegment, LacSegment};
use kurbo::{Point, Vec2};

/// Splits of one segment at most (a piece turns 1/32 of its segment at the least).
const MAX_SPLITS: usize = 5;

/// Kind of a piece of the spline.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SplinePieceKind {
    /// A straight line (zero curvature).
    Line,
    /// A LAC segment in its control triangle.
    Lac,
    /// A segment with an inflection (zero curvature) at one end.
    LacInflection,
}

impl SplinePieceKind {
    /// `"line"`, `"lac"` or `"lac_inflection"` (the protocol's names, as the sketch's).
    pub fn as_str(&self) -> &'static str {
        match self {
            SplinePieceKind::Line => "line",
            SplinePieceKind::Lac => "lac",
            SplinePieceKind::LacInflection => "lac_inflection",
        }
    }
}

/// One piece of the spline, in curve order.
#[derive(Clone, Debug)]
pub struct SplinePiece {
    /// Which family.
    pub kind: SplinePieceKind,
    /// The span (from point `span` to the next) it belongs to.
    pub span: usize,
    /// Its α (`None` for a line).
    pub alpha: Option<f64>,
    /// Control triangle in curve order: start, tangent intersection, end (a line's middle
    /// point is its midpoint).
    pub control: [Point; 3],
    /// Signed curvature at the start and at the end.
    pub end_curvatures: (f64, f64),
    /// The rational cubic, in curve order.
    pub rational: RationalBezier,
    /// Largest distance of the rational cubic from the segment.
    pub rational_error: f64,
    /// The rational cubic's curvature is monotone, proven by the exact test (a line's is
    /// constant).
    pub monotone: bool,
}

/// A segment and whether its own order (`control[0]` first) is the curve's.
enum Part {
    Lac(LacSegment, bool),
    Inflection(LacInflectionSegment, bool),
}

/// Every span's pieces at the solved tangents, in curve order (the spans fitted in
/// parallel: each is pure work on its own data).
pub(super) fn build(
    problem: &Problem,
    theta: &[f64],
    approx: &ApproxOptions,
) -> Result<Vec<SplinePiece>> {
    use rayon::prelude::*;
    let spans: Vec<Result<Vec<SplinePiece>>> = (0..problem.ends.len())
        .into_par_iter()
        .map(|k| span_pieces(problem, theta, k, approx))
        .collect();
    let mut out = Vec::new();
    for s in spans {
        out.extend(s?);
    }
    Ok(out)
}

/// The pieces of span `k`, in curve order.
fn span_pieces(
    problem: &Problem,
    theta: &[f64],
    k: usize,
    approx: &ApproxOptions,
) -> Result<Vec<SplinePiece>> {
    let solved = problem.span(k, theta)?;
    let (i, j) = problem.ends[k];
    let frame = Frame {
        a: problem.points[i],
        b: problem.points[j],
    };
    let (da, db) = problem.deviations(k, theta);
    match solved.shape {
        Shape::Line => Ok(vec![line(k, frame.a, frame.b)]),
        Shape::Arc { turn } => arcs(&frame, da, turn)
            .into_iter()
            .map(|tri| arc_piece(k, problem.alphas[k], tri, approx))
            .collect(),
        Shape::Lac { alpha } if da.abs() + db.abs() >= std::f64::consts::PI => {
            let mut out = Vec::new();
            for tri in long_halves(alpha, da, db)? {
                let seg = segment_in(alpha, frame.triangle(tri))?;
                out.extend(fit(k, Part::Lac(seg, true), approx, 0)?);
            }
            Ok(out)
        }
        Shape::Lac { alpha } => {
            let seg = segment_in(alpha, frame.triangle(triangle(da, db)))?;
            fit(k, Part::Lac(seg, true), approx, 0)
        }
        Shape::Pair {
            alpha,
            psi,
            side,
            scale,
            inflection,
        } => {
            let pair = PairHalves {
                frame: &frame,
                alpha,
                psi,
                side,
                scale,
                inflection,
            };
            let (first, second) = (pair.half(da, true)?, pair.half(db, false)?);
            let (first_empty, second_empty) = (first.is_empty(), second.is_empty());
            // A half of no turning (at the existence region's edge) still spans the short
            // way from the inflection to its point: a straight piece, so that the span ends
            // exactly at its points.
            let m = frame.point(inflection);
            let mut out = Vec::new();
            if first_empty && m != frame.a {
                out.push(line(k, frame.a, m));
            }
            for part in first.into_iter().chain(second) {
                out.extend(fit(k, part, approx, 0)?);
            }
            if second_empty && m != frame.b {
                out.push(line(k, m, frame.b));
            }
            Ok(out)
        }
    }
}

/// A span's segment turning half a turn or more (no control triangle holds it), in the
/// chord frame: the segment of shape `alpha` from the Λ solve and its standard form, mapped
/// onto the chord by the similarity (with or without a reflection) that sends its start
/// tangent along `da`; returned as the control triangles of its two halves by turning,
/// each a segment of the same curve.
fn long_halves(alpha: f64, da: f64, db: f64) -> Result<[[Point; 3]; 2]> {
    let theta_d = da.abs() + db.abs();
    let (std, (t0, t1), _) = LacSegment::solved_standard(alpha, theta_d, da.abs().max(db.abs()))?;
    // The standard form's start is the high-curvature end: the span's start when |a| >= |b|.
    let (ts, te) = if da.abs() >= db.abs() {
        (t0, t1)
    } else {
        (t1, t0)
    };
    let dir = |t: f64| Vec2::from_angle(t) * (te - ts).signum();
    let tm = 0.5 * (t0 + t1);
    let (ps, pm, pe) = (
        std.eval(ts)?.to_vec2(),
        std.eval(tm)?.to_vec2(),
        std.eval(te)?.to_vec2(),
    );
    // z -> f (z - ps), or the same of the conjugates: ps to 0, pe to 1.
    let maps = [false, true].map(|m| {
        let c = |v: Vec2| if m { conj(v) } else { v };
        let f = cdiv(Vec2::new(1.0, 0.0), c(pe) - c(ps));
        (m, f)
    });
    let start = Vec2::from_angle(da);
    let (m, f) = maps
        .into_iter()
        .max_by(|x, y| {
            let d = |(m, f): (bool, Vec2)| {
                let v = cmul(f, if m { conj(dir(ts)) } else { dir(ts) });
                v.normalize().dot(start)
            };
            d(*x).total_cmp(&d(*y))
        })
        .expect("two maps");
    let c = |v: Vec2| if m { conj(v) } else { v };
    let mid = cmul(f, c(pm) - c(ps)).to_point();
    let tangent = cmul(f, c(dir(tm))).normalize();
    let meet = |p: Point, dp: Vec2, q: Point, dq: Vec2| -> Result<Point> {
        tangents_meet(p, dp, q, dq)
            .ok_or_else(|| Error::Degenerate("a half's end tangents are parallel".into()))
    };
    let (a, b) = (Point::ZERO, Point::new(1.0, 0.0));
    let end = Vec2::from_angle(db);
    Ok([
        [a, meet(a, start, mid, tangent)?, mid],
        [mid, meet(mid, tangent, b, end)?, b],
    ])
}

/// The map from a span's chord frame (start 0, end 1) to the input.
struct Frame {
    a: Point,
    b: Point,
}

impl Frame {
    fn point(&self, z: Vec2) -> Point {
        self.a + cmul(self.b - self.a, z)
    }
    /// A triangle of the chord frame in the input (the chord's ends exactly).
    fn triangle(&self, t: [Point; 3]) -> [Point; 3] {
        t.map(|p| {
            if p == Point::new(1.0, 0.0) {
                self.b
            } else {
                self.point(p.to_vec2())
            }
        })
    }
    /// The unit vector at angle `x` from the chord.
    fn direction(&self, x: f64) -> Vec2 {
        let c = self.b - self.a;
        let g = c.y.atan2(c.x);
        Vec2::from_angle(g + x)
    }
}

/// An S-span's two inflection-end halves in input coordinates (`Shape::Pair`'s fields).
struct PairHalves<'a> {
    frame: &'a Frame,
    alpha: f64,
    psi: f64,
    side: f64,
    scale: f64,
    inflection: Vec2,
}

impl PairHalves<'_> {
    /// The half from the inflection to the span's start (`first`, tangent deviation `d`
    /// there) or its end, as parts in curve order: one inflection-end segment where it
    /// turns less than a half turn (its control triangle), else (the wider family,
    /// [`super::span::WIDE_HALF`]) the inflection-end segment of its first half of turning
    /// and the segment of the same α that continues it, each from its own triangle on the
    /// curve's points and tangents there (as [`LacInflectionSegment::split`] makes them).
    fn half(&self, d: f64, first: bool) -> Result<Vec<Part>> {
        let f = self.frame;
        let (m, dm) = (f.point(self.inflection), f.direction(self.psi));
        let (end, de) = (if first { f.a } else { f.b }, f.direction(d));
        let turn = self.side * (d - self.psi);
        if turn <= 1e-12 * std::f64::consts::PI {
            // A half of no turning (the pair at the existence region's edge is the other
            // half alone): no segment (the caller joins the inflection to the point).
            return Ok(Vec::new());
        }
        if turn < std::f64::consts::PI {
            let seg = inflection_segment((self.alpha, turn), m, dm, end, de)?;
            return Ok(vec![Part::Inflection(seg, !first)]);
        }
        // The point at turning τ from the inflection, in the chord frame: the standard
        // segment's, turned to ψ, mirrored for side -1, scaled, backwards for the first.
        let tau = 0.5 * turn;
        let w = LacInflectionSegment::standard_chord(self.alpha, tau)?;
        let w = cmul(Vec2::from_angle(self.psi), Vec2::new(w.x, self.side * w.y)) * self.scale;
        let q = f.point(if first {
            self.inflection - w
        } else {
            self.inflection + w
        });
        let dq = f.direction(self.psi + self.side * tau);
        let head = inflection_segment((self.alpha, tau), m, dm, q, dq)?;
        let apex = tangents_meet(q, dq, end, de)
            .ok_or_else(|| Error::Degenerate("a half's tangents are parallel".into()))?;
        Ok(if first {
            let tail = LacSegment::new(self.alpha, [end, apex, q])?;
            vec![Part::Lac(tail, true), Part::Inflection(head, false)]
        } else {
            let tail = LacSegment::new(self.alpha, [q, apex, end])?;
            vec![Part::Inflection(head, true), Part::Lac(tail, true)]
        })
    }
}

/// The inflection-end segment of shape α turning θ_d (`shape`) from the inflection `m`
/// (tangent `dm`) to the end `p` (tangent `dp`): the triangle from where the two tangent
/// lines meet, α and θ_d the pair's own (not solved again from the triangle:
/// [`LacInflectionSegment::with_shape`]).
fn inflection_segment(
    (alpha, theta_d): (f64, f64),
    m: Point,
    dm: Vec2,
    p: Point,
    dp: Vec2,
) -> Result<LacInflectionSegment> {
    let apex = tangents_meet(m, dm, p, dp)
        .ok_or_else(|| Error::Degenerate("an inflection half's tangents are parallel".into()))?;
    LacInflectionSegment::with_shape(alpha, theta_d, [m, apex, p])
}

fn line(span: usize, a: Point, b: Point) -> SplinePiece {
    let at = |t: f64| a + (b - a) * t;
    SplinePiece {
        kind: SplinePieceKind::Line,
        span,
        alpha: None,
        control: [a, at(0.5), b],
        end_curvatures: (0.0, 0.0),
        rational: RationalBezier::new(vec![a, at(1.0 / 3.0), at(2.0 / 3.0), b], vec![1.0; 4])
            .expect("a line's cubic is valid"),
        rational_error: 0.0,
        monotone: true,
    }
}

/// A circular arc leaving the chord at `da` and turning `turn`, as the isosceles triangles
/// of equal arcs of at most a quarter turn each.
fn arcs(frame: &Frame, da: f64, turn: f64) -> Vec<[Point; 3]> {
    let parts = (turn.abs() / std::f64::consts::FRAC_PI_2).ceil().max(1.0) as usize;
    let step = turn / parts as f64;
    // On the arc, the point at turning τ from the start: the chord from the start is at
    // angle da + τ/2 with length sin(τ/2)/sin(turn/2) (chord 1).
    let at = |tau: f64| -> Vec2 {
        Vec2::from_angle(da + 0.5 * tau) * ((0.5 * tau).sin() / (0.5 * turn).sin())
    };
    (0..parts)
        .map(|i| {
            let (t0, t1) = (step * i as f64, step * (i + 1) as f64);
            let p0 = if i == 0 { frame.a } else { frame.point(at(t0)) };
            let p2 = if i + 1 == parts {
                frame.b
            } else {
                frame.point(at(t1))
            };
            let tangent = frame.direction(da + t0);
            let half = (p2 - p0).hypot() / (2.0 * (0.5 * step).cos());
            [p0, p0 + tangent * half, p2]
        })
        .collect()
}

/// The piece of an arc in the isosceles triangle `t`: the cubic of the log-aesthetic
/// segment next to it that the exact test proves monotone ([`tilted`]), or, where none
/// is, the exact arc's cubic reported as not proven.
fn arc_piece(
    span: usize,
    alpha: f64,
    t: [Point; 3],
    approx: &ApproxOptions,
) -> Result<SplinePiece> {
    if let Some((seg, f)) = tilted(alpha, t, approx) {
        return piece(span, &Part::Lac(seg, true), f);
    }
    let (theta_d, _) = LacSegment::triangle_angles(t)?;
    let c = (0.5 * theta_d).cos();
    let f = 2.0 * c / (1.0 + 2.0 * c);
    let w = (2.0 * c + 1.0) / 3.0;
    let curve = RationalBezier::new(
        vec![
            t[0],
            t[0] + (t[1] - t[0]) * f,
            t[2] + (t[1] - t[2]) * f,
            t[2],
        ],
        vec![1.0, w, w, 1.0],
    )?;
    let side = (t[1] - t[0]).cross(t[2] - t[1]).signum();
    let k = side * 2.0 * (0.5 * theta_d).sin() / (t[2] - t[0]).hypot();
    Ok(SplinePiece {
        kind: SplinePieceKind::Lac,
        span,
        alpha: Some(alpha),
        control: t,
        end_curvatures: (k, k),
        rational: curve,
        rational_error: 0.0,
        monotone: false,
    })
}

/// The segment of shape `alpha` in the triangle `t`; where rounding puts the triangle's
/// measured base angles just below the circle's (the span solved it as a circle, or within
/// 1e-8 of its turning of one), the segment with the start tangent turned from the chord by
/// 1e-14 of its base angle (then by tens): the circle to that accuracy.
fn segment_in(alpha: f64, t: [Point; 3]) -> Result<LacSegment> {
    match LacSegment::new(alpha, t) {
        Err(Error::NoSegment(m)) => {
            let (theta_d, phi) = LacSegment::triangle_angles(t)?;
            if phi - 0.5 * theta_d > 1e-8 * theta_d {
                return Err(Error::NoSegment(m));
            }
            (0..6)
                .find_map(|k| {
                    let turned = turned_triangle(t, true, 1e-14 * 10f64.powi(k))?;
                    LacSegment::new(alpha, turned).ok()
                })
                .ok_or(Error::NoSegment(m))
        }
        other => other,
    }
}

/// The pieces of one segment in curve order: its cubic, or (when it has no monotone one)
/// the pieces of its two halves.
fn fit(span: usize, part: Part, approx: &ApproxOptions, depth: usize) -> Result<Vec<SplinePiece>> {
    let fitted = fit_cubic(&part, approx);
    let tilt = |seg: &LacSegment, fwd: bool| {
        tilted(seg.alpha(), seg.control(), approx).map(|(t, f)| (Part::Lac(t, fwd), f))
    };
    match (fitted, &part) {
        (Ok(f), _) if f.monotone => Ok(vec![piece(span, &part, f)?]),
        (Ok(f), Part::Lac(seg, fwd)) => match tilt(seg, *fwd) {
            Some((p, f)) => Ok(vec![piece(span, &p, f)?]),
            None => Ok(vec![piece(span, &part, f)?]),
        },
        (Ok(f), _) => Ok(vec![piece(span, &part, f)?]),
        (Err(Error::NoSegment(m)), _) => {
            if let Part::Lac(seg, fwd) = &part {
                if let Some((p, f)) = tilt(seg, *fwd) {
                    return Ok(vec![piece(span, &p, f)?]);
                }
            }
            if depth >= MAX_SPLITS {
                return Err(Error::NoSegment(m));
            }
            let (first, second) = halves(&part)?;
            let mut out = fit(span, first, approx, depth + 1)?;
            out.extend(fit(span, second, approx, depth + 1)?);
            Ok(out)
        }
        (Err(e), _) => Err(e),
    }
}

/// Tilts tried, in powers of ten from the smallest.
const TILTS: i32 = 5;

/// The least bend (radians, both tangents' deviations from the chord) of an arc whose
/// circle cubic is tried first by [`tilted`].
const ARC_FIRST_BEND: f64 = 0.05;

/// A segment whose cubic the exact test cannot prove monotone because its curvature varies
/// by less than the rounding of its control points: a circular arc (the f64 arc is an
/// ellipse's by a relative 1e-16, with a curvature extremum in the middle, docs/math.md
/// §2), or a nearly circular or nearly straight piece far from the origin. Its high-
/// curvature end's tangent turned away from the chord by δ of its base angle makes a
/// log-aesthetic segment whose curvature varies by about δ more from end to end, which the
/// exact test proves monotone once δ is well above the coordinates' rounding relative to
/// the piece's bend (its sagitta, about chord × θ_d / 8, is what its curvature is read
/// from). Near the rounding the exact test is slow (its f64 filter cannot decide, and the
/// Sturm sequences of the nearly degenerate polynomial grow long: tens of milliseconds a
/// try), so the first δ is well above it, δ₀ = 100 ε |x|max / (chord θ_d), between 1e-12
/// and 1e-9 (the end curvatures move by about δ, which must stay well below the 1e-8 of
/// [`LacSpline::g2`](super::LacSpline::g2)); then up by tens, the first whose cubic is
/// monotone. The ends stay exact; that end's tangent turns by δ φ, and the spline's
/// measure of its cubics reports the curvature steps. An arc bent by more than
/// [`ARC_FIRST_BEND`] tries the circle's own cubic first (tilted by 1e-13, which the fit
/// still takes for an arc: one cheap verdict, which often proves it). The ladder is then
/// climbed with fits from the table's starts alone ([`fit_from_table`]: a failing try
/// costs a few refinements), and only where none is monotone with the whole search.
fn tilted(
    alpha: f64,
    c: [Point; 3],
    approx: &ApproxOptions,
) -> Option<(LacSegment, RationalCubicFit)> {
    let chord = c[2] - c[0];
    let reach = c
        .iter()
        .fold(0.0f64, |m, p| m.max(p.x.abs()).max(p.y.abs()));
    let (e0, e2) = base_angles(c);
    let bend = (e0.abs() + e2.abs()).max(f64::MIN_POSITIVE);
    let first = (100.0 * f64::EPSILON * reach / (chord.hypot() * bend)).clamp(1e-12, 1e-9);
    let turned = |d: f64| {
        let t = turned_triangle(c, e0.abs() >= e2.abs(), d)?;
        LacSegment::new(alpha, t).ok()
    };
    let tilt = |k: i32| first * 10f64.powi(k);
    // A bent arc tilted by 1e-13 keeps its legs equal within the fit's test of an arc, so
    // its cubic is the circle's own, whose exact verdict is cheap there and often proves
    // it (the rounding tilts it as well): tried first, where the bend is clear of the
    // flat arcs whose verdicts are slow.
    let circle_tilt = (bend > ARC_FIRST_BEND)
        .then(|| {
            let seg = turned(1e-13)?;
            let f = fit_from_table(&seg, approx)?;
            (f.monotone && f.evaluations == 0).then_some((seg, f))
        })
        .flatten();
    let quick = circle_tilt.or_else(|| {
        (0..TILTS).find_map(|k| {
            let seg = turned(tilt(k))?;
            let f = fit_from_table(&seg, approx)?;
            f.monotone.then_some((seg, f))
        })
    });
    quick.or_else(|| {
        (0..TILTS).find_map(|k| {
            let seg = turned(tilt(k))?;
            let f = fit_cubic(&Part::Lac(seg.clone(), true), approx).ok()?;
            f.monotone.then_some((seg, f))
        })
    })
}

/// A LAC segment's cubic from the table's starts alone
/// ([`crate::approx::fit_rational_cubic_from_table`]), fitted with its start at the origin
/// and moved back as [`fit_cubic`] does; `None` where that gives no cubic proven
/// monotone in place.
fn fit_from_table(seg: &LacSegment, approx: &ApproxOptions) -> Option<RationalCubicFit> {
    let c = seg.control();
    let o = c[0].to_vec2();
    let local = LacSegment::new(seg.alpha(), c.map(|p| p - o)).ok()?;
    let f = fit_rational_cubic_from_table(&local, approx).ok()??;
    moved_back(f, c, o)
}

/// A cubic fitted with its segment's start moved to the origin (by `-o`), moved back onto
/// the triangle `c` (its ends exactly `c`'s) and proven again in place.
fn moved_back(f: RationalCubicFit, c: [Point; 3], o: Vec2) -> Option<RationalCubicFit> {
    use crate::monotone::CurvatureMonotone;
    let mut pts: Vec<Point> = f.curve.points().iter().map(|p| *p + o).collect();
    pts[0] = c[0];
    pts[3] = c[2];
    let curve = RationalBezier::new(pts, f.curve.weights().to_vec()).ok()?;
    let monotone = curve.is_curvature_monotone().ok()?;
    Some(RationalCubicFit {
        curve,
        monotone,
        ..f
    })
}

/// The signed angles of a triangle's start and end tangents from its chord.
fn base_angles(c: [Point; 3]) -> (f64, f64) {
    let chord = (c[2] - c[0]).angle();
    (
        wrap((c[1] - c[0]).angle() - chord),
        wrap(chord - (c[2] - c[1]).angle()),
    )
}

/// The triangle `c` with its start tangent (`at_start`) or its end tangent turned away from
/// the chord by `d` of its angle to it, the other tangent and both ends kept.
fn turned_triangle(c: [Point; 3], at_start: bool, d: f64) -> Option<[Point; 3]> {
    let chord = c[2] - c[0];
    let (e0, e2) = base_angles(c);
    let apex = if at_start {
        let dir = Vec2::from_angle(chord.angle() + e0 * (1.0 + d));
        tangents_meet(c[0], dir, c[2], c[1] - c[2])
    } else {
        let dir = Vec2::from_angle((-chord).angle() - e2 * (1.0 + d));
        tangents_meet(c[2], dir, c[0], c[1] - c[0])
    }?;
    Some([c[0], apex, c[2]])
}

/// `x` wrapped into (-π, π].
fn wrap(x: f64) -> f64 {
    super::system::wrap(x)
}

/// A segment's cubic, fitted with its start moved to the origin and moved back: a piece
/// far from the origin has the same shape with less rounding in its control points, and
/// the search for a monotone cubic of a short piece, which meets the rounding in every
/// candidate's verdict there, is some 25 times faster. The moved-back cubic is proven
/// monotone again by the exact test; where it is not, the fit in place.
fn fit_cubic(part: &Part, approx: &ApproxOptions) -> Result<RationalCubicFit> {
    let in_place = || match part {
        Part::Lac(seg, _) => fit_rational_cubic(seg, approx),
        Part::Inflection(seg, _) => fit_inflection_cubic(seg, approx),
    };
    let c = match part {
        Part::Lac(seg, _) => seg.control(),
        Part::Inflection(seg, _) => seg.control(),
    };
    let o = c[0].to_vec2();
    if o == Vec2::ZERO {
        return in_place();
    }
    let local = c.map(|p| p - o);
    let fitted = match part {
        Part::Lac(seg, _) => {
            LacSegment::new(seg.alpha(), local).and_then(|s| fit_rational_cubic(&s, approx))
        }
        // α and θ_d kept, not solved again from the moved triangle (ill-conditioned
        // where thin).
        Part::Inflection(seg, _) => {
            LacInflectionSegment::with_shape(seg.alpha(), seg.theta_d(), local)
                .and_then(|s| fit_inflection_cubic(&s, approx))
        }
    };
    let back = fitted.ok().and_then(|f| {
        let was_monotone = f.monotone;
        moved_back(f, c, o).filter(|b| b.monotone || !was_monotone)
    });
    match back {
        Some(f) => Ok(f),
        None => in_place(),
    }
}

/// The two halves of a segment by turning, in curve order.
fn halves(part: &Part) -> Result<(Part, Part)> {
    Ok(match part {
        Part::Lac(seg, fwd) => {
            let h = 0.5 * seg.theta_d();
            let (x, y) = (seg.sub_segment(0.0, h)?, seg.sub_segment(h, seg.theta_d())?);
            if *fwd {
                (Part::Lac(x, true), Part::Lac(y, true))
            } else {
                (Part::Lac(y, false), Part::Lac(x, false))
            }
        }
        Part::Inflection(seg, fwd) => {
            let (head, tail) = seg.split(0.5 * seg.theta_d())?;
            if *fwd {
                (Part::Inflection(head, true), Part::Lac(tail, true))
            } else {
                (Part::Lac(tail, false), Part::Inflection(head, false))
            }
        }
    })
}

/// A fitted segment as a piece in curve order.
fn piece(span: usize, part: &Part, f: RationalCubicFit) -> Result<SplinePiece> {
    let (kind, alpha, control, kappa, forward) = match part {
        Part::Lac(seg, fwd) => (
            SplinePieceKind::Lac,
            seg.alpha(),
            seg.control(),
            seg.end_curvatures()?,
            *fwd,
        ),
        Part::Inflection(seg, fwd) => (
            SplinePieceKind::LacInflection,
            seg.alpha(),
            seg.control(),
            (0.0, seg.end_curvature()),
            *fwd,
        ),
    };
    let (control, kappa, rational) = if forward {
        (control, kappa, f.curve)
    } else {
        (
            [control[2], control[1], control[0]],
            (-kappa.1, -kappa.0),
            f.curve.reversed(),
        )
    };
    Ok(SplinePiece {
        kind,
        span,
        alpha: Some(alpha),
        control,
        end_curvatures: kappa,
        rational,
        rational_error: f.max_error,
        monotone: f.monotone,
    })
}

/// The spline from its pieces and the solve's report.
pub(super) fn result(
    mut pieces: Vec<SplinePiece>,
    problem: &Problem,
    sol: &Solution,
    closed: bool,
) -> LacSpline {
    super::joins::sharpen(&mut pieces);
    let n = problem.points.len();
    let mut tangents = vec![Vec2::ZERO; n];
    for p in &pieces {
        let (i, _) = problem.ends[p.span];
        if tangents[i] == Vec2::ZERO {
            tangents[i] = start_tangent(p);
        }
    }
    if !closed {
        if let Some(last) = pieces.last() {
            let c = last.rational.points();
            tangents[n - 1] = (c[3] - c[2]).normalize();
        }
    }
    let ends: Vec<(f64, f64)> = pieces.iter().map(|p| p.end_curvatures).collect();
    let (inflections, curvature_extrema) = crate::sketch::count_events(&ends);
    let (max_cubic_jump, max_cubic_angle) = cubic_joins(&pieces, problem, closed);
    LacSpline {
        max_cubic_jump,
        max_cubic_angle,
        all_monotone: pieces.iter().all(|p| p.monotone),
        max_rational_error: pieces.iter().fold(0.0, |m, p| m.max(p.rational_error)),
        tangents,
        iterations: sol.iterations,
        converged: sol.jump <= super::ACCEPTED_JUMP,
        max_curvature_jump: sol.jump,
        inflections,
        curvature_extrema,
        closed,
        span_alphas: problem.alphas.clone(),
        relaxed_spans: Vec::new(),
        pieces,
    }
}

/// The largest relative curvature jump and tangent angle at the cubics' smooth joins.
fn cubic_joins(pieces: &[SplinePiece], problem: &Problem, closed: bool) -> (f64, f64) {
    let n = pieces.len();
    let big = pieces.iter().fold(0.0f64, |m, p| {
        m.max(p.rational.kappa_start().abs())
            .max(p.rational.kappa_end().abs())
    });
    let joins = if closed { n } else { n.saturating_sub(1) };
    let (mut jump, mut angle) = (0.0f64, 0.0f64);
    for j in 0..joins {
        let (a, b) = (&pieces[j], &pieces[(j + 1) % n]);
        let at_point = b.span != a.span || n == 1;
        if at_point && problem.unknown[problem.ends[b.span].0].is_none() {
            continue;
        }
        let ta = {
            let c = a.rational.points();
            (c[3] - c[2]).normalize()
        };
        angle = angle.max(ta.cross(start_tangent(b)).asin().abs());
        jump = jump.max((a.rational.kappa_end() - b.rational.kappa_start()).abs());
    }
    (if big > 0.0 { jump / big } else { 0.0 }, angle)
}

fn start_tangent(p: &SplinePiece) -> Vec2 {
    let c = p.rational.points();
    (c[1] - c[0]).normalize()
}
