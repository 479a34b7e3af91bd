//! One file per command of `aecurve` (the `clap` types are in `cli.rs`, the dispatch in
//! `main.rs`), and the output helpers they share.

pub(crate) mod approx;
pub(crate) mod demo;
pub(crate) mod lac;
pub(crate) mod lcg;
pub(crate) mod monotone;
pub(crate) mod sketch;
pub(crate) mod spline;

use aecurve::plot;
use anyhow::Result;
use std::path::PathBuf;

/// Where `--curvature-plot` writes, if given.
pub(crate) static CURVATURE_PLOT: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();

/// `--curvature-plot`: curvature against arc length (chord sums of the samples) of a curve.
pub(crate) fn write_curvature_plot(samples: &[plot::CombSample], title: &str) -> Result<()> {
    let Some(path) = CURVATURE_PLOT.get() else {
        return Ok(());
    };
    let mut s = 0.0;
    let mut pts = Vec::with_capacity(samples.len());
    for (i, (p, _, k)) in samples.iter().enumerate() {
        if i > 0 {
            s += (*p - samples[i - 1].0).hypot();
        }
        if k.is_finite() {
            pts.push((s, *k));
        }
    }
    let mut series = plot::Series::new("curvature", pts, plot::PALETTE[0]);
    series.markers = false;
    plot::write_picture(
        path,
        &plot::fitted_chart(
            title,
            "arc length (input units)",
            "curvature (1 / input unit)",
            &[series],
        ),
    )?;
    eprintln!("wrote {}", path.display());
    Ok(())
}
