use super::constants::tame_curvatures;
use super::slot::{rotate, triangle, Cut, Slot};
use super::types::{PieceCurve, PieceKind, PieceShape};
use crate::error::{Error, Result};
use crate::lac::{LacInflectionSegment, LacSegment, ALPHA_RANGE};
use crate::solve::roots::bisect_by;
use kurbo::{Point, Vec2};

/// A built piece.
#[derive(Clone, Debug)]
pub(super) struct Built {
    pub(super) curve: PieceCurve,
    pub(super) alpha: f64,
    /// Signed curvature at the start and at the end (curve order).
    pub(super) kappa: (f64, f64),
}

pub(super) fn build_piece(slot: &Slot, pa: Point, da: Vec2, pb: Point, db: Vec2) -> Result<Built> {
    let tri = triangle(pa, da, pb, db).ok_or_else(|| {
        Error::Degenerate("the end tangents of a piece do not form a triangle".into())
    })?;
    let infl_a = slot.cut_a.zero();
    let infl_b = slot.cut_b.zero();
    if infl_a != infl_b {
        let ctrl = if infl_a {
            tri
        } else {
            [tri[2], tri[1], tri[0]]
        };
        if let Ok(segment) = bounded_inflection(ctrl) {
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
    // A piece at a line's end has zero curvature there or does not exist.
    if slot.at_line() {
        return Err(Error::NoSegment(
            "no inflection-end segment leaves the line along it to this joint".into(),
        ));
    }
    let target = slot.alpha.unwrap_or(1.0);
    let seg = match LacSegment::new(target, tri) {
        Ok(s) => s,
        Err(Error::NoSegment(_)) => nearest_admissible(target, tri)?,
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

/// The inflection-end segment in `ctrl` (`ctrl[0]` = inflection end) whose α, fixed by
/// the triangle, lies within [`ALPHA_RANGE`]: a base angle near half the turning asks for
/// α towards -∞ (a curvature graph too steep for any fit to mean), and such a piece is not
/// built, as if the triangle held none (no piece outside the bound).
pub(super) fn bounded_inflection(ctrl: [Point; 3]) -> Result<LacInflectionSegment> {
    let segment = LacInflectionSegment::new(ctrl)?;
    if segment.alpha < ALPHA_RANGE.0 {
        return Err(Error::NoSegment(format!(
            "the inflection-end segment in this triangle has alpha {:.3}, beyond the bound {}",
            segment.alpha, ALPHA_RANGE.0
        )));
    }
    Ok(segment)
}

/// The pieces for joint tangents `dirs` (one unit vector per joint, ends included).
pub(super) fn build_all(slots: &[Slot], pts: &[Point], dirs: &[Vec2]) -> Result<Vec<Built>> {
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
pub(super) fn settle_inflections(slots: &[Slot], pts: &[Point], dirs: &mut [Vec2]) -> Vec<usize> {
    let mut failed = Vec::new();
    let both = |j: usize, d: Vec2, before: Vec2, after: Vec2| {
        let l = build_piece(&slots[j - 1], pts[j - 1], before, pts[j], d);
        let r = build_piece(&slots[j], pts[j], d, pts[j + 1], after);
        is_inflection(&l) && is_inflection(&r)
    };
    for j in 1..slots.len() {
        if !(slots[j - 1].cut_b == Cut::Inflection && slots[j].cut_a == Cut::Inflection) {
            continue;
        }
        let (before, here, after) = (dirs[j - 1], dirs[j], dirs[j + 1]);
        if both(j, here, before, after) {
            continue;
        }
        let found = turned_until(here, |d| both(j, d, before, after));
        if let Some(d) = found {
            dirs[j] = d;
        } else {
            if !is_inflection(&build_piece(
                &slots[j - 1],
                pts[j - 1],
                before,
                pts[j],
                here,
            )) {
                failed.push(j - 1);
            }
            if !is_inflection(&build_piece(&slots[j], pts[j], here, pts[j + 1], after)) {
                failed.push(j);
            }
        }
    }
    failed.extend(settle_line_ends(slots, pts, dirs));
    failed.sort_unstable();
    failed.dedup();
    failed
}

/// Whether a piece was built, as an inflection-end piece.
fn is_inflection(built: &Result<Built>) -> bool {
    built
        .as_ref()
        .is_ok_and(|b| b.curve.kind() == PieceKind::LacInflection)
}

/// The tangent `here` turned by the least angle (steps of 0.0025 rad, either way, up to
/// 0.5 rad) at which `works` holds.
fn turned_until(here: Vec2, works: impl Fn(Vec2) -> bool) -> Option<Vec2> {
    (1..=200).find_map(|k| {
        let a = 0.0025 * k as f64;
        [a, -a]
            .into_iter()
            .map(|x| rotate(here, x))
            .find(|d| works(*d))
    })
}

/// Each end piece at a line's end ([`Cut::Line`]) made an inflection-end piece by turning
/// the tangent at its other joint (least first, within ±0.5 rad) while the piece beyond that
/// joint still builds. Returns the end pieces that cannot be.
fn settle_line_ends(slots: &[Slot], pts: &[Point], dirs: &mut [Vec2]) -> Vec<usize> {
    let m = slots.len();
    let mut failed = Vec::new();
    for (i, j, at_line) in [
        (0, 1, slots[0].cut_a == Cut::Line),
        (m - 1, m - 1, slots[m - 1].cut_b == Cut::Line),
    ] {
        if !at_line || j == 0 || j == m {
            // A single piece between two lines has no free joint (the segmentation cuts it).
            if at_line && m == 1 {
                failed.push(i);
            }
            continue;
        }
        let works = |d: Vec2| {
            let mut trial = dirs.to_vec();
            trial[j] = d;
            let own = build_piece(&slots[i], pts[i], trial[i], pts[i + 1], trial[i + 1]);
            let k = if i == 0 { 1 } else { m - 2 };
            let other = build_piece(&slots[k], pts[k], trial[k], pts[k + 1], trial[k + 1]);
            is_inflection(&own) && other.is_ok()
        };
        let here = dirs[j];
        if works(here) {
            continue;
        }
        let found = turned_until(here, works);
        match found {
            Some(d) => dirs[j] = d,
            None => failed.push(i),
        }
    }
    failed
}

/// The segment in `tri` at the admissible α nearest to `target` towards 0.5 (0 <= α <= 1
/// always admits a triangle) whose end curvatures stay within
/// [`MAX_CURVATURE_RATIO`](super::constants::MAX_CURVATURE_RATIO) of each other: at the
/// bare edge of the existence region one end's curvature is 0 or ∞, which no rational
/// cubic follows. The edge by bisection on the existence test (no Λ solve), then steps
/// back towards 0.5, growing fourfold from 1e-4 of the way, until the segment is tame (a
/// few solves: the fairing builds pieces for every column of its Jacobian); failing all,
/// bisection on the solve itself.
fn nearest_admissible(target: f64, tri: [Point; 3]) -> Result<LacSegment> {
    let towards_half = |test: &dyn Fn(f64) -> bool| {
        let mean = |a: f64, b: f64| 0.5 * (a + b);
        bisect_by(
            |a| test(a).then_some(()),
            0.5,
            target,
            mean,
            |_, _| false,
            40,
        )
        .inside
    };
    let edge = towards_half(&|a| LacSegment::exists(a, tri).unwrap_or(false));
    let tame = |s: &LacSegment| {
        s.end_curvatures()
            .is_ok_and(|(k0, k1)| tame_curvatures(k0, k1))
    };
    let mut share = 1e-4;
    let mut first_built = None;
    while share < 1.0 {
        if let Ok(s) = LacSegment::new(edge + (0.5 - edge) * share, tri) {
            if tame(&s) {
                return Ok(s);
            }
            first_built.get_or_insert(s);
        }
        share *= 4.0;
    }
    match first_built {
        Some(s) => Ok(s),
        None => LacSegment::new(towards_half(&|a| LacSegment::new(a, tri).is_ok()), tri),
    }
}
