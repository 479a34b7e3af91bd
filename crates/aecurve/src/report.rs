//! The HTML report of `aecurve check -o report.html`: one picture per glyph or path, the
//! worst first. Each picture shows the outline, its curvature comb (teeth on the convex side,
//! the longest a sixth of the shape's size), curvature extrema (blue circles), inflections
//! (green diamonds), near-breaks (red rings) and curvature jumps at smooth joins (small
//! orange rings), with the
//! shape's name, its counts and its findings under it. No script: a static page.

use crate::outline_io::{Shape, ShapeCheck};
use aesthetic_curves::{Curve, Point};
use std::fmt::Write;

/// The start of a report page: its head with the shared style (and `css`), the body's
/// title.
pub(crate) fn page_start(title: &str, css: &str) -> String {
    format!(
        "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{t}</title>\
         <style>body{{font-family:sans-serif;margin:1.5em;color:#222}}\
         .grid{{display:flex;flex-wrap:wrap;gap:14px}}\
         figcaption{{font-size:12px}} figcaption b{{font-size:14px}}\
         .key span{{margin-right:1.2em}}{css}</style></head><body>\n<h1>{t}</h1>\n",
        t = esc(title)
    )
}

/// Escape text for HTML.
pub(crate) fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The report page: `shapes` and their checks in the same order, at most `limit` pictures
/// (the worst shapes first: the highest finding score, then the most findings).
pub fn outline_report(
    title: &str,
    y_up: bool,
    shapes: &[&Shape],
    checked: &[ShapeCheck],
    limit: usize,
) -> String {
    let mut order: Vec<usize> = (0..shapes.len()).collect();
    order.sort_by(|&a, &b| worse_first(&checked[a], &checked[b]));
    let drawn: Vec<(&Shape, &ShapeCheck)> = order
        .iter()
        .take(limit)
        .map(|&i| (shapes[i], &checked[i]))
        .collect();
    outline_report_drawn(title, y_up, shapes.len(), &drawn)
}

/// The report's order: the highest finding score first, then the most findings.
pub fn worse_first(a: &ShapeCheck, b: &ShapeCheck) -> std::cmp::Ordering {
    worse_rank_first(rank(a), rank(b))
}

/// What [`worse_first`] orders a shape's check by: its worst finding's score and its
/// number of findings.
pub fn rank(c: &ShapeCheck) -> (f64, usize) {
    (
        c.findings.first().map_or(0.0, |f| f.score),
        c.findings.len(),
    )
}

/// [`worse_first`] on ranks kept without their checks.
pub fn worse_rank_first(a: (f64, usize), b: (f64, usize)) -> std::cmp::Ordering {
    b.0.total_cmp(&a.0).then(b.1.cmp(&a.1))
}

/// The report page of `total` shapes of which `drawn` (in order) are drawn.
pub fn outline_report_drawn(
    title: &str,
    y_up: bool,
    total: usize,
    drawn: &[(&Shape, &ShapeCheck)],
) -> String {
    let mut html = page_start(
        title,
        "figure{margin:0;width:330px;border:1px solid #ddd;padding:6px}",
    );
    let _ = write!(
        html,
        "<p class=\"key\"><span style=\"color:#d62728\">curve</span>\
         <span style=\"color:#6baed6\">curvature comb</span>\
         <span style=\"color:#1f77b4\">&#9675; curvature extremum</span>\
         <span style=\"color:#2ca02c\">&#9671; inflection</span>\
         <span style=\"color:#e41a1c\">&#9711; near-break (probably meant smooth)</span>\
         <span style=\"color:#ff9f40\">&#9675; smooth join, curvature jumps (not G2)</span>\
         <span style=\"color:#2ca02c\">- - suggested handles (monotone)</span></p>\n\
         <p>{n} shapes, the worst first{more}.</p>\n<div class=\"grid\">\n",
        n = total,
        more = if total > drawn.len() {
            format!("; the first {} are drawn", drawn.len())
        } else {
            String::new()
        }
    );
    for (shape, check) in drawn {
        html.push_str(&picture(shape, check, y_up));
    }
    html.push_str("</div>\n</body></html>\n");
    html
}

/// One shape's figure.
fn picture(shape: &Shape, check: &ShapeCheck, y_up: bool) -> String {
    let pts: Vec<Point> = shape
        .contours
        .iter()
        .flat_map(|c| c.segments.iter().flat_map(|s| s.points().iter().copied()))
        .collect();
    let (mut x0, mut y0, mut x1, mut y1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
    for p in &pts {
        x0 = x0.min(p.x);
        x1 = x1.max(p.x);
        y0 = y0.min(p.y);
        y1 = y1.max(p.y);
    }
    let size = (x1 - x0).max(y1 - y0).max(1e-9);
    let (w, h) = (320.0, 320.0);
    let pad = 0.22 * size;
    let s = (w - 10.0) / (size + 2.0 * pad);
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    let map = |p: Point| -> (f64, f64) {
        let x = w / 2.0 + (p.x - cx) * s;
        let y = if y_up {
            h / 2.0 - (p.y - cy) * s
        } else {
            h / 2.0 + (p.y - cy) * s
        };
        (x, y)
    };
    let mut svg = String::new();
    let _ = write!(
        svg,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">"
    );
    // Curve and comb from the exact points of each segment.
    let mut kmax = 0.0f64;
    let mut samples = Vec::new();
    for c in &shape.contours {
        for seg in &c.segments {
            if let Ok(q) = seg.curve_points(if seg.degree() > 1 { 24 } else { 2 }) {
                kmax = q.iter().fold(kmax, |m, p| m.max(p.kappa.abs()));
                samples.push(q);
            }
        }
    }
    let tooth = if kmax > 0.0 { size / 6.0 / kmax } else { 0.0 };
    let mut comb = String::new();
    let mut outline = String::new();
    for q in &samples {
        let mut tips = Vec::with_capacity(q.len());
        for (k, p) in q.iter().enumerate() {
            let (x, y) = map(p.p);
            let _ = write!(outline, "{}{x:.1},{y:.1} ", if k == 0 { "M" } else { "L" });
            let tip = p.p - p.normal() * (p.kappa * tooth);
            let (u, v) = map(tip);
            tips.push((u, v));
            if k % 2 == 0 {
                let _ = write!(comb, "M{x:.1},{y:.1}L{u:.1},{v:.1}");
            }
        }
        for (k, (u, v)) in tips.iter().enumerate() {
            let _ = write!(comb, "{}{u:.1},{v:.1}", if k == 0 { "M" } else { "L" });
        }
    }
    let _ = write!(
        svg,
        "<path d=\"{comb}\" fill=\"none\" stroke=\"#9ecae1\" stroke-width=\"0.7\"/>\
         <path d=\"{outline}\" fill=\"none\" stroke=\"#d62728\" stroke-width=\"1.6\"/>"
    );
    let mut extrema = 0;
    let mut inflections = 0;
    for c in &check.contours {
        for seg in &c.segments {
            for (_, p) in &seg.extrema {
                let (x, y) = map(*p);
                extrema += 1;
                let _ = write!(
                    svg,
                    "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"3\" fill=\"none\" stroke=\"#1f77b4\" stroke-width=\"1.2\"/>"
                );
            }
            if let Some(g) = &seg.suggestion {
                let q = g.curve.points();
                let m: Vec<(f64, f64)> = q.iter().map(|p| map(*p)).collect();
                let _ = write!(
                    svg,
                    "<path d=\"M{:.1},{:.1}C{:.1},{:.1} {:.1},{:.1} {:.1},{:.1}\" fill=\"none\" stroke=\"#2ca02c\" stroke-width=\"1.4\" stroke-dasharray=\"4 3\"/>",
                    m[0].0, m[0].1, m[1].0, m[1].1, m[2].0, m[2].1, m[3].0, m[3].1
                );
            }
            for (_, p) in &seg.inflections {
                let (x, y) = map(*p);
                inflections += 1;
                let _ = write!(
                    svg,
                    "<path d=\"M{:.1},{y:.1}L{x:.1},{:.1}L{:.1},{y:.1}L{x:.1},{:.1}Z\" fill=\"#2ca02c\"/>",
                    x - 4.0,
                    y - 4.0,
                    x + 4.0,
                    y + 4.0
                );
            }
        }
        for j in &c.joins {
            let (x, y) = map(j.point);
            if j.near_break {
                let _ = write!(
                    svg,
                    "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"8\" fill=\"none\" stroke=\"#e41a1c\" stroke-width=\"2.2\"/>"
                );
            } else if j.curvature_jump.is_some_and(|v| v >= 0.05) {
                let _ = write!(
                    svg,
                    "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"4.5\" fill=\"none\" stroke=\"#ff9f40\" stroke-width=\"1.2\"/>"
                );
            }
        }
    }
    svg.push_str("</svg>");
    let segs: usize = check.contours.iter().map(|c| c.segments.len()).sum();
    let mono: usize = check.contours.iter().map(|c| c.monotone_count()).sum();
    let mut cap = format!(
        "<b>{}</b><br>{segs} segments, {mono} monotone; {extrema} extrema, {inflections} inflections",
        esc(&shape.name)
    );
    for f in check.findings.iter().take(3) {
        let _ = write!(
            cap,
            "<br>{}: contour {}, segment {}",
            esc(&f.message),
            f.contour,
            f.segment
        );
    }
    if check.findings.len() > 3 {
        let _ = write!(cap, "<br>and {} more", check.findings.len() - 3);
    }
    format!("<figure>{svg}<figcaption>{cap}</figcaption></figure>\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_report_shows_the_worst_shapes_first_and_no_more_than_asked() {
        // A straight line (nothing to flag) and a polyline with a 1.1° kink (a near-break).
        let svg = br#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">
            <path id="straight" d="M 10 10 L 50 10"/>
            <path id="kink&amp;co" d="M 0 50 L 50 50 L 100 51"/></svg>"#;
        let o = crate::outline_io::read_svg(svg).unwrap();
        let shapes: Vec<&Shape> = o.shapes.iter().collect();
        let opts = crate::outline_io::options_for(&o);
        let checked = crate::outline_io::check_shapes(&shapes, &opts, &|| {});
        let page = outline_report("two <shapes>", false, &shapes, &checked, 10);
        assert!(page.contains("two &lt;shapes&gt;") && !page.contains("two <shapes>"));
        let (kink, straight) = (page.find("kink&amp;co"), page.find("straight"));
        assert!(kink.is_some() && straight.is_some());
        assert!(kink < straight, "the kinked path first");
        let one = outline_report("one", false, &shapes, &checked, 1);
        assert!(one.contains("kink&amp;co") && !one.contains("straight"));
        assert_eq!(esc("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
    }
}
