//! The HTML page of `aecurve fix --report`: per changed glyph or path, the worst before
//! first, the outline before and after side by side at the same scale, each with its
//! curvature comb, the moved control points marked in a colour of their own with their
//! handle lines, and the joins' counts under the pictures. No script: a static page.
//!
//! The comb's scale is per contour (`CombScale`), the same before and after so that the
//! two compare: a tooth at the contour's typical curvature (its 90th percentile by arc
//! length) is an eighth of the contour's size, and teeth past 1.5 times that are cut and
//! drawn thin in orange. One scale for the whole glyph let a sharp point flatten every
//! other comb of the glyph, and the small contours of a perthousand or an oe fill with
//! teeth scaled to the large ones.

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
         <span style=\"color:#3182bd\">curvature comb (scaled per contour, the same before and after: a step in it at a join is a curvature jump)</span>\
         <span style=\"color:{CUT}\">comb teeth cut at 1.5 times the contour's typical length</span>\
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
/// picture's, and per contour the comb's scale.
struct Frame {
    centre: Point,
    scale: f64,
    y_up: bool,
    combs: Vec<CombScale>,
}

/// One contour's comb: the tooth length per unit of curvature, and the longest tooth drawn
/// (outline units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct CombScale {
    pub(crate) tooth: f64,
    pub(crate) longest: f64,
}

/// A tooth at the contour's typical curvature, over the contour's size.
const TOOTH_OF_SIZE: f64 = 0.125;

/// The longest tooth drawn, over the typical one.
const LONGEST_TOOTH: f64 = 1.5;

/// The cut teeth's colour.
const CUT: &str = "#ff7f0e";

impl CombScale {
    /// The scale of one contour, from its segments before and after (either may be
    /// missing): its typical curvature the 90th percentile of |κ| by arc length over both.
    pub(crate) fn of(contours: &[&[Vec<Point>]]) -> CombScale {
        let (x0, x1, y0, y1) = extent(contours.iter().flat_map(|c| c.iter()).flatten());
        let size = (x1 - x0).max(y1 - y0).max(1e-9);
        let mut ks: Vec<(f64, f64)> = Vec::new();
        for seg in contours.iter().flat_map(|c| c.iter()) {
            let q = samples(seg);
            for w in q.windows(2) {
                let k = w[0].1.abs();
                if k.is_finite() {
                    ks.push((k, (w[1].0 - w[0].0).hypot()));
                }
            }
        }
        let typical = crate::plot::weighted_quantile(&mut ks, 0.9).unwrap_or(0.0);
        let nominal = TOOTH_OF_SIZE * size;
        CombScale {
            tooth: if typical > 0.0 {
                nominal / typical
            } else {
                0.0
            },
            longest: LONGEST_TOOTH * nominal,
        }
    }

    /// The tooth at curvature `k` (signed, outline units) and whether it was cut.
    fn tooth(&self, k: f64) -> (f64, bool) {
        let t = k * self.tooth;
        if t.abs() > self.longest {
            (self.longest.copysign(t), true)
        } else {
            (t, false)
        }
    }
}

impl Frame {
    fn of(f: &FixFigure, y_up: bool) -> Frame {
        let (x0, x1, y0, y1) = extent(f.before.iter().chain(&f.after).flatten().flatten());
        let size = (x1 - x0).max(y1 - y0).max(1e-9);
        let pad = 0.2 * size;
        let n = f.before.len().max(f.after.len());
        let combs = (0..n)
            .map(|ci| {
                let both: Vec<&[Vec<Point>]> = [f.before.get(ci), f.after.get(ci)]
                    .into_iter()
                    .flatten()
                    .map(|c| c.as_slice())
                    .collect();
                CombScale::of(&both)
            })
            .collect();
        Frame {
            centre: Point::new(0.5 * (x0 + x1), 0.5 * (y0 + y1)),
            scale: (W - 10.0) / (size + 2.0 * pad),
            y_up,
            combs,
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

/// The box of `points`: (x min, x max, y min, y max).
fn extent<'a>(points: impl Iterator<Item = &'a Point>) -> (f64, f64, f64, f64) {
    points.fold(
        (f64::MAX, f64::MIN, f64::MAX, f64::MIN),
        |(x0, x1, y0, y1), p| (x0.min(p.x), x1.max(p.x), y0.min(p.y), y1.max(p.y)),
    )
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
    let (mut teeth, mut cut) = (String::new(), String::new());
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
            let scale = fr.combs.get(ci).copied().unwrap_or(CombScale {
                tooth: 0.0,
                longest: 0.0,
            });
            let teeth_at: Vec<(f64, bool)> = q.iter().map(|(_, k, _)| scale.tooth(*k)).collect();
            let tips: Vec<(f64, f64)> = q
                .iter()
                .zip(&teeth_at)
                .map(|((p, _, n), (t, _))| fr.map(*p - *n * *t))
                .collect();
            for (k, ((p, ..), t)) in q.iter().zip(&tips).enumerate() {
                let cut_here = teeth_at[k].1;
                if k % 2 == 0 {
                    let (x, y) = fr.map(*p);
                    let path = if cut_here { &mut cut } else { &mut teeth };
                    let _ = write!(path, "M{x:.1},{y:.1}L{:.1},{:.1}", t.0, t.1);
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
         <path d=\"{cut}\" fill=\"none\" stroke=\"{CUT}\" stroke-width=\"0.4\"/>\
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A circle of radius `r` about `c` as four cubics.
    fn circle(c: Point, r: f64) -> Vec<Vec<Point>> {
        let k = 0.552_284_749_8 * r;
        let q = |a: f64| {
            let (s, co) = a.sin_cos();
            (
                c + aesthetic_curves::Vec2::new(co, s) * r,
                aesthetic_curves::Vec2::new(-s, co) * k,
            )
        };
        (0..4)
            .map(|i| {
                let a = std::f64::consts::FRAC_PI_2 * i as f64;
                let ((p0, t0), (p3, t3)) = (q(a), q(a + std::f64::consts::FRAC_PI_2));
                vec![p0, p0 + t0, p3 - t3, p3]
            })
            .collect()
    }

    #[test]
    fn each_contour_gets_teeth_of_its_own_size_and_a_sharp_point_is_cut() {
        // A glyph of a large bowl and a small dot: each comb an eighth of its own contour.
        let bowl = circle(Point::new(0.0, 0.0), 400.0);
        let dot = circle(Point::new(600.0, 0.0), 20.0);
        for (c, r) in [(&bowl, 400.0), (&dot, 20.0)] {
            let s = CombScale::of(&[c.as_slice()]);
            let typical = s.tooth / r;
            assert!(
                (typical - TOOTH_OF_SIZE * 2.0 * r).abs() < 0.02 * r,
                "radius {r}: tooth {typical}"
            );
            assert!(!s.tooth(1.0 / r).1);
        }
        // The bowl with one corner rounded to a tiny radius (a sharp point): its scale
        // follows the bowl's own curvature, and the point's teeth are cut.
        let mut sharp = bowl.clone();
        let p = sharp[0][3];
        sharp[0][2] = p + aesthetic_curves::Vec2::new(2.0, -1.0);
        sharp[1][1] = p + aesthetic_curves::Vec2::new(-1.0, 2.0);
        let s = CombScale::of(&[sharp.as_slice()]);
        let ks: Vec<f64> = sharp
            .iter()
            .flat_map(|seg| samples(seg))
            .map(|(_, k, _)| k.abs())
            .collect();
        let kmax = ks.iter().cloned().fold(0.0, f64::max);
        assert!(kmax > 50.0 / 400.0, "the point is sharp: {kmax}");
        let (t, cut) = s.tooth(kmax);
        assert!(cut && (t.abs() - s.longest).abs() < 1e-9);
        assert!(s.longest <= LONGEST_TOOTH * TOOTH_OF_SIZE * 800.0 * 1.01);
        // Most of the bowl's teeth are still drawn at full length (not flattened by the
        // point): the median curvature's tooth is over a twentieth of the size.
        let mut sorted = ks.clone();
        sorted.sort_by(f64::total_cmp);
        let median = sorted[sorted.len() / 2];
        assert!(
            s.tooth(median).0.abs() > 800.0 / 20.0,
            "{}",
            s.tooth(median).0
        );
    }
}
