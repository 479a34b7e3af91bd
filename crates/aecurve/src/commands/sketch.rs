//! `aecurve sketch`: pen input (CSV or SVG path) to a G2 curve of LAC pieces.

use crate::commands::{write_curvature_plot, write_curve_outputs};
use aecurve::plot;
use aesthetic_curves::Curve;
use anyhow::Result;
use std::path::PathBuf;

pub(crate) fn sketch(
    input: &std::path::Path,
    tolerance: Option<f64>,
    json: bool,
    output: &[PathBuf],
    curvature_plot: Option<&std::path::Path>,
) -> Result<()> {
    use aesthetic_curves::sketch::{fit_sketch, SketchOptions};
    let pts = aecurve::read_points_file(input)?;
    let tol = match tolerance {
        Some(t) => {
            anyhow::ensure!(t.is_finite() && t > 0.0, "--tolerance must be positive");
            t
        }
        None => aesthetic_curves::sketch::default_tolerance(&pts),
    };
    let sk = fit_sketch(&pts, &SketchOptions::with_tolerance(tol))?;
    if json {
        println!("{}", aecurve::protocol::sketch_json(&sk, tol));
    } else {
        println!(
            "sketch of {} points: {} pieces, deviation {:.4e} (tolerance {:.4e}), curvature jump {:.2e} ({}), {}",
            pts.len(),
            sk.pieces.len(),
            sk.max_deviation,
            tol,
            sk.max_curvature_jump,
            if sk.g2 { "G2" } else { "not G2" },
            if sk.all_monotone {
                "every piece curvature-monotone (exact test)"
            } else {
                "NOT every piece curvature-monotone"
            }
        );
        println!(
            "  {} inflections, {} curvature extrema; fairing: {} Newton iterations, jump {:.2e} -> {:.2e}",
            sk.inflections,
            sk.curvature_extrema,
            sk.fairing.iterations,
            sk.fairing.initial_jump,
            sk.fairing.final_jump
        );
        for (i, p) in sk.pieces.iter().enumerate() {
            println!(
                "  piece {i}: {:<14} alpha {:>8.4}{}  curvature {:+.4e} -> {:+.4e}  {}",
                p.kind.as_str(),
                p.alpha,
                if p.alpha_at_bound { " (bound)" } else { "" },
                p.end_curvatures.0,
                p.end_curvatures.1,
                if p.monotone {
                    "monotone"
                } else {
                    "not monotone"
                }
            );
        }
    }
    let nurbs = sk.as_curve().to_nurbs(0.0)?;
    let comb = plot::curve_samples(&sk.as_curve(), 61)?;
    write_curvature_plot(
        curvature_plot,
        &comb,
        "curvature of the G2 curve (rational cubic pieces)",
    )?;
    let caption = format!(
        "sketch: {} LAC pieces (rational cubics), deviation {:.3e}, jump {:.1e}",
        sk.pieces.len(),
        sk.max_deviation,
        sk.max_curvature_jump
    );
    write_curve_outputs(
        output,
        "sketch",
        &mut || Ok(nurbs.clone()),
        &comb,
        &caption,
        &mut || Ok(plot::comb_svg(&comb, &pts, &sk.joints(), &caption)),
    )?;
    Ok(())
}
