//! Shared by the rational-cubic tests (`approx_reference.rs`, `approx_sweep.rs`): the
//! test triangles and the committed exhaustive optima.

use aesthetic_curves::{Point, Vec2};

/// Triangle with turning angle `td` and base angle `phi` at the start (start (0,0), tangent
/// intersection (1,0)), scaled and rotated.
pub fn triangle(td: f64, phi: f64, scale: f64, rot: f64) -> [Point; 3] {
    let d = phi.sin() / (td - phi).sin();
    let end = Vec2::new(1.0 + d * td.cos(), d * td.sin());
    let r = Vec2::from_angle(rot);
    let m = |v: Vec2| {
        Point::new(
            scale * (v.x * r.x - v.y * r.y),
            scale * (v.x * r.y + v.y * r.x),
        )
    };
    [m(Vec2::ZERO), m(Vec2::new(1.0, 0.0)), m(end)]
}

/// The rows of a committed optima file: the case (alpha, turning, base angle, scale,
/// rotation) and its exhaustive optimum (rms, f0, f1; rms `inf` when no monotone cubic
/// exists).
pub fn read_optima(path: &str) -> Vec<([f64; 5], (f64, f64, f64))> {
    std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{path}: {e}"))
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with("alpha"))
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.trim().parse().unwrap()).collect();
            ([v[0], v[1], v[2], v[3], v[4]], (v[5], v[6], v[7]))
        })
        .collect()
}
