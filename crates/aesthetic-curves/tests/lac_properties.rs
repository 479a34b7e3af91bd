//! Similarity properties of LAC segments: moving, rotating, scaling or mirroring the control
//! triangle moves the curve the same way; reversing the triangle reverses the curve.

use aesthetic_curves::lac::{LacInflectionSegment, LacSegment};
use aesthetic_curves::{Error, Point};
use proptest::prelude::*;

fn similar(p: Point, angle: f64, scale: f64, d: (f64, f64), mirror: bool) -> Point {
    let (c, s) = (angle.cos(), angle.sin());
    let y = if mirror { -p.y } else { p.y };
    Point::new(
        scale * (c * p.x - s * y) + d.0,
        scale * (s * p.x + c * y) + d.1,
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(120))]

    #[test]
    fn segment_follows_similarities(alpha in -3.0f64..3.0, turn in 0.3f64..2.6, split in 0.52f64..0.95,
                                    angle in -3.2f64..3.2, scale in 0.01f64..100.0,
                                    dx in -50.0f64..50.0, dy in -50.0f64..50.0, mirror in any::<bool>()) {
        // Triangle with turning angle `turn` and base angles split * turn, (1 - split) * turn.
        let te = split * turn;
        let p1 = Point::new(1.0, 0.0);
        let dir = turn;
        // P2 = P1 + t (cos dir, sin dir) with the base angle at P0 equal to te.
        let t = te.sin() / (turn - te).sin();
        let p2 = Point::new(1.0 + t * dir.cos(), t * dir.sin());
        let tri = [Point::ZERO, p1, p2];
        let base = match LacSegment::new(alpha, tri) {
            Ok(s) => s,
            Err(Error::NoSegment(_)) => return Ok(()),
            // The known limit below, one step further: within about 1 % of θ_lim (for alpha
            // near 0) Λ is Λ_max to f64 resolution and may leave no curve f64 can evaluate;
            // `new` says so with a typed error. (alpha -0.18, turn 1.2136, split 0.872: the
            // base angle 2.3e-4 below θ_lim, Λ = Λ_max to 1e-9.)
            Err(Error::NoConvergence(_))
                if LacSegment::theta_lim(alpha, turn).is_ok_and(|lim| te > lim * 0.99) =>
            {
                return Ok(())
            }
            Err(e) => return Err(TestCaseError::fail(format!("{e}"))),
        };
        // Known limit: near the edge of the existence region Λ approaches Λ_max
        // closer than f64 resolves (for alpha near 0 already 1% below theta_lim), and the
        // curve is then not determined to these tolerances. Such triangles are skipped here.
        let lmax = LacSegment::lambda_max(alpha, base.theta_d());
        if base.lambda() > lmax * (1.0 - 1e-9) {
            return Ok(());
        }
        let aesthetic_curves::Polyline { points: pa, kappa: ka } = base.sample(17).unwrap();
        let moved = tri.map(|p| similar(p, angle, scale, (dx * scale, dy * scale), mirror));
        let aesthetic_curves::Polyline { points: pb, kappa: kb } = LacSegment::new(alpha, moved).unwrap().sample(17).unwrap();
        let size = scale * (1.0 + t);
        for i in 0..17 {
            let want = similar(pa[i], angle, scale, (dx * scale, dy * scale), mirror);
            prop_assert!((pb[i] - want).hypot() < 1e-9 * size, "{i}: {:?} vs {:?}", pb[i], want);
            let kw = if mirror { -ka[i] } else { ka[i] } / scale;
            // Curvature depends on Λ, which is ill-conditioned towards the edge of the
            // existence region: rounding of the moved triangle's angles (~1e-14) moves it by
            // more than that, so the bound is looser than for points.
            prop_assert!((kb[i] - kw).abs() < 1e-6 * kw.abs(), "{} vs {}", kb[i], kw);
        }
        // Reversal.
        let pr = LacSegment::new(alpha, [tri[2], tri[1], tri[0]]).unwrap().sample(17).unwrap().points;
        for i in 0..17 {
            prop_assert!((pr[i] - pa[16 - i]).hypot() < 1e-9 * (1.0 + t));
        }
    }

    #[test]
    fn inflection_segment_follows_similarities(turn in 0.3f64..2.6, split in 0.05f64..0.48,
                                               angle in -3.2f64..3.2, scale in 0.01f64..100.0,
                                               mirror in any::<bool>()) {
        let te = split * turn;
        let t = te.sin() / (turn - te).sin();
        let tri = [Point::ZERO, Point::new(1.0, 0.0), Point::new(1.0 + t * turn.cos(), t * turn.sin())];
        let base = LacInflectionSegment::new(tri).unwrap();
        let moved = tri.map(|p| similar(p, angle, scale, (3.0, -2.0), mirror));
        let other = LacInflectionSegment::new(moved).unwrap();
        prop_assert!((base.alpha() - other.alpha()).abs() < 1e-9 * base.alpha().abs().max(1.0));
        let pa = base.sample(9).unwrap().points;
        let pb = other.sample(9).unwrap().points;
        for i in 0..9 {
            let want = similar(pa[i], angle, scale, (3.0, -2.0), mirror);
            prop_assert!((pb[i] - want).hypot() < 1e-9 * scale * (1.0 + t));
        }
    }
}
