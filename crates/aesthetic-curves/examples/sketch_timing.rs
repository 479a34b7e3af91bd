//! Time the sketch pipeline's stages on a 999-point bump (a development aid).
use aesthetic_curves::lac::LacSegment;
use aesthetic_curves::sketch::{fit_sketch, SketchOptions};
use aesthetic_curves::{Point, Vec2};

fn main() {
    let seg = LacSegment::new(
        0.5,
        [
            Point::new(0.0, 0.0),
            Point::new(6.0, 3.0),
            Point::new(9.0, 0.5),
        ],
    )
    .unwrap();
    let (pts, _) = seg.sample(500).unwrap();
    let end = pts[499];
    let (_, d) = seg.eval_turning(&[seg.theta_d]).unwrap();
    let nrm = Vec2::new(-d[0].y, d[0].x) / d[0].hypot();
    let mut out = pts.clone();
    for q in pts.iter().rev().skip(1) {
        let v = *q - end;
        out.push(end + nrm * (2.0 * v.dot(nrm)) - v);
    }
    let opts = SketchOptions::with_tolerance(3e-3 * 15.0);
    for _ in 0..3 {
        let t = std::time::Instant::now();
        let sk = fit_sketch(&out, &opts).unwrap();
        println!("{:?} pieces {}", t.elapsed(), sk.pieces.len());
    }
}
