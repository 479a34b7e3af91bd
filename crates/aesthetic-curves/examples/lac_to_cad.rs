//! A log-aesthetic segment from three control points, its rational cubic (G2 ends,
//! curvature proven monotone) and the NURBS a CAD system imports.
//!
//! `cargo run -p aesthetic-curves --example lac_to_cad`

use aesthetic_curves::approx::{fit_rational_cubic, ApproxOptions};
use aesthetic_curves::{CurvatureMonotone, LacSegment, Nurbs, Point};

fn main() -> aesthetic_curves::Result<()> {
    let p = Point::new;
    let control = [p(0.0, 0.0), p(10.0, 0.0), p(16.0, 9.0)];
    for alpha in [-1.0, 0.0, 1.0, 2.0] {
        let seg = LacSegment::new(alpha, control)?;
        let (k0, k1) = seg.end_curvatures()?;
        let fit = fit_rational_cubic(&seg, &ApproxOptions::default())?;
        println!(
            "alpha {alpha:4}: Lambda {:.6}, length {:.6}, curvature {k0:.6} -> {k1:.6}",
            seg.lambda(),
            seg.arc_length()?
        );
        println!(
            "  rational cubic f0 {:.4} f1 {:.4}: max error {:.2e} of the length, monotone {}",
            fit.f0,
            fit.f1,
            fit.max_error,
            fit.curve.curvature_monotone()?.monotone
        );
        let nurbs = Nurbs::from_bezier(&fit.curve);
        println!(
            "  NURBS: degree {}, knots {:?}, weights {:?}",
            nurbs.degree, nurbs.knots, nurbs.weights
        );
    }
    // Outside the existence region there is no segment, and the message says the range.
    match LacSegment::new(-1.0, [p(0.0, 0.0), p(10.0, 0.0), p(11.0, 1.0)]) {
        Ok(_) => println!("unexpected segment"),
        Err(e) => println!("{}: {e}", e.kind()),
    }
    Ok(())
}
