//! The delivered cubics' joins as their f64 coordinates give them. A cubic's end curvature
//! is read from its first three control points, `(2/3) (w0 w2 / w1²) (P1 - P0) × (P2 - P1)
//! / |P1 - P0|³`: where a piece is short and far from the origin, the rounding of those
//! points to f64 moves it by about `ulp / |P1 - P0|²`, above the G2 a user's tool checks
//! (the harsh sets of `tests/spiro_oracle.rs`: pieces 8e-5 long 2.8 from the origin, whose cubics'
//! curvatures jumped by 3e-8 to 4e-7 of the largest curvature at smooth joins). Two repairs, each
//! kept only where the exact test proves the moved cubic monotone as it did the first:
//!
//! - an inflection end (zero curvature): P0 and P2 kept (so both end tangents are), P1
//!   moved to a point of the f64 grid within 1e-5 of its handle of the line P0 P2 and
//!   nearest it: in units of the grid, `P2 - P0 = V` and `P1 - P0 = X` are integer vectors
//!   and the reading is proportional to the integer `c = X × V`; the grid points with a
//!   given c are one solution (from the extended gcd of V) plus multiples of `V / gcd`,
//!   and a small c whose point lies near the handle's place is a short vector of a 2D
//!   lattice (reduced, then the place rounded onto it). The reading is then at the noise
//!   of evaluating the cross product in f64 (about ε |P1 - P0| |P2 - P1|), some 1e-12 of
//!   the curvature where it was 1e-7;
//! - an end of non-zero curvature: its end weight scaled so that the curvature read from
//!   the coordinates is the segment's (the curvature at t = 0 is linear in w0, at t = 1 in
//!   w3, and neither weight enters the other end's).
//!
//! A moved piece's reported error grows by a bound of the move: its largest control point
//! displacement plus its largest relative weight change times its control polygon's
//! diameter (a rational Bézier's point is a convex combination of its control points).

use super::pieces::{SplinePiece, SplinePieceKind};
use crate::bezier::RationalBezier;
use crate::monotone::CurvatureMonotone;
use kurbo::{Point, Vec2};

/// A curvature read off by more than this share of the spline's largest is repaired (the
/// spline's accepted jump, [`super::ACCEPTED_JUMP`]: below it a move would cost an exact
/// test a piece for nothing a user's tool sees; at 1e-13 the circle of the spline's
/// bench took 10 times as long).
const READ_OFF: f64 = super::ACCEPTED_JUMP;

/// The most an end weight is scaled by (relative): a short, nearly straight piece's end
/// curvature moves by up to a few per mille with its coordinates' rounding.
const MOST_REWEIGHT: f64 = 0.05;

/// An inflection end's P1 moves along its handle by at most this share of it.
const HANDLE_SHARE: f64 = 1e-5;

/// Repair the pieces' cubics where their f64 coordinates read their end curvatures off
/// the segments' (module documentation).
pub(super) fn sharpen(pieces: &mut [SplinePiece]) {
    let big = pieces.iter().fold(0.0f64, |m, p| {
        m.max(p.end_curvatures.0.abs())
            .max(p.end_curvatures.1.abs())
    });
    if big == 0.0 {
        return;
    }
    let off = READ_OFF * big;
    for p in pieces.iter_mut() {
        let mut c = p.rational.clone();
        if p.kind == SplinePieceKind::LacInflection {
            if p.end_curvatures.0 == 0.0 && c.kappa_start().abs() > off {
                c = straightened_start(&c).unwrap_or(c);
            } else if p.end_curvatures.1 == 0.0 && c.kappa_end().abs() > off {
                c = straightened_start(&c.reversed())
                    .map(|r| r.reversed())
                    .unwrap_or(c);
            }
        }
        let c = matched(&c, p.end_curvatures, off).unwrap_or(c);
        if c != p.rational && keeps_proof(p, &c) {
            replace(p, c);
        }
    }
}

/// `c` with its end weights scaled so that its end curvatures read `target` from its
/// coordinates, where one reads off by more than `off` (and by less than
/// [`MOST_REWEIGHT`] of itself); `None` where nothing needs it or can have it.
fn matched(c: &RationalBezier, target: (f64, f64), off: f64) -> Option<RationalBezier> {
    let mut w = c.weights().to_vec();
    let mut changed = false;
    for (end, want) in [(0, target.0), (3, target.1)] {
        let read = |c: &RationalBezier| {
            if end == 0 {
                c.kappa_start()
            } else {
                c.kappa_end()
            }
        };
        if want == 0.0 || (read(c) - want).abs() <= off {
            continue;
        }
        // Twice: the reading is linear in the weight up to its own rounding.
        for _ in 0..2 {
            let now = RationalBezier::new(c.points().to_vec(), w.clone()).ok()?;
            let f = want / read(&now);
            if (f - 1.0).abs() >= MOST_REWEIGHT || f.is_nan() {
                return None;
            }
            w[end] *= f;
        }
        changed = true;
    }
    if !changed {
        return None;
    }
    RationalBezier::new(c.points().to_vec(), w).ok()
}

/// `c`, whose start is an inflection, with P1 on the f64 grid nearest the line P0 P2 within
/// [`HANDLE_SHARE`] of its place along it (module documentation); `None` where the
/// differences are not exact in f64 or no grid point is near enough.
fn straightened_start(c: &RationalBezier) -> Option<RationalBezier> {
    let p = c.points();
    let (m, p1, p2) = (p[0], p[1], p[2]);
    let unit = Vec2::new(
        ulp(m.x).min(ulp(p1.x)).min(ulp(p2.x)),
        ulp(m.y).min(ulp(p1.y)).min(ulp(p2.y)),
    );
    let v = (
        grid_steps(m.x, p2.x, unit.x)?,
        grid_steps(m.y, p2.y, unit.y)?,
    );
    let (dv, d1) = (p2 - m, p1 - m);
    let s = d1.dot(dv) / dv.hypot2();
    if !(s > 0.0 && s.is_finite()) {
        return None;
    }
    let (x, y) = near_line(v, s, HANDLE_SHARE * s)?;
    let q = Point::new(on_grid(m.x, x, unit.x)?, on_grid(m.y, y, unit.y)?);
    let mut pts = p.to_vec();
    pts[1] = q;
    let out = RationalBezier::new(pts, c.weights().to_vec()).ok()?;
    (out.kappa_start().abs() < c.kappa_start().abs()).then_some(out)
}

/// The spacing of the f64 numbers at `x` (the smallest positive normal at 0).
fn ulp(x: f64) -> f64 {
    let x = x.abs();
    if x == 0.0 || !x.is_normal() {
        return f64::MIN_POSITIVE;
    }
    f64::from_bits(x.to_bits() + 1) - x
}

/// `to - from` in grid steps `u`, where that difference is exact in f64 (Sterbenz) and a
/// whole number of steps.
fn grid_steps(from: f64, to: f64, u: f64) -> Option<i128> {
    if !close(from, to) {
        return None;
    }
    let d = to - from;
    let k = (d / u).round();
    (k.abs() < 2f64.powi(60) && k * u == d).then_some(k as i128)
}

/// Whether `a - b` is exact in f64: equal, zero, or within a factor 2 of each other with
/// the same sign (Sterbenz's lemma).
fn close(a: f64, b: f64) -> bool {
    a == b
        || a == 0.0
        || b == 0.0
        || (a.signum() == b.signum() && a.abs() <= 2.0 * b.abs() && b.abs() <= 2.0 * a.abs())
}

/// `from + k u`, where that is exact in f64 and its difference from `from` is too.
fn on_grid(from: f64, k: i128, u: f64) -> Option<f64> {
    if k.unsigned_abs() >= 1 << 52 {
        return None;
    }
    let d = k as f64 * u;
    let out = from + d;
    (close(out, from) && out - from == d).then_some(out)
}

/// An integer point X near the line through 0 and `v` (small |c| for `c = X × v`) whose
/// place along it, `X · v / |v|²`, is within `tol` of `s`. The points with `X × v = c` are
/// `c/g (b, -a) + t v/g` (g = gcd(v), `a vx + b vy = g`): in the plane of (c, place) the
/// points are the lattice spanned by `(g, α)` (k = 1: (b, -a), α its place) and `(0, 1/g)`
/// (t = 1). Scaled so that the box |c| <= 1/tol, |place - s| <= tol is a square, the basis
/// reduced (Lagrange–Gauss): its points lie on rows along one reduced vector, spaced by
/// the other; on the rows nearest the target, the points nearest its place.
fn near_line(v: (i128, i128), s: f64, tol: f64) -> Option<(i128, i128)> {
    let (g, a, b) = extended_gcd(v.0, v.1);
    if g == 0 || tol.is_nan() || tol <= 0.0 {
        return None;
    }
    let norm = (v.0 * v.0 + v.1 * v.1) as f64;
    let alpha = (b * v.0 - a * v.1) as f64 / norm;
    // Basis vectors in the scaled plane with their integer combination (k, t).
    let scaled = |k: f64, t: f64| ((k * g as f64) * tol, (k * alpha + t / g as f64) / tol);
    let mut basis = [
        ((1i128, 0i128), scaled(1.0, 0.0)),
        ((0, 1), scaled(0.0, 1.0)),
    ];
    let dot = |x: (f64, f64), y: (f64, f64)| x.0 * y.0 + x.1 * y.1;
    for _ in 0..200 {
        if dot(basis[0].1, basis[0].1) > dot(basis[1].1, basis[1].1) {
            basis.swap(0, 1);
        }
        let (b0, b1) = (basis[0], basis[1]);
        let mu = (dot(b0.1, b1.1) / dot(b0.1, b0.1)).round();
        if mu == 0.0 || !mu.is_finite() {
            break;
        }
        let m = mu as i128;
        basis[1] = (
            (b1.0 .0 - m * b0.0 .0, b1.0 .1 - m * b0.0 .1),
            (b1.1 .0 - mu * b0.1 .0, b1.1 .1 - mu * b0.1 .1),
        );
    }
    // The target (0, s / tol): the rows `j R + i S` (R either reduced vector, j near the
    // target's coordinate on it) crossed at the place nearest it by i, the least |c| of
    // those within the tolerance.
    let target = s / tol;
    let ((u, p), (w, q)) = (basis[0].1, basis[1].1);
    let det = u * q - w * p;
    let along = [-w * target / det, u * target / det];
    let mut best: Option<(i128, (i128, i128))> = None;
    for (r, st) in [(0usize, 1usize), (1, 0)] {
        let (row, step) = (basis[r], basis[st]);
        if step.1 .1 == 0.0 {
            continue;
        }
        let j0 = along[r].round() as i128;
        for j in j0 - 3..=j0 + 3 {
            let i_real = (target - j as f64 * row.1 .1) / step.1 .1;
            for i in [i_real.floor() as i128, i_real.ceil() as i128] {
                let k = j * row.0 .0 + i * step.0 .0;
                let t = j * row.0 .1 + i * step.0 .1;
                let x = (k * b + t * (v.0 / g), -k * a + t * (v.1 / g));
                let place = (x.0 * v.0 + x.1 * v.1) as f64 / norm;
                let c = (x.0 * v.1 - x.1 * v.0).abs();
                if (place - s).abs() <= tol && best.is_none_or(|(bc, _)| c < bc) {
                    best = Some((c, x));
                }
            }
        }
    }
    best.map(|(_, x)| x)
}

/// (g, a, b) with `a x + b y = g = gcd(x, y) >= 0`.
fn extended_gcd(x: i128, y: i128) -> (i128, i128, i128) {
    let (mut r0, mut r1) = (x, y);
    let (mut a0, mut a1) = (1i128, 0i128);
    let (mut b0, mut b1) = (0i128, 1i128);
    while r1 != 0 {
        let q = r0 / r1;
        (r0, r1) = (r1, r0 - q * r1);
        (a0, a1) = (a1, a0 - q * a1);
        (b0, b1) = (b1, b0 - q * b1);
    }
    if r0 < 0 {
        (-r0, -a0, -b0)
    } else {
        (r0, a0, b0)
    }
}

/// Whether the moved cubic keeps the piece's proof: proven monotone by the exact test, or
/// the piece was not proven either.
fn keeps_proof(piece: &SplinePiece, c: &RationalBezier) -> bool {
    !piece.monotone || c.is_curvature_monotone().unwrap_or(false)
}

/// The piece with its cubic moved to `c`, its error grown by the move's bound.
fn replace(piece: &mut SplinePiece, c: RationalBezier) {
    let old = &piece.rational;
    let shift = old
        .points()
        .iter()
        .zip(c.points())
        .fold(0.0f64, |m, (a, b)| m.max((*a - *b).hypot()));
    let reweight = old
        .weights()
        .iter()
        .zip(c.weights())
        .fold(0.0f64, |m, (a, b)| m.max((a / b - 1.0).abs()));
    let pts = c.points();
    let diameter = pts.iter().fold(0.0f64, |m, a| {
        pts.iter().fold(m, |m, b| m.max((*a - *b).hypot()))
    });
    piece.rational_error += shift + reweight * diameter;
    piece.rational = c;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_extended_gcd_combines_to_the_gcd() {
        for (x, y) in [
            (240, 46),
            (-240, 46),
            (7, 0),
            (0, -5),
            (123456789012, 98765432109),
        ] {
            let (g, a, b) = extended_gcd(x, y);
            assert_eq!(a * x + b * y, g);
            assert!(g > 0 && x % g == 0 && y % g == 0, "{x} {y} {g}");
        }
    }

    #[test]
    fn a_point_near_the_line_is_the_nearest_the_gcd_allows() {
        // v coprime: X × v = c has its points one v apart, so a place within tol of s
        // needs |c| about 1/tol; the found point's c and place are checked here.
        let v = (104_729i128, 7_919i128);
        let (x, y) = near_line(v, 0.37, 1e-3).unwrap();
        let place = (x * v.0 + y * v.1) as f64 / ((v.0 * v.0 + v.1 * v.1) as f64);
        assert!((place - 0.37).abs() <= 1e-3);
        let c = x * v.1 - y * v.0;
        assert!(c.abs() <= 2_000, "{c}");
        // With a common factor, c = 0 has points every v/g: one is near enough.
        let (x, y) = near_line((1000, 300), 0.5, 0.06).unwrap();
        assert_eq!(x * 300 - y * 1000, 0);
    }

    /// A short, nearly straight inflection end far from the origin (the harsh sets' 3e-5
    /// handles 2.8 from the origin): read at 1e-7 of its far curvature before, at the
    /// noise of the cross product's evaluation after, its ends and tangents kept.
    #[test]
    fn a_straightened_inflection_end_reads_near_zero() {
        let m = Point::new(1.7271987702846534, 2.814496353427613);
        let t = Vec2::new(0.9977, 0.0655).normalize();
        let n = Vec2::new(-t.y, t.x);
        let h = 3e-5;
        let c = RationalBezier::new(
            vec![m, m + t * h, m + t * 1.9 * h, m + t * 2.8 * h + n * 2e-7],
            vec![1.0, 1.0, 1.0, 1.1],
        )
        .unwrap();
        let far = c.kappa_end().abs();
        let before = c.kappa_start().abs();
        let s = straightened_start(&c).expect("a grid point near the line");
        let after = s.kappa_start().abs();
        eprintln!("read {before:e} -> {after:e} (far end {far:e})");
        assert!(after < 1e-9 * far, "{after:e}");
        let (p, q) = (c.points(), s.points());
        assert_eq!((p[0], p[2], p[3]), (q[0], q[2], q[3]));
        assert!((p[1] - q[1]).hypot() <= 2.0 * HANDLE_SHARE * h);
        let turn = (q[1] - q[0]).normalize().cross(t).abs();
        assert!(turn < 1e-10, "{turn:e}");
    }

    #[test]
    fn matched_weights_read_the_target_curvatures() {
        let c = RationalBezier::new(
            vec![
                Point::new(1000.0, 1000.0),
                Point::new(1000.00001, 1000.0),
                Point::new(1000.00002, 1000.000001),
                Point::new(1000.00003, 1000.000003),
            ],
            vec![1.0, 0.9, 0.95, 1.1],
        )
        .unwrap();
        let want = (c.kappa_start() * (1.0 + 1e-6), c.kappa_end() * (1.0 - 2e-6));
        let m = matched(&c, want, 0.0).unwrap();
        assert!((m.kappa_start() - want.0).abs() <= 1e-14 * want.0.abs());
        assert!((m.kappa_end() - want.1).abs() <= 1e-14 * want.1.abs());
        assert_eq!(m.weights()[1..3], c.weights()[1..3]);
    }
}
