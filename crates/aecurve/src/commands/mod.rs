//! One file per command of `aecurve`: its arguments (a `clap::Args` struct named `Args`),
//! its [`Command`] impl and its work. The list of commands, their help and the dispatch are
//! `cli.rs`'s `commands!` table; the output helpers the commands share are here.

pub(crate) mod approx;
pub(crate) mod batch;
pub(crate) mod bench;
pub(crate) mod check;
pub(crate) mod demo;
pub(crate) mod editor;
pub(crate) mod fix;
pub(crate) mod lac;
pub(crate) mod lcg;
pub(crate) mod monotone;
pub(crate) mod schema;
pub(crate) mod sketch;
pub(crate) mod spline;

/// One command: what it will write, a check of that before any work, and the work.
pub(crate) trait Command {
    /// The curve outputs of a command that makes one curve (`--json`, `-o`,
    /// `--curvature-plot`).
    fn curve_output(&self) -> Option<&crate::cli::CurveOutput> {
        None
    }

    /// The other pictures it will write (.svg or .png: a graph, a map, a chart).
    fn pictures(&self) -> &[PathBuf] {
        &[]
    }

    /// Every file path it will write (its curve outputs, then its pictures; a command that
    /// writes something else says so here): `main` makes their folders before it runs.
    fn outputs(&self) -> Vec<&Path> {
        let curve = self.curve_output().into_iter().flat_map(|o| o.paths());
        curve
            .chain(self.pictures().iter().map(PathBuf::as_path))
            .collect()
    }

    /// Refuses an output it could not write (an unknown CAD or picture format) before any
    /// work.
    fn check(&self) -> Result<()> {
        if let Some(o) = self.curve_output() {
            o.check()?;
        }
        plot::check_picture_paths(self.pictures())
    }

    /// Does the command's work.
    fn run(self) -> Result<()>;
}

use aecurve::plot;
use anyhow::Result;
use std::path::{Path, PathBuf};

/// `--control`: the three points of a control triangle, "x,y x,y x,y".
pub(crate) fn control_triangle(control: &str) -> Result<[aesthetic_curves::Point; 3]> {
    use anyhow::Context;
    let pts = aecurve::parse_points(control).context("--control")?;
    anyhow::ensure!(
        pts.len() == 3,
        "--control needs exactly 3 points, got {}",
        pts.len()
    );
    Ok([pts[0], pts[1], pts[2]])
}

impl crate::cli::CurveOutput {
    /// Every file this will write.
    pub(crate) fn paths(&self) -> impl Iterator<Item = &Path> {
        self.output
            .iter()
            .chain(self.curvature_plot.iter())
            .map(PathBuf::as_path)
    }

    /// Refuses an unknown format before any work: `-o` takes a CAD format, .svg or .png;
    /// `--curvature-plot` a picture.
    pub(crate) fn check(&self) -> Result<()> {
        plot::check_picture_paths(self.curvature_plot.as_slice())?;
        for p in &self.output {
            let ext = aecurve::export::extension(p).unwrap_or_default();
            if !aecurve::export::CURVE_FORMATS.contains(&ext.as_str())
                && plot::check_picture_paths(std::slice::from_ref(p)).is_err()
            {
                anyhow::bail!(
                    "{}: unknown format (use .svg, .png, .{})",
                    p.display(),
                    aecurve::export::CURVE_FORMATS.join(", .")
                );
            }
        }
        Ok(())
    }

    /// Writes `--curvature-plot` (curvature against arc length, chord sums of the comb's
    /// samples, titled `caption`) and every `-o`, by its extension: the CAD formats
    /// ([`aecurve::export::CURVE_FORMATS`]) get the curve as the entity `entity`; SVG gets
    /// the curve itself (cubic Béziers within 1e-6 of its size, in its own coordinates) with
    /// its curvature comb; a PNG gets `picture()`, an SVG drawing. The curve is built once,
    /// on first need (some commands approximate it for CAD).
    pub(crate) fn write(
        &self,
        entity: &str,
        curve: &mut dyn FnMut() -> Result<aesthetic_curves::nurbs::Nurbs>,
        comb: &[plot::CombSample],
        caption: &str,
        picture: &mut dyn FnMut() -> Result<String>,
    ) -> Result<()> {
        use anyhow::Context;
        if let Some(path) = &self.curvature_plot {
            write_curvature_plot(path, comb, caption)?;
        }
        let mut built = None;
        for path in &self.output {
            let ext = aecurve::export::extension(path).unwrap_or_default();
            if ext == "svg" || aecurve::export::CURVE_FORMATS.contains(&ext.as_str()) {
                if built.is_none() {
                    built = Some(curve()?);
                }
                let c = built.as_ref().expect("built above");
                if ext == "svg" {
                    let doc = aecurve::export::svg_document(c, 1e-6 * c.size(), comb, caption)
                        .context("the curve has no Bézier spans")?;
                    std::fs::write(path, doc)
                        .with_context(|| format!("writing {}", path.display()))?;
                } else {
                    aecurve::export::write_curve(path, c, entity)?;
                }
            } else {
                plot::write_picture(path, &picture()?)?;
            }
            eprintln!("wrote {}", path.display());
        }
        Ok(())
    }
}

/// Curvature against arc length (chord sums of the samples) of a curve.
fn write_curvature_plot(path: &Path, samples: &[plot::CombSample], title: &str) -> Result<()> {
    let pts = plot::curvature_series(samples);
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
