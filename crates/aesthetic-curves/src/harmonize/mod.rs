//! Harmonize: the smooth joins of a contour of cubics made G2 by moving handles along their
//! own tangent directions, within a tolerance, on a grid, and never making a join or a
//! segment worse (docs/math.md §10); with [`repair`], curvature hooks and extra extrema
//! removed first ([`remove_bumps`]).
//!
//! **The join.** At a join P between cubic A (a0 a1 a2 P) and cubic B (P b1 b2 b3), with
//! unit end tangent T_A = (P - a2)/v and start tangent T_B = (b1 - P)/u (v, u the lengths of
//! the two handles at P), the curvatures are
//! `κ_A(1) = (2/3) e_A / v²` and `κ_B(0) = (2/3) e_B / u²`, where `e_A = (P - a1) × T_A` and
//! `e_B = T_B × (b2 - P)` are the distances of the far handles from the tangent lines. Sliding
//! a2 and b1 along their tangents changes v and u and neither e, so the join is G2 exactly
//! when `u / v = √(e_B / e_A)`: one equation in the two lengths, solved with the least change
//! of their logarithms, inside the box the tolerance allows.
//!
//! **The tolerance** bounds how far the outline moves: each cubic's shape within it of the
//! original's (a sound bound of their Fréchet distance, [`outline_distance`]), whichever
//! stage moved it; a handle may move further, since it pulls its cubic by a fraction of its
//! own move, and mostly along the curve when it slides along its tangent.
//!
//! **The coupling.** `e_A` depends on A's other handle length (a1 slides along A's start
//! tangent, and its distance from T_A's line changes unless the two tangents are parallel),
//! which the join before solves. The joins are therefore swept in turn until nothing moves
//! ([`crate::solve::systems::sweep_to_fixed_point`]). A cubic the result spoils (more curvature
//! extrema than the input, a hook it did not have, or a join of its worse) is held half
//! way back (then at a quarter, then at its input) and the rest swept again, so that its
//! neighbours make up for it from their other sides (`settle`).
//!
//! **Which joins.** Those marked smooth, and those whose tangents meet within
//! [`HarmonizeOptions::g1_angle`] (G1 in the check's eyes, marked or not). At a corner the
//! sweep moves no handle; its curvature jump means nothing and is free, its angle may not
//! grow.
//!
//! **The joint stage** (`harmonize/joint.rs`). After the sweep, every handle length of the
//! contour's cubics at moving joins (a corner's too, along its tangent) is solved at once
//! inside the tolerance's true region, not the sweep's box: the far handles' lever on the
//! end curvatures, which a join-by-join sweep cannot use.
//!
//! **The grid.** A font's coordinates are integers. Each cubic gets a few states (its
//! handles at their input places, at grid points around the sweep's targets nearest their
//! tangent lines, or half way), and the states of the whole contour are chosen together by
//! dynamic programming: as many joins under [`HarmonizeOptions::g2_jump`] as the grid
//! allows, then the smallest jumps, no join worse than the input (`harmonize/grid.rs`).
//!
//! **No worse.** Last, every join whose curvature jump or angle is worse than in the input,
//! and every cubic that has more curvature extrema than before (the exact test), gets its
//! original handles back, until none is left (a safety net: the grid stage already keeps
//! to both).

mod grid;
mod joint;

use crate::bezier::{outline_distance, outline_move, outline_within};
use crate::monotone::CurvatureMonotone;
use crate::{Bezier, Point, Vec2};

/// What [`harmonize`] may do.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HarmonizeOptions {
    /// How far the outline may move: every segment within this of the input at equal
    /// parameters ([`outline_move`]; a handle may move further, alone up to 9/4 of it).
    pub tolerance: f64,
    /// The coordinates' grid (1 for font units; 0 for none).
    pub grid: f64,
    /// Most sweeps over the joins.
    pub max_sweeps: usize,
    /// Also move the on-curve point of a smooth join along the line of its two handles
    /// (Grey Harmony's way: the two handles stay, so the curvature elsewhere does not
    /// change), before the handles slide.
    pub move_points: bool,
    /// A join not marked smooth whose tangents meet within this angle (radians) in the
    /// input, plus what the grid can turn its handles by ([`crate::outline::g1_slack`]),
    /// is G1 all the same (the check reports its curvature jump): it is harmonized like a
    /// smooth one, and its jump may not grow (negative: the marks alone decide). At the other corners the
    /// tangents are kept (a handle there only slides along its tangent, in the joint stage)
    /// and the angle may not grow; their curvature jumps mean nothing.
    pub g1_angle: f64,
    /// A relative curvature jump under this counts as G2: on a grid, as many joins as
    /// can are put under it first, then the jumps made small.
    pub g2_jump: f64,
}

impl Default for HarmonizeOptions {
    fn default() -> Self {
        HarmonizeOptions {
            tolerance: 1.0,
            grid: 0.0,
            max_sweeps: 100,
            move_points: false,
            g1_angle: 0.05f64.to_radians(),
            g2_jump: 0.01,
        }
    }
}

/// What happened at one join.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JoinOutcome {
    /// Not a smooth join (the caller said so): left alone.
    Corner,
    /// A line (or a retracted handle) on one side: G2 would need zero curvature on the
    /// other, which handle lengths cannot give.
    NotBetweenCubics,
    /// The curvature changes sign at the join (or is zero on one side only): no handle
    /// lengths make it continuous.
    SignChange,
    /// Already G2 within rounding, or zero curvature on both sides.
    AlreadyG2,
    /// Made G2: the jump under [`HarmonizeOptions::g2_jump`] (on the grid).
    Harmonized,
    /// G2 needs more than the tolerance: moved as far towards it as allowed.
    Limited,
    /// Moved part of the way: the whole move would give a cubic more curvature extrema,
    /// or another join a worse jump, or the grid allows no closer.
    Partly,
    /// Moved, then given back its handles because the result was worse (after the grid).
    Reverted,
    /// Held as it was (the caller said so: [`harmonize_holding`]).
    Held,
}

/// One join of the result.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct JoinReport {
    /// The join after segment `after_segment`.
    pub after_segment: usize,
    /// What was done.
    pub outcome: JoinOutcome,
    /// The relative curvature jump `|κ_A - κ_B| / max(|κ_A|, |κ_B|)` before and after.
    pub jump: (f64, f64),
    /// The angle between the two tangents (radians) before and after.
    pub angle: (f64, f64),
}

impl JoinReport {
    /// Whether the join ended worse than it began: a larger angle (beyond 1e-12 rad) or a
    /// larger jump (beyond rounding); the rule every stage of the repair keeps to.
    pub fn worse(&self) -> bool {
        worse((self.jump.1, self.angle.1), (self.jump.0, self.angle.0))
    }
}

/// Whether a join's (jump, angle) `after` is worse than `before`: a larger angle (beyond
/// 1e-12 rad: sliding a handle along its tangent turns it by rounding only) or a larger
/// jump (beyond the rounding of its computation). A NaN jump (a zero-length handle) is
/// not worse.
fn worse(after: (f64, f64), before: (f64, f64)) -> bool {
    after.1 > before.1 + 1e-12 || after.0 > before.0 * (1.0 + 1e-12) + 1e-15
}

/// The largest distance between the control points of `a` and `b`.
fn max_move(a: &[Point], b: &[Point]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (*p - *q).hypot())
        .fold(0.0, f64::max)
}

/// What the tolerance allows: the outline of each segment within `tolerance` of the
/// `original`'s ([`outline_move`]), whatever stage moved it.
struct Reach<'a> {
    original: &'a [Vec<Point>],
    tolerance: f64,
}

impl Reach<'_> {
    /// Whether `q` may replace segment `i`.
    fn allows(&self, i: usize, q: &[Point]) -> bool {
        q == &self.original[i][..] || outline_within(&self.original[i], q, self.tolerance)
    }

    /// How far segment `i`'s on-curve points in `now` are from the original's.
    fn ends_moved(&self, i: usize, now: &[Point]) -> f64 {
        let o = &self.original[i];
        (now[0] - o[0])
            .hypot()
            .max((now[now.len() - 1] - o[o.len() - 1]).hypot())
    }

    /// How far each handle of cubic `i` (its ends at `now`'s) may be from the original's
    /// place so that the outline stays within the tolerance T. With the ends moved by m and
    /// both handles by r >= m, `|Δ(t)| <= (b0 + b3) m + (b1 + b2) r = m + s (r - m)` with
    /// `s = b1 + b2 = 3t(1-t) <= 3/4`: at most T for `r = 4/3 T - m/3`; one handle alone
    /// (the other at its original place), with `b1 <= 4/9`, for `r = 9/4 T - 5/4 m`. Both
    /// are T at m = T, and nothing when the ends already moved further.
    fn handle_radius(&self, i: usize, now: &[Point], alone: bool) -> f64 {
        let (t, m) = (self.tolerance, self.ends_moved(i, now));
        if m > t {
            return 0.0;
        }
        if alone {
            2.25 * t - 1.25 * m
        } else {
            (4.0 * t - m) / 3.0
        }
    }
}

/// The four grid points around `q` (step `g`).
fn grid_corners(q: Point, g: f64) -> [Point; 4] {
    let (fx, fy) = ((q.x / g).floor() * g, (q.y / g).floor() * g);
    [
        Point::new(fx, fy),
        Point::new(fx + g, fy),
        Point::new(fx, fy + g),
        Point::new(fx + g, fy + g),
    ]
}

/// The harmonized contour and what was done.
#[derive(Clone, Debug, PartialEq)]
pub struct Harmonized {
    /// The segments' control points, in order (handles moved along their tangents; with
    /// `move_points`, on-curve points along their handles' line).
    pub segments: Vec<Vec<Point>>,
    /// Per join (n - 1 for an open contour, n for a closed one).
    pub joins: Vec<JoinReport>,
    /// Per segment: how far its outline moved from the input ([`outline_move`]).
    pub moved: Vec<f64>,
    /// Per segment: interior curvature extrema before and after (None: not a cubic, or the
    /// exact test could not run).
    pub extrema: Vec<(Option<usize>, Option<usize>)>,
    /// The sweeps over the joins.
    pub sweeps: crate::solve::systems::Sweeps,
    /// The cubics whose curvature defects [`repair`] removed first (none from
    /// [`harmonize`] alone).
    pub bumps: Vec<BumpFix>,
    /// The cubics with a curvature defect whose repair search stopped at its budget for
    /// exact arithmetic ([`crate::monotone::SEARCH_EXACT_BUDGET`]: coordinates spanning
    /// hundreds of orders of magnitude), left as they are although a repair may exist.
    pub bumps_undecided: Vec<usize>,
}

/// The handle lengths of the cubics and their tangent directions.
struct Handles {
    /// Per segment: start tangent, end tangent (unit), or None for a line or a retracted
    /// handle.
    dirs: Vec<Option<(Vec2, Vec2)>>,
    /// Per segment: the input's start and end handle lengths.
    orig: Vec<(f64, f64)>,
    /// Per segment: the current lengths.
    len: Vec<(f64, f64)>,
    /// Per segment: held at its current lengths (a sweep spoiled it).
    held: Vec<bool>,
    /// Per segment: how often it was held back.
    holds: Vec<u8>,
    /// Per segment: the range each of its two lengths may take (the tolerance's box).
    bounds: Vec<((f64, f64), (f64, f64))>,
}

impl Handles {
    fn of(segs: &[Vec<Point>]) -> Handles {
        let mut dirs = Vec::with_capacity(segs.len());
        let mut orig = Vec::with_capacity(segs.len());
        for s in segs {
            if s.len() == 4 {
                let (h0, h1) = (s[1] - s[0], s[3] - s[2]);
                let (u, v) = (h0.hypot(), h1.hypot());
                if u > 0.0 && v > 0.0 && u.is_finite() && v.is_finite() {
                    dirs.push(Some((h0 / u, h1 / v)));
                    orig.push((u, v));
                    continue;
                }
            }
            dirs.push(None);
            orig.push((0.0, 0.0));
        }
        Handles {
            held: vec![false; dirs.len()],
            holds: vec![0; dirs.len()],
            bounds: orig.iter().map(|&(u, v)| ((u, u), (v, v))).collect(),
            dirs,
            len: orig.clone(),
            orig,
        }
    }

    /// [`Handles::of`] with each length's range: where its handle stays within
    /// [`Reach::handle_radius`] of the original's place (both handles moving), and positive.
    fn within(segs: &[Vec<Point>], reach: &Reach) -> Handles {
        let mut h = Handles::of(segs);
        for i in 0..segs.len() {
            h.bound(segs, reach, i);
        }
        h
    }

    /// Segment `i`'s length ranges for [`Reach::handle_radius`]; a range that would not
    /// hold the current length is just that length.
    fn bound(&mut self, segs: &[Vec<Point>], reach: &Reach, i: usize) {
        let Some((d0, d1)) = self.dirs[i] else {
            return;
        };
        let s = &segs[i];
        let radius = reach.handle_radius(i, s, false);
        let o = &reach.original[i];
        let (floor_u, floor_v) = (1e-3 * self.orig[i].0, 1e-3 * self.orig[i].1);
        let (u, v) = self.len[i];
        self.bounds[i] = (
            length_range((s[0], d0), o[1], (radius, floor_u), u),
            length_range((s[3], -d1), o[2], (radius, floor_v), v),
        );
    }

    /// The control points of segment `i` with the current lengths (exactly the input's
    /// points where a length is unchanged).
    fn points(&self, segs: &[Vec<Point>], i: usize) -> Vec<Point> {
        let s = &segs[i];
        if self.dirs[i].is_none() {
            return s.clone();
        }
        let (u0, v0) = self.orig[i];
        let (u, v) = self.len[i];
        let p1 = if u == u0 {
            s[1]
        } else {
            s[0] + (s[1] - s[0]) * (u / u0)
        };
        let p2 = if v == v0 {
            s[2]
        } else {
            s[3] + (s[2] - s[3]) * (v / v0)
        };
        vec![s[0], p1, p2, s[3]]
    }

    /// Every segment's control points with the current lengths ([`Handles::points`]).
    fn contour(&self, segs: &[Vec<Point>]) -> Vec<Vec<Point>> {
        (0..segs.len()).map(|i| self.points(segs, i)).collect()
    }
}

/// The lengths `L` for which the handle `anchor + L k` stays within `radius` of `original`
/// (`k` a unit vector), and at least `floor`; just `now` where that range does not hold it.
fn length_range(
    (anchor, k): (Point, Vec2),
    original: Point,
    (radius, floor): (f64, f64),
    now: f64,
) -> (f64, f64) {
    let w = anchor - original;
    let (c, e) = (w.dot(k), w.cross(k).abs());
    if radius.is_nan() || radius < e {
        return (now, now);
    }
    let r = (radius * radius - e * e).sqrt();
    let (lo, hi) = ((-c - r).max(floor), -c + r);
    if (lo..=hi).contains(&now) {
        (lo, hi)
    } else {
        (now, now)
    }
}

/// End curvatures of a cubic's control points: at the start and at the end.
fn end_curvatures(p: &[Point]) -> (f64, f64) {
    let k = |a: Vec2, b: Vec2, h: f64| 2.0 / 3.0 * a.cross(b) / (h * h * h);
    let (d0, d1, d2) = (p[1] - p[0], p[2] - p[1], p[3] - p[2]);
    (k(d0, d1, d0.hypot()), k(d1, d2, d2.hypot()))
}

fn relative_jump(a: f64, b: f64) -> f64 {
    let m = a.abs().max(b.abs());
    if m > 0.0 {
        (a - b).abs() / m
    } else {
        0.0
    }
}

/// The angle (radians, 0 to π) between two tangent vectors, each scaled to its largest
/// coordinate first so that the cross and dot products cannot overflow (coordinates near
/// 1e308); 0 where either is zero.
pub fn tangent_angle(a: Vec2, b: Vec2) -> f64 {
    let unit = |v: Vec2| {
        let m = v.x.abs().max(v.y.abs());
        if m > 0.0 && m.is_finite() {
            v / m
        } else {
            Vec2::ZERO
        }
    };
    let (a, b) = (unit(a), unit(b));
    a.cross(b).atan2(a.dot(b)).abs()
}

/// The tangent vectors at the join of segments `a` and `b` (control points), into the join
/// and out of it, each from the nearest control point distinct from the join's point (a
/// retracted handle gives its direction to the next one); None where all coincide.
pub fn join_tangents(a: &[Point], b: &[Point]) -> [Option<Vec2>; 2] {
    [end_tangents(a)[1], end_tangents(b)[0]]
}

/// The tangent vectors of a segment (control points) out of its start and into its end,
/// each from the nearest control point distinct from that end's; None where all coincide.
fn end_tangents(p: &[Point]) -> [Option<Vec2>; 2] {
    let (first, last) = (p[0], p[p.len() - 1]);
    [
        p.iter().find(|q| **q != first).map(|q| *q - first),
        p.iter().rev().find(|q| **q != last).map(|q| last - *q),
    ]
}

/// The jump and angle at the join of segments `a` and `b` (control points).
fn join_state(a: &[Point], b: &[Point]) -> (f64, f64) {
    Ends::of(a).join(&Ends::of(b))
}

/// What a segment brings to its joins: the tangent at each end (from the nearest distinct
/// control point: a retracted handle gives its direction to the next one; zero where all
/// coincide) and the curvature there (0 on a line: a join with one keeps its jump, 0 or 1).
#[derive(Clone, Copy)]
struct Ends {
    /// Out of the start.
    start: Vec2,
    /// Into the end.
    end: Vec2,
    /// At the start and at the end ([`end_curvature`]).
    curvature: (f64, f64),
    /// The directions of `start` and `end` (radians; NaN for a zero tangent).
    directions: (f64, f64),
}

impl Ends {
    fn of(p: &[Point]) -> Ends {
        let [start, end] = end_tangents(p).map(|t| t.unwrap_or(Vec2::ZERO));
        let curvature = if p.len() == 4 {
            (end_curvature(p, 0), end_curvature(p, 1))
        } else {
            (0.0, 0.0)
        };
        let direction = |v: Vec2| {
            if v == Vec2::ZERO {
                f64::NAN
            } else {
                v.y.atan2(v.x)
            }
        };
        Ends {
            start,
            end,
            curvature,
            directions: (direction(start), direction(end)),
        }
    }

    /// [`Ends::join`] with the angle from the two directions (no atan2 per pair: within
    /// a few units in the last place of it; what the grid's chain ranks, the safety net
    /// checking the chosen states with [`join_state`] after).
    fn join_fast(&self, next: &Ends) -> (f64, f64) {
        let d = (next.directions.0 - self.directions.1).abs();
        let angle = if d.is_nan() {
            0.0
        } else if d > std::f64::consts::PI {
            std::f64::consts::TAU - d
        } else {
            d
        };
        (relative_jump(self.curvature.1, next.curvature.0), angle)
    }

    /// The jump and angle at the join of this segment's end with `next`'s start.
    fn join(&self, next: &Ends) -> (f64, f64) {
        let angle = tangent_angle(self.end, next.start);
        (relative_jump(self.curvature.1, next.curvature.0), angle)
    }
}

/// The curvature of the cubic `p` at its end `end` (0 or 1) as the check sees it: at a
/// handle retracted onto its point (no formula: the speed vanishes) the exact test's limit
/// (0 on a straight stretch), NaN where it grows without bound (no jump to compare).
fn end_curvature(p: &[Point], end: usize) -> f64 {
    let retracted = if end == 0 { p[1] == p[0] } else { p[2] == p[3] };
    if !retracted {
        let k = end_curvatures(p);
        return if end == 0 { k.0 } else { k.1 };
    }
    let report = Bezier::new(p.to_vec()).and_then(|b| b.curvature_monotone());
    (report.ok())
        .and_then(|r| r.ends[end].value())
        .unwrap_or(f64::NAN)
}

/// The new lengths (v of A's end handle, u of B's start handle) for G2 at the join of
/// segments `ia` and `ib`, and whether the tolerance held them short of it; None when the
/// join cannot be made G2 by lengths.
fn solve_join(
    segs: &[Vec<Point>],
    h: &Handles,
    (ia, ib): (usize, usize),
) -> Result<((f64, f64), bool), JoinOutcome> {
    let (Some((ta0, ta)), Some((tb, tb3))) = (h.dirs[ia], h.dirs[ib]) else {
        return Err(JoinOutcome::NotBetweenCubics);
    };
    let (a, b) = (&segs[ia], &segs[ib]);
    let p = a[3];
    // e_A with a1 = a0 + u_A t_A0 and e_B with b2 = b3 - v_B t_B3, at the current lengths.
    let e_a = (p - a[0]).cross(ta) - h.len[ia].0 * ta0.cross(ta);
    let e_b = tb.cross(b[3] - p) - h.len[ib].1 * tb.cross(tb3);
    let scale = (p - a[0]).hypot().max((b[3] - p).hypot());
    let flat = |e: f64| e.abs() <= 1e-12 * scale;
    if flat(e_a) && flat(e_b) {
        return Err(JoinOutcome::AlreadyG2);
    }
    if flat(e_a) || flat(e_b) || (e_a > 0.0) != (e_b > 0.0) {
        return Err(JoinOutcome::SignChange);
    }
    let rho = (e_b / e_a).sqrt(); // u / v at G2
    let (v0, u0) = (h.orig[ia].1, h.orig[ib].0);
    let ((v_lo, v_hi), (u_lo, u_hi)) = (h.bounds[ia].1, h.bounds[ib].0);
    match (h.held[ia], h.held[ib]) {
        (true, true) => return Err(JoinOutcome::Reverted),
        (true, false) => {
            let v = h.len[ia].1;
            return Ok(one_sided(rho * v, (u_lo, u_hi)).map_u(v));
        }
        (false, true) => {
            let u = h.len[ib].0;
            return Ok(one_sided(u / rho, (v_lo, v_hi)).map_v(u));
        }
        (false, false) => {}
    }
    // Least change of (ln v, ln u) on the line ln u - ln v = ln ρ, inside the box the
    // tolerance allows ([`Handles::within`]).
    let v_star = (v0 * u0 / rho).sqrt();
    let (lo, hi) = (v_lo.max(u_lo / rho), v_hi.min(u_hi / rho));
    if lo <= hi {
        let v = v_star.clamp(lo, hi);
        return Ok(((v, rho * v), false));
    }
    // Out of reach: the corner of the box nearest the ratio.
    Ok((
        if rho * v_lo > u_hi {
            (v_lo, u_hi)
        } else {
            (v_hi, u_lo)
        },
        true,
    ))
}

/// The length `want` clamped to the tolerance's range, and whether it had to be.
fn one_sided(want: f64, (lo, hi): (f64, f64)) -> OneSided {
    let got = want.clamp(lo, hi);
    OneSided(got, got != want)
}

/// A length solved with the other side of the join held.
struct OneSided(f64, bool);

impl OneSided {
    /// As (v, u) with the held v.
    fn map_u(self, v: f64) -> ((f64, f64), bool) {
        ((v, self.0), self.1)
    }
    /// As (v, u) with the held u.
    fn map_v(self, u: f64) -> ((f64, f64), bool) {
        ((self.0, u), self.1)
    }
}

/// The joins of a contour of `n` segments: (join index, segment before, segment after).
fn joins(n: usize, closed: bool) -> impl Iterator<Item = (usize, usize, usize)> {
    let count = if closed { n } else { n.saturating_sub(1) };
    (0..count).map(move |j| (j, j, (j + 1) % n))
}

/// Harmonize a contour: `segments` are consecutive lines (2 points) and cubics (4 points),
/// `smooth[j]` says whether the join after segment j is meant smooth (a font's smooth flag,
/// or the angle test), one per join. See the module documentation.
pub fn harmonize(
    segments: &[Vec<Point>],
    closed: bool,
    smooth: &[bool],
    opts: &HarmonizeOptions,
) -> crate::Result<Harmonized> {
    harmonize_holding(segments, closed, (smooth, &vec![false; smooth.len()]), opts)
}

/// [`harmonize`], with the joins where `held[j]` kept as they are: no handle at them moves
/// (so their handles' ratio stays: what keeps the instances of compatible masters G1 where
/// the tangent turns from master to master), their jumps still may not grow.
pub fn harmonize_holding(
    segments: &[Vec<Point>],
    closed: bool,
    (smooth, held): (&[bool], &[bool]),
    opts: &HarmonizeOptions,
) -> crate::Result<Harmonized> {
    check_input(segments, closed, smooth, opts)?;
    check_input(segments, closed, held, opts)?;
    let reach = Reach {
        original: segments,
        tolerance: opts.tolerance,
    };
    Ok(harmonize_within(
        segments,
        closed,
        (smooth, held),
        opts,
        &reach,
    ))
}

/// [`harmonize_holding`] of `segments` (checked), an earlier stage's result, with what the
/// tolerance allows measured from `reach`'s original.
fn harmonize_within(
    segments: &[Vec<Point>],
    closed: bool,
    (smooth, held): (&[bool], &[bool]),
    opts: &HarmonizeOptions,
    reach: &Reach,
) -> Harmonized {
    let limits = Limits::of(segments, (closed, smooth), opts);
    // The joins whose handles move: kept and not held.
    let moving: Vec<bool> = limits
        .kept
        .iter()
        .zip(held)
        .map(|(k, h)| *k && !*h)
        .collect();
    let stage = Stage {
        input: segments,
        closed,
        held,
        moving: &moving,
        limits: &limits,
        opts,
        reach,
    };
    // With `move_points`, the joins' on-curve points first; each takes part of the
    // outline's tolerance from the handles of its two cubics, so the contour is harmonized
    // with the points moved at most none, half or all of the tolerance, and the result
    // with the fewest joins short of G2 (then the smallest jumps) kept.
    let shares: &[f64] = if opts.move_points {
        &[0.0, 0.5, 1.0]
    } else {
        &[0.0]
    };
    let score = |h: &Harmonized| Shortfall::of(h, &limits.kept, opts.g2_jump);
    let first = stage.run(shares[0]);
    let mut best = (score(&first), first);
    for &share in &shares[1..] {
        let h = stage.run(share);
        let s = score(&h);
        if s < best.0 {
            best = (s, h);
        }
    }
    best.1
}

/// How far a result is from G2 at its kept joins: how many are not under the threshold,
/// then the sum of their jumps (ordered so: fewer first).
#[derive(Clone, Copy, PartialEq, PartialOrd)]
pub(super) struct Shortfall(usize, f64);

impl Shortfall {
    fn of(h: &Harmonized, kept: &[bool], g2: f64) -> Shortfall {
        let jumps = (h.joins.iter())
            .filter(|j| kept[j.after_segment])
            .map(|j| j.jump.1);
        Shortfall::of_jumps(jumps, g2)
    }

    /// Of the contour `pts` at the joins `which` marks (one flag per join).
    pub(super) fn at_joins(pts: &[Vec<Point>], closed: bool, which: &[bool], g2: f64) -> Shortfall {
        let jumps = (joins(pts.len(), closed).filter(|&(j, ..)| which[j]))
            .map(|(_, a, b)| join_state(&pts[a], &pts[b]).0);
        Shortfall::of_jumps(jumps, g2)
    }

    /// Of the finite ones among `jumps`.
    fn of_jumps(jumps: impl Iterator<Item = f64>, g2: f64) -> Shortfall {
        (jumps.filter(|j| j.is_finite())).fold(Shortfall(0, 0.0), |s, j| {
            Shortfall(s.0 + (j >= g2) as usize, s.1 + j)
        })
    }
}

/// One contour's harmonization: its input (checked), which joins are held and which move,
/// the limits from the input, and what the tolerance allows.
struct Stage<'a> {
    input: &'a [Vec<Point>],
    closed: bool,
    held: &'a [bool],
    moving: &'a [bool],
    limits: &'a Limits,
    opts: &'a HarmonizeOptions,
    reach: &'a Reach<'a>,
}

impl Stage<'_> {
    /// The sweep (its targets), the grid and the safety net, after the on-curve points
    /// moved at most `share` of the tolerance (none: 0).
    fn run(&self, share: f64) -> Harmonized {
        let (closed, opts, reach) = (self.closed, self.opts, self.reach);
        let Limits {
            before,
            kept,
            guard,
            profiles: extrema_before,
        } = self.limits;
        let n = self.input.len();
        let limits = (&guard[..], &extrema_before[..]);
        let start = if share > 0.0 {
            let cap = opts.tolerance * share;
            let points = (opts, reach, cap);
            move_on_curve_points(self.input, (closed, self.moving), points, limits)
        } else {
            self.input.to_vec()
        };
        let segments = &start[..];
        let mut h = Handles::within(segments, reach);
        let (sweeps, mut outcome) = settle(segments, &mut h, (closed, self.moving), opts, limits);
        // The joint stage solves the joins the sweep could move or held back (not a sign
        // change, a line or a corner: no lengths make those G2), and keeps flat ones flat.
        let solvable: Vec<bool> = (self.moving.iter().zip(&outcome))
            .map(|(m, o)| {
                *m && matches!(
                    o,
                    JoinOutcome::Harmonized
                        | JoinOutcome::Limited
                        | JoinOutcome::AlreadyG2
                        | JoinOutcome::Reverted
                )
            })
            .collect();
        jointly(
            segments,
            &mut h,
            (closed, &solvable, self.held, opts.g2_jump),
            reach,
            limits,
        );
        let target = h.contour(segments);
        // The joins the joint stage solved (all solvable ones but the flat), by their result.
        for (j, a, b) in joins(n, closed) {
            if solvable[j] && outcome[j] != JoinOutcome::AlreadyG2 {
                outcome[j] = if join_state(&target[a], &target[b]).0 < opts.g2_jump {
                    JoinOutcome::Harmonized
                } else {
                    JoinOutcome::Limited
                };
            }
        }
        for (o, _) in outcome.iter_mut().zip(self.held).filter(|(_, h)| **h) {
            *o = JoinOutcome::Held;
        }
        let contour = grid::Contour {
            input: segments,
            reach,
            closed,
            smooth: kept,
            guard,
            extrema_before,
        };
        let mut pts = grid::place(&contour, &target, opts);
        revert_what_got_worse(
            segments,
            &mut pts,
            (closed, opts.grid, reach),
            (guard, extrema_before),
            &mut outcome,
        );
        label_delivered(&contour, (&target, &pts), opts.g2_jump, &mut outcome);
        let after = states(&pts, closed);
        let joins = joins(n, closed)
            .map(|(j, ..)| JoinReport {
                after_segment: j,
                outcome: outcome[j],
                jump: (before[j].0, after[j].0),
                angle: (before[j].1, after[j].1),
            })
            .collect();
        let moved = (reach.original.iter().zip(&pts))
            .map(|(s, p)| outline_distance(s, p))
            .collect();
        let extrema = (extrema_before.iter().map(|b| b.map(|b| b.0)))
            .zip(pts.iter().map(|p| extrema(p)))
            .collect();
        Harmonized {
            segments: pts,
            joins,
            moved,
            extrema,
            sweeps,
            bumps: Vec::new(),
            bumps_undecided: Vec::new(),
        }
    }
}

/// Rounds of [`jointly`].
const JOINT_ROUNDS: usize = 3;

/// The joint stage ([`joint::refine`]) after the sweep: a cubic its result spoils (as in
/// [`settle`]) gets the sweep's lengths back and is held, and the rest is solved again, for
/// at most [`JOINT_ROUNDS`] rounds; the sweep's lengths stay where they leave the moving
/// joins nearer G2 ([`Shortfall`]: the joint problem weighs the extrema rule's margins
/// against G2 and can settle short of a G2 the sweep found).
fn jointly(
    segments: &[Vec<Point>],
    h: &mut Handles,
    (closed, moving, held, g2): (bool, &[bool], &[bool], f64),
    reach: &Reach,
    limits: (&[(f64, f64)], &[Option<Profile>]),
) {
    let swept = h.len.clone();
    let shortfall = |h: &Handles| Shortfall::at_joins(&h.contour(segments), closed, moving, g2);
    let before = shortfall(h);
    let mut hold = vec![false; segments.len()];
    for _ in 0..JOINT_ROUNDS {
        let joins = joint::Joins {
            closed,
            moving,
            held,
            guard: limits.0,
        };
        if joint::refine(segments, h, &joins, &hold, reach).is_none() {
            break;
        }
        let pts = h.contour(segments);
        let spoiled = spoiled(segments, &pts, closed, limits);
        if spoiled.is_empty() {
            break;
        }
        for i in spoiled {
            h.len[i] = swept[i];
            hold[i] = true;
        }
    }
    if before < shortfall(h) {
        h.len = swept;
    }
}

/// After the grid stage, each moved join labelled by what was delivered: one under the G2
/// threshold is `Harmonized` (also where the float stages stopped short, `Limited` or
/// `Partly`, and the grid's own search along the tangent lines got there, or where its own
/// handles went back but its cubics' far handles made it G2); else one the sweep moved
/// whose two handles are back at their input places is `Reverted`, and a `Harmonized` one
/// is `Partly`.
fn label_delivered(
    contour: &grid::Contour,
    (target, pts): (&[Vec<Point>], &[Vec<Point>]),
    g2_jump: f64,
    outcome: &mut [JoinOutcome],
) {
    let input = contour.input;
    for (j, a, b) in joins(pts.len(), contour.closed) {
        use JoinOutcome::{Harmonized, Limited, Partly, Reverted};
        let near = |s: &[Vec<Point>]| (s[a][s[a].len() - 2], s[b][1]);
        let back = near(pts) == near(input) && near(target) != near(input);
        let under = join_state(&pts[a], &pts[b]).0 < g2_jump;
        outcome[j] = match outcome[j] {
            Harmonized | Limited | Partly | Reverted if under => Harmonized,
            Harmonized | Limited if back => Reverted,
            Harmonized => Partly,
            o => o,
        };
    }
}

/// The joins to harmonize and keep: those marked smooth, and those G1 in the input as the
/// check sees it (within `g1_angle` plus what the grid can turn their handle legs by:
/// [`crate::outline::g1_slack`]).
fn g1_or_smooth(
    segments: &[Vec<Point>],
    (closed, smooth): (bool, &[bool]),
    before: &[(f64, f64)],
    opts: &HarmonizeOptions,
) -> Vec<bool> {
    joins(segments.len(), closed)
        .map(|(j, a, b)| {
            let (sa, sb) = (&segments[a], &segments[b]);
            let legs = (
                (sa[sa.len() - 1] - sa[sa.len() - 2]).hypot(),
                (sb[1] - sb[0]).hypot(),
            );
            let slack = crate::outline::g1_slack(opts.grid, legs);
            smooth[j] || before[j].1 <= opts.g1_angle + slack
        })
        .collect()
}

/// The limits no join may pass: the input's jump and angle, with no limit on the jump at
/// a corner.
fn guarded(before: &[(f64, f64)], smooth: &[bool]) -> Vec<(f64, f64)> {
    before
        .iter()
        .zip(smooth)
        .map(|(&(jump, angle), &s)| (if s { jump } else { f64::INFINITY }, angle))
        .collect()
}

/// Rounds of [`settle`]: each holds the cubics the sweep before spoiled and sweeps again.
const SETTLE_ROUNDS: usize = 6;

/// How often [`settle`] halves a spoiled cubic's move before it holds it at its input.
const HOLD_STEPS: u8 = 3;

/// The joins swept to G2 ([`sweep_joins`]); then every cubic the result spoils (more
/// curvature extrema than the input or a new hook, or a join of its worse than the
/// input's) is held half way back (then half of that, then at its input lengths) and the
/// rest swept again, so that the joins next to it make up for it from their other side,
/// for at most [`SETTLE_ROUNDS`] rounds. What
/// the last round still spoils is left to the grid stage and [`revert_what_got_worse`].
fn settle(
    segments: &[Vec<Point>],
    h: &mut Handles,
    (closed, smooth): (bool, &[bool]),
    opts: &HarmonizeOptions,
    (guard, extrema_before): (&[(f64, f64)], &[Option<Profile>]),
) -> (crate::solve::systems::Sweeps, Vec<JoinOutcome>) {
    let mut total = crate::solve::systems::Sweeps {
        sweeps: 0,
        last_change: 0.0,
        converged: true,
    };
    let mut outcome = Vec::new();
    for _round in 0..SETTLE_ROUNDS {
        let sweeps;
        (sweeps, outcome) = sweep_joins(segments, h, (closed, smooth), opts);
        total.sweeps += sweeps.sweeps;
        total.last_change = sweeps.last_change;
        total.converged = sweeps.converged;
        let pts = h.contour(segments);
        let spoiled = spoiled(segments, &pts, closed, (guard, extrema_before));
        if spoiled.is_empty() {
            break;
        }
        // Held half way back (in the logarithms of the lengths), then half of that, ...,
        // and at the input's lengths after HOLD_STEPS.
        for i in spoiled {
            h.holds[i] += 1;
            h.held[i] = true;
            h.len[i] = if h.holds[i] >= HOLD_STEPS {
                h.orig[i]
            } else {
                let mix = |a: f64, b: f64| a * (b / a).sqrt();
                (mix(h.orig[i].0, h.len[i].0), mix(h.orig[i].1, h.len[i].1))
            };
        }
    }
    (total, outcome)
}

/// The cubics of `pts` that moved and have more curvature extrema than the input, or a
/// join worse than the input's (both of its segments, where they moved).
fn spoiled(
    input: &[Vec<Point>],
    pts: &[Vec<Point>],
    closed: bool,
    (guard, extrema_before): (&[(f64, f64)], &[Option<Profile>]),
) -> Vec<usize> {
    let mut out: Vec<usize> = (0..pts.len())
        .filter(|&i| pts[i] != input[i] && gains_extrema(&pts[i], extrema_before[i]))
        .collect();
    for (_, a, b) in worse_joins(input, pts, closed, guard) {
        out.extend([a, b].into_iter().filter(|&i| pts[i] != input[i]));
    }
    out.sort_unstable();
    out.dedup();
    out
}

/// The smooth joins swept in turn to G2 until nothing moves
/// ([`crate::solve::systems::sweep_to_fixed_point`]), each join's two handle lengths solved with
/// [`solve_join`]; the outcome per join.
fn sweep_joins(
    segments: &[Vec<Point>],
    h: &mut Handles,
    (closed, smooth): (bool, &[bool]),
    opts: &HarmonizeOptions,
) -> (crate::solve::systems::Sweeps, Vec<JoinOutcome>) {
    let n = segments.len();
    let mut outcome = vec![JoinOutcome::Corner; smooth.len()];
    let sweeps = crate::solve::systems::sweep_to_fixed_point(opts.max_sweeps, 1e-13, || {
        let mut change = 0.0f64;
        for (j, ia, ib) in joins(n, closed) {
            if !smooth[j] {
                continue;
            }
            match solve_join(segments, h, (ia, ib)) {
                Ok(((v, u), limited)) => {
                    let (ov, ou) = (h.len[ia].1, h.len[ib].0);
                    change = change.max(((v - ov) / ov).abs()).max(((u - ou) / ou).abs());
                    h.len[ia].1 = v;
                    h.len[ib].0 = u;
                    outcome[j] = if limited {
                        JoinOutcome::Limited
                    } else {
                        JoinOutcome::Harmonized
                    };
                }
                Err(o) => outcome[j] = o,
            }
        }
        change
    });
    (sweeps, outcome)
}

fn check_input(
    segments: &[Vec<Point>],
    closed: bool,
    smooth: &[bool],
    opts: &HarmonizeOptions,
) -> crate::Result<()> {
    use crate::Error;
    let n = segments.len();
    let want = if closed { n } else { n.saturating_sub(1) };
    if smooth.len() != want {
        return Err(Error::invalid(
            "smooth",
            format!("{} flags for {want} joins", smooth.len()),
        ));
    }
    if !(opts.tolerance.is_finite() && opts.tolerance >= 0.0) {
        return Err(Error::invalid(
            "tolerance",
            "must be a finite distance >= 0",
        ));
    }
    if !(opts.grid.is_finite() && opts.grid >= 0.0) {
        return Err(Error::invalid("grid", "must be a finite step >= 0"));
    }
    for (i, s) in segments.iter().enumerate() {
        if s.len() != 2 && s.len() != 4 {
            return Err(Error::invalid(
                "segments",
                format!("segment {i} has {} points (lines 2, cubics 4)", s.len()),
            ));
        }
        if s.iter().any(|p| !(p.x.is_finite() && p.y.is_finite())) {
            return Err(Error::invalid(
                "segments",
                format!("segment {i} has a non-finite point"),
            ));
        }
    }
    for (j, ia, ib) in joins(n, closed) {
        if segments[ia][segments[ia].len() - 1] != segments[ib][0] {
            return Err(Error::invalid(
                "segments",
                format!("segment {ib} does not start where segment {ia} ends (join {j})"),
            ));
        }
    }
    Ok(())
}

/// The on-curve point of every smooth join between cubics moved along the line of its two
/// handles to where the join is G2 (`P = a2 + (b1 - a2) √e_A / (√e_A + √e_B)`: the distances
/// e of the far handles from that line do not change, and neither does the curvature at the
/// cubics' other ends), at most `cap`, on the grid (the best of the 3 × 3 points
/// around it, or half the way), where no cubic gains extrema and the join's angle is not
/// worse than the input's.
fn move_on_curve_points(
    segments: &[Vec<Point>],
    (closed, smooth): (bool, &[bool]),
    (opts, reach, cap): (&HarmonizeOptions, &Reach, f64),
    (before, extrema_before): (&[(f64, f64)], &[Option<Profile>]),
) -> Vec<Vec<Point>> {
    let mut pts = segments.to_vec();
    for (j, a, b) in joins(pts.len(), closed) {
        if !smooth[j] || pts[a].len() != 4 || pts[b].len() != 4 || a == b {
            continue;
        }
        let (a1, a2, p, b1, b2) = (pts[a][1], pts[a][2], pts[a][3], pts[b][1], pts[b][2]);
        let line = b1 - a2;
        let len = line.hypot();
        let usable = len > 0.0 && len.is_finite();
        if !usable {
            continue;
        }
        let t = line / len;
        let (ea, eb) = ((a2 - a1).cross(t), t.cross(b2 - b1));
        if !(ea > 0.0 && eb > 0.0 || ea < 0.0 && eb < 0.0) {
            continue;
        }
        let r = ea.abs().sqrt() / (ea.abs().sqrt() + eb.abs().sqrt());
        let mut target = a2 + line * r;
        let d = (target - p).hypot();
        if d > cap {
            target = p + (target - p) * (cap / d);
        }
        let mut best = (join_state(&pts[a], &pts[b]).0, p);
        for share in [1.0, 0.5] {
            let aim = p + (target - p) * share;
            for q in grid_candidates(aim, p, opts) {
                if q == p || (q - p).hypot() > cap {
                    continue;
                }
                pts[a][3] = q;
                pts[b][0] = q;
                let (jump, angle) = join_state(&pts[a], &pts[b]);
                if jump < best.0
                    && angle <= before[j].1 + 1e-12
                    && reach.allows(a, &pts[a])
                    && reach.allows(b, &pts[b])
                    && !gains_extrema(&pts[a], extrema_before[a])
                    && !gains_extrema(&pts[b], extrema_before[b])
                {
                    best = (jump, q);
                }
            }
        }
        pts[a][3] = best.1;
        pts[b][0] = best.1;
    }
    pts
}

/// Jump and angle at every join.
fn states(pts: &[Vec<Point>], closed: bool) -> Vec<(f64, f64)> {
    joins(pts.len(), closed)
        .map(|(_, a, b)| join_state(&pts[a], &pts[b]))
        .collect()
}

/// How many interior curvature extrema a cubic has (exact test); None for a line or no
/// verdict.
fn extrema(p: &[Point]) -> Option<usize> {
    extrema_at(p).map(|ts| ts.len())
}

/// The joins at both ends of segment `i` (moving a handle changes the curvature at both).
fn touching(n: usize, closed: bool, i: usize) -> Vec<(usize, usize, usize)> {
    joins(n, closed)
        .filter(|&(_, a, b)| a == i || b == i)
        .collect()
}

/// Where a handle aimed at `target` may go: `target` itself without a grid, else the 3 × 3
/// grid points around it; only those within the tolerance of `input` (the input place is
/// always allowed).
fn grid_candidates(target: Point, input: Point, opts: &HarmonizeOptions) -> Vec<Point> {
    let within = |q: Point| (q - input).hypot() <= opts.tolerance || q == input;
    if opts.grid <= 0.0 {
        return [target, input].into_iter().filter(|q| within(*q)).collect();
    }
    let g = opts.grid;
    let (cx, cy) = ((target.x / g).round(), (target.y / g).round());
    let mut out = vec![input];
    for dx in -1..=1 {
        for dy in -1..=1 {
            let q = Point::new((cx + dx as f64) * g, (cy + dy as f64) * g);
            if within(q) {
                out.push(q);
            }
        }
    }
    out
}

/// Whether the cubic `p` has more interior curvature extrema than `before`, or a hook where
/// it had none (or no verdict where there was one).
fn gains_extrema(p: &[Point], before: Option<Profile>) -> bool {
    match (before, profile(p)) {
        (Some(b), Some(a)) => a.0 > b.0 || (a.1 && !b.1),
        (Some(_), None) => true,
        _ => false,
    }
}

/// A cubic's curvature profile for the no-worse rule: its interior extrema, and whether one
/// is a hook (within [`HOOK_ZONE`] of an end).
type Profile = (usize, bool);

/// An extremum within this fraction of the parameter of an end is a hook (a defect at the
/// join: [`Repairs::hook_zone`]'s default, and what no repair may create).
pub const HOOK_ZONE: f64 = 0.05;

/// The exact test's [`Profile`]; None for a line or no verdict.
fn profile(p: &[Point]) -> Option<Profile> {
    extrema_at(p).map(|ts| {
        (
            ts.len(),
            ts.iter().any(|t| *t < HOOK_ZONE || *t > 1.0 - HOOK_ZONE),
        )
    })
}

/// The cubic `moved` pulled back towards `input` (its handles' moves halved, up to five
/// times, each time on the grid) until it has no more extrema than before; else `input`.
fn pull_back(
    (input, moved): (&[Point], &[Point]),
    before: Option<Profile>,
    grid: f64,
    allows: impl Fn(&[Point]) -> bool,
) -> Vec<Point> {
    let on_grid = |v: f64| {
        if grid > 0.0 {
            (v / grid).round() * grid
        } else {
            v
        }
    };
    let mut f = 0.5;
    for _ in 0..5 {
        let q: Vec<Point> = input
            .iter()
            .zip(moved)
            .map(|(a, b)| {
                let c = *a + (*b - *a) * f;
                Point::new(on_grid(c.x), on_grid(c.y))
            })
            .collect();
        if !gains_extrema(&q, before) && allows(&q) {
            return q;
        }
        f *= 0.5;
    }
    input.to_vec()
}

/// The joins that are worse than in the input (a larger jump, or a larger angle) and whose
/// segments moved.
fn worse_joins(
    input: &[Vec<Point>],
    pts: &[Vec<Point>],
    closed: bool,
    before: &[(f64, f64)],
) -> Vec<(usize, usize, usize)> {
    joins(pts.len(), closed)
        .filter(|&(j, a, b)| {
            (pts[a] != input[a] || pts[b] != input[b])
                && worse(join_state(&pts[a], &pts[b]), before[j])
        })
        .collect()
}

/// Give back the input's segments at every join that got worse (both segments whole:
/// through the coupling, the far handles set the join's curvature too), and pull back every
/// cubic that gained curvature extrema, until none is left; a last pass gives back whole
/// segments only, so it ends with no join worse and no cubic with more extrema than before.
fn revert_what_got_worse(
    input: &[Vec<Point>],
    pts: &mut [Vec<Point>],
    (closed, grid, reach): (bool, f64, &Reach),
    (before, extrema_before): (&[(f64, f64)], &[Option<Profile>]),
    outcome: &mut [JoinOutcome],
) {
    let n = pts.len();
    let mark = |outcome: &mut [JoinOutcome], i: usize| {
        for (j, a, b) in joins(n, closed) {
            if (a == i || b == i)
                && matches!(
                    outcome[j],
                    JoinOutcome::Harmonized | JoinOutcome::Limited | JoinOutcome::Partly
                )
            {
                outcome[j] = JoinOutcome::Reverted;
            }
        }
    };
    for round in 0..3 * n + 3 {
        let pull = round < 3 * n;
        let mut changed = false;
        for (j, a, b) in worse_joins(input, pts, closed, before) {
            pts[a] = input[a].clone();
            pts[b] = input[b].clone();
            outcome[j] = JoinOutcome::Reverted;
            mark(outcome, a);
            mark(outcome, b);
            changed = true;
        }
        for i in 0..n {
            if pts[i] != input[i] && gains_extrema(&pts[i], extrema_before[i]) {
                pts[i] = if pull {
                    let allows = |q: &[Point]| reach.allows(i, q);
                    pull_back((&input[i], &pts[i]), extrema_before[i], grid, allows)
                } else {
                    input[i].clone()
                };
                mark(outcome, i);
                changed = true;
            }
        }
        if !changed {
            return;
        }
    }
    // Still not settled: every moved segment back.
    for i in 0..n {
        if pts[i] != input[i] {
            pts[i] = input[i].clone();
            mark(outcome, i);
        }
    }
}

/// A contour to hold moved versions of it to: what got worse from it to a moved version
/// ([`Baseline::regressions`]) is the segments of every join with a larger angle, or a
/// larger curvature jump where the join is smooth or G1 (the rule [`harmonize`] keeps to), and every cubic with more curvature extrema (the
/// exact test); sorted, once each. What an interpolated instance of repaired masters is
/// held to, against the same instance of the input's masters.
///
/// The input's side (its joins, the exact test of its cubics) is computed once, when the
/// baseline is made, and serves every comparison after.
pub struct Baseline {
    segments: Vec<Vec<Point>>,
    closed: bool,
    limits: Limits,
}

impl Baseline {
    /// The baseline of `segments` (`smooth[j]`: the join after segment j is marked smooth).
    pub fn new(
        segments: &[Vec<Point>],
        closed: bool,
        smooth: &[bool],
        opts: &HarmonizeOptions,
    ) -> Self {
        Baseline {
            segments: segments.to_vec(),
            closed,
            limits: Limits::of(segments, (closed, smooth), opts),
        }
    }

    /// The segments of `after` (the same contour, moved) that got worse (see [`Baseline`]).
    pub fn regressions(&self, after: &[Vec<Point>]) -> Vec<usize> {
        let l = &self.limits;
        spoiled(&self.segments, after, self.closed, (&l.guard, &l.profiles))
    }
}

/// What a repair of a contour is held to, from its input: the joins' jumps and angles, which
/// joins are kept (smooth or G1), the limits no join may pass, and the cubics' profiles.
struct Limits {
    before: Vec<(f64, f64)>,
    kept: Vec<bool>,
    guard: Vec<(f64, f64)>,
    profiles: Vec<Option<Profile>>,
}

impl Limits {
    fn of(
        segments: &[Vec<Point>],
        (closed, smooth): (bool, &[bool]),
        opts: &HarmonizeOptions,
    ) -> Self {
        let before = states(segments, closed);
        let kept = g1_or_smooth(segments, (closed, smooth), &before, opts);
        let guard = guarded(&before, &kept);
        let profiles = segments.iter().map(|s| profile(s)).collect();
        Limits {
            before,
            kept,
            guard,
            profiles,
        }
    }
}

impl Harmonized {
    /// Give `segments` back their input's control points (`input`: what the result was
    /// repaired from) and bring the report up to date: the joins at them `Reverted`, their
    /// jumps and angles after, the moves and extrema.
    pub fn restore(&mut self, input: &[Vec<Point>], closed: bool, segments: &[usize]) {
        for &i in segments {
            self.segments[i] = input[i].clone();
            self.moved[i] = 0.0;
            self.extrema[i].1 = self.extrema[i].0;
            self.bumps.retain(|b| b.segment != i);
        }
        let after = states(&self.segments, closed);
        let n = self.segments.len();
        for j in &mut self.joins {
            let (a, b) = (j.after_segment, (j.after_segment + 1) % n);
            let touched = segments.contains(&a) || segments.contains(&b);
            if touched && j.outcome != JoinOutcome::Corner {
                j.outcome = JoinOutcome::Reverted;
            }
            (j.jump.1, j.angle.1) = after[j.after_segment];
        }
    }
}

/// What [`repair`] does.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Repairs {
    /// Remove hooks and extra extrema first ([`remove_bumps`]).
    pub bumps: bool,
    /// Then harmonize the smooth joins ([`harmonize`]).
    pub harmonize: bool,
    /// An extremum within this fraction of the parameter of an end is a hook.
    pub hook_zone: f64,
}

impl Default for Repairs {
    fn default() -> Self {
        Repairs {
            bumps: true,
            harmonize: true,
            hook_zone: HOOK_ZONE,
        }
    }
}

/// The repairs of a contour in turn: its curvature defects removed ([`remove_bumps`]), then
/// its smooth joins harmonized ([`harmonize`]), the tolerance measured from `segments` for
/// both stages together (no outline moves further than it in all), each stage no worse
/// than the one before; the
/// report compares the result with `segments` (jumps, angles, extrema, moves).
pub fn repair(
    segments: &[Vec<Point>],
    closed: bool,
    smooth: &[bool],
    opts: &HarmonizeOptions,
    what: &Repairs,
) -> crate::Result<Harmonized> {
    repair_holding(
        segments,
        closed,
        (smooth, &vec![false; smooth.len()]),
        opts,
        what,
    )
}

/// [`repair`] with the joins where `held[j]` kept as they are ([`harmonize_holding`]; no
/// bump is removed from a cubic at a held join either).
pub fn repair_holding(
    segments: &[Vec<Point>],
    closed: bool,
    (smooth, held): (&[bool], &[bool]),
    opts: &HarmonizeOptions,
    what: &Repairs,
) -> crate::Result<Harmonized> {
    check_input(segments, closed, smooth, opts)?;
    check_input(segments, closed, held, opts)?;
    let at_held =
        |i: usize| joins(segments.len(), closed).any(|(j, a, b)| held[j] && (a == i || b == i));
    let (start, bumps) = if what.bumps {
        remove_bumps_except(segments, closed, opts, what.hook_zone, &at_held)
    } else {
        (segments.to_vec(), Bumps::default())
    };
    let rest = HarmonizeOptions {
        // No join harmonized when not asked, G1 or not.
        g1_angle: if what.harmonize { opts.g1_angle } else { -1.0 },
        ..*opts
    };
    let none = vec![false; smooth.len()];
    // The tolerance measured from the input, across both stages.
    let reach = Reach {
        original: segments,
        tolerance: opts.tolerance,
    };
    let smooth = if what.harmonize { smooth } else { &none };
    let mut h = harmonize_within(&start, closed, (smooth, held), &rest, &reach);
    // Against the input, not the stage's start.
    let before = states(segments, closed);
    for j in &mut h.joins {
        j.jump.0 = before[j.after_segment].0;
        j.angle.0 = before[j.after_segment].1;
    }
    for (i, s) in segments.iter().enumerate() {
        h.extrema[i].0 = extrema(s);
    }
    h.bumps = bumps.fixed;
    h.bumps_undecided = bumps.undecided;
    Ok(h)
}

/// One cubic whose curvature defect [`remove_bumps`] removed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BumpFix {
    /// The segment.
    pub segment: usize,
    /// Interior curvature extrema before and after.
    pub extrema: (usize, usize),
    /// How far its outline moved ([`outline_move`]).
    pub moved: f64,
}

/// The curvature parameters of a cubic's interior extrema (exact test); None for a line
/// or no verdict.
fn extrema_at(p: &[Point]) -> Option<Vec<f64>> {
    if p.len() != 4 {
        return None;
    }
    let b = Bezier::new(p.to_vec()).ok()?;
    b.curvature_monotone().ok().map(|r| r.extrema)
}

/// Whether the cubic `p` has a curvature defect of type design: a hook (an interior extremum
/// within `zone` of an end) or several extrema (exact test); None for a line or no verdict.
pub fn has_bump(p: &[Point], zone: f64) -> Option<bool> {
    extrema_at(p).map(|ts| is_bump(&ts, zone))
}

/// Whether extrema at `ts` are a defect in type design: one within `zone` of an end (a hook
/// at the join) or more than one.
fn is_bump(ts: &[f64], zone: f64) -> bool {
    ts.len() > 1 || ts.iter().any(|t| *t < zone || *t > 1.0 - zone)
}

/// The curvature defects that matter in type design removed where a change within the
/// tolerance exists: every cubic with a hook (an extremum within `zone` of an end) or more
/// than one extremum gets the handle lengths nearest to its own that make its curvature
/// monotone ([`crate::outline::suggest_handles`]: ends and tangent directions kept), on
/// the grid (its handles' four roundings tried), taken only where it then has fewer
/// extrema and no hook, the outline moves no further than the tolerance, and neither join of the
/// cubic ends with a larger curvature jump or angle than before. A single smooth extremum
/// inside a cubic is left (often the design).
pub fn remove_bumps(
    segments: &[Vec<Point>],
    closed: bool,
    opts: &HarmonizeOptions,
    zone: f64,
) -> (Vec<Vec<Point>>, Vec<BumpFix>) {
    let (pts, bumps) = remove_bumps_except(segments, closed, opts, zone, &|_| false);
    (pts, bumps.fixed)
}

/// What [`remove_bumps_except`] did: the cubics fixed, and those whose search stopped at
/// its budget for exact arithmetic.
#[derive(Default)]
struct Bumps {
    fixed: Vec<BumpFix>,
    undecided: Vec<usize>,
}

/// [`remove_bumps`], leaving the segments where `skip` says so.
fn remove_bumps_except(
    segments: &[Vec<Point>],
    closed: bool,
    opts: &HarmonizeOptions,
    zone: f64,
    skip: &dyn Fn(usize) -> bool,
) -> (Vec<Vec<Point>>, Bumps) {
    let mut pts = segments.to_vec();
    let before = states(segments, closed);
    let mut bumps = Bumps::default();
    for i in (0..pts.len()).filter(|&i| !skip(i)) {
        let Some(ts) = extrema_at(&segments[i]) else {
            continue;
        };
        if !is_bump(&ts, zone) {
            continue;
        }
        let Ok(b) = Bezier::new(segments[i].clone()) else {
            continue;
        };
        // Each cubic's search (hundreds of candidates) under one budget for exact work.
        let (found, refused) =
            crate::monotone::with_exact_budget(crate::monotone::SEARCH_EXACT_BUDGET, || {
                // The monotone handle lengths nearest to the cubic's own first, then the
                // nearest lengths that at least leave fewer extrema and no hook.
                let monotone = crate::outline::suggest_handles(&b, opts.tolerance)
                    .map(|s| s.curve.points().to_vec());
                let ctx = ((segments, &before[..]), (closed, opts));
                monotone
                    .into_iter()
                    .chain(relieving_lengths(&segments[i], opts.tolerance))
                    .find_map(|aim| best_rounding(&mut pts, i, &aim, ctx.0, ctx.1, ts.len(), zone))
            });
        if let Some((q, after)) = found {
            let moved = outline_move(&segments[i], &q);
            pts[i] = q;
            bumps.fixed.push(BumpFix {
                segment: i,
                extrema: (ts.len(), after),
                moved,
            });
        } else if refused {
            bumps.undecided.push(i);
        }
    }
    (pts, bumps)
}

/// Cubics with the handles of `p` scaled (factors 0.5 to 2, log-spaced, 21 × 21), the
/// tangent directions kept, moving the outline no further than `tolerance`
/// ([`outline_move`]), nearest first: candidates for [`remove_bumps`] where no monotone
/// lengths exist.
fn relieving_lengths(p: &[Point], tolerance: f64) -> impl Iterator<Item = Vec<Point>> {
    let (h1, h2) = (p[1] - p[0], p[2] - p[3]);
    let factor = |k: i32| 2f64.powf(k as f64 / 10.0);
    let mut out: Vec<(f64, Vec<Point>)> = Vec::new();
    for i in -10..=10 {
        for k in -10..=10 {
            let (a, b) = (factor(i), factor(k));
            let q = vec![p[0], p[0] + h1 * a, p[3] + h2 * b, p[3]];
            let d = outline_move(p, &q);
            if (i, k) != (0, 0) && d <= tolerance {
                out.push((d, q));
            }
        }
    }
    out.sort_by(|x, y| x.0.total_cmp(&y.0));
    out.into_iter().map(|(_, q)| q)
}

/// The suggested cubic `aim` for segment `i` on the grid (its two handles each at one of
/// their four roundings, the nearest first), if one has fewer than `had` extrema, no hook,
/// moves the outline no further than the tolerance and leaves both of its joins no worse; with its
/// extrema count. `pts[i]` is left as it was.
fn best_rounding(
    pts: &mut [Vec<Point>],
    i: usize,
    aim: &[Point],
    (input, before): (&[Vec<Point>], &[(f64, f64)]),
    (closed, opts): (bool, &HarmonizeOptions),
    had: usize,
    zone: f64,
) -> Option<(Vec<Point>, usize)> {
    let g = opts.grid;
    let options = |q: Point| -> Vec<Point> {
        if g <= 0.0 {
            return vec![q];
        }
        let mut v = grid_corners(q, g).to_vec();
        v.sort_by(|a, b| (*a - q).hypot().total_cmp(&(*b - q).hypot()));
        v
    };
    let keep = pts[i].clone();
    let touched = touching(pts.len(), closed, i);
    for h1 in options(aim[1]) {
        for h2 in options(aim[2]) {
            let q = vec![aim[0], h1, h2, aim[3]];
            if outline_move(&input[i], &q) > opts.tolerance {
                continue;
            }
            pts[i] = q.clone();
            // No join worse, and none with a jump that cannot be told (a NaN jump).
            let joins_ok = touched.iter().all(|&(j, a, b)| {
                let state = join_state(&pts[a], &pts[b]);
                !worse(state, before[j]) && !state.0.is_nan()
            });
            let after = if joins_ok { extrema_at(&q) } else { None };
            if let Some(ts) = after {
                if ts.len() < had && !is_bump(&ts, zone) {
                    pts[i] = keep;
                    return Some((q, ts.len()));
                }
            }
        }
    }
    pts[i] = keep;
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The angle between tangents near 1e308 is what it is at unit size (no overflow to
    /// NaN), and 0 for a zero vector.
    #[test]
    fn tangent_angles_do_not_overflow() {
        let (a, b) = (Vec2::new(1.0, 2.0), Vec2::new(-1.0, -1.0));
        let want = tangent_angle(a, b);
        let huge = tangent_angle(a * 1e300, b * 1e300);
        assert!(
            want.is_finite() && (huge - want).abs() < 1e-15,
            "{huge} vs {want}"
        );
        assert_eq!(tangent_angle(a * 1e-300, Vec2::ZERO), 0.0);
    }

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    /// A cubic of monotone curvature split in two at t = 1/2 (a G2 join), then the two
    /// handles at the join lengthened and shortened: a clear curvature jump, which handle
    /// lengths can undo without a new curvature extremum.
    fn two_cubics() -> Vec<Vec<Point>> {
        let c = Bezier::new(vec![p(0.0, 0.0), p(10.0, 0.0), p(18.0, 4.0), p(22.0, 12.0)]).unwrap();
        let (a, b) = c.subdivide(0.5);
        let (mut a, mut b) = (a.points().to_vec(), b.points().to_vec());
        a[2] = a[3] + (a[2] - a[3]) * 0.8;
        b[1] = b[0] + (b[1] - b[0]) * 1.4;
        vec![a, b]
    }

    #[test]
    fn a_join_at_a_retracted_handle_has_the_checks_jump() {
        // The last join of TeX Gyre Adventor's `ringhalfright` after an earlier stage made
        // its first cubic straight (both handles retracted): the curvature there is 0 (the
        // exact test's limit), so the jump is 1 as `check` says, not NaN (which the
        // safety net takes for "cannot tell" and let through).
        let a = vec![
            p(71.0, 453.0),
            p(67.0, 453.0),
            p(62.0, 448.0),
            p(63.0, 445.0),
        ];
        let b = vec![
            p(63.0, 445.0),
            p(63.0, 445.0),
            p(64.0, 442.0),
            p(64.0, 442.0),
        ];
        let (jump, angle) = join_state(&a, &b);
        assert_eq!(jump, 1.0);
        assert!(angle < 1e-12);
        let check = crate::outline::check_contour(
            &[a.clone(), b.clone()].map(|s| crate::RationalBezier::new(s, vec![1.0; 4]).unwrap()),
            false,
            &crate::outline::OutlineOptions::default(),
        );
        assert_eq!(check.joins[0].curvature_jump, Some(jump));
        // One retracted handle on a curved cubic: the curvature grows without bound, no
        // jump (NaN here, None in the check).
        let c = vec![
            p(63.0, 445.0),
            p(63.0, 445.0),
            p(70.0, 440.0),
            p(80.0, 442.0),
        ];
        assert!(join_state(&a, &c).0.is_nan());
    }

    #[test]
    fn a_smooth_join_becomes_g2_with_its_tangents_kept() {
        let segs = two_cubics();
        let opts = HarmonizeOptions {
            tolerance: 5.0,
            ..Default::default()
        };
        let r = harmonize(&segs, false, &[true], &opts).unwrap();
        let j = r.joins[0];
        assert_eq!(j.outcome, JoinOutcome::Harmonized, "{:?}", r.extrema);
        assert!(j.jump.0 > 0.2, "{j:?}");
        assert!(j.jump.1 < 1e-9, "{j:?}");
        // Tangent directions exactly as before (the handles slid along them).
        for (s, t) in segs.iter().zip(&r.segments) {
            assert_eq!(s[0], t[0]);
            assert_eq!(s[3], t[3]);
            let (a, b) = (s[1] - s[0], t[1] - t[0]);
            assert!(a.cross(b).abs() <= 1e-12 * a.hypot() * b.hypot());
            let (a, b) = (s[3] - s[2], t[3] - t[2]);
            assert!(a.cross(b).abs() <= 1e-12 * a.hypot() * b.hypot());
        }
        assert!(r.moved.iter().all(|m| *m <= 5.0 + 1e-12), "{:?}", r.moved);
        assert!(r.sweeps.converged);
        for (b, a) in &r.extrema {
            assert!(a <= b, "{:?}", r.extrema);
        }
    }

    /// A round dot as TeX Gyre Bonum draws it (`dotbelowcomb`, radius 59 on the 1-unit
    /// grid, its top point one unit off centre): every small float change spoils the
    /// extrema rule on its wobbling quarter arcs, so the float stages leave it; the
    /// lengths searched on the grid make its two jumps (15 % and 6 %) no more than
    /// 2 %, one under 1 %, and take away its three hooks, with no cubic gaining an extremum.
    #[test]
    fn a_round_dot_is_harmonized_on_the_grid() {
        let q = |v: [(f64, f64); 4]| v.iter().map(|&(x, y)| p(x, y)).collect::<Vec<_>>();
        let segs = vec![
            q([(396., -150.), (396., -118.), (369., -91.), (338., -91.)]),
            q([(338., -91.), (305., -91.), (278., -117.), (278., -150.)]),
            q([(278., -150.), (278., -182.), (305., -209.), (337., -209.)]),
            q([(337., -209.), (369., -209.), (396., -182.), (396., -150.)]),
        ];
        let hooked = |s: &[Point]| {
            let ts = extrema_at(s).unwrap();
            ts.iter().any(|t| *t < HOOK_ZONE || *t > 1.0 - HOOK_ZONE)
        };
        assert_eq!(segs.iter().filter(|s| hooked(s)).count(), 3);
        let opts = HarmonizeOptions {
            tolerance: 2.0,
            grid: 1.0,
            ..Default::default()
        };
        let r = harmonize(&segs, true, &[true; 4], &opts).unwrap();
        assert!(r.segments.iter().all(|s| !hooked(s)), "{:?}", r.segments);
        for (b, a) in &r.extrema {
            assert!(a <= b, "{:?}", r.extrema);
        }
        let jumps: Vec<f64> = r.joins.iter().map(|j| j.jump.1).collect();
        assert!(jumps.iter().all(|j| *j <= 0.02), "{jumps:?}");
        assert!(
            jumps.iter().filter(|j| **j < 0.01).count() >= 3,
            "{jumps:?}"
        );
        // The report says what the delivered joins are: under 1 % is Harmonized.
        for j in &r.joins {
            assert_eq!(
                j.jump.1 < 0.01,
                j.outcome == JoinOutcome::Harmonized,
                "{j:?}"
            );
        }
        for (s, t) in segs.iter().zip(&r.segments) {
            assert!(t.iter().all(|c| c.x.fract() == 0.0 && c.y.fract() == 0.0));
            assert!(outline_distance(s, t) <= 2.0);
            assert!(crate::bezier::sampled_shape_distance(s, t) <= 2.0);
        }
    }

    /// TeX Gyre Adventor's `tilde` (two lines, eight cubics, six smooth joins): every
    /// join's label says what was delivered, `Harmonized` exactly when its jump ends under
    /// the G2 threshold (before, joins the grid's second pass took under it were still
    /// `Limited`, and joins whose near handles went back but whose far ones made them G2
    /// `Reverted`).
    #[test]
    fn join_labels_say_what_was_delivered() {
        let q = |v: &[(f64, f64)]| v.iter().map(|&(x, y)| p(x, y)).collect::<Vec<_>>();
        let segs = vec![
            q(&[(76., 673.), (108., 618.)]),
            q(&[(108., 618.), (121., 641.), (138., 664.), (164., 664.)]),
            q(&[(164., 664.), (175., 664.), (202., 648.), (220., 638.)]),
            q(&[(220., 638.), (243., 625.), (267., 615.), (293., 615.)]),
            q(&[(293., 615.), (324., 615.), (348., 639.), (365., 667.)]),
            q(&[(365., 667.), (333., 722.)]),
            q(&[(333., 722.), (319., 699.), (302., 676.), (276., 676.)]),
            q(&[(276., 676.), (265., 676.), (238., 692.), (220., 702.)]),
            q(&[(220., 702.), (197., 715.), (173., 725.), (147., 725.)]),
            q(&[(147., 725.), (116., 725.), (92., 701.), (76., 673.)]),
        ];
        let smooth = [
            false, true, true, true, false, false, true, true, true, false,
        ];
        let opts = HarmonizeOptions {
            tolerance: 2.0,
            grid: 1.0,
            ..Default::default()
        };
        let r = harmonize(&segs, true, &smooth, &opts).unwrap();
        let smooth_joins: Vec<&JoinReport> =
            r.joins.iter().filter(|j| smooth[j.after_segment]).collect();
        assert!(
            smooth_joins.iter().any(|j| j.jump.1 < 0.01),
            "{:?}",
            r.joins
        );
        for j in smooth_joins {
            let moved = !matches!(
                j.outcome,
                JoinOutcome::AlreadyG2 | JoinOutcome::SignChange | JoinOutcome::NotBetweenCubics
            );
            if moved {
                assert_eq!(
                    j.jump.1 < 0.01,
                    j.outcome == JoinOutcome::Harmonized,
                    "{j:?}"
                );
            }
        }
    }

    /// With `move_points`, the join's point slides along the line of its two handles to
    /// where the join is G2, the handles staying where they were.
    #[test]
    fn the_on_curve_point_moves_along_its_handles_to_g2() {
        let segs = two_cubics();
        let opts = HarmonizeOptions {
            tolerance: 5.0,
            move_points: true,
            ..Default::default()
        };
        let r = harmonize(&segs, false, &[true], &opts).unwrap();
        let j = r.joins[0];
        assert!(j.jump.1 < 1e-9, "{j:?}");
        let (a, b) = (&r.segments[0], &r.segments[1]);
        assert_eq!(a[3], b[0]);
        assert_eq!((a[2], b[1]), (segs[0][2], segs[1][1]), "the handles moved");
        let (u, v) = (a[3] - a[2], b[1] - a[3]);
        assert!(
            u.cross(v).abs() <= 1e-9 * u.hypot() * v.hypot(),
            "off the handles' line"
        );
        assert!((a[3] - segs[0][3]).hypot() <= 5.0);
    }

    /// A cubic whose coordinates span 600 orders of magnitude, with three curvature extrema:
    /// the floating-point filter decides none of the repair's candidates and each exact
    /// stage works on 21,000-bit coefficients (20 s for the whole search before the budget).
    /// The search stops at its budget, says so, and leaves the cubic as it was; the verdict
    /// on the cubic alone, outside any search, is still exact.
    #[test]
    fn a_search_the_filter_cannot_decide_stops_at_its_budget_and_says_so() {
        let wide = vec![
            p(-1.0, 1e-300),
            p(1.0, -1.0),
            p(1e300, 0.33530130125527186),
            p(1e-300, -1e300),
        ];
        let ts = extrema_at(&wide).expect("decided exactly alone");
        assert_eq!(ts.len(), 3, "{ts:?}");
        let opts = HarmonizeOptions {
            tolerance: 1e300,
            ..Default::default()
        };
        let h = repair(
            std::slice::from_ref(&wide),
            false,
            &[],
            &opts,
            &Repairs::default(),
        )
        .unwrap();
        assert_eq!(h.bumps_undecided, [0]);
        assert!(h.bumps.is_empty());
        assert_eq!(h.segments[0], wide);
        // A font's hooked cubic is not near the budget.
        let hooked = vec![p(0.0, 0.0), p(0.5, 2.0), p(6.0, 1.0), p(10.0, 0.0)];
        let opts = HarmonizeOptions {
            tolerance: 3.0,
            ..Default::default()
        };
        let h = repair(&[hooked], false, &[], &opts, &Repairs::default()).unwrap();
        assert_eq!((h.bumps.len(), h.bumps_undecided.len()), (1, 0));
    }

    /// A cubic with a curvature hook at its start (an extremum at t ≈ 0.04) loses it to
    /// new handle lengths within the tolerance, its ends and tangents kept; a cubic with one
    /// smooth extremum inside is left.
    #[test]
    fn a_hook_is_removed_within_the_tolerance() {
        let hooked = vec![vec![p(0.0, 0.0), p(0.5, 2.0), p(6.0, 1.0), p(10.0, 0.0)]];
        let opts = HarmonizeOptions {
            tolerance: 3.0,
            ..Default::default()
        };
        let (out, fixes) = remove_bumps(&hooked, false, &opts, 0.05);
        assert_eq!(fixes.len(), 1, "{fixes:?}");
        let ts = extrema_at(&out[0]).unwrap();
        assert!(!is_bump(&ts, 0.05), "{ts:?}");
        assert!(fixes[0].moved <= 3.0);
        let (a, b) = (&hooked[0], &out[0]);
        assert_eq!((a[0], a[3]), (b[0], b[3]));
        assert!((a[1] - a[0]).cross(b[1] - b[0]).abs() < 1e-9);
        assert!((a[2] - a[3]).cross(b[2] - b[3]).abs() < 1e-9);
        // One smooth extremum in the middle: the design, not a bump.
        let bowl = vec![vec![p(0.0, 0.0), p(3.0, 4.0), p(7.0, 4.0), p(10.0, 0.0)]];
        let (out, fixes) = remove_bumps(&bowl, false, &opts, 0.05);
        assert!(fixes.is_empty());
        assert_eq!(out, bowl);
    }

    #[test]
    fn the_tolerance_holds_the_handles_short_of_g2() {
        let segs = two_cubics();
        let opts = HarmonizeOptions {
            tolerance: 0.02,
            ..Default::default()
        };
        let r = harmonize(&segs, false, &[true], &opts).unwrap();
        let j = r.joins[0];
        assert_eq!(j.outcome, JoinOutcome::Limited, "{j:?}");
        assert!(j.jump.1 < j.jump.0 && j.jump.1 > 1e-6, "{j:?}");
        assert!(r.moved.iter().all(|m| *m <= 0.02 + 1e-12), "{:?}", r.moved);
        // The oracle: the two outlines sampled, each point's distance to the other shape
        // (not outline_distance).
        for (a, b) in segs.iter().zip(&r.segments) {
            assert!(crate::bezier::sampled_shape_distance(a, b) <= 0.02 + 1e-12);
        }
    }

    /// `max_t |b(t) - a(t)|` over 20001 parameters, from the Bernstein sums (a lower bound
    /// of the true maximum, and close to it).
    fn sampled_distance(a: &[Point], b: &[Point]) -> f64 {
        let n = a.len() - 1;
        let at = |p: &[Point], t: f64| {
            let mut c = Vec2::ZERO;
            for (i, q) in p.iter().enumerate() {
                let binom = (0..i).fold(1.0, |x, k| x * (n - k) as f64 / (k + 1) as f64);
                c += q.to_vec2() * (binom * t.powi(i as i32) * (1.0 - t).powi((n - i) as i32));
            }
            c
        };
        (0..=20000)
            .map(|k| k as f64 / 20000.0)
            .map(|t| (at(b, t) - at(a, t)).hypot())
            .fold(0.0, f64::max)
    }

    /// A small deterministic generator (xorshift) for the property tests below.
    fn random(seed: &mut u64) -> f64 {
        *seed ^= *seed << 13;
        *seed ^= *seed >> 7;
        *seed ^= *seed << 17;
        (*seed >> 11) as f64 / (1u64 << 53) as f64
    }

    /// outline_move is an upper bound of the distance the sampled outlines give, and within
    /// 1e-3 of it, for lines and cubics at scales from 1e-3 to 1e6; a handle alone moved by d
    /// moves the outline by 4/9 d, both handles moved the same way by d by 3/4 d.
    #[test]
    fn outline_move_bounds_the_distance_between_the_outlines() {
        let mut seed = 0x2545_f491_4f6c_dd1d;
        for k in 0..300 {
            let scale = 10f64.powi(k % 10 - 3);
            let deg = if k % 5 == 0 { 1 } else { 3 };
            let mut r = || (random(&mut seed) - 0.5) * scale;
            let a: Vec<Point> = (0..=deg).map(|_| Point::new(r(), r())).collect();
            let b: Vec<Point> = a.iter().map(|q| *q + Vec2::new(r(), r()) * 0.1).collect();
            let (bound, sampled) = (outline_move(&a, &b), sampled_distance(&a, &b));
            assert!(
                sampled <= bound && bound <= sampled * (1.0 + 1e-3),
                "{a:?} {b:?}: {bound} vs {sampled}"
            );
        }
        let a = vec![p(0.0, 0.0), p(30.0, 0.0), p(70.0, 40.0), p(70.0, 70.0)];
        let mut b = a.clone();
        b[1].x += 9.0;
        assert!((outline_move(&a, &b) - 4.0).abs() < 1e-3);
        b[2].x += 9.0;
        assert!((outline_move(&a, &b) - 6.75).abs() < 1e-3);
    }

    /// The handle radii of Reach keep the sampled outline within the tolerance: ends moved
    /// by m (any direction), both handles by 4/3 T - m/3 or one by 9/4 T - 5/4 m (any
    /// directions).
    #[test]
    fn the_handle_radii_keep_the_outline_within_the_tolerance() {
        let mut seed = 0x9e37_79b9_7f4a_7c15;
        let original = vec![vec![
            p(0.0, 0.0),
            p(40.0, 5.0),
            p(80.0, 60.0),
            p(90.0, 100.0),
        ]];
        let tol = 2.0;
        let reach = Reach {
            original: &original,
            tolerance: tol,
        };
        for k in 0..400 {
            let mut dir = |len: f64| {
                let a = random(&mut seed) * std::f64::consts::TAU;
                Vec2::new(a.cos(), a.sin()) * len
            };
            let m = tol * (k % 11) as f64 / 10.0;
            let o = &original[0];
            let mut now = vec![o[0] + dir(m), o[1], o[2], o[3] + dir(m)];
            let alone = k % 2 == 0;
            let radius = reach.handle_radius(0, &now, alone);
            now[1] = o[1] + dir(radius);
            if !alone {
                now[2] = o[2] + dir(radius);
            }
            let d = sampled_distance(o, &now);
            assert!(d <= tol * (1.0 + 1e-9), "m {m}, alone {alone}: {d}");
        }
    }

    #[test]
    fn corners_lines_and_inflections_are_left_alone() {
        let segs = two_cubics();
        // Not marked smooth, and only the marks count: a corner.
        let flags_only = HarmonizeOptions {
            g1_angle: -1.0,
            ..Default::default()
        };
        let r = harmonize(&segs, false, &[false], &flags_only).unwrap();
        assert_eq!(r.segments, segs);
        assert_eq!(r.joins[0].outcome, JoinOutcome::Corner);
        // By default a G1 join is harmonized, marked or not.
        let r = harmonize(&segs, false, &[false], &HarmonizeOptions::default()).unwrap();
        assert!(
            matches!(
                r.joins[0].outcome,
                JoinOutcome::Harmonized | JoinOutcome::Limited
            ),
            "{:?}",
            r.joins
        );
        let start = segs[1][0];
        let line = vec![vec![start - (segs[1][1] - start), start], segs[1].clone()];
        let r = harmonize(&line, false, &[true], &HarmonizeOptions::default()).unwrap();
        assert_eq!(r.segments, line);
        assert_eq!(r.joins[0].outcome, JoinOutcome::NotBetweenCubics);
        // An S at the join: the second cubic bends the other way.
        // The second cubic mirrored in its start tangent.
        let (o, t) = (segs[1][0], (segs[1][1] - segs[1][0]).normalize());
        let mirror = |q: Point| {
            let d = q - o;
            o + t * (2.0 * d.dot(t)) - d
        };
        let s = vec![
            segs[0].clone(),
            segs[1].iter().map(|q| mirror(*q)).collect(),
        ];
        let r = harmonize(&s, false, &[true], &HarmonizeOptions::default()).unwrap();
        assert_eq!(r.joins[0].outcome, JoinOutcome::SignChange);
        assert_eq!(r.segments, s);
    }

    /// A closed contour of four cubics whose joins couple: the sweeps converge, the move is
    /// shared back until no cubic gains an extremum, and on a unit grid no join ends worse
    /// than it began.
    #[test]
    fn a_closed_contour_converges_and_the_grid_makes_nothing_worse() {
        // A quarter-ellipse per cubic (G2 by symmetry), each handle then scaled.
        let (ea, eb, k) = (120.0, 80.0, 0.5523);
        let q = [p(ea, 0.0), p(0.0, eb), p(-ea, 0.0), p(0.0, -eb), p(ea, 0.0)];
        let dir = [
            Vec2::new(0.0, eb),
            Vec2::new(-ea, 0.0),
            Vec2::new(0.0, -eb),
            Vec2::new(ea, 0.0),
        ];
        let f = [(1.2, 0.85), (1.1, 0.9), (0.8, 1.15), (1.05, 0.7)];
        let segs: Vec<Vec<Point>> = (0..4)
            .map(|i| {
                let (a, b) = (q[i], q[i + 1]);
                vec![
                    a,
                    a + dir[i] * (k * f[i].0),
                    b - dir[(i + 1) % 4] * (k * f[i].1),
                    b,
                ]
            })
            .collect();
        let free = harmonize(
            &segs,
            true,
            &[true; 4],
            &HarmonizeOptions {
                tolerance: 30.0,
                ..Default::default()
            },
        )
        .unwrap();
        assert!(free.sweeps.converged, "{:?}", free.sweeps);
        // Part of the way (the whole way gives the monotone cubics an extremum each): no
        // join worse, and the jumps' sum less than half what it was.
        let sum = |r: &Harmonized| -> (f64, f64) {
            r.joins
                .iter()
                .fold((0.0, 0.0), |s, j| (s.0 + j.jump.0, s.1 + j.jump.1))
        };
        for j in &free.joins {
            assert!(j.jump.1 <= j.jump.0, "{j:?}");
        }
        let (b, a) = sum(&free);
        assert!(a < 0.5 * b, "{a} vs {b}: {:?}", free.joins);
        let grid = harmonize(
            &segs,
            true,
            &[true; 4],
            &HarmonizeOptions {
                tolerance: 30.0,
                grid: 1.0,
                ..Default::default()
            },
        )
        .unwrap();
        // Every moved point on the grid (the input's own points stay where they were).
        for (s, t) in segs.iter().zip(&grid.segments) {
            assert_eq!(s.len(), t.len());
            for (q0, q) in s.iter().zip(t) {
                if q0 != q {
                    assert_eq!((q.x.fract(), q.y.fract()), (0.0, 0.0), "{t:?}");
                }
            }
        }
        for j in &grid.joins {
            assert!(
                j.jump.1 <= j.jump.0 && j.angle.1 <= j.angle.0 + 1e-15,
                "{j:?}"
            );
            assert!(
                j.outcome != JoinOutcome::Harmonized || j.jump.1 < 0.01,
                "{j:?}"
            );
        }
        for (b, a) in &grid.extrema {
            assert!(a <= b, "{:?}", grid.extrema);
        }
        let (b, a) = sum(&grid);
        assert!(a < 0.6 * b, "{a} vs {b}: {:?}", grid.joins);
    }
}
