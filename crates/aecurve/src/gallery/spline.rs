//! The gallery of S2: the pseudo-elastic spline, its tables and comparisons.

use aecurve::plot;
use anyhow::Result;

/// Comb samples of consecutive Hermite spans, `per` intervals per span.
pub(crate) fn span_samples(
    spans: &[aesthetic_curves::pseudo_spline::HermiteSpan],
    per: usize,
) -> Result<Vec<plot::CombSample>> {
    let pieces: aesthetic_curves::Result<Vec<aesthetic_curves::Bezier>> =
        spans.iter().map(|g| g.to_bezier()).collect();
    Ok(plot::curve_samples(
        &aesthetic_curves::Pieces(pieces?),
        per + 1,
    )?)
}

/// S2's printed Table 4 (length) and Table 5 (area) for n = 3..10, from its 36 x 36 table.
pub(crate) const S2_TABLE4: [f64; 8] = [
    6.18957607, 6.26067766, 6.27774034, 6.27785088, 6.28605010, 6.28591825, 6.28219908, 6.28757066,
];
pub(crate) const S2_TABLE5: [f64; 8] = [
    3.04563765, 3.11345972, 3.13063511, 3.13614662, 3.13830387, 3.13961368, 3.14053616, 3.14105203,
];

/// Independent reference for the unit circle (mpmath, `tools/pseudo_reference.py`): rows
/// "n length area r J".
pub(crate) const CIRCLE_REFERENCE: &str = aesthetic_curves_data::PSEUDO_UNIT_CIRCLE_REFERENCE;

/// S2 Tables 4-5 (unit circle), Fig. 8-12 (Table 1 data) and Fig. 13-17 (Table 2 data):
/// the pseudo-elastic spline against the cubic splines and Hermite curves S2 compares it
/// with, with fairness numbers for every curve.
pub(crate) fn spline_gallery(out: &std::path::Path, quick: bool) -> Result<String> {
    use aesthetic_curves::pseudo_spline::{
        comparison_curve, fairness, pseudo_elastic, Comparison, HermiteSpan, Mode,
    };
    use aesthetic_curves::Point;
    use std::f64::consts::PI;
    let mut html = String::from(
        "<h2>The pseudo-elastic spline through points — Inoue &amp; Shibata (S2)</h2>\n<p>Hermite cubics through the points; each \
         span's tangent lengths minimise the pseudo-energy J = E L² (E = ∫κ²ds, L its length); \
         tangent directions by S2 eq. 11-12. <b>Table mode</b> reads J, r0, r1, L and S from \
         tables over the end angles (288 x 288 nodes, 1.25°, against S2's 36 x 36) and J(θ) \
         from a 1-D table, so a 1000-point curve takes well under a millisecond; \
         <b>exact mode</b> minimises at every span.</p>\n\
         <h3>A closed spline through n points of the unit circle: length and area (S2 Tables 4 and 5)</h3>\n\
         <p>The reference is independent of this library: mpmath at 40 digits \
         (tools/pseudo_reference.py; the exact mode matches it to 1e-7, tested). S2's printed \
         values came from its 36 x 36 table: within 1e-4 where the span's end angle 180°/n \
         lies on its 10° grid (n = 3, 6, 9) and off by 4e-3 to 6e-3 elsewhere (its \
         interpolation); the finer table here stays within 3e-7.</p>\n\
         <table border=\"1\" cellpadding=\"4\"><tr><th>n</th><th>length, table mode</th>\
         <th>reference</th><th>table − ref</th><th>S2 printed</th><th>S2 − ref</th>\
         <th>area, table mode</th><th>reference</th><th>table − ref</th><th>S2 printed</th>\
         <th>S2 − ref</th></tr>\n",
    );
    let reference: Vec<Vec<f64>> = CIRCLE_REFERENCE
        .lines()
        .map(|l| {
            l.split_whitespace()
                .filter_map(|x| x.parse().ok())
                .collect()
        })
        .filter(|v: &Vec<f64>| v.len() >= 3)
        .collect();
    for r in &reference {
        let n = r[0] as usize;
        let pts: Vec<Point> = (0..n)
            .map(|k| {
                let a = 2.0 * PI * k as f64 / n as f64;
                Point::new(a.cos(), a.sin())
            })
            .collect();
        let s = pseudo_elastic(&pts, true, Mode::Table)?;
        let (pl, pa) = (S2_TABLE4[n - 3], S2_TABLE5[n - 3]);
        html += &format!(
            "<tr><td>{n}</td><td>{:.8}</td><td>{:.8}</td><td>{:+.1e}</td><td>{pl:.8}</td>\
             <td>{:+.1e}</td><td>{:.8}</td><td>{:.8}</td><td>{:+.1e}</td><td>{pa:.8}</td>\
             <td>{:+.1e}</td></tr>\n",
            s.length,
            r[1],
            s.length - r[1],
            pl - r[1],
            s.area,
            r[2],
            s.area - r[2],
            pa - r[2]
        );
    }
    html += "</table>\n";
    if !quick {
        // Exact mode on the smallest case (a second or two per point).
        let pts: Vec<Point> = (0..3)
            .map(|k| {
                let a = 2.0 * PI * k as f64 / 3.0;
                Point::new(a.cos(), a.sin())
            })
            .collect();
        let t = std::time::Instant::now();
        let s = pseudo_elastic(&pts, true, Mode::Exact)?;
        html += &format!(
            "<p>Exact mode, n = 3: length {:.9}, area {:.9} (reference {:.9}, {:.9}; {:.1} s).\
             </p>\n",
            s.length,
            s.area,
            reference[0][1],
            reference[0][2],
            t.elapsed().as_secs_f64()
        );
    }
    // The five curves of S2's comparison.
    let methods: Vec<(&str, Option<Comparison>)> = Comparison::ALL
        .iter()
        .map(|m| (m.name(), Some(*m)))
        .chain(std::iter::once(("pseudo-elastic spline", None)))
        .collect();
    let curve = |pts: &[Point], m: Option<Comparison>| -> Result<Vec<HermiteSpan>> {
        Ok(match m {
            Some(m) => comparison_curve(pts, m)?,
            None => pseudo_elastic(pts, false, Mode::Table)?.segments,
        })
    };
    let fair_row = |label: String, spans: &[HermiteSpan]| -> Result<String> {
        let f = fairness(spans)?;
        Ok(format!(
            "<tr><td>{label}</td><td>{:.4}</td><td>{:.4}</td><td>{}</td><td>{:.4}</td></tr>\n",
            f.bending_energy, f.kappa_variation, f.curvature_extrema, f.max_abs_kappa
        ))
    };
    let fair_head = "<table border=\"1\" cellpadding=\"4\"><tr><th>curve</th><th>∫κ²ds</th>\
                     <th>∫(dκ/ds)²ds</th><th>curvature extrema</th><th>max |κ|</th></tr>\n";
    html += "<h3>Nine points with the middle one raised: the five methods compared (S2 Fig. 8-12)</h3>\n<p>Nine points on a line, the middle one \
             raised to Y = 0..5; one picture per method with the six curves. Cubic spline A \
             (uniform parameters, natural ends) wiggles beside the raised point; cubic spline \
             B (chord-length parameters) overshoots; the Hermite curves (tangent length = \
             chord) and the pseudo-elastic spline stay close to the polygon. Fairness \
             numbers below the pictures: curvature extrema by the exact test inside the \
             spans plus sign changes of dκ/ds at the points.</p>\n";
    let ys: Vec<f64> = (0..=5).map(|y| y as f64).collect();
    let mut fair = String::from(fair_head);
    // Per Y: the lowest ∫κ²ds and ∫(dκ/ds)²ds and which curve has it.
    let mut best_energy = vec![(f64::INFINITY, 0usize); ys.len()];
    let mut best_variation = vec![(f64::INFINITY, 0usize); ys.len()];
    for (fig, (name, m)) in methods.iter().enumerate() {
        let mut series = Vec::new();
        let mut dots = Vec::new();
        for (k, &y) in ys.iter().enumerate() {
            let pts: Vec<Point> = (-4..=4)
                .map(|i| Point::new(i as f64, if i == 0 { y } else { 0.0 }))
                .collect();
            let spans = curve(&pts, *m)?;
            if y > 0.0 {
                fair += &fair_row(format!("{name}, Y = {y}"), &spans)?;
                let f = fairness(&spans)?;
                if f.bending_energy < best_energy[k].0 {
                    best_energy[k] = (f.bending_energy, fig);
                }
                if f.kappa_variation < best_variation[k].0 {
                    best_variation[k] = (f.kappa_variation, fig);
                }
            }
            let samples = span_samples(&spans, 24)?;
            series.push(plot::Series::nth(
                format!("Y = {y}"),
                samples.iter().map(|s| (s.0.x, s.0.y)).collect(),
                k,
            ));
            dots.extend(pts);
        }
        let file = format!("s2-fig{}.svg", 8 + fig);
        std::fs::write(
            out.join(&file),
            plot::curves_svg(&format!("S2 Fig. {}: {name}", 8 + fig), &series, &dots),
        )?;
        html += &format!(
            "<figure><img src=\"{file}\" alt=\"S2 Fig. {}\" width=\"70%\"><figcaption>Fig. {}: \
             {name} through the Table 1 points.</figcaption></figure>\n",
            8 + fig,
            8 + fig
        );
    }
    html += &fair;
    html += "</table>\n<p>Lowest bending energy ∫κ²ds, by Y: ";
    let names: Vec<&str> = methods.iter().map(|m| m.0).collect();
    let list = |best: &[(f64, usize)]| -> String {
        best.iter()
            .zip(&ys)
            .filter(|(_, y)| **y > 0.0)
            .map(|(b, y)| format!("Y = {y}: {}", names[b.1]))
            .collect::<Vec<_>>()
            .join("; ")
    };
    html += &list(&best_energy);
    html += ". Lowest ∫(dκ/ds)²ds: ";
    html += &list(&best_variation);
    html += ".</p>\n";
    // Table 2: a zig-zag of four points (S2 Fig. 13-17).
    let t2 = [
        Point::new(0.0, 0.0),
        Point::new(2.0, -0.1),
        Point::new(1.0, -0.1),
        Point::new(3.0, 0.0),
    ];
    html +=
        "<h3>Four points that double back (S2 Fig. 13-17)</h3>\n<p>Four points that double back: \
             (0, 0), (2, -0.1), (1, -0.1), (3, 0). Each curve with its curvature comb.</p>\n";
    let mut fair = String::from(fair_head);
    for (fig, (name, m)) in methods.iter().enumerate() {
        let spans = curve(&t2, *m)?;
        fair += &fair_row(name.to_string(), &spans)?;
        let file = format!("s2-fig{}.svg", 13 + fig);
        std::fs::write(
            out.join(&file),
            plot::comb_svg(
                &span_samples(&spans, 60)?,
                &t2,
                &[],
                &format!("S2 Fig. {}: {name}", 13 + fig),
            ),
        )?;
        html += &format!(
            "<figure><img src=\"{file}\" alt=\"S2 Fig. {}\" width=\"60%\"><figcaption>Fig. {}: \
             {name} through the Table 2 points, with its curvature comb.</figcaption></figure>\n",
            13 + fig,
            13 + fig
        );
    }
    html += &fair;
    html += "</table>\n";
    Ok(html)
}

/// S2's point sets through the pseudo-elastic spline (G1: its curvature steps at every
/// point) and the G2 log-aesthetic spline (α = -1 and α = -0.4) side by side, each with
/// its comb, and their curvature plots on one chart.
pub(crate) fn g1_g2_gallery(out: &std::path::Path) -> Result<String> {
    use aesthetic_curves::lac_spline::{lac_spline, LacSplineOptions};
    use aesthetic_curves::pseudo_spline::{pseudo_elastic, Mode};
    use aesthetic_curves::Point;
    let mut html = String::from(
        "<h2>G1 and G2 through the same points: the pseudo-elastic spline and the \
         log-aesthetic spline</h2>\n<p>The pseudo-elastic spline (S2) is G1: its tangent is \
         continuous, its curvature steps at every point. The log-aesthetic spline \
         (<code>spline.lac</code>, docs/math.md §5.1) is G2 at every point, made of LAC pieces \
         of one α (α = -1: clothoids, Spiro's curve), each one rational cubic proven \
         curvature-monotone: α = -1 and α = -0.4 (its pieces' curvature grows faster near \
         their inflections). Same points, side by side, then the three curvature plots on \
         one chart. (α >= 0 has no inflection-end segment: an S-shaped span there takes \
         clothoid halves, and where the spans are nearly straight the solve can stop short \
         of G2: docs/math.md §5.1.)</p>\n",
    );
    let raised: Vec<Point> = (-4..=4)
        .map(|i| Point::new(i as f64, if i == 0 { 2.0 } else { 0.0 }))
        .collect();
    let wave = vec![
        Point::new(0.0, 0.0),
        Point::new(2.0, 1.5),
        Point::new(4.0, 1.0),
        Point::new(6.0, 3.0),
        Point::new(8.0, 2.5),
        Point::new(10.0, 4.0),
    ];
    let sets = [
        (
            "S2 Table 1, Y = 2: nine points, the middle one raised",
            raised,
            "g1g2-raised",
        ),
        (
            "S2's example points (examples/spline-points.csv)",
            wave,
            "g1g2-wave",
        ),
    ];
    for (title, pts, stem) in sets {
        html += &format!("<h3>{title}</h3>\n");
        let pe = span_samples(&pseudo_elastic(&pts, false, Mode::Table)?.segments, 60)?;
        let mut curves = vec![(
            "pseudo-elastic (G1)".to_string(),
            "pseudo-elastic (G1)".to_string(),
            pe,
        )];
        for alpha in [-1.0, -0.4] {
            let opts = LacSplineOptions {
                alpha,
                ..Default::default()
            };
            match lac_spline(&pts, &opts) {
                Ok(s) => {
                    let label = format!(
                        "log-aesthetic, α = {alpha} (G2 to {:.0e}, {} pieces)",
                        s.max_cubic_jump.max(1e-16),
                        s.pieces.len()
                    );
                    let short = format!("log-aesthetic, α = {alpha}");
                    curves.push((short, label, plot::curve_samples(&s.rationals(), 41)?));
                }
                Err(e) => html += &format!("<p>α = {alpha}: {e}</p>\n"),
            }
        }
        let mut series = Vec::new();
        for (i, (short, label, samples)) in curves.iter().enumerate() {
            let file = format!("{stem}-{i}.svg");
            std::fs::write(out.join(&file), plot::comb_svg(samples, &pts, &[], label))?;
            html += &format!(
                "<figure style=\"display:inline-block;width:32%;margin:0\"><img src=\"{file}\" \
                 alt=\"{label}\" width=\"100%\"><figcaption>{label}</figcaption></figure>\n"
            );
            let mut s = plot::Series::nth(short.clone(), plot::curvature_series(samples), i);
            s.markers = false;
            series.push(s);
        }
        let file = format!("{stem}-curvature.svg");
        std::fs::write(
            out.join(&file),
            plot::fitted_chart(
                &format!("curvature: {title}"),
                "arc length",
                "curvature",
                &series,
            ),
        )?;
        html += &format!(
            "<figure><img src=\"{file}\" alt=\"curvature plots\" width=\"70%\"><figcaption>The \
             curvature of the three curves against arc length: the pseudo-elastic spline's \
             steps at the points, the log-aesthetic splines' continuous curvature (linear \
             pieces for clothoids).</figcaption></figure>\n"
        );
    }
    Ok(html)
}
