//! The gallery of segments with an inflection end (S4 Fig. 1-3).

use aecurve::plot;
use anyhow::Result;

/// S4 Fig. 1-3: inflection-end segments from (0, 0) (tangent along x) to (√2 + 1, 1), the
/// direction angle θ at the far end from 50° to 130°; the curvature there and alpha against θ.
pub(crate) fn inflection_gallery(out: &std::path::Path) -> Result<String> {
    use aesthetic_curves::lac::LacInflectionSegment;
    use aesthetic_curves::Point;
    let p2 = Point::new(2f64.sqrt() + 1.0, 1.0);
    let mut curves = Vec::new();
    let (mut kappa, mut alpha) = (Vec::new(), Vec::new());
    let mut rows = String::new();
    for (k, deg) in (50..=130).step_by(10).enumerate() {
        let th = (deg as f64).to_radians();
        let p1 = Point::new(p2.x - p2.y / th.tan(), 0.0);
        let seg = LacInflectionSegment::new([Point::ORIGIN, p1, p2])?;
        let pts = seg.sample(120)?.points;
        curves.push(plot::Series::nth(
            format!("θ = {deg}°"),
            pts.iter().map(|p| (p.x, p.y)).collect(),
            k,
        ));
        let kap = seg.end_curvature();
        kappa.push((deg as f64, kap));
        alpha.push((deg as f64, seg.alpha()));
        rows += &format!(
            "<tr><td>{deg}</td><td>{:.5}</td><td>{:.5}</td><td>{:.5}</td></tr>\n",
            seg.alpha(),
            kap,
            seg.arc_length()
        );
    }
    for c in curves.iter_mut() {
        c.markers = false;
    }
    // The graphs on a finer step (2°).
    kappa.clear();
    alpha.clear();
    for deg in (50..=130).step_by(2) {
        let th = (deg as f64).to_radians();
        let p1 = Point::new(p2.x - p2.y / th.tan(), 0.0);
        let seg = LacInflectionSegment::new([Point::ORIGIN, p1, p2])?;
        kappa.push((deg as f64, seg.end_curvature()));
        alpha.push((deg as f64, seg.alpha()));
    }
    std::fs::write(
        out.join("s4-fig1.svg"),
        plot::curves_svg(
            "S4 Fig. 1: segments with an inflection end at (0, 0)",
            &curves,
            &[Point::ORIGIN, p2],
        ),
    )?;
    std::fs::write(
        out.join("s4-fig2.svg"),
        plot::fitted_chart(
            "S4 Fig. 2: curvature at the far end against its direction angle",
            "θ (degrees)",
            "κ at (√2 + 1, 1)  (1 / length unit)",
            &[plot::Series::new("κ", kappa, plot::PALETTE[0])],
        ),
    )?;
    std::fs::write(
        out.join("s4-fig3.svg"),
        plot::fitted_chart(
            "S4 Fig. 3: alpha against the direction angle",
            "θ (degrees)",
            "alpha",
            &[plot::Series::new("alpha", alpha, plot::PALETTE[1])],
        ),
    )?;
    Ok(format!(
        "<h2>Log-aesthetic segments that start at an inflection — Miura, Yagi, Kawata &amp; Fujisawa (S4), Fig. 1-3</h2>\n<p>The \
         inflection point is (0, 0) with its tangent along x, the other end is (√2 + 1, 1) and \
         the direction angle θ there runs from 50° to 130°; alpha follows from the triangle. \
         As S4 says, the curvature at the far end and alpha both increase with θ: that \
         monotone relation is what lets the G2 fairing match curvatures by turning the joint \
         tangent.</p>\n<figure><img src=\"s4-fig1.svg\" alt=\"S4 Fig. 1\" width=\"70%\">\
         <figcaption>Fig. 1: the nine segments.</figcaption></figure>\n<figure><img \
         src=\"s4-fig2.svg\" alt=\"S4 Fig. 2\" width=\"48%\"><img src=\"s4-fig3.svg\" \
         alt=\"S4 Fig. 3\" width=\"48%\"><figcaption>Fig. 2 and 3: curvature at the far end \
         and alpha against θ.</figcaption></figure>\n<table border=\"1\" cellpadding=\"4\">\
         <tr><th>θ (°)</th><th>alpha</th><th>κ at the far end</th><th>arc length</th></tr>\n\
         {rows}</table>\n"
    ))
}
