//! `aecurve fix` on a UFO: the written UFO has the same structure, only
//! off-curve points move, the outline within the tolerance and on the grid, no join is worse and no
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

/// A closed contour of curve points as its cubics (on, off, off, on).
fn cubics(c: &Contour) -> Vec<[kurbo::Point; 4]> {
    let pts: Vec<(kurbo::Point, bool)> = (c.points.iter())
        .map(|p| (kurbo::Point::new(p.x, p.y), p.typ != PointType::OffCurve))
        .collect();
    let n = pts.len();
    let first = pts.iter().position(|p| p.1).unwrap();
    (0..n)
        .map(|k| (first + k) % n)
        .filter(|&i| pts[i].1 && !pts[(i + 1) % n].1)
        .map(|i| [0, 1, 2, 3].map(|k| pts[(i + k) % n].0))
        .collect()
}

/// The largest distance between two lists of cubics as shapes: per pair, the Hausdorff
/// distance both ways (401 points of one, each point's nearest of 2,001 samples of the
/// other refined by golden sections; Bernstein sums here, not the fix's sound bound).
fn outline_distance(a: &[[kurbo::Point; 4]], b: &[[kurbo::Point; 4]]) -> f64 {
    assert_eq!(a.len(), b.len());
    let at = |c: &[kurbo::Point; 4], t: f64| {
        let m = 1.0 - t;
        let w = [m * m * m, 3.0 * t * m * m, 3.0 * t * t * m, t * t * t];
        (0..4).fold(kurbo::Vec2::ZERO, |s, i| s + c[i].to_vec2() * w[i])
    };
    let one_way = |x: &[kurbo::Point; 4], y: &[kurbo::Point; 4]| {
        let n = 2000;
        (0..=400)
            .map(|k| at(y, k as f64 / 400.0))
            .map(|q| {
                let d = |s: f64| (at(x, s) - q).hypot();
                let best = (0..=n)
                    .min_by(|&i, &j| d(i as f64 / n as f64).total_cmp(&d(j as f64 / n as f64)));
                let best = best.unwrap() as f64 / n as f64;
                let (mut lo, mut hi) = (
                    (best - 1.0 / n as f64).max(0.0),
                    (best + 1.0 / n as f64).min(1.0),
                );
                for _ in 0..60 {
                    let (x1, x2) = (lo + 0.382 * (hi - lo), lo + 0.618 * (hi - lo));
                    if d(x1) < d(x2) {
                        hi = x2;
                    } else {
                        lo = x1;
                    }
                }
                d(0.5 * (lo + hi)).min(d(best))
            })
            .fold(0.0, f64::max)
    };
    let mut worst = 0.0f64;
    for (x, y) in a.iter().zip(b) {
        if x != y {
            worst = worst.max(one_way(x, y)).max(one_way(y, x));
        }
    }
    worst
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
            deadline: None,
        },
        false,
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
                assert_eq!(
                    (pb.x.fract(), pb.y.fract()),
                    (0.0, 0.0),
                    "{name}: off the grid"
                );
            }
        }
    }
    // The outline within the tolerance (a handle alone may move further: the outline
    // follows it by at most 4/9 of its move).
    for (ca, cb) in
        (a.get_glyph("o").unwrap().contours.iter()).zip(&b.get_glyph("o").unwrap().contours)
    {
        let d = outline_distance(&cubics(ca), &cubics(cb));
        assert!(d <= tolerance, "the outline moved {d}");
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
    // Closer to G2: the sum of the jumps down by more than 40 % (G2 everywhere would push
    // the cubics' extrema into hooks at the joins, which the fix never makes).
    assert!(total.1 < 0.6 * total.0, "jumps {total:?}");
    for (x, y) in before.segments.iter().zip(&after.segments) {
        let hook = |s: &aesthetic_curves::outline::SegmentCheck| {
            s.extrema.iter().any(|(t, _)| *t < 0.05 || *t > 0.95)
        };
        assert!(!hook(y) || hook(x), "a new hook: {y:?}");
    }
    for (x, y) in before.segments.iter().zip(&after.segments) {
        assert!(y.extrema.len() <= x.extrema.len());
    }
}

#[test]
fn fix_refuses_to_replace_a_file_and_says_what_it_cannot_read() {
    let dir = scratch("refuse");
    let src = source(&dir);
    let exe = env!("CARGO_BIN_EXE_aecurve");
    let run = |args: &[&str]| std::process::Command::new(exe).args(args).output().unwrap();
    let out = run(&["fix", src.to_str().unwrap(), "-o", src.to_str().unwrap()]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("already exists"));
    // A designspace with no source, and a file of another kind: said so.
    let ds = dir.join("a.designspace");
    std::fs::write(&ds, "<designspace/>").unwrap();
    let out = run(&[
        "fix",
        ds.to_str().unwrap(),
        "-o",
        dir.join("b.designspace").to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("no <source>"));
    let txt = dir.join("a.txt");
    std::fs::write(&txt, "x").unwrap();
    let out = run(&[
        "fix",
        txt.to_str().unwrap(),
        "-o",
        dir.join("b.txt").to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("designspaces and SVG files"));
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
        deadline: None,
    };
    let (fixes, counts) = fix_svg(&src, &dst, &opts, false).unwrap();
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

/// The UFO at `p` with every point of every contour of "o" mapped by `f`.
fn mapped(p: &Path, out: &Path, f: impl Fn(f64, f64) -> (f64, f64)) {
    let mut font = Font::load(p).unwrap();
    let o = font.default_layer_mut().get_glyph_mut("o").unwrap();
    for c in &mut o.contours {
        for q in &mut c.points {
            let (x, y) = f(q.x, q.y);
            (q.x, q.y) = (x.round(), y.round());
        }
    }
    font.save(out).unwrap();
}

/// The instance half way between the "o" of two UFOs (same structure), written as a UFO.
fn halfway(a: &Path, b: &Path, out: &Path) {
    let (fa, fb) = (Font::load(a).unwrap(), Font::load(b).unwrap());
    let mut font = Font::new();
    let mut g = fa.get_glyph("o").unwrap().clone();
    let gb = fb.get_glyph("o").unwrap();
    for (c, cb) in g.contours.iter_mut().zip(&gb.contours) {
        for (q, qb) in c.points.iter_mut().zip(&cb.points) {
            (q.x, q.y) = ((q.x + qb.x) / 2.0, (q.y + qb.y) / 2.0);
        }
    }
    font.default_layer_mut().insert_glyph(g);
    font.save(out).unwrap();
}

/// Two masters of the "o" whose tangents turn between them (the second sheared and
/// widened, so the handle ratios at its slanted joins matter to the instances): after
/// `fix` on the designspace, both masters have the same structure as before, and the
/// instance half way between them, made here point by point and checked by `check`, has
/// no join with a larger angle or curvature jump and no segment with more extrema than
/// the same instance of the input's masters. A sparse master (a layer source) is refused.
#[test]
fn fix_on_a_designspace_keeps_the_instances_no_worse() {
    use aecurve::fix::masters::fix_designspace;
    let dir = scratch("designspace");
    let thin = source(&dir);
    std::fs::create_dir_all(dir.join("masters")).unwrap();
    let (a, b) = (dir.join("masters/A.ufo"), dir.join("masters/B.ufo"));
    mapped(&thin, &a, |x, y| (x, y));
    mapped(&thin, &b, |x, y| (1.3 * x + 0.25 * y, 0.9 * y));
    let ds = |sources: &str| {
        format!(
            "<?xml version='1.0' encoding='UTF-8'?>\n<designspace format=\"5.0\">\n  <axes>\n    \
             <axis tag=\"wght\" name=\"weight\" minimum=\"100\" maximum=\"800\" default=\"100\"/>\n  \
             </axes>\n  <sources>\n{sources}  </sources>\n</designspace>\n"
        )
    };
    let source_el = |file: &str, w: u32, extra: &str| {
        format!(
            "    <source filename=\"{file}\" name=\"{w}\"{extra}>\n      <location><dimension \
             name=\"weight\" xvalue=\"{w}\"/></location>\n    </source>\n"
        )
    };
    let input = dir.join("o.designspace");
    std::fs::write(
        &input,
        ds(&(source_el("masters/A.ufo", 100, "") + &source_el("masters/B.ufo", 800, ""))),
    )
    .unwrap();
    let output = dir.join("out/o.designspace");
    let opts = FixOptions {
        tolerance: 30.0,
        grid: 1.0,
        move_points: false,
        repairs: Default::default(),
        deadline: None,
    };
    let d = fix_designspace(&input, &output, &opts, false).unwrap();
    assert_eq!(d.masters.len(), 2);
    assert_eq!(d.compatible_contours, 1, "the o's contour is held together");
    let outs = [dir.join("out/masters/A.ufo"), dir.join("out/masters/B.ufo")];
    assert!(output.is_file());
    let mut changed = 0;
    for (src, out) in [&a, &b].into_iter().zip(&outs) {
        let (ga, gb) = (
            Font::load(src).unwrap().get_glyph("o").unwrap().clone(),
            Font::load(out).unwrap().get_glyph("o").unwrap().clone(),
        );
        for (ca, cb) in ga.contours.iter().zip(&gb.contours) {
            assert_eq!(ca.points.len(), cb.points.len());
            for (pa, pb) in ca.points.iter().zip(&cb.points) {
                assert_eq!((pa.typ, pa.smooth, &pa.name), (pb.typ, pb.smooth, &pb.name));
                changed += ((pa.x, pa.y) != (pb.x, pb.y)) as usize;
            }
        }
    }
    assert!(changed > 0, "nothing was fixed");
    halfway(&a, &b, &dir.join("half-in.ufo"));
    halfway(&outs[0], &outs[1], &dir.join("half-out.ufo"));
    let (before, after) = (
        check_o(&dir.join("half-in.ufo")),
        check_o(&dir.join("half-out.ufo")),
    );
    for (x, y) in before.joins.iter().zip(&after.joins) {
        assert!(y.angle_break <= x.angle_break + 1e-12, "{x:?} -> {y:?}");
        if let (Some(p), Some(q)) = (x.curvature_jump, y.curvature_jump) {
            assert!(q <= p * (1.0 + 1e-9) + 1e-12, "{x:?} -> {y:?}");
        }
    }
    for (x, y) in before.segments.iter().zip(&after.segments) {
        assert!(y.extrema.len() <= x.extrema.len());
    }
    // A sparse master: refused, naming the layer.
    let sparse = dir.join("sparse.designspace");
    std::fs::write(
        &sparse,
        ds(&(source_el("masters/A.ufo", 100, "")
            + &source_el("masters/B.ufo", 800, " layer=\"bold\""))),
    )
    .unwrap();
    let err = fix_designspace(&sparse, &dir.join("out2/o.designspace"), &opts, false)
        .err()
        .unwrap();
    assert!(format!("{err:#}").contains("\"bold\""), "{err:#}");
}

/// `fix --report`: a page with the changed glyph drawn before and after (its moved points
/// marked in their own colour), and nothing for the glyph left alone.
#[test]
fn fix_report_draws_the_changed_glyphs_before_and_after() {
    let dir = scratch("report");
    let src = source(&dir);
    let page = dir.join("fix.html");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_aecurve"))
        .args(["fix", src.to_str().unwrap(), "-o"])
        .arg(dir.join("fixed.ufo"))
        .args(["--tolerance", "40", "--report"])
        .arg(&page)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let html = std::fs::read_to_string(&page).unwrap();
    assert!(html.contains("<b>o</b>"), "the o is drawn");
    assert!(
        !html.contains("<b>q</b>"),
        "the quadratic q was not changed"
    );
    assert_eq!(html.matches("<svg").count(), 2, "before and after");
    let after = &html[html.rfind("<svg").unwrap()..];
    let before = &html[html.find("<svg").unwrap()..html.rfind("<svg").unwrap()];
    assert!(
        after.contains("fill=\"#c2189b\""),
        "moved points marked after"
    );
    assert!(!before.contains("#c2189b"), "nothing marked before");
    assert!(html.contains("1 shapes changed"));
}

/// `fix --json` prints the protocol's types (`x-cli.fix` of `aecurve schema`): on a UFO and
/// an SVG file the `FixFileResult`, on a designspace the `FixDesignspaceResult`, each valid
/// against the schema; its counts are the library's, and its joins say `harmonized` exactly
/// when the jump after is under 1 %.
#[test]
fn fix_json_is_the_schemas_fix_result() {
    use aecurve::protocol::fix_file::{FixDesignspaceResult, FixFileResult};
    let dir = scratch("json");
    let exe = env!("CARGO_BIN_EXE_aecurve");
    let fix = |src: &Path, dst: &Path| -> serde_json::Value {
        crate::cli::json_output(
            std::process::Command::new(exe)
                .args(["fix", src.to_str().unwrap(), "-o", dst.to_str().unwrap()])
                .args(["--tolerance", "40", "--json"]),
        )
    };
    let ufo = fix(&source(&dir), &dir.join("out.ufo"));
    crate::schema::valid_as::<FixFileResult>(&ufo);
    let counts = &ufo["counts"];
    assert!(counts["changed_segments"].as_u64().unwrap() > 0, "{counts}");
    assert_eq!(counts["worse_joins"], 0);
    let joins: Vec<&serde_json::Value> = ufo["contours"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|c| c["joins"].as_array().unwrap())
        .collect();
    assert!(!joins.is_empty());
    for j in &joins {
        let after = j["jump"][1].as_f64();
        let harmonized = j["outcome"] == "harmonized";
        assert_eq!(
            harmonized,
            harmonized && after.is_some_and(|a| a < 0.01),
            "{j}"
        );
    }
    // An SVG with a path fix cannot read: listed with its reason.
    let svg = dir.join("in.svg");
    std::fs::write(
        &svg,
        "<svg xmlns=\"http://www.w3.org/2000/svg\"><path d=\"M 0 0 C 0 265 -270 400 -600 400 \
         C -890 400 -1200 200 -1200 0\"/><path d=\"M 0 0 A 50 50 0 0 1 100 0\"/></svg>",
    )
    .unwrap();
    let v = fix(&svg, &dir.join("out.svg"));
    crate::schema::valid_as::<FixFileResult>(&v);
    assert!(
        v["contours"]
            .as_array()
            .unwrap()
            .iter()
            .any(|c| c["skipped"].is_string()),
        "{v}"
    );
    // A designspace of one master.
    let ds = dir.join("o.designspace");
    std::fs::rename(dir.join("out.ufo"), dir.join("m.ufo")).unwrap();
    std::fs::write(
        &ds,
        "<?xml version='1.0' encoding='UTF-8'?>\n<designspace format=\"5.0\"><axes><axis \
         tag=\"wght\" name=\"weight\" minimum=\"100\" maximum=\"800\" default=\"100\"/></axes>\
         <sources><source filename=\"m.ufo\" name=\"m\"><location><dimension name=\"weight\" \
         xvalue=\"100\"/></location></source></sources></designspace>\n",
    )
    .unwrap();
    let v = fix(&ds, &dir.join("out/o.designspace"));
    crate::schema::valid_as::<FixDesignspaceResult>(&v);
    assert_eq!(v["masters"][0]["source"], "m.ufo", "{v}");
}
