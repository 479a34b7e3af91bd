use aesthetic_curves::sketch::{fit_sketch, SketchOptions};
use aesthetic_curves::Point;
fn main() {
    let i: usize = std::env::args().nth(1).unwrap().parse().unwrap();
    let n: usize = std::env::args().nth(2).unwrap().parse().unwrap();
    let pts: Vec<Point> = aesthetic_curves_data::PRIUS[i - 1].points().into_iter().map(|[x, y]| Point::new(x, y)).collect();
    let t = std::time::Instant::now();
    for _ in 0..n { let sk = fit_sketch(&pts, &SketchOptions::with_tolerance(0.3)).unwrap(); std::hint::black_box(sk); }
    println!("{:?} per fit", t.elapsed() / n as u32);
}
