//! Shared by the rational-cubic tests (`approx_reference.rs`, `approx_sweep.rs`): the
//! test triangles and the committed exhaustive optima (read and written).

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

/// One row of an optima file: the case (alpha, turning, base angle, scale, rotation) and
/// its exhaustive optimum (rms, f0, f1).
pub type OptimumRow = ([f64; 5], (f64, f64, f64));

/// The rows of a committed optima file: the case (alpha, turning, base angle, scale,
/// rotation) and its exhaustive optimum (rms, f0, f1; rms `inf` when no monotone cubic
/// exists).
pub fn read_optima(path: &str) -> Vec<OptimumRow> {
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

/// Write optima rows in the format [`read_optima`] reads, after `header` (comment lines and
/// the column names, each ending in a newline). Floats by `{:?}`: they read back exactly.
pub fn write_optima(path: &str, header: &str, rows: &[OptimumRow]) {
    let mut text = header.to_string();
    for (c, b) in rows {
        text += &format!(
            "{:?},{:?},{:?},{:?},{:?},{:?},{:?},{:?}\n",
            c[0], c[1], c[2], c[3], c[4], b.0, b.1, b.2
        );
    }
    std::fs::write(path, text).unwrap_or_else(|e| panic!("{path}: {e}"));
}
