//! A `.glif` file with only its moved points' coordinates changed: the text of the file as
//! it was (element and attribute order, indentation, quoting, comments, number style), with
//! the `x` and `y` values of the points the fix moved replaced, and nothing else. A diff of
//! a fixed UFO shows exactly the lines of moved points.
//!
//! Points are matched by their place: the `n`-th `<contour>` of `<outline>` and its `k`-th
//! `<point>`, as norad numbers them (in a format 1 glif, a contour of one named `move` point
//! is an anchor and is not counted). A file whose structure does not match what norad read
//! is an error, and the glyph is written as it was.

use aesthetic_curves::Point;
use anyhow::{bail, Result};

/// One moved point: its contour and point index (as norad numbers them) and its new place.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Moved {
    /// The contour's index in the glyph's contours.
    pub contour: usize,
    /// The point's index in the contour.
    pub point: usize,
    /// The new coordinates.
    pub to: Point,
}

/// The glif text with the moved points' coordinates replaced. `contour_sizes` are the point
/// counts of norad's contours of the glyph (checked against the file's).
pub fn patch_glif(text: &str, contour_sizes: &[usize], moved: &[Moved]) -> Result<String> {
    let doc = crate::contained::contained(|| {
        roxmltree::Document::parse(text).map_err(|e| anyhow::anyhow!("not an XML document: {e}"))
    })?;
    let glyph = doc.root_element();
    let v1 = glyph.attribute("format") == Some("1");
    let Some(outline) = glyph.children().find(|n| n.has_tag_name("outline")) else {
        bail!("no <outline>, but the glyph has contours");
    };
    let contours: Vec<Vec<roxmltree::Node>> = outline
        .children()
        .filter(|n| n.has_tag_name("contour"))
        .map(|c| {
            c.children()
                .filter(|p| p.has_tag_name("point"))
                .collect::<Vec<_>>()
        })
        .filter(|pts| !(v1 && is_v1_anchor(pts)))
        .collect();
    let sizes: Vec<usize> = contours.iter().map(Vec::len).collect();
    if sizes != contour_sizes {
        bail!(
            "its contours in the file ({} of {:?} points) are not the ones read ({} of {:?})",
            sizes.len(),
            sizes,
            contour_sizes.len(),
            contour_sizes
        );
    }
    let mut edits: Vec<(std::ops::Range<usize>, String)> = Vec::new();
    for m in moved {
        let Some(node) = contours.get(m.contour).and_then(|c| c.get(m.point)) else {
            bail!(
                "point {} of contour {} is not in the file",
                m.point,
                m.contour
            );
        };
        for (name, v) in [("x", m.to.x), ("y", m.to.y)] {
            let Some(attr) = node.attributes().find(|a| a.name() == name) else {
                bail!("a point without {name}");
            };
            let old: f64 = attr.value().trim().parse().unwrap_or(f64::NAN);
            if old == v {
                continue;
            }
            let range = attr.range_value();
            if &text[range.clone()] != attr.value() {
                bail!("a coordinate written with a character reference: left as it is");
            }
            edits.push((range, number(v)));
        }
    }
    // A point shared by two segments (an on-curve point) is listed once per segment.
    edits.sort_by_key(|e| std::cmp::Reverse(e.0.start));
    edits.dedup_by(|a, b| a.0 == b.0);
    if edits.windows(2).any(|w| w[1].0.end > w[0].0.start) {
        bail!("two different moves of one coordinate");
    }
    let mut out = text.to_string();
    for (range, s) in edits {
        out.replace_range(range, &s);
    }
    Ok(out)
}

/// A format 1 glif's anchor: a contour of one named `move` point.
fn is_v1_anchor(points: &[roxmltree::Node]) -> bool {
    points.len() == 1
        && points[0].attribute("type") == Some("move")
        && points[0].attribute("name").is_some()
}

/// A coordinate in the shortest form that reads back as the same `f64`: an integer without
/// a point (`120`, `-3`), otherwise the shortest decimal, or the exponent form where that
/// is shorter (`1e308`, not 309 digits).
pub fn number(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let plain = format!("{v}");
    let exp = format!("{v:e}");
    if exp.len() < plain.len() {
        exp
    } else {
        plain
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_back_exactly_and_short() {
        for v in [
            120.0,
            -3.0,
            0.5,
            1e308,
            -2.5e-7,
            0.1 + 0.2,
            123456.789,
            5e15,
        ] {
            let s = number(v);
            assert_eq!(s.parse::<f64>().unwrap(), v, "{s}");
            assert!(s.len() <= 24, "{s}");
        }
        assert_eq!(number(120.0), "120");
        assert_eq!(number(-0.0), "0");
        assert_eq!(number(1e308), "1e308");
    }

    #[test]
    fn only_the_moved_coordinates_change() {
        let text = "<?xml version='1.0' encoding='UTF-8'?>\n<glyph name=\"o\" format=\"2\">\n  \
                    <advance width=\"500\"/>\n  <!-- keep me -->\n  <outline>\n    <contour>\n      \
                    <point x='10' y=\"0\" type=\"line\"/>\n      <point y=\"5\" x=\"20.50\"/>\n    \
                    </contour>\n  </outline>\n</glyph>\n";
        let moved = [Moved {
            contour: 0,
            point: 1,
            to: Point::new(21.0, 5.0),
        }];
        let out = patch_glif(text, &[2], &moved).unwrap();
        assert_eq!(out, text.replace("x=\"20.50\"", "x=\"21\""));
        assert!(patch_glif(text, &[3], &moved).is_err());
        // A point listed twice (shared by two segments) is written once.
        let twice = [moved[0], moved[0]];
        assert_eq!(patch_glif(text, &[2], &twice).unwrap(), out);
    }
}
