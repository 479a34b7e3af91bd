//! `aecurve`: the command-line tool of aesthetic-curves.

use aecurve::protocol::AnyBezier;
use aecurve::{batch, bench, parse_numbers, parse_points, plot};
use anyhow::{Context, Result};
use clap::Parser;
use std::time::Duration;

mod cli;
mod commands;
mod gallery;

use cli::{BenchCmd, Cli, Cmd, TargetArgs};
use commands::approx::approx;
use commands::demo::demo;
use commands::lac::lac;
use commands::lcg::{lcg, LcgSource};
use commands::monotone::monotone;
use commands::sketch::{sketch, sketch_contour};
use commands::spline::{lac_spline, spline};

fn main() {
    // A closed stdout (`aecurve ... | head`) ends the program quietly, as for other Unix
    // tools, instead of a panic message from println!.
    let default_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let p = info.payload();
        let msg = p
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| p.downcast_ref::<&str>().copied())
            .unwrap_or("");
        if msg.contains("Broken pipe") {
            std::process::exit(141);
        }
        // Any other failure to write the output (a full disk, /dev/full): a message and a
        // failure status, not a panic.
        if let Some(why) = msg.strip_prefix("failed printing to stdout: ") {
            eprintln!("error: cannot write the output: {why}");
            std::process::exit(1);
        }
        default_hook(info);
    }));
    if let Err(e) = run() {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}

/// Every file path a command will write (its `-o`, `--map`, `--curvature-plot`).
fn output_paths(cli: &Cli) -> Vec<&std::path::Path> {
    let mut paths: Vec<&std::path::Path> = Vec::new();
    if let Some(out) = curve_output(&cli.cmd) {
        paths.extend(out.paths());
    }
    match &cli.cmd {
        Cmd::Lcg { output, .. } => paths.extend(output.iter().map(|p| p.as_path())),
        Cmd::Approx { map, .. } => paths.extend(map.iter().map(|p| p.as_path())),
        Cmd::Bench {
            what: BenchCmd::Monotone { output, .. },
        } => paths.extend(output.iter().map(|p| p.as_path())),
        Cmd::Check { output, .. } => paths.extend(output.iter().map(|p| p.as_path())),
        _ => {}
    }
    paths
}

/// The curve outputs of a command that makes one curve.
fn curve_output(cmd: &Cmd) -> Option<&cli::CurveOutput> {
    match cmd {
        Cmd::Monotone { out, .. }
        | Cmd::Lac { out, .. }
        | Cmd::Approx { out, .. }
        | Cmd::Spline { out, .. }
        | Cmd::Sketch { out, .. } => Some(out),
        _ => None,
    }
}

/// `aecurve bench lac | approx | spline`: the table, or JSON.
fn bench_targets(group: aecurve::bench_targets::Group, args: &TargetArgs) {
    let rows =
        aecurve::bench_targets::run(group, args.rounds, Duration::from_millis(args.round_ms));
    if args.json {
        println!(
            "{}",
            serde_json::json!({ "group": group.name(), "results": rows })
        );
    } else {
        print!("{}", aecurve::bench_targets::table(&rows));
    }
}

fn run() -> Result<()> {
    let cli = Cli::parse();
    if let Some(out) = curve_output(&cli.cmd) {
        out.check()?;
    }
    match &cli.cmd {
        Cmd::Lcg { output, .. } => plot::check_picture_paths(output)?,
        Cmd::Approx { map, .. } => plot::check_picture_paths(map.as_slice())?,
        Cmd::Bench {
            what: BenchCmd::Monotone { output, .. },
        } => plot::check_picture_paths(output.as_slice())?,
        _ => {}
    }
    // Outputs go where the user says: create their folders.
    for path in output_paths(&cli) {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)
                .with_context(|| format!("creating the folder {}", dir.display()))?;
        }
    }
    match cli.cmd {
        Cmd::Batch {
            max_line_bytes,
            timeout_secs,
        } => {
            let stdin = std::io::stdin();
            let stdout = std::io::stdout();
            batch::run_with_timeout(
                stdin.lock(),
                stdout.lock(),
                max_line_bytes,
                std::time::Duration::from_secs(timeout_secs as u64),
            )?;
        }
        Cmd::Monotone {
            points,
            weights,
            method,
            samples,
            out,
        } => monotone(&points, weights.as_deref(), method, samples, &out)?,
        Cmd::Bench {
            what:
                BenchCmd::Monotone {
                    curves,
                    seed,
                    round_ms,
                    json,
                    output,
                },
        } => {
            let cfg = bench::BenchConfig {
                curves,
                seed,
                round_time: Duration::from_millis(round_ms),
                ..Default::default()
            };
            let rows = bench::run(&cfg);
            if json {
                println!("{}", serde_json::json!({ "results": rows }));
            } else {
                print!("{}", bench::table(&rows));
            }
            if let Some(path) = output {
                plot::write_picture(&path, &bench::chart(&rows, &bench::conditions(&cfg)))?;
                eprintln!("wrote {}", path.display());
            }
        }
        Cmd::Bench {
            what: BenchCmd::Lac(args),
        } => bench_targets(aecurve::bench_targets::Group::Lac, &args),
        Cmd::Bench {
            what: BenchCmd::Approx(args),
        } => bench_targets(aecurve::bench_targets::Group::Approx, &args),
        Cmd::Bench {
            what: BenchCmd::Spline(args),
        } => bench_targets(aecurve::bench_targets::Group::Spline, &args),
        Cmd::Demo { out, quick } => demo(&out, quick)?,
        Cmd::Fix {
            input,
            output,
            tolerance,
            grid,
            move_points,
            no_bumps,
            no_harmonize,
            json,
            report,
        } => commands::fix::fix(
            &input,
            &output,
            aecurve::fix::FixOptions {
                tolerance,
                grid: grid.unwrap_or(if is_svg(&input) { 1e-4 } else { 1.0 }),
                move_points,
                repairs: aesthetic_curves::harmonize::Repairs {
                    bumps: !no_bumps,
                    harmonize: !no_harmonize,
                    ..Default::default()
                },
            },
            (json, report.as_deref()),
        )?,
        Cmd::Check {
            file,
            select,
            json,
            top,
            output,
            pictures,
            suggest,
            thresholds,
        } => commands::check::check(
            &file,
            &select,
            (json, top),
            (output.as_deref(), pictures),
            aesthetic_curves::outline::OutlineOptions {
                suggest,
                ..thresholds.options()?
            },
        )?,
        Cmd::Editor {
            port,
            no_open,
            timeout,
        } => aecurve::editor::serve(
            port,
            !no_open,
            aecurve::editor::Limits {
                request_timeout: std::time::Duration::from_secs_f64(timeout),
                ..Default::default()
            },
        )?,
        Cmd::Lac {
            alpha,
            control,
            samples,
            out,
            ..
        } => lac(alpha, &control, samples, &out)?,
        Cmd::Spline {
            input,
            closed,
            kind,
            alpha,
            corners,
            mode,
            out,
        } => {
            if kind == "lac" {
                let opts = aesthetic_curves::lac_spline::LacSplineOptions {
                    alpha,
                    closed,
                    corners,
                    ..Default::default()
                };
                lac_spline(&input, &opts, &out)?
            } else {
                spline(&input, closed, &mode, &out)?
            }
        }
        Cmd::Sketch {
            input,
            tolerance,
            contour,
            out,
        } => {
            if contour {
                sketch_contour(&input, tolerance, &out)?
            } else {
                sketch(&input, tolerance, &out)?
            }
        }
        Cmd::Approx {
            alpha,
            control,
            tolerance,
            out,
            map,
            map_cells,
        } => approx(alpha, &control, tolerance, &out, map.as_deref(), map_cells)?,
        Cmd::Lcg {
            points,
            input,
            bezier,
            weights,
            control,
            alpha,
            json,
            output,
        } => {
            let source = match (points, input, bezier, control) {
                (Some(p), _, _, _) => LcgSource::Points(parse_points(&p).context("--points")?),
                (_, Some(f), _, _) => LcgSource::Points(aecurve::read_points_file(&f)?),
                (_, _, Some(b), _) => {
                    let w = weights
                        .as_deref()
                        .map(parse_numbers)
                        .transpose()
                        .context("--weights")?;
                    LcgSource::Bezier(AnyBezier::new(parse_points(&b).context("--bezier")?, w)?)
                }
                (_, _, _, Some(c)) => {
                    let pts = commands::control_triangle(&c)?;
                    let a = alpha.context("--alpha is needed with --control")?;
                    LcgSource::Lac(aesthetic_curves::lac::LacSegment::new(a, pts)?)
                }
                _ => anyhow::bail!("give --points, --input, --bezier or --alpha with --control"),
            };
            lcg(source, json, &output)?
        }
    }
    Ok(())
}

/// Whether a path names an SVG file (by its extension).
fn is_svg(p: &std::path::Path) -> bool {
    p.extension().is_some_and(|e| e.eq_ignore_ascii_case("svg"))
}
