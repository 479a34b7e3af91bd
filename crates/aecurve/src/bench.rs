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
use schemars::JsonSchema;
use serde::Serialize;
use std::hint::black_box;
use std::time::{Duration, Instant};

/// What `aecurve bench monotone --json` prints (`x-cli.bench` of the schema).
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct BenchMonotoneResult {
    /// One row per method and degree.
    pub results: Vec<BenchRow>,
}

/// One row of the comparison.
#[derive(Debug, Clone, Serialize, JsonSchema)]
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
    /// Of which the exact test's floating-point filter could not decide and big-integer
    /// arithmetic did (the same for every row of a degree).
    pub exact_fallbacks: usize,
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
            rounds: 7,
            round_time: Duration::from_millis(40),
            degrees: vec![3, 4, 5],
            samples: vec![100, 200, 400],
        }
    }
}

/// One timing round: the test over the whole set, repeated for at least `round_time`.
fn round_ns(curves: &[Bezier], round_time: Duration, f: &dyn Fn(&Bezier) -> bool) -> f64 {
    let start = Instant::now();
    let mut reps = 0usize;
    loop {
        let mut count = 0usize;
        for c in curves {
            count += f(black_box(c)) as usize;
        }
        black_box(count);
        reps += 1;
        if start.elapsed() >= round_time {
            break;
        }
    }
    start.elapsed().as_nanos() as f64 / (reps * curves.len().max(1)) as f64
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

/// Run the comparison (progress bar on stderr when it is a terminal). The methods of one
/// degree are timed interleaved, round after round, so that a slow spell of this shared
/// machine hits them alike; each reports the median of its rounds.
pub fn run(cfg: &BenchConfig) -> Vec<BenchRow> {
    let rounds = cfg.rounds.max(1);
    let tasks = cfg.degrees.len() * rounds;
    let pb = crate::progress::bar(tasks as u64, "", true);
    let mut rows = Vec::new();
    for &degree in &cfg.degrees {
        let all = random_curves(degree, cfg.curves, cfg.seed);
        let mut curves = Vec::new();
        let mut verdicts = Vec::new();
        let before = aesthetic_curves::monotone::exact_fallbacks();
        for c in all {
            if let Ok(m) = c.is_curvature_monotone() {
                curves.push(c);
                verdicts.push(m);
            }
        }
        let exact_fallbacks = (aesthetic_curves::monotone::exact_fallbacks() - before) as usize;
        let monotone = verdicts.iter().filter(|v| **v).count();
        // Method 0 is the exact test, then one per sampling count.
        let methods: Vec<Option<usize>> = std::iter::once(None)
            .chain(cfg.samples.iter().map(|&n| Some(n)))
            .collect();
        let test = |m: Option<usize>, c: &Bezier| match m {
            None => c.is_curvature_monotone().unwrap_or(false),
            Some(n) => c
                .curvature_monotone_sampled(n)
                .map(|r| r.monotone)
                .unwrap_or(false),
        };
        let mut times: Vec<Vec<f64>> = vec![Vec::new(); methods.len()];
        for r in 0..rounds {
            pb.set_message(format!("degree {degree}: round {}", r + 1));
            for (k, &m) in methods.iter().enumerate() {
                times[k].push(round_ns(&curves, cfg.round_time, &|c| test(m, c)));
            }
            pb.inc(1);
        }
        for (k, &m) in methods.iter().enumerate() {
            let disagreements = curves
                .iter()
                .zip(&verdicts)
                .filter(|(c, v)| test(m, c) != **v)
                .count();
            rows.push(BenchRow {
                degree,
                method: if m.is_some() { "sampling" } else { "exact" },
                samples: m,
                ns_per_curve: median(std::mem::take(&mut times[k])),
                disagreements,
                curves: curves.len(),
                monotone,
                exact_fallbacks,
            });
        }
    }
    pb.finish_and_clear();
    rows
}

/// The table for a person.
pub fn table(rows: &[BenchRow]) -> String {
    let mut s = String::from(
        "degree  method          time/curve   vs exact   disagreements  (curves, monotone, exact fallbacks)\n",
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
            "{:>6}  {:<14} {:>9.3} µs  {:>8.1}x  {:>13}  ({}, {}, {})\n",
            r.degree,
            name,
            r.ns_per_curve / 1000.0,
            r.ns_per_curve / exact,
            r.disagreements,
            r.curves,
            r.monotone,
            r.exact_fallbacks
        );
    }
    s
}

/// The conditions a run was measured under, for a person: the curve set, the rounds, the
/// build and the machine. Times mean little without them.
pub fn conditions(cfg: &BenchConfig) -> String {
    format!(
        "{} random curves per degree (seed {}), median of {} interleaved rounds of at least {} \
         ms;\n{} build, one thread of a {}-thread {} machine",
        cfg.curves,
        cfg.seed,
        cfg.rounds,
        cfg.round_time.as_millis(),
        if cfg!(debug_assertions) {
            "unoptimised (debug)"
        } else {
            "optimised"
        },
        std::thread::available_parallelism().map_or(1, |n| n.get()),
        std::env::consts::ARCH
    )
}

/// S1 Fig. 4-like chart: time per curve against degree, one line per method, with the
/// conditions of the run under the title.
pub fn chart(rows: &[BenchRow], conditions: &str) -> String {
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
            line: true,
            markers: true,
        })
        .collect();
    crate::plot::line_chart(
        &format!("Curvature-monotonicity test: time per curve\n{conditions}"),
        "degree of the Bézier curve",
        "time per curve (µs, log scale)",
        &series,
        true,
    )
}
