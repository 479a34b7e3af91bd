//! Pen or measured input to a G2 curve of log-aesthetic pieces: a measured Prius key line
//! (Graiff Zurita, Kajiwara & Miura 2023, MIT licence) at a tolerance of 0.3 mm, and the
//! pseudo-elastic spline through a few of its points.
//!
//! `cargo run --release -p aesthetic-curves --example prius_key_line`

use aesthetic_curves::pseudo_spline::{pseudo_elastic, Mode};
use aesthetic_curves::sketch::{fit_sketch, SketchOptions};
use aesthetic_curves::Point;

fn main() -> aesthetic_curves::Result<()> {
    let line = &aesthetic_curves_data::PRIUS[2];
    let pts: Vec<Point> = line.points_as::<Point>();
    let t0 = std::time::Instant::now();
    let sketch = fit_sketch(&pts, &SketchOptions::with_tolerance(0.3))?;
    println!(
        "{}: {} points -> {} pieces in {:.0} ms; max deviation {:.3} mm, G2 {} (jump {:.1e}), \
         every piece monotone {}",
        line.name,
        pts.len(),
        sketch.pieces.len(),
        t0.elapsed().as_secs_f64() * 1e3,
        sketch.max_deviation,
        sketch.g2,
        sketch.max_curvature_jump,
        sketch.all_monotone
    );
    for (i, piece) in sketch.pieces.iter().enumerate() {
        println!(
            "  piece {i}: {:14} alpha {:7.3}  curvature {:+.3e} -> {:+.3e} /mm",
            piece.kind.as_str(),
            piece.alpha,
            piece.end_curvatures.0,
            piece.end_curvatures.1
        );
    }
    // Every 60th point, through the pseudo-elastic spline.
    let few: Vec<Point> = pts.iter().step_by(60).copied().collect();
    let spline = pseudo_elastic(&few, false, Mode::Table)?;
    println!(
        "pseudo-elastic spline through {} of its points: length {:.3} mm, energy {:.3e}",
        few.len(),
        spline.length,
        spline.energy
    );
    Ok(())
}
