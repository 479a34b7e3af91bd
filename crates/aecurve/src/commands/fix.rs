//! `aecurve fix INPUT -o OUTPUT`: a UFO's, a designspace's masters' or an SVG file's smooth
//! joins harmonized and the file written back (`aecurve::fix`), with a summary or every
//! change as JSON.

use crate::commands::Command;
use aecurve::atomic_out::{write_new, Staging};
use aecurve::fix::masters::fix_designspace;
use aecurve::fix::{figures, fix_ufo, ContourFix, FixCounts, FixOptions};
use aecurve::protocol::fix_file::{
    ContourFixJson, FixDesignspaceResult, FixFileResult, FixHead, MasterFixJson,
};
use anyhow::{Context, Result};
use std::path::Path;
use std::path::PathBuf;

pub(crate) fn fix(
    input: &Path,
    output: &Path,
    opts: FixOptions,
    (json, report): (bool, Option<&Path>),
    overwrite: bool,
) -> Result<()> {
    let (tolerance, grid) = (opts.tolerance, opts.grid);
    anyhow::ensure!(
        tolerance.is_finite() && tolerance >= 0.0,
        "--tolerance must be a distance >= 0 (font units)"
    );
    anyhow::ensure!(
        grid.is_finite() && grid >= 0.0,
        "--grid must be a step >= 0 (0: none)"
    );
    let kind = Kind::of(input)?;
    // The report page is staged too (checked before the work, moved in after the output).
    let report = match report {
        Some(page) => Some((page, Staging::new(page, overwrite, &[input, output])?)),
        None => None,
    };
    let head = FixHead::new(input, output, &opts);
    if kind == Kind::Designspace {
        let d = fix_designspace(input, output, &opts, overwrite)?;
        if let Some((page, staging)) = report {
            let mut all = Vec::new();
            let mut total = 0;
            for m in &d.masters {
                let (f, n) = figures(&m.fixes, &format!("{}: ", m.filename), REPORT_FIGURES);
                all.extend(f);
                total += n;
            }
            write_report((page, staging), input, true, &all, total)?;
        }
        if json {
            let masters = (d.masters.iter())
                .map(|m| MasterFixJson {
                    source: m.filename.clone(),
                    counts: (&m.counts).into(),
                    contours: m.fixes.iter().map(ContourFixJson::from).collect(),
                })
                .collect();
            let out = FixDesignspaceResult {
                head,
                masters,
                compatible_contours: d.compatible_contours,
                restored_segments: d.restored_segments,
            };
            println!("{}", serde_json::to_string(&out)?);
            return Ok(());
        }
        println!(
            "wrote {} and its {} masters",
            output.display(),
            d.masters.len()
        );
        for m in &d.masters {
            println!("master {}:", m.filename);
            summary(&m.fixes, &m.counts, (tolerance, grid));
        }
        println!(
            "  {} contours with the same structure in every master held together: {} segments \
             given back in every master where an instance half way between two masters (or a \
             master) ended worse",
            d.compatible_contours, d.restored_segments
        );
        return Ok(());
    }
    let (fixes, c) = if kind == Kind::Svg {
        aecurve::fix::fix_svg(input, output, &opts, overwrite)?
    } else {
        fix_ufo(input, output, &opts, overwrite)?
    };
    if let Some((page, staging)) = report {
        let (f, n) = figures(&fixes, "", REPORT_FIGURES);
        write_report((page, staging), input, kind != Kind::Svg, &f, n)?;
    }
    if json {
        let out = FixFileResult::new(head, &fixes, &c);
        println!("{}", serde_json::to_string(&out)?);
        return Ok(());
    }
    println!("wrote {}", output.display());
    summary(&fixes, &c, (tolerance, grid));
    Ok(())
}

/// Most figures on the `--report` page (per master in a designspace).
const REPORT_FIGURES: usize = 80;

fn write_report(
    (page, staging): (&Path, Staging),
    input: &Path,
    y_up: bool,
    figures: &[aecurve::fix::report::FixFigure],
    total: usize,
) -> Result<()> {
    let title = format!("aecurve fix: {}", input.display());
    let html = aecurve::fix::report::fix_report(&title, y_up, figures, total);
    write_new(&staging.output()?, html.as_bytes(), None)
        .with_context(|| format!("writing the report {}", page.display()))?;
    staging.commit()
}

/// What `fix` reads.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    Ufo,
    Svg,
    Designspace,
}

impl Kind {
    fn of(input: &Path) -> Result<Kind> {
        let ext = |e: &str| input.extension().is_some_and(|x| x.eq_ignore_ascii_case(e));
        if ext("svg") {
            Ok(Kind::Svg)
        } else if ext("designspace") {
            Ok(Kind::Designspace)
        } else if ext("ufo") && input.is_dir() {
            Ok(Kind::Ufo)
        } else {
            anyhow::bail!(
                "{}: fix reads UFO sources (a .ufo folder), designspaces and SVG files",
                input.display()
            )
        }
    }
}

/// The summary of one file's (or master's) fix.
fn summary(fixes: &[ContourFix], c: &FixCounts, (tolerance, grid): (f64, f64)) {
    let pct = |k: usize| 100.0 * k as f64 / c.smooth_cubic_joins.max(1) as f64;
    println!(
        "  {} smooth joins between cubics: {} ({:.1} %) under a 1 % curvature jump before, {} ({:.1} %) after",
        c.smooth_cubic_joins,
        c.under_1_percent.0,
        pct(c.under_1_percent.0),
        c.under_1_percent.1,
        pct(c.under_1_percent.1)
    );
    println!(
        "  {} joins worse, {} cubics with more curvature extrema (the exact test); {} segments changed, no outline moved more than {:.3} (tolerance {tolerance}, grid {grid})",
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
}

/// The arguments of `aecurve fix` (the command's help is its entry in `cli.rs`).
#[derive(clap::Args)]
pub(crate) struct Args {
    /// The UFO source (a .ufo folder), a .designspace file, or an SVG file.
    input: PathBuf,
    /// Where to write the result (a new .ufo folder, .svg file, or .designspace file:
    /// its masters are written beside it at the same relative paths). It appears complete
    /// or not at all; nothing is written anywhere else.
    #[arg(short, long)]
    output: PathBuf,
    /// How far the outline may move (font units): every segment's shape within this of
    /// the original's (every point of each within this of the other; a sound bound of
    /// their Fréchet distance). On-curve points move at most this much; a handle may move
    /// further (it pulls its cubic by a fraction of its own move, and mostly along the
    /// curve when it slides along its tangent).
    #[arg(long, default_value_t = 2.0)]
    tolerance: f64,
    /// The coordinates' grid (default 1 for a UFO: integer font units; for an SVG
    /// 0.0001 user units, the precision moved numbers are written with).
    #[arg(long)]
    grid: Option<f64>,
    /// Leave curvature hooks and extra extrema alone (by default each cubic with a hook
    /// within 5 % of an end, or several extrema, gets monotone handle lengths first where
    /// they exist within the tolerance).
    #[arg(long)]
    no_bumps: bool,
    /// Leave the smooth joins alone (only the bumps).
    #[arg(long)]
    no_harmonize: bool,
    /// Also move the on-curve point of a smooth join along the line of its two handles
    /// (the handles stay, so the curvature elsewhere does not change; within the
    /// tolerance).
    #[arg(long)]
    move_points: bool,
    /// Replace what exists at the output (and the report's) path: the previous output is
    /// swapped for the new one in one step when the new one is complete. Without it, an
    /// existing output is refused.
    #[arg(long)]
    overwrite: bool,
    /// Stop starting contours after this many seconds: those not begun are left as they
    /// are and listed, and the output is written with the rest (a contour begun finishes:
    /// each takes a few seconds at most).
    #[arg(long, value_name = "SECONDS")]
    timeout: Option<f64>,
    /// Print every change as JSON instead of the summary.
    #[arg(long)]
    json: bool,
    /// Also write an HTML page of the changed glyphs or paths, before and after side by
    /// side with their curvature combs and the moved points marked.
    #[arg(long, value_name = "HTML")]
    report: Option<PathBuf>,
}

impl Command for Args {
    fn outputs(&self) -> Vec<&Path> {
        // The output's folder is made by `fix` itself (a UFO folder is refused when it exists).
        Vec::new()
    }

    fn run(self) -> Result<()> {
        anyhow::ensure!(
            self.timeout.is_none_or(|t| t.is_finite() && t > 0.0),
            "--timeout must be a number of seconds > 0"
        );
        let opts = FixOptions {
            tolerance: self.tolerance,
            grid: self
                .grid
                .unwrap_or(if is_svg(&self.input) { 1e-4 } else { 1.0 }),
            move_points: self.move_points,
            repairs: aesthetic_curves::harmonize::Repairs {
                bumps: !self.no_bumps,
                harmonize: !self.no_harmonize,
                ..Default::default()
            },
            deadline: self
                .timeout
                .map(|t| std::time::Instant::now() + std::time::Duration::from_secs_f64(t)),
        };
        fix(
            &self.input,
            &self.output,
            opts,
            (self.json, self.report.as_deref()),
            self.overwrite,
        )
    }
}

/// Whether a path names an SVG file (by its extension).
fn is_svg(p: &Path) -> bool {
    p.extension().is_some_and(|e| e.eq_ignore_ascii_case("svg"))
}
