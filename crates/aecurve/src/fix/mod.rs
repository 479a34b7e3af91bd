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

pub mod glif_patch;
pub mod masters;
pub mod report;
pub mod svg_path;
use crate::atomic_out::{write_new, Staging};
use crate::ufo_tree::UfoTree;
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
    /// When to stop starting contours (`--timeout`): those not begun by then are left as
    /// they are and listed.
    pub deadline: Option<std::time::Instant>,
}

/// Most segments of a contour `fix` repairs. The repair's time grows about linearly with a
/// contour's length (a long cycle is cut and its joint problem solved in windows): about
/// 20 ms a segment on a 2-core machine where every join of a wavy closed contour is off,
/// so one contour takes at most about 8 s. A longer one (no glyph's contour comes near:
/// the largest have a few hundred points) is left as it is and listed with its size.
pub const MAX_FIX_SEGMENTS: usize = 400;

/// Why a contour is not repaired before any work: over [`MAX_FIX_SEGMENTS`], or the
/// deadline passed.
fn left_before_work(segments: usize, opts: &FixOptions) -> Option<String> {
    if segments > MAX_FIX_SEGMENTS {
        return Some(format!(
            "{segments} segments: over the {MAX_FIX_SEGMENTS} fix repairs in one contour; left as it is"
        ));
    }
    if opts
        .deadline
        .is_some_and(|d| std::time::Instant::now() >= d)
    {
        return Some("the --timeout was reached before this contour: left as it is".into());
    }
    None
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

/// Fix every glyph of the UFO at `input`'s default layer and write the UFO to `output`
/// (replacing what is there only when `overwrite`): the per-contour results and the counts.
///
/// The UFO is read whole and confined to its folder first ([`UfoTree`]); the output is
/// built in a staging folder and moved into place complete ([`Staging`]): every file as it
/// was read, byte for byte with its modification time, but the `.glif` files of glyphs
/// whose points moved, in which only those points' coordinates change ([`glif_patch`]).
pub fn fix_ufo(
    input: &Path,
    output: &Path,
    opts: &FixOptions,
    overwrite: bool,
) -> Result<(Vec<ContourFix>, FixCounts)> {
    let staging = Staging::new(output, overwrite, &[input])?;
    let tree = UfoTree::read(input, crate::outline_io::MAX_FILE_BYTES)?;
    let font =
        load_font(&tree).with_context(|| format!("{}: not a UFO `fix` reads", input.display()))?;
    let mut fixes = fix_font(&font, opts);
    let patched = patched_glifs(&tree, &font, &mut fixes)?;
    let counts = counts_of(&fixes);
    write_tree(&tree, &patched, &staging.output()?)?;
    staging.commit()?;
    Ok((fixes, counts))
}

/// The font of a UFO tree, with a default layer that holds glyphs.
pub fn load_font(tree: &UfoTree) -> Result<norad::Font> {
    let font = tree.font()?;
    if font.default_layer().is_empty() {
        anyhow::bail!("not a readable UFO: its default layer has no glyphs");
    }
    Ok(font)
}

/// The counts of a font's (or a master's) fixes.
pub fn counts_of(fixes: &[ContourFix]) -> FixCounts {
    let mut counts = FixCounts::default();
    for f in fixes {
        match (&f.result, &f.input) {
            (Ok(h), Some(c)) => counts.add(h, c),
            _ => counts.skipped_contours += 1,
        }
    }
    counts
}

/// The new text of every `.glif` file of the default layer whose points moved (path in the
/// tree to bytes). A glyph whose file cannot be patched (its structure is not what norad
/// read) keeps its file, and its contours' results become that error.
pub fn patched_glifs(
    tree: &UfoTree,
    font: &norad::Font,
    fixes: &mut [ContourFix],
) -> Result<std::collections::BTreeMap<std::path::PathBuf, Vec<u8>>> {
    let layers = tree.layers()?;
    let default_dir = Path::new("glyphs");
    let Some(layer) = layers.iter().find(|l| l.dir == default_dir) else {
        anyhow::bail!("{}: no default layer (`glyphs`)", tree.root.display());
    };
    let mut moved: std::collections::BTreeMap<String, Vec<glif_patch::Moved>> = Default::default();
    for f in fixes.iter() {
        let (Ok(h), Some(c)) = (&f.result, &f.input) else {
            continue;
        };
        let list = moved.entry(f.glyph.clone()).or_default();
        for (idx, (before, after)) in c.indices.iter().zip(c.segments.iter().zip(&h.segments)) {
            for ((&i, a), b) in idx.iter().zip(after).zip(before) {
                if a != b {
                    list.push(glif_patch::Moved {
                        contour: f.contour,
                        point: i,
                        to: *a,
                    });
                }
            }
        }
    }
    let mut out = std::collections::BTreeMap::new();
    let mut failed: std::collections::HashMap<String, String> = Default::default();
    for (glyph, list) in moved.iter().filter(|(_, l)| !l.is_empty()) {
        let result = (|| {
            let file = layer
                .glyphs
                .get(glyph)
                .ok_or_else(|| anyhow::anyhow!("no file"))?;
            let g = font.default_layer().get_glyph(glyph.as_str());
            let sizes: Vec<usize> = g.map_or(Vec::new(), |g| {
                g.contours.iter().map(|c| c.points.len()).collect()
            });
            let text = std::str::from_utf8(tree.get(file).unwrap_or_default())?;
            Ok::<_, anyhow::Error>((file.clone(), glif_patch::patch_glif(text, &sizes, list)?))
        })();
        match result {
            Ok((file, text)) => {
                out.insert(file, text.into_bytes());
            }
            Err(e) => {
                failed.insert(
                    glyph.clone(),
                    format!("its .glif file was not written back: {e}"),
                );
            }
        }
    }
    for f in fixes.iter_mut() {
        if let Some(why) = failed.get(&f.glyph) {
            f.result = Err(why.clone());
        }
    }
    Ok(out)
}

/// The tree written at `at` (a new folder): every folder, every file as read (with its
/// modification time) or as `patched` holds it.
pub fn write_tree(
    tree: &UfoTree,
    patched: &std::collections::BTreeMap<std::path::PathBuf, Vec<u8>>,
    at: &Path,
) -> Result<()> {
    std::fs::create_dir(at).with_context(|| format!("making {}", at.display()))?;
    for d in &tree.dirs {
        let p = at.join(d);
        std::fs::create_dir(&p).with_context(|| format!("making {}", p.display()))?;
    }
    for (rel, f) in &tree.files {
        let (bytes, modified) = match patched.get(rel) {
            Some(b) => (b.as_slice(), None),
            None => (f.bytes.as_slice(), f.modified),
        };
        write_new(&at.join(rel), bytes, modified)?;
    }
    Ok(())
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
                if let Some(why) = left_before_work(c.segments.len(), opts) {
                    return Err(why);
                }
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

/// A tangent break of at most this (degrees) counts as a smooth join in an SVG path (SVG
/// stores no smooth flags; editors keep smooth handles collinear to rounding).
pub const SVG_SMOOTH_DEGREES: f64 = 0.5;

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

/// The width of a contour's points' bounding box's diagonal.
fn extent(segs: &[Vec<Point>]) -> f64 {
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
    (hi - lo).hypot()
}

/// Whether a repair made something better: a join's curvature jump or angle smaller
/// (beyond 1e-9), or fewer cubics with a hook or several extrema.
fn improves(h: &Harmonized, c: &IndexedContour) -> bool {
    let joins = h
        .joins
        .iter()
        .any(|j| j.jump.1 < j.jump.0 - 1e-9 || j.angle.1 < j.angle.0 - 1e-9);
    let zone = Repairs::default().hook_zone;
    let bumps = |segs: &[Vec<Point>]| {
        segs.iter()
            .filter(|p| has_bump(p, zone).unwrap_or(false))
            .count()
    };
    joins || bumps(&h.segments) < bumps(&c.segments)
}

/// A repair's result given back its input (nothing moved, every join as it was).
fn unchanged(mut h: Harmonized, c: &IndexedContour) -> Harmonized {
    let all: Vec<usize> = (0..c.segments.len()).collect();
    h.restore(&c.segments, c.closed, &all);
    h
}

/// Why an SVG `<path>` is not drawn, if it is not: not in SVG's namespace, inside
/// `<defs>`, `<clipPath>`, `<mask>`, `<metadata>` and the like (used or never drawn, not
/// seen as such), or hidden (`display="none"`, `visibility` hidden or collapsed, as an
/// attribute or in `style`, on it or on an element that holds it).
fn not_rendered(node: roxmltree::Node) -> Option<String> {
    const SVG: &str = "http://www.w3.org/2000/svg";
    if node.tag_name().namespace() != Some(SVG) {
        return Some("not an SVG-namespace path".into());
    }
    let style = |n: roxmltree::Node, prop: &str| -> Option<String> {
        let inline = n.attribute("style").and_then(|s| {
            s.split(';').find_map(|decl| {
                let (k, v) = decl.split_once(':')?;
                (k.trim() == prop).then(|| v.trim().to_string())
            })
        });
        inline.or_else(|| n.attribute(prop).map(|v| v.trim().to_string()))
    };
    let mut visibility: Option<String> = None;
    for n in node.ancestors().filter(|n| n.is_element()) {
        let tag = n.tag_name().name();
        if n != node
            && matches!(
                tag,
                "defs"
                    | "clipPath"
                    | "mask"
                    | "metadata"
                    | "symbol"
                    | "marker"
                    | "pattern"
                    | "title"
                    | "desc"
                    | "switch"
            )
        {
            return Some(format!("inside <{tag}>, not drawn as it is"));
        }
        if n.tag_name().namespace() != Some(SVG) {
            return Some(format!("inside the foreign element <{tag}>"));
        }
        if style(n, "display").as_deref() == Some("none") {
            return Some("hidden (display: none)".into());
        }
        if visibility.is_none() {
            visibility = style(n, "visibility");
        }
    }
    match visibility.as_deref() {
        Some("hidden") | Some("collapse") => Some("hidden (visibility)".into()),
        _ => None,
    }
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
    overwrite: bool,
) -> Result<(Vec<ContourFix>, FixCounts)> {
    let staging = Staging::new(output, overwrite, &[input])?;
    let data = crate::outline_io::read_regular_file(input, crate::outline_io::MAX_FILE_BYTES)?;
    crate::outline_io::read_svg(&data).with_context(|| format!("{}", input.display()))?;
    let text =
        std::str::from_utf8(&data).with_context(|| format!("{}: not UTF-8", input.display()))?;
    let popts = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..Default::default()
    };
    let doc = crate::contained::contained(|| {
        roxmltree::Document::parse_with_options(text, popts)
            .with_context(|| format!("{}: not an XML document", input.display()))
    })?;
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
        let Some(attr) = node
            .attributes()
            .find(|a| a.name() == "d" && a.namespace().is_none())
        else {
            continue;
        };
        let name = node
            .attribute("id")
            .map_or(format!("path {}", k + 1), str::to_string);
        let left = |why: String| ContourFix {
            glyph: name.clone(),
            contour: 0,
            input: None,
            result: Err(why),
        };
        if let Some(why) = not_rendered(node) {
            counts.skipped_contours += 1;
            fixes.push(left(format!("{why}: left as it is")));
            continue;
        }
        let raw = &text[attr.range_value()];
        if raw != attr.value() {
            counts.skipped_contours += 1;
            fixes.push(left(
                "path data with character references: left as it is".into(),
            ));
            continue;
        }
        let decimals = svg_decimals(raw);
        let cmds = match svg_path::parse(raw) {
            Ok(c) => c,
            Err(why) => {
                counts.skipped_contours += 1;
                fixes.push(left(why));
                continue;
            }
        };
        let abs = svg_path::absolute(&cmds);
        let contours = svg_path::contours(&cmds, &abs, decimals);
        let mut fixed = contours.clone();
        let mut changed = false;
        for (ci, ((segs, closed, _), _)) in contours.iter().enumerate() {
            // A contour under 1,000 grid steps across (0.1 user units at the 1e-4 grid) is
            // left: the written precision is too coarse for it (a moved handle would turn
            // by degrees).
            if extent(segs) < 1000.0 * hopts.grid {
                counts.skipped_contours += 1;
                let why = format!(
                    "smaller than 1,000 grid steps of {} across: left as it is",
                    hopts.grid
                );
                fixes.push(ContourFix {
                    contour: ci,
                    ..left(why)
                });
                continue;
            }
            let c = IndexedContour {
                segments: segs.clone(),
                indices: Vec::new(),
                closed: *closed,
                smooth: svg_smooth(segs, *closed),
            };
            let result = match left_before_work(segs.len(), opts) {
                Some(why) => Err(why),
                None => repair(segs, *closed, &c.smooth, &hopts, &opts.repairs)
                    .map_err(|e| e.to_string()),
            };
            // A contour is written back only where a join or a bump got better: moves that
            // improve nothing (rounding to the grid) leave its numbers as they were.
            let result = result.map(|h| {
                if improves(&h, &c) {
                    h
                } else {
                    unchanged(h, &c)
                }
            });
            if let Ok(h) = &result {
                counts.add(h, &c);
                changed |= h.segments != *segs;
                fixed[ci].0 .0 = h.segments.clone();
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
        if changed {
            let new = svg_path::moved_points(&abs, &fixed);
            let d = svg_path::rewrite(raw, &cmds, (&abs, &new), decimals.max(4), svg_number);
            edits.push((attr.range_value(), d));
        }
    }
    let mut out = text.to_string();
    edits.sort_by_key(|e| std::cmp::Reverse(e.0.start));
    for (range, d) in edits {
        out.replace_range(range, &d);
    }
    write_new(&staging.output()?, out.as_bytes(), None)?;
    staging.commit()?;
    Ok((fixes, counts))
}
