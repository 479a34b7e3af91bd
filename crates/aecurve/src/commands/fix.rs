//! `aecurve fix INPUT.ufo -o OUTPUT.ufo`: the UFO's smooth joins harmonized and the source
//! written back (`aecurve::fix`), with a summary or every change as JSON.

use aecurve::fix::{fix_json, fix_ufo, FixOptions};
use anyhow::Result;
use std::path::Path;

pub(crate) fn fix(input: &Path, output: &Path, opts: FixOptions, json: bool) -> Result<()> {
    let (tolerance, grid) = (opts.tolerance, opts.grid);
    anyhow::ensure!(
        tolerance.is_finite() && tolerance >= 0.0,
        "--tolerance must be a distance >= 0 (font units)"
    );
    anyhow::ensure!(
        grid.is_finite() && grid >= 0.0,
        "--grid must be a step >= 0 (0: none)"
    );
    let svg = input
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("svg"));
    let ufo = input.is_dir()
        && input
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("ufo"));
    anyhow::ensure!(
        svg || ufo,
        "{}: fix reads UFO sources (a .ufo folder) and SVG files; designspaces are not done yet",
        input.display()
    );
    anyhow::ensure!(
        !output.exists(),
        "{}: already exists; fix writes a new folder and never replaces one",
        output.display()
    );
    if let Some(parent) = output.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent)
            .map_err(|e| anyhow::anyhow!("creating {}: {e}", parent.display()))?;
    }
    let (fixes, c) = if svg {
        aecurve::fix::fix_svg(input, output, &opts)?
    } else {
        fix_ufo(input, output, &opts)?
    };
    if json {
        let changes: Vec<_> = fixes.iter().map(fix_json).collect();
        let out = serde_json::json!({
            "input": input.display().to_string(), "output": output.display().to_string(),
            "tolerance": tolerance, "grid": grid, "move_points": opts.move_points,
            "counts": {
                "smooth_cubic_joins": c.smooth_cubic_joins,
                "under_1_percent_before": c.under_1_percent.0,
                "under_1_percent_after": c.under_1_percent.1,
                "worse_joins": c.worse, "cubics_with_more_extrema": c.gained_extrema,
                "changed_segments": c.changed_segments, "max_moved": c.max_moved,
                "skipped_contours": c.skipped_contours,
                "bumps_before": c.bumps.0, "bumps_after": c.bumps.1,
            },
            "contours": changes,
        });
        println!("{out}");
        return Ok(());
    }
    let pct = |k: usize| 100.0 * k as f64 / c.smooth_cubic_joins.max(1) as f64;
    println!("wrote {}", output.display());
    println!(
        "  {} smooth joins between cubics: {} ({:.1} %) under a 1 % curvature jump before, {} ({:.1} %) after",
        c.smooth_cubic_joins,
        c.under_1_percent.0,
        pct(c.under_1_percent.0),
        c.under_1_percent.1,
        pct(c.under_1_percent.1)
    );
    println!(
        "  {} joins worse, {} cubics with more curvature extrema (the exact test); {} segments changed, no point moved more than {:.3} (tolerance {tolerance}, grid {grid})",
        c.worse, c.gained_extrema, c.changed_segments, c.max_moved
    );
    println!(
        "  {} cubics with a curvature hook at an end or several extrema before, {} after",
        c.bumps.0, c.bumps.1
    );
    if c.skipped_contours > 0 {
        println!("  {} contours left as they are:", c.skipped_contours);
        for f in fixes.iter().filter(|f| f.result.is_err()).take(5) {
            if let Err(why) = &f.result {
                println!("    {}, contour {}: {why}", f.glyph, f.contour);
            }
        }
    }
    Ok(())
}
