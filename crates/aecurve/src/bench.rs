//! `aecurve bench monotone`: S1's comparison of the exact test and the sampling test.
//!
//! One set of random curves per degree (the same set for every method, from
//! [`aesthetic_curves::samples::random_curves`]); curves the exact test calls degenerate are
//! left out of every method. Each method's time per curve is the median of several rounds,
//! each round running the test over the whole set repeatedly for a fixed minimum time.
//! A sampling verdict that differs from the exact one is a disagreement.

use aesthetic_curves::monotone::CurvatureMonotone;
use aesthetic_curves::samples::random_curves;
use aesthetic_curves::Bezier;
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;
use std::hint::black_box;
use std::time::{Duration, Instant};

/// One row of the comparison.
#[derive(Debug, Clone, Serialize)]
pub struct BenchRow {
    /// Curve degree.
    pub degree: usize,
    /// `"exact"` or `"sampling"`.
    pub method: &'static str,
    /// Divisions of the sampling test.
    pub samples: Option<usize>,
    /// Median time per curve, nanoseconds.
    pub ns_per_curve: f64,
    /// Curves whose verdict differs from the exact test's.
    pub disagreements: usize,
    /// Curves of the set that were tested (degenerate ones left out).
    pub curves: usize,
    /// Of which the exact test found monotone.
    pub monotone: usize,
}

/// Settings of a run.
#[derive(Debug, Clone)]
pub struct BenchConfig {
    /// Curves per degree.
    pub curves: usize,
    /// Seed of the curve set.
    pub seed: u64,
    /// Rounds per method (the median is reported).
    pub rounds: usize,
    /// Minimum time of one round.
    pub round_time: Duration,
    /// Degrees to compare.
    pub degrees: Vec<usize>,
    /// Sampling divisions to compare.
    pub samples: Vec<usize>,
}

impl Default for BenchConfig {
    fn default() -> Self {
        BenchConfig {
            curves: 2000,
            seed: 2024,
            rounds: 5,
            round_time: Duration::from_millis(60),
            degrees: vec![3, 4, 5],
            samples: vec![100, 200, 400],
        }
    }
}

fn time_per_curve(curves: &[Bezier], cfg: &BenchConfig, f: &dyn Fn(&Bezier) -> bool) -> f64 {
    let mut rounds: Vec<f64> = (0..cfg.rounds.max(1))
        .map(|_| {
            let start = Instant::now();
            let mut reps = 0usize;
            loop {
                let mut count = 0usize;
                for c in curves {
                    count += f(black_box(c)) as usize;
                }
                black_box(count);
                reps += 1;
                if start.elapsed() >= cfg.round_time {
                    break;
                }
            }
            start.elapsed().as_nanos() as f64 / (reps * curves.len().max(1)) as f64
        })
        .collect();
    rounds.sort_by(|a, b| a.total_cmp(b));
    rounds[rounds.len() / 2]
}

/// Run the comparison (progress bar on stderr when it is a terminal).
pub fn run(cfg: &BenchConfig) -> Vec<BenchRow> {
    let tasks = cfg.degrees.len() * (1 + cfg.samples.len());
    let pb = ProgressBar::new(tasks as u64);
    pb.set_style(
        ProgressStyle::with_template("{bar:30} {pos}/{len} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let mut rows = Vec::new();
    for &degree in &cfg.degrees {
        let all = random_curves(degree, cfg.curves, cfg.seed);
        let mut curves = Vec::new();
        let mut verdicts = Vec::new();
        for c in all {
            if let Ok(m) = c.is_curvature_monotone() {
                curves.push(c);
                verdicts.push(m);
            }
        }
        let monotone = verdicts.iter().filter(|v| **v).count();
        pb.set_message(format!("degree {degree}: exact"));
        let ns = time_per_curve(&curves, cfg, &|c| {
            c.is_curvature_monotone().unwrap_or(false)
        });
        rows.push(BenchRow {
            degree,
            method: "exact",
            samples: None,
            ns_per_curve: ns,
            disagreements: 0,
            curves: curves.len(),
            monotone,
        });
        pb.inc(1);
        for &n in &cfg.samples {
            pb.set_message(format!("degree {degree}: sampling {n}"));
            let disagreements = curves
                .iter()
                .zip(&verdicts)
                .filter(|(c, v)| {
                    c.curvature_monotone_sampled(n)
                        .map(|r| r.monotone)
                        .unwrap_or(false)
                        != **v
                })
                .count();
            let ns = time_per_curve(&curves, cfg, &|c| {
                c.curvature_monotone_sampled(n)
                    .map(|r| r.monotone)
                    .unwrap_or(false)
            });
            rows.push(BenchRow {
                degree,
                method: "sampling",
                samples: Some(n),
                ns_per_curve: ns,
                disagreements,
                curves: curves.len(),
                monotone,
            });
            pb.inc(1);
        }
    }
    pb.finish_and_clear();
    rows
}

/// The table for a person.
pub fn table(rows: &[BenchRow]) -> String {
    let mut s = String::from(
        "degree  method          time/curve   vs exact   disagreements  (curves, monotone)\n",
    );
    for r in rows {
        let exact = rows
            .iter()
            .find(|e| e.degree == r.degree && e.method == "exact")
            .map(|e| e.ns_per_curve)
            .unwrap_or(f64::NAN);
        let name = match r.samples {
            Some(n) => format!("sampling {n}"),
            None => "exact".to_string(),
        };
        s += &format!(
            "{:>6}  {:<14} {:>9.3} µs  {:>8.1}x  {:>13}  ({}, {})\n",
            r.degree,
            name,
            r.ns_per_curve / 1000.0,
            r.ns_per_curve / exact,
            r.disagreements,
            r.curves,
            r.monotone
        );
    }
    s
}

/// S1 Fig. 4-like chart: time per curve against degree, one line per method.
pub fn chart(rows: &[BenchRow]) -> String {
    let mut methods: Vec<Option<usize>> = Vec::new();
    for r in rows {
        if !methods.contains(&r.samples) {
            methods.push(r.samples);
        }
    }
    let series: Vec<crate::plot::Series> = methods
        .iter()
        .enumerate()
        .map(|(i, m)| crate::plot::Series {
            name: match m {
                Some(n) => format!("sampling, N = {n}"),
                None => "exact (Bernstein)".into(),
            },
            points: rows
                .iter()
                .filter(|r| r.samples == *m)
                .map(|r| (r.degree as f64, r.ns_per_curve / 1000.0))
                .collect(),
            color: crate::plot::PALETTE[i % crate::plot::PALETTE.len()],
            dashed: m.is_some(),
        })
        .collect();
    crate::plot::line_chart(
        "Curvature-monotonicity test: time per curve",
        "degree of the Bézier curve",
        "time per curve (µs, log scale)",
        &series,
        true,
    )
}
