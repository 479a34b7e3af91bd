//! `fit_lac` on the Prius key lines against the published fits of Graiff Zurita, Kajiwara &
//! Miura (2023), shipped in the `aesthetic-curves-data` crate (`data/prius`).

use aesthetic_curves::lac_fit::{fit_lac, LacFitOptions, LacFitStart};
use aesthetic_curves::Point;

fn points(i: usize) -> Vec<Point> {
    aesthetic_curves_data::PRIUS[i - 1]
        .points()
        .into_iter()
        .map(|[x, y]| Point::new(x, y))
        .collect()
}

/// (guess, output) alpha of the published fit.
fn published(i: usize) -> (f64, f64) {
    let line = &aesthetic_curves_data::PRIUS[i - 1];
    (
        line.published("alpha", false).unwrap(),
        line.published("alpha", true).unwrap(),
    )
}

#[test]
fn paper_procedure_reproduces_the_published_alphas() {
    for i in [1, 2, 3, 5] {
        let pts = points(i);
        let (guess, out) = published(i);
        let paper = fit_lac(
            &pts,
            LacFitOptions {
                start: LacFitStart::Paper,
                ..Default::default()
            },
        )
        .unwrap();
        let scan = fit_lac(&pts, LacFitOptions::default()).unwrap();
        println!(
            "ps_{i}: published guess {guess} alpha {out}; paper guess {:.3} alpha {:.3} rms {:.3}; \
             scan alpha {:.3} rms {:.3}",
            paper.alpha_guess.unwrap(),
            paper.alpha,
            paper.rms_deviation,
            scan.alpha,
            scan.rms_deviation
        );
        assert!(
            (paper.alpha - out).abs() < 1.0,
            "ps_{i}: {} vs {out}",
            paper.alpha
        );
        // The guess stays within the paper's ±10 % box.
        let g = paper.alpha_guess.unwrap();
        assert!((paper.alpha - g).abs() <= 0.1 * g.abs() + 1e-12);
        // The free least-squares fit is at least as close to the points (same objective).
        assert!(scan.rms_correspondence <= paper.rms_correspondence * 1.001);
    }
}

/// The distances `fit_lac` reports are true of the fitted segment: checked against the
/// nearest point of a dense polyline of it (every chord, no assumption that the measured
/// points advance along the line; ps_4 has points that step back).
#[test]
fn reported_distances_are_the_true_ones() {
    for i in 1..=5 {
        let pts = points(i);
        let fit = fit_lac(&pts, LacFitOptions::default()).unwrap();
        let (poly, _) = fit.segment.sample(6001).unwrap();
        let d: Vec<f64> = pts
            .iter()
            .map(|q| {
                poly.windows(2)
                    .map(|w| {
                        let v = w[1] - w[0];
                        let t = ((*q - w[0]).dot(v) / v.hypot2()).clamp(0.0, 1.0);
                        (w[0] + v * t - *q).hypot()
                    })
                    .fold(f64::INFINITY, f64::min)
            })
            .collect();
        let max = d.iter().copied().fold(0.0, f64::max);
        let rms = (d.iter().map(|x| x * x).sum::<f64>() / d.len() as f64).sqrt();
        let (k0, k1) = fit.segment.end_curvatures().unwrap();
        println!(
            "ps_{i}: alpha {:.3} (converged {}); reported max {:.4} rms {:.4}; measured max \
             {max:.4} rms {rms:.4}; end curvatures {k0:.2e} {k1:.2e}",
            fit.alpha, fit.converged, fit.max_deviation, fit.rms_deviation
        );
        assert!(
            (fit.max_deviation - max).abs() <= 2e-3 + 1e-3 * max,
            "ps_{i}: max"
        );
        assert!(
            (fit.rms_deviation - rms).abs() <= 2e-3 + 1e-3 * rms,
            "ps_{i}: rms"
        );
    }
}
