//! Check the curvature of a few Bézier curves exactly, and compare with sampling.
//!
//! `cargo run -p aesthetic-curves --example check_monotone`

use aesthetic_curves::{Bezier, CurvatureMonotone, Point, RationalBezier};

fn main() -> aesthetic_curves::Result<()> {
    let p = Point::new;
    let curves = [
        (
            "symmetric arch",
            vec![p(0.0, 0.0), p(1.0, 1.0), p(2.0, 1.0), p(3.0, 0.0)],
        ),
        // Edges scaled by 0.8 and turned by 20 degrees each: a spiral ("class A") polygon.
        (
            "spiral cubic",
            vec![p(0.0, 0.0), p(3.0, 0.0), p(5.255, 0.821), p(6.726, 2.055)],
        ),
        (
            "quartic",
            vec![
                p(0.0, 0.0),
                p(1.0, 0.0),
                p(2.0, 0.5),
                p(2.5, 1.5),
                p(2.6, 3.0),
            ],
        ),
    ];
    for (name, pts) in curves {
        let curve = Bezier::new(pts)?;
        let exact = curve.curvature_monotone()?;
        let sampled = curve.curvature_monotone_sampled(100)?;
        println!(
            "{name:18} degree {}: exact {} (test polynomial of degree {}, extrema at t = {:?}); \
             sampling with 100 divisions says {}",
            curve.degree(),
            if exact.monotone {
                "monotone"
            } else {
                "NOT monotone"
            },
            exact.test_degree,
            exact.extrema,
            if sampled.monotone {
                "monotone"
            } else {
                "not monotone"
            },
        );
    }
    // A quarter circle as a rational quadratic: constant curvature counts as monotone.
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let arc = RationalBezier::new(
        vec![p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)],
        vec![1.0, w, 1.0],
    )?;
    let r = arc.curvature_monotone()?;
    println!(
        "quarter circle: monotone = {}, trend = {:?}",
        r.monotone, r.trend
    );
    // Coincident control points: no curvature there, an error rather than a verdict.
    let bad = Bezier::new(vec![p(0.0, 0.0), p(0.0, 0.0), p(0.0, 0.0), p(1.0, 1.0)])?;
    match bad.curvature_monotone() {
        Ok(r) => println!("degenerate cubic: {r:?}"),
        Err(e) => println!("degenerate cubic: {} error: {e}", e.kind()),
    }
    Ok(())
}
