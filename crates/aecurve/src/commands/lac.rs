//! `aecurve lac` and `aecurve lac --inflection`: a log-aesthetic segment (or one with an
//! inflection end) from its control triangle, with plots and exports.

use crate::commands::{control_triangle, write_curvature_plot, write_curve_outputs};
use aecurve::plot;
use anyhow::Result;
use std::path::PathBuf;

pub(crate) fn lac(
    alpha: f64,
    control: &str,
    samples: usize,
    json: bool,
    output: &[PathBuf],
    curvature_plot: Option<&std::path::Path>,
) -> Result<()> {
    let pts = control_triangle(control)?;
    let seg = aesthetic_curves::lac::LacSegment::new(alpha, pts)?;
    let (k0, k1) = seg.end_curvatures()?;
    if json {
        println!(
            "{}",
            aecurve::protocol::lac_segment_json(&seg, samples.max(2))?
        );
    } else {
        println!("log-aesthetic segment, alpha = {alpha}");
        println!("  turning angle  {:.6} deg", seg.theta_d().to_degrees());
        println!("  lambda         {:.12}", seg.lambda());
        println!("  arc length     {:.9}", seg.arc_length()?);
        println!("  curvature      {k0:.9} at the start, {k1:.9} at the end");
        println!(
            "  high-curvature end at {}",
            if seg.reversed() {
                "the end point"
            } else {
                "the start point"
            }
        );
    }
    let caption = format!("LAC alpha = {alpha}, lambda = {:.6}", seg.lambda());
    let samples = plot::curve_samples(&seg, samples.max(2))?;
    // CAD formats get the segment as rational cubics within 1e-7 of its size (a LAC segment
    // has no exact rational form): the exact rational geometry of that approximation.
    let cad = || {
        cad_nurbs(aesthetic_curves::approx::fit_rational_spline(
            &seg,
            cad_tolerance(&pts),
            64,
            &aesthetic_curves::approx::ApproxOptions::default(),
        )?)
    };
    write_segment_outputs(output, curvature_plot, &samples, &pts, &caption, &cad)
}

/// The CAD tolerance of a segment: 1e-7 of its triangle's size.
fn cad_tolerance(pts: &[aesthetic_curves::Point; 3]) -> f64 {
    1e-7 * pts
        .iter()
        .map(|p| (*p - pts[0]).hypot())
        .fold(0.0, f64::max)
}

/// A segment's rational cubics as one NURBS for the CAD formats, reported on stderr.
fn cad_nurbs(
    sp: aesthetic_curves::approx::RationalSpline,
) -> Result<aesthetic_curves::nurbs::Nurbs> {
    eprintln!(
        "as {} rational cubic(s), max distance {:.2e} from the segment, curvature {}",
        sp.pieces.len(),
        sp.max_error,
        if sp.pieces.iter().all(|p| p.monotone) {
            "monotone in every piece (proven)"
        } else {
            "NOT monotone in every piece"
        }
    );
    Ok(sp.nurbs)
}

/// `-o` for a LAC segment command: pictures (.svg, .png) of the segment with its comb; CAD
/// formats and .json through `cad` (built once, only when asked for).
pub(crate) fn write_segment_outputs(
    output: &[PathBuf],
    curvature_plot: Option<&std::path::Path>,
    samples: &[plot::CombSample],
    control: &[aesthetic_curves::Point],
    caption: &str,
    cad: &dyn Fn() -> Result<aesthetic_curves::nurbs::Nurbs>,
) -> Result<()> {
    write_curvature_plot(curvature_plot, samples, caption)?;
    write_curve_outputs(
        output,
        "log_aesthetic_segment",
        &mut || cad(),
        samples,
        caption,
        &mut || Ok(plot::comb_svg(samples, control, &[], caption)),
    )
}

pub(crate) fn lac_inflection(
    control: &str,
    samples: usize,
    json: bool,
    output: &[PathBuf],
    curvature_plot: Option<&std::path::Path>,
) -> Result<()> {
    let pts = control_triangle(control)?;
    let seg = aesthetic_curves::lac::LacInflectionSegment::new(pts)?;
    let k1 = seg.end_curvature();
    if json {
        println!(
            "{}",
            aecurve::protocol::lac_inflection_json(&seg, samples.max(2))?
        );
    } else {
        println!("log-aesthetic segment with an inflection at the start point");
        println!("  alpha          {:.10}", seg.alpha());
        println!("  turning angle  {:.6} deg", seg.theta_d().to_degrees());
        println!("  arc length     {:.9}", seg.arc_length());
        println!("  curvature      0 at the start, {k1:.9} at the end");
    }
    let caption = format!("LAC with an inflection end, alpha = {:.6}", seg.alpha());
    let samples = plot::curve_samples(&seg, samples.max(2))?;
    // CAD formats: rational cubics within 1e-7 of the size, as for a LAC segment: next to the
    // inflection one cubic with zero curvature there, then the rest (an ordinary LAC
    // segment); G2 at the joints, every piece's curvature proven monotone.
    let cad = || {
        cad_nurbs(aesthetic_curves::approx::fit_inflection_spline(
            &seg,
            cad_tolerance(&pts),
            64,
            &aesthetic_curves::approx::ApproxOptions::default(),
        )?)
    };
    write_segment_outputs(output, curvature_plot, &samples, &pts, &caption, &cad)
}
