//! The `aecurve` command-line tool as a library: the JSON protocol, the batch loop, the
//! benchmark of the monotonicity tests, plots and the demo gallery.

pub mod any_bezier;
pub mod atomic_out;
pub mod batch;
pub mod bench;
pub mod bench_targets;
pub mod cff_exact;
pub mod check_json;
pub mod contained;
pub mod editor;
/// The exports live in their own crate (shared with the Python package).
pub use aesthetic_curves_export as export;
pub mod fix;
pub mod json_out;
pub mod outline_io;
pub mod plot;
pub mod progress;
pub mod protocol;
pub mod regular_file;
pub mod report;
pub mod summary;
pub mod ufo_tree;

/// Parse `"x,y x,y ..."` (whitespace or `;` between points) into points.
pub fn parse_points(s: &str) -> anyhow::Result<Vec<aesthetic_curves::Point>> {
    s.split(|c: char| c.is_whitespace() || c == ';')
        .filter(|p| !p.is_empty())
        .map(|p| {
            let (x, y) = p
                .split_once(',')
                .ok_or_else(|| anyhow::anyhow!("point '{p}' is not of the form x,y"))?;
            let x: f64 = x
                .trim()
                .parse()
                .map_err(|_| anyhow::anyhow!("bad x in '{p}'"))?;
            let y: f64 = y
                .trim()
                .parse()
                .map_err(|_| anyhow::anyhow!("bad y in '{p}'"))?;
            anyhow::ensure!(x.is_finite() && y.is_finite(), "point '{p}' is not finite");
            Ok(aesthetic_curves::Point::new(x, y))
        })
        .collect()
}

/// Parse `"a b c"` or `"a,b,c"` into numbers.
pub fn parse_numbers(s: &str) -> anyhow::Result<Vec<f64>> {
    s.split(|c: char| c.is_whitespace() || c == ',' || c == ';')
        .filter(|p| !p.is_empty())
        .map(|p| {
            let v: f64 = p
                .parse()
                .map_err(|_| anyhow::anyhow!("'{p}' is not a number"))?;
            anyhow::ensure!(v.is_finite(), "'{p}' is not finite");
            Ok(v)
        })
        .collect()
}

/// Read an ordered point sequence from a file: CSV or whitespace-separated `x,y` / `x y`
/// rows (a header line, blank lines and `#` comments are skipped), or a JSON array of
/// `[x, y]` pairs. Errors name the line.
pub fn read_points_file(path: &std::path::Path) -> anyhow::Result<Vec<aesthetic_curves::Point>> {
    use anyhow::Context;
    let bytes = crate::outline_io::read_regular_file(path, crate::outline_io::MAX_FILE_BYTES)?;
    let text = String::from_utf8(bytes).map_err(|_| {
        anyhow::anyhow!(
            "{}: not a text file of points (it holds binary data: a font or an image?); \
             points are read from CSV or x y rows, a JSON array of [x, y] pairs, or SVG path \
             data",
            path.display()
        )
    })?;
    // The extension decides where it names a format; the content otherwise.
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let parsed = match ext.as_deref() {
        Some("svg") => svg_path_points(text.trim_start()),
        Some("json") => json_points(text.trim_start()),
        Some("csv") | Some("txt") | Some("tsv") => csv_points(&text),
        _ => parse_points_text(&text),
    };
    parsed.with_context(|| format!("in {}", path.display()))
}

/// Whether text is SVG path data: `M` or `m` followed by a coordinate (so a CSV header such
/// as `mx,my` is not taken for one).
fn is_path_data(t: &str) -> bool {
    let mut it = t.chars();
    matches!(it.next(), Some('M' | 'm'))
        && it
            .find(|c| !c.is_whitespace())
            .is_some_and(|c| c.is_ascii_digit() || matches!(c, '-' | '+' | '.'))
}

/// [`read_points_file`] on text: an SVG document or path data, a JSON array of pairs, or
/// CSV rows, recognised by their content.
pub fn parse_points_text(text: &str) -> anyhow::Result<Vec<aesthetic_curves::Point>> {
    let trimmed = text.trim_start();
    if trimmed.starts_with('<') || is_path_data(trimmed) {
        return svg_path_points(trimmed);
    }
    if trimmed.starts_with('[') {
        return json_points(trimmed);
    }
    csv_points(text)
}

/// A JSON array of `[x, y]` pairs.
fn json_points(trimmed: &str) -> anyhow::Result<Vec<aesthetic_curves::Point>> {
    let v: Vec<[f64; 2]> = serde_json::from_str(trimmed)
        .map_err(|e| anyhow::anyhow!("not a JSON array of [x, y] pairs: {e}"))?;
    anyhow::ensure!(
        v.iter().all(|p| p[0].is_finite() && p[1].is_finite()),
        "coordinates must be finite"
    );
    Ok(v.into_iter()
        .map(|p| aesthetic_curves::Point::new(p[0], p[1]))
        .collect())
}

/// CSV rows `x,y` (also `;`, tab or space separated), comments `#`, one header line.
fn csv_points(text: &str) -> anyhow::Result<Vec<aesthetic_curves::Point>> {
    let mut out = Vec::new();
    let mut header = false;
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line
            .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
            .filter(|f| !f.is_empty())
            .collect();
        let nums: Option<Vec<f64>> = fields.iter().map(|f| f.parse().ok()).collect();
        match nums {
            Some(v) if v.len() >= 2 => {
                anyhow::ensure!(
                    v[0].is_finite() && v[1].is_finite(),
                    "line {}: coordinates must be finite",
                    i + 1
                );
                out.push(aesthetic_curves::Point::new(v[0], v[1]));
            }
            // One header row (such as `x,y`) before the first point.
            _ if out.is_empty() && !header => header = true,
            _ => anyhow::bail!("line {}: expected 'x,y', got '{line}'", i + 1),
        }
    }
    Ok(out)
}

/// Points of an SVG path: the `d` data itself, or the first `d="..."` attribute of an SVG
/// document. Line segments give their end points (a pen stroke's samples); curved segments
/// are flattened to within 1e-4 of the path's size. Only the first subpath is read, in the
/// path's own coordinates (y down in SVG, not flipped).
pub fn svg_path_points(text: &str) -> anyhow::Result<Vec<aesthetic_curves::Point>> {
    let d = if text.starts_with('<') {
        let start = text
            .find(" d=\"")
            .or_else(|| text.find("\nd=\""))
            .ok_or_else(|| anyhow::anyhow!("no path d=\"...\" attribute in the SVG"))?
            + 4;
        let end = text[start..]
            .find('"')
            .ok_or_else(|| anyhow::anyhow!("unterminated d attribute"))?;
        &text[start..start + end]
    } else {
        text
    };
    let path = kurbo::BezPath::from_svg(d).map_err(|e| anyhow::anyhow!("SVG path: {e}"))?;
    let bbox = kurbo::Shape::bounding_box(&path);
    let size = bbox.width().hypot(bbox.height());
    anyhow::ensure!(
        size.is_finite() && size > 0.0,
        "the SVG path is empty or a point"
    );
    let mut out: Vec<aesthetic_curves::Point> = Vec::new();
    let mut subpaths = 0;
    kurbo::flatten(path, 1e-4 * size, |el| match el {
        kurbo::PathEl::MoveTo(p) => {
            subpaths += 1;
            if subpaths == 1 {
                out.push(p);
            }
        }
        kurbo::PathEl::LineTo(p) if subpaths == 1 => out.push(p),
        _ => {}
    });
    anyhow::ensure!(out.len() >= 2, "the SVG path has fewer than 2 points");
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_text_forms() {
        let a = parse_points_text("x,y\n1,2\n\n# c\n3 4\n").unwrap();
        assert_eq!(a.len(), 2);
        assert_eq!(a[1], aesthetic_curves::Point::new(3.0, 4.0));
        let b = parse_points_text(" [[1,2],[3,4.5]]").unwrap();
        assert_eq!(b[1].y, 4.5);
        assert!(parse_points_text("1,2\nfoo\n").is_err());
        assert!(parse_points_text("[[1,2],[3]]").is_err());
    }
}
