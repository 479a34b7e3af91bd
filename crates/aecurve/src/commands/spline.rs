//! `aecurve spline`: the G2 log-aesthetic spline through points (`--kind lac`) and S2's
//! pseudo-elastic spline (`--kind pseudo-elastic`, G1).

use crate::cli::CurveOutput;
use crate::commands::Command;
use aecurve::plot;
use aesthetic_curves::Curve;
use anyhow::Result;
use std::path::PathBuf;

pub(crate) fn spline(
    input: &std::path::Path,
    closed: bool,
    mode: &str,
    out: &CurveOutput,
) -> Result<()> {
    let pts = aecurve::read_points_file(input)?;
    // The command line writes files, not a JSON answer in memory: table mode takes up to a
    // million points here (the protocol's request limit is lower).
    let max = if mode == "exact" {
        aecurve::protocol::MAX_EXACT_SPLINE_POINTS
    } else {
        1_000_000
    };
    anyhow::ensure!(
        pts.len() <= max,
        "at most {max} points in {mode} mode, got {}",
        pts.len()
    );
    let m = aesthetic_curves::pseudo_spline::Mode::from_name(mode)?;
    let s = aesthetic_curves::pseudo_spline::pseudo_elastic(&pts, closed, m)?;
    let r = &aecurve::protocol::spline_json(&s, m.into());
    if out.json {
        println!("{r}");
    } else {
        println!(
            "pseudo-elastic spline through {} points ({}), {mode} mode",
            pts.len(),
            if closed { "closed" } else { "open" }
        );
        println!("  length   {:.9}", r.length);
        println!(
            "  area     {:.9} ({})",
            r.area,
            if closed {
                "enclosed"
            } else {
                "between the curve and the chord of its ends"
            }
        );
        println!("  energy   {:.9} (sum of l_i J_i)", r.energy);
    }
    let caption = format!("pseudo-elastic spline: length {:.6}", s.length);
    write_spline(
        out,
        "pseudo_elastic_spline",
        &s.as_curve()?,
        &pts,
        closed,
        &caption,
    )
}

/// The `-o` files and `--curvature-plot` of a spline through `pts`: the curve, its comb and
/// the points (joined back to the first when `closed`).
fn write_spline(
    out: &CurveOutput,
    entity: &str,
    curve: &dyn Curve,
    pts: &[aesthetic_curves::Point],
    closed: bool,
    caption: &str,
) -> Result<()> {
    if out.paths().next().is_none() {
        return Ok(());
    }
    let samples = plot::curve_samples(curve, 41)?;
    let mut polygon = pts.to_vec();
    if closed {
        polygon.push(pts[0]);
    }
    let nurbs = curve.to_exact_nurbs()?;
    out.write(
        entity,
        &mut || Ok(nurbs.clone()),
        &samples,
        caption,
        &mut || Ok(plot::comb_svg(&samples, &polygon, &[], caption)),
    )
}

/// `aecurve spline --kind lac`: the G2 log-aesthetic spline through the points of a file.
pub(crate) fn lac_spline(
    input: &std::path::Path,
    opts: &aesthetic_curves::lac_spline::LacSplineOptions,
    out: &CurveOutput,
) -> Result<()> {
    let pts = aecurve::read_points_file(input)?;
    let max = aecurve::protocol::MAX_LAC_SPLINE_POINTS;
    anyhow::ensure!(
        pts.len() <= max,
        "at most {max} points for the log-aesthetic spline, got {}",
        pts.len()
    );
    let s = aesthetic_curves::lac_spline::lac_spline(&pts, opts)?;
    if out.json {
        println!("{}", aecurve::protocol::lac_spline_json(&s));
    } else {
        print_lac_spline(&s, pts.len(), opts);
    }
    let caption = format!(
        "log-aesthetic spline, alpha {}: {} pieces, G2 to {:.1e}",
        opts.alpha,
        s.pieces.len(),
        s.max_cubic_jump
    );
    write_spline(
        out,
        "lac_spline",
        &s.rationals(),
        &pts,
        opts.closed,
        &caption,
    )
}

fn print_lac_spline(
    s: &aesthetic_curves::lac_spline::LacSpline,
    n: usize,
    opts: &aesthetic_curves::lac_spline::LacSplineOptions,
) {
    println!(
        "log-aesthetic spline through {n} points ({}), alpha {}{}",
        if opts.closed { "closed" } else { "open" },
        opts.alpha,
        if opts.corners.is_empty() {
            String::new()
        } else {
            format!(", corners at {:?}", opts.corners)
        }
    );
    println!(
        "  pieces        {} ({} lines, {} inflection halves)",
        s.pieces.len(),
        s.pieces
            .iter()
            .filter(|p| p.kind.as_str() == "line")
            .count(),
        s.pieces
            .iter()
            .filter(|p| p.kind.as_str() == "lac_inflection")
            .count()
    );
    println!(
        "  G2            curvature jump {:.2e} of the largest (segments), {:.2e} (cubics), \
         in {} Newton steps",
        s.max_curvature_jump, s.max_cubic_jump, s.iterations
    );
    println!(
        "  monotone      {} (every cubic by the exact test); largest cubic error {:.2e}",
        if s.all_monotone { "proven" } else { "NOT all" },
        s.max_rational_error
    );
    println!(
        "  events        {} inflections, {} curvature extrema",
        s.inflections, s.curvature_extrema
    );
}

/// The arguments of `aecurve spline` (the command's help is its entry in `cli.rs`).
#[derive(clap::Args)]
pub(crate) struct Args {
    /// The points file.
    input: PathBuf,
    /// Closed curve through all points.
    #[arg(long)]
    closed: bool,
    /// Which spline: the G2 log-aesthetic one or S2's pseudo-elastic (G1) one.
    #[arg(long, default_value = "lac", value_parser = ["lac", "pseudo-elastic"])]
    kind: String,
    /// Alpha of the log-aesthetic spline's pieces (-1: clothoids; within ±1000).
    #[arg(long, default_value_t = -1.0, allow_hyphen_values = true)]
    alpha: f64,
    /// Corner points of the log-aesthetic spline, by index ("0,4").
    #[arg(long, value_delimiter = ',')]
    corners: Vec<usize>,
    /// Pseudo-elastic segment values from the shipped tables (fast) or by direct
    /// minimisation.
    #[arg(long, default_value = "table", value_parser = ["table", "exact"])]
    mode: String,
    #[command(flatten)]
    out: CurveOutput,
}

impl Command for Args {
    fn curve_output(&self) -> Option<&CurveOutput> {
        Some(&self.out)
    }

    fn run(self) -> Result<()> {
        if self.kind == "lac" {
            let opts = aesthetic_curves::lac_spline::LacSplineOptions {
                alpha: self.alpha,
                closed: self.closed,
                corners: self.corners,
                ..Default::default()
            };
            lac_spline(&self.input, &opts, &self.out)
        } else {
            spline(&self.input, self.closed, &self.mode, &self.out)
        }
    }
}
