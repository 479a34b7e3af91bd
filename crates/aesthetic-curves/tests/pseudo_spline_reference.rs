//! The pseudo-elastic spline (exact mode) against S2's unit-circle values (math.md §5):
//! n = 3 points on the unit circle, closed: length 6.18957616, area 3.04563775 (S2 Table 4/5,
//! where 60 degrees lies on the paper's table grid, so its value is exact to its 9 digits).

use aesthetic_curves::pseudo_spline::pseudo_elastic;
use aesthetic_curves::Point;
use std::f64::consts::PI;

#[test]
fn unit_circle_three_points() {
    let n = 3;
    let pts: Vec<Point> = (0..n)
        .map(|k| {
            let a = 2.0 * PI * k as f64 / n as f64;
            Point::new(a.cos(), a.sin())
        })
        .collect();
    let s = pseudo_elastic(&pts, true).unwrap();
    assert!((s.length - 6.18957616).abs() < 1e-7, "length {}", s.length);
    assert!((s.area - 3.04563775).abs() < 1e-7, "area {}", s.area);
    // The spans interpolate the points, meet with one tangent direction (G1), and their own
    // length (measured here independently by dense chords) is the reported length.
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
    assert!((total - s.length).abs() < 1e-7, "{total} vs {}", s.length);
    // Symmetry: the three tangents are the circle's tangents.
    for (k, a) in s.tangent_angles.iter().enumerate() {
        let want = 2.0 * PI * k as f64 / n as f64 + PI / 2.0;
        let d = (a - want).rem_euclid(2.0 * PI);
        assert!(d.min(2.0 * PI - d) < 1e-6, "tangent {k}: {a} vs {want}");
    }
}

/// n = 4: math.md gives the exact length 6.25483827 (S2 Table 4 printed 6.26067766, its table
/// interpolation error). Also prints n = 3..10 for the record.
#[test]
fn unit_circle_four_points_and_table() {
    for n in 3..=10usize {
        let pts: Vec<Point> = (0..n)
            .map(|k| {
                let a = 2.0 * PI * k as f64 / n as f64;
                Point::new(a.cos(), a.sin())
            })
            .collect();
        let t = std::time::Instant::now();
        let s = pseudo_elastic(&pts, true).unwrap();
        println!(
            "n = {n}: length {:.8} area {:.8} ({:.2?})",
            s.length,
            s.area,
            t.elapsed()
        );
        if n == 4 {
            assert!((s.length - 6.25483827).abs() < 1e-7, "length {}", s.length);
        }
        // Points on a circle: the curve lies between the polygon and the circle's perimeter
        // plus a little; the length approaches 2π from below as n grows.
        let polygon = 2.0 * n as f64 * (PI / n as f64).sin();
        assert!(
            s.length > polygon && s.length < 2.0 * PI + 0.1,
            "n = {n}: {}",
            s.length
        );
    }
}
