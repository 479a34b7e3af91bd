//! The sketch pipeline end to end: 1000 points (target: under 20 ms median), the five
//! measured Prius key lines at 0.3 mm (target: under 20 ms each) and the probe's two
//! random-walk strokes at their tight tolerances (target: well under a second).
//! Hand strokes of the stroke model through `sketch::contour`: 1,000 points (target: under
//! 100 ms) and 20,000 (target: under 1 s).

use aesthetic_curves::lac::LacSegment;
use aesthetic_curves::sketch::{fit_sketch, SketchOptions};
use aesthetic_curves::{Point, Vec2};
use criterion::{criterion_group, criterion_main, Criterion};

#[path = "../tests/common/hand.rs"]
mod hand;

/// A symmetric bump of two alpha = 0.5 LAC segments (peak at the joint), 999 points,
/// with or without noise of 1e-4 of its size.
fn bump(noise: f64) -> Vec<Point> {
    let seg = LacSegment::new(
        0.5,
        [
            Point::new(0.0, 0.0),
            Point::new(6.0, 3.0),
            Point::new(9.0, 0.5),
        ],
    )
    .unwrap();
    let pts = seg.sample(500).unwrap().points;
    let end = pts[499];
    let d = seg.eval_turning(&[seg.theta_d()]).unwrap().tangents[0];
    let nrm = Vec2::new(-d.y, d.x);
    let mut out = pts.clone();
    for q in pts.iter().rev().skip(1) {
        let v = *q - end;
        out.push(end + nrm * (2.0 * v.dot(nrm)) - v);
    }
    let mut s = 99u64;
    out.iter()
        .map(|q| {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1);
            let r = ((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0;
            Point::new(q.x + noise * 15.0 * r, q.y - noise * 15.0 * r)
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("sketch");
    g.sample_size(20);
    for (name, noise) in [("bump1000_exact", 0.0), ("bump1000_noisy", 1e-4)] {
        let pts = bump(noise);
        let opts = SketchOptions::with_tolerance(3e-3 * 15.0);
        g.bench_function(name, |b| b.iter(|| fit_sketch(&pts, &opts).unwrap()));
    }
    // The measured Prius key lines at 0.3 mm (target: under 20 ms each).
    for line in &aesthetic_curves_data::PRIUS {
        let pts: Vec<Point> = line.points_as::<Point>();
        let opts = SketchOptions::with_tolerance(0.3);
        g.bench_function(format!("prius_{}", line.name), |b| {
            b.iter(|| fit_sketch(&pts, &opts).unwrap())
        });
    }
    for (name, text) in [
        (
            "probe_52",
            include_str!("../tests/data/sketch-slow-52-points.json"),
        ),
        (
            "probe_181",
            include_str!("../tests/data/sketch-slow-181-points.json"),
        ),
    ] {
        let (pts, opts) = probe(text);
        g.bench_function(name, |b| b.iter(|| fit_sketch(&pts, &opts).unwrap()));
    }
    g.finish();
}

/// The points and tolerance of a `sketch.fit` request.
fn probe(text: &str) -> (Vec<Point>, SketchOptions) {
    let v: serde_json::Value = serde_json::from_str(text).unwrap();
    let pts = v["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|q| Point::new(q[0].as_f64().unwrap(), q[1].as_f64().unwrap()))
        .collect();
    let tol = v["tolerance"].as_f64().unwrap();
    (pts, SketchOptions::with_tolerance(tol))
}

/// Hand strokes of the stroke model (`tests/common/hand.rs`) as `sketch.contour` gets them
/// from a file (every event, nothing said of the device): 1,000 points (target: under
/// 100 ms) and 20,000 (target: under 1 s).
fn hand_strokes(c: &mut Criterion) {
    use aesthetic_curves::sketch::contour::{fit_contour, ContourOptions};
    use hand::{Device, Kind};
    let mut g = c.benchmark_group("hand");
    g.sample_size(10);
    for (name, kind, device, n) in [
        ("mouse_circle_1000", Kind::Circle, Device::Mouse, 1000),
        ("pen_s_1000", Kind::S, Device::Pen, 1000),
        (
            "trackpad_rounded_rectangle_1000",
            Kind::RoundedRectangle,
            Device::Trackpad,
            1000,
        ),
        ("pen_spiral_20000", Kind::Spiral, Device::Pen, 20_000),
    ] {
        let stroke = hand::with_points(kind, device, n, 7);
        let opts = ContourOptions::default();
        g.bench_function(format!("{name}_{}", stroke.points.len()), |b| {
            b.iter(|| fit_contour(&stroke.points, &opts).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, bench, hand_strokes);
criterion_main!(benches);
