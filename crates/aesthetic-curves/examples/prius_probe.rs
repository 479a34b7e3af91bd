//! Where a B-spline fit of a Prius line deviates most (a development aid).
use aesthetic_curves::bspline::{chord_parameters, fit_segments};
use aesthetic_curves::Point;

fn main() {
    let path = std::env::args().nth(1).unwrap();
    let text = std::fs::read_to_string(path).unwrap();
    let pts: Vec<Point> = text
        .lines()
        .skip(1)
        .filter_map(|l| {
            let v: Vec<f64> = l.split(',').filter_map(|x| x.trim().parse().ok()).collect();
            (v.len() == 2).then(|| Point::new(v[0], v[1]))
        })
        .collect();
    let params = chord_parameters(&pts).unwrap();
    for segs in [5, 10, 20, 40] {
        let s = fit_segments(&pts, &params, segs).unwrap();
        let mut worst = (0.0, 0);
        for (i, (q, u)) in pts.iter().zip(&params).enumerate() {
            let d = (s.eval(*u) - *q).hypot();
            if d > worst.0 {
                worst = (d, i);
            }
        }
        println!(
            "{segs} segments: worst (param distance) {:.4} at point {} of {}",
            worst.0,
            worst.1,
            pts.len()
        );
    }
}
