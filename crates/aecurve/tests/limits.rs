//! Every op at its limits: one answer per request, never `internal`, memory under
//! a stated bound, and the time of each. Each request runs in its own `aecurve batch`
//! process, whose peak memory the kernel reports (Linux's `/proc/PID/status`).
//!
//! The measured run is `#[ignore]`d (CI runs it optimised, in `cargo test --release --
//! --ignored`): in a debug build the exact checks at their limits take minutes. The
//! refusals, which must come before any work, are checked in every build.

use serde_json::{json, Value};
use std::io::Write;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The bound on any request within the limits (docs/protocol.md, "Limits").
const MEMORY_BOUND_MB: f64 = 500.0;

/// One request in a fresh `aecurve batch`: its answer, peak resident memory (MB) and time.
/// The peak is the process's own `VmHWM`, read while it waits for the next line (the
/// `ru_maxrss` of a reaped child also counts the memory of the test process that spawned it).
fn run_one(request: &Value) -> (Value, f64, Duration) {
    let t = Instant::now();
    let mut child = Command::new(env!("CARGO_BIN_EXE_aecurve"))
        .arg("batch")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("aecurve runs");
    let mut stdin = child.stdin.take().unwrap();
    let line = format!("{request}\n");
    let writer = std::thread::spawn(move || {
        stdin.write_all(line.as_bytes()).unwrap();
        stdin // kept open: the process stays up until its peak is read
    });
    let mut stdout = std::io::BufReader::new(child.stdout.take().unwrap());
    let mut answer = String::new();
    std::io::BufRead::read_line(&mut stdout, &mut answer).unwrap();
    let time = t.elapsed();
    let stdin = writer.join().unwrap();
    let peak_mb = peak_resident_mb(child.id());
    drop(stdin);
    let mut rest = String::new();
    std::io::Read::read_to_string(&mut stdout, &mut rest).unwrap();
    let status = child.wait().unwrap();
    assert!(status.success(), "aecurve batch ended with {status}");
    assert!(rest.is_empty(), "one answer per request, then: {rest:.300}");
    let answer: Value = serde_json::from_str(&answer).expect("the answer is one line of JSON");
    (answer, peak_mb, time)
}

/// The peak resident memory of the live process `pid` (MB), from `/proc/PID/status`.
fn peak_resident_mb(pid: u32) -> f64 {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).unwrap();
    let kb: f64 = status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
        .expect("VmHWM in /proc/PID/status");
    kb / 1e3
}

fn wave(n: usize) -> Vec<[f64; 2]> {
    (0..n)
        .map(|i| [i as f64 * 0.01, (i as f64 * 0.01).sin()])
        .collect()
}

fn font_base64() -> String {
    use base64::Engine;
    let font = std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/DejaVuSans.ttf"
    ))
    .unwrap();
    base64::engine::general_purpose::STANDARD.encode(font)
}

/// 10,000 consecutive segments of degree 20 (the most `outline.check` takes), wavy.
fn degree20_segments() -> Vec<Value> {
    (0..10_000)
        .map(|i| {
            let pts: Vec<[f64; 2]> = (0..21)
                .map(|j| [(i * 20 + j) as f64, ((i * 20 + j) as f64).sin()])
                .collect();
            json!({ "control_points": pts })
        })
        .collect()
}

/// The requests at (or next to) each op's limits, named.
fn requests_at_the_limits() -> Vec<(&'static str, Value)> {
    let path = std::iter::once("M0 0".to_string())
        .chain((0..10_000).map(|i| format!("c1 2 3 {} 5 {}", i % 7, i % 5)))
        .collect::<Vec<_>>()
        .join(" ");
    let degree20 = degree20_segments();
    let circle16: Vec<[f64; 2]> = (0..16)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / 16.0;
            [100.0 * a.cos(), 60.0 * a.sin()]
        })
        .collect();
    let thetas: Vec<f64> = (0..100_000).map(|i| i as f64 * 1e-5).collect();
    let arc = |n: usize| (0..n).map(|i| [i as f64 * 1e-4, (i as f64 * 1e-4).powi(2) * 0.3]);
    vec![
        (
            "bezier.curvature_monotone, 1,000,000 samples",
            json!({"op": "bezier.curvature_monotone",
            "control_points": [[0, 0], [1, 2], [3, 3], [4, 0]], "method": "sampling", "samples": 1_000_000}),
        ),
        (
            "bezier.curvature_monotone, degree 20, draw 2000",
            json!({"op": "bezier.curvature_monotone",
            "control_points": wave(21).iter().map(|p| [p[0] * 100.0, p[1]]).collect::<Vec<_>>(), "draw": 2000}),
        ),
        (
            "lac.point, 100,000 angles",
            json!({"op": "lac.point", "alpha": -1, "lambda": 0.2, "theta": thetas}),
        ),
        (
            "lac.inflection_segment, 100,000 samples, its cubic and a spline to 1e-6, draw 2000",
            json!({"op": "lac.inflection_segment", "control": [[0, 0], [1, 0], [1, 0.577]],
                "samples": 100_000, "rational": true, "tolerance": 1e-6, "draw": 2000}),
        ),
        (
            "lac.segment, 100,000 samples, draw 2000",
            json!({"op": "lac.segment", "alpha": -1,
            "control": [[0, 0], [10, 0], [16, 9]], "samples": 100_000, "draw": 2000}),
        ),
        (
            "lcg.estimate, 100,000 points",
            json!({"op": "lcg.estimate", "points": wave(100_000)}),
        ),
        (
            "lac.rational_approx, tolerance 1e-9, draw 2000",
            json!({"op": "lac.rational_approx",
            "alpha": -1, "control": [[0, 0], [10, 0], [16, 9]], "tolerance": 1e-9, "draw": 2000}),
        ),
        (
            "spline.pseudo_elastic, 20,000 points, draw 10",
            json!({"op": "spline.pseudo_elastic",
            "points": wave(20_000), "draw": 10}),
        ),
        (
            "spline.pseudo_elastic, exact, 16 points",
            json!({"op": "spline.pseudo_elastic",
            "points": circle16, "closed": true, "mode": "exact"}),
        ),
        (
            "spline.lac, 500 points, draw 300",
            json!({"op": "spline.lac",
            "points": wave(500).iter().map(|p| [p[0] * 100.0, p[1] * 30.0]).collect::<Vec<_>>(), "draw": 300}),
        ),
        (
            "lac.fit, 20,000 points",
            json!({"op": "lac.fit", "points": arc(20_000).collect::<Vec<_>>()}),
        ),
        (
            "sketch.fit, 20,000 points, draw 1000",
            json!({"op": "sketch.fit", "points": wave(20_000), "draw": 1000}),
        ),
        (
            "sketch.contour, 20,000 points, draw 1000",
            json!({"op": "sketch.contour", "points": wave(20_000), "draw": 1000}),
        ),
        (
            "outline.check, 10,000 cubics as a path, draw 20",
            json!({"op": "outline.check", "path": path, "draw": 20}),
        ),
        (
            "outline.check, 10,000 segments of degree 20, draw 20",
            json!({"op": "outline.check",
            "segments": degree20, "draw": 20}),
        ),
        (
            "outline.check, a font's glyph, draw 1000",
            json!({"op": "outline.check", "shape": 100,
            "draw": 1000, "file": {"name": "DejaVuSans.ttf", "base64": font_base64()}}),
        ),
        ("outline.fix, 10,000 cubics with smooth joins", {
            // Cubic i from (i, 0) to (i + 1, 0), handles of heights a_i and -a_(i+1):
            // every join is smooth (G1) with a curvature jump to harmonize.
            let n = 10_000;
            let a = |i: usize| 0.2 + 0.1 * ((i % n) as f64 * 0.7).sin();
            let mut segs: Vec<Value> = (0..n)
                .map(|i| {
                    let x = i as f64;
                    json!({"control_points": [[x, 0.0], [x + 1.0 / 3.0, a(i)],
                            [x + 2.0 / 3.0, -a(i + 1)], [x + 1.0, 0.0]]})
                })
                .collect();
            segs.push(json!({"control_points": [[n as f64, 0.0], [0.0, 0.0]]}));
            segs.truncate(n);
            json!({"op": "outline.fix", "tolerance": 0.05, "segments": segs})
        }),
        (
            "region.map, a LAC segment, 200 x 200 cells",
            json!({"op": "region.map", "kind": "lac", "alpha": -1,
                "control": [[0, 0], [10, 0], [16, 9]],
                "grid": {"x0": -20, "y0": -20, "x1": 40, "y1": 40, "nx": 200, "ny": 200}}),
        ),
        (
            "region.map, a rational curve of degree 20 at its work budget",
            {
                let pts: Vec<[f64; 2]> = (0..21)
                    .map(|i| [i as f64, ((i * 7 % 5) as f64) - 2.0])
                    .collect();
                let w: Vec<f64> = (0..21).map(|i| 1.0 + (i % 3) as f64 * 0.25).collect();
                json!({"op": "region.map", "kind": "bezier", "control_points": pts,
                    "weights": w, "index": 10,
                    "grid": {"x0": 0, "y0": -5, "x1": 20, "y1": 5, "nx": 42, "ny": 42}})
            },
        ),
    ]
}

/// Every op of the protocol has a case at its limits above.
#[test]
fn every_op_has_a_case_at_its_limits() {
    let cases = requests_at_the_limits();
    for op in aecurve::protocol::OPS {
        assert!(
            cases.iter().any(|(_, r)| r["op"] == *op),
            "{op} has no case in requests_at_the_limits"
        );
    }
}

#[test]
#[ignore = "minutes in a debug build; CI runs it with --release"]
fn every_op_at_its_limits_answers_under_the_memory_bound() {
    for (name, mut request) in requests_at_the_limits() {
        request["id"] = json!(name);
        let (answer, mb, time) = run_one(&request);
        eprintln!("{name}: {mb:.0} MB, {:.2} s", time.as_secs_f64());
        assert_eq!(answer["id"], json!(name));
        assert_eq!(
            answer["ok"],
            json!(true),
            "{name}: {:.400}",
            answer.to_string()
        );
        assert!(
            mb < MEMORY_BOUND_MB,
            "{name}: {mb:.0} MB, over the bound of {MEMORY_BOUND_MB} MB"
        );
    }
}

/// Over a limit, the answer is `invalid_input` naming the limit, before any work: at once,
/// and in little memory.
#[test]
fn requests_over_the_limits_are_refused_at_once() {
    let font = font_base64();
    let cases = [
        (
            json!({"op": "outline.check", "file": {"name": "DejaVuSans.ttf", "base64": font}}),
            "shape",
            "over the 10000 one outline.check answers for",
        ),
        (
            json!({"op": "spline.pseudo_elastic", "points": wave(17), "mode": "exact"}),
            "points",
            "16",
        ),
        (
            json!({"op": "spline.lac", "points": wave(501)}),
            "points",
            "500",
        ),
        (
            json!({"op": "spline.pseudo_elastic", "points": wave(20_000), "draw": 11}),
            "draw",
            "at most 10 points per piece",
        ),
        // 10,000 degree-20 segments drawn at 21 points: refused after 21.8 s of work before.
        (
            json!({"op": "outline.check", "segments": degree20_segments(), "draw": 21}),
            "draw",
            "at most 20 points per piece",
        ),
    ];
    for (request, field, words) in cases {
        let (answer, mb, time) = run_one(&request);
        let e = &answer["error"];
        assert_eq!(e["kind"], "invalid_input", "{answer}");
        let msg = e["message"].as_str().unwrap();
        assert!(msg.starts_with(field) && msg.contains(words), "{msg}");
        assert!(mb < 200.0, "{mb} MB for a refusal");
        assert!(time < Duration::from_secs(20), "{time:?} for a refusal");
    }
}
