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
