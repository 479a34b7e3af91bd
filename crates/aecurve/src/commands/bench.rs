//! `aecurve bench`: the exact test against the sampling test, and the library's hot paths
//! against their targets.

use crate::cli::{count, millis};
use crate::commands::Command;
use aecurve::{bench, plot};
use anyhow::Result;
use clap::Subcommand;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// The arguments of `aecurve bench` (the command's help is its entry in `cli.rs`).
#[derive(clap::Args)]
pub(crate) struct Args {
    #[command(subcommand)]
    what: BenchCmd,
}

#[derive(Subcommand)]
pub(crate) enum BenchCmd {
    /// Exact test against the sampling test (S1's comparison), degrees 3, 4, 5.
    Monotone {
        /// Random curves per degree (1 to 1,000,000).
        #[arg(long, default_value_t = 2000, value_parser = count::<1, 1_000_000>)]
        curves: usize,
        /// Seed of the random curve set.
        #[arg(long, default_value_t = 2024)]
        seed: u64,
        /// Minimum milliseconds per timing round (7 interleaved rounds, median reported; 1 to
        /// 60,000).
        #[arg(long, default_value_t = 40, value_parser = millis)]
        round_ms: u64,
        /// Print JSON instead of the table.
        #[arg(long)]
        json: bool,
        /// Write the chart (.svg or .png).
        #[arg(short, long)]
        output: Option<PathBuf>,
    },
    /// The LAC segment solve (typical and near theta_lim) and the 1000-sample polyline,
    /// against their targets.
    Lac(TargetArgs),
    /// The rational cubic fits and the rational monotone test, against their targets.
    Approx(TargetArgs),
    /// The pseudo-elastic spline in table mode on the spline race's point sets, against a tenth of
    /// libspiro's times (the ratio itself: `cargo bench -p spiro-oracle --features libspiro
    /// --bench spiro_compare`, with libspiro installed).
    Spline(TargetArgs),
}

#[derive(clap::Args)]
pub(crate) struct TargetArgs {
    /// Timing rounds (interleaved; the median is reported; 1 to 101).
    #[arg(long, default_value_t = 7, value_parser = count::<1, 101>)]
    pub(crate) rounds: usize,
    /// Minimum milliseconds per round and work (1 to 60,000).
    #[arg(long, default_value_t = 40, value_parser = millis)]
    pub(crate) round_ms: u64,
    /// Print JSON instead of the table.
    #[arg(long)]
    pub(crate) json: bool,
}

impl Command for Args {
    fn pictures(&self) -> &[PathBuf] {
        match &self.what {
            BenchCmd::Monotone { output, .. } => output.as_slice(),
            _ => &[],
        }
    }

    fn run(self) -> Result<()> {
        use aecurve::bench_targets::Group;
        match self.what {
            BenchCmd::Monotone {
                curves,
                seed,
                round_ms,
                json,
                output,
            } => monotone(curves, seed, round_ms, json, output.as_deref())?,
            BenchCmd::Lac(args) => targets(Group::Lac, &args),
            BenchCmd::Approx(args) => targets(Group::Approx, &args),
            BenchCmd::Spline(args) => targets(Group::Spline, &args),
        }
        Ok(())
    }
}

/// `aecurve bench monotone`: the table or JSON, and the chart with -o.
fn monotone(
    curves: usize,
    seed: u64,
    round_ms: u64,
    json: bool,
    output: Option<&Path>,
) -> Result<()> {
    let cfg = bench::BenchConfig {
        curves,
        seed,
        round_time: Duration::from_millis(round_ms),
        ..Default::default()
    };
    let rows = bench::run(&cfg);
    if let Some(path) = output {
        plot::write_picture(path, &bench::chart(&rows, &bench::conditions(&cfg)))?;
        eprintln!("wrote {}", path.display());
    }
    if json {
        let out = bench::BenchMonotoneResult { results: rows };
        println!("{}", serde_json::to_string(&out)?);
    } else {
        print!("{}", bench::table(&rows));
    }
    Ok(())
}

/// `aecurve bench lac | approx | spline`: the table, or JSON.
fn targets(group: aecurve::bench_targets::Group, args: &TargetArgs) {
    let rows =
        aecurve::bench_targets::run(group, args.rounds, Duration::from_millis(args.round_ms));
    if args.json {
        let out = aecurve::bench_targets::BenchTargetsResult {
            group: group.name(),
            results: rows,
        };
        println!(
            "{}",
            serde_json::to_string(&out).expect("plain numbers and names")
        );
    } else {
        print!("{}", aecurve::bench_targets::table(&rows));
    }
}
