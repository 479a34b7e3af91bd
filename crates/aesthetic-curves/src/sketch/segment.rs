use super::alpha::{curve_distance, fit_slot_alpha, points_in};
use super::constants::{
    FLAT_STRETCH_SHARE, LINE_END_SHARE, MERGE_SHARE, MID_TURN_ROOM, PEAK_FALL_SPLIT,
    PEAK_MERGE_FACTOR, PEAK_PROMINENCE,
};
use super::input::Context;
use super::slot::{slot, slot_ends, triangle, Cut, EndPoints, Slot};

use super::track::{u_at_turn, Track};
use super::types::SketchOptions;
use crate::bspline;
use crate::error::{Error, Result};

/// Step 2: the cuts of the B-spline, in stages: the events located on the tight spline,
/// inflections that are noise dropped (too close to an end or to each other, near a line's
/// end, across a flat stretch), one maximum cut per interval, long pieces split.
pub(super) fn segment(cx: &Context) -> Result<Vec<Slot>> {
    let (track, opts) = (&cx.track, cx.opts);
    let (u0, u1) = track.domain();
    let (mut infl, maxima) = located_events(cx);
    drop_close_inflections(track, &mut infl, opts.min_turn);
    let total = track.angle_between(u0, u1).abs();
    let turn = |a: f64, b: f64| track.angle_between(a, b).abs();
    drop_near_line_ends(&mut infl, &turn, (u0, u1, total), opts);
    drop_flat_stretches(track, &mut infl);
    let cuts = cuts(cx, &infl, &maxima, total);
    Ok(within_max_turn(track, &cuts, opts.max_turn))
}

/// The inflections and curvature maxima of the shape track, each moved to the tight
/// spline's own event nearby (its location is more accurate) when there is one: the
/// nearest inflection, the largest maximum; for precise input whose tight spline has its
/// peak on a knot, that peak found by sampling.
fn located_events(cx: &Context) -> (Vec<f64>, Vec<f64>) {
    let (track, shape) = (&cx.track, cx.shape());
    let (u0, u1) = track.domain();
    let (mut infl, mut maxima) = shape.events();
    if std::ptr::eq(track, shape) {
        return (infl, maxima);
    }
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
        } else if let Some(v) = cx
            .precise
            .then(|| sampled_peak(track, (*u - w).max(u0), (*u + w).min(u1)))
            .flatten()
        {
            *u = v;
        }
    }
    (infl, maxima)
}

/// Inflections that turn less than `min_turn` from an end dropped, then inflection pairs
/// with less turning between them, until none is left to drop.
fn drop_close_inflections(track: &Track, infl: &mut Vec<f64>, min_turn: f64) {
    let (u0, u1) = track.domain();
    let turn = |a: f64, b: f64| track.angle_between(a, b).abs();
    loop {
        let before = infl.len();
        infl.retain(|&u| turn(u0, u) >= min_turn && turn(u, u1) >= min_turn);
        let mut i = 0;
        while i + 1 < infl.len() {
            if turn(infl[i], infl[i + 1]) < min_turn {
                infl.drain(i..i + 2);
            } else {
                i += 1;
            }
        }
        if infl.len() == before {
            break;
        }
    }
}

/// An inflection pair (or an inflection and an end) with hardly any curvature between them
/// is a flat stretch crossed by noise, not an S: dropped, the flattest first, while a
/// stretch next to an inflection stays below [`FLAT_STRETCH_SHARE`] of the curve's largest
/// |κ|.
fn drop_flat_stretches(track: &Track, infl: &mut Vec<f64>) {
    let (u0, u1) = track.domain();
    let kappa_max_on = |a: f64, b: f64| {
        (0..=16)
            .map(|k| track.abs_kappa(a + (b - a) * k as f64 / 16.0))
            .fold(0.0, f64::max)
    };
    let k_all = kappa_max_on(u0, u1);
    loop {
        let mut bounds = vec![u0];
        bounds.extend(infl.iter());
        bounds.push(u1);
        let flat = (0..bounds.len() - 1)
            .map(|i| (i, kappa_max_on(bounds[i], bounds[i + 1])))
            .filter(|(_, k)| *k < FLAT_STRETCH_SHARE * k_all)
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
}

/// The cuts in order: the ends (an end that joins a line has zero curvature: a line cut),
/// the inflections, and one |κ| maximum per interval between them ([`interval_cut`]; a
/// peak of precise input is the data's, which no merge crosses).
fn cuts(cx: &Context, infl: &[f64], maxima: &[f64], total: f64) -> Vec<(f64, Cut)> {
    let (track, opts) = (&cx.track, cx.opts);
    let end_cut = |given: Option<kurbo::Vec2>| {
        if given.is_some() {
            Cut::Line
        } else {
            Cut::End
        }
    };
    let (u0, u1) = track.domain();
    let mut bounds: Vec<(f64, Cut)> = vec![(u0, end_cut(opts.line_ends[0]))];
    bounds.extend(infl.iter().map(|&u| (u, Cut::Inflection)));
    bounds.push((u1, end_cut(opts.line_ends[1])));
    let mut cuts: Vec<(f64, Cut)> = vec![bounds[0]];
    for w in bounds.windows(2) {
        if let Some(u) = interval_cut(cx, maxima, (w[0], w[1]), total) {
            cuts.push((u, if cx.precise { Cut::Peak } else { Cut::Other }));
        }
        cuts.push(w[1]);
    }
    cuts
}

/// The slots between the cuts, each split evenly in turning into pieces that turn at most
/// `max_turn`.
fn within_max_turn(track: &Track, cuts: &[(f64, Cut)], max_turn: f64) -> Vec<Slot> {
    let mut slots = Vec::new();
    for w in cuts.windows(2) {
        let ((a, ca), (b, cb)) = (w[0], w[1]);
        let t = track.angle_between(a, b).abs();
        let parts = ((t / max_turn).ceil() as usize).max(1);
        let mut prev = (a, ca);
        for k in 1..parts {
            let u = u_at_turn(track, a, b, t * k as f64 / parts as f64);
            slots.push(slot(track, prev, (u, Cut::Other)));
            prev = (u, Cut::Other);
        }
        slots.push(slot(track, prev, (b, cb)));
    }
    slots
}

/// The cut inside the interval between two bounds (ends or inflections): its largest
/// curvature maximum, if that stands above both ends (between two inflections always one,
/// at half the turning if the root finder found none). For precise input, the tight
/// spline's own largest peak instead where it stands [`PEAK_PROMINENCE`] above that one
/// (or there is none): a peak on a knot, which the root finder cannot see, or one that the
/// smoother shape spline rounds into two.
fn interval_cut(
    cx: &Context,
    maxima: &[f64],
    ((a, ca), (b, cb)): ((f64, Cut), (f64, Cut)),
    total: f64,
) -> Option<f64> {
    let (track, opts) = (&cx.track, cx.opts);
    let turn = |a: f64, b: f64| track.angle_between(a, b).abs();
    // Away from a line's end as the inflections are (the spline's wiggle about the zero
    // curvature there is no peak).
    let room = |c: Cut| {
        if c == Cut::Line {
            LINE_END_SHARE * total
        } else {
            0.5 * opts.min_turn
        }
    };
    let allowed = |u: f64| u > a && u < b && turn(a, u) >= room(ca) && turn(u, b) >= room(cb);
    let k = |u: f64| track.abs_kappa(u);
    let best = maxima
        .iter()
        .copied()
        .filter(|&u| allowed(u))
        .max_by(|x, y| k(*x).total_cmp(&k(*y)));
    let both_zero = ca.zero() && cb.zero();
    let pick = match best {
        // Only a true interior maximum: above both ends of its interval.
        Some(u) if both_zero || (k(u) > k(a) && k(u) > k(b)) => Some(u),
        Some(_) => None,
        // Between two inflections there is a maximum; the root finder missed it (flat):
        // take the half-turning point.
        None if both_zero => Some(u_at_turn(track, a, b, 0.5 * turn(a, b))),
        None => None,
    };
    let own = cx
        .precise
        .then(|| sampled_peak(track, a, b))
        .flatten()
        .filter(|&v| allowed(v));
    match (pick, own) {
        (Some(u), Some(v)) if k(v) > (1.0 + PEAK_PROMINENCE) * k(u) => Some(v),
        (None, Some(v)) => Some(v),
        (pick, _) => pick,
    }
}

/// The largest |κ| strictly inside [a, b], [`PEAK_PROMINENCE`] above |κ| at both ends, if
/// there is one (a maximum the root finder may not see: on a knot, dκ/ds jumps from + to -
/// without a root; symmetric data put their peak there). Sampled at 64 steps, then refined
/// by golden sections to 1e-9 of the interval.
fn sampled_peak(track: &Track, a: f64, b: f64) -> Option<f64> {
    let n = 64;
    let k = |u: f64| track.abs_kappa(u);
    let (i, _) = (1..n)
        .map(|i| (i, k(a + (b - a) * i as f64 / n as f64)))
        .max_by(|x, y| x.1.total_cmp(&y.1))?;
    let h = (b - a) / n as f64;
    let u0 = a + h * i as f64;
    let g = crate::solve::line_search::golden_bracket(
        &mut |u| -k(u),
        u0 - h,
        u0 + h,
        1e-9 * (b - a),
        80,
    );
    let u = 0.5 * (g.lo + g.hi);
    (u > a && u < b && k(u) > (1.0 + PEAK_PROMINENCE) * k(a).max(k(b))).then_some(u)
}

/// Next to a line's end the curvature starts from zero: a sign change there is the noise
/// around that zero, not an S, unless the curve has turned [`LINE_END_SHARE`] of its way.
fn drop_near_line_ends(
    infl: &mut Vec<f64>,
    turn: &dyn Fn(f64, f64) -> f64,
    (u0, u1, total): (f64, f64, f64),
    opts: &SketchOptions,
) {
    if opts.line_ends[0].is_some() {
        infl.retain(|&u| turn(u0, u) >= LINE_END_SHARE * total);
    }
    if opts.line_ends[1].is_some() {
        infl.retain(|&u| turn(u, u1) >= LINE_END_SHARE * total);
    }
}

/// Split where the curve misses the points most, kept off the piece's ends; a piece with an
/// inflection end at its half turning, so the inflection piece left keeps a proper triangle,
/// kept [`MID_TURN_ROOM`] of the parameter from either end. From a curvature peak to an
/// inflection the turning gathers at the peak, and a cut at its half sits just past it,
/// leaving a sliver whose curvature falls steeply (read as a step): when the half turning
/// lies within that room of an end, the cut goes where the curvature has fallen to
/// [`PEAK_FALL_SPLIT`] of its larger end's, so the fall stays in one piece.
pub(super) fn split_worst(
    track: &Track,
    slots: &mut Vec<Slot>,
    piece: usize,
    u: f64,
) -> Result<()> {
    let s = &slots[piece];
    let (ua, ub) = (s.ua, s.ub);
    let u = if s.cut_a.zero() || s.cut_b.zero() {
        let room = MID_TURN_ROOM * (ub - ua);
        let mid = mid_turn(track, ua, ub);
        let gathered = mid < ua + room || mid > ub - room;
        let cut = if gathered {
            fallen_to(track, ua, ub, PEAK_FALL_SPLIT)
        } else {
            mid
        };
        cut.clamp(ua + room, ub - room)
    } else {
        u.clamp(ua + 0.25 * (ub - ua), ub - 0.25 * (ub - ua))
    };
    split_at(track, slots, piece, u)
}

/// Split `slots[i]` at its largest |κ| (sampled) when that lies inside it: an inflection
/// piece whose curvature peaks near the inflection (a maximum the simplification dropped)
/// becomes a short inflection piece and a monotone rest. Returns whether it split.
pub(super) fn split_at_peak(track: &Track, slots: &mut Vec<Slot>, i: usize) -> bool {
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

/// Split every piece whose end tangents do not form a control triangle (an S shape: an
/// inflection dropped as noise, or too flat to be found) at its smallest |κ|, an inflection
/// when κ changes sign there.
pub(super) fn split_s_shapes(track: &Track, slots: &mut Vec<Slot>) -> Result<()> {
    let mut i = 0;
    let mut guard = 0;
    while i < slots.len() {
        let s = &slots[i];
        // A piece at a line's end takes the line's direction, which the fair spline near
        // there need not share (noise); whether its piece exists is settled with its other
        // joint's tangent (`settle_inflections`).
        let ok = s.at_line()
            || triangle(
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
        // A curve end fitted with the tangent of a flat end stretch's last sign change
        // (`Track::with_flat_ends`) forms no triangle with a piece cut inside that stretch:
        // its own tangent again, rather than splits that run into the end.
        let at_end = |u: f64, cut: Cut| cut == Cut::End && track.release_end(u);
        if at_end(s.ua, s.cut_a) || at_end(s.ub, s.cut_b) {
            continue;
        }
        guard += 1;
        if guard > 200 || (s.ub - s.ua) < 1e-9 {
            let (a, b) = (track.point(s.ua), track.point(s.ub));
            return Err(Error::Degenerate(format!(
                "a piece of the curve, from ({:.6}, {:.6}) to ({:.6}, {:.6}), has end \
                 tangents that form no triangle however it is cut: the stroke turns back \
                 there (a corner? a contour fit, `sketch.contour`, splits a stroke at its \
                 corners)",
                a.x, a.y, b.x, b.y
            )));
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

/// Split `slots[i]` at parameter `u`, then any S-shaped results.
pub(super) fn split_at(track: &Track, slots: &mut Vec<Slot>, i: usize, u: f64) -> Result<()> {
    let s = slots[i].clone();
    let left = slot(track, (s.ua, s.cut_a), (u, Cut::Other));
    let right = slot(track, (u, Cut::Other), (s.ub, s.cut_b));
    slots.splice(i..=i, [left, right]);
    split_s_shapes(track, slots)
}

/// Split `slots[i]` where it has turned half its turning, then any S-shaped results.
pub(super) fn split_at_mid_turn(track: &Track, slots: &mut Vec<Slot>, i: usize) -> Result<()> {
    let mid = mid_turn(track, slots[i].ua, slots[i].ub);
    split_at(track, slots, i, mid)
}

/// The first parameter (of 64 steps from the end with the larger |κ| towards the other)
/// where the track's |κ| has fallen to `share` of that end's; the middle if it never does.
fn fallen_to(track: &Track, ua: f64, ub: f64, share: f64) -> f64 {
    let (ka, kb) = (track.abs_kappa(ua), track.abs_kappa(ub));
    let (from, to) = if ka >= kb { (ua, ub) } else { (ub, ua) };
    let target = share * ka.max(kb);
    let n = 64;
    (1..n)
        .map(|k| from + (to - from) * k as f64 / n as f64)
        .find(|&u| track.abs_kappa(u) <= target)
        .unwrap_or(0.5 * (ua + ub))
}

/// The parameter where the track between `ua` and `ub` has turned half its turning.
fn mid_turn(track: &Track, ua: f64, ub: f64) -> f64 {
    u_at_turn(track, ua, ub, 0.5 * track.angle_between(ua, ub).abs())
}

/// Merge neighbouring pieces (across curvature-extremum cuts, never across inflections or
/// the curve's ends) while one LAC segment, α fitted by least squares, stays within
/// `limit` of the input points and turns less than `max_turn`: as few pieces as the
/// tolerance allows. Each remaining LAC slot gets its least-squares α.
pub(super) fn merge_slots(
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
    // A peak of precise input is the data's unless one segment fits across it as closely
    // as the two on its sides do (within PEAK_MERGE_FACTOR of the closer fit's deviation):
    // then the peak is the spline's own (a tight spline's wave at a free end, where exact
    // samples of one segment have none) and the data show none.
    let peak_is_noise = |merged: f64, a: &Slot, b: &Slot| {
        let apart = [a, b].map(|s| {
            fit_slot_alpha(track, fit, &mut s.clone(), ends, false).unwrap_or(f64::INFINITY)
        });
        merged <= PEAK_MERGE_FACTOR * apart[0].max(apart[1])
    };
    // The merged slot of each neighbouring pair and its deviation (None: no merge),
    // recomputed only next to a merge.
    let pair = |a: &Slot, b: &Slot| -> Option<(Slot, f64)> {
        let crossable = matches!(a.cut_b, Cut::Other | Cut::Peak);
        if !crossable || track.angle_between(a.ua, b.ub).abs() > max_turn {
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
        let infl_a = a.cut_a.zero();
        let infl_b = b.cut_b.zero();
        if infl_a || infl_b {
            // A peak next to an inflection end stays: the two pieces' own deviations are
            // not measured for inflection-end pieces.
            if (infl_a && infl_b) || a.cut_b == Cut::Peak {
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
            let seg = super::pieces::bounded_inflection(ctrl).ok()?;
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
        if a.cut_b == Cut::Peak && !peak_is_noise(d, a, b) {
            return None;
        }
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

/// Stages 2 and 3: the pieces cut at the shape track's events, S shapes split, neighbours
/// merged while one LAC segment fits their points within [`MERGE_SHARE`] of the tolerance.
/// The pieces at the curve's ends fit their outer tangent with α (in the rounds).
pub(super) fn initial_slots(cx: &Context) -> Result<Vec<Slot>> {
    let opts = cx.opts;
    let mut slots = segment(cx)?;
    split_s_shapes(&cx.track, &mut slots)?;
    let merge_tol = MERGE_SHARE * opts.tolerance;
    merge_slots(
        &cx.track,
        &cx.fit,
        &mut slots,
        cx.ends,
        merge_tol,
        opts.max_turn,
    );
    slots[0].fitted = false;
    if let Some(s) = slots.last_mut() {
        s.fitted = false;
    }
    Ok(slots)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lac::LacSegment;
    use kurbo::{Point, Vec2};

    /// A clothoid rising to its curvature peak and its mirror image: the tight spline of
    /// these exact samples has a knot at the peak, where dκ/ds jumps from + to - and the
    /// root finder sees no maximum; the cut still lands on the peak.
    #[test]
    fn a_peak_on_a_knot_is_cut() {
        let seg = LacSegment::new(
            -1.0,
            [Point::ZERO, Point::new(5.0, 2.0), Point::new(9.0, 1.0)],
        )
        .unwrap();
        let half = seg.sample(200).unwrap().points;
        let peak = half[199];
        let d = seg.eval_turning(&[seg.theta_d()]).unwrap().tangents[0];
        let n = Vec2::new(-d.y, d.x);
        let mut pts = half.clone();
        for q in half.iter().rev().skip(1) {
            let v = *q - peak;
            pts.push(peak + n * (2.0 * v.dot(n)) - v);
        }
        let opts = SketchOptions::with_tolerance(1e-3);
        let cx = Context::new(&pts, &opts).unwrap();
        assert!(cx.precise);
        assert!(
            cx.track.events().1.is_empty(),
            "the root finder sees the peak now"
        );
        let slots = segment(&cx).unwrap();
        assert_eq!(slots.len(), 2);
        assert_eq!(slots[0].cut_b, Cut::Peak);
        assert!((cx.track.point(slots[0].ub) - peak).hypot() < 1e-4);
    }

    #[test]
    fn an_s_is_cut_at_its_inflection_into_slots_that_cover_the_spline() {
        let pts: Vec<Point> = (0..120)
            .map(|i| {
                let t = i as f64 / 119.0;
                Point::new(300.0 * t, 60.0 * (2.0 * std::f64::consts::PI * t).sin())
            })
            .collect();
        let opts = SketchOptions::with_tolerance(0.5);
        let cx = Context::new(&pts, &opts).unwrap();
        let slots = initial_slots(&cx).unwrap();
        let b = &cx.track.breaks;
        assert_eq!(slots[0].ua, b[0]);
        assert_eq!(slots.last().unwrap().ub, *b.last().unwrap());
        assert_eq!(slots[0].cut_a, Cut::End);
        assert_eq!(slots.last().unwrap().cut_b, Cut::End);
        assert!(!slots[0].fitted && !slots.last().unwrap().fitted);
        for w in slots.windows(2) {
            assert_eq!(w[0].ub, w[1].ua, "slots meet");
            assert_eq!(w[0].cut_b, w[1].cut_a, "one cut between two slots");
        }
        let inflections: Vec<f64> = slots
            .windows(2)
            .filter(|w| w[0].cut_b == Cut::Inflection)
            .map(|w| cx.track.point(w[0].ub).x)
            .collect();
        assert_eq!(inflections.len(), 1, "{inflections:?}");
        assert!((inflections[0] - 150.0).abs() < 3.0, "{inflections:?}");
    }
}
