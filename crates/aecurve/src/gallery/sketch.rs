//! The gallery of S4: pen input to a G2 curve of LAC pieces, on real and drawn lines.

use aecurve::plot;
use anyhow::Result;

/// S4 §3 (Fig. 9-12): the pen-input pipeline on the built-in stroke and on a Prius key line.
pub(crate) fn sketch_gallery(out: &std::path::Path) -> Result<String> {
    use aesthetic_curves::sketch::{fit_sketch, SketchOptions};
    let mut html = String::from(
        "<h2>From pen strokes and measured lines to a G2 aesthetic curve — Miura et al. (S4) §3, Fig. 9-12</h2>\n<p>Points → \
         least-squares cubic B-spline → pieces at inflections and curvature maxima → one \
         log-aesthetic segment per piece (alpha from its curvature graph; inflection-end \
         segments at inflections) → G2 fairing of the joint tangents → one rational cubic \
         per piece, its curvature proven monotone. Grey: the input; red: the result; \
         circles: the joints; blue: the curvature comb (continuous across every joint: G2).</p>\n",
    );
    let prius = aesthetic_curves_data::PRIUS.map(|l| l.csv);
    let mut inputs: Vec<(String, &str, String, Option<f64>)> = vec![(
        "sketch-stroke".into(),
        aesthetic_curves_data::HAND_STROKE,
        "A pen stroke (240 points with hand jitter), default \
         tolerance (0.5% of its size)."
            .into(),
        None,
    )];
    for (i, text) in prius.iter().enumerate() {
        inputs.push((
            format!("sketch-prius{}", i + 1),
            text,
            format!(
                "Prius key line {} (measured points, about 1500 mm long and 80-100 mm deep; \
                 Graiff Zurita, Kajiwara & Miura 2023, MIT licence), tolerance 0.3 mm.",
                i + 1
            ),
            Some(0.3),
        ));
    }
    for (name, text, caption, tol) in &inputs {
        let (name, text, caption, tol) = (name.as_str(), *text, caption.as_str(), *tol);
        // The Prius lines are measured in millimetres, the pen stroke in pixels.
        let unit = if name.starts_with("sketch-prius") {
            "mm"
        } else {
            "px"
        };
        let pts = aecurve::parse_points_text(text)?;
        let tol = tol.unwrap_or_else(|| aesthetic_curves::sketch::default_tolerance(&pts));
        let t0 = std::time::Instant::now();
        let sk = fit_sketch(&pts, &SketchOptions::with_tolerance(tol))?;
        let ms = t0.elapsed().as_secs_f64() * 1e3;
        // Comb picture and curvature against arc length, pieces in turn.
        let mut samples: Vec<plot::CombSample> = Vec::new();
        let mut kappa_s: Vec<plot::Series> = Vec::new();
        let mut s_acc = 0.0;
        for (i, p) in sk.pieces.iter().enumerate() {
            let mut line = Vec::new();
            let mut prev = p.rational.points()[0];
            for q in aesthetic_curves::Curve::curve_points(&p.rational, 81)? {
                samples.push((q.p, q.normal(), q.kappa));
                s_acc += q.p.distance(prev);
                prev = q.p;
                line.push((s_acc, q.kappa));
            }
            let mut series = plot::Series::nth(format!("{i}: α {:.2}", p.alpha), line, i);
            series.markers = false;
            kappa_s.push(series);
        }
        let joints = sk.joints();
        let title = format!(
            "{} pieces, deviation {:.3} {unit} (tolerance {:.3} {unit}), curvature jump {:.1e}",
            sk.pieces.len(),
            sk.max_deviation,
            tol,
            sk.max_curvature_jump
        );
        std::fs::write(
            out.join(format!("{name}.svg")),
            plot::comb_svg_in(&samples, &pts, &joints, &title, unit),
        )?;
        std::fs::write(
            out.join(format!("{name}-curvature.svg")),
            plot::fitted_chart(
                "signed curvature of the result (one colour per piece)",
                &format!("arc length ({unit})"),
                &format!("curvature (1/{unit})"),
                &kappa_s,
            ),
        )?;
        let sum = aecurve::summary::sketch(&sk, tol, unit);
        html += &format!(
            "<h3>{name}</h3><p>{caption} {} in {ms:.0} ms; {}; {}.</p>\n\
             <figure><img src=\"{name}.svg\" alt=\"{name}\"></figure>\n\
             <figure><img src=\"{name}-curvature.svg\" alt=\"curvature\"><figcaption>Curvature \
             against arc length: monotone on each piece, continuous at the joints.\
             </figcaption></figure>\n<table border=\"1\" cellpadding=\"4\"><tr>",
            sum.headline, sum.details, sum.fairing
        );
        for head in aecurve::summary::sketch_columns(unit) {
            html += &format!("<th>{head}</th>");
        }
        html += "</tr>\n";
        for row in &sum.rows {
            html += "<tr>";
            for cell in row {
                html += &format!("<td>{cell}</td>");
            }
            html += "</tr>\n";
        }
        html += "</table>\n";
    }
    Ok(html)
}
