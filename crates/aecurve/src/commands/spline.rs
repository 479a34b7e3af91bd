//! `aecurve spline`: the pseudo-elastic spline through points (S2).

use crate::cli::CurveOutput;
use aecurve::plot;
use aesthetic_curves::Curve;
use anyhow::Result;

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
    let s = aesthetic_curves::pseudo_spline::pseudo_elastic(
        &pts,
        closed,
        aecurve::protocol::spline_mode(mode),
    )?;
    let r = &aecurve::protocol::spline_json(&s, mode);
    if out.json {
        println!("{r}");
    } else {
        println!(
            "pseudo-elastic spline through {} points ({}), {mode} mode",
            pts.len(),
            if closed { "closed" } else { "open" }
        );
        println!("  length   {:.9}", r["length"].as_f64().unwrap_or(f64::NAN));
        println!(
            "  area     {:.9} ({})",
            r["area"].as_f64().unwrap_or(f64::NAN),
            if closed {
                "enclosed"
            } else {
                "between the curve and the chord of its ends"
            }
        );
        println!(
            "  energy   {:.9} (sum of l_i J_i)",
            r["energy"].as_f64().unwrap_or(f64::NAN)
        );
    }
    if out.paths().next().is_some() {
        let samples = plot::curve_samples(&s.as_curve()?, 41)?;
        let caption = format!("pseudo-elastic spline: length {:.6}", s.length);
        let mut polygon = pts.clone();
        if closed {
            polygon.push(pts[0]);
        }
        let nurbs = s.as_curve()?.to_nurbs(0.0)?;
        out.write(
            "pseudo_elastic_spline",
            &mut || Ok(nurbs.clone()),
            &samples,
            &caption,
            &mut || Ok(plot::comb_svg(&samples, &polygon, &[], &caption)),
        )?;
    }
    Ok(())
}
