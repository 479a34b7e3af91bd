//! End-to-end runs of the `aecurve` binary.

use crate::schema::{valid_as, valid_response};
use std::io::Write;
use std::process::{Command, Stdio};

fn aecurve() -> Command {
    Command::new(env!("CARGO_BIN_EXE_aecurve"))
}

/// Run a command that must succeed and print one JSON value.
pub(crate) fn json_output(cmd: &mut Command) -> serde_json::Value {
    let out = cmd.output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// The first answer of `aecurve batch` to one request line.
fn batch_one(request: &str) -> serde_json::Value {
    let mut child = aecurve()
        .arg("batch")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(format!("{request}\n").as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    let text = String::from_utf8(out.stdout).unwrap();
    let v = serde_json::from_str(text.lines().next().unwrap()).unwrap();
    valid_response(&v);
    v
}

#[test]
fn batch_answers_every_line_in_order() {
    let mut child = aecurve()
        .arg("batch")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let input = concat!(
        r#"{"id": 1, "op": "bezier.curvature_monotone", "control_points": [[0,0],[1,1],[2,1],[3,0]]}"#,
        "\n\nnot json\n",
        r#"{"id": 2, "op": "bezier.curvature_monotone", "control_points": [[1,0],[1,1],[0,1]], "weights": [1, 0.7071067811865476, 1]}"#,
        "\n",
        r#"{"id": 3, "op": "bezier.curvature_monotone", "control_points": [[0,0],[1,1],[2,1],[3,0]], "method": "sampling", "samples": 50}"#,
        "\n"
    );
    child
        .stdin
        .take()
        .unwrap()
        .write_all(input.as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success());
    let lines: Vec<serde_json::Value> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 4);
    lines.iter().for_each(valid_response);
    assert_eq!(lines[0]["id"], 1);
    assert_eq!(lines[0]["result"]["monotone"], false);
    assert_eq!(lines[1]["error"]["kind"], "parse");
    // The f64 quarter arc is exactly an ellipse arc: its extremum at the middle.
    assert_eq!(lines[2]["result"]["monotone"], false);
    assert!((lines[2]["result"]["extrema"][0].as_f64().unwrap() - 0.5).abs() < 1e-12);
    assert_eq!(lines[3]["result"]["samples"], 50);
}

#[test]
fn monotone_command_reads_for_a_person_and_fails_clearly() {
    let out = aecurve()
        .args(["monotone", "--points", "0,0 1,1 2,1 3,0"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("NOT monotone"), "{text}");
    assert!(text.contains("t = 0.500000000"), "{text}");
    // A retracted handle gets a verdict and says what the curvature does there.
    let out = aecurve()
        .args(["monotone", "--points", "0,0 0,0 1,1 2,0"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.contains("retracted handle") && text.contains("unbounded"),
        "{text}"
    );
    // A cusp does not.
    let out = aecurve()
        .args(["monotone", "--points", "0,0 2,1 0,1 2,0"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8(out.stderr)
        .unwrap()
        .contains("degenerate"));
    let out = aecurve()
        .args(["monotone", "--points", "0,0 1,x"])
        .output()
        .unwrap();
    assert!(!out.status.success());
}

#[test]
fn bench_json_has_the_promised_shape() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("aecurve-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let svg = dir.join("fig.svg");
    let v = json_output(
        aecurve()
            .args(["bench", "monotone", "--curves", "60", "--round-ms", "2"])
            .args(["--json", "-o"])
            .arg(&svg),
    );
    valid_as::<aecurve::bench::BenchMonotoneResult>(&v);
    let rows = v["results"].as_array().unwrap();
    assert_eq!(rows.len(), 12);
    for r in rows {
        assert!(r["ns_per_curve"].as_f64().unwrap() > 0.0);
        assert!(r["disagreements"].as_u64().is_some());
        let m = r["method"].as_str().unwrap();
        assert!(
            m == "exact" && r["samples"].is_null()
                || m == "sampling" && r["samples"].as_u64().is_some()
        );
    }
    let chart = std::fs::read_to_string(&svg).unwrap();
    assert!(chart.starts_with("<svg") && chart.contains("polyline"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bench_targets_report_every_hot_path() {
    for (group, least) in [("lac", 8), ("approx", 6), ("spline", 4)] {
        let v = json_output(aecurve().args([
            "bench",
            group,
            "--rounds",
            "1",
            "--round-ms",
            "1",
            "--json",
        ]));
        valid_as::<aecurve::bench_targets::BenchTargetsResult>(&v);
        assert_eq!(v["group"], group);
        let rows = v["results"].as_array().unwrap();
        assert!(rows.len() >= least, "{group}: {rows:?}");
        for r in rows {
            let ns = r["ns"].as_f64().unwrap();
            assert!(ns > 0.0 && ns.is_finite(), "{r}");
            assert!(r["work"].as_str().is_some_and(|w| !w.is_empty()));
            match r["target_ns"].as_f64() {
                Some(t) => assert_eq!(r["meets_target"].as_bool(), Some(ns <= t)),
                None => assert!(r["meets_target"].is_null()),
            }
        }
    }
    // Sizes are capped with a message.
    let out = aecurve()
        .args(["bench", "lac", "--rounds", "0"])
        .output()
        .unwrap();
    assert!(!out.status.success());
}

#[test]
fn lac_command_summarises_and_refuses_outside_the_region() {
    let v = json_output(aecurve().args([
        "lac",
        "--alpha",
        "-1",
        "--control",
        "0,0 10,0 16,9",
        "--json",
    ]));
    valid_as::<aecurve::protocol::lac::LacSegmentResult>(&v);
    assert!(v["lambda"].as_f64().unwrap() > 0.0);
    assert_eq!(v["points"].as_array().unwrap().len(), 65);
    let out = aecurve()
        .args(["lac", "--alpha", "-1", "--control", "0,0 1,0 1,0.3"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains("no segment") && err.contains("60.666"),
        "{err}"
    );
}

#[test]
fn lcg_command_reads_a_file_and_plots() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("aecurve-lcg-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // Samples of a LAC segment (alpha = 2) written as CSV, read back by `lcg --input`.
    let seg = json_output(aecurve().args([
        "lac",
        "--alpha",
        "2",
        "--control",
        "0,0 4,0 7,3",
        "--samples",
        "150",
        "--json",
    ]));
    valid_as::<aecurve::protocol::lac::LacSegmentResult>(&seg);
    let mut csv = String::from("x,y\n");
    for p in seg["points"].as_array().unwrap() {
        csv += &format!("{},{}\n", p[0], p[1]);
    }
    let input = dir.join("pts.csv");
    std::fs::write(&input, csv).unwrap();
    let svg = dir.join("lcg.svg");
    let v = json_output(aecurve().args([
        "lcg",
        "--input",
        input.to_str().unwrap(),
        "--json",
        "-o",
        svg.to_str().unwrap(),
    ]));
    valid_as::<aecurve::protocol::lcg::LcgResult>(&v);
    assert!(
        (v["alpha"].as_f64().unwrap() - 2.0).abs() < 1e-4,
        "{}",
        v["alpha"]
    );
    let chart = std::fs::read_to_string(&svg).unwrap();
    assert!(chart.starts_with("<svg") && chart.contains("circle"));
    // The analytic graph of the segment itself.
    let v =
        json_output(aecurve().args(["lcg", "--alpha", "-1", "--control", "0,0 4,0 7,3", "--json"]));
    valid_as::<aecurve::protocol::lcg::LcgResult>(&v);
    assert!((v["alpha"].as_f64().unwrap() + 1.0).abs() < 1e-9);
    // A circle has no LCG slope: a clear error, not a number.
    let circle: Vec<String> = (0..12)
        .map(|i| {
            let a = 0.1 * i as f64;
            format!("{},{}", a.cos(), a.sin())
        })
        .collect();
    let out = aecurve()
        .args(["lcg", "--points", &circle.join(" ")])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn lac_inflection_form() {
    let v = json_output(aecurve().args([
        "lac",
        "--inflection",
        "--control",
        "0,0 1,0 1,0.5773502691896257",
        "--json",
    ]));
    valid_as::<aecurve::protocol::lac::LacInflectionResult>(&v);
    // 90 degrees of turning, 30 degrees at the inflection end: docs/math.md §3.2's check value.
    assert!(
        (v["alpha"].as_f64().unwrap() + 1.066636984).abs() < 1e-8,
        "{}",
        v["alpha"]
    );
    // 45 degrees at the inflection end is outside the region (it must be below 45).
    let out = aecurve()
        .args(["lac", "--inflection", "--control", "0,0 1,0 1,1"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("no segment"));
}

#[test]
fn pictures_follow_the_extension() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("aecurve-png-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let png = dir.join("c.png");
    let svg = dir.join("c.svg");
    let out = aecurve()
        .args(["lac", "--alpha", "0", "--control", "0,0 3,0 5,2", "-o"])
        .arg(&png)
        .arg("-o")
        .arg(&svg)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    assert!(
        bytes.len() > 5000,
        "an empty picture? {} bytes",
        bytes.len()
    );
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
    // An unknown extension fails before any work, naming the file.
    let out = aecurve()
        .args([
            "lac",
            "--alpha",
            "0",
            "--control",
            "0,0 3,0 5,2",
            "-o",
            "x.jpeg",
        ])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("x.jpeg"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn approx_command_gives_a_checked_cubic_and_pictures() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("aecurve-approx-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let map = dir.join("map.svg");
    let v = json_output(
        aecurve()
            .args([
                "approx",
                "--alpha",
                "-1",
                "--control",
                "0,0 10,0 16,9",
                "--tolerance",
                "1e-9",
                "--json",
                "--map-cells",
                "20",
                "--map",
            ])
            .arg(&map),
    );
    valid_as::<aecurve::protocol::lac::RationalApproxResult>(&v);
    assert_eq!(v["control_points"].as_array().unwrap().len(), 4);
    let w: Vec<f64> = v["weights"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!(w.len() == 4 && w.iter().all(|x| *x > 0.0));
    assert_eq!(v["monotone"], true);
    assert!(v["rms"].as_f64().unwrap() < 1e-6);
    let sp = &v["spline"];
    let pieces = sp["pieces"].as_u64().unwrap() as usize;
    assert!(pieces >= 2);
    assert_eq!(
        sp["control_points"].as_array().unwrap().len(),
        3 * pieces + 1
    );
    assert!(sp["max_error"].as_f64().unwrap() <= 1e-9);
    let svg = std::fs::read_to_string(&map).unwrap();
    // 400 cells and the colour bar; the non-monotone cells hatched (plotters draws the
    // hatching as line pieces, and its key as text).
    assert!(svg.matches("<rect").count() > 400);
    assert!(svg.contains("not monotone") && svg.matches("<polyline").count() > 20);
    // Outside the existence region: no_segment, said clearly.
    let out = aecurve()
        .args(["approx", "--alpha", "-1", "--control", "0,0 1,0 1,0.3"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("no_segment"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn spline_command_and_op() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("aecurve-spline-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let input = dir.join("p.csv");
    std::fs::write(&input, "x,y\n0,0\n1,1\n2,0\n").unwrap();
    let step = dir.join("s.step");
    let v = json_output(
        aecurve()
            .args(["spline", "--kind", "pseudo-elastic"])
            .arg(&input)
            .arg("--json")
            .arg("-o")
            .arg(&step),
    );
    valid_as::<aecurve::protocol::spline::PseudoSplineResult>(&v);
    assert!(std::fs::read_to_string(&step)
        .unwrap()
        .contains("B_SPLINE_CURVE_WITH_KNOTS"));
    let segs = v["segments"].as_array().unwrap();
    assert_eq!(segs.len(), 2);
    assert_eq!(v["tangent_angles"].as_array().unwrap().len(), 3);
    // Symmetric data: the middle tangent is horizontal, the length is above the polygon's.
    assert!(v["tangent_angles"][1].as_f64().unwrap().abs() < 1e-6);
    assert!(v["length"].as_f64().unwrap() > 2.0 * 2f64.sqrt());
    assert_eq!(v["mode"], "table");
    // --curvature-plot: curvature against arc length as a picture.
    let kplot = dir.join("k.svg");
    let out = aecurve()
        .args(["spline", "--kind", "pseudo-elastic"])
        .arg(&input)
        .arg("--curvature-plot")
        .arg(&kplot)
        .output()
        .unwrap();
    assert!(out.status.success());
    let k = std::fs::read_to_string(&kplot).unwrap();
    assert!(k.contains("arc length") && k.contains("<polyline"));
    // The exact mode gives the same curve to the table's accuracy.
    let e = json_output(
        aecurve()
            .args(["spline", "--kind", "pseudo-elastic"])
            .arg(&input)
            .args(["--json", "--mode", "exact"]),
    );
    assert_eq!(e["mode"], "exact");
    let (lt, le) = (v["length"].as_f64().unwrap(), e["length"].as_f64().unwrap());
    assert!((lt - le).abs() < 1e-4 * le, "{lt} vs {le}");
    // A thousand points in table mode: fast, and every span present.
    let many: String = (0..1000)
        .map(|i| {
            let t = i as f64 * 0.5;
            format!("{t},{}\n", (t / 3.0).sin())
        })
        .collect();
    std::fs::write(&input, many).unwrap();
    let t0 = std::time::Instant::now();
    let v = json_output(
        aecurve()
            .args(["spline", "--kind", "pseudo-elastic"])
            .arg(&input)
            .arg("--json"),
    );
    assert_eq!(v["segments"].as_array().unwrap().len(), 999);
    assert!(t0.elapsed().as_secs_f64() < 10.0);
    // Too many points for the exact mode: refused with a clear message.
    let out = aecurve()
        .args(["spline", "--kind", "pseudo-elastic"])
        .arg(&input)
        .args(["--mode", "exact"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("exact mode"));
    // Repeated points: degenerate.
    std::fs::write(&input, "0,0\n0,0\n1,0\n").unwrap();
    let out = aecurve()
        .args(["spline", "--kind", "pseudo-elastic"])
        .arg(&input)
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("degenerate"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn lac_spline_command_and_op() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("aecurve-lac-spline-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let input = dir.join("p.csv");
    std::fs::write(&input, "x,y\n0,0\n2,1.5\n4,1\n6,3\n8,2.5\n10,4\n").unwrap();
    let dxf = dir.join("s.dxf");
    let v = json_output(
        aecurve()
            .arg("spline")
            .arg(&input)
            .args(["--json", "--alpha", "-1", "-o"])
            .arg(&dxf),
    );
    valid_as::<aecurve::protocol::spline::LacSplineResult>(&v);
    assert!(std::fs::read_to_string(&dxf).unwrap().contains("SPLINE"));
    let segs = v["segments"].as_array().unwrap();
    // Each piece starts where the last ended; the spans cover the five gaps.
    assert_eq!(segs.last().unwrap()["span"], 4);
    assert!(v["all_monotone"].as_bool().unwrap() && v["g2"].as_bool().unwrap());
    assert!(v["max_cubic_jump"].as_f64().unwrap() < 1e-10);
    // The protocol gives the same answer.
    let pts = "[[0,0],[2,1.5],[4,1],[6,3],[8,2.5],[10,4]]";
    let req = format!(r#"{{"id":1,"op":"spline.lac","points":{pts},"alpha":-1,"draw":20}}"#);
    let a = batch_one(&req);
    assert_eq!(a["result"]["segments"], v["segments"]);
    assert!(a["result"]["drawing"]["nurbs"].is_object());
    // Corners and a closed curve; a bad corner index named.
    let req =
        format!(r#"{{"id":2,"op":"spline.lac","points":{pts},"closed":true,"corners":[0,5]}}"#);
    let a = batch_one(&req);
    assert_eq!(a["ok"], true, "{a}");
    let req = r#"{"id":3,"op":"spline.lac","points":[[0,0],[1,1],[2,0]],"corners":[7]}"#;
    let a = batch_one(req);
    assert_eq!(a["error"]["kind"], "invalid_input");
    assert!(a["error"]["message"].as_str().unwrap().contains("corner"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn sketch_command_and_op() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("aecurve-sketch-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let input = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/sketch-stroke.csv"
    );
    let svg = dir.join("s.svg");
    let dxf = dir.join("s.dxf");
    let v = json_output(
        aecurve()
            .arg("sketch")
            .arg(input)
            .arg("--json")
            .arg("-o")
            .arg(&svg)
            .arg("-o")
            .arg(&dxf),
    );
    valid_as::<aecurve::protocol::sketch::SketchResult>(&v);
    let segs = v["segments"].as_array().unwrap();
    assert!(!segs.is_empty());
    assert!(v["g2"].as_bool().unwrap());
    assert!(v["max_deviation"].as_f64().unwrap() <= v["tolerance"].as_f64().unwrap());
    for s in segs {
        assert_eq!(s["rational"]["weights"].as_array().unwrap().len(), 4);
        assert!(["lac", "lac_inflection"].contains(&s["kind"].as_str().unwrap()));
    }
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<svg"));
    assert!(std::fs::read_to_string(&dxf).unwrap().contains("SPLINE"));
    // The same stroke as an SVG document with one path: the same result.
    let csv = std::fs::read_to_string(input).unwrap();
    let d: Vec<String> = csv.lines().skip(1).map(|l| l.replace(',', " ")).collect();
    let svg_in = dir.join("stroke.svg");
    std::fs::write(
        &svg_in,
        format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\"><path fill=\"none\" d=\"M {}\"/></svg>",
            d.join(" L ")
        ),
    )
    .unwrap();
    let w = json_output(aecurve().arg("sketch").arg(&svg_in).arg("--json"));
    valid_as::<aecurve::protocol::sketch::SketchResult>(&w);
    assert_eq!(w["segments"].as_array().unwrap().len(), segs.len());
    assert_eq!(w["max_deviation"], v["max_deviation"]);
    // The op: bad input gets typed errors, the batch goes on.
    let mut child = aecurve()
        .arg("batch")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let lines = [
        r#"{"id":1,"op":"sketch.fit","points":[[0,0],[1,0]]}"#,
        r#"{"id":2,"op":"sketch.fit","points":[[0,0],[1,0],[2,0],[3,0],[4,0],[5,0]]}"#,
        r#"{"id":3,"op":"sketch.fit","points":[[0,0],[1,1],[2,1],[3,0],[4,-1]],"tolerance":-1}"#,
        r#"{"id":4,"op":"sketch.fit","points":[[0,0],[1,0.5],[2,0.8],[3,0.9],[4,0.8],[5,0.5],[6,0]]}"#,
    ];
    child
        .stdin
        .take()
        .unwrap()
        .write_all((lines.join("\n") + "\n").as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    let resp: Vec<serde_json::Value> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(resp.len(), 4);
    resp.iter().for_each(valid_response);
    assert_eq!(resp[0]["error"]["kind"], "invalid_input");
    assert_eq!(resp[1]["error"]["kind"], "degenerate");
    assert_eq!(resp[2]["error"]["kind"], "invalid_input");
    assert_eq!(resp[3]["ok"], true, "{}", resp[3]);
    let _ = std::fs::remove_dir_all(&dir);
}

/// One HTTP/1.1 request over a plain socket; returns (status, headers + body text).
fn http(addr: std::net::SocketAddr, method: &str, path: &str, body: &[u8]) -> (u16, String) {
    http_with(
        addr,
        method,
        path,
        &[
            ("Host", addr.to_string()),
            ("Content-Type", "application/json".into()),
        ],
        body,
    )
}

/// [`http`] with the given `Host`, `Content-Type` and other headers.
fn http_with(
    addr: std::net::SocketAddr,
    method: &str,
    path: &str,
    headers: &[(&str, String)],
    body: &[u8],
) -> (u16, String) {
    use std::io::Read;
    let mut s = std::net::TcpStream::connect(addr).unwrap();
    s.set_read_timeout(Some(std::time::Duration::from_secs(30)))
        .unwrap();
    let extra: String = headers
        .iter()
        .map(|(k, v)| format!("{k}: {v}\r\n"))
        .collect();
    let head = format!(
        "{method} {path} HTTP/1.1\r\n{extra}Content-Length: {}\r\nConnection: close\r\n\r\n",
        body.len()
    );
    s.write_all(head.as_bytes()).unwrap();
    // A server may answer 413 before reading the whole body and close: ignore write errors.
    let _ = s.write_all(body);
    let mut out = Vec::new();
    let _ = s.read_to_end(&mut out);
    let text = String::from_utf8_lossy(&out).to_string();
    let status = text
        .split_whitespace()
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or(0);
    (status, text)
}

/// Start `aecurve editor` on a free port: the child and its address.
fn start_editor() -> (std::process::Child, std::net::SocketAddr) {
    start_editor_with(&[])
}

/// [`start_editor`] with more arguments.
fn start_editor_with(args: &[&str]) -> (std::process::Child, std::net::SocketAddr) {
    use std::io::BufRead;
    let mut child = aecurve()
        .args(["editor", "--port", "0", "--no-open"])
        .args(args)
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let mut line = String::new();
    std::io::BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let url = line.trim().strip_prefix("editor: ").unwrap().to_string();
    let addr = url
        .trim_start_matches("http://")
        .trim_end_matches('/')
        .parse()
        .unwrap();
    (child, addr)
}

/// Same origin only: what a page on another site (or a DNS-rebinding name) can send is
/// refused, what the editor's own page sends is answered.
#[test]
fn editor_refuses_other_origins() {
    let (mut child, addr) = start_editor();
    let port = addr.port();
    let req = br#"{"id": 1, "op": "lac.segment", "alpha": 0.5, "control": [[0,0],[4,0],[6,3]]}"#;
    let json = || ("Content-Type", "application/json".to_string());
    let host = || ("Host", addr.to_string());
    // A simple cross-site request: text/plain needs no preflight.
    let (st, r) = http_with(
        addr,
        "POST",
        "/api",
        &[host(), ("Content-Type", "text/plain".into())],
        req,
    );
    assert_eq!(st, 415, "{r}");
    assert!(r.contains("application/json"), "{r}");
    for path in ["/api", "/api/region", "/api/export"] {
        let (st, _) = http_with(
            addr,
            "POST",
            path,
            &[
                host(),
                ("Content-Type", "application/x-www-form-urlencoded".into()),
            ],
            b"a=1",
        );
        assert_eq!(st, 415, "{path}");
        // Another site's page, even with the JSON type (a browser would ask first; a
        // script outside a browser is refused all the same).
        let (st, r) = http_with(
            addr,
            "POST",
            path,
            &[host(), json(), ("Origin", "http://evil.example".into())],
            req,
        );
        assert_eq!(st, 403, "{path}: {r}");
    }
    // DNS rebinding: the right address under another name.
    for name in [
        "evil.example",
        &format!("evil.example:{port}"),
        "127.0.0.1:1",
    ] {
        let (st, _) = http_with(addr, "GET", "/", &[("Host", name.to_string())], b"");
        assert_eq!(st, 421, "{name}");
        let (st, _) = http_with(
            addr,
            "POST",
            "/api",
            &[("Host", name.to_string()), json()],
            req,
        );
        assert_eq!(st, 421, "{name}");
    }
    // The editor's own page, under each loopback name.
    for name in [
        format!("127.0.0.1:{port}"),
        format!("localhost:{port}"),
        format!("[::1]:{port}"),
    ] {
        let (st, r) = http_with(
            addr,
            "POST",
            "/api",
            &[
                ("Host", name.clone()),
                json(),
                ("Origin", format!("http://{name}")),
            ],
            req,
        );
        assert_eq!(st, 200, "{name}: {r}");
        assert!(r.contains(r#""ok":true"#), "{r}");
    }
    child.kill().unwrap();
    let _ = child.wait();
}

#[test]
fn editor_serves_on_loopback_only_with_limits() {
    let (mut child, addr) = start_editor();
    assert!(addr.ip().is_loopback(), "{addr}");
    // The page and its script are embedded.
    let (st, page) = http(addr, "GET", "/", b"");
    assert_eq!(st, 200);
    assert!(page.contains("<canvas id=\"view\""));
    let (st, js) = http(addr, "GET", "/app.js", b"");
    assert_eq!(st, 200);
    assert!(js.contains("lac.rational_approx"));
    // One protocol request, one response; malformed JSON is a parse error; too big is 413.
    let (st, r) = http(
        addr,
        "POST",
        "/api",
        br#"{"id": 3, "op": "lac.segment", "alpha": 0.5, "control": [[0,0],[4,0],[6,3]]}"#,
    );
    assert_eq!(st, 200);
    assert!(
        r.contains("server-timing") && r.contains(r#""ok":true"#),
        "{r}"
    );
    let (st, r) = http(addr, "POST", "/api", b"{\"id\": 1, ");
    assert_eq!(st, 200);
    assert!(r.contains(r#""kind":"parse""#), "{r}");
    let big = vec![b' '; 20 * 1024 * 1024];
    let (st, _) = http(addr, "POST", "/api", &big);
    assert_eq!(st, 413);
    let (st, r) = http(
        addr,
        "POST",
        "/api/region",
        br#"{"kind": "lac", "alpha": -1, "control": [[0,0],[8,0],[12,5]], "grid": {"x0": -1, "y0": -2, "x1": 15, "y1": 9, "nx": 20, "ny": 10}}"#,
    );
    assert_eq!(st, 200);
    assert!(r.contains(r#""rows""#), "{r}");
    let (st, r) = http(
        addr,
        "POST",
        "/api/region",
        br#"{"kind": "lac", "grid": {"nx": 100000}}"#,
    );
    assert_eq!(st, 200);
    assert!(r.contains("invalid_input"), "{r}");
    // Not reachable on this machine's other addresses: find the address the machine would
    // use towards the outside (no packet is sent) and try the same port there.
    if let Some(ip) = std::net::UdpSocket::bind("0.0.0.0:0")
        .and_then(|u| u.connect("192.0.2.1:9").map(|_| u))
        .and_then(|u| u.local_addr())
        .ok()
        .map(|a| a.ip())
        .filter(|ip| !ip.is_loopback() && !ip.is_unspecified())
    {
        let other = std::net::SocketAddr::new(ip, addr.port());
        let reach = std::net::TcpStream::connect_timeout(&other, std::time::Duration::from_secs(2));
        assert!(reach.is_err(), "the editor answered on {other}");
    }
    child.kill().unwrap();
    let _ = child.wait();
}

/// Server hygiene: 300 connections that send half a header and wait do not lock a normal
/// request out (it answers within a second), and the server closes them once the header
/// time limit (5 s) has passed.
#[test]
fn editor_survives_idle_and_slow_connections() {
    use std::io::Read;
    let (mut child, addr) = start_editor();
    let mut hostile: Vec<std::net::TcpStream> = (0..300)
        .filter_map(|_| std::net::TcpStream::connect(addr).ok())
        .collect();
    for s in &mut hostile {
        let _ = s.write_all(b"GET / HTTP/1.1\r\nHo");
    }
    let t = std::time::Instant::now();
    let (st, r) = http(
        addr,
        "POST",
        "/api",
        br#"{"id": 1, "op": "lac.segment", "alpha": 0.5, "control": [[0,0],[4,0],[6,3]]}"#,
    );
    let secs = t.elapsed().as_secs_f64();
    println!("normal request among 300 idle connections: {st} in {secs:.3} s");
    assert_eq!(st, 200, "{r}");
    assert!(secs < 1.0, "{secs} s");
    // After the header limit, the held connections are closed by the server.
    std::thread::sleep(std::time::Duration::from_secs(7));
    let mut closed = 0;
    for s in &mut hostile {
        s.set_read_timeout(Some(std::time::Duration::from_millis(200)))
            .unwrap();
        let mut buf = [0u8; 256];
        match s.read(&mut buf) {
            Ok(_) => closed += 1, // end of stream, or the server's error response and close
            Err(e)
                if e.kind() != std::io::ErrorKind::WouldBlock
                    && e.kind() != std::io::ErrorKind::TimedOut =>
            {
                closed += 1
            }
            Err(_) => {}
        }
    }
    println!(
        "{closed} of {} held connections closed by the server",
        hostile.len()
    );
    assert_eq!(closed, hostile.len());
    child.kill().unwrap();
    let _ = child.wait();
}

/// A request past the editor's time limit gets a typed `timeout` error in time, and the
/// server goes on answering.
#[test]
fn editor_times_requests_out() {
    let (mut child, addr) = start_editor_with(&["--timeout", "0.5"]);
    // Exact mode minimises directly: seconds for a handful of points.
    let slow = br#"{"id": 7, "op": "spline.pseudo_elastic", "mode": "exact", "points": [[0,0],[1,2],[3,3],[5,2],[6,0],[8,1],[9,3],[11,4]]}"#;
    let t = std::time::Instant::now();
    let (st, r) = http(addr, "POST", "/api", slow);
    let secs = t.elapsed().as_secs_f64();
    println!("slow request: {st} in {secs:.2} s");
    assert_eq!(st, 200);
    assert!(r.contains(r#""kind":"timeout""#), "{r}");
    assert!(secs < 2.0, "{secs} s");
    let (st, r) = http(
        addr,
        "POST",
        "/api",
        br#"{"id": 1, "op": "lac.segment", "alpha": 0.5, "control": [[0,0],[4,0],[6,3]]}"#,
    );
    assert_eq!(st, 200);
    assert!(r.contains(r#""ok":true"#), "{r}");
    // Out of range limits are refused with a message.
    let out = aecurve()
        .args(["editor", "--port", "0", "--no-open", "--timeout", "0"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("outside 0.1 to 600"));
    child.kill().unwrap();
    let _ = child.wait();
}

/// A full disk, an absurd size and a negative tolerance get a message and a failure status,
/// never a panic or an abort; a CSV whose header starts with "m" is read as CSV.
#[test]
fn write_errors_and_limits_get_messages() {
    let stroke = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/sketch-stroke.csv"
    );
    let spline = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/spline-points.csv"
    );
    if std::path::Path::new("/dev/full").exists() {
        let runs: [&[&str]; 6] = [
            &["lac", "--alpha", "0.5", "--control", "0,0 4,0 6,3"],
            &[
                "lac",
                "--alpha",
                "0.5",
                "--control",
                "0,0 4,0 6,3",
                "--json",
            ],
            &["sketch", stroke],
            &["spline", spline, "--json"],
            &["spline", spline, "--kind", "pseudo-elastic", "--json"],
            &[
                "approx",
                "--alpha",
                "0.5",
                "--control",
                "0,0 4,0 6,3",
                "--json",
            ],
        ];
        for args in runs {
            let full = std::fs::OpenOptions::new()
                .write(true)
                .open("/dev/full")
                .unwrap();
            let out = aecurve().args(args).stdout(full).output().unwrap();
            let err = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
            assert!(err.contains("cannot write the output"), "{args:?}: {err}");
            assert!(!err.contains("panicked"), "{args:?}: {err}");
        }
    }
    for (args, want) in [
        (
            vec![
                "lac",
                "--alpha",
                "0.5",
                "--control",
                "0,0 4,0 6,3",
                "--samples",
                "10000000000",
            ],
            "outside 2 to 1000000",
        ),
        (
            vec!["sketch", stroke, "--tolerance", "-1"],
            "not a positive length",
        ),
        (
            vec!["sketch", stroke, "--tolerance", "nan"],
            "not a positive length",
        ),
    ] {
        let out = aecurve().args(&args).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(want), "{args:?}: {err}");
    }
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("aecurve-mxmy-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for name in ["m.csv", "m.dat"] {
        let path = dir.join(name);
        std::fs::write(&path, "mx,my\n0,0\n1,1\n2,1.5\n3,1.2\n4,0.5\n5,0\n").unwrap();
        let out = aecurve().arg("sketch").arg(&path).output().unwrap();
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(String::from_utf8_lossy(&out.stdout).contains("sketch of 6 points"));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A region request over its work budget (a degree-20 rational curve on 200 x 200 cells,
/// 10 s of work) is refused at once with the limit named; a cubic's region on the same grid
/// is answered.
#[test]
fn editor_region_budget() {
    let (mut child, addr) = start_editor();
    let pts: Vec<String> = (0..=20)
        .map(|i| format!("[{}, {}]", i, (i as f64 * 0.7).sin() * 3.0))
        .collect();
    let w: Vec<String> = (0..=20)
        .map(|i| format!("{}", 1.0 + 0.3 * (i % 3) as f64))
        .collect();
    let grid = r#"{"x0": -2, "y0": -5, "x1": 22, "y1": 8, "nx": 200, "ny": 200}"#;
    let req = format!(
        r#"{{"kind": "bezier", "control_points": [{}], "weights": [{}], "index": 10, "grid": {grid}}}"#,
        pts.join(","),
        w.join(",")
    );
    let t = std::time::Instant::now();
    let (st, r) = http(addr, "POST", "/api/region", req.as_bytes());
    assert_eq!(st, 200);
    assert!(r.contains("invalid_input") && r.contains("at most"), "{r}");
    assert!(t.elapsed().as_secs_f64() < 1.0);
    let cubic = format!(
        r#"{{"kind": "bezier", "control_points": [[0,0],[1,2],[3,2],[4,0]], "index": 1, "grid": {grid}}}"#
    );
    let (st, r) = http(addr, "POST", "/api/region", cubic.as_bytes());
    assert_eq!(st, 200);
    assert!(r.contains(r#""rows""#), "{r}");
    child.kill().unwrap();
    let _ = child.wait();
}

/// Export: a clamped spline with simple interior knots is written as SVG (its Bézier spans
/// by knot insertion); a curve whose extent overflows f64 is refused, never written as
/// `inf` or `NaN`.
#[test]
fn editor_export_simple_knots_and_huge_coordinates() {
    let (mut child, addr) = start_editor();
    let simple = br#"{"format": "svg", "degree": 3, "knots": [0,0,0,0,0.3,0.6,1,1,1,1], "control_points": [[0,0],[1,2],[2,3],[4,3],[5,1],[6,0]]}"#;
    let (st, r) = http(addr, "POST", "/api/export", simple);
    assert_eq!(st, 200);
    assert!(r.contains("<svg") && r.contains(" C "), "{r}");
    for fmt in ["svg", "iges", "step", "dxf", "json"] {
        let huge = format!(
            r#"{{"format": "{fmt}", "degree": 1, "knots": [0,0,1,1], "control_points": [[-1e308,-1e308],[1e308,1e308]]}}"#
        );
        let (st, r) = http(addr, "POST", "/api/export", huge.as_bytes());
        assert_eq!(st, 200, "{fmt}");
        assert!(
            r.contains("invalid_input") && r.contains("too large"),
            "{fmt}: {r}"
        );
        assert!(
            !r.contains("inf") || r.contains("invalid_input"),
            "{fmt}: {r}"
        );
    }
    child.kill().unwrap();
    let _ = child.wait();
}

/// `aecurve sketch --contour`: an L written as CSV comes back as two lines and one corner,
/// in the summary and in the JSON (the protocol's `sketch.contour`), and its SVG has no
/// comb on the straight runs (zero curvature drawn as none).
#[test]
fn sketch_contour_command() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("aecurve-contour-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("l.csv");
    let mut text = String::from("x,y\n");
    for i in 0..=100 {
        text += &format!("0,{}\n", 2 * i);
    }
    for i in 1..=100 {
        text += &format!("{},200\n", 2 * i);
    }
    std::fs::write(&csv, text).unwrap();
    let v = json_output(aecurve().args(["sketch", "--contour", "--json"]).arg(&csv));
    valid_as::<aecurve::protocol::sketch::ContourResult>(&v);
    let kinds: Vec<&str> = v["runs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["kind"].as_str().unwrap())
        .collect();
    assert_eq!(kinds, ["line", "line"], "{v}");
    assert_eq!(v["corners"][0]["index"], 100, "{v}");
    let svg = dir.join("l.svg");
    let out = aecurve()
        .args(["sketch", "--contour"])
        .arg(&csv)
        .arg("-o")
        .arg(&svg)
        .output()
        .unwrap();
    assert!(out.status.success());
    let summary = String::from_utf8_lossy(&out.stdout);
    assert!(summary.contains("2 runs, 1 corners"), "{summary}");
    let doc = std::fs::read_to_string(&svg).unwrap();
    assert!(doc.contains("<path"), "{doc}");
    // Every comb tooth (a light blue line from the curve) has zero length.
    let attr = |tag: &str, name: &str| -> f64 {
        let at = tag.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
        tag[at..at + tag[at..].find('"').unwrap()].parse().unwrap()
    };
    let teeth: Vec<&str> = doc
        .split("<line ")
        .skip(1)
        .filter(|t| t.contains("stroke=\"#9ecae1\""))
        .collect();
    assert!(!teeth.is_empty());
    for t in teeth {
        let t = format!(" {t}");
        assert_eq!(
            (attr(&t, "x1"), attr(&t, "y1")),
            (attr(&t, "x2"), attr(&t, "y2")),
            "{t}"
        );
    }
}
