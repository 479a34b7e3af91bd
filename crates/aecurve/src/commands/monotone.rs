//! `aecurve monotone`: the exact curvature-monotonicity test of a Bézier curve (and the
//! sampling test beside it), with plots and exports.

use crate::cli::count;
use crate::cli::CurveOutput;
use crate::commands::Command;
use aecurve::any_bezier::AnyBezier;
use aecurve::{parse_numbers, parse_points, plot};
use anyhow::{Context, Result};
use std::io::Write;

pub(crate) fn monotone(
    points: &str,
    weights: Option<&str>,
    method: Method,
    samples: usize,
    out_files: &CurveOutput,
) -> Result<()> {
    let json = out_files.json;
    let pts = parse_points(points).context("--points")?;
    let w = weights
        .map(parse_numbers)
        .transpose()
        .context("--weights")?;
    let curve = AnyBezier::new(pts.clone(), w.clone())?;
    let c = curve.as_monotone();
    let kind = if w.is_some() {
        "rational"
    } else {
        "polynomial"
    };
    let degree = pts.len() - 1;
    let mut out = std::io::stdout().lock();
    match method {
        Method::Exact => {
            let r = c.curvature_monotone()?;
            if json {
                writeln!(out, "{}", aecurve::protocol::monotone_json(&r))?;
            } else {
                writeln!(out, "{kind} Bézier curve of degree {degree}")?;
                let end = |e: &aesthetic_curves::monotone::EndCurvature| match e.value() {
                    Some(k) => format!("{k:.6}"),
                    None => "unbounded".to_string(),
                };
                writeln!(
                    out,
                    "curvature at the ends: {} (t = 0), {} (t = 1)",
                    end(&r.ends[0]),
                    end(&r.ends[1])
                )?;
                for (e, at) in r.ends.iter().zip(["t = 0", "t = 1"]) {
                    if let Some(d) = e.describe() {
                        writeln!(out, "  {at}: {d}")?;
                    }
                }
                if r.monotone {
                    let how = r.trend.map(|t| t.as_str()).unwrap_or("constant");
                    writeln!(out, "curvature is MONOTONE ({how})")?;
                } else {
                    writeln!(
                        out,
                        "curvature is NOT monotone: {} extrema",
                        r.extrema.len()
                    )?;
                    for t in &r.extrema {
                        let p = curve.eval(*t);
                        writeln!(
                            out,
                            "  extremum at t = {t:.9}: point ({:.6}, {:.6}), curvature {:.6}",
                            p.x,
                            p.y,
                            curve.kappa(*t)
                        )?;
                    }
                }
                writeln!(
                    out,
                    "proof: sign of dkappa/ds from a Bernstein polynomial of degree {}, {}",
                    r.test_degree,
                    if r.exact {
                        "decided in exact integer arithmetic (the floating-point filter could \
                         not: Sturm sequence and exact bisection)"
                    } else {
                        "decided by its coefficients with rigorous rounding bounds (convex \
                         hull + subdivision)"
                    }
                )?;
            }
        }
        Method::Sampling => {
            let r = c.curvature_monotone_sampled(samples)?;
            if json {
                writeln!(out, "{}", aecurve::protocol::sampled_json(&r))?;
            } else {
                writeln!(
                    out,
                    "sampling test, {} divisions: curvature {} (not a proof: extrema between \
                     samples go unseen)",
                    r.samples,
                    if r.monotone {
                        "looks monotone"
                    } else {
                        "is NOT monotone"
                    }
                )?;
            }
        }
    }
    let comb = plot::curve_samples(curve.as_curve(), 201)?;
    let caption = format!("{kind} Bézier curve of degree {degree}");
    let weights = w.clone().unwrap_or_else(|| vec![1.0; pts.len()]);
    out_files.write(
        "bezier",
        &mut || {
            let rb = aesthetic_curves::RationalBezier::new(pts.clone(), weights.clone())?;
            Ok(aesthetic_curves::nurbs::Nurbs::from_bezier(&rb))
        },
        &comb,
        &caption,
        &mut || {
            let extrema = match method {
                Method::Exact => c.curvature_monotone()?.extrema,
                Method::Sampling => Vec::new(),
            };
            Ok(plot::curve_with_comb(&curve, &pts, &extrema, &caption))
        },
    )?;
    Ok(())
}

/// The arguments of `aecurve monotone` (the command's help is its entry in `cli.rs`).
#[derive(clap::Args)]
pub(crate) struct Args {
    /// Control points: "x,y x,y ..." (2 to 21 points).
    #[arg(long, allow_hyphen_values = true)]
    points: String,
    /// Weights (rational curve): "w w w ...", one per point.
    #[arg(long)]
    weights: Option<String>,
    /// Which test.
    #[arg(long, value_enum, default_value_t = Method::Exact)]
    method: Method,
    /// Divisions of the sampling test (1 to 10,000,000).
    #[arg(long, default_value_t = 100, value_parser = count::<1, 10_000_000>)]
    samples: usize,
    #[command(flatten)]
    out: CurveOutput,
}

impl Command for Args {
    fn curve_output(&self) -> Option<&CurveOutput> {
        Some(&self.out)
    }

    fn run(self) -> Result<()> {
        monotone(
            &self.points,
            self.weights.as_deref(),
            self.method,
            self.samples,
            &self.out,
        )
    }
}

/// Which test `aecurve monotone` runs.
#[derive(Clone, Copy, clap::ValueEnum, PartialEq)]
pub(crate) enum Method {
    Exact,
    Sampling,
}
