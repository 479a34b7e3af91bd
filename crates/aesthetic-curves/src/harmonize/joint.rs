//! The joint stage: every free handle length of a contour solved at once, after the sweep.
//!
//! The sweep solves one join at a time and moves only the two handles at it, inside a box
//! that fits the tolerance for both handles of a cubic moving their most. It leaves two
//! levers unused: the curvature at a cubic's end also depends on its *far* handle (the far
//! handle's distance from the end's tangent line changes as it slides), and the tolerance
//! allows more than the box wherever one handle needs less than the other. Measured on
//! TeX Gyre Adventor at T = 2 font units off the grid, a joint optimum (scipy's SLSQP,
//! ignoring the extrema rules) puts 87 % of the smooth joins under 1 % where the sweep
//! put 59 %; with this stage `aecurve fix` puts 78 % there on the grid (67 % before).
//!
//! **The problem.** The unknowns are, per free cubic (a cubic with both handles, not held,
//! next to a moving join), the two length changes `Δ = (Δu, Δv)` from the stage's start.
//! Its outline moves from the original's by `D(t) = f(t) + Δu B₁(t) d₀ − Δv B₂(t) d₁`
//! (`f` the start's own move, `d₀`, `d₁` the unit handle directions): affine in Δ, so the
//! Δ that keep `max_t |D(t)| ≤ T` form a convex set around 0. It is mapped onto the whole
//! plane, `Δ = ρ(w) tanh|z| w` for `w = z/|z|`, with `ρ(w)` the distance from 0 to the
//! set's boundary along `w` (closed form per sample of t, and the handle lengths kept
//! positive), so that Levenberg–Marquardt ([`crate::solve::least_squares`]) runs without
//! constraints and slides along the tolerance's boundary instead of stopping at it. The
//! residuals are the joins' relative curvature differences `(κ_A − κ_B)/√(κ_A² + κ_B²)`,
//! a hinge per join a free cubic touches (no jump past the input's), and per free cubic the
//! extrema rule ([`shape_samples`]: the sign of dκ/dt kept where the rule asks it), so that
//! the optimum keeps the rules the exact test enforces after instead of being handed back
//! (on Adventor, cubics handed back in the first round: 847 without, about 400 with); the
//! Jacobian is the forward difference of the residuals each unknown touches.
//!
//! **Soundness.** `ρ` is taken on samples and a little inside the tolerance; every cubic
//! of the result is checked with the sound bound ([`super::Reach::allows`]) and pulled
//! back towards its start until it passes.

use super::{end_curvatures, Handles, Reach};
use crate::solve::least_squares::{levenberg_marquardt_dyn, LmOptions, Stop};
use crate::{Point, Vec2};
use kurbo::{ParamCurve, ParamCurveDeriv};

/// Samples of t for the tolerance's boundary.
const SAMPLES: usize = 64;

/// The model's move at equal parameters counts at this share (the normal part in full):
/// a handle sliding along its tangent moves its cubic mostly along itself, which
/// [`crate::bezier::outline_distance`] does not count.
const PARAMETRIC_SHARE: f64 = 0.25;

/// The share of the tolerance the samples may use (the sound bound decides the rest).
const INSIDE: f64 = 1.0 - 1e-3;

/// Residuals past this grow only logarithmically (`c asinh(r/c)`): a join no length can
/// make G2 (a designed curvature step, a sign change) does not pull its neighbours away
/// from G2 (measured on Adventor at T = 2 on the grid: 73.9 % under 1 % plain, 74.3 %
/// with this).
const ROBUST: f64 = 0.02;

/// How much the shape residuals weigh against the joins' (a sign the extrema rule forbids
/// costs as much as a join 10 % off G2).
const SHAPE_WEIGHT: f64 = 1.0;

/// How much a guarded join's excess weighs (a penalty: the solver's optimum leaves a
/// little of what it weighs against, so the hinge starts at [`GUARD_SHARE`] of the limit).
const GUARD_WEIGHT: f64 = 1.0;

/// Where a guarded join's hinge starts, as a share of its input's jump.
const GUARD_SHARE: f64 = 0.98;

/// The margin the shape residuals keep: the sign of dκ/dt held with a tenth of the
/// original's slope (relative), so that the exact test after finds no extremum between
/// samples where there was none.
const SHAPE_MARGIN: f64 = 0.1;

/// A cubic's curvature and its derivative in t at `t`: `κ = G/|x'|³` and
/// `dκ/dt = (G'|x'|² − 3G x'·x'')/|x'|⁵` with `G = x' × x''` (the exact test's numerator,
/// [`crate::monotone`], in floating point here: the residuals only steer, the exact test
/// decides after).
fn curvature_slope(p: &[Point; 4], t: f64) -> (f64, f64) {
    let (d0, d1, d2) = (p[1] - p[0], p[2] - p[1], p[3] - p[2]);
    let m = 1.0 - t;
    let x1 = (d0 * (m * m) + d1 * (2.0 * t * m) + d2 * (t * t)) * 3.0;
    let x2 = ((d1 - d0) * m + (d2 - d1) * t) * 6.0;
    let x3 = (d2 - d1 * 2.0 + d0) * 6.0;
    let (g, g1, v2) = (x1.cross(x2), x1.cross(x3), x1.dot(x1));
    let v = v2.sqrt();
    (
        g / (v2 * v),
        (g1 * v2 - 3.0 * g * x1.dot(x2)) / (v2 * v2 * v),
    )
}

/// The extrema rule as residuals: samples of t where the original's curvature slope has a
/// sign the result must keep, each with the sign and the slope's scale: everywhere on a
/// monotone original (no extremum may appear), else in its hook zones without an extremum
/// (its extrema may move, but not into one; more extrema inside are left to the exact
/// test after, which hands such a cubic back).
fn shape_samples(original: &[Point], hook_zone: f64) -> Vec<Sample> {
    let Ok(o) = <[Point; 4]>::try_from(original) else {
        return Vec::new();
    };
    let ts = super::extrema_at(original).unwrap_or_default();
    let zone = |t: f64| t < hook_zone || t > 1.0 - hook_zone;
    let grid = (1..64).map(|k| k as f64 / 64.0);
    let ends = (0..5).flat_map(|k| {
        let t = 0.002 + k as f64 * 0.01;
        [t, 1.0 - t]
    });
    let raw: Vec<(f64, f64, f64)> = (grid.chain(ends))
        .map(|t| {
            let (k, dk) = curvature_slope(&o, t);
            (t, k.abs(), dk)
        })
        .collect();
    let scale = raw.iter().map(|r| r.1).fold(0.0, f64::max);
    let top = raw.iter().map(|r| r.2.abs()).fold(0.0, f64::max) / scale.max(f64::MIN_POSITIVE);
    if !(scale > 0.0 && top.is_finite() && top > 0.0) {
        return Vec::new();
    }
    let monotone = ts.is_empty();
    raw.into_iter()
        .filter(|&(t, _, dk)| {
            // Asked everywhere on a monotone cubic; else only in a hook zone with no
            // extremum of the original (its extrema move freely, but not into one).
            let free =
                !monotone && (!zone(t) || ts.iter().any(|&e| zone(e) && (t < 0.5) == (e < 0.5)));
            !free && (dk / scale).abs() > 0.02 * top
        })
        .map(|(t, _, dk)| {
            let g = dk / scale;
            Sample {
                t,
                sign: g.signum(),
                inv: 1.0 / (scale * g.abs().max(0.05 * top)),
            }
        })
        .collect()
}

/// One sample of the extrema rule ([`shape_samples`]).
#[derive(Clone, Copy, Debug)]
struct Sample {
    t: f64,
    /// The sign the curvature slope keeps.
    sign: f64,
    /// One over the original's slope scale there.
    inv: f64,
}

/// One free cubic: its start and what its outline's move is made of.
struct Free {
    /// The segment index.
    seg: usize,
    /// The start's handle lengths.
    start: (f64, f64),
    /// Per sample: the start's move from the original, and the moves per unit of Δu, Δv.
    samples: Vec<(Vec2, Vec2, Vec2)>,
    /// The smallest lengths allowed.
    floor: (f64, f64),
    /// Which of the two handles may slide (those at moving joins).
    mask: (bool, bool),
    /// The extrema rule's samples.
    shape: Vec<Sample>,
}

impl Free {
    /// How far from the start along the unit direction `w` the set reaches.
    fn reach(&self, w: (f64, f64), tolerance: f64) -> f64 {
        let t2 = (tolerance * INSIDE).powi(2);
        let mut rho = f64::INFINITY;
        for &(f, g0, g1) in &self.samples {
            let g = g0 * w.0 + g1 * w.1;
            let (gg, fg, ff) = (g.dot(g), f.dot(g), f.dot(f));
            if gg <= 0.0 {
                continue;
            }
            let disc = fg * fg - gg * (ff - t2);
            let s = if disc > 0.0 {
                ((-fg + disc.sqrt()) / gg).max(0.0)
            } else {
                0.0
            };
            rho = rho.min(s);
        }
        for (wk, (start, floor)) in [
            (w.0, (self.start.0, self.floor.0)),
            (w.1, (self.start.1, self.floor.1)),
        ] {
            if wk < 0.0 {
                rho = rho.min(((start - floor) / -wk).max(0.0));
            }
        }
        rho
    }

    /// The lengths for the unknowns `z`.
    fn lengths(&self, z: (f64, f64), tolerance: f64) -> (f64, f64) {
        let r = z.0.hypot(z.1);
        if r == 0.0 || !r.is_finite() {
            return self.start;
        }
        let w = (z.0 / r, z.1 / r);
        let s = self.reach(w, tolerance) * r.tanh();
        (self.start.0 + s * w.0, self.start.1 + s * w.1)
    }

    /// The unknowns for the lengths `len` (inside the set, else its boundary's near side).
    fn unknowns(&self, len: (f64, f64), tolerance: f64) -> (f64, f64) {
        let d = (len.0 - self.start.0, len.1 - self.start.1);
        let r = d.0.hypot(d.1);
        if r == 0.0 {
            return (0.0, 0.0);
        }
        let w = (d.0 / r, d.1 / r);
        let rho = self.reach(w, tolerance);
        if rho <= 0.0 {
            return (0.0, 0.0);
        }
        let a = (r / rho).min(0.99).atanh();
        (a * w.0, a * w.1)
    }
}

/// The contour's joint problem.
struct Problem<'a> {
    segs: &'a [Vec<Point>],
    h: &'a Handles,
    tolerance: f64,
    free: Vec<Free>,
    /// The unknowns: (index in `free`, handle 0 or 1).
    vars: Vec<(usize, usize)>,
    /// The moving joins: (segment before, segment after).
    joins: Vec<(usize, usize)>,
    /// The joins a free cubic touches with their jump limit (no worse than the input).
    guards: Vec<(usize, usize, f64)>,
}

impl Problem<'_> {
    /// The control points of cubic `i` with `len`, each handle rebuilt from its unit
    /// direction (within rounding of [`Handles::points`], which the stage delivers and the
    /// grid stage checks again with the sound bound).
    fn cubic(&self, i: usize, len: (f64, f64)) -> [Point; 4] {
        let s = &self.segs[i];
        let (d0, d1) = self.h.dirs[i].unwrap_or((Vec2::ZERO, Vec2::ZERO));
        [s[0], s[0] + d0 * len.0, s[3] - d1 * len.1, s[3]]
    }

    /// Every segment's lengths for the unknowns `x`.
    fn lengths(&self, x: &[f64]) -> Vec<(f64, f64)> {
        let mut len = self.h.len.clone();
        for (k, z) in self.unknowns_of(x).into_iter().enumerate() {
            let f = &self.free[k];
            len[f.seg] = f.lengths(z, self.tolerance);
        }
        len
    }

    /// The unknowns `x` per free cubic (0 for a handle that stays).
    fn unknowns_of(&self, x: &[f64]) -> Vec<(f64, f64)> {
        let mut z = vec![(0.0, 0.0); self.free.len()];
        for (&(k, c), v) in self.vars.iter().zip(x) {
            if c == 0 {
                z[k].0 = *v;
            } else {
                z[k].1 = *v;
            }
        }
        z
    }

    /// The curvatures on both sides of the join (a, b) with the lengths `len`.
    fn sides(&self, (a, b): (usize, usize), len: &[(f64, f64)]) -> (f64, f64) {
        let ka = end_curvatures(&self.cubic(a, len[a])).1;
        let kb = end_curvatures(&self.cubic(b, len[b])).0;
        (ka, kb)
    }

    /// The residual of the join (a, b) with the lengths `len`.
    fn residual(&self, join: (usize, usize), len: &[(f64, f64)]) -> f64 {
        let (ka, kb) = self.sides(join, len);
        let m = (ka * ka + kb * kb).sqrt();
        let r = if m > 0.0 { (ka - kb) / m } else { 0.0 };
        ROBUST * (r / ROBUST).asinh()
    }

    /// The hinge of a guarded join: how far its jump passes the input's.
    fn guard(&self, (a, b, limit): (usize, usize, f64), len: &[(f64, f64)]) -> f64 {
        let (ka, kb) = self.sides((a, b), len);
        GUARD_WEIGHT * (super::relative_jump(ka, kb) - GUARD_SHARE * limit).max(0.0)
    }

    /// The shape residual of free cubic `k` with its lengths `len`: the norm of its
    /// samples' hinges (one residual per cubic, the same sum of squares).
    fn shape(&self, k: usize, len: (f64, f64)) -> f64 {
        let f = &self.free[k];
        let q = self.cubic(f.seg, len);
        let sq: f64 = (f.shape.iter())
            .map(|s| {
                let slope = curvature_slope(&q, s.t).1 * s.sign * s.inv;
                (SHAPE_MARGIN - slope).max(0.0).powi(2)
            })
            .sum();
        SHAPE_WEIGHT * sq.sqrt()
    }

    fn residuals(&self, x: &[f64], out: &mut Vec<f64>) -> Option<()> {
        let len = self.lengths(x);
        out.clear();
        out.extend(self.joins.iter().map(|&j| self.residual(j, &len)));
        out.extend(self.guards.iter().map(|&g| self.guard(g, &len)));
        out.extend((self.free.iter().enumerate()).map(|(k, f)| self.shape(k, len[f.seg])));
        out.iter().all(|r| r.is_finite()).then_some(())
    }

    /// The residuals and their columns: each unknown moves the joins of its own cubic.
    fn jacobian(&self, x: &[f64], out: &mut Vec<f64>, cols: &mut [Vec<f64>]) -> Option<()> {
        self.residuals(x, out)?;
        let mut len = self.lengths(x);
        let z = self.unknowns_of(x);
        for (c, col) in cols.iter_mut().enumerate() {
            col.clear();
            col.resize(out.len(), 0.0);
            let (k, which) = self.vars[c];
            let f = &self.free[k];
            let step = 1e-7 * x[c].abs().max(1.0);
            let mut zp = z[k];
            if which == 0 {
                zp.0 += step;
            } else {
                zp.1 += step;
            }
            let keep = len[f.seg];
            len[f.seg] = f.lengths(zp, self.tolerance);
            for (r, &j) in self.joins.iter().enumerate() {
                if j.0 == f.seg || j.1 == f.seg {
                    col[r] = (self.residual(j, &len) - out[r]) / step;
                }
            }
            let at = self.joins.len();
            for (r, &g) in self.guards.iter().enumerate() {
                if g.0 == f.seg || g.1 == f.seg {
                    col[at + r] = (self.guard(g, &len) - out[at + r]) / step;
                }
            }
            let r = at + self.guards.len() + k;
            col[r] = (self.shape(k, len[f.seg]) - out[r]) / step;
            len[f.seg] = keep;
            if !col.iter().all(|v| v.is_finite()) {
                return None;
            }
        }
        Some(())
    }
}

/// The free cubic `i` of the stage's start `segs` whose handles `mask` may slide, or None.
fn free(
    segs: &[Vec<Point>],
    h: &Handles,
    reach: &Reach,
    (i, mask): (usize, (bool, bool)),
) -> Option<Free> {
    let (d0, d1) = h.dirs[i]?;
    if !(mask.0 || mask.1) {
        return None;
    }
    let cubic = |p: &[Point]| kurbo::CubicBez::new(p[0], p[1], p[2], p[3]);
    let (s, o) = (cubic(&segs[i]), cubic(&reach.original[i]));
    let od = o.deriv();
    let samples = (0..=SAMPLES)
        .flat_map(|k| {
            let t = k as f64 / SAMPLES as f64;
            let m = 1.0 - t;
            let f = s.eval(t) - o.eval(t);
            let (g0, g1) = (d0 * (3.0 * t * m * m), -d1 * (3.0 * t * t * m));
            // Off the original's outline: the move's normal part (the tangential part
            // slides along the curve); and at equal parameters, PARAMETRIC_SHARE of it.
            let tangent = od.eval(t).to_vec2();
            let n = Vec2::new(-tangent.y, tangent.x) / tangent.hypot();
            let normal = |v: Vec2| n * n.dot(v);
            let off = (normal(f), normal(g0), normal(g1));
            let along = (
                f * PARAMETRIC_SHARE,
                g0 * PARAMETRIC_SHARE,
                g1 * PARAMETRIC_SHARE,
            );
            [off, along]
                .into_iter()
                .filter(|x| x.0.is_finite() && x.1.is_finite())
        })
        .collect();
    let start = h.orig[i];
    Some(Free {
        seg: i,
        start,
        samples,
        floor: (1e-3 * start.0, 1e-3 * start.1),
        mask,
        shape: shape_samples(&reach.original[i], super::HOOK_ZONE),
    })
}

/// The contour's joins as the joint stage sees them.
#[derive(Clone, Copy)]
pub(super) struct Joins<'a> {
    pub closed: bool,
    /// Per join: solved for G2.
    pub moving: &'a [bool],
    /// Per join: its handles stay.
    pub held: &'a [bool],
    /// Per join: the jump and angle it may not pass.
    pub guard: &'a [(f64, f64)],
}

/// Most segments the joint stage solves as one problem. Its solver's normal equations are
/// dense (cubic in the unknowns), so a longer contour is solved in overlapping windows of
/// this many segments, one after the other, each with the cubics outside it held and only
/// the joins that touch it counted: time linear in the contour's length. A window this
/// long holds every contour of a real glyph whole (the largest have a few dozen segments).
const WINDOW: usize = 48;

/// Segments two consecutive windows share (the later one may adjust a join the earlier
/// one left at its edge).
const WINDOW_OVERLAP: usize = 8;

/// The joint stage: the handle lengths of `h` (the sweep's result on the stage's start
/// `segs`) of the cubics at `moving` joins, except those in `hold` and the handles at
/// `held` joins, solved together for G2 at the moving joins, with no join's jump past its
/// `guard` and the extrema rule kept as residuals ([`shape_samples`]); why the solver
/// stopped, or None when nothing was free. A contour of more than [`WINDOW`] segments is
/// solved window by window.
pub(super) fn refine(
    segs: &[Vec<Point>],
    h: &mut Handles,
    joins: &Joins,
    hold: &[bool],
    reach: &Reach,
) -> Option<Stop> {
    let n = segs.len();
    if n <= WINDOW {
        return refine_window(segs, h, joins, hold, reach);
    }
    let all: Vec<(usize, usize, usize)> = super::joins(n, joins.closed).collect();
    let mut last = None;
    let mut start = 0;
    loop {
        let end = (start + WINDOW).min(n);
        let inside = |i: usize| (start..end).contains(&i);
        let window_hold: Vec<bool> = (0..n).map(|i| hold[i] || !inside(i)).collect();
        let mut moving = joins.moving.to_vec();
        for &(j, a, b) in &all {
            moving[j] &= inside(a) || inside(b);
        }
        let window = Joins {
            moving: &moving,
            ..*joins
        };
        if let Some(stop) = refine_window(segs, h, &window, &window_hold, reach) {
            last = Some(stop);
        }
        if end == n {
            return last;
        }
        start = end - WINDOW_OVERLAP;
    }
}

/// [`refine`] on one problem: every cubic not held at once.
fn refine_window(
    segs: &[Vec<Point>],
    h: &mut Handles,
    joins: &Joins,
    hold: &[bool],
    reach: &Reach,
) -> Option<Stop> {
    let Joins {
        closed,
        moving,
        held,
        guard,
    } = *joins;
    let n = segs.len();
    let all: Vec<(usize, usize, usize)> = super::joins(n, closed).collect();
    let joins: Vec<(usize, usize)> = (all.iter())
        .filter(|&&(j, a, b)| moving[j] && h.dirs[a].is_some() && h.dirs[b].is_some())
        .map(|&(_, a, b)| (a, b))
        .collect();
    // A handle slides unless its join is held (the start's at the join before, the end's at
    // the join after): at a corner too, along its tangent, for the curvature at its cubic's
    // other end.
    let at = |i: usize, end: bool| {
        !all.iter()
            .any(|&(j, a, b)| held[j] && if end { a == i } else { b == i })
    };
    let touches = |i: usize| joins.iter().any(|&(a, b)| a == i || b == i);
    let list: Vec<Free> = (0..n)
        .filter(|&i| !hold[i] && touches(i))
        .filter_map(|i| free(segs, h, reach, (i, (at(i, false), at(i, true)))))
        .collect();
    if list.is_empty() || joins.is_empty() {
        return None;
    }
    let vars = (list.iter().enumerate())
        .flat_map(|(k, f)| [(f.mask.0, (k, 0)), (f.mask.1, (k, 1))])
        .filter_map(|(m, v)| m.then_some(v))
        .collect();
    let is_free = |i: usize| list.iter().any(|f| f.seg == i);
    let guards: Vec<(usize, usize, f64)> = (all.iter())
        .filter(|&&(j, a, b)| {
            guard[j].0.is_finite()
                && h.dirs[a].is_some()
                && h.dirs[b].is_some()
                && (is_free(a) || is_free(b))
        })
        .map(|&(j, a, b)| (a, b, guard[j].0))
        .collect();
    let problem = Problem {
        segs,
        h,
        tolerance: reach.tolerance,
        free: list,
        vars,
        joins,
        guards,
    };
    let x0: Vec<f64> = (problem.vars.iter())
        .map(|&(k, c)| {
            let f = &problem.free[k];
            let z = f.unknowns(problem.h.len[f.seg], problem.tolerance);
            if c == 0 {
                z.0
            } else {
                z.1
            }
        })
        .collect();
    let opts = LmOptions {
        max_iterations: 100,
        rel_progress: 1e-10,
        ..LmOptions::default()
    };
    let mut res = |x: &[f64], r: &mut Vec<f64>| problem.residuals(x, r);
    let mut jac = |x: &[f64], r: &mut Vec<f64>, c: &mut [Vec<f64>]| problem.jacobian(x, r, c);
    let fit = levenberg_marquardt_dyn(&mut res, Some(&mut jac), &|_| true, x0, &opts);
    if fit.cost.is_infinite() {
        return Some(fit.stop);
    }
    let mut len = problem.lengths(&fit.x);
    // The sound bound: each cubic pulled back towards its start until it passes.
    for f in &problem.free {
        let got = len[f.seg];
        for k in 1..=20 {
            if reach.allows(f.seg, &problem.cubic(f.seg, len[f.seg])) {
                break;
            }
            let s = 1.0 - 1e-3 * (1u32 << k.min(10)) as f64;
            let back = |a: f64, b: f64| a + (b - a) * s.max(0.0);
            len[f.seg] = (back(f.start.0, got.0), back(f.start.1, got.1));
        }
        if !reach.allows(f.seg, &problem.cubic(f.seg, len[f.seg])) {
            len[f.seg] = problem.h.len[f.seg];
        }
    }
    h.len = len;
    Some(fit.stop)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bezier::outline_distance;

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    /// A cubic of `seg` as a free one with both handles sliding, the original `orig`.
    fn free_of(seg: &[Point], orig: &[Point], tolerance: f64) -> (Free, Handles) {
        let segs = vec![seg.to_vec()];
        let original = vec![orig.to_vec()];
        let reach = Reach {
            original: &original,
            tolerance,
        };
        let h = Handles::of(&segs);
        let f = free(&segs, &h, &reach, (0, (true, true))).expect("a cubic");
        (f, h)
    }

    #[test]
    fn the_curvature_slope_is_the_derivative_of_kurbos_curvature() {
        // The slope against a central difference of kurbo's own curvature (other code; its
        // sign is the opposite of this library's).
        use kurbo::ParamCurveCurvature;
        let q = [p(3.0, -2.0), p(40.0, 25.0), p(95.0, 30.0), p(120.0, 90.0)];
        let c = kurbo::CubicBez::new(q[0], q[1], q[2], q[3]);
        for k in 1..20 {
            let t = k as f64 / 20.0;
            let (kappa, slope) = curvature_slope(&q, t);
            let h = 1e-5;
            let fd = -(c.curvature(t + h) - c.curvature(t - h)) / (2.0 * h);
            assert!((kappa + c.curvature(t)).abs() < 1e-12 * kappa.abs().max(1e-3));
            assert!(
                (slope - fd).abs() < 1e-6 * fd.abs().max(1e-4),
                "{t}: {slope} vs {fd}"
            );
        }
    }

    #[test]
    fn the_shape_samples_ask_the_originals_signs_outside_its_extrema() {
        // A cubic with one curvature maximum inside: samples in its hook zones only, with
        // signs that agree with the original's slope, and all hinges zero at the original;
        // a monotone cubic is asked everywhere, its hook zones included.
        let bump = [p(0.0, 0.0), p(30.0, 40.0), p(70.0, 40.0), p(100.0, 0.0)];
        let ts = super::super::extrema_at(&bump).unwrap();
        assert_eq!(ts.len(), 1);
        let samples = shape_samples(&bump, super::super::HOOK_ZONE);
        assert!(!samples.is_empty());
        for s in &samples {
            assert!(!(0.05..=0.95).contains(&s.t), "{s:?}");
            let slope = curvature_slope(&bump, s.t).1;
            assert!(slope * s.sign * s.inv >= SHAPE_MARGIN, "{s:?}: {slope}");
        }
        let arc = [p(0.0, 0.0), p(40.0, 0.0), p(70.0, 10.0), p(90.0, 30.0)];
        assert!(super::super::extrema_at(&arc).unwrap().is_empty());
        let samples = shape_samples(&arc, super::super::HOOK_ZONE);
        let zone = |a: f64, b: f64| samples.iter().filter(|s| s.t >= a && s.t <= b).count();
        assert!(zone(0.0, 0.05) >= 4 && zone(0.95, 1.0) >= 4 && zone(0.3, 0.7) >= 20);
        let sign = samples[0].sign;
        assert!(samples.iter().all(|s| s.sign == sign));
    }

    /// The model's move of `q` from `orig` (the larger of its normal part and
    /// PARAMETRIC_SHARE of the move at equal parameters, over 257 parameters), from
    /// kurbo's evaluation of the two cubics, not the stage's samples.
    fn model_move(orig: &[Point; 4], q: &[Point; 4]) -> f64 {
        let c = |p: &[Point; 4]| kurbo::CubicBez::new(p[0], p[1], p[2], p[3]);
        let (o, b) = (c(orig), c(q));
        (0..=256)
            .map(|k| k as f64 / 256.0)
            .map(|t| {
                let d = b.eval(t) - o.eval(t);
                let tangent = o.deriv().eval(t).to_vec2();
                let normal = d.cross(tangent).abs() / tangent.hypot();
                normal.max(PARAMETRIC_SHARE * d.hypot())
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn the_map_stays_inside_the_model_and_reaches_its_boundary() {
        // Any unknowns give lengths whose cubic is within T of the original by the model
        // (its outline's normal move, and a share of its move at equal parameters), and far
        // out along any direction the model's move comes within 1 % of T: the map covers
        // the region, not a box in it. The model is first order: the sound bound
        // (outline_distance) stays within a fifth of T above it here, and the stage pulls
        // every cubic back until the sound bound passes.
        let orig = [p(0.0, 0.0), p(40.0, 5.0), p(80.0, 60.0), p(90.0, 120.0)];
        // The start with its end moved a little (as after `move_points`).
        let mut start = orig;
        start[3] = p(90.3, 120.2);
        start[2] += start[3] - orig[3];
        let mut worst_excess = 0.0f64;
        for (seg, t) in [(orig, 2.0), (start, 2.0), (orig, 0.3)] {
            let (f, h) = free_of(&seg, &orig, t);
            for k in 0..24 {
                let a = k as f64 * std::f64::consts::TAU / 24.0;
                for r in [0.3, 1.0, 3.0, 12.0] {
                    let len = f.lengths((r * a.cos(), r * a.sin()), t);
                    let (d0, d1) = h.dirs[0].unwrap();
                    let q = [seg[0], seg[0] + d0 * len.0, seg[3] - d1 * len.1, seg[3]];
                    let moved = model_move(&orig, &q);
                    assert!(moved <= t * (1.0 + 1e-9), "{a} {r}: {moved} > {t}");
                    if r == 12.0 {
                        assert!(moved >= 0.99 * t, "{a}: only {moved} of {t}");
                    }
                    worst_excess = worst_excess.max(outline_distance(&orig, &q) / t);
                    // And back: the unknowns of those lengths give them again.
                    if r < 3.0 {
                        let z = f.unknowns(len, t);
                        let again = f.lengths(z, t);
                        assert!((again.0 - len.0).abs() < 1e-9 && (again.1 - len.1).abs() < 1e-9);
                    }
                }
            }
        }
        assert!(worst_excess < 1.25, "{worst_excess}");
    }

    #[test]
    fn the_joint_stage_reaches_g2_where_the_sweeps_box_cannot() {
        // Two cubics whose join needs one handle shortened by more than the box's 4/3 T
        // (both handles moving) allows but within the 9/4 T one handle alone may move:
        // the joint stage makes it G2 within the tolerance, the box alone does not.
        // e_A = 20, e_B = 28 with both near handles 40: u/v = √1.4 = 1.18 at G2, beyond the
        // box's (40 + 8/3)/(40 - 8/3) = 1.14; the far handles' lever closes the rest.
        let a = vec![p(0.0, 0.0), p(0.0, 40.0), p(20.0, 60.0), p(60.0, 60.0)];
        let b = vec![p(60.0, 60.0), p(100.0, 60.0), p(120.0, 32.0), p(120.0, 0.0)];
        let segs = vec![a, b];
        let t = 2.0;
        let reach = Reach {
            original: &segs,
            tolerance: t,
        };
        let jump = |h: &Handles| {
            let q: Vec<Vec<Point>> = (0..2).map(|i| h.points(&segs, i)).collect();
            (super::super::join_state(&q[0], &q[1]).0, q)
        };
        let mut boxed = Handles::within(&segs, &reach);
        // The box's best: the sweep's one join, solved alone.
        let ((v, u), limited) = super::super::solve_join(&segs, &boxed, (0, 1)).unwrap();
        boxed.len[0].1 = v;
        boxed.len[1].0 = u;
        let (before, _) = jump(&Handles::of(&segs));
        let (in_box, _) = jump(&boxed);
        assert!(
            limited && in_box > 0.01,
            "the case must be out of the box's reach: {in_box}"
        );
        let stop = refine(
            &segs,
            &mut boxed,
            &Joins {
                closed: false,
                moving: &[true],
                held: &[false],
                guard: &[(f64::INFINITY, 0.0)],
            },
            &[false; 2],
            &reach,
        );
        assert!(stop.is_some());
        let (after, q) = jump(&boxed);
        assert!(
            after < 0.01 && after < in_box,
            "{before} -> box {in_box} -> joint {after}"
        );
        for i in 0..2 {
            assert!(outline_distance(&segs[i], &q[i]) <= t);
            assert!(crate::bezier::sampled_shape_distance(&segs[i], &q[i]) <= t);
        }
    }
}
