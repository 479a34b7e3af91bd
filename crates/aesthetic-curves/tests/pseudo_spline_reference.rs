//! The pseudo-elastic spline (docs/math.md §5, S2) against an independent reference: n = 3..10
//! points on the unit circle, closed curve. The reference (`aesthetic_curves_data::PSEUDO_UNIT_CIRCLE_REFERENCE`)
//! comes from `tools/pseudo_reference.py`: mpmath at 40 digits, tanh-sinh quadrature and a
//! root of dJ/dr for the symmetric span (by symmetry every tangent is the circle's), with the
//! Hessian checked positive definite. It reproduces the exact n = 3 and n = 4 values.
//!
//! Done criteria of the issue: exact mode within 1e-7 of the reference, table mode within
//! 1e-5; the spans interpolate the points, are G1 at every point, and their own length is the
//! reported length.

use aesthetic_curves::pseudo_spline::{pseudo_elastic, Mode, PseudoSpline};
use aesthetic_curves::Point;
use std::f64::consts::PI;

fn reference() -> Vec<(usize, f64, f64)> {
    let text = aesthetic_curves_data::PSEUDO_UNIT_CIRCLE_REFERENCE;
    text.lines()
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            (v[0] as usize, v[1], v[2])
        })
        .collect()
}

fn circle(n: usize) -> Vec<Point> {
    (0..n)
        .map(|k| {
            let a = 2.0 * PI * k as f64 / n as f64;
            Point::new(a.cos(), a.sin())
        })
        .collect()
}

/// Interpolation, G1 at every point, the circle's tangents, and the spans' own length
/// (dense chords, independent of the reported number) against the reported length.
fn check_geometry(s: &PseudoSpline, pts: &[Point], length_tol: f64) {
    let n = pts.len();
    let mut total = 0.0;
    for (i, sp) in s.segments.iter().enumerate() {
        assert!((sp.eval(0.0) - pts[i]).hypot() < 1e-14);
        assert!((sp.eval(1.0) - pts[(i + 1) % n]).hypot() < 1e-14);
        let next = &s.segments[(i + 1) % n];
        assert!(sp.d1.cross(next.d0).abs() < 1e-12 * sp.d1.hypot() * next.d0.hypot());
        assert!(sp.d1.dot(next.d0) > 0.0);
        let m = 20000;
        total += (0..m)
            .map(|k| (sp.eval((k + 1) as f64 / m as f64) - sp.eval(k as f64 / m as f64)).hypot())
            .sum::<f64>();
    }
    // Dense chords fall short of the arc by about L h² κ² / 24: below 1e-9 here.
    assert!(
        (total - s.length).abs() < length_tol,
        "n = {n}: spans' own length {total} vs reported {}",
        s.length
    );
    for (k, a) in s.tangent_angles.iter().enumerate() {
        let want = 2.0 * PI * k as f64 / n as f64 + PI / 2.0;
        let d = (a - want).rem_euclid(2.0 * PI);
        assert!(d.min(2.0 * PI - d) < 1e-6, "tangent {k}: {a} vs {want}");
    }
}

/// The exact mode minimises at every point: the default run checks n = 3 and 4 (a few
/// seconds); all of n = 3..10 (about 45 s on two threads) is a slow oracle that `.ci/run`
/// runs with `--ignored`.
#[test]
fn unit_circle_exact_mode_within_1e_7() {
    exact_mode_against_reference(&reference()[..2]);
}

#[test]
#[ignore = "slow oracle (n = 3..10 in exact mode, about 45 s); .ci/run runs it"]
fn unit_circle_exact_mode_within_1e_7_all() {
    exact_mode_against_reference(&reference());
}

fn exact_mode_against_reference(cases: &[(usize, f64, f64)]) {
    std::thread::scope(|scope| {
        for half in cases.chunks(cases.len().div_ceil(2)) {
            scope.spawn(move || {
                for &(n, length, area) in half {
                    let pts = circle(n);
                    let s = pseudo_elastic(&pts, true, Mode::Exact).unwrap();
                    assert!((s.length - length).abs() < 1e-7, "n = {n}: {}", s.length);
                    assert!((s.area - area).abs() < 1e-7, "n = {n}: {}", s.area);
                    check_geometry(&s, &pts, 1e-7);
                }
            });
        }
    });
}

#[test]
fn unit_circle_table_mode_within_1e_5() {
    for (n, length, area) in reference() {
        let pts = circle(n);
        let s = pseudo_elastic(&pts, true, Mode::Table).unwrap();
        println!(
            "n = {n}: table length {:.9} ({:+.1e}), area {:.9} ({:+.1e})",
            s.length,
            s.length - length,
            s.area,
            s.area - area
        );
        assert!((s.length - length).abs() < 1e-5, "n = {n}: {}", s.length);
        assert!((s.area - area).abs() < 1e-5, "n = {n}: {}", s.area);
        check_geometry(&s, &pts, 1e-5);
    }
}

/// S2's printed Table 4 came from its 36 x 36 table: within 1e-4 where the span's end angle
/// 180°/n is on its 10° grid (n = 3, 6, 9), off by more than 1e-3 elsewhere (its
/// interpolation). This pins the claim made in the gallery, against the independent
/// reference (not against this library).
#[test]
fn collinear_points_zero_energy_in_both_modes() {
    let pts: Vec<Point> = [0.0, 1.0, 2.5, 3.0, 4.5]
        .iter()
        .map(|t| Point::new(2.0 + t, -1.0 + 0.5 * t))
        .collect();
    let dir = 0.5f64.atan2(1.0);
    // Table mode: Newton from the bisector stops at once (J(θ) is even): exact. Exact mode:
    // its search of eq. 11 stops at 1e-7.
    for (mode, tol) in [(Mode::Table, 1e-12), (Mode::Exact, 1e-7)] {
        let s = pseudo_elastic(&pts, false, mode).unwrap();
        for a in &s.tangent_angles {
            assert!((a - dir).abs() < tol, "{mode:?}: {a}");
        }
        assert!(s.energy.abs() < 1e-12, "{mode:?}: {}", s.energy);
        assert!((s.length - 4.5 * 1.25f64.sqrt()).abs() < 1e-9, "{mode:?}");
        assert!(s.area.abs() < 10.0 * tol, "{mode:?}: {}", s.area);
    }
}

#[test]
fn bad_input_gets_typed_errors_in_both_modes() {
    use aesthetic_curves::Error;
    let p = Point::new;
    for mode in [Mode::Table, Mode::Exact] {
        assert!(matches!(
            pseudo_elastic(&[], false, mode),
            Err(Error::InvalidInput { .. })
        ));
        assert!(matches!(
            pseudo_elastic(&[p(0.0, 0.0)], false, mode),
            Err(Error::InvalidInput { .. })
        ));
        assert!(matches!(
            pseudo_elastic(
                &[p(0.0, 0.0), p(1.0, 1.0), p(1.0, 1.0), p(2.0, 0.0)],
                false,
                mode
            ),
            Err(Error::Degenerate(_))
        ));
        assert!(matches!(
            pseudo_elastic(&[p(0.0, 0.0), p(1.0, 1.0), p(0.0, 0.0)], true, mode),
            Err(Error::Degenerate(_))
        ));
        assert!(matches!(
            pseudo_elastic(&[p(0.0, 0.0), p(f64::NAN, 1.0)], false, mode),
            Err(Error::InvalidInput { .. })
        ));
    }
}

#[test]
fn table_mode_is_similarity_invariant_and_reversible() {
    let pts = aesthetic_curves::samples::wavy_points(40, 3);
    let s = pseudo_elastic(&pts, false, Mode::Table).unwrap();
    // Scale by 3, rotate by 0.7, translate: length and area scale, energy (Σ l J) scales
    // with the length, tangents rotate.
    let (c, sn) = (0.7f64.cos(), 0.7f64.sin());
    let moved: Vec<Point> = pts
        .iter()
        .map(|q| {
            Point::new(
                3.0 * (c * q.x - sn * q.y) + 5.0,
                3.0 * (sn * q.x + c * q.y) - 2.0,
            )
        })
        .collect();
    let t = pseudo_elastic(&moved, false, Mode::Table).unwrap();
    assert!((t.length - 3.0 * s.length).abs() < 1e-9 * t.length);
    assert!((t.area - 9.0 * s.area).abs() < 1e-9 * t.area.abs().max(1.0));
    assert!((t.energy - 3.0 * s.energy).abs() < 1e-9 * t.energy);
    for (a, b) in s.tangent_angles.iter().zip(&t.tangent_angles) {
        let d = (b - a - 0.7).rem_euclid(2.0 * PI);
        assert!(d.min(2.0 * PI - d) < 1e-9);
    }
    // Reversed order: the same curve traced backwards.
    let rev: Vec<Point> = pts.iter().rev().copied().collect();
    let r = pseudo_elastic(&rev, false, Mode::Table).unwrap();
    assert!(
        (r.length - s.length).abs() < 1e-6 * s.length,
        "{} {}",
        r.length,
        s.length
    );
    assert!((r.energy - s.energy).abs() < 1e-6 * s.energy);
    for (a, b) in s.tangent_angles.iter().zip(r.tangent_angles.iter().rev()) {
        let d = (b - a - PI).rem_euclid(2.0 * PI);
        assert!(d.min(2.0 * PI - d) < 1e-6, "{a} {b}");
    }
}
