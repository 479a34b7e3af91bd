//! Outline readers for `aecurve check`: fonts (TrueType and OpenType/CFF, with `skrifa`) and
//! SVG (paths, basic shapes and transforms resolved, with `usvg`). Each file becomes named
//! shapes (glyph names, SVG element ids) of contours of Bézier segments, in the file's own
//! coordinates (font units; SVG user units with y down, as the file has them).
//!
//! Bad input is a clear error, never a panic: a file over [`MAX_FILE_BYTES`] is refused
//! before it is read, a truncated or foreign file says what it is not, a glyph that cannot be
//! drawn is reported with its name and the others are read.

use aesthetic_curves::outline::{check_contour, findings, ContourCheck, Finding, OutlineOptions};
use aesthetic_curves::{Point, RationalBezier};
use anyhow::{bail, Context, Result};
use skrifa::instance::{LocationRef, Size};
use skrifa::outline::{DrawSettings, OutlinePen};
use skrifa::{FontRef, GlyphId, MetadataProvider};
use std::path::Path;

/// Largest file `aecurve check` reads (bytes): a font or drawing beyond this is refused.
pub const MAX_FILE_BYTES: u64 = 64 * 1024 * 1024;

/// A contour: consecutive segments, each starting where the previous one ends.
#[derive(Clone, Debug, Default)]
pub struct Contour {
    /// The segments (lines are degree 1).
    pub segments: Vec<RationalBezier>,
    /// Whether it closes on its start.
    pub closed: bool,
}

/// A named shape: a glyph or an SVG path.
#[derive(Clone, Debug)]
pub struct Shape {
    /// Glyph name or element id (or `path N` when the element has none).
    pub name: String,
    /// Its contours.
    pub contours: Vec<Contour>,
}

/// What a file held.
#[derive(Clone, Debug)]
pub struct Outlines {
    /// "font" or "svg".
    pub kind: &'static str,
    /// The shapes, in file order (glyph id order for a font).
    pub shapes: Vec<Shape>,
    /// Shapes that could not be read: name and why.
    pub unreadable: Vec<(String, String)>,
}

/// Collects pen commands into contours.
#[derive(Default)]
struct Collector {
    contours: Vec<Contour>,
    current: Contour,
    start: Point,
    at: Point,
    bad: Option<String>,
}

impl Collector {
    fn push(&mut self, pts: Vec<Point>) {
        if self.bad.is_some() {
            return;
        }
        let n = pts.len();
        match RationalBezier::new(pts, vec![1.0; n]) {
            Ok(c) => self.current.segments.push(c),
            Err(e) => self.bad = Some(e.to_string()),
        }
    }
    fn move_to(&mut self, p: Point) {
        self.finish(false);
        self.start = p;
        self.at = p;
    }
    fn line_to(&mut self, p: Point) {
        self.push(vec![self.at, p]);
        self.at = p;
    }
    fn quad_to(&mut self, c: Point, p: Point) {
        self.push(vec![self.at, c, p]);
        self.at = p;
    }
    fn cubic_to(&mut self, c0: Point, c1: Point, p: Point) {
        self.push(vec![self.at, c0, c1, p]);
        self.at = p;
    }
    fn close(&mut self) {
        // The closing line, unless the contour already ends on its start.
        if self.at != self.start {
            self.line_to(self.start);
        }
        self.finish(true);
        self.at = self.start;
    }
    fn finish(&mut self, closed: bool) {
        if !self.current.segments.is_empty() {
            self.current.closed = closed;
            self.contours.push(std::mem::take(&mut self.current));
        }
    }
    fn done(mut self) -> std::result::Result<Vec<Contour>, String> {
        self.finish(false);
        match self.bad {
            Some(b) => Err(b),
            None => Ok(self.contours),
        }
    }
}

impl OutlinePen for Collector {
    fn move_to(&mut self, x: f32, y: f32) {
        Collector::move_to(self, Point::new(x as f64, y as f64));
    }
    fn line_to(&mut self, x: f32, y: f32) {
        Collector::line_to(self, Point::new(x as f64, y as f64));
    }
    fn quad_to(&mut self, cx0: f32, cy0: f32, x: f32, y: f32) {
        let p = |x: f32, y: f32| Point::new(x as f64, y as f64);
        Collector::quad_to(self, p(cx0, cy0), p(x, y));
    }
    fn curve_to(&mut self, cx0: f32, cy0: f32, cx1: f32, cy1: f32, x: f32, y: f32) {
        let p = |x: f32, y: f32| Point::new(x as f64, y as f64);
        Collector::cubic_to(self, p(cx0, cy0), p(cx1, cy1), p(x, y));
    }
    fn close(&mut self) {
        Collector::close(self);
    }
}

/// Read a font or an SVG file by its extension (`.ttf`, `.otf`, `.svg`).
pub fn read(path: &Path) -> Result<Outlines> {
    let len = std::fs::metadata(path)
        .with_context(|| format!("reading {}", path.display()))?
        .len();
    if len > MAX_FILE_BYTES {
        bail!(
            "{}: {len} bytes, over the {} MB that `check` reads",
            path.display(),
            MAX_FILE_BYTES / (1024 * 1024)
        );
    }
    let data = std::fs::read(path).with_context(|| format!("reading {}", path.display()))?;
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    match ext.as_str() {
        "ttf" | "otf" => read_font(&data).with_context(|| format!("{}", path.display())),
        "svg" => read_svg(&data).with_context(|| format!("{}", path.display())),
        _ => bail!(
            "{}: not a file `check` reads (.ttf, .otf, .svg)",
            path.display()
        ),
    }
}

/// Every glyph of a TrueType or OpenType/CFF font, unhinted, in font units.
pub fn read_font(data: &[u8]) -> Result<Outlines> {
    let font = FontRef::new(data).map_err(|e| anyhow::anyhow!("not a readable font: {e}"))?;
    let names = font.glyph_names();
    let outlines = font.outline_glyphs();
    let count = names.num_glyphs();
    let mut shapes = Vec::with_capacity(count as usize);
    let mut unreadable = Vec::new();
    for gid in 0..count {
        let id = GlyphId::new(gid);
        let name = names
            .get(id)
            .map(|n| n.as_str().to_string())
            .unwrap_or_else(|| format!("gid{gid}"));
        let Some(glyph) = outlines.get(id) else {
            unreadable.push((name, "no outline".into()));
            continue;
        };
        let mut pen = Collector::default();
        let settings = DrawSettings::unhinted(Size::unscaled(), LocationRef::default());
        if let Err(e) = glyph.draw(settings, &mut pen) {
            unreadable.push((name, e.to_string()));
            continue;
        }
        match pen.done() {
            Ok(contours) => shapes.push(Shape { name, contours }),
            Err(e) => unreadable.push((name, e)),
        }
    }
    if count == 0 {
        bail!("not a readable font: it has no glyphs (a truncated or damaged file?)");
    }
    Ok(Outlines {
        kind: "font",
        shapes,
        unreadable,
    })
}

/// Every path of an SVG document (basic shapes and text-free groups resolved by usvg), with
/// its transforms applied.
pub fn read_svg(data: &[u8]) -> Result<Outlines> {
    let tree = usvg::Tree::from_data(data, &usvg::Options::default())
        .map_err(|e| anyhow::anyhow!("not a readable SVG document: {e}"))?;
    let mut shapes = Vec::new();
    fn walk(g: &usvg::Group, shapes: &mut Vec<Shape>) {
        for node in g.children() {
            match node {
                usvg::Node::Group(g) => walk(g, shapes),
                usvg::Node::Path(p) => {
                    let t = p.abs_transform();
                    let map = |q: usvg::tiny_skia_path::Point| {
                        let mut q = q;
                        t.map_point(&mut q);
                        Point::new(q.x as f64, q.y as f64)
                    };
                    let mut pen = Collector::default();
                    use usvg::tiny_skia_path::PathSegment as S;
                    for seg in p.data().segments() {
                        match seg {
                            S::MoveTo(a) => pen.move_to(map(a)),
                            S::LineTo(a) => pen.line_to(map(a)),
                            S::QuadTo(a, b) => pen.quad_to(map(a), map(b)),
                            S::CubicTo(a, b, c) => pen.cubic_to(map(a), map(b), map(c)),
                            S::Close => pen.close(),
                        }
                    }
                    let name = if p.id().is_empty() {
                        format!("path {}", shapes.len() + 1)
                    } else {
                        p.id().to_string()
                    };
                    if let Ok(contours) = pen.done() {
                        shapes.push(Shape { name, contours });
                    }
                }
                _ => {}
            }
        }
    }
    walk(tree.root(), &mut shapes);
    if shapes.is_empty() {
        bail!("the SVG document has no path");
    }
    Ok(Outlines {
        kind: "svg",
        shapes,
        unreadable: Vec::new(),
    })
}

/// The check of one shape.
#[derive(Clone, Debug)]
pub struct ShapeCheck<'a> {
    /// The shape's name.
    pub name: &'a str,
    /// Per contour.
    pub contours: Vec<ContourCheck>,
    /// Its places worth a look, worst first.
    pub findings: Vec<Finding>,
}

/// The options for a file: fonts store integer units, so a smooth join rounded to them
/// breaks by up to about 1 / handle length.
pub fn options_for(outlines: &Outlines) -> OutlineOptions {
    OutlineOptions {
        grid: if outlines.kind == "font" { 1.0 } else { 0.0 },
        ..OutlineOptions::default()
    }
}

/// Check `shapes` (in parallel), calling `tick` once per shape (a progress bar).
pub fn check_shapes<'a>(
    shapes: &[&'a Shape],
    opts: &OutlineOptions,
    tick: &(dyn Fn() + Sync),
) -> Vec<ShapeCheck<'a>> {
    use rayon::prelude::*;
    shapes
        .par_iter()
        .map(|s| {
            tick();
            let contours: Vec<ContourCheck> = s
                .contours
                .iter()
                .map(|c| check_contour(&c.segments, c.closed, opts))
                .collect();
            let findings = findings(&contours, opts);
            ShapeCheck {
                name: &s.name,
                contours,
                findings,
            }
        })
        .collect()
}
