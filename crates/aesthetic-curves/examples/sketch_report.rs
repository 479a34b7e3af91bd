//! What `fit_sketch` delivers on the measured Prius key lines: pieces, the deviation of the
//! delivered rational cubics from every input point, the largest curvature against the
//! smoothest spline within the same tolerance, inflections and curvature extrema, time.
//!
//! `cargo run --release -p aesthetic-curves --example sketch_report [TOLERANCE]`

use aesthetic_curves::bspline::smoothing_fit;
use aesthetic_curves::sketch::{fit_sketch, Sketch, SketchOptions};
use aesthetic_curves::{PlanarCurve, Point};

/// Dense samples (point, signed curvature) of the delivered curve.
fn dense(sk: &Sketch, per_piece: usize) -> Vec<(Point, f64)> {
    let mut out = Vec::new();
    for p in &sk.pieces {
        for i in 0..=per_piece {
            let d = p.rational.derivs(i as f64 / per_piece as f64);
            out.push((d.p, d.kappa()));
        }
    }
    out
}

fn main() {
    let tol: f64 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(0.3);
    for line in &aesthetic_curves_data::PRIUS {
        let pts: Vec<Point> = line
            .points()
            .into_iter()
            .map(|[x, y]| Point::new(x, y))
            .collect();
        let t0 = std::time::Instant::now();
        let sk = match fit_sketch(&pts, &SketchOptions::with_tolerance(tol)) {
            Ok(s) => s,
            Err(e) => {
                println!("{}: error {e}", line.name);
                continue;
            }
        };
        let ms = t0.elapsed().as_secs_f64() * 1e3;
        let d = dense(&sk, 400);
        // True nearest distance: brute force over the dense polyline's chords.
        let mut worst = 0.0f64;
        for q in &pts {
            let mut best = f64::INFINITY;
            for w in d.windows(2) {
                let (a, b) = (w[0].0, w[1].0);
                let v = b - a;
                let t = ((*q - a).dot(v) / v.hypot2().max(1e-300)).clamp(0.0, 1.0);
                best = best.min((a + v * t - *q).hypot());
            }
            worst = worst.max(best);
        }
        let kmax = d.iter().map(|x| x.1.abs()).fold(0.0, f64::max);
        let infl = d.windows(2).filter(|w| w[0].1 * w[1].1 < 0.0).count();
        let ks: Vec<f64> = d.iter().map(|x| x.1).collect();
        let mut extrema = 0;
        let mut last = 0.0f64;
        for w in ks.windows(2) {
            let dk = w[1] - w[0];
            if dk.abs() > 1e-12 * kmax {
                if last != 0.0 && dk.signum() != last.signum() {
                    extrema += 1;
                }
                last = dk;
            }
        }
        let t1 = std::time::Instant::now();
        let reference = smoothing_fit(&pts, tol).unwrap();
        let smooth_ms = t1.elapsed().as_secs_f64() * 1e3;
        println!("  (smoothing spline alone: {smooth_ms:.1} ms)");
        let spans = reference.spline.to_beziers().unwrap();
        let kref = spans
            .iter()
            .flat_map(|b| (0..=50).map(move |i| b.kappa(i as f64 / 50.0).abs()))
            .fold(0.0, f64::max);
        println!(
            "{}: {} pieces, {ms:.0} ms; deviation {worst:.3} (reported {:.3}); max |k| {kmax:.2e} \
             vs smoothest {kref:.2e} ({:.2}x); {infl} inflections, {extrema} curvature extrema; \
             G2 {} ({:.1e}); monotone {}; alphas {:?}",
            line.name,
            sk.pieces.len(),
            sk.max_deviation,
            kmax / kref,
            sk.g2,
            sk.max_curvature_jump,
            sk.all_monotone,
            sk.pieces
                .iter()
                .map(|p| (p.alpha * 100.0).round() / 100.0)
                .collect::<Vec<_>>()
        );
    }
}
