//! Outline readers for `aecurve check`: fonts (TrueType and OpenType/CFF, with `skrifa`; UFO
//! sources, with `norad`),
//! SVG (paths, basic shapes and transforms resolved, with `usvg`) and DXF (LINE, ARC, CIRCLE,
//! LWPOLYLINE with bulges, SPLINE with weights, with the `dxf` crate). Each file becomes
//! named shapes (glyph names, SVG element ids, DXF layer and handle) of contours of Bézier
//! segments, in the file's own coordinates (font units; SVG user units with y down, as the
//! file has them; DXF drawing units). Arcs and bulges become rational quadratics of at most
//! 90° each and splines their Bézier spans: exactly, no resampling. Open DXF entities of one
//! layer that meet end to end are chained into one contour (one shape), so the joins between
//! separate LINEs, ARCs and polylines are checked too.
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

/// Most segments one shape (a glyph, a path, a chain of entities) may have to be checked:
/// the check of a shape holds about 0.6 KB per segment until the shape is done, so this keeps
/// one shape's check near 300 MB. A larger shape is listed as unreadable with its count, not
/// checked (no design outline comes near: the largest glyphs of real fonts have a few
/// hundred segments).
pub const MAX_SHAPE_SEGMENTS: usize = 500_000;

/// The shapes of `o` with more than [`MAX_SHAPE_SEGMENTS`] segments moved to its unreadable
/// list, with their count and what to do.
fn within_limits(mut o: Outlines) -> Outlines {
    let count = |s: &Shape| s.contours.iter().map(|c| c.segments.len()).sum::<usize>();
    let (keep, over): (Vec<Shape>, Vec<Shape>) = std::mem::take(&mut o.shapes)
        .into_iter()
        .partition(|s| count(s) <= MAX_SHAPE_SEGMENTS);
    o.shapes = keep;
    o.unreadable.extend(over.into_iter().map(|s| {
        let why = format!(
            "{} segments: more than the {MAX_SHAPE_SEGMENTS} one shape may have to be checked \
             (about 0.6 KB of memory each); split it into smaller paths",
            count(&s)
        );
        (s.name, why)
    }));
    o
}

/// A contour: consecutive segments, each starting where the previous one ends.
#[derive(Clone, Debug, Default)]
pub struct Contour {
    /// The segments (lines are degree 1).
    pub segments: Vec<RationalBezier>,
    /// Whether it closes on its start.
    pub closed: bool,
    /// The source's smooth marks, per join: `smooth[i]` for the point after segment `i`
    /// (a UFO's `smooth="yes"`; implied on-curve points of quadratics are smooth). None
    /// where the source marks no points (binary fonts, SVG, DXF).
    pub smooth: Option<Vec<bool>>,
}

/// A named shape: a glyph or an SVG path.
#[derive(Clone, Debug)]
pub struct Shape {
    /// Glyph name or element id (or `path N` when the element has none).
    pub name: String,
    /// Its contours.
    pub contours: Vec<Contour>,
    /// The code points a font maps to the glyph (none for SVG and DXF paths).
    pub unicodes: Vec<u32>,
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
    /// The smooth mark of the point the last segment ends on, where the source has marks.
    fn mark(&mut self, smooth: bool) {
        if let Some(m) = &mut self.current.smooth {
            m.push(smooth);
        }
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

/// Read a font, an SVG or a DXF file by its extension (`.ttf`, `.otf`, `.svg`, `.dxf`), or
/// a UFO source (a `.ufo` folder). Only the file (or the folder's own regular files) is
/// read, into memory, at most [`MAX_FILE_BYTES`]: pipes, devices and sockets are refused
/// before they are opened, so nothing can block, and nothing the file names is resolved.
pub fn read(path: &Path) -> Result<Outlines> {
    let meta = std::fs::metadata(path).with_context(|| format!("reading {}", path.display()))?;
    if meta.is_dir() {
        anyhow::ensure!(
            path.extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("ufo")),
            "{}: a folder, and not a .ufo source",
            path.display()
        );
        return read_ufo(path).with_context(|| format!("{}", path.display()));
    }
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    let reader: fn(&[u8]) -> Result<Outlines> = match ext.as_str() {
        "ttf" | "otf" => read_font,
        "svg" => read_svg,
        "dxf" => read_dxf,
        _ => bail!(
            "{}: not a file `check` reads (.ttf, .otf, .svg, .dxf, or a .ufo folder)",
            path.display()
        ),
    };
    let data = read_regular_file(path, MAX_FILE_BYTES)?;
    // Each reader contains its parser's panics itself.
    reader(&data).with_context(|| format!("{}", path.display()))
}

pub use crate::regular_file::read_regular_file;

pub use crate::contained::contained;

impl crate::cff_exact::ExactPen for Collector {
    fn move_to(&mut self, p: Point) {
        Collector::move_to(self, p);
    }
    fn line_to(&mut self, p: Point) {
        Collector::line_to(self, p);
    }
    fn cubic_to(&mut self, a: Point, b: Point, p: Point) {
        Collector::cubic_to(self, a, b, p);
    }
    fn close(&mut self) {
        Collector::close(self);
    }
}

/// Every glyph of a TrueType or OpenType/CFF font, unhinted, in font units (CFF and CFF2
/// coordinates at their charstrings' full precision: [`crate::cff_exact`]). A glyph whose
/// name another glyph also has is named with its glyph id too (`uni00AD (gid 2584)`), so
/// each shape has its own name; a glyph the parser fails on (a panic inside it included) is
/// listed as unreadable, and the others are read.
pub fn read_font(data: &[u8]) -> Result<Outlines> {
    contained(|| read_font_inner(data)).map(within_limits)
}

fn read_font_inner(data: &[u8]) -> Result<Outlines> {
    let font = FontRef::new(data).map_err(|e| anyhow::anyhow!("not a readable font: {e}"))?;
    let names = font.glyph_names();
    let outlines = font.outline_glyphs();
    // CFF and CFF2 charstrings at their own precision (skrifa's unscaled drawing truncates
    // them to whole units); TrueType glyphs through skrifa, whose points are integers.
    let exact = crate::cff_exact::ExactCff::of(&font);
    let count = names.num_glyphs();
    if count == 0 {
        bail!("not a readable font: it has no glyphs (a truncated or damaged file?)");
    }
    let raw: Vec<String> = (0..count)
        .map(|gid| {
            names
                .get(GlyphId::new(gid))
                .map(|n| n.as_str().to_string())
                .unwrap_or_else(|| format!("gid{gid}"))
        })
        .collect();
    let mut seen = std::collections::HashMap::<&str, usize>::new();
    for n in &raw {
        *seen.entry(n.as_str()).or_default() += 1;
    }
    let mut codes = std::collections::HashMap::<u32, Vec<u32>>::new();
    for (cp, gid) in font.charmap().mappings() {
        codes.entry(gid.to_u32()).or_default().push(cp);
    }
    let mut shapes = Vec::with_capacity(count as usize);
    let mut unreadable = Vec::new();
    for gid in 0..count {
        let name = if seen[raw[gid as usize].as_str()] > 1 {
            format!("{} (gid {gid})", raw[gid as usize])
        } else {
            raw[gid as usize].clone()
        };
        let drawn = contained(|| {
            if let Some(cff) = &exact {
                let mut pen = Collector::default();
                let drawn = cff
                    .draw(gid, &mut pen)
                    .map_err(|e| anyhow::anyhow!("glyph {gid}: {e}"))?;
                if drawn {
                    return pen.done().map_err(|e| anyhow::anyhow!("glyph {gid}: {e}"));
                }
            }
            let glyph = outlines
                .get(GlyphId::new(gid))
                .ok_or_else(|| anyhow::anyhow!("glyph {gid}: {}", why_no_outline(&font, gid)))?;
            let mut pen = Collector::default();
            let settings = DrawSettings::unhinted(Size::unscaled(), LocationRef::default());
            glyph
                .draw(settings, &mut pen)
                .map_err(|e| anyhow::anyhow!("glyph {gid}: {e}"))?;
            pen.done().map_err(|e| anyhow::anyhow!("glyph {gid}: {e}"))
        });
        match drawn {
            Ok(contours) => shapes.push(Shape {
                name,
                contours,
                unicodes: codes.remove(&gid).unwrap_or_default(),
            }),
            Err(e) => unreadable.push((name, format!("{e:#}"))),
        }
    }
    Ok(Outlines {
        kind: "font",
        shapes,
        unreadable,
    })
}

/// usvg options that resolve nothing outside the document: every `<image>` (a file, a URL
/// or embedded data) is refused and counted, fonts are not loaded (no text support).
fn svg_options(images: std::sync::Arc<std::sync::atomic::AtomicUsize>) -> usvg::Options<'static> {
    use std::sync::atomic::Ordering;
    let (a, b) = (images.clone(), images);
    usvg::Options {
        resources_dir: None,
        image_href_resolver: usvg::ImageHrefResolver {
            resolve_data: Box::new(move |_, _, _| {
                a.fetch_add(1, Ordering::Relaxed);
                None
            }),
            resolve_string: Box::new(move |_, _| {
                b.fetch_add(1, Ordering::Relaxed);
                None
            }),
        },
        ..usvg::Options::default()
    }
}

/// Components the font reader follows (skrifa's limit, as FreeType's).
const COMPONENT_DEPTH_LIMIT: usize = 32;

/// Why the font reader gives no outline for glyph `gid`: a TrueType composite nested deeper
/// than it follows, or one whose components lead back to itself, or else a table it cannot
/// read.
fn why_no_outline(font: &FontRef, gid: u32) -> String {
    use skrifa::raw::tables::glyf::Glyph;
    use skrifa::raw::TableProvider;
    let (Ok(loca), Ok(glyf)) = (font.loca(None), font.glyf()) else {
        return "no outline in the font's tables (its outline table cannot be read)".into();
    };
    // Depth-first over the components: the deepest chain, and whether one comes back.
    let mut stack = vec![(GlyphId::new(gid), 0usize, vec![gid])];
    let mut deepest = 0;
    while let Some((g, depth, chain)) = stack.pop() {
        deepest = deepest.max(depth);
        if depth > COMPONENT_DEPTH_LIMIT || stack.len() > 10_000 {
            break;
        }
        if let Ok(Some(Glyph::Composite(c))) = loca.get_glyf(g, &glyf) {
            for comp in c.components() {
                let next = comp.glyph.to_u32();
                if chain.contains(&next) {
                    return format!(
                        "a composite whose components lead back to itself (through glyph \
                         {next}); break the loop in its components"
                    );
                }
                let mut longer = chain.clone();
                longer.push(next);
                stack.push((GlyphId::new(next), depth + 1, longer));
            }
        }
    }
    if deepest > COMPONENT_DEPTH_LIMIT {
        format!(
            "a composite nested more than {COMPONENT_DEPTH_LIMIT} deep (components of \
             components), more than the font reader follows; decompose it, or flatten its \
             components"
        )
    } else {
        "no outline in the font's tables (a damaged glyph record?)".into()
    }
}

/// Every path of an SVG document (basic shapes and text-free groups resolved by usvg), with
/// its transforms applied. Nothing outside the document is read: images are refused and
/// listed as unreadable. A path with coordinates that are not finite numbers after its
/// transforms is listed as unreadable with the reason, not dropped.
pub fn read_svg(data: &[u8]) -> Result<Outlines> {
    contained(|| read_svg_inner(data)).map(within_limits)
}

fn read_svg_inner(data: &[u8]) -> Result<Outlines> {
    let images = std::sync::Arc::new(std::sync::atomic::AtomicUsize::new(0));
    let tree = usvg::Tree::from_data(data, &svg_options(images.clone())).map_err(|e| {
        let msg = e.to_string();
        if msg.contains("nodes limit") {
            anyhow::anyhow!(
                "not a readable SVG document: its elements nest too deeply (the XML reader \
                 stops at 1024 levels) or are too many; flatten the groups"
            )
        } else {
            anyhow::anyhow!("not a readable SVG document: {msg}")
        }
    })?;
    let mut shapes = Vec::new();
    let mut unreadable = Vec::new();
    walk_svg(tree.root(), &mut shapes, &mut unreadable);
    list_dropped_elements(data, &shapes, &mut unreadable);
    let images = images.load(std::sync::atomic::Ordering::Relaxed);
    for i in 0..images {
        unreadable.push((
            format!("image {}", i + 1),
            "an <image>: images are never read (no file, URL or embedded data is resolved)".into(),
        ));
    }
    if shapes.is_empty() && unreadable.is_empty() {
        bail!("the SVG document has no path");
    }
    Ok(Outlines {
        kind: "svg",
        shapes,
        unreadable,
    })
}

/// The geometry elements of the document (outside definitions) that usvg dropped without
/// a word (invalid or non-finite geometry, zero size, not rendered): listed by id, the
/// unnamed ones counted, so nothing vanishes silently.
fn list_dropped_elements(data: &[u8], shapes: &[Shape], unreadable: &mut Vec<(String, String)>) {
    const GEOMETRY: [&str; 7] = [
        "path", "rect", "circle", "ellipse", "line", "polyline", "polygon",
    ];
    const DEFINITIONS: [&str; 7] = [
        "defs", "clipPath", "mask", "pattern", "marker", "symbol", "metadata",
    ];
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let opts = roxmltree::ParsingOptions {
        allow_dtd: true,
        ..Default::default()
    };
    let Ok(doc) = roxmltree::Document::parse_with_options(text, opts) else {
        return;
    };
    let known: std::collections::HashSet<&str> = shapes
        .iter()
        .map(|s| s.name.as_str())
        .chain(unreadable.iter().map(|u| u.0.as_str()))
        .collect();
    let mut missing = Vec::new();
    let mut unnamed = 0usize;
    for node in doc.descendants().filter(|n| n.is_element()) {
        if !GEOMETRY.contains(&node.tag_name().name())
            || node
                .ancestors()
                .skip(1)
                .any(|a| DEFINITIONS.contains(&a.tag_name().name()))
        {
            continue;
        }
        match node.attribute("id") {
            Some(id) if !id.is_empty() => {
                if !known.contains(id) {
                    missing.push(id.to_string());
                }
            }
            _ => unnamed += 1,
        }
    }
    let read_unnamed = shapes
        .iter()
        .filter(|s| s.name.starts_with("path "))
        .count()
        + unreadable
            .iter()
            .filter(|u| u.0.starts_with("path "))
            .count();
    let why = "the SVG reader (usvg) dropped this element: its geometry is invalid, not \
               finite, empty, or not rendered (display none, zero size)";
    for id in missing {
        unreadable.push((id, why.into()));
    }
    if unnamed > read_unnamed {
        let n = unnamed - read_unnamed;
        unreadable.push((
            format!("{n} unnamed element{}", if n == 1 { "" } else { "s" }),
            why.into(),
        ));
    }
}

fn walk_svg(g: &usvg::Group, shapes: &mut Vec<Shape>, unreadable: &mut Vec<(String, String)>) {
    for node in g.children() {
        match node {
            usvg::Node::Group(g) => walk_svg(g, shapes, unreadable),
            usvg::Node::Path(p) => {
                let name = if p.id().is_empty() {
                    format!("path {}", shapes.len() + unreadable.len() + 1)
                } else {
                    p.id().to_string()
                };
                match svg_path_contours(p) {
                    Ok(contours) => shapes.push(Shape {
                        name,
                        contours,
                        unicodes: Vec::new(),
                    }),
                    Err(e) => unreadable.push((name, e)),
                }
            }
            _ => {}
        }
    }
}

fn svg_path_contours(p: &usvg::Path) -> std::result::Result<Vec<Contour>, String> {
    let t = p.abs_transform();
    let mut bad = None;
    let mut map = |q: usvg::tiny_skia_path::Point| {
        let mut m = q;
        t.map_point(&mut m);
        if !(m.x.is_finite() && m.y.is_finite()) && bad.is_none() {
            bad = Some(format!(
                "a point ({}, {}) is not finite once transformed (coordinates or a transform \
                 beyond single precision's range)",
                q.x, q.y
            ));
        }
        Point::new(m.x as f64, m.y as f64)
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
    if let Some(b) = bad {
        return Err(b);
    }
    pen.done()
}

/// Every glyph of a UFO source's default layer (with `norad`, from the folder read whole
/// and confined to it: [`crate::ufo_tree`]), in font units, in name order. Contours are
/// read from the UFO point stream: `line`, `curve` (cubic, or a line or a quadratic with
/// fewer off-curve points), `qcurve` (TrueType quadratics with implied on-curve points,
/// also a contour of off-curve points alone). Components are drawn through their base
/// glyphs and transforms, as a font reader draws composites; a component whose base is
/// missing, or that names itself through its bases, is listed as unreadable with the
/// glyph's name, and the glyph's other contours are read.
pub fn read_ufo(path: &Path) -> Result<Outlines> {
    let tree = crate::ufo_tree::UfoTree::read(path, MAX_FILE_BYTES)?;
    let font = tree.font()?;
    let layer = font.default_layer();
    let mut shapes = Vec::new();
    let mut unreadable = Vec::new();
    let mut glyphs: Vec<_> = layer.iter().collect();
    glyphs.sort_by(|a, b| a.name().as_str().cmp(b.name().as_str()));
    for g in glyphs {
        let name = g.name().as_str().to_string();
        let mut pen = Collector::default();
        let mut trouble = Vec::new();
        draw_glyph(layer, g, &IDENTITY, &mut Vec::new(), &mut pen, &mut trouble);
        match pen.done() {
            Ok(contours) => shapes.push(Shape {
                name: name.clone(),
                contours,
                unicodes: g.codepoints.iter().map(|c| c as u32).collect(),
            }),
            Err(e) => unreadable.push((name.clone(), e)),
        }
        if !trouble.is_empty() {
            unreadable.push((name, trouble.join("; ")));
        }
    }
    if shapes.is_empty() && unreadable.is_empty() {
        bail!("not a readable UFO: its default layer has no glyphs");
    }
    Ok(within_limits(Outlines {
        kind: "font",
        shapes,
        unreadable,
    }))
}

/// An affine map `(xx, xy, yx, yy, dx, dy)` as a UFO component's transform holds it.
type Affine = [f64; 6];
const IDENTITY: Affine = [1.0, 0.0, 0.0, 1.0, 0.0, 0.0];

/// Components nested deeper than this are refused (fonts nest two or three).
const MAX_COMPONENT_DEPTH: usize = 32;

/// A glyph's contours and, through their bases, its components' into the pen, mapped by
/// `m`; `path` is the chain of bases being drawn (a base already on it is a cycle); what
/// cannot be drawn goes to `trouble`.
fn draw_glyph(
    layer: &norad::Layer,
    g: &norad::Glyph,
    m: &Affine,
    path: &mut Vec<String>,
    pen: &mut Collector,
    trouble: &mut Vec<String>,
) {
    for c in &g.contours {
        if *m == IDENTITY {
            ufo_contour(&c.points, pen);
        } else {
            let moved: Vec<norad::ContourPoint> = (c.points.iter())
                .map(|q| {
                    let mut q = q.clone();
                    (q.x, q.y) = (
                        m[0] * q.x + m[2] * q.y + m[4],
                        m[1] * q.x + m[3] * q.y + m[5],
                    );
                    q
                })
                .collect();
            ufo_contour(&moved, pen);
        }
    }
    path.push(g.name().as_str().to_string());
    for comp in &g.components {
        let base = comp.base.as_str();
        let Some(bg) = layer.get_glyph(base) else {
            trouble.push(format!("its component's base glyph {base:?} is missing"));
            continue;
        };
        if path.iter().any(|p| p == base) {
            trouble.push(format!(
                "its component {base:?} names itself through its bases ({} -> {base})",
                path.join(" -> ")
            ));
            continue;
        }
        if path.len() >= MAX_COMPONENT_DEPTH {
            trouble.push(format!(
                "components nested more than {MAX_COMPONENT_DEPTH} deep"
            ));
            continue;
        }
        let t = &comp.transform;
        let c = [
            t.x_scale, t.xy_scale, t.yx_scale, t.y_scale, t.x_offset, t.y_offset,
        ];
        // m after c: a point p of the base goes to m(c(p)).
        let mc = [
            m[0] * c[0] + m[2] * c[1],
            m[1] * c[0] + m[3] * c[1],
            m[0] * c[2] + m[2] * c[3],
            m[1] * c[2] + m[3] * c[3],
            m[0] * c[4] + m[2] * c[5] + m[4],
            m[1] * c[4] + m[3] * c[5] + m[5],
        ];
        draw_glyph(layer, bg, &mc, path, pen, trouble);
    }
    path.pop();
}

/// One UFO contour into the pen.
fn ufo_contour(points: &[norad::ContourPoint], pen: &mut Collector) {
    use norad::PointType as T;
    if points.is_empty() {
        return;
    }
    let p = |q: &norad::ContourPoint| Point::new(q.x, q.y);
    let open = points[0].typ == T::Move;
    // A closed contour starts at its first on-curve point (rotated); one of off-curve
    // points alone is all implied quadratics.
    let start = if open {
        0
    } else {
        match points.iter().position(|q| q.typ != T::OffCurve) {
            Some(i) => i,
            None => {
                let n = points.len();
                let mid = |i: usize| p(&points[i]).midpoint(p(&points[(i + 1) % n]));
                pen.move_to(mid(n - 1));
                for (i, q) in points.iter().enumerate() {
                    pen.quad_to(p(q), mid(i));
                }
                pen.close();
                return;
            }
        }
    };
    let n = points.len();
    let order: Vec<&norad::ContourPoint> = (0..n).map(|k| &points[(start + k) % n]).collect();
    pen.move_to(p(order[0]));
    pen.current.smooth = Some(Vec::new());
    let mut off: Vec<Point> = Vec::new();
    // The on-curve points after the first, and (closed) the first again at the end.
    let rest = order[1..]
        .iter()
        .copied()
        .chain((!open).then_some(order[0]));
    for q in rest {
        match q.typ {
            T::OffCurve => off.push(p(q)),
            T::QCurve => {
                // Implied on-curve points halfway between consecutive off-curve ones.
                let end = p(q);
                match off.len() {
                    0 => {
                        pen.line_to(end);
                        pen.mark(q.smooth);
                    }
                    k => {
                        for i in 0..k {
                            let to = if i + 1 < k {
                                off[i].midpoint(off[i + 1])
                            } else {
                                end
                            };
                            pen.quad_to(off[i], to);
                            pen.mark(i + 1 < k || q.smooth);
                        }
                    }
                }
                off.clear();
            }
            _ => {
                let end = p(q);
                match off.len() {
                    0 => pen.line_to(end),
                    1 => pen.quad_to(off[0], end),
                    2 => pen.cubic_to(off[0], off[1], end),
                    _ => {
                        pen.bad = Some(format!(
                            "a curve point after {} off-curve points (at most 2)",
                            off.len()
                        ));
                    }
                }
                pen.mark(q.smooth);
                off.clear();
            }
        }
    }
    if open {
        pen.finish(false);
    } else {
        // The closing segment is drawn (back to the first point): close without another line.
        pen.finish(true);
        pen.at = pen.start;
    }
}

/// A circular arc about `c` of radius `r` from angle `a0` (radians) turning by `sweep`
/// (signed: positive counter-clockwise), as rational quadratics of at most 90° each.
pub fn arc(c: Point, r: f64, a0: f64, sweep: f64) -> Vec<RationalBezier> {
    let n = (sweep.abs() / std::f64::consts::FRAC_PI_2).ceil().max(1.0) as usize;
    let step = sweep / n as f64;
    let at = |a: f64| Point::new(c.x + r * a.cos(), c.y + r * a.sin());
    (0..n)
        .filter_map(|i| {
            let (s, e) = (a0 + step * i as f64, a0 + step * (i + 1) as f64);
            let half = 0.5 * step;
            let m = 0.5 * (s + e);
            let mid = Point::new(
                c.x + r / half.cos() * m.cos(),
                c.y + r / half.cos() * m.sin(),
            );
            RationalBezier::new(vec![at(s), mid, at(e)], vec![1.0, half.cos().abs(), 1.0]).ok()
        })
        .collect()
}

/// The segment of a polyline from `p0` to `p1` with DXF bulge `b` (tan of a quarter of the
/// included angle, positive counter-clockwise): a line, or an arc.
fn bulge_segment(p0: Point, p1: Point, b: f64) -> Vec<RationalBezier> {
    let chord = p1 - p0;
    let c = chord.hypot();
    if b == 0.0 || !b.is_finite() || c == 0.0 {
        return RationalBezier::new(vec![p0, p1], vec![1.0, 1.0])
            .into_iter()
            .collect();
    }
    let theta = 4.0 * b.atan();
    let m = p0.midpoint(p1);
    let left = chord.turn_90() / c;
    let center = m + left * (0.5 * c / (0.5 * theta).tan());
    let r = (p0 - center).hypot();
    let a0 = (p0.y - center.y).atan2(p0.x - center.x);
    let mut out = arc(center, r, a0, theta);
    // The ends exactly as given (the arc's are equal to rounding).
    if let (Some(first), Some(last)) = (out.first().cloned(), out.last().cloned()) {
        let n = out.len();
        let mut pts = first.points().to_vec();
        pts[0] = p0;
        out[0] = RationalBezier::new(pts, first.weights().to_vec()).unwrap_or(first);
        let mut pts = out[n - 1].points().to_vec();
        let k = pts.len() - 1;
        pts[k] = p1;
        out[n - 1] = RationalBezier::new(pts, last.weights().to_vec()).unwrap_or(last);
    }
    out
}

/// The curves of a DXF drawing: one shape per LINE, ARC, CIRCLE, LWPOLYLINE and SPLINE
/// (named by layer and handle), open ones chained by layer. A malformed entity (a coordinate,
/// radius or angle that is not a finite number, a spline whose weights or degree do not fit
/// its control points, one given by fit points only) is listed as unreadable with the
/// reason; the entity kinds not read (ELLIPSE, POLYLINE, INSERT, ...) are listed once per
/// kind with their count. No external reference (XREF) is followed.
pub fn read_dxf(data: &[u8]) -> Result<Outlines> {
    contained(|| read_dxf_inner(data)).map(within_limits)
}

fn read_dxf_inner(data: &[u8]) -> Result<Outlines> {
    let drawing = dxf::Drawing::load(&mut std::io::Cursor::new(data))
        .map_err(|e| anyhow::anyhow!("not a readable DXF drawing: {e}"))?;
    let mut pieces: Vec<(String, String, Contour)> = Vec::new(); // (layer, name, contour)
    let mut unreadable = Vec::new();
    let mut skipped = std::collections::BTreeMap::<String, usize>::new();
    for e in drawing.entities() {
        let name = format!("{} #{:X}", e.common.layer, e.common.handle.0);
        match dxf_contour(&e.specific) {
            Ok(Some(contour)) if !contour.segments.is_empty() => {
                pieces.push((e.common.layer.clone(), name, contour))
            }
            Ok(Some(_)) => unreadable.push((name, "an entity of zero length".into())),
            Ok(None) => *skipped.entry(dxf_kind(&e.specific)).or_default() += 1,
            Err(why) => unreadable.push((name, why)),
        }
    }
    for (kind, n) in skipped {
        unreadable.push((
            format!("{kind} ({n} entit{})", if n == 1 { "y" } else { "ies" }),
            "an entity kind `check` does not read (it reads LINE, ARC, CIRCLE, LWPOLYLINE and \
             SPLINE)"
                .into(),
        ));
    }
    let shapes = chain_entities(pieces);
    if shapes.is_empty() && unreadable.is_empty() {
        bail!("the DXF drawing has no curves (LINE, ARC, CIRCLE, LWPOLYLINE or SPLINE)");
    }
    Ok(Outlines {
        kind: "dxf",
        shapes,
        unreadable,
    })
}

/// The entity's kind as DXF names it (from the dxf crate's variant name).
fn dxf_kind(e: &dxf::entities::EntityType) -> String {
    let debug = format!("{e:?}");
    let variant = debug.split(['(', ' ', '{']).next().unwrap_or("entity");
    variant.to_ascii_uppercase()
}

fn finite_point(p: &dxf::Point, what: &str) -> std::result::Result<Point, String> {
    if p.x.is_finite() && p.y.is_finite() {
        Ok(Point::new(p.x, p.y))
    } else {
        Err(format!(
            "its {what} ({}, {}) is not a finite number",
            p.x, p.y
        ))
    }
}

fn finite(v: f64, what: &str) -> std::result::Result<f64, String> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(format!("its {what} ({v}) is not a finite number"))
    }
}

fn positive_radius(r: f64) -> std::result::Result<f64, String> {
    if r.is_finite() && r > 0.0 {
        Ok(r)
    } else {
        Err(format!("its radius ({r}) is not a positive finite number"))
    }
}

/// One entity as a contour; `Ok(None)` for a kind not read.
fn dxf_contour(e: &dxf::entities::EntityType) -> std::result::Result<Option<Contour>, String> {
    use dxf::entities::EntityType;
    let open = |segments| Contour {
        segments,
        closed: false,
        smooth: None,
    };
    Ok(Some(match e {
        EntityType::Line(l) => {
            let (a, b) = (finite_point(&l.p1, "start")?, finite_point(&l.p2, "end")?);
            open(
                RationalBezier::new(vec![a, b], vec![1.0, 1.0])
                    .map(|c| vec![c])
                    .map_err(|e| e.to_string())?,
            )
        }
        EntityType::Arc(a) => {
            let c = finite_point(&a.center, "center")?;
            let r = positive_radius(a.radius)?;
            let s = finite(a.start_angle, "start angle")?.to_radians();
            let e = finite(a.end_angle, "end angle")?.to_radians();
            // The sweep counterclockwise from start to end, in (0, 2π].
            let mut sweep = (e - s).rem_euclid(std::f64::consts::TAU);
            if sweep == 0.0 {
                sweep = std::f64::consts::TAU;
            }
            open(arc(c, r, s, sweep))
        }
        EntityType::Circle(ci) => Contour {
            segments: arc(
                finite_point(&ci.center, "center")?,
                positive_radius(ci.radius)?,
                0.0,
                std::f64::consts::TAU,
            ),
            closed: true,
            smooth: None,
        },
        EntityType::LwPolyline(pl) => {
            let v = &pl.vertices;
            let closed = pl.is_closed();
            let count = if closed {
                v.len()
            } else {
                v.len().saturating_sub(1)
            };
            let mut segments = Vec::new();
            for i in 0..count {
                let (a, b) = (&v[i], &v[(i + 1) % v.len()]);
                let pa = Point::new(finite(a.x, "vertex x")?, finite(a.y, "vertex y")?);
                let pb = Point::new(finite(b.x, "vertex x")?, finite(b.y, "vertex y")?);
                segments.extend(bulge_segment(pa, pb, finite(a.bulge, "bulge")?));
            }
            Contour {
                segments,
                closed,
                smooth: None,
            }
        }
        EntityType::Spline(sp) => dxf_spline(sp)?,
        _ => return Ok(None),
    }))
}

fn dxf_spline(sp: &dxf::entities::Spline) -> std::result::Result<Contour, String> {
    // The DXF reader pairs x, y and z (group codes 10, 20, 30) in order and stops at the
    // shortest list: control points without a z vanish (or pair with the wrong z). The count
    // the file declares (group code 73) shows it.
    let declared = sp.__number_of_control_points_ignored;
    if declared > 0 && declared as usize != sp.control_points.len() {
        return Err(format!(
            "a spline declaring {declared} control points (group code 73) of which {} are \
             complete: each needs its x, y and z (group codes 10, 20 and 30, z 0 in a 2D \
             drawing); save the drawing again from a CAD program",
            sp.control_points.len()
        ));
    }
    if sp.control_points.is_empty() {
        return Err(if sp.fit_points.is_empty() {
            "a spline with no control points".into()
        } else {
            "a spline given by fit points only (its curve is not determined by the file: \
             save it with control points)"
                .into()
        });
    }
    let pts = sp
        .control_points
        .iter()
        .map(|p| finite_point(p, "control point"))
        .collect::<std::result::Result<Vec<_>, _>>()?;
    if sp.degree_of_curve < 1 {
        return Err(format!(
            "a spline of degree {} (a degree is at least 1)",
            sp.degree_of_curve
        ));
    }
    let w = match sp.weight_values.len() {
        0 => vec![1.0; pts.len()],
        n if n == pts.len() => sp.weight_values.clone(),
        n => {
            return Err(format!(
                "a spline with {n} weights for {} control points (one weight per control \
                 point, or none)",
                pts.len()
            ))
        }
    };
    let segments = aesthetic_curves::nurbs::Nurbs::new(
        sp.degree_of_curve as usize,
        sp.knot_values.clone(),
        pts,
        w,
    )
    .map_err(|e| e.to_string())
    .and_then(|n| {
        n.bezier_spans()
            .ok_or_else(|| "no Bézier spans".to_string())
    })?;
    let closed = match (segments.first(), segments.last()) {
        (Some(a), Some(b)) => a.points()[0] == b.points()[b.points().len() - 1],
        _ => false,
    };
    Ok(Contour {
        segments,
        closed,
        smooth: None,
    })
}

/// Open entities of one layer that meet end to end (within 1e-9 of the drawing's size),
/// joined into one contour each, so the joins between them are checked like any other (a
/// CAD profile is usually separate LINEs and ARCs); an entity is reversed where its end
/// meets the chain's end. A chain whose ends meet is closed. Closed entities stay alone.
/// The shape's name is the layer and the handles of its entities.
fn chain_entities(pieces: Vec<(String, String, Contour)>) -> Vec<Shape> {
    let size = pieces
        .iter()
        .flat_map(|p| p.2.segments.iter().flat_map(|s| s.points().iter()))
        .map(|q| q.to_vec2().hypot())
        .fold(1.0, f64::max);
    let tol = 1e-9 * size;
    let ends = |c: &Contour| -> (Point, Point) {
        let (a, b) = (&c.segments[0], &c.segments[c.segments.len() - 1]);
        (a.points()[0], b.points()[b.points().len() - 1])
    };
    let reversed = |c: Contour| -> Contour {
        let segments = c.segments.iter().rev().map(|s| s.reversed()).collect();
        Contour {
            segments,
            closed: c.closed,
            smooth: None,
        }
    };
    // Open entities' ends in a grid of cells 4 tolerances wide: a search looks at the 3 x 3
    // cells around a point, so chaining stays linear in the number of entities.
    let cell = 4.0 * tol;
    let key = |p: Point| ((p.x / cell).floor() as i64, (p.y / cell).floor() as i64);
    let mut grid: std::collections::HashMap<(i64, i64), Vec<usize>> = Default::default();
    for (j, (_, _, c)) in pieces.iter().enumerate() {
        if !c.closed {
            let (a, b) = ends(c);
            grid.entry(key(a)).or_default().push(j);
            if key(b) != key(a) {
                grid.entry(key(b)).or_default().push(j);
            }
        }
    }
    let near = |p: Point| {
        let (kx, ky) = key(p);
        let mut out: Vec<usize> = (-1..=1)
            .flat_map(|dx| (-1..=1).map(move |dy| (kx + dx, ky + dy)))
            .filter_map(|k| grid.get(&k))
            .flatten()
            .copied()
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    };
    let mut used = vec![false; pieces.len()];
    let mut shapes = Vec::new();
    for i in 0..pieces.len() {
        if used[i] {
            continue;
        }
        used[i] = true;
        let (layer, name, first) = &pieces[i];
        let mut chain = first.clone();
        let mut names = vec![name.clone()];
        if !chain.closed {
            // Extend at the end, then at the start, while an unused open entity of the layer
            // meets it.
            for at_end in [true, false] {
                loop {
                    let (start, end) = ends(&chain);
                    if (end - start).hypot() <= tol && chain.segments.len() > 1 {
                        break;
                    }
                    let here = if at_end { end } else { start };
                    let next = near(here).into_iter().find_map(|j| {
                        let (l, _, c) = &pieces[j];
                        if used[j] || c.closed || l != layer {
                            return None;
                        }
                        let (a, b) = ends(c);
                        // At the end: the piece's start should meet it (else reverse);
                        // at the start: the piece's end should.
                        let (keep, flip) = if at_end { (a, b) } else { (b, a) };
                        if (keep - here).hypot() <= tol {
                            Some((j, false))
                        } else if (flip - here).hypot() <= tol {
                            Some((j, true))
                        } else {
                            None
                        }
                    });
                    let Some((j, flip)) = next else { break };
                    used[j] = true;
                    let piece = pieces[j].2.clone();
                    let piece = if flip { reversed(piece) } else { piece };
                    if at_end {
                        chain.segments.extend(piece.segments);
                        names.push(pieces[j].1.clone());
                    } else {
                        let mut segs = piece.segments;
                        segs.extend(chain.segments);
                        chain.segments = segs;
                        names.insert(0, pieces[j].1.clone());
                    }
                }
            }
            let (start, end) = ends(&chain);
            chain.closed = chain.segments.len() > 1 && (end - start).hypot() <= tol;
        }
        let name = if names.len() == 1 {
            names.remove(0)
        } else {
            let handles: Vec<&str> = names.iter().filter_map(|n| n.rsplit(" #").next()).collect();
            let list = if handles.len() <= 4 {
                handles.join("+#")
            } else {
                format!(
                    "{}+#{}+…+#{}",
                    handles[0],
                    handles[1],
                    handles[handles.len() - 1]
                )
            };
            format!("{layer} #{list} ({} entities)", names.len())
        };
        shapes.push(Shape {
            name,
            contours: vec![chain],
            unicodes: Vec::new(),
        });
    }
    shapes
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

/// Check `shapes` (in parallel, the worker threads under the caller's deadline: past it,
/// segments are flagged as not checked), calling `tick` once per shape (a progress bar).
pub fn check_shapes<'a>(
    shapes: &[&'a Shape],
    opts: &OutlineOptions,
    tick: &(dyn Fn() + Sync),
) -> Vec<ShapeCheck<'a>> {
    use aesthetic_curves::deadline;
    use rayon::prelude::*;
    let deadline = deadline::current();
    shapes
        .par_iter()
        .map(|s| {
            deadline::inherit(deadline, || {
                tick();
                let contours: Vec<ContourCheck> = s
                    .contours
                    .iter()
                    .map(|c| {
                        let mut k = check_contour(&c.segments, c.closed, opts);
                        if let Some(m) = &c.smooth {
                            k.mark_smooth(m);
                        }
                        k
                    })
                    .collect();
                let findings = findings(&contours, opts);
                ShapeCheck {
                    name: &s.name,
                    contours,
                    findings,
                }
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use aesthetic_curves::Curve;

    /// Largest distance from `c` of 50 points of each piece, minus `r`, and the largest
    /// curvature error against 1/r (counter-clockwise positive).
    fn off_circle(pieces: &[RationalBezier], c: Point, r: f64, sign: f64) -> (f64, f64) {
        let mut worst = (0.0f64, 0.0f64);
        for piece in pieces {
            for q in piece.curve_points(50).unwrap() {
                worst.0 = worst.0.max(((q.p - c).hypot() - r).abs());
                worst.1 = worst.1.max((q.kappa - sign / r).abs());
            }
        }
        worst
    }

    #[test]
    fn an_arc_is_exact_rational_quadratics_of_at_most_90_degrees() {
        let c = Point::new(3.0, -2.0);
        let pieces = arc(c, 2.5, 0.3, 1.5 * std::f64::consts::PI);
        assert_eq!(pieces.len(), 3);
        let (dist, kappa) = off_circle(&pieces, c, 2.5, 1.0);
        assert!(dist < 1e-13 && kappa < 1e-12, "{dist:e} {kappa:e}");
        // Clockwise: negative curvature.
        let cw = arc(c, 2.5, 0.3, -0.4);
        assert_eq!(cw.len(), 1);
        assert!(off_circle(&cw, c, 2.5, -1.0).1 < 1e-12);
    }

    #[test]
    fn a_bulge_is_a_line_or_an_arc_through_the_given_ends() {
        let (p0, p1) = (Point::new(0.0, 0.0), Point::new(2.0, 0.0));
        let line = bulge_segment(p0, p1, 0.0);
        assert_eq!(line.len(), 1);
        assert_eq!(line[0].degree(), 1);
        // Bulge 1: a half circle, counter-clockwise, so below the chord from left to right.
        let half = bulge_segment(p0, p1, 1.0);
        assert_eq!(half.len(), 2);
        assert_eq!(half[0].points()[0], p0);
        assert_eq!(half[1].points()[2], p1);
        assert!((half[0].points()[2] - Point::new(1.0, -1.0)).hypot() < 1e-12);
        assert!(off_circle(&half, Point::new(1.0, 0.0), 1.0, 1.0).1 < 1e-12);
    }

    #[test]
    fn svg_shapes_keep_their_ids_and_closed_contours() {
        let svg = br#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100">
            <path id="tri" d="M 10 10 L 60 10 L 60 60 Z"/>
            <circle id="ring" cx="50" cy="50" r="20"/></svg>"#;
        let o = read_svg(svg).unwrap();
        assert_eq!(o.kind, "svg");
        let names: Vec<&str> = o.shapes.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names, ["tri", "ring"]);
        let tri = &o.shapes[0].contours[0];
        assert!(tri.closed);
        assert!(tri.segments.iter().all(|s| s.degree() == 1));
        // The circle: usvg's four cubics, within 3e-4 of the radius; their curvature, as
        // any four-cubic circle's, varies by a few per cent about 1/20.
        let ring = &o.shapes[1].contours[0];
        assert!(ring.closed && ring.segments.len() == 4);
        for seg in &ring.segments {
            for q in seg.curve_points(20).unwrap() {
                let r = (q.p - Point::new(50.0, 50.0)).hypot();
                assert!((r - 20.0).abs() < 3e-4 * 20.0, "radius {r}");
                assert!((q.kappa.abs() - 0.05).abs() < 0.03 * 0.05, "{}", q.kappa);
            }
        }
        assert!(read_svg(br#"<svg xmlns="http://www.w3.org/2000/svg"/>"#).is_err());
        assert!(read_svg(b"not svg at all").is_err());
    }

    #[test]
    fn dxf_entities_that_meet_are_one_contour() {
        let line = |a: (f64, f64), b: (f64, f64)| Contour {
            segments: vec![RationalBezier::new(
                vec![Point::new(a.0, a.1), Point::new(b.0, b.1)],
                vec![1.0, 1.0],
            )
            .unwrap()],
            closed: false,
            smooth: None,
        };
        // Three sides of a square, the middle one drawn against the others, and a line of
        // another layer at the same place.
        let shapes = chain_entities(vec![
            ("0".into(), "A".into(), line((0.0, 0.0), (1.0, 0.0))),
            ("0".into(), "B".into(), line((1.0, 1.0), (1.0, 0.0))),
            ("0".into(), "C".into(), line((1.0, 1.0), (0.0, 1.0))),
            ("walls".into(), "D".into(), line((0.0, 0.0), (1.0, 0.0))),
        ]);
        assert_eq!(shapes.len(), 2);
        let chain = shapes
            .iter()
            .find(|s| s.contours[0].segments.len() == 3)
            .unwrap();
        let segs = &chain.contours[0].segments;
        for w in segs.windows(2) {
            assert_eq!(w[0].points()[1], w[1].points()[0], "{}", chain.name);
        }
        assert!(!chain.contours[0].closed);
    }
}
