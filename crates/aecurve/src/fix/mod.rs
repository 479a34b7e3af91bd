//! `aecurve fix`: a UFO source's smooth joins harmonized (the library's `harmonize`) and the
//! UFO written back with the same structure: same glyphs, contours, points, kinds, names,
//! identifiers, anchors and components; only off-curve coordinates move (and, with
//! `--move-points`, on-curve points of smooth joins, along their handles' line), no
//! outline further than the tolerance from the original, on the grid.
//!
//! A contour is taken as the designer drew it: its segments are read from the points in
//! order (an open contour from its `move`, a closed one from its first on-curve point), and a
//! join is smooth where the on-curve point says `smooth="yes"`. Contours with quadratic
//! segments (`qcurve`, or one off-curve point) are left as they are and listed: `fix` works
//! on cubic outlines (convert a TrueType source to cubics first).

use aesthetic_curves::harmonize::{
    has_bump, repair, repair_holding, HarmonizeOptions, Harmonized, Repairs,
};
use aesthetic_curves::Point;

pub mod masters;
pub mod report;
use anyhow::{Context, Result};
use std::path::Path;

pub use aesthetic_curves::contour_points::IndexedContour;

/// The segments of a UFO contour with the indices of their points (the library's
/// [`aesthetic_curves::contour_points::index_contour`] on norad's points); Err says why the
/// contour is not one `fix` works on.
pub fn index_contour(
    points: &[norad::ContourPoint],
) -> std::result::Result<IndexedContour, String> {
    use aesthetic_curves::contour_points::{ListPoint, PointKind as K};
    use norad::PointType as T;
    let list: Vec<ListPoint> = points
        .iter()
        .map(|q| ListPoint {
            at: Point::new(q.x, q.y),
            kind: match q.typ {
                T::Move => K::Move,
                T::Line => K::Line,
                T::Curve => K::Curve,
                T::QCurve => K::QCurve,
                T::OffCurve => K::OffCurve,
            },
            smooth: q.smooth,
        })
        .collect();
    aesthetic_curves::contour_points::index_contour(&list).map_err(|e| match e {
        aesthetic_curves::Error::InvalidInput { message, .. } => message,
        e => e.to_string(),
    })
}

/// What `fix` does.
#[derive(Clone, Copy, Debug)]
pub struct FixOptions {
    /// How far a point may move (font units).
    pub tolerance: f64,
    /// The coordinates' grid (1: integer font units; 0: none).
    pub grid: f64,
    /// Also move the on-curve points of smooth joins along their handles' line.
    pub move_points: bool,
    /// Which repairs run (hooks and extra extrema first, then the joins).
    pub repairs: Repairs,
}

/// One contour's result, as JSON and as counts.
pub struct ContourFix {
    /// The glyph's name.
    pub glyph: String,
    /// The contour's index in the glyph.
    pub contour: usize,
    /// The contour as read (None: not one `fix` works on).
    pub input: Option<IndexedContour>,
    /// The harmonize result (Err: not a contour `fix` works on, with the reason).
    pub result: std::result::Result<Harmonized, String>,
}

/// The counts the summary and the tests use.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FixCounts {
    /// Smooth joins between two cubics.
    pub smooth_cubic_joins: usize,
    /// Of those, under 1 % relative curvature jump before, and after.
    pub under_1_percent: (usize, usize),
    /// Joins worse after than before (jump or angle): 0 by construction.
    pub worse: usize,
    /// Cubics with more curvature extrema after: 0 by construction.
    pub gained_extrema: usize,
    /// Segments changed.
    pub changed_segments: usize,
    /// How far the outline moved, the largest over the segments.
    pub max_moved: f64,
    /// Contours left alone (quadratic or unreadable).
    pub skipped_contours: usize,
    /// Cubics with a hook (an extremum within 5 % of an end) or several extrema, before and
    /// after (the exact test).
    pub bumps: (usize, usize),
}

impl FixCounts {
    fn add(&mut self, h: &Harmonized, c: &IndexedContour) {
        let input = &c.segments;
        let n = input.len();
        for j in &h.joins {
            let (a, b) = (j.after_segment, (j.after_segment + 1) % n);
            if !c.smooth[j.after_segment] || input[a].len() != 4 || input[b].len() != 4 {
                continue;
            }
            self.smooth_cubic_joins += 1;
            self.under_1_percent.0 += (j.jump.0 < 0.01) as usize;
            self.under_1_percent.1 += (j.jump.1 < 0.01) as usize;
            self.worse += j.worse() as usize;
        }
        for (b, a) in &h.extrema {
            if let (Some(b), Some(a)) = (b, a) {
                self.gained_extrema += (a > b) as usize;
            }
        }
        let zone = Repairs::default().hook_zone;
        let bump = |p: &[Point]| has_bump(p, zone).unwrap_or(false) as usize;
        for (s, t) in input.iter().zip(&h.segments) {
            self.bumps.0 += bump(s);
            self.bumps.1 += bump(t);
        }
        self.changed_segments += h.segments.iter().zip(input).filter(|(a, b)| a != b).count();
        self.max_moved = h.moved.iter().copied().fold(self.max_moved, f64::max);
    }
}

/// Fix every glyph of the UFO at `input`'s default layer and write the UFO to `output`:
/// the per-contour results and the counts.
pub fn fix_ufo(
    input: &Path,
    output: &Path,
    opts: &FixOptions,
) -> Result<(Vec<ContourFix>, FixCounts)> {
    // The readers' folder check and norad's load, once (not `read` and then norad again).
    let mut font = crate::outline_io::load_ufo_checked(input)
        .with_context(|| format!("{}: not a UFO `fix` reads", input.display()))?;
    let fixes = fix_font(&font, opts);
    let counts = write_font_back(&mut font, &fixes);
    font.save(output)
        .with_context(|| format!("writing {}", output.display()))?;
    Ok((fixes, counts))
}

/// The options of the library's repair for `fix`'s.
fn harmonize_options(opts: &FixOptions) -> HarmonizeOptions {
    HarmonizeOptions {
        tolerance: opts.tolerance,
        grid: opts.grid,
        move_points: opts.move_points,
        ..HarmonizeOptions::default()
    }
}

/// Every contour of the font's default layer repaired (nothing written yet), in glyph and
/// contour order.
pub fn fix_font(font: &norad::Font, opts: &FixOptions) -> Vec<ContourFix> {
    fix_font_holding(font, opts, &Held::new())
}

/// Per (glyph, contour): the joins to keep as they are ([`repair_holding`]).
pub type Held = std::collections::HashMap<(String, usize), Vec<bool>>;

/// [`fix_font`], keeping the joins `held` names as they are. The contours are repaired in
/// parallel (each on its own: rayon's threads), the results in glyph and contour order; a
/// font of many contours shows a progress bar on a terminal (a font takes seconds).
pub fn fix_font_holding(font: &norad::Font, opts: &FixOptions, held: &Held) -> Vec<ContourFix> {
    use rayon::prelude::*;
    let hopts = harmonize_options(opts);
    let contours: Vec<(&str, usize, &norad::Contour)> = font
        .default_layer()
        .iter()
        .flat_map(|glyph| {
            let name = glyph.name().as_str();
            glyph
                .contours
                .iter()
                .enumerate()
                .map(move |(ci, c)| (name, ci, c))
        })
        .collect();
    let shown = contours.len() >= PROGRESS_FROM;
    let bar = crate::progress::bar(contours.len() as u64, "repairing contours", shown);
    let fixes = contours
        .par_iter()
        .map(|&(name, ci, contour)| {
            bar.inc(1);
            let indexed = index_contour(&contour.points);
            let hold = held.get(&(name.to_string(), ci));
            let result = indexed.as_ref().map_err(Clone::clone).and_then(|c| {
                let none = vec![false; c.smooth.len()];
                let hold = hold.filter(|h| h.len() == none.len()).unwrap_or(&none);
                repair_holding(
                    &c.segments,
                    c.closed,
                    (&c.smooth, hold),
                    &hopts,
                    &opts.repairs,
                )
                .map_err(|e| e.to_string())
            });
            ContourFix {
                glyph: name.to_string(),
                contour: ci,
                input: indexed.ok(),
                result,
            }
        })
        .collect();
    bar.finish_and_clear();
    fixes
}

/// Fonts of at least this many contours show their repair's progress.
const PROGRESS_FROM: usize = 200;

/// The results of [`fix_font`] written into the font's points; the counts.
pub fn write_font_back(font: &mut norad::Font, fixes: &[ContourFix]) -> FixCounts {
    let mut counts = FixCounts::default();
    let layer = font.default_layer_mut();
    for f in fixes {
        let (Ok(h), Some(c)) = (&f.result, &f.input) else {
            counts.skipped_contours += 1;
            continue;
        };
        if let Some(contour) = layer
            .get_glyph_mut(f.glyph.as_str())
            .and_then(|g| g.contours.get_mut(f.contour))
        {
            write_back(&mut contour.points, c, h);
            counts.add(h, c);
        }
    }
    counts
}

/// The figures of `fix --report` ([`report::fix_report`]): one per glyph or path with a
/// changed segment (its contours `fix` read, before and after), the most joins brought under
/// a 1 % jump first, at most `limit`; and how many shapes changed. `prefix` goes before each
/// name (a designspace's master).
pub fn figures(
    fixes: &[ContourFix],
    prefix: &str,
    limit: usize,
) -> (Vec<report::FixFigure>, usize) {
    let mut out: Vec<report::FixFigure> = Vec::new();
    let mut changed = false;
    for (k, f) in fixes.iter().enumerate() {
        let new_shape = k == 0 || fixes[k - 1].glyph != f.glyph;
        if new_shape {
            if !changed {
                out.pop();
            }
            changed = false;
            out.push(report::FixFigure {
                name: format!("{prefix}{}", f.glyph),
                before: Vec::new(),
                after: Vec::new(),
                joins: (0, 0, 0),
                moved: 0.0,
            });
        }
        let (Ok(h), Some(c), Some(fig)) = (&f.result, &f.input, out.last_mut()) else {
            continue;
        };
        let mut counts = FixCounts::default();
        counts.add(h, c);
        changed |= counts.changed_segments > 0;
        fig.joins.0 += counts.smooth_cubic_joins;
        fig.joins.1 += counts.under_1_percent.0;
        fig.joins.2 += counts.under_1_percent.1;
        fig.moved = fig.moved.max(counts.max_moved);
        fig.before.push(c.segments.clone());
        fig.after.push(h.segments.clone());
    }
    if !changed {
        out.pop();
    }
    let total = out.len();
    out.sort_by_key(|f| std::cmp::Reverse(f.joins.2 as i64 - f.joins.1 as i64));
    out.truncate(limit);
    (out, total)
}

/// The harmonized coordinates into the contour's points (only those that moved).
fn write_back(points: &mut [norad::ContourPoint], c: &IndexedContour, h: &Harmonized) {
    for (idx, pts) in c.indices.iter().zip(&h.segments) {
        for (&i, p) in idx.iter().zip(pts) {
            points[i].x = p.x;
            points[i].y = p.y;
        }
    }
}

/// A tangent break of at most this (degrees) counts as a smooth join in an SVG path (SVG
/// stores no smooth flags; editors keep smooth handles collinear to rounding).
pub const SVG_SMOOTH_DEGREES: f64 = 0.5;

/// An SVG subpath: its segments' control points, whether it closes (`Z`), and whether its
/// last segment is the closing line `Z` draws (written back as `Z` alone).
type SvgContour = (Vec<Vec<Point>>, bool, bool);

/// The contours of SVG path data of moves, lines and cubics (`M L H V C S Z`, absolute or
/// relative), each with whether it closes by `Z` (the closing line, when the last point is
/// not the first, is a segment for the check but is written back as `Z`). Err for arcs and
/// quadratics, which `fix` leaves as they are. `decimals`: the most decimal places a number
/// of `d` has ([`svg_decimals`]).
fn svg_contours(d: &str, decimals: usize) -> std::result::Result<Vec<SvgContour>, String> {
    if d.chars().any(|c| "AaQqTt".contains(c)) {
        return Err("arcs or quadratics: fix works on paths of lines and cubics".into());
    }
    let path = kurbo::BezPath::from_svg(d).map_err(|e| format!("path data not read: {e}"))?;
    let mut out = Vec::new();
    let mut segs: Vec<Vec<Point>> = Vec::new();
    let (mut start, mut at) = (Point::ZERO, Point::ZERO);
    let flush = |segs: &mut Vec<Vec<Point>>, out: &mut Vec<_>, closed: bool, extra: bool| {
        if !segs.is_empty() {
            out.push((std::mem::take(segs), closed, extra));
        }
    };
    for el in path.elements() {
        match *el {
            kurbo::PathEl::MoveTo(p) => {
                flush(&mut segs, &mut out, false, false);
                start = p;
                at = p;
            }
            kurbo::PathEl::LineTo(p) => {
                segs.push(vec![at, p]);
                at = p;
            }
            kurbo::PathEl::CurveTo(a, b, p) => {
                segs.push(vec![at, a, b, p]);
                at = p;
            }
            kurbo::PathEl::QuadTo(..) => {
                return Err("a quadratic: fix works on lines and cubics".into())
            }
            kurbo::PathEl::ClosePath => {
                // Relative commands summed to absolute points miss the start by their
                // rounding (a unit in the last written place per segment, plus float
                // noise): that is the start (a reader closes there with no segment).
                let written = 10f64.powi(-(decimals as i32)) * (segs.len() + 1) as f64;
                let noise = (1e-9 * start.to_vec2().hypot().max(1.0)).max(written);
                if at != start && (at - start).hypot() <= noise {
                    if let Some(last) = segs.last_mut().and_then(|s| s.last_mut()) {
                        *last = start;
                    }
                    at = start;
                }
                let extra = at != start;
                if extra {
                    segs.push(vec![at, start]);
                }
                flush(&mut segs, &mut out, true, extra);
                at = start;
            }
        }
    }
    flush(&mut segs, &mut out, false, false);
    Ok(out)
}

/// A coordinate as written back, with `decimals` places (trailing zeros dropped): the
/// input's own precision for points that did not move (relative commands summed to
/// absolute ones carry rounding below it), 4 or more for moved ones (the grid `fix` puts
/// them on).
fn svg_number(v: f64, decimals: usize) -> String {
    let s = format!("{v:.decimals$}");
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.')
    } else {
        &s
    };
    if s == "-0" {
        "0".into()
    } else {
        s.to_string()
    }
}

/// The most decimal places a number of the path data has (at most 9).
fn svg_decimals(d: &str) -> usize {
    let mut most = 0;
    let mut run: Option<usize> = None;
    for c in d.chars() {
        match (c, run) {
            ('.', _) => run = Some(0),
            (c, Some(k)) if c.is_ascii_digit() => run = Some(k + 1),
            _ => {
                most = most.max(run.unwrap_or(0));
                run = None;
            }
        }
    }
    most.max(run.unwrap_or(0)).min(9)
}

/// Path data for the contours (absolute `M L C Z`), `orig` telling which points moved,
/// unmoved ones with `decimals` places.
fn svg_data(contours: &[SvgContour], orig: &[SvgContour], decimals: usize) -> String {
    let mut out = Vec::new();
    for ((segs, closed, extra), (o, ..)) in contours.iter().zip(orig) {
        let pt = |p: Point, q: Point| {
            let k = if p == q { decimals } else { decimals.max(4) };
            format!("{} {}", svg_number(p.x, k), svg_number(p.y, k))
        };
        out.push(format!("M{}", pt(segs[0][0], o[0][0])));
        let n = segs.len() - usize::from(*extra);
        for (s, q) in segs.iter().zip(o).take(n) {
            match s.len() {
                2 => out.push(format!("L{}", pt(s[1], q[1]))),
                _ => out.push(format!(
                    "C{} {} {}",
                    pt(s[1], q[1]),
                    pt(s[2], q[2]),
                    pt(s[3], q[3])
                )),
            }
        }
        if *closed {
            out.push("Z".into());
        }
    }
    out.join(" ")
}

/// Smooth flags of a contour's joins by the angle test ([`SVG_SMOOTH_DEGREES`]).
fn svg_smooth(segs: &[Vec<Point>], closed: bool) -> Vec<bool> {
    let n = segs.len();
    let count = if closed { n } else { n.saturating_sub(1) };
    (0..count)
        .map(|j| {
            let (a, b) = (&segs[j], &segs[(j + 1) % n]);
            let (ta, tb) = (a[a.len() - 1] - a[a.len() - 2], b[1] - b[0]);
            let angle = aesthetic_curves::harmonize::tangent_angle(ta, tb);
            angle.to_degrees() <= SVG_SMOOTH_DEGREES
        })
        .collect()
}

/// One contour of lines (2 points) and cubics (4) repaired as `fix` repairs an SVG path:
/// its joins smooth where the tangent breaks by at most [`SVG_SMOOTH_DEGREES`]; the result
/// and those smooth flags (the protocol's `outline.fix`, the editor's Fix).
pub fn fix_segments(
    segments: &[Vec<Point>],
    closed: bool,
    opts: &FixOptions,
) -> aesthetic_curves::Result<(Harmonized, Vec<bool>)> {
    let smooth = svg_smooth(segments, closed);
    let h = repair(
        segments,
        closed,
        &smooth,
        &harmonize_options(opts),
        &opts.repairs,
    )?;
    Ok((h, smooth))
}

/// Fix every `<path>` of the SVG file at `input` (its own user units; the tolerance in
/// them) and write the file to `output` with only the `d` attributes of changed paths
/// replaced: everything else byte for byte as it was. Paths with arcs or quadratics are
/// left as they are and listed.
pub fn fix_svg(
    input: &Path,
    output: &Path,
    opts: &FixOptions,
) -> Result<(Vec<ContourFix>, FixCounts)> {
    let data = crate::outline_io::read_regular_file(input, crate::outline_io::MAX_FILE_BYTES)?;
    crate::outline_io::read_svg(&data).with_context(|| format!("{}", input.display()))?;
    let text =
        std::str::from_utf8(&data).with_context(|| format!("{}: not UTF-8", input.display()))?;
    let popts = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..Default::default()
    };
    let doc = roxmltree::Document::parse_with_options(text, popts)
        .with_context(|| format!("{}: not an XML document", input.display()))?;
    let hopts = HarmonizeOptions {
        tolerance: opts.tolerance,
        // At least 1e-4 user units: what the written numbers keep.
        grid: opts.grid.max(1e-4),
        move_points: opts.move_points,
        ..HarmonizeOptions::default()
    };
    let (mut fixes, mut counts) = (Vec::new(), FixCounts::default());
    let mut edits: Vec<(std::ops::Range<usize>, String)> = Vec::new();
    let paths = doc.descendants().filter(|n| n.has_tag_name("path"));
    for (k, node) in paths.enumerate() {
        let Some(attr) = node.attributes().find(|a| a.name() == "d") else {
            continue;
        };
        let name = node
            .attribute("id")
            .map_or(format!("path {}", k + 1), str::to_string);
        let decimals = svg_decimals(attr.value());
        let parsed = svg_contours(attr.value(), decimals);
        let contours = match parsed {
            Ok(c) => c,
            Err(why) => {
                counts.skipped_contours += 1;
                fixes.push(ContourFix {
                    glyph: name,
                    contour: 0,
                    input: None,
                    result: Err(why),
                });
                continue;
            }
        };
        let mut fixed = contours.clone();
        for (ci, (segs, closed, extra)) in contours.iter().enumerate() {
            // A contour under 1,000 grid steps across (0.1 user units at the 1e-4 grid) is
            // left: the written precision is too coarse for it (a moved handle would turn
            // by degrees).
            let (lo, hi) = segs.iter().flatten().fold(
                (
                    Point::new(f64::MAX, f64::MAX),
                    Point::new(f64::MIN, f64::MIN),
                ),
                |(lo, hi), p| {
                    (
                        Point::new(lo.x.min(p.x), lo.y.min(p.y)),
                        Point::new(hi.x.max(p.x), hi.y.max(p.y)),
                    )
                },
            );
            if (hi - lo).hypot() < 1000.0 * hopts.grid {
                counts.skipped_contours += 1;
                let why = format!(
                    "smaller than 1,000 grid steps of {} across: left as it is",
                    hopts.grid
                );
                fixes.push(ContourFix {
                    glyph: name.clone(),
                    contour: ci,
                    input: None,
                    result: Err(why),
                });
                continue;
            }
            let c = IndexedContour {
                segments: segs.clone(),
                indices: Vec::new(),
                closed: *closed,
                smooth: svg_smooth(segs, *closed),
            };
            let result =
                repair(segs, *closed, &c.smooth, &hopts, &opts.repairs).map_err(|e| e.to_string());
            if let Ok(h) = &result {
                counts.add(h, &c);
                fixed[ci] = (h.segments.clone(), *closed, *extra);
            } else {
                counts.skipped_contours += 1;
            }
            fixes.push(ContourFix {
                glyph: name.clone(),
                contour: ci,
                input: Some(c),
                result,
            });
        }
        if fixed != contours {
            edits.push((attr.range_value(), svg_data(&fixed, &contours, decimals)));
        }
    }
    let mut out = text.to_string();
    edits.sort_by_key(|e| std::cmp::Reverse(e.0.start));
    for (range, d) in edits {
        out.replace_range(range, &d);
    }
    std::fs::write(output, out).with_context(|| format!("writing {}", output.display()))?;
    Ok((fixes, counts))
}
