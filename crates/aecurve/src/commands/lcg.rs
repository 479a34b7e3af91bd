//! `aecurve lcg`: the logarithmic curvature graph and alpha of samples or of a segment.

use crate::commands::{control_triangle, Command};
use aecurve::any_bezier::AnyBezier;
use aecurve::plot;
use aecurve::{parse_numbers, parse_points};
use anyhow::Context;
use anyhow::Result;
use std::path::PathBuf;

pub(crate) enum LcgSource {
    Points(Vec<aesthetic_curves::Point>),
    Bezier(AnyBezier),
    Lac(aesthetic_curves::lac::LacSegment),
}

pub(crate) fn lcg(source: LcgSource, json: bool, output: &[PathBuf]) -> Result<()> {
    use aesthetic_curves::lcg;
    let (what, fit) = match &source {
        LcgSource::Points(p) => (
            format!("{} sampled points", p.len()),
            lcg::estimate_from_points(p)?,
        ),
        LcgSource::Bezier(b) => (
            "the Bézier curve (analytic)".to_string(),
            lcg::fit_line(lcg::curve_lcg(b.as_monotone(), 81))?,
        ),
        LcgSource::Lac(seg) => (
            format!("the LAC segment, alpha = {}", seg.standard().alpha()),
            lcg::fit_line(seg.lcg(81)?)?,
        ),
    };
    if json {
        println!("{}", aecurve::protocol::lcg_json(&fit));
    } else {
        println!("logarithmic curvature graph of {what}");
        println!("  alpha (slope)  {:.9}", fit.alpha);
        println!("  intercept      {:.9}", fit.intercept);
        println!("  r squared      {:.12}", fit.r_squared);
        println!("  rms residual   {:.3e}", fit.rms_residual);
        println!("  graph points   {}", fit.graph.len());
    }
    for path in output {
        plot::write_picture(path, &plot::lcg_chart(&fit, &format!("LCG of {what}")))?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

/// The arguments of `aecurve lcg` (the command's help is its entry in `cli.rs`).
#[derive(clap::Args)]
pub(crate) struct Args {
    /// Ordered points "x,y x,y ..." (at least 8).
    #[arg(long, allow_hyphen_values = true, group = "source")]
    points: Option<String>,
    /// File of ordered points: CSV / whitespace rows "x,y", or a JSON array of pairs.
    #[arg(long, group = "source")]
    input: Option<PathBuf>,
    /// Control points of a Bézier curve "x,y x,y ...".
    #[arg(long, allow_hyphen_values = true, group = "source")]
    bezier: Option<String>,
    /// Weights of the Bézier curve (rational).
    #[arg(long, requires = "bezier")]
    weights: Option<String>,
    /// Control triangle of a LAC segment (with --alpha).
    #[arg(long, allow_hyphen_values = true, group = "source", requires = "alpha")]
    control: Option<String>,
    /// Alpha of the LAC segment.
    #[arg(long, allow_hyphen_values = true, requires = "control")]
    alpha: Option<f64>,
    /// Print the protocol's JSON result.
    #[arg(long)]
    json: bool,
    /// Write the graph with its fitted line (.svg or .png; repeatable).
    #[arg(short, long)]
    output: Vec<PathBuf>,
}

impl Command for Args {
    fn pictures(&self) -> &[PathBuf] {
        &self.output
    }

    fn run(self) -> Result<()> {
        let source = match (self.points, self.input, self.bezier, self.control) {
            (Some(p), _, _, _) => LcgSource::Points(parse_points(&p).context("--points")?),
            (_, Some(f), _, _) => LcgSource::Points(aecurve::read_points_file(&f)?),
            (_, _, Some(b), _) => {
                let w = self
                    .weights
                    .as_deref()
                    .map(parse_numbers)
                    .transpose()
                    .context("--weights")?;
                LcgSource::Bezier(AnyBezier::new(parse_points(&b).context("--bezier")?, w)?)
            }
            (_, _, _, Some(c)) => {
                let pts = control_triangle(&c)?;
                let a = self.alpha.context("--alpha is needed with --control")?;
                LcgSource::Lac(aesthetic_curves::lac::LacSegment::new(a, pts)?)
            }
            _ => anyhow::bail!("give --points, --input, --bezier or --alpha with --control"),
        };
        lcg(source, self.json, &self.output)
    }
}
