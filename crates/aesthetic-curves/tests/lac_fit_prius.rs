//! `fit_lac` on the Prius key lines against the published fits of Graiff Zurita, Kajiwara &
//! Miura (2023), `shared/data/prius/ps_N-published-fit.txt`.

use aesthetic_curves::lac_fit::{fit_lac, LacFitOptions, LacFitStart};
use aesthetic_curves::Point;

fn data(name: &str) -> String {
    let path = format!(
        "{}/../../../shared/data/prius/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    std::fs::read_to_string(&path).expect("prius data beside the checkout")
}

fn points(i: usize) -> Vec<Point> {
    data(&format!("ps_{i}.csv"))
        .lines()
        .skip(1)
        .filter_map(|l| {
            let v: Vec<f64> = l.split(',').filter_map(|x| x.trim().parse().ok()).collect();
            (v.len() == 2).then(|| Point::new(v[0], v[1]))
        })
        .collect()
}

/// (guess, output) alpha of the published fit.
fn published(i: usize) -> (f64, f64) {
    let text = data(&format!("ps_{i}-published-fit.txt"));
    let a: Vec<f64> = text
        .lines()
        .filter(|l| l.starts_with("alpha"))
        .map(|l| l.split_whitespace().nth(1).unwrap().parse().unwrap())
        .collect();
    (a[0], a[1])
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
