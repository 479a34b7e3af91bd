//! `aecurve lcg`: the logarithmic curvature graph and alpha of samples or of a segment.

use aecurve::plot;
use aecurve::protocol::AnyBezier;
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
