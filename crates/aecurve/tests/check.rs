//! `aecurve check` on real and hand-made files: the font's own glyph count, verdicts that
//! dense sampling never contradicts, known shapes' known answers, bad input refused clearly.

use aecurve::outline_io::{check_shapes, options_for, read, read_font, read_svg};
use aesthetic_curves::outline::check_segment;
use aesthetic_curves::PlanarCurve;
use std::path::Path;

const FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

/// numGlyphs of the font's `maxp` table, read from the bytes (independent of skrifa).
fn maxp_glyphs(font: &[u8]) -> usize {
    let be16 = |o: usize| u16::from_be_bytes([font[o], font[o + 1]]) as usize;
    let be32 =
        |o: usize| u32::from_be_bytes([font[o], font[o + 1], font[o + 2], font[o + 3]]) as usize;
    let tables = be16(4);
    for i in 0..tables {
        let rec = 12 + 16 * i;
        if &font[rec..rec + 4] == b"maxp" {
            return be16(be32(rec + 8) + 4);
        }
    }
    panic!("no maxp table");
}

#[test]
fn every_glyph_of_a_real_font_is_read_and_checked() {
    let o = read_font(FONT).unwrap();
    assert_eq!(o.shapes.len() + o.unreadable.len(), maxp_glyphs(FONT));
    assert!(
        o.unreadable.is_empty(),
        "{:?}",
        &o.unreadable[..o.unreadable.len().min(3)]
    );
    let shapes: Vec<_> = o.shapes.iter().collect();
    let checked = check_shapes(&shapes, &options_for(&o), &|| {});
    let segments: usize = checked
        .iter()
        .flat_map(|c| &c.contours)
        .map(|c| c.segments.len())
        .sum();
    assert!(segments > 100_000, "{segments}");
    // Every curved segment got a verdict or a flag; nothing is NaN.
    for c in checked.iter().flat_map(|c| &c.contours) {
        for s in &c.segments {
            assert!(s.monotone.is_some() || s.flag.is_some());
            assert!(s.max_abs_curvature.is_finite());
        }
        for j in &c.joins {
            assert!(j.angle_break.is_finite() && j.angle_break >= 0.0);
        }
    }
    // The letter o: two closed contours, smooth all round.
    let o_glyph = checked.iter().find(|c| c.name == "o").unwrap();
    assert_eq!(o_glyph.contours.len(), 2);
    for c in &o_glyph.contours {
        assert!(c.closed && c.joins.iter().all(|j| j.g1), "{:?}", c.joins);
    }
}

#[test]
fn monotone_verdicts_on_the_font_never_contradict_dense_sampling() {
    // Every 300th curved segment of the font: where the exact test says monotone, 20,000
    // samples of the curvature never turn back (beyond rounding).
    let o = read_font(FONT).unwrap();
    let curved: Vec<_> = o
        .shapes
        .iter()
        .flat_map(|s| &s.contours)
        .flat_map(|c| &c.segments)
        .filter(|s| s.degree() > 1)
        .collect();
    let mut checked = 0;
    for seg in curved.iter().step_by(300) {
        // Retracted handles are left to the exact oracles (tests/monotone_exact.rs, the font
        // oracle in CI): next to them floating-point κ is rounding noise over a vanishing
        // speed (1e-10 at t = 1e-3 on a straight segment whose curvature is exactly 0).
        let p = seg.points();
        if p[1] == p[0] || p[p.len() - 2] == p[p.len() - 1] {
            continue;
        }
        if check_segment(seg).monotone != Some(true) {
            continue;
        }
        checked += 1;
        let ks: Vec<f64> = (0..20_000)
            .map(|i| seg.kappa(i as f64 / 19_999.0))
            .collect();
        let scale = ks.iter().fold(0.0f64, |m, k| m.max(k.abs()));
        // A floor for straight segments, whose sampled curvature is rounding noise around the
        // exact 0: 1e-9 of the curvature of a circle the segment's size.
        let size = p.iter().map(|q| (*q - p[0]).hypot()).fold(0.0f64, f64::max);
        let tol = 1e-9 * scale + 1e-9 / size;
        let up = ks.windows(2).all(|w| w[1] >= w[0] - tol);
        let down = ks.windows(2).all(|w| w[1] <= w[0] + tol);
        assert!(up || down, "{:?}", seg.points());
    }
    assert!(checked > 50, "{checked}");
}

#[test]
fn svg_shapes_give_their_known_answers() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/check-shapes.svg");
    let o = read(&path).unwrap();
    let names: Vec<&str> = o.shapes.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["circle", "kinked", "s-curve"]);
    let shapes: Vec<_> = o.shapes.iter().collect();
    let checked = check_shapes(&shapes, &options_for(&o), &|| {});
    // The circle: moved by its group, radius 20 everywhere (curvature 1/20 within 1 %),
    // G1 and G2 at every join.
    let circle = &checked[0].contours[0];
    assert!(circle.closed);
    for seg in &o.shapes[0].contours[0].segments {
        for i in 0..=50 {
            let p = seg.eval(i as f64 / 50.0);
            assert!(
                ((p.x - 40.0).hypot(p.y - 60.0) - 20.0).abs() < 0.02,
                "{p:?}"
            );
        }
    }
    for s in &circle.segments {
        assert!(
            (s.max_abs_curvature - 0.05).abs() < 5e-4,
            "{}",
            s.max_abs_curvature
        );
    }
    assert!(
        circle.joins.iter().all(|j| j.g1 && j.g2),
        "{:?}",
        circle.joins
    );
    // The kink: a 1° near-break, the first finding.
    let kinked = &checked[1];
    assert!((kinked.contours[0].joins[0].angle_break.to_degrees() - 1.0).abs() < 1e-3);
    assert_eq!(kinked.findings[0].kind, "near-break");
    // The S: one inflection, in the middle.
    let s = &checked[2].contours[0].segments[0];
    assert_eq!(s.inflections.len(), 1);
    assert!((s.inflections[0].0 - 0.5).abs() < 1e-9);
}

#[test]
fn bad_files_get_clear_errors() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("aecurve-check-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let err = |name: &str, bytes: &[u8]| {
        let p = dir.join(name);
        std::fs::write(&p, bytes).unwrap();
        format!("{:#}", read(&p).unwrap_err())
    };
    assert!(err("cut.ttf", &FONT[..1000]).contains("not a readable font"));
    // Cut in the middle of its glyphs: either refused, or every glyph accounted for (read,
    // or listed as unreadable with its name).
    let half = dir.join("half.ttf");
    std::fs::write(&half, &FONT[..FONT.len() / 2]).unwrap();
    if let Ok(o) = read(&half) {
        assert_eq!(o.shapes.len() + o.unreadable.len(), maxp_glyphs(FONT));
    }
    assert!(err("empty.svg", br#"<svg xmlns="http://www.w3.org/2000/svg"/>"#).contains("no path"));
    assert!(err("junk.svg", b"not xml at all").contains("not a readable SVG"));
    assert!(err("notes.txt", b"x").contains("not a file `check` reads"));
    // Too big: refused before it is read (a sparse file).
    let big = dir.join("big.svg");
    let f = std::fs::File::create(&big).unwrap();
    f.set_len(aecurve::outline_io::MAX_FILE_BYTES + 1).unwrap();
    assert!(format!("{:#}", read(&big).unwrap_err()).contains("over the"));
    // A zero-length segment is flagged, not an error; a retracted handle is an ordinary
    // segment whose curvature grows without bound at that end (said in its notes, never NaN).
    let o = read_svg(br#"<svg xmlns="http://www.w3.org/2000/svg"><path d="M 0 0 L 0 0 C 0 0 10 10 20 10" stroke="black" fill="none"/></svg>"#).unwrap();
    let shapes: Vec<_> = o.shapes.iter().collect();
    let checked = check_shapes(&shapes, &options_for(&o), &|| {});
    let segs = &checked[0].contours[0].segments;
    assert!(segs.iter().all(|s| !s.max_abs_curvature.is_nan()));
    assert!(segs.iter().any(|s| s.flag.is_some()), "{segs:?}");
    assert!(
        segs.iter()
            .any(|s| s.notes.iter().any(|n| n.contains("without bound"))),
        "{segs:?}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn dxf_entities_that_meet_are_one_contour() {
    use dxf::entities::{Arc, Entity, EntityType, Line};
    // A slot drawn as four entities in no particular order, one line against the flow, and
    // a line of another layer touching it: the slot is one closed contour of 4 entities
    // whose joins are all smooth (G1) with curvature jumps where line meets arc.
    let mut d = dxf::Drawing::new();
    let pt = |x: f64, y: f64| dxf::Point::new(x, y, 0.0);
    let mut add = |layer: &str, t: EntityType| {
        let mut e = Entity::new(t);
        e.common.layer = layer.into();
        d.add_entity(e);
    };
    add(
        "slot",
        EntityType::Arc(Arc::new(pt(0.0, 2.0), 2.0, 90.0, 270.0)),
    );
    add(
        "slot",
        EntityType::Line(Line::new(pt(0.0, 0.0), pt(10.0, 0.0))),
    );
    add(
        "slot",
        EntityType::Line(Line::new(pt(0.0, 4.0), pt(10.0, 4.0))),
    );
    add(
        "slot",
        EntityType::Arc(Arc::new(pt(10.0, 2.0), 2.0, 270.0, 90.0)),
    );
    add(
        "other",
        EntityType::Line(Line::new(pt(10.0, 0.0), pt(20.0, -5.0))),
    );
    let mut bytes = Vec::new();
    d.save(&mut bytes).unwrap();
    let o = aecurve::outline_io::read_dxf(&bytes).unwrap();
    assert_eq!(
        o.shapes.len(),
        2,
        "{:?}",
        o.shapes.iter().map(|s| &s.name).collect::<Vec<_>>()
    );
    let slot = o
        .shapes
        .iter()
        .find(|s| s.name.starts_with("slot"))
        .unwrap();
    assert!(slot.name.ends_with("(4 entities)"), "{}", slot.name);
    let c = &slot.contours[0];
    assert!(c.closed);
    // Consecutive segments meet exactly (the reversed line included).
    for w in c.segments.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        assert!((a.eval(1.0) - b.eval(0.0)).hypot() < 1e-12);
    }
    let shapes = vec![slot];
    let checked = check_shapes(&shapes, &options_for(&o), &|| {});
    let joins = &checked[0].contours[0].joins;
    assert_eq!(
        joins.len(),
        c.segments.len(),
        "a closed contour: a join after every segment"
    );
    assert!(joins.iter().all(|j| j.g1), "{joins:?}");
    let jumps = joins.iter().filter(|j| j.g1 && !j.g2).count();
    assert_eq!(jumps, 4, "{joins:?}");
    // 20,000 LINEs of a zigzag, written in reverse order: one open contour, chained in
    // linear time (ends found through a grid, not by a search of every entity).
    let mut d = dxf::Drawing::new();
    let n = 20_000;
    let zig = |i: usize| pt(i as f64, (i % 2) as f64);
    for i in (0..n).rev() {
        d.add_entity(Entity::new(EntityType::Line(Line::new(zig(i), zig(i + 1)))));
    }
    let mut bytes = Vec::new();
    d.save(&mut bytes).unwrap();
    let t = std::time::Instant::now();
    let o = aecurve::outline_io::read_dxf(&bytes).unwrap();
    let secs = t.elapsed().as_secs_f64();
    assert_eq!(o.shapes.len(), 1);
    assert_eq!(o.shapes[0].contours[0].segments.len(), n);
    assert!(!o.shapes[0].contours[0].closed);
    assert!(o.shapes[0].name.len() < 60, "{}", o.shapes[0].name);
    println!("{n} LINEs read and chained in {secs:.2} s");
}

#[test]
fn dxf_entities_read_exactly() {
    use dxf::entities::{Arc, Circle, Entity, EntityType, Line, LwPolyline};
    use dxf::LwPolylineVertex;
    let mut d = dxf::Drawing::new();
    // LWPOLYLINE needs R14 or later.
    d.header.version = dxf::enums::AcadVersion::R2000;
    let pt = |x: f64, y: f64| dxf::Point::new(x, y, 0.0);
    d.add_entity(Entity::new(EntityType::Line(Line::new(
        pt(0.0, 0.0),
        pt(10.0, 0.0),
    ))));
    d.add_entity(Entity::new(EntityType::Arc(Arc::new(
        pt(20.0, 0.0),
        5.0,
        0.0,
        120.0,
    ))));
    d.add_entity(Entity::new(EntityType::Circle(Circle::new(
        pt(40.0, 0.0),
        4.0,
    ))));
    // A slot: straight sides, half-circle ends (bulge 1: 180°, radius 2).
    let mut slot = LwPolyline::default();
    for (x, y, b) in [
        (50.0, 0.0, 0.0),
        (60.0, 0.0, 1.0),
        (60.0, 4.0, 0.0),
        (50.0, 4.0, 1.0),
    ] {
        slot.vertices.push(LwPolylineVertex {
            x,
            y,
            bulge: b,
            ..Default::default()
        });
    }
    slot.set_is_closed(true);
    d.add_entity(Entity::new(EntityType::LwPolyline(slot)));
    let mut bytes = Vec::new();
    d.save(&mut bytes).unwrap();
    let o = aecurve::outline_io::read_dxf(&bytes).unwrap();
    assert_eq!(o.shapes.len(), 4);
    let shapes: Vec<_> = o.shapes.iter().collect();
    let checked = check_shapes(&shapes, &options_for(&o), &|| {});
    let curvatures = |i: usize| -> Vec<f64> {
        checked[i].contours[0]
            .segments
            .iter()
            .filter(|s| s.degree > 1)
            .map(|s| s.max_abs_curvature)
            .collect()
    };
    // The arc (120°: two pieces), the circle (four), the slot's ends (two of 90° each): 1/r
    // exactly.
    for (i, r, n) in [(1, 5.0, 2), (2, 4.0, 4), (3, 2.0, 4)] {
        let k = curvatures(i);
        assert_eq!(k.len(), n, "{i}");
        assert!(k.iter().all(|k| (k - 1.0 / r).abs() < 1e-12), "{i}: {k:?}");
        assert!(checked[i].contours[0].joins.iter().all(|j| j.g1));
    }
    let arc_end = o.shapes[1].contours[0].segments[1].eval(1.0);
    let a = 120f64.to_radians();
    assert!(
        (arc_end - aesthetic_curves::Point::new(20.0 + 5.0 * a.cos(), 5.0 * a.sin())).hypot()
            < 1e-12
    );
    // Our own SPLINE export reads back as the same rational cubics.
    let seg = aesthetic_curves::LacSegment::new(
        -1.0,
        [
            aesthetic_curves::Point::new(0.0, 0.0),
            aesthetic_curves::Point::new(10.0, 0.0),
            aesthetic_curves::Point::new(16.0, 9.0),
        ],
    )
    .unwrap();
    let fit = aesthetic_curves::approx::fit_rational_cubic(&seg, &Default::default()).unwrap();
    let nurbs = aesthetic_curves::nurbs::Nurbs::from_bezier(&fit.curve);
    let o = aecurve::outline_io::read_dxf(&aecurve::export::dxf_bytes(&nurbs).unwrap()).unwrap();
    let back = &o.shapes[0].contours[0].segments[0];
    let worst = (0..=20)
        .map(|i| (back.eval(i as f64 / 20.0) - fit.curve.eval(i as f64 / 20.0)).hypot())
        .fold(0.0, f64::max);
    // DXF stores decimal text, which the dxf crate writes with 12 digits after the point:
    // the round trip moves the curve by about 1e-12 drawing units (measured 1.1e-12 here).
    assert!(worst < 1e-11, "{worst:e}");
    // No curves: a clear error.
    let mut empty = Vec::new();
    dxf::Drawing::new().save(&mut empty).unwrap();
    let e = format!("{:#}", aecurve::outline_io::read_dxf(&empty).unwrap_err());
    assert!(e.contains("no curves"), "{e}");
}

#[test]
fn the_html_report_has_a_labelled_picture_per_shape_worst_first() {
    let o = read_font(FONT).unwrap();
    let shapes: Vec<_> = o
        .shapes
        .iter()
        .filter(|s| ["o", "S", "a", "period"].contains(&s.name.as_str()))
        .collect();
    let checked = check_shapes(&shapes, &options_for(&o), &|| {});
    let page = aecurve::report::outline_report("DejaVu Sans", true, &shapes, &checked, 3);
    assert_eq!(page.matches("<figure>").count(), 3);
    for bad in ["NaN", "Linf", "Minf", ",inf", "-inf", "=\"inf"] {
        assert!(!page.contains(bad), "{bad}");
    }
    // The S has near-breaks (the worst findings here): it comes first; the period, with
    // nothing to look at, is left out of three pictures.
    let first = page.find("<b>S</b>").unwrap();
    assert!(page.find("<b>o</b>").is_none_or(|i| i > first));
    assert!(!page.contains("<b>period</b>"));
    assert!(page.contains("the first 3 are drawn"));
}

#[test]
fn ufo_point_streams_read_as_their_segments() {
    use norad::{Contour, ContourPoint, Font, Glyph, PointType as T};
    let pt = |x: f64, y: f64, t: T| ContourPoint::new(x, y, t, false, None, None);
    let mut font = Font::new();
    // A circle of off-curve points only (TrueType style): four implied quadratics.
    let mut o = Glyph::new("o");
    o.contours.push(Contour::new(
        vec![
            pt(10.0, 0.0, T::OffCurve),
            pt(10.0, 10.0, T::OffCurve),
            pt(-10.0, 10.0, T::OffCurve),
            pt(-10.0, -10.0, T::OffCurve),
        ],
        None,
    ));
    // A closed contour starting with off-curve points, with a line, a cubic and a qcurve
    // of two off-curve points (two quadratics).
    let mut d = Glyph::new("d");
    d.contours.push(Contour::new(
        vec![
            pt(5.0, 10.0, T::OffCurve),
            pt(0.0, 10.0, T::Curve),
            pt(0.0, 0.0, T::Line),
            pt(4.0, -2.0, T::OffCurve),
            pt(8.0, -2.0, T::OffCurve),
            pt(10.0, 0.0, T::Curve),
            pt(12.0, 3.0, T::OffCurve),
            pt(12.0, 7.0, T::OffCurve),
            pt(10.0, 10.0, T::QCurve),
        ],
        None,
    ));
    // An open contour.
    let mut l = Glyph::new("l");
    l.contours.push(Contour::new(
        vec![
            pt(0.0, 0.0, T::Move),
            pt(0.0, 5.0, T::Line),
            pt(2.0, 7.0, T::OffCurve),
            pt(4.0, 7.0, T::Curve),
        ],
        None,
    ));
    for g in [o, d, l] {
        font.default_layer_mut().insert_glyph(g);
    }
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("aecurve-ufo-{}.ufo", std::process::id()));
    font.save(&dir).unwrap();
    let u = read(&dir).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    let get = |n: &str| &u.shapes.iter().find(|s| s.name == n).unwrap().contours[0];
    let o = get("o");
    assert!(o.closed && o.segments.len() == 4);
    assert!(o.segments.iter().all(|s| s.degree() == 2));
    let d = get("d");
    let degrees: Vec<usize> = d.segments.iter().map(|s| s.degree()).collect();
    // From (0, 10): line, cubic, two quadratics (the implied point at (12, 5)), quadratic back.
    assert_eq!(degrees, [1, 3, 2, 2, 2], "{:?}", d.segments);
    assert_eq!(
        d.segments[2].points()[2],
        aesthetic_curves::Point::new(12.0, 5.0)
    );
    assert!(d.closed);
    // Consecutive segments share their ends, and the contour closes on its start.
    for w in d.segments.windows(2) {
        assert_eq!(w[0].points().last(), w[1].points().first());
    }
    assert_eq!(
        d.segments.last().unwrap().points().last(),
        d.segments[0].points().first()
    );
    let l = get("l");
    assert!(!l.closed);
    assert_eq!(
        l.segments.iter().map(|s| s.degree()).collect::<Vec<_>>(),
        [1, 2]
    );
}

/// `check --json` on DejaVu Sans: findings ranked by severity and use, each place once
/// however many glyphs draw it (the `B` of `Beta` and of Cyrillic `В` is `B`'s own finding,
/// with them in `also_in`), and no two findings for the same place.
#[test]
fn findings_are_ranked_by_severity_and_listed_once_per_place() {
    let font = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/DejaVuSans.ttf");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_aecurve"))
        .args(["check", "--json", font])
        .output()
        .unwrap();
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let f = v["findings"].as_array().unwrap();
    // The rank: severity times the glyph's use weight, raised by 5 % per other glyph that
    // shares the place (up to ten); the list falls by it.
    let rank: Vec<f64> = f
        .iter()
        .map(|x| {
            let others = x["also_in"].as_array().map_or(0, |a| a.len()).min(10);
            let r = x["severity"].as_f64().unwrap()
                * x["use_weight"].as_f64().unwrap()
                * (1.0 + 0.05 * others as f64);
            assert!(
                (r - x["rank"].as_f64().unwrap()).abs() <= 1e-12 * r.abs(),
                "{x}"
            );
            r
        })
        .collect();
    assert!(rank.windows(2).all(|w| w[0] >= w[1]), "not ranked");
    // By use: basic Latin weighs 1, a dingbat 0.2; the top of the list is text, not
    // symbols (DejaVu Sans has thousands of symbol and non-Latin glyphs).
    let weight = |name: &str| {
        f.iter()
            .find(|x| x["shape"] == name)
            .map(|x| x["use_weight"].as_f64().unwrap())
    };
    assert_eq!(weight("S"), Some(1.0));
    let dingbat = f
        .iter()
        .find(|x| x["shape"].as_str().is_some_and(|n| n.starts_with("uni27")))
        .unwrap();
    assert_eq!(dingbat["use_weight"].as_f64(), Some(0.2), "{dingbat}");
    for x in &f[..20] {
        assert!(x["use_weight"].as_f64().unwrap() >= 0.4, "{x}");
    }
    // Defects apart from the design: the counts' defects and single extrema inside.
    let counts = &v["counts"];
    assert!(counts["defects"]["hooks"].as_u64().unwrap() > 0);
    assert!(counts["one_extremum_inside"].as_u64().unwrap() > 0);
    let b_in_beta = f.iter().any(|x| {
        x["shape"] == "B"
            && x["also_in"]
                .as_array()
                .is_some_and(|a| a.iter().any(|n| n == "Beta"))
    });
    assert!(b_in_beta, "B's findings do not name Beta");
    assert!(
        !f.iter().any(|x| x["shape"] == "Beta"),
        "Beta repeats B's findings"
    );
    // Each finding's glyph is named once (the first glyph, not again in also_in).
    for x in f {
        if let Some(a) = x["also_in"].as_array() {
            assert!(!a.iter().any(|n| *n == x["shape"]), "{x}");
        }
    }
}

/// A line running tangentially into a curve has a curvature step unless the curve ends
/// flat: the design of a stem meeting a bowl. It is listed only where the UFO marks the
/// point smooth; the same outline unmarked lists nothing there.
#[test]
fn line_curve_steps_are_listed_only_where_the_ufo_marks_them_smooth() {
    use norad::{Contour, ContourPoint, Font, Glyph, PointType as T};
    let glyph = |name: &str, smooth: bool| {
        let pt = |x: f64, y: f64, t: T, s: bool| ContourPoint::new(x, y, t, s, None, None);
        let mut g = Glyph::new(name);
        // A stem from (0, 0) up to (0, 300), then a bowl leaving it tangentially (its
        // first handle on the stem's line), back down to (0, 0) by a line.
        g.contours.push(Contour::new(
            vec![
                pt(0.0, 0.0, T::Line, false),
                pt(0.0, 300.0, T::Line, smooth),
                pt(0.0, 420.0, T::OffCurve, false),
                pt(250.0, 450.0, T::OffCurve, false),
                pt(300.0, 200.0, T::Curve, false),
            ],
            None,
        ));
        g
    };
    let mut font = Font::new();
    font.default_layer_mut().insert_glyph(glyph("marked", true));
    font.default_layer_mut().insert_glyph(glyph("plain", false));
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("aecurve-smooth-{}.ufo", std::process::id()));
    font.save(&dir).unwrap();
    let u = read(&dir).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    let shapes: Vec<_> = u.shapes.iter().collect();
    let checked = check_shapes(&shapes, &options_for(&u), &|| {});
    let at_stem_top = |name: &str| {
        let c = checked.iter().find(|c| c.name == name).unwrap();
        let join = c.contours[0]
            .joins
            .iter()
            .find(|j| j.point == aesthetic_curves::Point::new(0.0, 300.0))
            .unwrap();
        assert!(join.g1 && !join.g2, "{join:?}");
        let listed = c
            .findings
            .iter()
            .any(|f| f.kind == "curvature-jump" && f.point == join.point);
        (join.smooth_mark, listed)
    };
    assert_eq!(at_stem_top("marked"), (Some(true), true));
    assert_eq!(at_stem_top("plain"), (Some(false), false));
}

/// `check --json` is one document of the schema's `x-cli.check` (`CheckFileJson`): every
/// field it prints is a property there and every property is printed, on a font with
/// findings shared by several glyphs and on an SVG.
#[test]
fn check_json_is_the_documented_type() {
    use aecurve::check_json::CheckFileJson;
    let schema = aecurve::protocol::response_schema::<CheckFileJson>();
    let props = |s: &serde_json::Value| -> std::collections::BTreeSet<String> {
        s["properties"]
            .as_object()
            .unwrap()
            .keys()
            .cloned()
            .collect()
    };
    for file in [
        concat!(env!("CARGO_MANIFEST_DIR"), "/assets/DejaVuSans.ttf"),
        concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/outline.svg"),
    ] {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_aecurve"))
            .args(["check", "--json", file])
            .output()
            .unwrap();
        assert!(out.status.success(), "{file}");
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        crate::schema::valid_as::<CheckFileJson>(&v);
        let printed: std::collections::BTreeSet<String> =
            v.as_object().unwrap().keys().cloned().collect();
        assert_eq!(printed, props(&schema), "{file}");
        let counts = &schema["$defs"]["CheckCountsJson"];
        assert_eq!(
            v["counts"]
                .as_object()
                .unwrap()
                .keys()
                .cloned()
                .collect::<std::collections::BTreeSet<_>>(),
            props(counts),
            "{file}"
        );
    }
}
