//! `aecurve sketch`: pen input (CSV or SVG path) to a G2 curve of LAC pieces.

use crate::cli::CurveOutput;
use aecurve::plot;
use aesthetic_curves::Curve;
use anyhow::Result;

pub(crate) fn sketch(
    input: &std::path::Path,
    tolerance: Option<f64>,
    out: &CurveOutput,
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
    let nurbs = sk.as_curve().to_nurbs(0.0)?;
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
