//! `aecurve bench lac | approx | spline`: the hot paths against their targets.
//!
//! Each piece of work runs repeatedly for at least a round's time; the works of one group
//! are timed interleaved, round after round (a slow spell of this shared machine hits them
//! alike), and each reports the median of its rounds, per call (or per curve for the
//! monotone test, which runs over a set). The targets are the project's
//! (docs/performance.md); a row says whether its median meets it. libspiro is not linked
//! into `aecurve`: the spline's ratio to it is measured by `cargo bench -p spiro-oracle
//! --features libspiro --bench spiro_compare` (the targets below are a tenth of libspiro's
//! times on this machine class).

use aesthetic_curves::approx::{fit_inflection_cubic, fit_rational_cubic, ApproxOptions};
use aesthetic_curves::lac::{LacInflectionSegment, LacSegment};
use aesthetic_curves::monotone::CurvatureMonotone;
use aesthetic_curves::pseudo_spline::{pseudo_elastic, Mode};
use aesthetic_curves::samples::{random_rational_curves, wavy_points};
use aesthetic_curves::Point;
use schemars::JsonSchema;
use serde::Serialize;
use std::hint::black_box;
use std::time::{Duration, Instant};

/// The groups of work.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Group {
    /// The LAC segment solve and its polyline.
    Lac,
    /// The rational cubic fits and the rational monotone test.
    Approx,
    /// The pseudo-elastic spline in table mode.
    Spline,
}

impl Group {
    /// The group's name on the command line and in the JSON.
    pub fn name(self) -> &'static str {
        match self {
            Group::Lac => "lac",
            Group::Approx => "approx",
            Group::Spline => "spline",
        }
    }
}

/// What `aecurve bench lac | approx | spline --json` prints (`x-cli.bench` of the schema).
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct BenchTargetsResult {
    /// The group run.
    pub group: &'static str,
    /// One row per piece of work.
    pub results: Vec<TargetRow>,
}

/// One measured piece of work.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct TargetRow {
    /// The group.
    pub group: &'static str,
    /// What was timed.
    pub work: String,
    /// Median time per call (per curve for a set), nanoseconds.
    pub ns: f64,
    /// The target, nanoseconds, if the issue sets one.
    pub target_ns: Option<f64>,
    /// Whether the median is within the target.
    pub meets_target: Option<bool>,
}

/// A piece of work: its name, target, the calls one run makes, and the run.
struct Work {
    name: String,
    target_ns: Option<f64>,
    per_run: usize,
    run: Box<dyn Fn() -> usize>,
}

/// The triangle with turning `td` and base angle `phi` at the start: (0,0), (1,0), end.
fn triangle(td: f64, phi: f64) -> [Point; 3] {
    let d = phi.sin() / (td - phi).sin();
    [
        Point::new(0.0, 0.0),
        Point::new(1.0, 0.0),
        Point::new(1.0 + d * td.cos(), d * td.sin()),
    ]
}

fn works(group: Group) -> Vec<Work> {
    let typical = [
        Point::new(0.0, 0.0),
        Point::new(10.0, 0.0),
        Point::new(16.0, 9.0),
    ];
    let mut out: Vec<Work> = Vec::new();
    match group {
        Group::Lac => {
            for alpha in [-1.0, 0.5, 1.0, 2.0] {
                out.push(Work {
                    name: format!("LacSegment::new, alpha {alpha}"),
                    target_ns: Some(3_000.0),
                    per_run: 1,
                    run: Box::new(move || {
                        LacSegment::new(black_box(alpha), typical).is_ok() as usize
                    }),
                });
            }
            for alpha in [-1.0, 2.0] {
                let td = std::f64::consts::FRAC_PI_2;
                let phi = LacSegment::theta_lim(alpha, td).map_or(1.0, |l| l - 1e-3);
                let tri = triangle(td, phi);
                out.push(Work {
                    name: format!("LacSegment::new 1e-3 rad below theta_lim, alpha {alpha}"),
                    target_ns: Some(10_000.0),
                    per_run: 1,
                    run: Box::new(move || LacSegment::new(black_box(alpha), tri).is_ok() as usize),
                });
            }
            for alpha in [-1.0, 2.0] {
                if let Ok(seg) = LacSegment::new(alpha, typical) {
                    out.push(Work {
                        name: format!("LAC polyline, 1000 samples with curvature, alpha {alpha}"),
                        target_ns: Some(20_000.0),
                        per_run: 1,
                        run: Box::new(move || black_box(&seg).sample(1000).is_ok() as usize),
                    });
                }
            }
        }
        Group::Approx => {
            for alpha in [-1.0, 0.0, 1.0, 2.0] {
                if let Ok(seg) = LacSegment::new(alpha, typical) {
                    out.push(Work {
                        name: format!("fit_rational_cubic, alpha {alpha}"),
                        target_ns: Some(100_000.0),
                        per_run: 1,
                        run: Box::new(move || {
                            fit_rational_cubic(black_box(&seg), &ApproxOptions::default()).is_ok()
                                as usize
                        }),
                    });
                }
            }
            // Random shapes as in the library's sweep test.
            let segs = aesthetic_curves::samples::random_lac_segments(200, 17);
            let segs = std::rc::Rc::new(segs);
            for (table, target) in [(true, Some(100_000.0)), (false, None)] {
                let segs = segs.clone();
                let opts = ApproxOptions {
                    table,
                    ..ApproxOptions::default()
                };
                out.push(Work {
                    name: format!(
                        "fit_rational_cubic, 200 random segments (per segment){}",
                        if table { "" } else { ", grid search only" }
                    ),
                    target_ns: target,
                    per_run: segs.len(),
                    run: Box::new(move || {
                        segs.iter()
                            .filter(|s| fit_rational_cubic(black_box(s), &opts).is_ok())
                            .count()
                    }),
                });
            }
            let curves = random_rational_curves(3, 256, 42);
            out.push(Work {
                name: "exact monotone verdict, random rational cubic (per curve)".into(),
                target_ns: Some(1_000.0),
                per_run: curves.len(),
                run: Box::new(move || {
                    curves
                        .iter()
                        .filter(|c| black_box(c).is_curvature_monotone().unwrap_or(false))
                        .count()
                }),
            });
            if let Ok(seg) = LacInflectionSegment::new([
                Point::new(0.0, 0.0),
                Point::new(6.0, 0.0),
                Point::new(9.0, 5.0),
            ]) {
                out.push(Work {
                    name: "fit_inflection_cubic (inflection-end segment)".into(),
                    target_ns: None,
                    per_run: 1,
                    run: Box::new(move || {
                        fit_inflection_cubic(black_box(&seg), &ApproxOptions::default()).is_ok()
                            as usize
                    }),
                });
            }
        }
        Group::Spline => {
            let circle = |n: usize| -> Vec<Point> {
                (0..n)
                    .map(|i| {
                        let a = std::f64::consts::TAU * i as f64 / n as f64;
                        Point::new(a.cos(), a.sin())
                    })
                    .collect()
            };
            let sets: [(&str, Vec<Point>, bool, f64); 4] = [
                ("15 wavy points", wavy_points(15, 7), false, 2_500.0),
                ("1000 wavy points", wavy_points(1000, 7), false, 125_000.0),
                (
                    "1000 points on a circle, closed",
                    circle(1000),
                    true,
                    165_000.0,
                ),
                (
                    "100,000 wavy points",
                    wavy_points(100_000, 7),
                    false,
                    41_000_000.0,
                ),
            ];
            for (name, pts, closed, target) in sets {
                out.push(Work {
                    name: format!("pseudo_elastic (table mode), {name}"),
                    target_ns: Some(target),
                    per_run: 1,
                    run: Box::new(move || {
                        pseudo_elastic(black_box(&pts), closed, Mode::Table).is_ok() as usize
                    }),
                });
            }
        }
    }
    out
}

/// One round of `work`: runs for at least `round_time`; nanoseconds per call.
fn round_ns(work: &Work, round_time: Duration) -> f64 {
    let start = Instant::now();
    let mut runs = 0usize;
    loop {
        black_box((work.run)());
        runs += 1;
        if start.elapsed() >= round_time {
            break;
        }
    }
    start.elapsed().as_nanos() as f64 / (runs * work.per_run.max(1)) as f64
}

/// Time a group: `rounds` interleaved rounds of at least `round_time` each (progress bar
/// on stderr when it is a terminal); the median per work.
pub fn run(group: Group, rounds: usize, round_time: Duration) -> Vec<TargetRow> {
    let works = works(group);
    let rounds = rounds.max(1);
    let pb = crate::progress::bar(rounds as u64, "", true);
    // One call each first: lazily built tables (the spline's) are not timed.
    for w in &works {
        black_box((w.run)());
    }
    let mut times: Vec<Vec<f64>> = vec![Vec::new(); works.len()];
    for r in 0..rounds {
        pb.set_message(format!("{}: round {}", group.name(), r + 1));
        for (k, w) in works.iter().enumerate() {
            times[k].push(round_ns(w, round_time));
        }
        pb.inc(1);
    }
    pb.finish_and_clear();
    works
        .iter()
        .zip(times)
        .map(|(w, mut t)| {
            t.sort_by(|a, b| a.total_cmp(b));
            let ns = t[t.len() / 2];
            TargetRow {
                group: group.name(),
                work: w.name.clone(),
                ns,
                target_ns: w.target_ns,
                meets_target: w.target_ns.map(|t| ns <= t),
            }
        })
        .collect()
}

/// A time for a person: ns, µs or ms.
fn human(ns: f64) -> String {
    if ns < 1e3 {
        format!("{ns:.0} ns")
    } else if ns < 1e6 {
        format!("{:.2} µs", ns / 1e3)
    } else {
        format!("{:.2} ms", ns / 1e6)
    }
}

/// The table for a person: work, median, target, and the median as a multiple of it.
pub fn table(rows: &[TargetRow]) -> String {
    let width = rows
        .iter()
        .map(|r| r.work.chars().count())
        .max()
        .unwrap_or(4);
    let mut s = format!(
        "{:<width$}  {:>10}  {:>10}  {:>8}\n",
        "work", "median", "target", "x target"
    );
    for r in rows {
        let (target, ratio) = match r.target_ns {
            Some(t) => (human(t), format!("{:.2}", r.ns / t)),
            None => ("-".into(), "-".into()),
        };
        s += &format!(
            "{:<width$}  {:>10}  {:>10}  {:>8}\n",
            r.work,
            human(r.ns),
            target,
            ratio
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_group_measures_real_work() {
        for g in [Group::Lac, Group::Approx, Group::Spline] {
            // Each work succeeds on its input (a failing call would be timed as nothing).
            for w in works(g) {
                assert!((w.run)() > 0 || w.per_run > 1, "{}: {}", g.name(), w.name);
            }
        }
        let rows = run(Group::Lac, 1, Duration::from_millis(1));
        assert!(rows.len() >= 6);
        assert!(rows.iter().all(|r| r.ns > 0.0 && r.ns.is_finite()));
        assert!(table(&rows).lines().count() == rows.len() + 1);
    }
}
