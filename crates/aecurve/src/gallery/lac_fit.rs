//! The gallery of single-LAC fits (the Prius key lines and their published fits).

use aecurve::plot;
use anyhow::Result;

/// `lac.fit` on the Prius lines beside the published single-LAC fits.
pub(crate) fn lac_fit_gallery(out: &std::path::Path) -> Result<String> {
    use aesthetic_curves::lac_fit::{fit_lac, LacFitOptions};
    use aesthetic_curves::Point;
    // Nearest distance from each point to a polyline, every chord a candidate.
    let distances = aesthetic_curves::lac_fit::nearest_distances;
    let max_rms = |d: &[f64]| {
        (
            d.iter().copied().fold(0.0, f64::max),
            (d.iter().map(|x| x * x).sum::<f64>() / d.len() as f64).sqrt(),
        )
    };
    let mut rows = String::new();
    let mut at_bound = 0;
    let (mut ours, mut theirs): (Vec<plot::Series>, Vec<plot::Series>) = (vec![], vec![]);
    for (i, line) in aesthetic_curves_data::PRIUS.iter().enumerate() {
        let pts: Vec<Point> = line.points_as::<Point>();
        let t0 = std::time::Instant::now();
        let fit = fit_lac(&pts, LacFitOptions::default())?;
        let ms = t0.elapsed().as_secs_f64() * 1e3;
        let pf = line
            .published_curve(true)
            .ok_or_else(|| anyhow::anyhow!("{}: published fit unreadable", line.name))?;
        let to_pts = |v: Vec<[f64; 2]>| {
            v.into_iter()
                .map(|[x, y]| Point::new(x, y))
                .collect::<Vec<_>>()
        };
        let (m1, r1) = max_rms(&distances(&to_pts(pf.points(3000)), &pts));
        let (m2, r2) = max_rms(&distances(&to_pts(pf.euler_points()), &pts));
        // Curvature against arc length, both from the line's first point.
        let aesthetic_curves::Polyline {
            points: poly,
            kappa: k,
        } = fit.segment.sample(400)?;
        let mut s = 0.0;
        let mut line_ours = Vec::new();
        for (j, kj) in k.iter().enumerate() {
            if j > 0 {
                s += poly[j].distance(poly[j - 1]);
            }
            line_ours.push((s, kj.abs()));
        }
        let n = 400;
        let length = pf.l * pf.scale;
        let mut line_theirs: Vec<(f64, f64)> = (0..=n)
            .map(|j| {
                let u = j as f64 / n as f64;
                (u * length, pf.curvature(u))
            })
            .collect();
        if pf.case % 2 == 1 {
            // Case 1 lists the curve from its other end.
            line_theirs = line_theirs
                .iter()
                .rev()
                .map(|(x, k)| (length - x, *k))
                .collect();
        }
        at_bound += usize::from(fit.alpha_at_bound);
        let mut a = plot::Series::nth(format!("ps_{}", i + 1), line_ours, i);
        a.markers = false;
        ours.push(a);
        let mut b = plot::Series::nth(format!("ps_{}", i + 1), line_theirs, i);
        b.markers = false;
        theirs.push(b);
        rows += &format!(
            "<tr><td>ps_{}</td><td>{:.3}{}</td><td>{:.3}</td><td>{:.3}</td><td>{:.3}</td>\
             <td>{:.3}</td><td>{:.3}</td><td>{:.2e}</td><td>{:.2e}</td><td>{}</td><td>{ms:.0}</td></tr>\n",
            i + 1,
            fit.alpha,
            if fit.alpha_at_bound { " (bound)" } else { "" },
            pf.alpha,
            fit.max_deviation,
            m1.min(m2),
            fit.rms_deviation,
            r1.min(r2),
            fit.max_curvature,
            pf.max_curvature(),
            if fit.converged { "yes" } else { "no" },
        );
    }
    std::fs::write(
        out.join("lac-fit-ours.svg"),
        plot::fitted_chart(
            "lac.fit: |curvature| along each Prius line",
            "arc length (mm)",
            "|curvature| (1/mm)",
            &ours,
        ),
    )?;
    std::fs::write(
        out.join("lac-fit-published.svg"),
        plot::fitted_chart(
            "Published fits (Graiff Zurita et al. 2023): |curvature|",
            "arc length (mm)",
            "|curvature| (1/mm)",
            &theirs,
        ),
    )?;
    Ok(format!(
        "<h2>One log-aesthetic curve per measured line — lac.fit against the published fits \
         (Graiff Zurita, Kajiwara &amp; Miura 2023)</h2>\n<p>The single LAC segment closest to \
         each Prius line (default objective: the narrowest band, the L8 norm of the \
         point-to-curve distances), held to no more than 1.5 times the curvature of the \
         smoothest spline as close to the points (no end hooks), its ends at the feet of the \
         first and last points. The published fits are rebuilt from their printed parameters \
         (3 decimals), as the continuous curve and as the authors' Euler polyline; the table \
         gives them the better of the two. Distances: nearest point of the curve, in mm.</p>\n\
         <table border=\"1\" cellpadding=\"4\"><tr><th>line</th><th>alpha</th>\
         <th>published alpha</th><th>max distance</th><th>published</th><th>rms distance</th>\
         <th>published</th><th>max |κ| (1/mm)</th><th>published</th><th>converged</th>\
         <th>ms</th></tr>\n{rows}</table>\n<figure><img src=\"lac-fit-ours.svg\" \
         alt=\"curvature of lac.fit\" width=\"48%\"><img src=\"lac-fit-published.svg\" \
         alt=\"curvature of the published fits\" width=\"48%\"><figcaption>Curvature along \
         each line: lac.fit (left), the published fits (right), same colour per line. On \
         lines this shallow alpha is poorly determined: the distances hardly change along it, \
         and {at_bound} of the 5 fits end on the alpha bound ±5 (reported).</figcaption></figure>\n"
    ))
}
