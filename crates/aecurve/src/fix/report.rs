//! The HTML page of `aecurve fix --report`: per changed glyph or path, the worst before
//! first, the outline before and after side by side at the same scale, each with its
//! curvature comb (one tooth scale for both, so the combs compare), the moved control
//! points marked in a colour of their own with their handle lines, and the joins' counts
//! under the pictures. No script: a static page.

use crate::report::esc;
use aesthetic_curves::{Bezier, Curve, Point};
use std::fmt::Write;

/// One figure: a shape's contours before and after (per contour, per segment, its control
/// points: 2 for a line, 4 for a cubic) and the caption's lines.
pub struct FixFigure {
    /// Glyph name or path id.
    pub name: String,
    /// Before.
    pub before: Vec<Vec<Vec<Point>>>,
    /// After (the same structure).
    pub after: Vec<Vec<Vec<Point>>>,
    /// Smooth joins between cubics, and of those under a 1 % jump before and after.
    pub joins: (usize, usize, usize),
    /// Largest distance a point moved.
    pub moved: f64,
}

const W: f64 = 280.0;
/// The moved points' colour.
const MOVED: &str = "#c2189b";

/// The page: `figures` in order, of `total` changed shapes.
pub fn fix_report(title: &str, y_up: bool, figures: &[FixFigure], total: usize) -> String {
    let mut html = crate::report::page_start(
        title,
        "figure{margin:0;border:1px solid #ddd;padding:6px}\
         .pair{display:flex;gap:4px} .pair div{font-size:11px;color:#666;text-align:center}",
    );
    let _ = write!(
        html,
        "<p class=\"key\"><span style=\"color:#d62728\">outline</span>\
         <span style=\"color:#3182bd\">curvature comb (one scale for before and after: a step in it at a join is a curvature jump)</span>\
         <span style=\"color:{MOVED}\">&#9679; moved control point, its handle</span></p>\n\
         <p>{total} shapes changed; {n} drawn, the most joins brought under a 1 % curvature \
         jump first.</p>\n<div class=\"grid\">\n",
        n = figures.len(),
    );
    for f in figures {
        html.push_str(&figure(f, y_up));
    }
    html.push_str("</div>\n</body></html>\n");
    html
}

/// The frame both pictures of a figure share: a map from outline coordinates to the
/// picture's, and the comb's tooth length per unit of curvature.
struct Frame {
    centre: Point,
    scale: f64,
    y_up: bool,
    tooth: f64,
}

impl Frame {
    fn of(f: &FixFigure, y_up: bool) -> Frame {
        let all = f.before.iter().chain(&f.after).flatten().flatten();
        let (mut x0, mut y0, mut x1, mut y1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
        for p in all {
            (x0, x1, y0, y1) = (x0.min(p.x), x1.max(p.x), y0.min(p.y), y1.max(p.y));
        }
        let size = (x1 - x0).max(y1 - y0).max(1e-9);
        let pad = 0.2 * size;
        let kmax = f
            .before
            .iter()
            .chain(&f.after)
            .flatten()
            .flat_map(|s| samples(s))
            .fold(0.0f64, |m, (_, k, _)| m.max(k.abs()));
        Frame {
            centre: Point::new(0.5 * (x0 + x1), 0.5 * (y0 + y1)),
            scale: (W - 10.0) / (size + 2.0 * pad),
            y_up,
            tooth: if kmax > 0.0 { size / 6.0 / kmax } else { 0.0 },
        }
    }

    fn map(&self, p: Point) -> (f64, f64) {
        let x = W / 2.0 + (p.x - self.centre.x) * self.scale;
        let dy = (p.y - self.centre.y) * self.scale;
        (
            x,
            if self.y_up {
                W / 2.0 - dy
            } else {
                W / 2.0 + dy
            },
        )
    }
}

/// Points of a segment with their curvature and unit normal (none for a line).
fn samples(seg: &[Point]) -> Vec<(Point, f64, aesthetic_curves::Vec2)> {
    if seg.len() != 4 {
        return Vec::new();
    }
    let Ok(b) = Bezier::new(seg.to_vec()) else {
        return Vec::new();
    };
    b.curve_points(32)
        .map(|q| q.iter().map(|c| (c.p, c.kappa, c.normal())).collect())
        .unwrap_or_default()
}

/// One picture: the outline, its comb, and (after) the moved points.
fn picture(contours: &[Vec<Vec<Point>>], input: Option<&[Vec<Vec<Point>>]>, fr: &Frame) -> String {
    let (mut outline, mut comb, mut moved) = (String::new(), String::new(), String::new());
    let mut teeth = String::new();
    for (ci, c) in contours.iter().enumerate() {
        for (si, s) in c.iter().enumerate() {
            let (x, y) = fr.map(s[0]);
            let _ = write!(outline, "M{x:.1},{y:.1}");
            let m: Vec<(f64, f64)> = s.iter().map(|p| fr.map(*p)).collect();
            if s.len() == 4 {
                let _ = write!(
                    outline,
                    "C{:.1},{:.1} {:.1},{:.1} {:.1},{:.1}",
                    m[1].0, m[1].1, m[2].0, m[2].1, m[3].0, m[3].1
                );
            } else {
                let _ = write!(outline, "L{:.1},{:.1}", m[m.len() - 1].0, m[m.len() - 1].1);
            }
            let q = samples(s);
            let tips: Vec<(f64, f64)> = q
                .iter()
                .map(|(p, k, n)| fr.map(*p - *n * (k * fr.tooth)))
                .collect();
            for (k, ((p, ..), t)) in q.iter().zip(&tips).enumerate() {
                if k % 2 == 0 {
                    let (x, y) = fr.map(*p);
                    let _ = write!(teeth, "M{x:.1},{y:.1}L{:.1},{:.1}", t.0, t.1);
                }
            }
            for (k, t) in tips.iter().enumerate() {
                let _ = write!(
                    comb,
                    "{}{:.1},{:.1}",
                    if k == 0 { "M" } else { "L" },
                    t.0,
                    t.1
                );
            }
            let Some(before) = input.and_then(|i| i.get(ci)).and_then(|c| c.get(si)) else {
                continue;
            };
            for (k, (p, p0)) in s.iter().zip(before).enumerate() {
                if p == p0 {
                    continue;
                }
                let (x, y) = fr.map(*p);
                // The handle line to the on-curve point it belongs to.
                let anchor = if k == 1 {
                    Some(s[0])
                } else if k == 2 {
                    Some(s[3])
                } else {
                    None
                };
                if let Some(a) = anchor.filter(|_| s.len() == 4) {
                    let (u, v) = fr.map(a);
                    let _ = write!(moved, "<path d=\"M{u:.1},{v:.1}L{x:.1},{y:.1}\" stroke=\"{MOVED}\" stroke-width=\"1\"/>");
                }
                let _ = write!(
                    moved,
                    "<circle cx=\"{x:.1}\" cy=\"{y:.1}\" r=\"2.6\" fill=\"{MOVED}\"/>"
                );
            }
        }
    }
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{W}\" height=\"{W}\" viewBox=\"0 0 {W} {W}\">\
         <path d=\"{teeth}\" fill=\"none\" stroke=\"#c6dbef\" stroke-width=\"0.6\"/>\
         <path d=\"{comb}\" fill=\"none\" stroke=\"#3182bd\" stroke-width=\"0.9\"/>\
         <path d=\"{outline}\" fill=\"none\" stroke=\"#d62728\" stroke-width=\"1.5\"/>{moved}</svg>"
    )
}

fn figure(f: &FixFigure, y_up: bool) -> String {
    let fr = Frame::of(f, y_up);
    let (n, u0, u1) = f.joins;
    format!(
        "<figure><div class=\"pair\"><div>{}<br>before</div><div>{}<br>after</div></div>\
         <figcaption><b>{}</b><br>{n} smooth joins between cubics: {u0} under a 1 % curvature \
         jump before, {u1} after; no outline moved more than {:.2}</figcaption></figure>\n",
        picture(&f.before, None, &fr),
        picture(&f.after, Some(&f.before), &fr),
        esc(&f.name),
        f.moved
    )
}
