//! `aecurve sketch`: pen input (CSV or SVG path) to a G2 curve of LAC pieces.

use crate::cli::positive;
use crate::cli::CurveOutput;
use crate::commands::Command;
use aecurve::plot;
use aesthetic_curves::Curve;
use anyhow::Result;
use std::path::PathBuf;

pub(crate) fn sketch(
    input: &std::path::Path,
    tolerance: Option<f64>,
    out: &CurveOutput,
) -> Result<()> {
    let pts = aecurve::read_points_file(input)?;
    if let Some(t) = tolerance {
        anyhow::ensure!(t.is_finite() && t > 0.0, "--tolerance must be positive");
    }
    let (sk, tol) = aesthetic_curves::sketch::fit_sketch_within(&pts, tolerance)?;
    if out.json {
        println!("{}", aecurve::protocol::sketch_json(&sk, tol));
    } else {
        let sum = aecurve::summary::sketch(&sk, tol, "input units");
        println!("sketch of {} points: {}", pts.len(), sum.headline);
        println!("  {}; {}", sum.details, sum.fairing);
        for [i, kind, alpha, k0, k1, monotone] in &sum.rows {
            println!(
                "  piece {i}: {kind:<14} alpha {alpha:>10}  curvature {k0} -> {k1}  monotone: {monotone}"
            );
        }
    }
    let nurbs = sk.as_curve().to_exact_nurbs()?;
    let comb = plot::curve_samples(&sk.as_curve(), 61)?;
    let caption = format!(
        "sketch: {} LAC pieces (rational cubics), deviation {:.3e}, jump {:.1e}",
        sk.pieces.len(),
        sk.max_deviation,
        sk.max_curvature_jump
    );
    out.write(
        "sketch",
        &mut || Ok(nurbs.clone()),
        &comb,
        &caption,
        &mut || Ok(plot::comb_svg(&comb, &pts, &sk.joints(), &caption)),
    )?;
    Ok(())
}

/// `aecurve sketch --contour`: the stroke as a contour of runs joined at corners.
pub(crate) fn sketch_contour(
    input: &std::path::Path,
    tolerance: Option<f64>,
    out: &CurveOutput,
) -> Result<()> {
    use aesthetic_curves::sketch::contour::{fit_contour, ContourOptions, Run};
    let pts = aecurve::read_points_file(input)?;
    let opts = ContourOptions {
        tolerance,
        ..Default::default()
    };
    let c = fit_contour(&pts, &opts)?;
    if out.json {
        println!("{}", aecurve::protocol::contour_json(&c));
    } else {
        let seam = match c.seam {
            Some(s) => format!(
                ", seam: {:.2e} deg, curvature jump {:.1e}",
                s.angle.to_degrees(),
                s.curvature_jump
            ),
            None => String::new(),
        };
        println!(
            "contour of {} points: {} runs, {} corners, {}{seam}; {} pieces, deviation {:.3e} (tolerance {:.3e})",
            pts.len(),
            c.runs.len(),
            c.corners.len(),
            if c.closed { "closed" } else { "open" },
            c.pieces(),
            c.max_deviation,
            c.tolerance
        );
        for (k, run) in c.runs.iter().enumerate() {
            let (a, b) = run.ends();
            let what = match run {
                Run::Line { .. } => "line".to_string(),
                Run::Curve(s) => format!(
                    "curve of {} LAC pieces, G2 {}",
                    s.pieces.len(),
                    if s.g2 { "yes" } else { "no" }
                ),
            };
            println!(
                "  run {k}: {what}, ({:.4}, {:.4}) -> ({:.4}, {:.4})",
                a.x, a.y, b.x, b.y
            );
        }
        for k in &c.corners {
            println!(
                "  corner at point {} ({:.4}, {:.4}): turns {:.1} deg",
                k.index,
                k.point.x,
                k.point.y,
                k.angle.to_degrees()
            );
        }
    }
    let curve = c.as_curve()?;
    let nurbs = curve.to_exact_nurbs()?;
    let comb = plot::curve_samples(&curve, 61)?;
    let caption = format!(
        "sketch contour: {} runs, {} corners, {} pieces, deviation {:.3e}",
        c.runs.len(),
        c.corners.len(),
        c.pieces(),
        c.max_deviation
    );
    let marks: Vec<aesthetic_curves::Point> = c.corners.iter().map(|k| k.point).collect();
    out.write(
        "sketch",
        &mut || Ok(nurbs.clone()),
        &comb,
        &caption,
        &mut || Ok(plot::comb_svg(&comb, &pts, &marks, &caption)),
    )?;
    Ok(())
}

/// The arguments of `aecurve sketch` (the command's help is its entry in `cli.rs`).
#[derive(clap::Args)]
pub(crate) struct Args {
    /// The points file.
    input: PathBuf,
    /// Largest distance from an input point to the result (default from the points: about
    /// twice a hand's jitter, 3 times the noise estimated from them; for points sampled from
    /// a curve 0.5 % of their bounding box's diagonal). A value inside the noise gets the
    /// fairest curve within it, or an error naming the smallest tolerance that has one.
    #[arg(long, allow_hyphen_values = true, value_parser = positive)]
    tolerance: Option<f64>,
    /// Take the stroke as a contour: corners found, straight runs as lines, a stroke
    /// that ends at its start closed (docs/math.md §6.1; the protocol's sketch.contour).
    #[arg(long)]
    contour: bool,
    #[command(flatten)]
    out: CurveOutput,
}

impl Command for Args {
    fn curve_output(&self) -> Option<&CurveOutput> {
        Some(&self.out)
    }

    fn run(self) -> Result<()> {
        if self.contour {
            sketch_contour(&self.input, self.tolerance, &self.out)
        } else {
            sketch(&self.input, self.tolerance, &self.out)
        }
    }
}
