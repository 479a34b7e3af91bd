//! Standard-form LAC points against mpmath references at 40 digits
//! (`tools/lac_reference.py`): alpha from -20 to 20, near-singular ends, several turns.

use aesthetic_curves::lac::LacStandard;

#[test]
fn standard_form_matches_high_precision_reference() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/lac_reference.csv");
    let text = std::fs::read_to_string(path).unwrap();
    let mut worst = (0.0f64, String::new());
    let mut n = 0;
    for line in text.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|s| s.parse().unwrap()).collect();
        let (a, l, t, x, y) = (v[0], v[1], v[2], v[3], v[4]);
        let p = LacStandard::new(a, l)
            .unwrap()
            .eval(t)
            .unwrap_or_else(|e| panic!("alpha {a} lambda {l} theta {t}: {e}"));
        let err = ((p.x - x).powi(2) + (p.y - y).powi(2)).sqrt() / (x * x + y * y).sqrt();
        if err > worst.0 {
            worst = (err, line.to_string());
        }
        assert!(
            err < 1e-12,
            "alpha {a} lambda {l} theta {t}: relative error {err:e} ({p:?} vs {x}, {y})"
        );
        n += 1;
    }
    println!(
        "{n} reference points, worst relative error {:e} at {}",
        worst.0, worst.1
    );
    assert!(n > 150);
}

/// The same references reached by a dense polyline: `eval_many` on 1000 uniform theta from
/// 0 (every step integrated on its own, mostly by the fast fixed rules), so the end point
/// carries the sum of all step errors.
#[test]
fn dense_polyline_ends_on_the_reference() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/lac_reference.csv");
    let text = std::fs::read_to_string(path).unwrap();
    let mut worst = 0.0f64;
    for line in text.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|s| s.parse().unwrap()).collect();
        let (a, l, t, x, y) = (v[0], v[1], v[2], v[3], v[4]);
        let c = LacStandard::new(a, l).unwrap();
        let mut th: Vec<f64> = (0..1000).map(|i| t * (i as f64 / 999.0)).collect();
        th[999] = t;
        let pts = c
            .eval_many(&th)
            .unwrap_or_else(|e| panic!("alpha {a} lambda {l} theta {t}: {e}"));
        let p = pts[999];
        let err = ((p.x - x).powi(2) + (p.y - y).powi(2)).sqrt() / (x * x + y * y).sqrt();
        worst = worst.max(err);
        assert!(
            err < 1e-12,
            "alpha {a} lambda {l} theta {t}: relative error {err:e} ({p:?} vs {x}, {y})"
        );
        // Every intermediate point is the single-point evaluation too (spot check).
        let q = c.eval(th[500]).unwrap();
        let scale = (x * x + y * y).sqrt();
        assert!((pts[500] - q).hypot() < 1e-12 * scale.max(q.to_vec2().hypot()));
    }
    println!("dense polylines: worst relative error at the end {worst:e}");
}

/// θ_lim (the base angle of the limiting segment Λ = Λ_max, an integral up to the singular
/// end of the domain) against mpmath (`tools/lac_theta_lim.py`).
#[test]
fn theta_lim_matches_high_precision_reference() {
    use aesthetic_curves::lac::LacSegment;
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/lac_theta_lim.csv");
    let text = std::fs::read_to_string(path).unwrap();
    let mut worst = 0.0f64;
    let mut n = 0;
    for line in text.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|s| s.parse().unwrap()).collect();
        let (a, td, want) = (v[0], v[1], v[2]);
        let got = LacSegment::theta_lim(a, td).unwrap();
        let err = (got - want).abs() / want;
        worst = worst.max(err);
        assert!(
            err < 1e-12,
            "alpha {a} theta_d {td}: {got} vs {want} ({err:e})"
        );
        n += 1;
    }
    println!("{n} theta_lim references, worst relative error {worst:e}");
    assert!(n >= 60);
}
