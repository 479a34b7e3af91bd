//! `aecurve fix` on a UFO (issue 34): the written UFO has the same structure, only
//! off-curve points move, within the tolerance and on the grid, no join is worse and no
//! cubic gains curvature extrema (by the exact check of the output, not the fix's own
//! numbers); quadratic contours are left alone and said so.

use aecurve::fix::{fix_ufo, FixOptions};
use aecurve::outline_io::{check_shapes, options_for, read};
use norad::{Contour, ContourPoint, Font, Glyph, Name, PointType};
use std::path::{Path, PathBuf};

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("fix-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The exact check of the first contour of the shape named "o" in the file at `p`.
fn check_o(p: &Path) -> aesthetic_curves::outline::ContourCheck {
    let o = read(p).unwrap();
    let shapes: Vec<_> = o.shapes.iter().filter(|s| s.name == "o").collect();
    check_shapes(&shapes, &options_for(&o), &|| {})
        .remove(0)
        .contours
        .remove(0)
}

fn point(x: f64, y: f64, typ: PointType, smooth: bool) -> ContourPoint {
    ContourPoint::new(x, y, typ, smooth, None, None)
}

/// An "o" of four cubics (quarter ellipses with handles off their G2 lengths, integer
/// units, smooth joins, a named point) and a "q" drawn with quadratics.
fn source(dir: &Path) -> PathBuf {
    use PointType::{Curve, OffCurve, QCurve};
    let mut font = Font::new();
    let mut o = Glyph::new("o");
    let mut pts = vec![
        point(600.0, 0.0, Curve, true),
        point(600.0, 265.0, OffCurve, false),
        point(330.0, 400.0, OffCurve, false),
        point(0.0, 400.0, Curve, true),
        point(-290.0, 400.0, OffCurve, false),
        point(-600.0, 200.0, OffCurve, false),
        point(-600.0, 0.0, Curve, true),
        point(-600.0, -250.0, OffCurve, false),
        point(-360.0, -400.0, OffCurve, false),
        point(0.0, -400.0, Curve, true),
        point(300.0, -400.0, OffCurve, false),
        point(600.0, -190.0, OffCurve, false),
    ];
    pts[3].name = Some(Name::new("top").unwrap());
    o.contours.push(Contour::new(pts, None));
    let mut q = Glyph::new("q");
    q.contours.push(Contour::new(
        vec![
            point(0.0, 0.0, QCurve, true),
            point(100.0, 0.0, OffCurve, false),
            point(100.0, 100.0, QCurve, true),
            point(0.0, 100.0, OffCurve, false),
        ],
        None,
    ));
    font.default_layer_mut().insert_glyph(o);
    font.default_layer_mut().insert_glyph(q);
    let path = dir.join("source.ufo");
    font.save(&path).unwrap();
    path
}

#[test]
fn fix_writes_the_same_structure_and_nothing_worse() {
    let dir = scratch("structure");
    let src = source(&dir);
    let dst = dir.join("fixed.ufo");
    let tolerance = 40.0;
    let (fixes, counts) = fix_ufo(
        &src,
        &dst,
        &FixOptions {
            tolerance,
            grid: 1.0,
            move_points: false,
            repairs: Default::default(),
        },
    )
    .unwrap();
    // The quadratic contour is left alone, with the reason.
    let q = fixes.iter().find(|f| f.glyph == "q").unwrap();
    assert!(
        q.result.as_ref().unwrap_err().contains("quadratic"),
        "{:?}",
        q.result.as_ref().err()
    );
    assert_eq!(counts.skipped_contours, 1);
    assert!(counts.changed_segments > 0, "{counts:?}");
    let (a, b) = (Font::load(&src).unwrap(), Font::load(&dst).unwrap());
    for name in ["o", "q"] {
        let (ga, gb) = (a.get_glyph(name).unwrap(), b.get_glyph(name).unwrap());
        assert_eq!(ga.contours.len(), gb.contours.len());
        for (ca, cb) in ga.contours.iter().zip(&gb.contours) {
            assert_eq!(ca.points.len(), cb.points.len());
            for (pa, pb) in ca.points.iter().zip(&cb.points) {
                assert_eq!((pa.typ, pa.smooth, &pa.name), (pb.typ, pb.smooth, &pb.name));
                let d = (pa.x - pb.x).hypot(pa.y - pb.y);
                if pa.typ != PointType::OffCurve {
                    assert_eq!(d, 0.0, "an on-curve point of {name} moved");
                }
                assert!(d <= tolerance, "{name}: moved {d}");
                assert_eq!(
                    (pb.x.fract(), pb.y.fract()),
                    (0.0, 0.0),
                    "{name}: off the grid"
                );
            }
        }
    }
    assert_eq!(
        a.get_glyph("q").unwrap().contours,
        b.get_glyph("q").unwrap().contours
    );
    // The exact check of the written file: nothing worse, and the "o" closer to G2.
    let (before, after) = (check_o(&src), check_o(&dst));
    let mut total = (0.0, 0.0);
    for (x, y) in before.joins.iter().zip(&after.joins) {
        let (jx, jy) = (x.curvature_jump.unwrap(), y.curvature_jump.unwrap());
        assert!(
            jy <= jx * (1.0 + 1e-9) && y.angle_break <= x.angle_break + 1e-12,
            "{x:?} {y:?}"
        );
        total = (total.0 + jx, total.1 + jy);
    }
    assert!(total.1 < 0.5 * total.0, "jumps {total:?}");
    for (x, y) in before.segments.iter().zip(&after.segments) {
        assert!(y.extrema.len() <= x.extrema.len());
    }
}

#[test]
fn fix_refuses_to_replace_a_file_and_reads_only_ufo_and_svg() {
    let dir = scratch("refuse");
    let src = source(&dir);
    let exe = env!("CARGO_BIN_EXE_aecurve");
    let run = |args: &[&str]| std::process::Command::new(exe).args(args).output().unwrap();
    let out = run(&["fix", src.to_str().unwrap(), "-o", src.to_str().unwrap()]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("already exists"));
    let ds = dir.join("a.designspace");
    std::fs::write(&ds, "<designspace/>").unwrap();
    let out = run(&[
        "fix",
        ds.to_str().unwrap(),
        "-o",
        dir.join("b.designspace").to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("not done yet"));
}

/// An SVG: only the `d` of the changed path is rewritten (everything else byte for byte),
/// a path with an arc is left and listed, and the written file reads back with the same
/// segments and no join worse.
#[test]
fn fix_rewrites_only_the_path_data_of_an_svg() {
    use aecurve::fix::fix_svg;
    let dir = scratch("svg");
    let src = dir.join("in.svg");
    let o = "m 600 0 c 0 265 -270 400 -600 400 c -290 0 -600 -200 -600 -400 \
             c 0 -250 240 -400 600 -400 c 300 0 600 210 600 400 z";
    let text = format!(
        "<?xml version=\"1.0\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"-700 -500 1400 1000\">\n\
         <!-- kept -->\n<path id=\"o\" fill=\"#123\" d=\"{o}\"/>\n\
         <path id=\"arc\" d=\"M 0 0 A 50 50 0 0 1 100 0\"/>\n</svg>\n"
    );
    std::fs::write(&src, &text).unwrap();
    let dst = dir.join("out.svg");
    let opts = FixOptions {
        tolerance: 40.0,
        grid: 1e-4,
        move_points: false,
        repairs: Default::default(),
    };
    let (fixes, counts) = fix_svg(&src, &dst, &opts).unwrap();
    let out = std::fs::read_to_string(&dst).unwrap();
    // Outside the o's d attribute, the text is the input's.
    let (pre, post) = text.split_once(o).unwrap();
    assert!(out.starts_with(pre) && out.ends_with(post), "{out}");
    assert!(fixes.iter().any(|f| f.glyph == "arc" && f.result.is_err()));
    assert!(counts.changed_segments > 0, "{counts:?}");
    let (before, after) = (check_o(&src), check_o(&dst));
    assert_eq!(before.segments.len(), after.segments.len());
    for (x, y) in before.joins.iter().zip(&after.joins) {
        let (jx, jy) = (x.curvature_jump.unwrap(), y.curvature_jump.unwrap());
        assert!(jy <= jx + 1e-6, "{x:?} {y:?}");
    }
}
