//! `aecurve check FILE`: the exact curvature check of a font's glyphs or an SVG's paths
//! (`aesthetic_curves::outline`), as a summary with the places most worth a look, or JSON.

use aecurve::outline_io::{self, finding_json, shape_json, Outlines, ShapeCheck as Checked};
use aesthetic_curves::outline::{ContourCheck, Finding};
use anyhow::Result;
use serde_json::{json, Value};
use std::path::Path;

pub(crate) fn check(
    file: &Path,
    select: &[String],
    json_out: bool,
    top: usize,
    (report, pictures): (Option<&Path>, usize),
    suggest: Option<f64>,
) -> Result<()> {
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
        suggest,
        ..outline_io::options_for(&outlines)
    };
    let bar = (shapes.len() > 2000 && !json_out).then(|| {
        let b = indicatif::ProgressBar::new(shapes.len() as u64);
        b.set_style(
            indicatif::ProgressStyle::with_template("checking {bar:40} {pos}/{len} shapes")
                .expect("template"),
        );
        b
    });
    let t1 = std::time::Instant::now();
    let tick = || {
        if let Some(b) = &bar {
            b.inc(1);
        }
    };
    let checked: Vec<Checked> = outline_io::check_shapes(&shapes, &opts, &tick);
    let check_ms = t1.elapsed().as_secs_f64() * 1e3;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let count = |f: &dyn Fn(&ContourCheck) -> usize| -> usize {
        checked.iter().flat_map(|c| c.contours.iter()).map(f).sum()
    };
    let segments = count(&|c| c.segments.len());
    let monotone = count(&|c| c.monotone_count());
    let curved = count(&|c| c.segments.iter().filter(|s| s.degree > 1).count());
    let joins = count(&|c| c.joins.len());
    let g1 = count(&|c| c.joins.iter().filter(|j| j.g1).count());
    let g2 = count(&|c| c.joins.iter().filter(|j| j.g2).count());
    let near = count(&|c| c.joins.iter().filter(|j| j.near_break).count());
    let inflections = count(&|c| c.segments.iter().map(|s| s.inflections.len()).sum());
    let suggested = count(&|c| c.segments.iter().filter(|s| s.suggestion.is_some()).count());
    let exact = count(&|c| c.segments.iter().filter(|s| s.exact).count());
    let retracted = count(&|c| c.segments.iter().filter(|s| !s.notes.is_empty()).count());
    if let Some(r) = report {
        let title = format!(
            "aecurve check: {}",
            file.file_name()
                .map_or(String::new(), |n| n.to_string_lossy().to_string())
        );
        // Fonts have y up; SVG (and its user units) y down; DXF y up.
        let page = aecurve::report::outline_report(
            &title,
            outlines.kind != "svg",
            &shapes,
            &checked,
            pictures,
        );
        std::fs::write(r, page).map_err(|e| anyhow::anyhow!("writing {}: {e}", r.display()))?;
        if !json_out {
            eprintln!("wrote {}", r.display());
        }
    }
    let mut ranked: Vec<(&str, &Finding)> = checked
        .iter()
        .flat_map(|c| c.findings.iter().map(move |f| (c.name, f)))
        .collect();
    ranked.sort_by(|a, b| b.1.score.total_cmp(&a.1.score));
    if json_out {
        // Streamed shape by shape (keys in the order serde_json sorts them), so memory
        // grows with the file, not with a document of every shape's JSON at once.
        let counts = json!({
            "shapes": checked.len(), "segments": segments, "curved_segments": curved,
            "monotone_segments": monotone, "inflections": inflections, "joins": joins,
            "g1_joins": g1, "g2_joins": g2, "near_breaks": near, "suggestions": suggested,
            "exact_arithmetic": exact, "retracted_handles": retracted,
        });
        let unreadable: Vec<Value> = outlines
            .unreadable
            .iter()
            .map(|(n, e)| json!({"name": n, "error": e}))
            .collect();
        let out = std::io::stdout();
        let mut w = std::io::BufWriter::new(out.lock());
        let write = || -> std::io::Result<()> {
            use std::io::Write;
            write!(
                w,
                "{{\"counts\":{counts},\"file\":{},",
                json!(file.display().to_string())
            )?;
            write!(w, "\"findings\":")?;
            write_array(&mut w, ranked.iter().map(|(n, f)| finding_json(n, f)))?;
            write!(w, ",\"kind\":{},", json!(outlines.kind))?;
            write!(
                w,
                "\"milliseconds\":{},\"shapes\":",
                json!({"read": read_ms, "check": check_ms})
            )?;
            write_array(&mut w, checked.iter().map(shape_json))?;
            writeln!(w, ",\"unreadable\":{}}}", Value::Array(unreadable))?;
            w.flush()
        };
        write().map_err(|e| anyhow::anyhow!("writing the JSON report: {e}"))?;
        return Ok(());
    }
    println!(
        "{} ({}): {} {}, {segments} segments ({curved} curved), {joins} joins",
        file.display(),
        outlines.kind,
        checked.len(),
        if outlines.kind == "font" {
            "glyphs"
        } else {
            "paths"
        }
    );
    println!(
        "  curvature monotone: {monotone} of {segments} segments ({} not, or flagged); {inflections} inflection(s) inside segments",
        segments - monotone
    );
    println!(
        "  proofs: every verdict exact for the file's coordinates; {exact} of {segments} needed exact integer arithmetic ({:.2} %); {retracted} segment(s) with retracted handles",
        if segments > 0 { 100.0 * exact as f64 / segments as f64 } else { 0.0 }
    );
    println!(
        "  joins: {g1} G1 (of which {g2} G2), {near} near-breaks (above G1{} and under 3°: probably meant smooth)",
        if opts.grid > 0.0 { " and the integer grid's rounding" } else { "" }
    );
    if !outlines.unreadable.is_empty() {
        println!("  unreadable: {}", outlines.unreadable.len());
        for (n, e) in outlines.unreadable.iter().take(5) {
            println!("    {n}: {e}");
        }
    }
    if let Some(t) = suggest {
        println!(
            "  suggestions: {suggested} cubics become monotone by their handle lengths alone, moving at most {t}"
        );
    }
    println!("  read in {read_ms:.1} ms, checked in {check_ms:.1} ms");
    if !ranked.is_empty() {
        println!(
            "most worth a look ({} of {}):",
            top.min(ranked.len()),
            ranked.len()
        );
        for (n, f) in ranked.iter().take(top) {
            println!(
                "  {n}, contour {}, segment {} at ({:.1}, {:.1}): {}",
                f.contour, f.segment, f.point.x, f.point.y, f.message
            );
        }
    }
    Ok(())
}

/// A JSON array written element by element (none of them held beyond its own writing).
fn write_array(
    w: &mut impl std::io::Write,
    items: impl Iterator<Item = Value>,
) -> std::io::Result<()> {
    w.write_all(b"[")?;
    for (i, v) in items.enumerate() {
        if i > 0 {
            w.write_all(b",")?;
        }
        serde_json::to_writer(&mut *w, &v)?;
    }
    w.write_all(b"]")
}
