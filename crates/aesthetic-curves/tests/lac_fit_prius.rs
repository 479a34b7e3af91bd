//! `fit_lac` on the Prius key lines against the published fits of Graiff Zurita, Kajiwara &
//! Miura (2023), shipped in the `aesthetic-curves-data` crate (`data/prius`).

use aesthetic_curves::lac_fit::{fit_lac, LacFitObjective, LacFitOptions, LacFitStart};
use aesthetic_curves::Point;

fn points(i: usize) -> Vec<Point> {
    aesthetic_curves_data::PRIUS[i - 1].points_as::<Point>()
}

/// Nearest distance from each point to a polyline (every chord: no assumption that the
/// points advance along it).
fn distances(poly: &[Point], pts: &[Point]) -> Vec<f64> {
    pts.iter()
        .map(|q| {
            poly.windows(2)
                .map(|w| {
                    let v = w[1] - w[0];
                    let t = ((*q - w[0]).dot(v) / v.hypot2()).clamp(0.0, 1.0);
                    (w[0] + v * t - *q).hypot()
                })
                .fold(f64::INFINITY, f64::min)
        })
        .collect()
}

fn max_rms(d: &[f64]) -> (f64, f64) {
    (
        d.iter().copied().fold(0.0, f64::max),
        (d.iter().map(|x| x * x).sum::<f64>() / d.len() as f64).sqrt(),
    )
}

fn to_points(v: Vec<[f64; 2]>) -> Vec<Point> {
    v.into_iter().map(|[x, y]| Point::new(x, y)).collect()
}

/// Item 6 of the fair-curves issue, on all five lines: the default fit spans the data (its
/// ends are the feet of the perpendiculars from the first and last points), has no hook
/// (largest curvature at most twice the published fit's), is at least as close to the
/// points as the published fit by max AND rms distance, moved alpha off its scan starts and
/// says whether it converged.
///
/// The published fit is rebuilt from its parameters (printed to 3 decimals) both as the
/// continuous curve they define and as the authors' own forward-Euler polyline; it gets the
/// better of the two on each measure.
#[test]
fn beats_the_published_fits_without_hooks() {
    for i in 1..=5 {
        let pts = points(i);
        let line = &aesthetic_curves_data::PRIUS[i - 1];
        let pf = line.published_curve(true).unwrap();
        let (m1, r1) = max_rms(&distances(&to_points(pf.points(3000)), &pts));
        let (m2, r2) = max_rms(&distances(&to_points(pf.euler_points()), &pts));
        let (pub_max, pub_rms, pub_k) = (m1.min(m2), r1.min(r2), pf.max_curvature());
        let fit = fit_lac(&pts, LacFitOptions::default()).unwrap();
        let aesthetic_curves::Polyline {
            points: poly,
            kappa: k,
        } = fit.segment.sample(6001).unwrap();
        let (max, rms) = max_rms(&distances(&poly, &pts));
        let kmax = k.iter().map(|v| v.abs()).fold(0.0, f64::max);
        let c = fit.segment.control();
        let gap = |q: Point, p: Point, t: aesthetic_curves::Vec2| (q - p).dot(t.normalize());
        let (g0, g1) = (
            gap(pts[0], c[0], c[1] - c[0]),
            gap(pts[pts.len() - 1], c[2], c[2] - c[1]),
        );
        println!(
            "ps_{i}: alpha {:.3} (published {:.3}; at bound {}, converged {}); max {max:.3} \
             rms {rms:.3} mm (published {pub_max:.3} {pub_rms:.3}); max |k| {kmax:.3e} \
             (published {pub_k:.3e}); end gaps {g0:.1e} {g1:.1e} mm",
            fit.alpha, pf.alpha, fit.alpha_at_bound, fit.converged
        );
        assert!(g0.abs() < 1e-6 && g1.abs() < 1e-6, "ps_{i}: ends {g0} {g1}");
        assert!(kmax <= 2.0 * pub_k, "ps_{i}: hook {kmax:e} vs {pub_k:e}");
        assert!((kmax - fit.max_curvature).abs() <= 1e-3 * kmax, "ps_{i}");
        assert!(max <= pub_max, "ps_{i}: max {max} vs {pub_max}");
        assert!(rms <= pub_rms, "ps_{i}: rms {rms} vs {pub_rms}");
        for a in [-4.5, -3.0, -1.5, -0.5, 0.0, 0.5, 1.0, 1.5, 2.0, 3.0, 4.5] {
            assert!((fit.alpha - a).abs() > 1e-3, "ps_{i}: alpha stayed at {a}");
        }
        assert_eq!(
            fit.alpha_at_bound,
            (fit.alpha.abs() - 5.0).abs() < 1e-6,
            "ps_{i}"
        );
        assert!(fit.converged, "ps_{i}: not converged");
    }
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
                objective: LacFitObjective::ArcLength,
                ..Default::default()
            },
        )
        .unwrap();
        let scan = fit_lac(
            &pts,
            LacFitOptions {
                objective: LacFitObjective::ArcLength,
                ..Default::default()
            },
        )
        .unwrap();
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
        let poly = fit.segment.sample(6001).unwrap().points;
        let (max, rms) = max_rms(&distances(&poly, &pts));
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

/// 20,000 points (the protocol's limit) are fitted on a subsample and polished on all of
/// them, in about a second; the reported distances are those of every point.
#[test]
fn twenty_thousand_points_fit_in_about_a_second() {
    let line = points(1);
    // Every measured point and 24 points between each pair, on the chords.
    let mut many = Vec::new();
    for w in line.windows(2) {
        for k in 0..25 {
            many.push(w[0] + (w[1] - w[0]) * (k as f64 / 25.0));
        }
    }
    many.truncate(20_000);
    let t = std::time::Instant::now();
    let fit = fit_lac(&many, LacFitOptions::default()).unwrap();
    let secs = t.elapsed().as_secs_f64();
    let poly = fit.segment.sample(6001).unwrap().points;
    let (max, rms) = max_rms(&distances(
        &poly,
        &many[..many.len()]
            .iter()
            .step_by(7)
            .copied()
            .collect::<Vec<_>>(),
    ));
    println!(
        "20,000 points: {secs:.2} s, alpha {:.3}, reported max {:.3} rms {:.3} (every 7th point: {max:.3} {rms:.3})",
        fit.alpha, fit.max_deviation, fit.rms_deviation
    );
    assert!(secs < 5.0, "{secs} s");
    assert!(max <= fit.max_deviation + 2e-3);
    assert!((rms - fit.rms_deviation).abs() < 0.05 * fit.rms_deviation + 2e-3);
    // As close as the fit of the line itself (the added points lie on its chords).
    let own = fit_lac(&line, LacFitOptions::default()).unwrap();
    assert!(fit.max_deviation <= 1.05 * own.max_deviation + 1e-3);
}
