//! `aecurve check FILE`: the exact curvature check of a font's glyphs or an SVG's paths
//! (`aesthetic_curves::outline`), as a summary with the places most worth a look, or JSON.

use crate::commands::Command;
use aecurve::check_json::{
    shape_json, CheckCountsJson, CheckMillisJson, CheckTailJson, DefectCountsJson, FindingJson,
    RankedFindingJson, UnreadableJson,
};
use aecurve::outline_io::{self, Outlines, Shape, ShapeCheck as Checked};
use aesthetic_curves::outline::{ContourCheck, Finding};
use anyhow::Result;
use serde_json::{json, Value};
use std::io::Write;
use std::path::Path;
use std::path::PathBuf;

pub(crate) fn check(
    file: &Path,
    select: &[String],
    (json_out, top): (bool, usize),
    (report, pictures): (Option<&Path>, usize),
    thresholds: aesthetic_curves::outline::OutlineOptions,
) -> Result<()> {
    let suggest = thresholds.suggest;
    if let Some(t) = suggest {
        anyhow::ensure!(
            t.is_finite() && t > 0.0,
            "--suggest must be a positive distance"
        );
    }
    if let Some(r) = report {
        anyhow::ensure!(
            r.extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("html")),
            "{}: the report is an .html page",
            r.display()
        );
    }
    let t0 = std::time::Instant::now();
    let outlines: Outlines = outline_io::read(file)?;
    let read_ms = t0.elapsed().as_secs_f64() * 1e3;
    let shapes: Vec<_> = outlines
        .shapes
        .iter()
        .filter(|s| select.is_empty() || select.iter().any(|n| n == &s.name))
        .collect();
    if !select.is_empty() {
        for n in select {
            anyhow::ensure!(
                outlines.shapes.iter().any(|s| &s.name == n),
                "{}: no glyph or element named {n:?}",
                file.display()
            );
        }
    }
    let opts = aesthetic_curves::outline::OutlineOptions {
        grid: outline_io::options_for(&outlines).grid,
        ..thresholds
    };
    let shown = shapes.len() > 2000 && !json_out;
    let bar = aecurve::progress::bar(shapes.len() as u64, "checking shapes", shown);
    let tick = || bar.inc(1);
    let out = std::io::stdout();
    let mut json = json_out.then(|| std::io::BufWriter::new(out.lock()));
    if let Some(w) = &mut json {
        write!(
            w,
            "{{\"file\":{},\"kind\":{},\"shapes\":",
            json!(file.display().to_string()),
            json!(outlines.kind)
        )
        .map_err(json_error)?;
    }
    let font = outlines.kind == "font";
    let folded = fold_checks((&shapes, font), &opts, &tick, json.as_mut())?;
    bar.finish_and_clear();
    if let Some(r) = report {
        let title = format!(
            "aecurve check: {}",
            file.file_name()
                .map_or(String::new(), |n| n.to_string_lossy().to_string())
        );
        // The drawn shapes are checked again (the fold keeps no shape's checks).
        let drawn: Vec<&Shape> = folded
            .worst
            .iter()
            .take(pictures)
            .map(|&i| shapes[i])
            .collect();
        let checked = outline_io::check_shapes(&drawn, &opts, &|| {});
        let pairs: Vec<_> = drawn.iter().copied().zip(checked.iter()).collect();
        // Fonts have y up; SVG (and its user units) y down; DXF y up.
        let y_up = outlines.kind != "svg";
        let page = aecurve::report::outline_report_drawn(&title, y_up, shapes.len(), &pairs);
        std::fs::write(r, page).map_err(|e| anyhow::anyhow!("writing {}: {e}", r.display()))?;
        if !json_out {
            eprintln!("wrote {}", r.display());
        }
    }
    let times = (read_ms, folded.check_ms);
    match json {
        Some(mut w) => write_json_tail(&mut w, &folded, &outlines, times).map_err(json_error),
        None => {
            print_summary(file, &outlines, &folded, (&opts, suggest), times);
            print_findings(&folded.ranked, top);
            Ok(())
        }
    }
}

fn json_error(e: std::io::Error) -> anyhow::Error {
    anyhow::anyhow!("writing the JSON report: {e}")
}

/// The counts of the summary, folded shape by shape.
#[derive(Default)]
struct Tally {
    shapes: usize,
    segments: usize,
    curved: usize,
    cubics: usize,
    monotone: usize,
    inflections: usize,
    joins: usize,
    g1: usize,
    g2: usize,
    near: usize,
    suggested: usize,
    exact: usize,
    retracted: usize,
    /// G1 joins of a line and a curve with a curvature step, not marked smooth (not listed).
    line_steps: usize,
    /// Findings by kind, every shape's (a place shared by several glyphs counts in each).
    found: std::collections::BTreeMap<&'static str, usize>,
}

impl Tally {
    fn add(&mut self, c: &Checked) {
        self.shapes += 1;
        for k in &c.contours {
            self.add_contour(k);
        }
        for f in &c.findings {
            *self.found.entry(f.kind).or_default() += 1;
        }
    }

    fn found(&self, kind: &str) -> usize {
        self.found.get(kind).copied().unwrap_or(0)
    }

    fn add_contour(&mut self, c: &ContourCheck) {
        let segs = &c.segments;
        self.segments += segs.len();
        self.monotone += c.monotone_count();
        self.curved += segs.iter().filter(|s| s.degree > 1).count();
        self.cubics += segs.iter().filter(|s| s.degree == 3).count();
        self.inflections += segs.iter().map(|s| s.inflections.len()).sum::<usize>();
        self.suggested += segs.iter().filter(|s| s.suggestion.is_some()).count();
        self.exact += segs.iter().filter(|s| s.exact).count();
        self.retracted += segs.iter().filter(|s| !s.notes.is_empty()).count();
        self.joins += c.joins.len();
        self.g1 += c.joins.iter().filter(|j| j.g1).count();
        self.g2 += c.joins.iter().filter(|j| j.g2).count();
        self.near += c.joins.iter().filter(|j| j.near_break).count();
        self.line_steps += c.joins.iter().filter(|j| c.unlisted_line_step(j)).count();
    }

    fn json(&self) -> CheckCountsJson {
        CheckCountsJson {
            shapes: self.shapes,
            segments: self.segments,
            curved_segments: self.curved,
            monotone_segments: self.monotone,
            inflections: self.inflections,
            joins: self.joins,
            g1_joins: self.g1,
            g2_joins: self.g2,
            near_breaks: self.near,
            suggestions: self.suggested,
            exact_arithmetic: self.exact,
            retracted_handles: self.retracted,
            defects: DefectCountsJson {
                hooks: self.found("hook"),
                several_extrema: self.found("not-monotone"),
                curvature_jumps: self.found("curvature-jump"),
                near_breaks: self.found("near-break"),
                degenerate: self.found("degenerate"),
            },
            one_extremum_inside: self.found("curvature-extremum"),
            line_curve_steps: self.line_steps,
        }
    }
}

/// A finding, once for every shape that has it: the first shape's name, and the others'.
struct Ranked<'a> {
    name: &'a str,
    finding: Finding,
    also_in: Vec<&'a str>,
    /// The largest use weight of the glyphs that have it ([`use_weight`]).
    weight: f64,
}

impl Ranked<'_> {
    /// The ranking's key: the finding's score times the use weight, raised by 5 %
    /// for each other glyph that shares the place (up to ten).
    fn rank(&self) -> f64 {
        self.finding.score * self.weight * (1.0 + 0.05 * self.also_in.len().min(10) as f64)
    }
}

/// How much a glyph's findings weigh in the ranking, by what text uses it: basic Latin
/// (U+0020 to U+007E) 1; the rest of Latin up to Latin Extended-B, general punctuation and
/// currency signs 0.6; Greek, Cyrillic, Latin Extended Additional, and glyphs without a
/// code point (alternates, ligatures, small capitals, components) 0.4; any other code
/// point (symbols, arrows, dingbats, emoji, other scripts) 0.2. Paths of SVG and DXF files
/// weigh 1.
fn use_weight(shape: &Shape, font: bool) -> f64 {
    if !font {
        return 1.0;
    }
    let of = |cp: u32| match cp {
        0x20..=0x7E => 1.0,
        0xA0..=0x24F | 0x2010..=0x206F | 0x20A0..=0x20CF => 0.6,
        0x370..=0x52F | 0x1E00..=0x1FFF => 0.4,
        _ => 0.2,
    };
    if shape.unicodes.is_empty() {
        return 0.4;
    }
    shape.unicodes.iter().map(|&c| of(c)).fold(0.0, f64::max)
}

/// The same place in several shapes (a component drawn in each composite that uses it, a
/// serif repeated): the finding's kind and the shape of its segment (and, at a join, of the
/// next one), relative to the segment's first point, to the bit.
fn place_key(shape: &Shape, f: &Finding) -> Option<(&'static str, Vec<u64>)> {
    let c = shape.contours.get(f.contour)?;
    let n = c.segments.len();
    let first = c.segments.get(f.segment)?;
    let origin = first.points()[0];
    let mut key = Vec::new();
    let join = matches!(f.kind, "near-break" | "curvature-jump");
    let segs = if join {
        vec![f.segment, (f.segment + 1) % n]
    } else {
        vec![f.segment]
    };
    for s in segs {
        let b = &c.segments[s];
        for p in b.points() {
            key.push((p.x - origin.x).to_bits());
            key.push((p.y - origin.y).to_bits());
        }
        key.extend(b.weights().iter().map(|w| w.to_bits()));
    }
    Some((f.kind, key))
}

/// The findings of every shape, each place once (with the other shapes that have it), worst
/// first by [`Ranked::rank`] (`font`: weighed by use).
fn rank_once<'a>(found: Vec<(&'a Shape, Finding)>, font: bool) -> Vec<Ranked<'a>> {
    let mut seen: std::collections::HashMap<(&str, Vec<u64>), usize> = Default::default();
    let mut out: Vec<Ranked> = Vec::new();
    for (shape, f) in found {
        match place_key(shape, &f) {
            Some(key) if seen.contains_key(&key) => {
                let r = &mut out[seen[&key]];
                if r.name != shape.name && !r.also_in.contains(&shape.name.as_str()) {
                    r.also_in.push(&shape.name);
                }
                r.weight = r.weight.max(use_weight(shape, font));
            }
            key => {
                if let Some(k) = key {
                    seen.insert(k, out.len());
                }
                out.push(Ranked {
                    name: &shape.name,
                    finding: f,
                    also_in: Vec::new(),
                    weight: use_weight(shape, font),
                });
            }
        }
    }
    out.sort_by(|a, b| b.rank().total_cmp(&a.rank()));
    out
}

/// What the fold keeps of the checks: the counts, every finding (ranked, worst first) and
/// the shapes' indices, worst first (for the report's pictures).
struct Folded<'a> {
    tally: Tally,
    ranked: Vec<Ranked<'a>>,
    worst: Vec<usize>,
    check_ms: f64,
}

/// Shapes checked per round: enough to keep every core busy, few enough that memory holds
/// the checks of a few hundred shapes (plus the largest), not of the whole file.
const ROUND: usize = 256;

/// Check `shapes` round by round, folding each shape's check into counts and findings (and
/// writing its JSON to `json`) before the next round, so that memory grows with the file
/// and its findings, not with the checks of every segment.
fn fold_checks<'a>(
    (shapes, font): (&[&'a Shape], bool),
    opts: &aesthetic_curves::outline::OutlineOptions,
    tick: &(dyn Fn() + Sync),
    mut json: Option<&mut impl Write>,
) -> Result<Folded<'a>> {
    let mut tally = Tally::default();
    let mut ranked = Vec::new();
    let mut scores = Vec::with_capacity(shapes.len());
    let mut check_ms = 0.0;
    if let Some(w) = json.as_mut() {
        w.write_all(b"[").map_err(json_error)?;
    }
    for (round, chunk) in shapes.chunks(ROUND).enumerate() {
        let t = std::time::Instant::now();
        let checked = outline_io::check_shapes(chunk, opts, tick);
        check_ms += t.elapsed().as_secs_f64() * 1e3;
        for (j, c) in checked.into_iter().enumerate() {
            tally.add(&c);
            if let Some(w) = json.as_mut() {
                if round + j > 0 {
                    w.write_all(b",").map_err(json_error)?;
                }
                serde_json::to_writer(&mut **w, &shape_json(&c))?;
            }
            scores.push((round * ROUND + j, aecurve::report::rank(&c)));
            let shape = shapes[round * ROUND + j];
            ranked.extend(c.findings.into_iter().map(|f| (shape, f)));
        }
    }
    if let Some(w) = json.as_mut() {
        w.write_all(b"]").map_err(json_error)?;
    }
    let ranked = rank_once(ranked, font);
    scores.sort_by(|a, b| aecurve::report::worse_rank_first(a.1, b.1));
    Ok(Folded {
        tally,
        ranked,
        worst: scores.into_iter().map(|(i, _)| i).collect(),
        check_ms,
    })
}

/// The rest of `check --json` after the streamed shapes ([`CheckTailJson`]'s fields, each
/// after a comma: the document's object goes on).
fn write_json_tail(
    w: &mut impl Write,
    folded: &Folded,
    outlines: &Outlines,
    (read_ms, check_ms): (f64, f64),
) -> std::io::Result<()> {
    let tail = CheckTailJson {
        counts: folded.tally.json(),
        findings: (folded.ranked.iter())
            .map(|r| RankedFindingJson {
                finding: FindingJson::new(r.name, &r.finding),
                severity: r.finding.score,
                use_weight: r.weight,
                rank: r.rank(),
                also_in: r.also_in.iter().map(|n| n.to_string()).collect(),
            })
            .collect(),
        milliseconds: CheckMillisJson {
            read: read_ms,
            check: check_ms,
        },
        unreadable: (outlines.unreadable.iter())
            .map(|(n, e)| UnreadableJson {
                name: n.to_string(),
                error: e.to_string(),
            })
            .collect(),
    };
    if let Value::Object(fields) = serde_json::to_value(&tail)? {
        for (k, v) in fields {
            write!(w, ",{}:", Value::String(k))?;
            serde_json::to_writer(&mut *w, &v)?;
        }
    }
    writeln!(w, "}}")?;
    w.flush()
}

fn print_summary(
    file: &Path,
    outlines: &Outlines,
    folded: &Folded,
    (opts, suggest): (&aesthetic_curves::outline::OutlineOptions, Option<f64>),
    (read_ms, check_ms): (f64, f64),
) {
    let t = &folded.tally;
    let (segments, monotone, exact) = (t.segments, t.monotone, t.exact);
    println!(
        "{} ({}): {} {}, {segments} segments ({} curved), {} joins",
        file.display(),
        outlines.kind,
        t.shapes,
        if outlines.kind == "font" {
            "glyphs"
        } else {
            "paths"
        },
        t.curved,
        t.joins
    );
    let defects = [
        "hook",
        "not-monotone",
        "curvature-jump",
        "near-break",
        "degenerate",
    ]
    .iter()
    .map(|k| t.found(k))
    .sum::<usize>();
    println!(
        "  defects: {defects} ({} hooks, {} segments with several curvature extrema, {} curvature jumps at smooth joins, {} near-breaks, {} degenerate segments)",
        t.found("hook"),
        t.found("not-monotone"),
        t.found("curvature-jump"),
        t.found("near-break"),
        t.found("degenerate"),
    );
    println!(
        "  design, not counted as defects: {} segments with one curvature extremum inside, {} curvature steps where a line meets a curve at a point not marked smooth",
        t.found("curvature-extremum"),
        t.line_steps,
    );
    println!(
        "  curvature monotone: {monotone} of {segments} segments ({} not, or flagged: detours under --min-bump, one extremum inside and the defects above); {} inflection(s) inside segments",
        segments - monotone,
        t.inflections
    );
    println!(
        "  proofs: every verdict exact for the file's coordinates; {exact} of {segments} needed exact integer arithmetic ({:.2} %); {} segment(s) with retracted handles",
        if segments > 0 { 100.0 * exact as f64 / segments as f64 } else { 0.0 },
        t.retracted
    );
    println!(
        "  joins: {} G1 (of which {} G2), {} near-breaks (above G1{} and under 3°: probably meant smooth)",
        t.g1,
        t.g2,
        t.near,
        if opts.grid > 0.0 { " and the integer grid's rounding" } else { "" }
    );
    if !outlines.unreadable.is_empty() {
        println!("  unreadable: {}", outlines.unreadable.len());
        for (n, e) in outlines.unreadable.iter().take(5) {
            println!("    {n}: {e}");
        }
    }
    if let Some(t) = suggest {
        if folded.tally.cubics == 0 {
            println!(
                "  suggestions: none: the file has no cubic segments (TrueType outlines are quadratic), and --suggest changes cubic handles"
            );
        } else {
            println!(
                "  suggestions: {} cubics become monotone by their handle lengths alone, moving at most {t}",
                folded.tally.suggested
            );
        }
    }
    println!("  read in {read_ms:.1} ms, checked in {check_ms:.1} ms");
}

fn print_findings(ranked: &[Ranked], top: usize) {
    if ranked.is_empty() {
        return;
    }
    let kinds = [
        ("hook", "hooks"),
        ("not-monotone", "segments with several curvature extrema"),
        ("curvature-extremum", "with one extremum inside"),
        ("near-break", "near-breaks"),
        ("curvature-jump", "curvature jumps at smooth joins"),
        ("degenerate", "degenerate segments"),
    ];
    let counts: Vec<String> = kinds
        .iter()
        .map(|(k, words)| {
            (
                ranked.iter().filter(|r| r.finding.kind == *k).count(),
                words,
            )
        })
        .filter(|(n, _)| *n > 0)
        .map(|(n, words)| format!("{n} {words}"))
        .collect();
    println!(
        "findings, each place once however many glyphs share it: {}",
        counts.join(", ")
    );
    println!(
        "most worth a look ({} of {}):",
        top.min(ranked.len()),
        ranked.len()
    );
    for r in ranked.iter().take(top) {
        let f = &r.finding;
        let also = match r.also_in.len() {
            0 => String::new(),
            k => format!(
                " (also in {k}: {}{})",
                r.also_in
                    .iter()
                    .take(4)
                    .copied()
                    .collect::<Vec<_>>()
                    .join(", "),
                if k > 4 { ", ..." } else { "" }
            ),
        };
        println!(
            "  {}{also}, contour {}, segment {} at ({:.1}, {:.1}): {}",
            r.name, f.contour, f.segment, f.point.x, f.point.y, f.message
        );
    }
}

/// The arguments of `aecurve check` (the command's help is its entry in `cli.rs`).
#[derive(clap::Args)]
pub(crate) struct Args {
    /// The file.
    file: PathBuf,
    /// Only these glyphs or SVG element ids (repeatable).
    #[arg(long = "select", alias = "glyphs")]
    select: Vec<String>,
    /// Print everything as JSON instead of the summary.
    #[arg(long)]
    json: bool,
    /// How many findings the summary lists.
    #[arg(long, default_value_t = 20)]
    top: usize,
    /// Write an HTML report: a picture per glyph or path (curve, comb, extrema,
    /// inflections, flagged joins), the worst first.
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Most pictures in the report.
    #[arg(long, default_value_t = 200)]
    pictures: usize,
    /// For every cubic whose curvature is not monotone, suggest handle lengths that make
    /// it monotone (end points and tangent directions kept), moving it by at most this
    /// (file units: font units for a font).
    #[arg(long)]
    suggest: Option<f64>,
    /// The thresholds of the verdicts and the findings.
    #[command(flatten)]
    thresholds: Thresholds,
}

impl Command for Args {
    fn outputs(&self) -> Vec<&Path> {
        self.output.as_deref().into_iter().collect()
    }

    fn run(self) -> Result<()> {
        check(
            &self.file,
            &self.select,
            (self.json, self.top),
            (self.output.as_deref(), self.pictures),
            aesthetic_curves::outline::OutlineOptions {
                suggest: self.suggest,
                ..self.thresholds.options()?
            },
        )
    }
}

/// `check`'s thresholds (the library's `OutlineOptions`).
#[derive(clap::Args, Debug, Clone, Copy)]
pub struct Thresholds {
    /// A join whose tangents differ by at most this (degrees) is G1 (plus what the
    /// integer grid's rounding can make, for a font).
    #[arg(long, default_value_t = 0.05)]
    pub g1_angle: f64,
    /// A G1 join whose relative curvature jump is under this is G2 (0.05: 5 %).
    #[arg(long, default_value_t = 0.05)]
    pub g2_jump: f64,
    /// Breaks above G1 and under this (degrees) are listed as probably meant smooth.
    #[arg(long, default_value_t = 3.0)]
    pub near_break: f64,
    /// Non-monotone segments whose curvature detour is under this share of their largest
    /// curvature are not listed (0.05: 5 %; a cubic standing for a circular arc varies by a
    /// few per cent).
    #[arg(long, default_value_t = 0.05)]
    pub min_bump: f64,
}

impl Thresholds {
    /// The library's options (the grid and the suggestion set apart).
    pub fn options(&self) -> anyhow::Result<aesthetic_curves::outline::OutlineOptions> {
        aesthetic_curves::outline::Thresholds {
            g1_angle_degrees: self.g1_angle,
            g2_jump: self.g2_jump,
            near_break_degrees: self.near_break,
            min_bump: self.min_bump,
        }
        .options(0.0)
        .map_err(|e| match e {
            aesthetic_curves::Error::InvalidInput { field, message } => {
                anyhow::anyhow!("--{}: {message}", field.replace('_', "-"))
            }
            e => e.into(),
        })
    }
}
