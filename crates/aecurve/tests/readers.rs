//! The readers on hostile files: they read only the bytes they are given, never
//! block on a special file, never panic, and list what they cannot read instead of dropping
//! it. Each case here failed before the readers were hardened.

use aecurve::outline_io::{read, read_dxf, read_font, read_svg};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// A fresh empty folder under the target directory (removed first if left over).
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("readers-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs `f` on another thread and fails the test if it does not finish within `limit` (a
/// reader blocked on a pipe would hang the suite otherwise).
fn within<T: Send + 'static>(limit: Duration, f: impl FnOnce() -> T + Send + 'static) -> T {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(f());
    });
    rx.recv_timeout(limit)
        .expect("the reader did not finish in time (blocked on a special file?)")
}

#[cfg(unix)]
fn mkfifo(path: &Path) {
    let status = std::process::Command::new("mkfifo")
        .arg(path)
        .status()
        .expect("mkfifo runs");
    assert!(status.success());
}

/// An `<image>` naming a pipe, and one naming /dev/zero: neither is opened (the first hung
/// `check` forever, the second grew it to 2 GB); both are listed as unreadable, and the
/// path beside them is read.
#[cfg(unix)]
#[test]
fn svg_images_are_never_resolved() {
    let dir = scratch("image");
    let pipe = dir.join("pipe");
    mkfifo(&pipe);
    for href in [pipe.display().to_string(), "/dev/zero".to_string()] {
        let svg = format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg"><image href="{href}" width="9" height="9"/><path d="M0 0 L1 1"/></svg>"#
        );
        let file = dir.join("doc.svg");
        std::fs::write(&file, svg).unwrap();
        let t = Instant::now();
        let o = within(Duration::from_secs(20), move || read(&file)).unwrap();
        assert!(t.elapsed() < Duration::from_secs(5));
        assert_eq!(o.shapes.len(), 1, "{href}");
        assert_eq!(o.unreadable.len(), 1, "{href}: {:?}", o.unreadable);
        assert!(o.unreadable[0].1.contains("images are never read"));
    }
}

/// The file itself a pipe (or a device): refused before it is opened.
#[cfg(unix)]
#[test]
fn special_files_are_refused_without_blocking() {
    let dir = scratch("fifo");
    let pipe = dir.join("font.ttf");
    mkfifo(&pipe);
    let e = within(Duration::from_secs(20), move || read(&pipe)).unwrap_err();
    assert!(format!("{e:#}").contains("not a regular file"), "{e:#}");
    let e = read(Path::new("/dev/zero.svg")).unwrap_err();
    assert!(!format!("{e:#}").is_empty());
    // A UFO folder with a pipe inside: refused, naming the pipe, before norad opens it.
    let ufo = dir.join("font.ufo");
    std::fs::create_dir_all(ufo.join("glyphs")).unwrap();
    mkfifo(&ufo.join("glyphs").join("a.glif"));
    let e = within(Duration::from_secs(20), move || read(&ufo)).unwrap_err();
    let msg = format!("{e:#}");
    assert!(
        msg.contains("a.glif") && msg.contains("not a regular file"),
        "{msg}"
    );
}

/// A TrueType glyph with `numberOfContours = 0` and trailing bytes (fontTools' square with
/// two bytes zeroed) panicked inside read-fonts and ended `check` and `batch`: now that
/// glyph is unreadable, with the reason, and the rest of the font is read.
#[test]
fn a_glyph_that_panics_the_parser_is_listed_and_the_font_read() {
    let data = std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/zero_contours.ttf"
    ))
    .unwrap();
    let o = read_font(&data).unwrap();
    assert_eq!(o.shapes.len() + o.unreadable.len(), 2);
    assert!(o.shapes.iter().any(|s| s.name == ".notdef"));
    let (name, why) = &o.unreadable[0];
    assert_eq!(name, "square");
    assert!(why.contains("parser failed"), "{why}");
}

/// Bit flips and truncations of a real font: every one read or refused with an error, no
/// panic, and every glyph accounted for (read or listed).
#[test]
fn mutated_fonts_never_panic() {
    const FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");
    // A small font keeps the debug build fast: the fixture square, mutated at every byte.
    let square = std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/zero_contours.ttf"
    ))
    .unwrap();
    let mut state = 0x9e3779b97f4a7c15u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let mut cases: Vec<Vec<u8>> = Vec::new();
    for i in 0..square.len() {
        let mut m = square.clone();
        m[i] ^= 1 << (next() % 8);
        cases.push(m);
        cases.push(square[..i].to_vec());
    }
    // DejaVu: a few flips in its glyf and loca data and truncations.
    for _ in 0..12 {
        let mut m = FONT.to_vec();
        for _ in 0..8 {
            let at = (next() as usize) % m.len();
            m[at] ^= 1 << (next() % 8);
        }
        cases.push(m);
    }
    for cut in [12usize, 400, 70_000, FONT.len() / 2] {
        cases.push(FONT[..cut].to_vec());
    }
    for c in &cases {
        if let Ok(o) = read_font(c) {
            for (_, why) in &o.unreadable {
                assert!(!why.is_empty());
            }
        }
    }
}

/// SVG paths whose coordinates are not finite once transformed were dropped without a word
/// (and "has no path" when all were): now each is listed with the reason.
#[test]
fn svg_paths_that_cannot_be_read_are_listed() {
    let svg = br#"<svg xmlns="http://www.w3.org/2000/svg">
        <path id="ok" d="M0 0 C1 2 3 2 4 0"/>
        <path id="huge" transform="scale(1e30)" d="M0 0 C1e10 2e10 3 2 4 0"/>
    </svg>"#;
    let o = read_svg(svg).unwrap();
    assert_eq!(o.shapes.len(), 1);
    assert_eq!(o.unreadable.len(), 1, "{:?}", o.unreadable);
    assert_eq!(o.unreadable[0].0, "huge");
    assert!(
        o.unreadable[0].1.contains("not finite"),
        "{:?}",
        o.unreadable
    );
    // Unnamed ones are counted; a hidden one is listed too (with the reason's words).
    let svg = br#"<svg xmlns="http://www.w3.org/2000/svg">
        <path d="M0 0 C1 2 3 2 4 0"/>
        <path transform="scale(1e30)" d="M0 0 C1e10 2e10 3 2 4 0"/>
        <path transform="scale(1e30)" d="M0 0 C1e10 2e10 3 2 4 0"/>
        <defs><path id="def" d="M0 0 L1 1"/></defs>
    </svg>"#;
    let o = read_svg(svg).unwrap();
    assert_eq!(o.shapes.len(), 1);
    assert_eq!(o.unreadable.len(), 1, "{:?}", o.unreadable);
    assert_eq!(o.unreadable[0].0, "2 unnamed elements");
}

fn dxf_bytes(entities: Vec<dxf::entities::EntityType>) -> Vec<u8> {
    let mut d = dxf::Drawing::new();
    // SPLINE and ELLIPSE exist from R13 on (the default R12 would leave them out).
    d.header.version = dxf::enums::AcadVersion::R2000;
    for e in entities {
        d.add_entity(dxf::entities::Entity::new(e));
    }
    let mut out = Vec::new();
    d.save(&mut out).unwrap();
    out
}

/// DXF entities with NaN or infinite numbers vanished (and an ARC with an infinite angle
/// looped forever); unsupported kinds were skipped without notice; a SPLINE with 3 weights
/// for 4 control points was read as non-rational. Each is now listed with its reason.
#[test]
fn dxf_entities_that_cannot_be_read_are_listed() {
    use dxf::entities::*;
    use dxf::Point as P;
    let good = Line::new(P::new(0.0, 0.0, 0.0), P::new(1.0, 0.0, 0.0));
    let nan_line = Line::new(P::new(f64::NAN, 0.0, 0.0), P::new(1.0, 5.0, 0.0));
    let inf_circle = Circle::new(P::new(0.0, 0.0, 0.0), f64::INFINITY);
    let nan_arc = Arc::new(P::new(0.0, 0.0, 0.0), 1.0, f64::NAN, 90.0);
    let inf_arc = Arc::new(P::new(9.0, 9.0, 0.0), 1.0, 0.0, f64::INFINITY);
    let spline = Spline {
        degree_of_curve: 3,
        control_points: (0..4)
            .map(|i| P::new(i as f64, (i * i) as f64, 0.0))
            .collect(),
        knot_values: vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
        weight_values: vec![1.0, 2.0, 1.0],
        ..Default::default()
    };
    let ellipse = Ellipse::default();
    let data = dxf_bytes(vec![
        EntityType::Line(good),
        EntityType::Line(nan_line),
        EntityType::Circle(inf_circle),
        EntityType::Arc(nan_arc),
        EntityType::Arc(inf_arc),
        EntityType::Spline(spline),
        EntityType::Ellipse(ellipse.clone()),
        EntityType::Ellipse(ellipse),
    ]);
    let o = within(Duration::from_secs(20), move || read_dxf(&data)).unwrap();
    assert_eq!(o.shapes.len(), 1, "{:?}", o.unreadable);
    let why: Vec<&str> = o.unreadable.iter().map(|(_, w)| w.as_str()).collect();
    assert_eq!(o.unreadable.len(), 6, "{:?}", o.unreadable);
    assert!(
        why.iter()
            .filter(|w| w.contains("not a finite number"))
            .count()
            >= 3,
        "{why:?}"
    );
    assert!(why.iter().any(|w| w.contains("radius")), "{why:?}");
    assert!(
        why.iter()
            .any(|w| w.contains("3 weights for 4 control points")),
        "{why:?}"
    );
    assert!(
        o.unreadable
            .iter()
            .any(|(n, w)| n == "ELLIPSE (2 entities)" && w.contains("does not read")),
        "{:?}",
        o.unreadable
    );
}

/// One bad `.glif` made the whole UFO fail with "failed to load layer 'public.default'",
/// naming no file: now the message names the glyph file.
#[test]
fn a_bad_glif_is_named() {
    let dir = scratch("ufo");
    let ufo = dir.join("font.ufo");
    let mut font = norad::Font::new();
    for name in ["a", "b"] {
        let mut g = norad::Glyph::new(name);
        g.contours.push(norad::Contour::new(
            vec![
                norad::ContourPoint::new(0.0, 0.0, norad::PointType::Line, false, None, None),
                norad::ContourPoint::new(10.0, 0.0, norad::PointType::Line, false, None, None),
                norad::ContourPoint::new(0.0, 10.0, norad::PointType::Line, false, None, None),
            ],
            None,
        ));
        font.default_layer_mut().insert_glyph(g);
    }
    font.save(&ufo).unwrap();
    assert_eq!(read(&ufo).unwrap().shapes.len(), 2);
    std::fs::write(
        ufo.join("glyphs").join("b.glif"),
        "<glyph name=\"b\" format=\"2\"><outline><contour>",
    )
    .unwrap();
    let msg = format!("{:#}", read(&ufo).unwrap_err());
    assert!(msg.contains("b.glif"), "{msg}");
}

/// Bit flips and truncations of a real SVG and of a DXF drawing: each read or refused with
/// an error, never a panic or a hang, every unreadable part with a reason.
#[test]
fn mutated_svg_and_dxf_never_panic() {
    let svg = std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/check-shapes.svg"
    ))
    .unwrap();
    use dxf::entities::*;
    use dxf::Point as P;
    let dxf_data = dxf_bytes(vec![
        EntityType::Line(Line::new(P::new(0.0, 0.0, 0.0), P::new(1.0, 0.0, 0.0))),
        EntityType::Arc(Arc::new(P::new(1.0, 1.0, 0.0), 1.0, 270.0, 90.0)),
        EntityType::Circle(Circle::new(P::new(5.0, 5.0, 0.0), 2.0)),
    ]);
    let mut state = 0x2545f4914f6cdd1du64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let t = Instant::now();
    for (data, reader) in [
        (svg, read_svg as fn(&[u8]) -> anyhow::Result<_>),
        (dxf_data, read_dxf),
    ] {
        for k in 0..300 {
            let mut m = data.clone();
            if k % 3 == 0 {
                m.truncate((next() as usize) % m.len());
            } else {
                for _ in 0..1 + k % 4 {
                    let at = (next() as usize) % m.len();
                    m[at] = (next() & 0xff) as u8;
                }
            }
            if let Ok(o) = reader(&m) {
                assert!(o.unreadable.iter().all(|(_, why)| !why.is_empty()));
            }
        }
    }
    assert!(t.elapsed() < Duration::from_secs(60), "{:?}", t.elapsed());
}

/// A path of more segments than one shape may have is listed with its count and what to do,
/// not checked (its check alone would hold about 0.6 KB a segment), and the path beside it
/// is read.
#[test]
fn a_shape_over_the_segment_limit_is_listed_with_its_count() {
    use aecurve::outline_io::MAX_SHAPE_SEGMENTS;
    let n = MAX_SHAPE_SEGMENTS + 1;
    let mut svg = String::from(
        r#"<svg xmlns="http://www.w3.org/2000/svg"><path id="small" d="M0 0 C1 2 3 2 4 0"/><path id="huge" d="M0 0"#,
    );
    for _ in 0..n {
        svg.push_str("h1");
    }
    svg.push_str(r#""/></svg>"#);
    let o = read_svg(svg.as_bytes()).unwrap();
    let names: Vec<&str> = o.shapes.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["small"]);
    assert_eq!(o.unreadable.len(), 1, "{:?}", o.unreadable);
    let (name, why) = &o.unreadable[0];
    assert_eq!(name, "huge");
    assert!(
        why.contains(&format!("{n} segments")) && why.contains("split it"),
        "{why}"
    );
}

/// Composites nested deeper than the font reader follows, and two that refer to each
/// other, are listed with that reason (they were "no outline in the font's tables"), and the
/// other glyphs are read. The font is made by `tests/data/deep_composites.py` (fontTools): a
/// chain `c0` … `c39` of composites over one simple glyph, and `loopa` ↔ `loopb`.
#[test]
fn composites_too_deep_or_in_a_loop_are_named_as_such() {
    let font = include_bytes!("data/deep_composites.ttf");
    let o = read_font(font).unwrap();
    let why = |name: &str| {
        o.unreadable
            .iter()
            .find(|u| u.0 == name)
            .map(|u| u.1.clone())
            .unwrap_or_else(|| panic!("{name} is not listed: {:?}", o.unreadable))
    };
    assert!(
        why("c32").contains("nested more than 32 deep"),
        "{}",
        why("c32")
    );
    assert!(
        why("loopa").contains("lead back to itself"),
        "{}",
        why("loopa")
    );
    // c0 … c31 are 32 levels at most: read, as the simple glyph under them.
    assert!(o.shapes.iter().any(|s| s.name == "c31"));
    assert_eq!(
        o.shapes.len() + o.unreadable.len(),
        44,
        "every glyph is read or listed"
    );
}

/// A 2D SPLINE whose control points carry no z (group code 30): the DXF reader pairs x, y
/// and z in order, so its control points vanished and the spline was reported as "given by
/// fit points only". It is listed with the count the file declares and the cause.
#[test]
fn a_spline_whose_control_points_lack_z_is_named_as_such() {
    let mut text = String::from(
        "0\nSECTION\n2\nENTITIES\n0\nSPLINE\n8\n0\n70\n8\n71\n3\n72\n8\n73\n4\n74\n0\n",
    );
    for k in [0, 0, 0, 0, 1, 1, 1, 1] {
        text.push_str(&format!("40\n{k}.0\n"));
    }
    for (x, y) in [(0, 0), (1, 2), (3, 2), (4, 0)] {
        text.push_str(&format!("10\n{x}.0\n20\n{y}.0\n"));
    }
    text.push_str("0\nENDSEC\n0\nEOF\n");
    let o = read_dxf(text.as_bytes()).unwrap();
    assert!(o.shapes.is_empty(), "{:?}", o.shapes);
    let why = &o.unreadable.first().expect("the spline is listed").1;
    assert!(
        why.contains("declaring 4 control points") && why.contains("group codes 10, 20 and 30"),
        "{why}"
    );
}

/// A CFF font whose charstrings hold fractions (16.16 operands, as fontmake, FontForge and
/// interpolation write them), one glyph drawn with `flex` and `hflex`, and one whose last
/// point is 1/65536 from its start: every point is read as fontTools reads it (the font and
/// fontTools' reading are made by `tools/make_fractional_cff.py`), not truncated to whole
/// units, and the closing line of 1/65536 is a segment of its own.
#[test]
fn cff_coordinates_are_read_at_their_full_precision() {
    let o = read_font(include_bytes!("data/fractional.otf")).unwrap();
    let theirs: serde_json::Value =
        serde_json::from_str(include_str!("data/fractional.json")).unwrap();
    let theirs = theirs.as_object().unwrap();
    assert_eq!(theirs.len(), 3);
    for (name, ops) in theirs {
        let shape = (o.shapes.iter().find(|s| &s.name == name))
            .unwrap_or_else(|| panic!("{name} not read: {:?}", o.unreadable));
        // fontTools' points in order, and where each contour starts.
        let mut expected: Vec<Vec<(f64, f64)>> = Vec::new();
        for op in ops.as_array().unwrap() {
            let kind = op[0].as_str().unwrap();
            let pts: Vec<(f64, f64)> = (op[1].as_array().unwrap().iter())
                .map(|p| (p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
                .collect();
            match kind {
                "moveTo" => expected.push(pts),
                "closePath" | "endPath" => {}
                _ => expected.last_mut().unwrap().extend(pts),
            }
        }
        assert_eq!(shape.contours.len(), expected.len(), "{name}");
        for (c, want) in shape.contours.iter().zip(&expected) {
            let mut got = vec![c.segments[0].points()[0]];
            for s in &c.segments {
                got.extend(&s.points()[1..]);
            }
            // The closing line back to the start, which fontTools' closePath implies.
            if c.closed && got.len() == want.len() + 1 {
                assert_eq!(got.pop(), Some(got[0]), "{name}");
            }
            let got: Vec<(f64, f64)> = got.iter().map(|p| (p.x, p.y)).collect();
            assert_eq!(&got, want, "{name}: not the font's own numbers");
        }
    }
    // The glyph that ends 1/65536 from its start keeps its closing line.
    let nearly = o.shapes.iter().find(|s| s.name == "nearly").unwrap();
    let last = nearly.contours[0]
        .segments
        .last()
        .unwrap()
        .points()
        .to_vec();
    assert_eq!(last.len(), 2, "{last:?}");
    assert_eq!(last[0].x - last[1].x, 1.0 / 65536.0);
}
