//! The gallery of S0 and S3: one rational cubic per LAC segment, the error map.

use aecurve::plot;
use anyhow::Result;

/// S0 Fig. 4-7 (rational cubics for LAC segments of alpha -1, 0, 1, 2 at 90 degrees of
/// turning, three triangles each) and S3 Fig. 3 and 5 (the error map): pictures and HTML.
pub(crate) fn approx_gallery(out: &std::path::Path) -> Result<String> {
    use aesthetic_curves::approx;
    use aesthetic_curves::lac::{LacSegment, LacStandard};
    use aesthetic_curves::{Point, Vec2};
    let mut html = String::from(
        "<h2>One rational cubic per log-aesthetic segment — Yoshida &amp; Saito (S0), Fig. 4-7</h2>\n<p>Each LAC segment \
         (turning 90 degrees) is replaced by the rational cubic of docs/math.md §4 that matches \
         its end points, tangents and curvatures, with (f0, f1) chosen by the global search; \
         the exact test proves its curvature monotone. Errors are relative to the arc \
         length. An isosceles triangle gives the circular arc to rounding.</p>\n\
         <table border=\"1\" cellpadding=\"4\"><tr><th>alpha</th><th>base angle</th>\
         <th>f0</th><th>f1</th><th>rms</th><th>errMax</th></tr>\n",
    );
    let td = std::f64::consts::FRAC_PI_2;
    let mut figures = String::new();
    for alpha in [-1.0, 0.0, 1.0, 2.0] {
        let lim = LacSegment::theta_lim(alpha, td)?;
        for (k, frac) in [0.0, 0.35, 0.7].into_iter().enumerate() {
            let phi = 0.5 * td + frac * (lim - 0.5 * td);
            let d = phi.sin() / (td - phi).sin();
            let tri = [
                Point::new(0.0, 0.0),
                Point::new(1.0, 0.0),
                Point::new(1.0 + d * td.cos(), d * td.sin()),
            ];
            let seg = LacSegment::new(alpha, tri)?;
            let fit = approx::fit_rational_cubic(&seg, &approx::ApproxOptions::default())?;
            html += &format!(
                "<tr><td>{alpha}</td><td>{:.2} deg</td><td>{:.4}</td><td>{:.4}</td><td>{:.2e}</td><td>{:.2e}</td></tr>\n",
                phi.to_degrees(),
                fit.f0,
                fit.f1,
                fit.rms,
                fit.max_error
            );
            if k == 2 {
                let samples = plot::curve_samples(&fit.curve, 201)?;
                let file = format!("approx-alpha{alpha}.svg");
                let caption = format!(
                    "alpha = {alpha}: rms {:.2e}, errMax {:.2e}",
                    fit.rms, fit.max_error
                );
                std::fs::write(
                    out.join(&file),
                    plot::comb_svg(&samples, fit.curve.points(), &[], &caption),
                )?;
                let lcg = aesthetic_curves::lcg::fit_line(aesthetic_curves::lcg::curve_lcg(
                    &fit.curve, 61,
                ))?;
                let lfile = format!("approx-lcg-alpha{alpha}.svg");
                std::fs::write(
                    out.join(&lfile),
                    plot::lcg_chart(
                        &lcg,
                        &format!("LCG of the rational cubic (LAC alpha = {alpha})"),
                    ),
                )?;
                figures += &format!(
                    "<figure><img src=\"{file}\" alt=\"rational cubic alpha {alpha}\" width=\"48%\">\
                     <img src=\"{lfile}\" alt=\"its LCG\" width=\"48%\"><figcaption>alpha = {alpha}, \
                     base angle {:.1} deg: the rational cubic (control polygon dashed) with its \
                     curvature comb, and its logarithmic curvature graph, whose fitted slope \
                     {:.3} stays close to the LAC's alpha.</figcaption></figure>\n",
                    phi.to_degrees(),
                    lcg.alpha
                );
            }
        }
    }
    html += "</table>\n";
    html += &figures;
    // S3 Fig. 3 and 5: alpha = 1, Lambda = 1, theta in [0, 1.57].
    let std = LacStandard::new(1.0, 1.0)?;
    let t1 = 1.57f64;
    let (p0, p2) = (std.eval(0.0)?, std.eval(t1)?);
    let (d0, d1) = (Vec2::from_angle(0.0), Vec2::from_angle(t1));
    let p1 = p0 + d0 * ((p2 - p0).cross(d1) / d0.cross(d1));
    let seg = LacSegment::new(1.0, [p0, p1, p2])?;
    let fit = approx::fit_rational_cubic(&seg, &approx::ApproxOptions::default())?;
    let map = approx::error_map(&seg, 80, 32)?;
    std::fs::write(
        out.join("approx-map-s3.svg"),
        plot::error_map_svg(
            &map,
            (fit.f0, fit.f1),
            "S3: alpha = 1, Lambda = 1, theta in [0, 1.57]",
        ),
    )?;
    html += &format!(
        "<h2>Where the rational cubic fit can go wrong: its error over the two free handle ratios — the stable-approximation paper (S3), Fig. 3 and 5</h2>\n<figure><img src=\"approx-map-s3.svg\" \
         alt=\"error map\"><figcaption>Rms error over (f0, f1) for alpha = 1, Lambda = 1, \
         theta in [0, 1.57]; hatched: the cubic's curvature is not monotone. The global search \
         returns f0 = {:.3}, f1 = {:.3} (rms {:.2e}, circled); S3 reports the global minimum \
         at (0.444, 0.686) and a second local minimum at (0.298, 0.882), where a local \
         optimiser from a fixed start can get stuck.</figcaption></figure>\n",
        fit.f0, fit.f1, fit.rms
    );
    Ok(html)
}
