//! `aecurve approx`: one rational cubic (or a G2 rational spline within a tolerance) per
//! LAC segment, with the S3 error map.

use crate::cli::CurveOutput;
use crate::cli::{count, positive};
use crate::commands::control_triangle;
use crate::commands::Command;
use aecurve::plot;
use aesthetic_curves::curve::MAX_NURBS_PIECES;
use anyhow::Result;
use std::path::PathBuf;

pub(crate) fn approx(
    alpha: f64,
    control: &str,
    tolerance: Option<f64>,
    out: &CurveOutput,
    map: Option<&std::path::Path>,
    map_cells: usize,
) -> Result<()> {
    use aesthetic_curves::approx;
    let pts = control_triangle(control)?;
    anyhow::ensure!(
        (2..=1000).contains(&map_cells),
        "--map-cells must be 2 to 1000"
    );
    // Library errors keep the protocol's kind in the message (`no_segment: ...`).
    let kinded = |e: aesthetic_curves::Error| anyhow::anyhow!("{}: {}", e.kind(), e.message());
    let seg =
        aesthetic_curves::lac::LacSegment::new(alpha, [pts[0], pts[1], pts[2]]).map_err(kinded)?;
    let opts = approx::ApproxOptions::default();
    let fit = approx::fit_rational_cubic(&seg, &opts).map_err(kinded)?;
    let spline = tolerance
        .map(|t| approx::fit_rational_spline(&seg, t, MAX_NURBS_PIECES, &opts))
        .transpose()
        .map_err(kinded)?;
    let r = &aecurve::protocol::rational_approx_json(&seg, &fit, spline.as_ref())?;
    if out.json {
        println!("{r}");
    } else {
        let len = seg.arc_length()?;
        println!("rational cubic for the LAC segment alpha = {alpha}");
        println!("  turning angle   {:.6} deg", seg.theta_d().to_degrees());
        println!("  f0, f1          {:.9}, {:.9}", fit.f0, fit.f1);
        for (i, (p, w)) in fit
            .curve
            .points()
            .iter()
            .zip(fit.curve.weights())
            .enumerate()
        {
            println!("  b{i} = ({:.12}, {:.12})  w{i} = {w:.12}", p.x, p.y);
        }
        println!(
            "  error           rms {:.3e}, max {:.3e} of the arc length ({:.3e}, {:.3e} in input units)",
            fit.rms,
            fit.max_error,
            fit.rms * len,
            fit.max_error * len
        );
        println!("  curvature       monotone (exact test), G2 at both ends");
        if let Some(sp) = &r.spline {
            println!(
                "  spline          {} piece(s) within {:e}: max error {:.3e}",
                sp.pieces,
                tolerance.unwrap_or(0.0),
                sp.max_error
            );
        }
    }
    let nurbs = match &spline {
        Some(sp) => sp.nurbs.clone(),
        None => aesthetic_curves::nurbs::Nurbs::from_bezier(&fit.curve),
    };
    let pieces = nurbs.as_curve()?;
    let comb = plot::curve_samples(&pieces, (200 / pieces.0.len()).max(8) + 1)?;
    let caption = format!(
        "rational cubic for LAC alpha = {alpha}: rms {:.2e}, max {:.2e}",
        fit.rms, fit.max_error
    );
    out.write(
        "lac_rational",
        &mut || Ok(nurbs.clone()),
        &comb,
        &caption,
        &mut || Ok(plot::comb_svg(&comb, &nurbs.control_points, &[], &caption)),
    )?;
    if let Some(path) = map {
        let m = approx::error_map(&seg, map_cells, 32)?;
        let caption = format!(
            "error over (f0, f1), alpha = {alpha}, turning {:.1} deg",
            seg.theta_d().to_degrees()
        );
        plot::write_picture(path, &plot::error_map_svg(&m, (fit.f0, fit.f1), &caption))?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

/// The arguments of `aecurve approx` (the command's help is its entry in `cli.rs`).
#[derive(clap::Args)]
pub(crate) struct Args {
    /// Shape parameter alpha.
    #[arg(long, allow_hyphen_values = true)]
    alpha: f64,
    /// Control triangle: "x,y x,y x,y".
    #[arg(long, allow_hyphen_values = true)]
    control: String,
    /// Largest distance to the LAC (input units): as many G2-joined pieces as needed.
    #[arg(long, allow_hyphen_values = true, value_parser = positive)]
    tolerance: Option<f64>,
    #[command(flatten)]
    out: CurveOutput,
    /// Write the error map over (f0, f1) with the monotone region (S3 Fig. 3 and 5).
    #[arg(long)]
    map: Option<PathBuf>,
    /// Cells per axis of the error map (2 to 2,000).
    #[arg(long, default_value_t = 100, value_parser = count::<2, 2000>)]
    map_cells: usize,
}

impl Command for Args {
    fn curve_output(&self) -> Option<&CurveOutput> {
        Some(&self.out)
    }

    fn pictures(&self) -> &[PathBuf] {
        self.map.as_slice()
    }

    fn run(self) -> Result<()> {
        approx(
            self.alpha,
            &self.control,
            self.tolerance,
            &self.out,
            self.map.as_deref(),
            self.map_cells,
        )
    }
}
