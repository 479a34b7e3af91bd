//! Criterion benchmark of the repair `aecurve fix` runs per contour: the basic
//! Latin letters of DejaVu Sans (the shipped TrueType font; its quadratics raised to cubics
//! exactly, then put on the 1-unit grid as a font editor converting to CFF does), every
//! contour repaired with the defaults (bumps, then the smooth joins harmonized: sweep,
//! joint stage, grid), tolerance 2 units, grid 1; and one glyph at a time, as a designer
//! fixes the glyph being drawn (target: under 50 ms).

use aecurve::outline_io::read_font;
use aesthetic_curves::harmonize::{repair, tangent_angle, HarmonizeOptions, Repairs};
use aesthetic_curves::Point;
use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;

const FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

/// A contour's segments as cubics and lines on the grid, with its joins' smooth flags (G1
/// within 0.05°, as the reader of a UFO would mark them).
type Job = (Vec<Vec<Point>>, bool, Vec<bool>);

/// The jobs of the basic Latin letters, each with its glyph's name.
fn jobs() -> Vec<(String, Job)> {
    let outlines = read_font(FONT).unwrap();
    let letters = |n: &str| n.len() == 1 && n.chars().all(|c| c.is_ascii_alphabetic());
    let round = |p: Point| Point::new(p.x.round(), p.y.round());
    let mut out = Vec::new();
    for shape in outlines.shapes.iter().filter(|s| letters(&s.name)) {
        for c in &shape.contours {
            let segs: Vec<Vec<Point>> = (c.segments.iter())
                .map(|s| {
                    let p = s.points();
                    match p.len() {
                        3 => vec![
                            p[0],
                            round(p[0] + (p[1] - p[0]) * (2.0 / 3.0)),
                            round(p[2] + (p[1] - p[2]) * (2.0 / 3.0)),
                            p[2],
                        ],
                        _ => p.to_vec(),
                    }
                })
                .collect();
            let n = segs.len();
            let joins = if c.closed { n } else { n.saturating_sub(1) };
            let smooth = (0..joins)
                .map(|j| {
                    let (a, b) = (&segs[j], &segs[(j + 1) % n]);
                    let (ta, tb) = (a[a.len() - 1] - a[a.len() - 2], b[1] - b[0]);
                    tangent_angle(ta, tb) < 0.05f64.to_radians()
                })
                .collect();
            out.push((shape.name.clone(), (segs, c.closed, smooth)));
        }
    }
    out
}

/// Every job repaired; how many were.
fn repair_all<'a>(jobs: impl Iterator<Item = &'a Job>) -> usize {
    let opts = HarmonizeOptions {
        tolerance: 2.0,
        grid: 1.0,
        ..Default::default()
    };
    let what = Repairs::default();
    jobs.filter_map(|(s, closed, smooth)| repair(black_box(s), *closed, smooth, &opts, &what).ok())
        .count()
}

fn bench_fix(c: &mut Criterion) {
    let jobs = jobs();
    let mut g = c.benchmark_group("fix/dejavu_sans_letters");
    g.sample_size(10);
    g.bench_function(format!("repair_{}_contours", jobs.len()), |b| {
        b.iter(|| repair_all(jobs.iter().map(|(_, j)| j)))
    });
    // Glyphs of one contour (S), two (a, g) and three (B).
    for name in ["S", "a", "g", "B"] {
        let glyph: Vec<&Job> = (jobs.iter())
            .filter(|(n, _)| n == name)
            .map(|(_, j)| j)
            .collect();
        g.bench_function(format!("repair_glyph_{name}"), |b| {
            b.iter(|| repair_all(glyph.iter().copied()))
        });
    }
    g.finish();
}

criterion_group!(benches, bench_fix);
criterion_main!(benches);
