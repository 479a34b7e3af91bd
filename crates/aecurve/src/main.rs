//! `aecurve`: the command-line tool of aesthetic-curves.

use aecurve::protocol::AnyBezier;
use aecurve::{batch, bench, parse_numbers, parse_points, plot};
use anyhow::{Context, Result};
use clap::{Parser, Subcommand, ValueEnum};
use std::io::Write;
use std::path::PathBuf;
use std::time::Duration;

#[derive(Parser)]
#[command(
    name = "aecurve",
    version,
    about = "Aesthetic curves: checks, batch protocol, benchmarks, plots",
    after_help = "Papers cited as S0-S4 and the sections cited as docs/math.md §N are in the \
                  repository's docs/ folder (bibliography.md, math.md); the JSON protocol is \
                  docs/protocol.md."
)]
struct Cli {
    #[command(subcommand)]
    cmd: Cmd,
    /// Also write the curve's curvature against arc length (.svg or .png), for the commands
    /// that produce a curve (monotone, lac, spline, sketch).
    #[arg(long, global = true)]
    curvature_plot: Option<PathBuf>,
}

/// Where `--curvature-plot` writes, if given.
static CURVATURE_PLOT: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();

/// `--curvature-plot`: curvature against arc length (chord sums of the samples) of a curve.
fn write_curvature_plot(samples: &[plot::CombSample], title: &str) -> Result<()> {
    let Some(path) = CURVATURE_PLOT.get() else {
        return Ok(());
    };
    let mut s = 0.0;
    let mut pts = Vec::with_capacity(samples.len());
    for (i, (p, _, k)) in samples.iter().enumerate() {
        if i > 0 {
            s += (*p - samples[i - 1].0).hypot();
        }
        if k.is_finite() {
            pts.push((s, *k));
        }
    }
    let mut series = plot::Series::new("curvature", pts, plot::PALETTE[0]);
    series.markers = false;
    plot::write_picture(
        path,
        &plot::fitted_chart(
            title,
            "arc length (input units)",
            "curvature (1 / input unit)",
            &[series],
        ),
    )?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

#[derive(Subcommand)]
enum Cmd {
    /// JSON Lines requests on stdin, one response line per request on stdout.
    Batch {
        /// Largest accepted request line in bytes (1 to 1 GiB).
        #[arg(long, default_value_t = batch::DEFAULT_MAX_LINE, value_parser = count::<1, 1_073_741_824>)]
        max_line_bytes: usize,
    },
    /// Is the curvature of one Bézier curve monotone?
    Monotone {
        /// Control points: "x,y x,y ..." (2 to 21 points).
        #[arg(long, allow_hyphen_values = true)]
        points: String,
        /// Weights (rational curve): "w w w ...", one per point.
        #[arg(long)]
        weights: Option<String>,
        /// Which test.
        #[arg(long, value_enum, default_value_t = Method::Exact)]
        method: Method,
        /// Divisions of the sampling test (1 to 10,000,000).
        #[arg(long, default_value_t = 100, value_parser = count::<1, 10_000_000>)]
        samples: usize,
        /// Print the protocol's JSON result instead of text.
        #[arg(long)]
        json: bool,
        /// Write the curve: .svg (the curve as cubic Béziers within 1e-6 of its size, in its
        /// own coordinates, with its comb), .png (picture with the comb), .dxf/.step/.iges/
        /// .json exact; repeatable.
        #[arg(short, long)]
        output: Vec<PathBuf>,
    },
    /// A log-aesthetic segment in a control triangle: summary, and the curve with its
    /// curvature comb (SVG) with -o.
    Lac {
        /// Shape parameter alpha (not with --inflection, where the triangle fixes it).
        #[arg(
            long,
            allow_hyphen_values = true,
            required_unless_present = "inflection"
        )]
        alpha: Option<f64>,
        /// A segment with an inflection point at the first control point (docs/math.md §3.2):
        /// alpha < 0 comes from the triangle.
        #[arg(long, conflicts_with = "alpha")]
        inflection: bool,
        /// Control triangle: "x,y x,y x,y" (start, tangent intersection, end).
        #[arg(long, allow_hyphen_values = true)]
        control: String,
        /// Samples along the curve (2 to 1,000,000).
        #[arg(long, default_value_t = 65, value_parser = count::<2, 1_000_000>)]
        samples: usize,
        /// Print the protocol's JSON result.
        #[arg(long)]
        json: bool,
        /// Write the segment: .png (picture with its comb); .svg (as cubic Béziers, with its
        /// comb), .dxf/.step/.iges/.json as rational cubics within 1e-7 of its size (G2,
        /// distance reported; also for an inflection end); repeatable.
        #[arg(short, long)]
        output: Vec<PathBuf>,
    },
    /// The logarithmic curvature graph and alpha: of a point sequence (--points or
    /// --input), of a LAC segment (--alpha and --control) or of a Bézier curve (--bezier).
    Lcg {
        /// Ordered points "x,y x,y ..." (at least 8).
        #[arg(long, allow_hyphen_values = true, group = "source")]
        points: Option<String>,
        /// File of ordered points: CSV / whitespace rows "x,y", or a JSON array of pairs.
        #[arg(long, group = "source")]
        input: Option<PathBuf>,
        /// Control points of a Bézier curve "x,y x,y ...".
        #[arg(long, allow_hyphen_values = true, group = "source")]
        bezier: Option<String>,
        /// Weights of the Bézier curve (rational).
        #[arg(long, requires = "bezier")]
        weights: Option<String>,
        /// Control triangle of a LAC segment (with --alpha).
        #[arg(long, allow_hyphen_values = true, group = "source", requires = "alpha")]
        control: Option<String>,
        /// Alpha of the LAC segment.
        #[arg(long, allow_hyphen_values = true, requires = "control")]
        alpha: Option<f64>,
        /// Print the protocol's JSON result.
        #[arg(long)]
        json: bool,
        /// Write the graph with its fitted line (.svg or .png; repeatable).
        #[arg(short, long)]
        output: Vec<PathBuf>,
    },
    /// One rational cubic (or, with --tolerance, a rational cubic B-spline) for a LAC
    /// segment: G2 ends, curvature proven monotone, globally optimal in its family.
    Approx {
        /// Shape parameter alpha.
        #[arg(long, allow_hyphen_values = true)]
        alpha: f64,
        /// Control triangle: "x,y x,y x,y".
        #[arg(long, allow_hyphen_values = true)]
        control: String,
        /// Largest distance to the LAC (input units): as many G2-joined pieces as needed.
        #[arg(long, allow_hyphen_values = true, value_parser = positive)]
        tolerance: Option<f64>,
        /// Print the protocol's JSON result.
        #[arg(long)]
        json: bool,
        /// Write the curve (repeatable; by extension): .dxf, .step/.stp, .iges/.igs, .json
        /// (exact rational geometry), .svg (cubic Béziers within 1e-6 of the size, with the
        /// curvature comb), .png (picture).
        #[arg(short, long)]
        output: Vec<PathBuf>,
        /// Write the error map over (f0, f1) with the monotone region (S3 Fig. 3 and 5).
        #[arg(long)]
        map: Option<PathBuf>,
        /// Cells per axis of the error map (2 to 2,000).
        #[arg(long, default_value_t = 100, value_parser = count::<2, 2000>)]
        map_cells: usize,
    },
    /// The pseudo-elastic spline (S2) through points from a file (CSV rows "x,y" or a JSON
    /// array of pairs): tangents, length, area, energy; -o writes the curve with its comb.
    Spline {
        /// The points file.
        input: PathBuf,
        /// Closed curve through all points.
        #[arg(long)]
        closed: bool,
        /// Segment values from the shipped tables (fast) or by direct minimisation.
        #[arg(long, default_value = "table", value_parser = ["table", "exact"])]
        mode: String,
        /// Print the protocol's JSON result.
        #[arg(long)]
        json: bool,
        /// Write the curve: .svg (its cubics with the comb), .png (with the points), .dxf,
        /// .step, .iges, .json (exact); repeatable.
        #[arg(short, long)]
        output: Vec<PathBuf>,
    },
    /// Pen input to a G2 aesthetic curve (S4 §3): B-spline, pieces at inflections and
    /// curvature maxima, one LAC segment per piece, G2 fairing, one rational cubic per
    /// piece. Points from a file: CSV rows "x,y", a JSON array of pairs, or an SVG path
    /// (path data, or an SVG document whose first path is read).
    Sketch {
        /// The points file.
        input: PathBuf,
        /// Largest distance from an input point to the result (default 0.5% of the bounding
        /// box diagonal).
        #[arg(long, allow_hyphen_values = true, value_parser = positive)]
        tolerance: Option<f64>,
        /// Print the protocol's JSON result.
        #[arg(long)]
        json: bool,
        /// Write the curve: .svg (cubic Béziers within 1e-6 of its size, with its comb), .png
        /// (input, result, joints and comb), .dxf, .step, .iges, .json (exact rational
        /// geometry); repeatable.
        #[arg(short, long)]
        output: Vec<PathBuf>,
    },
    /// Benchmarks.
    Bench {
        #[command(subcommand)]
        what: BenchCmd,
    },
    /// Write the gallery of examples (HTML + SVG) to a folder.
    Demo {
        /// Output folder.
        #[arg(long, default_value = "demo-out")]
        out: PathBuf,
        /// Smaller benchmark (for CI smoke runs).
        #[arg(long)]
        quick: bool,
    },
    /// The interactive editor in the browser: a local server on 127.0.0.1 only (LAC
    /// segments, inflection segments, pseudo-elastic splines, sketches, Bézier curves).
    Editor {
        /// Port (0: any free port); the URL is printed.
        #[arg(long, default_value_t = 8731)]
        port: u16,
        /// Do not open the page in the system's browser.
        #[arg(long)]
        no_open: bool,
        /// Wall-clock limit of one request, in seconds (0.1 to 600); a request past it gets
        /// a `timeout` error.
        #[arg(long, default_value_t = 5.0, value_parser = parse_timeout)]
        timeout: f64,
    },
}

/// A count within `LO..=HI` (a size option: refused with its range rather than tried).
fn count<const LO: usize, const HI: usize>(s: &str) -> Result<usize, String> {
    let v: usize = s
        .trim()
        .parse()
        .map_err(|_| format!("{s:?} is not a whole number"))?;
    if (LO..=HI).contains(&v) {
        Ok(v)
    } else {
        Err(format!("{v} is outside {LO} to {HI}"))
    }
}

/// Milliseconds, 1 to 60,000.
fn millis(s: &str) -> Result<u64, String> {
    count::<1, 60_000>(s).map(|v| v as u64)
}

/// A positive finite number (a tolerance).
fn positive(s: &str) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("{s:?} is not a number"))?;
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(format!("{v} is not a positive length"))
    }
}

/// A request time limit in seconds, 0.1 to 600.
fn parse_timeout(s: &str) -> Result<f64, String> {
    let v: f64 = s
        .parse()
        .map_err(|_| format!("{s:?} is not a number of seconds"))?;
    if (0.1..=600.0).contains(&v) {
        Ok(v)
    } else {
        Err(format!("{v} s is outside 0.1 to 600 s"))
    }
}

#[derive(Subcommand)]
enum BenchCmd {
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
    /// The pseudo-elastic spline in table mode on the point sets, against a tenth of
    /// libspiro's times (the ratio itself: `cargo bench --features spiro-bench --bench
    /// spiro_compare` in crates/aesthetic-curves, with libspiro installed).
    Spline(TargetArgs),
}

#[derive(clap::Args)]
struct TargetArgs {
    /// Timing rounds (interleaved; the median is reported; 1 to 101).
    #[arg(long, default_value_t = 7, value_parser = count::<1, 101>)]
    rounds: usize,
    /// Minimum milliseconds per round and work (1 to 60,000).
    #[arg(long, default_value_t = 40, value_parser = millis)]
    round_ms: u64,
    /// Print JSON instead of the table.
    #[arg(long)]
    json: bool,
}

#[derive(Clone, Copy, ValueEnum, PartialEq)]
enum Method {
    Exact,
    Sampling,
}

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
    let mut out: Vec<&std::path::Path> = cli.curvature_plot.iter().map(|p| p.as_path()).collect();
    match &cli.cmd {
        Cmd::Monotone { output, .. }
        | Cmd::Lac { output, .. }
        | Cmd::Lcg { output, .. }
        | Cmd::Spline { output, .. }
        | Cmd::Sketch { output, .. } => out.extend(output.iter().map(|p| p.as_path())),
        Cmd::Approx { output, map, .. } => {
            out.extend(output.iter().map(|p| p.as_path()));
            out.extend(map.iter().map(|p| p.as_path()));
        }
        Cmd::Bench {
            what: BenchCmd::Monotone { output, .. },
        } => out.extend(output.iter().map(|p| p.as_path())),
        _ => {}
    }
    out
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
    if let Some(p) = &cli.curvature_plot {
        plot::check_picture_paths(std::slice::from_ref(p))?;
        let _ = CURVATURE_PLOT.set(p.clone());
    }
    match &cli.cmd {
        Cmd::Lcg { output, .. } => plot::check_picture_paths(output)?,
        Cmd::Lac { output, .. }
        | Cmd::Monotone { output, .. }
        | Cmd::Approx { output, .. }
        | Cmd::Sketch { output, .. }
        | Cmd::Spline { output, .. } => {
            for p in output {
                let ext = aecurve::export::extension(p).unwrap_or_default();
                if !aecurve::export::CURVE_FORMATS.contains(&ext.as_str())
                    && plot::check_picture_paths(std::slice::from_ref(p)).is_err()
                {
                    anyhow::bail!(
                        "{}: unknown format (use .svg, .png, .{})",
                        p.display(),
                        aecurve::export::CURVE_FORMATS.join(", .")
                    );
                }
            }
            if let Cmd::Approx { map, .. } = &cli.cmd {
                plot::check_picture_paths(map.as_slice())?;
            }
        }
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
        Cmd::Batch { max_line_bytes } => {
            let stdin = std::io::stdin();
            let stdout = std::io::stdout();
            batch::run(stdin.lock(), stdout.lock(), max_line_bytes)?;
        }
        Cmd::Monotone {
            points,
            weights,
            method,
            samples,
            json,
            output,
        } => monotone(&points, weights.as_deref(), method, samples, json, &output)?,
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
            inflection,
            control,
            samples,
            json,
            output,
        } => match (alpha, inflection) {
            (Some(a), false) => lac(a, &control, samples, json, &output)?,
            _ => lac_inflection(&control, samples, json, &output)?,
        },
        Cmd::Spline {
            input,
            closed,
            mode,
            json,
            output,
        } => spline(&input, closed, &mode, json, &output)?,
        Cmd::Sketch {
            input,
            tolerance,
            json,
            output,
        } => sketch(&input, tolerance, json, &output)?,
        Cmd::Approx {
            alpha,
            control,
            tolerance,
            json,
            output,
            map,
            map_cells,
        } => approx(
            alpha,
            &control,
            tolerance,
            json,
            &output,
            map.as_deref(),
            map_cells,
        )?,
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
                    let pts = parse_points(&c).context("--control")?;
                    anyhow::ensure!(pts.len() == 3, "--control needs exactly 3 points");
                    let a = alpha.context("--alpha is needed with --control")?;
                    LcgSource::Lac(aesthetic_curves::lac::LacSegment::new(
                        a,
                        [pts[0], pts[1], pts[2]],
                    )?)
                }
                _ => anyhow::bail!("give --points, --input, --bezier or --alpha with --control"),
            };
            lcg(source, json, &output)?
        }
    }
    Ok(())
}

fn monotone(
    points: &str,
    weights: Option<&str>,
    method: Method,
    samples: usize,
    json: bool,
    output: &[PathBuf],
) -> Result<()> {
    let pts = parse_points(points).context("--points")?;
    let w = weights
        .map(parse_numbers)
        .transpose()
        .context("--weights")?;
    let curve = AnyBezier::new(pts.clone(), w.clone())?;
    let c = curve.as_monotone();
    let kind = if w.is_some() {
        "rational"
    } else {
        "polynomial"
    };
    let degree = pts.len() - 1;
    let mut out = std::io::stdout().lock();
    match method {
        Method::Exact => {
            let r = c.curvature_monotone()?;
            if json {
                writeln!(
                    out,
                    "{}",
                    serde_json::json!({"monotone": r.monotone, "extrema": r.extrema,
                        "test_degree": r.test_degree, "trend": r.trend.map(|t| t.as_str())})
                )?;
            } else {
                writeln!(out, "{kind} Bézier curve of degree {degree}")?;
                writeln!(
                    out,
                    "curvature at the ends: {:.6} (t = 0), {:.6} (t = 1)",
                    curve.kappa(0.0),
                    curve.kappa(1.0)
                )?;
                if r.monotone {
                    let how = r.trend.map(|t| t.as_str()).unwrap_or("constant");
                    writeln!(out, "curvature is MONOTONE ({how})")?;
                } else {
                    writeln!(
                        out,
                        "curvature is NOT monotone: {} extrema",
                        r.extrema.len()
                    )?;
                    for t in &r.extrema {
                        let p = curve.eval(*t);
                        writeln!(
                            out,
                            "  extremum at t = {t:.9}: point ({:.6}, {:.6}), curvature {:.6}",
                            p.x,
                            p.y,
                            curve.kappa(*t)
                        )?;
                    }
                }
                writeln!(
                    out,
                    "proof: sign of dkappa/ds from a Bernstein polynomial of degree {} \
                     (convex hull + subdivision)",
                    r.test_degree
                )?;
            }
        }
        Method::Sampling => {
            let r = c.curvature_monotone_sampled(samples)?;
            if json {
                writeln!(
                    out,
                    "{}",
                    serde_json::json!({"monotone": r.monotone, "samples": r.samples,
                        "trend": r.trend.map(|t| t.as_str())})
                )?;
            } else {
                writeln!(
                    out,
                    "sampling test, {} divisions: curvature {} (not a proof: extrema between \
                     samples go unseen)",
                    r.samples,
                    if r.monotone {
                        "looks monotone"
                    } else {
                        "is NOT monotone"
                    }
                )?;
            }
        }
    }
    let comb: Vec<plot::CombSample> = (0..=200)
        .map(|i| {
            let d = curve.as_monotone().derivs(i as f64 / 200.0);
            let k = d.kappa();
            let speed = d.d1.hypot();
            let nrm = if speed > 0.0 {
                d.d1.turn_90() / speed
            } else {
                aesthetic_curves::Vec2::ZERO
            };
            (d.p, nrm, if k.is_finite() { k } else { 0.0 })
        })
        .collect();
    write_curvature_plot(&comb, "curvature of the Bézier curve")?;
    for path in output {
        let ext = aecurve::export::extension(path).unwrap_or_default();
        if aecurve::export::CURVE_FORMATS.contains(&ext.as_str()) {
            let weights = w.clone().unwrap_or_else(|| vec![1.0; pts.len()]);
            let rb = aesthetic_curves::RationalBezier::new(pts.clone(), weights)?;
            aecurve::export::write_curve(
                path,
                &aesthetic_curves::nurbs::Nurbs::from_bezier(&rb),
                "bezier",
            )?;
            eprintln!("wrote {}", path.display());
            continue;
        }
        let caption = format!("{kind} degree {degree}: curvature comb");
        if ext == "svg" {
            // The curve itself (cubic Béziers within 1e-6 of its size, in its own
            // coordinates) with its comb.
            let weights = w.clone().unwrap_or_else(|| vec![1.0; pts.len()]);
            let rb = aesthetic_curves::RationalBezier::new(pts.clone(), weights)?;
            let nurbs = aesthetic_curves::nurbs::Nurbs::from_bezier(&rb);
            let doc = aecurve::export::svg_document(&nurbs, 1e-6 * nurbs.size(), &comb, &caption)
                .context("the curve has no spans")?;
            std::fs::write(path, doc).with_context(|| format!("writing {}", path.display()))?;
            eprintln!("wrote {}", path.display());
            continue;
        }
        let extrema = match method {
            Method::Exact => c.curvature_monotone()?.extrema,
            Method::Sampling => Vec::new(),
        };
        plot::write_picture(
            path,
            &plot::curve_with_comb(&curve, &pts, &extrema, &caption),
        )?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

fn lac(alpha: f64, control: &str, samples: usize, json: bool, output: &[PathBuf]) -> Result<()> {
    let pts = parse_points(control).context("--control")?;
    anyhow::ensure!(
        pts.len() == 3,
        "--control needs exactly 3 points, got {}",
        pts.len()
    );
    let seg = aesthetic_curves::lac::LacSegment::new(alpha, [pts[0], pts[1], pts[2]])?;
    let (points, kappa) = seg.sample(samples.max(2))?;
    let (k0, k1) = seg.end_curvatures()?;
    if json {
        println!(
            "{}",
            serde_json::json!({"lambda": seg.lambda(), "theta_d": seg.theta_d,
                "arc_length": seg.arc_length()?, "curvature_start": k0, "curvature_end": k1,
                "points": points.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>(),
                "curvature": kappa})
        );
    } else {
        println!("log-aesthetic segment, alpha = {alpha}");
        println!("  turning angle  {:.6} deg", seg.theta_d.to_degrees());
        println!("  lambda         {:.12}", seg.lambda());
        println!("  arc length     {:.9}", seg.arc_length()?);
        println!("  curvature      {k0:.9} at the start, {k1:.9} at the end");
        println!(
            "  high-curvature end at {}",
            if seg.reversed {
                "the end point"
            } else {
                "the start point"
            }
        );
    }
    let caption = format!("LAC alpha = {alpha}, lambda = {:.6}", seg.lambda());
    let samples = plot::polyline_samples(&points, &kappa);
    // CAD formats get the segment as rational cubics within 1e-7 of its size (a LAC segment
    // has no exact rational form): the exact rational geometry of that approximation.
    let cad = || -> Result<aesthetic_curves::nurbs::Nurbs> {
        let size = pts
            .iter()
            .map(|p| (*p - pts[0]).hypot())
            .fold(0.0, f64::max);
        let sp = aesthetic_curves::approx::fit_rational_spline(
            &seg,
            1e-7 * size,
            64,
            &aesthetic_curves::approx::ApproxOptions::default(),
        )?;
        eprintln!(
            "as {} rational cubic(s), max distance {:.2e} from the segment",
            sp.pieces.len(),
            sp.max_error
        );
        Ok(aesthetic_curves::nurbs::Nurbs::new(
            sp.degree,
            sp.knots,
            sp.control_points,
            sp.weights,
        )?)
    };
    write_segment_outputs(output, &samples, &pts, &caption, &cad)
}

/// `-o` for a LAC segment command: pictures (.svg, .png) of the segment with its comb; CAD
/// formats and .json through `cad` (built once, only when asked for).
fn write_segment_outputs(
    output: &[PathBuf],
    samples: &[plot::CombSample],
    control: &[aesthetic_curves::Point],
    caption: &str,
    cad: &dyn Fn() -> Result<aesthetic_curves::nurbs::Nurbs>,
) -> Result<()> {
    write_curvature_plot(samples, caption)?;
    let mut curve = None;
    for path in output {
        let ext = aecurve::export::extension(path).unwrap_or_default();
        if aecurve::export::CURVE_FORMATS.contains(&ext.as_str()) {
            if curve.is_none() {
                curve = Some(cad()?);
            }
            let c = curve.as_ref().expect("built above");
            aecurve::export::write_curve(path, c, "log_aesthetic_segment")?;
        } else if ext == "svg" {
            // The segment's rational cubics as cubic Béziers within 1e-6 of its size, in its
            // own coordinates, with the segment's comb.
            if curve.is_none() {
                curve = Some(cad()?);
            }
            let c = curve.as_ref().expect("built above");
            let doc = aecurve::export::svg_document(c, 1e-6 * c.size(), samples, caption)
                .context("the curve has no spans")?;
            std::fs::write(path, doc).with_context(|| format!("writing {}", path.display()))?;
        } else {
            plot::write_picture(path, &plot::comb_svg(samples, control, &[], caption))?;
        }
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

fn lac_inflection(control: &str, samples: usize, json: bool, output: &[PathBuf]) -> Result<()> {
    let pts = parse_points(control).context("--control")?;
    anyhow::ensure!(
        pts.len() == 3,
        "--control needs exactly 3 points, got {}",
        pts.len()
    );
    let seg = aesthetic_curves::lac::LacInflectionSegment::new([pts[0], pts[1], pts[2]])?;
    let (points, kappa) = seg.sample(samples.max(2))?;
    let k1 = kappa[kappa.len() - 1];
    if json {
        println!(
            "{}",
            serde_json::json!({"alpha": seg.alpha, "theta_d": seg.theta_d,
                "arc_length": seg.arc_length(), "curvature_end": k1,
                "points": points.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>(),
                "curvature": kappa})
        );
    } else {
        println!("log-aesthetic segment with an inflection at the start point");
        println!("  alpha          {:.10}", seg.alpha);
        println!("  turning angle  {:.6} deg", seg.theta_d.to_degrees());
        println!("  arc length     {:.9}", seg.arc_length());
        println!("  curvature      0 at the start, {k1:.9} at the end");
    }
    let caption = format!("LAC with an inflection end, alpha = {:.6}", seg.alpha);
    let samples = plot::polyline_samples(&points, &kappa);
    // CAD formats: rational cubics within 1e-7 of the size, as for a LAC segment: next to the
    // inflection one cubic with zero curvature there, then the rest (an ordinary LAC
    // segment); G2 at the joints, every piece's curvature proven monotone.
    let cad = || -> Result<aesthetic_curves::nurbs::Nurbs> {
        let size = pts
            .iter()
            .map(|p| (*p - pts[0]).hypot())
            .fold(0.0, f64::max);
        let sp = aesthetic_curves::approx::fit_inflection_spline(
            &seg,
            1e-7 * size,
            64,
            &aesthetic_curves::approx::ApproxOptions::default(),
        )?;
        eprintln!(
            "as {} rational cubic(s), max distance {:.2e} from the segment, curvature {}",
            sp.pieces.len(),
            sp.max_error,
            if sp.pieces.iter().all(|p| p.monotone) {
                "monotone in every piece (proven)"
            } else {
                "NOT monotone in every piece"
            }
        );
        Ok(aesthetic_curves::nurbs::Nurbs::new(
            sp.degree,
            sp.knots,
            sp.control_points,
            sp.weights,
        )?)
    };
    write_segment_outputs(output, &samples, &pts, &caption, &cad)
}

fn approx(
    alpha: f64,
    control: &str,
    tolerance: Option<f64>,
    json: bool,
    output: &[PathBuf],
    map: Option<&std::path::Path>,
    map_cells: usize,
) -> Result<()> {
    use aesthetic_curves::approx;
    let pts = parse_points(control).context("--control")?;
    anyhow::ensure!(
        pts.len() == 3,
        "--control needs exactly 3 points, got {}",
        pts.len()
    );
    anyhow::ensure!(
        (2..=1000).contains(&map_cells),
        "--map-cells must be 2 to 1000"
    );
    // Library errors keep the protocol's kind in the message (`no_segment: ...`).
    let kinded = |e: aesthetic_curves::Error| anyhow::anyhow!("{}: {e}", e.kind());
    let seg =
        aesthetic_curves::lac::LacSegment::new(alpha, [pts[0], pts[1], pts[2]]).map_err(kinded)?;
    let opts = approx::ApproxOptions::default();
    let fit = approx::fit_rational_cubic(&seg, &opts).map_err(kinded)?;
    let spline = tolerance
        .map(|t| approx::fit_rational_spline(&seg, t, 64, &opts))
        .transpose()
        .map_err(kinded)?;
    let r = &aecurve::protocol::rational_approx_json(&seg, &fit, spline.as_ref())?;
    if json {
        println!("{r}");
    } else {
        let len = seg.arc_length()?;
        println!("rational cubic for the LAC segment alpha = {alpha}");
        println!("  turning angle   {:.6} deg", seg.theta_d.to_degrees());
        println!("  f0, f1          {:.9}, {:.9}", fit.f0, fit.f1);
        for (i, (p, w)) in fit
            .curve
            .points()
            .iter()
            .zip(fit.curve.weights())
            .enumerate()
        {
            println!("  b{i} = ({:.12}, {:.12})  w{i} = {w:.12}", p.x, p.y);
        }
        println!(
            "  error           rms {:.3e}, max {:.3e} of the arc length ({:.3e}, {:.3e} in input units)",
            fit.rms,
            fit.max_error,
            fit.rms * len,
            fit.max_error * len
        );
        println!("  curvature       monotone (exact test), G2 at both ends");
        if let Some(sp) = r.get("spline") {
            println!(
                "  spline          {} piece(s) within {:e}: max error {:.3e}",
                sp["pieces"],
                tolerance.unwrap_or(0.0),
                sp["max_error"].as_f64().unwrap_or(f64::NAN)
            );
        }
    }
    let nurbs = match &spline {
        Some(sp) => aesthetic_curves::nurbs::Nurbs::from_spline(sp),
        None => aesthetic_curves::nurbs::Nurbs::from_bezier(&fit.curve),
    };
    let n = 200;
    let comb: Vec<plot::CombSample> = (0..=n)
        .map(|i| {
            let u = i as f64 / n as f64;
            let spans = nurbs.bezier_spans().expect("spline spans");
            let k = ((u * spans.len() as f64) as usize).min(spans.len() - 1);
            let t = u * spans.len() as f64 - k as f64;
            let d = aesthetic_curves::PlanarCurve::derivs(&spans[k], t);
            (d.p, d.d1.turn_90() / d.d1.hypot(), d.kappa())
        })
        .collect();
    let caption = format!(
        "rational cubic for LAC alpha = {alpha}: rms {:.2e}, max {:.2e}",
        fit.rms, fit.max_error
    );
    for path in output {
        let ext = aecurve::export::extension(path).unwrap_or_default();
        match ext.as_str() {
            "svg" => {
                let tol = 1e-6 * nurbs.size();
                let doc = aecurve::export::svg_document(&nurbs, tol, &comb, &caption)
                    .context("the spline has no Bézier spans")?;
                std::fs::write(path, doc).with_context(|| format!("writing {}", path.display()))?;
            }
            "png" => plot::write_picture(
                path,
                &plot::comb_svg(&comb, &nurbs.control_points, &[], &caption),
            )?,
            _ => aecurve::export::write_curve(path, &nurbs, "lac_rational")?,
        }
        eprintln!("wrote {}", path.display());
    }
    if let Some(path) = map {
        let m = approx::error_map(&seg, map_cells, 32)?;
        let caption = format!(
            "error over (f0, f1), alpha = {alpha}, turning {:.1} deg",
            seg.theta_d.to_degrees()
        );
        plot::write_picture(path, &plot::error_map_svg(&m, (fit.f0, fit.f1), &caption))?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

/// S0 Fig. 4-7 (rational cubics for LAC segments of alpha -1, 0, 1, 2 at 90 degrees of
/// turning, three triangles each) and S3 Fig. 3 and 5 (the error map): pictures and HTML.
fn approx_gallery(out: &std::path::Path) -> Result<String> {
    use aesthetic_curves::approx;
    use aesthetic_curves::lac::{LacSegment, LacStandard};
    use aesthetic_curves::{Point, Vec2};
    let mut html = String::from(
        "<h2>One rational cubic per log-aesthetic segment — Yoshida &amp; Saito (S0), Fig. 4-7</h2>\n<p>Each LAC segment \
         (turning 90 degrees) is replaced by the rational cubic of docs/math.md §4 that matches \
         its end points, tangents and curvatures, with (f0, f1) chosen by the global search; \
         the exact test proves its curvature monotone. Errors are relative to the arc \
         length. An isosceles triangle gives the circular arc to rounding.</p>\n\
         <table border=\"1\" cellpadding=\"4\"><tr><th>alpha</th><th>base angle</th>\
         <th>f0</th><th>f1</th><th>rms</th><th>errMax</th></tr>\n",
    );
    let td = std::f64::consts::FRAC_PI_2;
    let mut figures = String::new();
    for alpha in [-1.0, 0.0, 1.0, 2.0] {
        let lim = LacSegment::theta_lim(alpha, td)?;
        for (k, frac) in [0.0, 0.35, 0.7].into_iter().enumerate() {
            let phi = 0.5 * td + frac * (lim - 0.5 * td);
            let d = phi.sin() / (td - phi).sin();
            let tri = [
                Point::new(0.0, 0.0),
                Point::new(1.0, 0.0),
                Point::new(1.0 + d * td.cos(), d * td.sin()),
            ];
            let seg = LacSegment::new(alpha, tri)?;
            let fit = approx::fit_rational_cubic(&seg, &approx::ApproxOptions::default())?;
            html += &format!(
                "<tr><td>{alpha}</td><td>{:.2} deg</td><td>{:.4}</td><td>{:.4}</td><td>{:.2e}</td><td>{:.2e}</td></tr>\n",
                phi.to_degrees(),
                fit.f0,
                fit.f1,
                fit.rms,
                fit.max_error
            );
            if k == 2 {
                let n = 200;
                let samples: Vec<plot::CombSample> = (0..=n)
                    .map(|i| {
                        let dd =
                            aesthetic_curves::PlanarCurve::derivs(&fit.curve, i as f64 / n as f64);
                        (dd.p, dd.d1.turn_90() / dd.d1.hypot(), dd.kappa())
                    })
                    .collect();
                let file = format!("approx-alpha{alpha}.svg");
                let caption = format!(
                    "alpha = {alpha}: rms {:.2e}, errMax {:.2e}",
                    fit.rms, fit.max_error
                );
                std::fs::write(
                    out.join(&file),
                    plot::comb_svg(&samples, fit.curve.points(), &[], &caption),
                )?;
                let lcg = aesthetic_curves::lcg::fit_line(aesthetic_curves::lcg::curve_lcg(
                    &fit.curve, 61,
                ))?;
                let lfile = format!("approx-lcg-alpha{alpha}.svg");
                std::fs::write(
                    out.join(&lfile),
                    plot::lcg_chart(
                        &lcg,
                        &format!("LCG of the rational cubic (LAC alpha = {alpha})"),
                    ),
                )?;
                figures += &format!(
                    "<figure><img src=\"{file}\" alt=\"rational cubic alpha {alpha}\" width=\"48%\">\
                     <img src=\"{lfile}\" alt=\"its LCG\" width=\"48%\"><figcaption>alpha = {alpha}, \
                     base angle {:.1} deg: the rational cubic (control polygon dashed) with its \
                     curvature comb, and its logarithmic curvature graph, whose fitted slope \
                     {:.3} stays close to the LAC's alpha.</figcaption></figure>\n",
                    phi.to_degrees(),
                    lcg.alpha
                );
            }
        }
    }
    html += "</table>\n";
    html += &figures;
    // S3 Fig. 3 and 5: alpha = 1, Lambda = 1, theta in [0, 1.57].
    let std = LacStandard::new(1.0, 1.0)?;
    let t1 = 1.57f64;
    let (p0, p2) = (std.eval(0.0)?, std.eval(t1)?);
    let (d0, d1) = (Vec2::from_angle(0.0), Vec2::from_angle(t1));
    let p1 = p0 + d0 * ((p2 - p0).cross(d1) / d0.cross(d1));
    let seg = LacSegment::new(1.0, [p0, p1, p2])?;
    let fit = approx::fit_rational_cubic(&seg, &approx::ApproxOptions::default())?;
    let map = approx::error_map(&seg, 80, 32)?;
    std::fs::write(
        out.join("approx-map-s3.svg"),
        plot::error_map_svg(
            &map,
            (fit.f0, fit.f1),
            "S3: alpha = 1, Lambda = 1, theta in [0, 1.57]",
        ),
    )?;
    html += &format!(
        "<h2>Where the rational cubic fit can go wrong: its error over the two free handle ratios — the stable-approximation paper (S3), Fig. 3 and 5</h2>\n<figure><img src=\"approx-map-s3.svg\" \
         alt=\"error map\"><figcaption>Rms error over (f0, f1) for alpha = 1, Lambda = 1, \
         theta in [0, 1.57]; hatched: the cubic's curvature is not monotone. The global search \
         returns f0 = {:.3}, f1 = {:.3} (rms {:.2e}, circled); S3 reports the global minimum \
         at (0.444, 0.686) and a second local minimum at (0.298, 0.882), where a local \
         optimiser from a fixed start can get stuck.</figcaption></figure>\n",
        fit.f0, fit.f1, fit.rms
    );
    Ok(html)
}

fn sketch(
    input: &std::path::Path,
    tolerance: Option<f64>,
    json: bool,
    output: &[PathBuf],
) -> Result<()> {
    use aesthetic_curves::sketch::{fit_sketch, SketchOptions};
    let pts = aecurve::read_points_file(input)?;
    let tol = match tolerance {
        Some(t) => {
            anyhow::ensure!(t.is_finite() && t > 0.0, "--tolerance must be positive");
            t
        }
        None => aesthetic_curves::sketch::default_tolerance(&pts),
    };
    let sk = fit_sketch(&pts, &SketchOptions::with_tolerance(tol))?;
    if json {
        println!("{}", aecurve::protocol::sketch_json(&sk, tol));
    } else {
        println!(
            "sketch of {} points: {} pieces, deviation {:.4e} (tolerance {:.4e}), curvature jump {:.2e} ({}), {}",
            pts.len(),
            sk.pieces.len(),
            sk.max_deviation,
            tol,
            sk.max_curvature_jump,
            if sk.g2 { "G2" } else { "not G2" },
            if sk.all_monotone {
                "every piece curvature-monotone (exact test)"
            } else {
                "NOT every piece curvature-monotone"
            }
        );
        println!(
            "  {} inflections, {} curvature extrema; fairing: {} Newton iterations, jump {:.2e} -> {:.2e}",
            sk.inflections,
            sk.curvature_extrema,
            sk.fairing.iterations,
            sk.fairing.initial_jump,
            sk.fairing.final_jump
        );
        for (i, p) in sk.pieces.iter().enumerate() {
            println!(
                "  piece {i}: {:<14} alpha {:>8.4}{}  curvature {:+.4e} -> {:+.4e}  {}",
                p.kind.as_str(),
                p.alpha,
                if p.alpha_at_bound { " (bound)" } else { "" },
                p.end_curvatures.0,
                p.end_curvatures.1,
                if p.monotone {
                    "monotone"
                } else {
                    "not monotone"
                }
            );
        }
    }
    let curves: Vec<aesthetic_curves::RationalBezier> =
        sk.pieces.iter().map(|p| p.rational.clone()).collect();
    let nurbs = aesthetic_curves::nurbs::Nurbs::from_beziers(&curves)?;
    let mut comb: Vec<plot::CombSample> = Vec::new();
    for p in &sk.pieces {
        for k in 0..=60 {
            let d = aesthetic_curves::PlanarCurve::derivs(&p.rational, k as f64 / 60.0);
            comb.push((d.p, d.d1.turn_90() / d.d1.hypot(), d.kappa()));
        }
    }
    write_curvature_plot(&comb, "curvature of the G2 curve (rational cubic pieces)")?;
    let caption = format!(
        "sketch: {} LAC pieces (rational cubics), deviation {:.3e}, jump {:.1e}",
        sk.pieces.len(),
        sk.max_deviation,
        sk.max_curvature_jump
    );
    for path in output {
        let ext = aecurve::export::extension(path).unwrap_or_default();
        if aecurve::export::CURVE_FORMATS.contains(&ext.as_str()) {
            aecurve::export::write_curve(path, &nurbs, "sketch")?;
        } else if ext == "svg" {
            // The curve itself as cubic Béziers (within 1e-6 of its size), with its comb.
            let doc = aecurve::export::svg_document(&nurbs, 1e-6 * nurbs.size(), &comb, &caption)
                .context("the curve has no Bézier spans")?;
            std::fs::write(path, doc).with_context(|| format!("writing {}", path.display()))?;
        } else {
            plot::write_picture(path, &plot::comb_svg(&comb, &pts, &sk.joints(), &caption))?;
        }
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

fn spline(
    input: &std::path::Path,
    closed: bool,
    mode: &str,
    json: bool,
    output: &[PathBuf],
) -> Result<()> {
    let pts = aecurve::read_points_file(input)?;
    // The command line writes files, not a JSON answer in memory: table mode takes up to a
    // million points here (the protocol's request limit is lower).
    let max = if mode == "exact" {
        aecurve::protocol::MAX_EXACT_SPLINE_POINTS
    } else {
        1_000_000
    };
    anyhow::ensure!(
        pts.len() <= max,
        "at most {max} points in {mode} mode, got {}",
        pts.len()
    );
    let s = aesthetic_curves::pseudo_spline::pseudo_elastic(
        &pts,
        closed,
        aecurve::protocol::spline_mode(mode),
    )?;
    let r = &aecurve::protocol::spline_json(&s, mode);
    if json {
        println!("{r}");
    } else {
        println!(
            "pseudo-elastic spline through {} points ({}), {mode} mode",
            pts.len(),
            if closed { "closed" } else { "open" }
        );
        println!("  length   {:.9}", r["length"].as_f64().unwrap_or(f64::NAN));
        println!(
            "  area     {:.9} ({})",
            r["area"].as_f64().unwrap_or(f64::NAN),
            if closed {
                "enclosed"
            } else {
                "between the curve and the chord of its ends"
            }
        );
        println!(
            "  energy   {:.9} (sum of l_i J_i)",
            r["energy"].as_f64().unwrap_or(f64::NAN)
        );
    }
    if !output.is_empty() || CURVATURE_PLOT.get().is_some() {
        let mut samples: Vec<plot::CombSample> = Vec::new();
        for g in &s.segments {
            let c = aesthetic_curves::Bezier::new(vec![
                g.p0,
                g.p0 + g.d0 / 3.0,
                g.p1 - g.d1 / 3.0,
                g.p1,
            ])?;
            for k in 0..=40 {
                let d = aesthetic_curves::PlanarCurve::derivs(&c, k as f64 / 40.0);
                samples.push((d.p, d.d1.turn_90() / d.d1.hypot(), d.kappa()));
            }
        }
        let caption = format!("pseudo-elastic spline: length {:.6}", s.length);
        write_curvature_plot(&samples, "curvature of the pseudo-elastic spline")?;
        let mut polygon = pts.clone();
        if closed {
            polygon.push(pts[0]);
        }
        let cubics: Vec<aesthetic_curves::RationalBezier> = s
            .segments
            .iter()
            .map(|g| g.to_bezier().map(|b| b.to_rational()))
            .collect::<Result<_, _>>()?;
        let nurbs = aesthetic_curves::nurbs::Nurbs::from_beziers(&cubics)?;
        for path in output {
            let ext = aecurve::export::extension(path).unwrap_or_default();
            if aecurve::export::CURVE_FORMATS.contains(&ext.as_str()) {
                aecurve::export::write_curve(path, &nurbs, "pseudo_elastic_spline")?;
            } else if ext == "svg" {
                // The curve itself (its cubics, exact) with its comb.
                let doc =
                    aecurve::export::svg_document(&nurbs, 1e-6 * nurbs.size(), &samples, &caption)
                        .context("the spline has no Bézier spans")?;
                std::fs::write(path, doc).with_context(|| format!("writing {}", path.display()))?;
            } else {
                plot::write_picture(path, &plot::comb_svg(&samples, &polygon, &[], &caption))?;
            }
            eprintln!("wrote {}", path.display());
        }
    }
    Ok(())
}

/// S4 §3 (Fig. 9-12): the pen-input pipeline on the built-in stroke and on a Prius key line.
/// S4 Fig. 1-3: inflection-end segments from (0, 0) (tangent along x) to (√2 + 1, 1), the
/// direction angle θ at the far end from 50° to 130°; the curvature there and alpha against θ.
fn inflection_gallery(out: &std::path::Path) -> Result<String> {
    use aesthetic_curves::lac::LacInflectionSegment;
    use aesthetic_curves::Point;
    let p2 = Point::new(2f64.sqrt() + 1.0, 1.0);
    let mut curves = Vec::new();
    let (mut kappa, mut alpha) = (Vec::new(), Vec::new());
    let mut rows = String::new();
    for (k, deg) in (50..=130).step_by(10).enumerate() {
        let th = (deg as f64).to_radians();
        let p1 = Point::new(p2.x - p2.y / th.tan(), 0.0);
        let seg = LacInflectionSegment::new([Point::ORIGIN, p1, p2])?;
        let (pts, _) = seg.sample(120)?;
        curves.push(plot::Series::nth(
            format!("θ = {deg}°"),
            pts.iter().map(|p| (p.x, p.y)).collect(),
            k,
        ));
        let kap = seg.end_curvature();
        kappa.push((deg as f64, kap));
        alpha.push((deg as f64, seg.alpha));
        rows += &format!(
            "<tr><td>{deg}</td><td>{:.5}</td><td>{:.5}</td><td>{:.5}</td></tr>\n",
            seg.alpha,
            kap,
            seg.arc_length()
        );
    }
    for c in curves.iter_mut() {
        c.markers = false;
    }
    // The graphs on a finer step (2°).
    kappa.clear();
    alpha.clear();
    for deg in (50..=130).step_by(2) {
        let th = (deg as f64).to_radians();
        let p1 = Point::new(p2.x - p2.y / th.tan(), 0.0);
        let seg = LacInflectionSegment::new([Point::ORIGIN, p1, p2])?;
        kappa.push((deg as f64, seg.end_curvature()));
        alpha.push((deg as f64, seg.alpha));
    }
    std::fs::write(
        out.join("s4-fig1.svg"),
        plot::curves_svg(
            "S4 Fig. 1: segments with an inflection end at (0, 0)",
            &curves,
            &[Point::ORIGIN, p2],
        ),
    )?;
    std::fs::write(
        out.join("s4-fig2.svg"),
        plot::fitted_chart(
            "S4 Fig. 2: curvature at the far end against its direction angle",
            "θ (degrees)",
            "κ at (√2 + 1, 1)  (1 / length unit)",
            &[plot::Series::new("κ", kappa, plot::PALETTE[0])],
        ),
    )?;
    std::fs::write(
        out.join("s4-fig3.svg"),
        plot::fitted_chart(
            "S4 Fig. 3: alpha against the direction angle",
            "θ (degrees)",
            "alpha",
            &[plot::Series::new("alpha", alpha, plot::PALETTE[1])],
        ),
    )?;
    Ok(format!(
        "<h2>Log-aesthetic segments that start at an inflection — Miura, Yagi, Kawata &amp; Fujisawa (S4), Fig. 1-3</h2>\n<p>The \
         inflection point is (0, 0) with its tangent along x, the other end is (√2 + 1, 1) and \
         the direction angle θ there runs from 50° to 130°; alpha follows from the triangle. \
         As S4 says, the curvature at the far end and alpha both increase with θ: that \
         monotone relation is what lets the G2 fairing match curvatures by turning the joint \
         tangent.</p>\n<figure><img src=\"s4-fig1.svg\" alt=\"S4 Fig. 1\" width=\"70%\">\
         <figcaption>Fig. 1: the nine segments.</figcaption></figure>\n<figure><img \
         src=\"s4-fig2.svg\" alt=\"S4 Fig. 2\" width=\"48%\"><img src=\"s4-fig3.svg\" \
         alt=\"S4 Fig. 3\" width=\"48%\"><figcaption>Fig. 2 and 3: curvature at the far end \
         and alpha against θ.</figcaption></figure>\n<table border=\"1\" cellpadding=\"4\">\
         <tr><th>θ (°)</th><th>alpha</th><th>κ at the far end</th><th>arc length</th></tr>\n\
         {rows}</table>\n"
    ))
}

fn sketch_gallery(out: &std::path::Path) -> Result<String> {
    use aesthetic_curves::sketch::{fit_sketch, SketchOptions};
    let mut html = String::from(
        "<h2>From pen strokes and measured lines to a G2 aesthetic curve — Miura et al. (S4) §3, Fig. 9-12</h2>\n<p>Points → \
         least-squares cubic B-spline → pieces at inflections and curvature maxima → one \
         log-aesthetic segment per piece (alpha from its curvature graph; inflection-end \
         segments at inflections) → G2 fairing of the joint tangents → one rational cubic \
         per piece, its curvature proven monotone. Grey: the input; red: the result; \
         circles: the joints; blue: the curvature comb (continuous across every joint: G2).</p>\n",
    );
    let prius = aesthetic_curves_data::PRIUS.map(|l| l.csv);
    let mut inputs: Vec<(String, &str, String, Option<f64>)> = vec![(
        "sketch-stroke".into(),
        aesthetic_curves_data::HAND_STROKE,
        "A pen stroke (240 points with hand jitter), default \
         tolerance (0.5% of its size)."
            .into(),
        None,
    )];
    for (i, text) in prius.iter().enumerate() {
        inputs.push((
            format!("sketch-prius{}", i + 1),
            text,
            format!(
                "Prius key line {} (measured points, about 1500 mm long and 80-100 mm deep; \
                 Graiff Zurita, Kajiwara & Miura 2023, MIT licence), tolerance 0.3 mm.",
                i + 1
            ),
            Some(0.3),
        ));
    }
    for (name, text, caption, tol) in &inputs {
        let (name, text, caption, tol) = (name.as_str(), *text, caption.as_str(), *tol);
        // The Prius lines are measured in millimetres, the pen stroke in pixels.
        let unit = if name.starts_with("sketch-prius") {
            "mm"
        } else {
            "px"
        };
        let pts = aecurve::parse_points_text(text)?;
        let tol = tol.unwrap_or_else(|| aesthetic_curves::sketch::default_tolerance(&pts));
        let t0 = std::time::Instant::now();
        let sk = fit_sketch(&pts, &SketchOptions::with_tolerance(tol))?;
        let ms = t0.elapsed().as_secs_f64() * 1e3;
        // Comb picture and curvature against arc length, pieces in turn.
        let mut samples: Vec<plot::CombSample> = Vec::new();
        let mut kappa_s: Vec<plot::Series> = Vec::new();
        let mut s_acc = 0.0;
        for (i, p) in sk.pieces.iter().enumerate() {
            let mut line = Vec::new();
            let mut prev = p.rational.points()[0];
            for k in 0..=80 {
                let d = aesthetic_curves::PlanarCurve::derivs(&p.rational, k as f64 / 80.0);
                samples.push((d.p, d.d1.turn_90() / d.d1.hypot(), d.kappa()));
                s_acc += d.p.distance(prev);
                prev = d.p;
                line.push((s_acc, d.kappa()));
            }
            let mut series = plot::Series::nth(format!("{i}: α {:.2}", p.alpha), line, i);
            series.markers = false;
            kappa_s.push(series);
        }
        let joints = sk.joints();
        let title = format!(
            "{} pieces, deviation {:.3} {unit} (tolerance {:.3} {unit}), curvature jump {:.1e}",
            sk.pieces.len(),
            sk.max_deviation,
            tol,
            sk.max_curvature_jump
        );
        std::fs::write(
            out.join(format!("{name}.svg")),
            plot::comb_svg_in(&samples, &pts, &joints, &title, unit),
        )?;
        std::fs::write(
            out.join(format!("{name}-curvature.svg")),
            plot::fitted_chart(
                "signed curvature of the result (one colour per piece)",
                &format!("arc length ({unit})"),
                &format!("curvature (1/{unit})"),
                &kappa_s,
            ),
        )?;
        html += &format!(
            "<h3>{name}</h3><p>{caption} {} pieces in {ms:.0} ms; largest deviation {:.4} {unit} \
             (tolerance {:.4} {unit}); largest curvature jump {:.1e} of the largest curvature ({}); \
             {}; {} inflections and {} curvature extrema.</p>\n<figure><img src=\"{name}.svg\" alt=\"{name}\"></figure>\n\
             <figure><img src=\"{name}-curvature.svg\" alt=\"curvature\"><figcaption>Curvature \
             against arc length: monotone on each piece, continuous at the joints.\
             </figcaption></figure>\n<table border=\"1\" cellpadding=\"4\"><tr><th>piece</th>\
             <th>kind</th><th>alpha</th><th>curvature at start (1/{unit})</th><th>at end (1/{unit})</th>\
             <th>monotone (exact test)</th></tr>\n",
            sk.pieces.len(),
            sk.max_deviation,
            tol,
            sk.max_curvature_jump,
            if sk.g2 { "G2" } else { "not G2" },
            if sk.all_monotone {
                "every piece curvature-monotone"
            } else {
                "NOT every piece curvature-monotone"
            },
            sk.inflections,
            sk.curvature_extrema
        );
        for (i, p) in sk.pieces.iter().enumerate() {
            html += &format!(
                "<tr><td>{i}</td><td>{}</td><td>{:.4}{}</td><td>{:+.4e}</td><td>{:+.4e}</td><td>{}</td></tr>\n",
                p.kind.as_str(),
                p.alpha,
                if p.alpha_at_bound { " (at its bound)" } else { "" },
                p.end_curvatures.0,
                p.end_curvatures.1,
                p.monotone
            );
        }
        html += "</table>\n";
    }
    Ok(html)
}

/// `lac.fit` on the Prius lines beside the published single-LAC fits.
fn lac_fit_gallery(out: &std::path::Path) -> Result<String> {
    use aesthetic_curves::lac_fit::{fit_lac, LacFitOptions};
    use aesthetic_curves::Point;
    // Nearest distance from each point to a polyline, every chord a candidate.
    let distances = aesthetic_curves::lac_fit::nearest_distances;
    let max_rms = |d: &[f64]| {
        (
            d.iter().copied().fold(0.0, f64::max),
            (d.iter().map(|x| x * x).sum::<f64>() / d.len() as f64).sqrt(),
        )
    };
    let mut rows = String::new();
    let mut at_bound = 0;
    let (mut ours, mut theirs): (Vec<plot::Series>, Vec<plot::Series>) = (vec![], vec![]);
    for (i, line) in aesthetic_curves_data::PRIUS.iter().enumerate() {
        let pts: Vec<Point> = line
            .points()
            .into_iter()
            .map(|[x, y]| Point::new(x, y))
            .collect();
        let t0 = std::time::Instant::now();
        let fit = fit_lac(&pts, LacFitOptions::default())?;
        let ms = t0.elapsed().as_secs_f64() * 1e3;
        let pf = line
            .published_curve(true)
            .ok_or_else(|| anyhow::anyhow!("{}: published fit unreadable", line.name))?;
        let to_pts = |v: Vec<[f64; 2]>| {
            v.into_iter()
                .map(|[x, y]| Point::new(x, y))
                .collect::<Vec<_>>()
        };
        let (m1, r1) = max_rms(&distances(&to_pts(pf.points(3000)), &pts));
        let (m2, r2) = max_rms(&distances(&to_pts(pf.euler_points()), &pts));
        // Curvature against arc length, both from the line's first point.
        let (poly, k) = fit.segment.sample(400)?;
        let mut s = 0.0;
        let mut line_ours = Vec::new();
        for (j, kj) in k.iter().enumerate() {
            if j > 0 {
                s += poly[j].distance(poly[j - 1]);
            }
            line_ours.push((s, kj.abs()));
        }
        let n = 400;
        let length = pf.l * pf.scale;
        let mut line_theirs: Vec<(f64, f64)> = (0..=n)
            .map(|j| {
                let u = j as f64 / n as f64;
                (u * length, pf.curvature(u))
            })
            .collect();
        if pf.case % 2 == 1 {
            // Case 1 lists the curve from its other end.
            line_theirs = line_theirs
                .iter()
                .rev()
                .map(|(x, k)| (length - x, *k))
                .collect();
        }
        at_bound += usize::from(fit.alpha_at_bound);
        let mut a = plot::Series::nth(format!("ps_{}", i + 1), line_ours, i);
        a.markers = false;
        ours.push(a);
        let mut b = plot::Series::nth(format!("ps_{}", i + 1), line_theirs, i);
        b.markers = false;
        theirs.push(b);
        rows += &format!(
            "<tr><td>ps_{}</td><td>{:.3}{}</td><td>{:.3}</td><td>{:.3}</td><td>{:.3}</td>\
             <td>{:.3}</td><td>{:.3}</td><td>{:.2e}</td><td>{:.2e}</td><td>{}</td><td>{ms:.0}</td></tr>\n",
            i + 1,
            fit.alpha,
            if fit.alpha_at_bound { " (bound)" } else { "" },
            pf.alpha,
            fit.max_deviation,
            m1.min(m2),
            fit.rms_deviation,
            r1.min(r2),
            fit.max_curvature,
            pf.max_curvature(),
            if fit.converged { "yes" } else { "no" },
        );
    }
    std::fs::write(
        out.join("lac-fit-ours.svg"),
        plot::fitted_chart(
            "lac.fit: |curvature| along each Prius line",
            "arc length (mm)",
            "|curvature| (1/mm)",
            &ours,
        ),
    )?;
    std::fs::write(
        out.join("lac-fit-published.svg"),
        plot::fitted_chart(
            "Published fits (Graiff Zurita et al. 2023): |curvature|",
            "arc length (mm)",
            "|curvature| (1/mm)",
            &theirs,
        ),
    )?;
    Ok(format!(
        "<h2>One log-aesthetic curve per measured line — lac.fit against the published fits \
         (Graiff Zurita, Kajiwara &amp; Miura 2023)</h2>\n<p>The single LAC segment closest to \
         each Prius line (default objective: the narrowest band, the L8 norm of the \
         point-to-curve distances), held to no more than 1.5 times the curvature of the \
         smoothest spline as close to the points (no end hooks), its ends at the feet of the \
         first and last points. The published fits are rebuilt from their printed parameters \
         (3 decimals), as the continuous curve and as the authors' Euler polyline; the table \
         gives them the better of the two. Distances: nearest point of the curve, in mm.</p>\n\
         <table border=\"1\" cellpadding=\"4\"><tr><th>line</th><th>alpha</th>\
         <th>published alpha</th><th>max distance</th><th>published</th><th>rms distance</th>\
         <th>published</th><th>max |κ| (1/mm)</th><th>published</th><th>converged</th>\
         <th>ms</th></tr>\n{rows}</table>\n<figure><img src=\"lac-fit-ours.svg\" \
         alt=\"curvature of lac.fit\" width=\"48%\"><img src=\"lac-fit-published.svg\" \
         alt=\"curvature of the published fits\" width=\"48%\"><figcaption>Curvature along \
         each line: lac.fit (left), the published fits (right), same colour per line. On \
         lines this shallow alpha is poorly determined: the distances hardly change along it, \
         and {at_bound} of the 5 fits end on the alpha bound ±5 (reported).</figcaption></figure>\n"
    ))
}

/// Comb samples of consecutive Hermite spans, `per` intervals per span.
fn span_samples(
    spans: &[aesthetic_curves::pseudo_spline::HermiteSpan],
    per: usize,
) -> Result<Vec<plot::CombSample>> {
    let mut samples = Vec::new();
    for g in spans {
        let c = g.to_bezier()?;
        for k in 0..=per {
            let d = aesthetic_curves::PlanarCurve::derivs(&c, k as f64 / per as f64);
            let speed = d.d1.hypot();
            let k = d.kappa();
            let nrm = if speed > 0.0 {
                d.d1.turn_90() / speed
            } else {
                aesthetic_curves::Vec2::ZERO
            };
            samples.push((d.p, nrm, if k.is_finite() { k } else { 0.0 }));
        }
    }
    Ok(samples)
}

/// S2's printed Table 4 (length) and Table 5 (area) for n = 3..10, from its 36 x 36 table.
const S2_TABLE4: [f64; 8] = [
    6.18957607, 6.26067766, 6.27774034, 6.27785088, 6.28605010, 6.28591825, 6.28219908, 6.28757066,
];
const S2_TABLE5: [f64; 8] = [
    3.04563765, 3.11345972, 3.13063511, 3.13614662, 3.13830387, 3.13961368, 3.14053616, 3.14105203,
];

/// Independent reference for the unit circle (mpmath, `tools/pseudo_reference.py`): rows
/// "n length area r J".
const CIRCLE_REFERENCE: &str = aesthetic_curves_data::PSEUDO_UNIT_CIRCLE_REFERENCE;

/// S2 Tables 4-5 (unit circle), Fig. 8-12 (Table 1 data) and Fig. 13-17 (Table 2 data):
/// the pseudo-elastic spline against the cubic splines and Hermite curves S2 compares it
/// with, with fairness numbers for every curve.
fn spline_gallery(out: &std::path::Path, quick: bool) -> Result<String> {
    use aesthetic_curves::pseudo_spline::{
        comparison_curve, fairness, pseudo_elastic, Comparison, HermiteSpan, Mode,
    };
    use aesthetic_curves::Point;
    use std::f64::consts::PI;
    let mut html = String::from(
        "<h2>The pseudo-elastic spline through points — Inoue &amp; Shibata (S2)</h2>\n<p>Hermite cubics through the points; each \
         span's tangent lengths minimise the pseudo-energy J = E L² (E = ∫κ²ds, L its length); \
         tangent directions by S2 eq. 11-12. <b>Table mode</b> reads J, r0, r1, L and S from \
         tables over the end angles (288 x 288 nodes, 1.25°, against S2's 36 x 36) and J(θ) \
         from a 1-D table, so a 1000-point curve takes well under a millisecond; \
         <b>exact mode</b> minimises at every span.</p>\n\
         <h3>A closed spline through n points of the unit circle: length and area (S2 Tables 4 and 5)</h3>\n\
         <p>The reference is independent of this library: mpmath at 40 digits \
         (tools/pseudo_reference.py; the exact mode matches it to 1e-7, tested). S2's printed \
         values came from its 36 x 36 table: within 1e-4 where the span's end angle 180°/n \
         lies on its 10° grid (n = 3, 6, 9) and off by 4e-3 to 6e-3 elsewhere (its \
         interpolation); the finer table here stays within 3e-7.</p>\n\
         <table border=\"1\" cellpadding=\"4\"><tr><th>n</th><th>length, table mode</th>\
         <th>reference</th><th>table − ref</th><th>S2 printed</th><th>S2 − ref</th>\
         <th>area, table mode</th><th>reference</th><th>table − ref</th><th>S2 printed</th>\
         <th>S2 − ref</th></tr>\n",
    );
    let reference: Vec<Vec<f64>> = CIRCLE_REFERENCE
        .lines()
        .map(|l| {
            l.split_whitespace()
                .filter_map(|x| x.parse().ok())
                .collect()
        })
        .filter(|v: &Vec<f64>| v.len() >= 3)
        .collect();
    for r in &reference {
        let n = r[0] as usize;
        let pts: Vec<Point> = (0..n)
            .map(|k| {
                let a = 2.0 * PI * k as f64 / n as f64;
                Point::new(a.cos(), a.sin())
            })
            .collect();
        let s = pseudo_elastic(&pts, true, Mode::Table)?;
        let (pl, pa) = (S2_TABLE4[n - 3], S2_TABLE5[n - 3]);
        html += &format!(
            "<tr><td>{n}</td><td>{:.8}</td><td>{:.8}</td><td>{:+.1e}</td><td>{pl:.8}</td>\
             <td>{:+.1e}</td><td>{:.8}</td><td>{:.8}</td><td>{:+.1e}</td><td>{pa:.8}</td>\
             <td>{:+.1e}</td></tr>\n",
            s.length,
            r[1],
            s.length - r[1],
            pl - r[1],
            s.area,
            r[2],
            s.area - r[2],
            pa - r[2]
        );
    }
    html += "</table>\n";
    if !quick {
        // Exact mode on the smallest case (a second or two per point).
        let pts: Vec<Point> = (0..3)
            .map(|k| {
                let a = 2.0 * PI * k as f64 / 3.0;
                Point::new(a.cos(), a.sin())
            })
            .collect();
        let t = std::time::Instant::now();
        let s = pseudo_elastic(&pts, true, Mode::Exact)?;
        html += &format!(
            "<p>Exact mode, n = 3: length {:.9}, area {:.9} (reference {:.9}, {:.9}; {:.1} s).\
             </p>\n",
            s.length,
            s.area,
            reference[0][1],
            reference[0][2],
            t.elapsed().as_secs_f64()
        );
    }
    // The five curves of S2's comparison.
    let methods: Vec<(&str, Option<Comparison>)> = Comparison::ALL
        .iter()
        .map(|m| (m.name(), Some(*m)))
        .chain(std::iter::once(("pseudo-elastic spline", None)))
        .collect();
    let curve = |pts: &[Point], m: Option<Comparison>| -> Result<Vec<HermiteSpan>> {
        Ok(match m {
            Some(m) => comparison_curve(pts, m)?,
            None => pseudo_elastic(pts, false, Mode::Table)?.segments,
        })
    };
    let fair_row = |label: String, spans: &[HermiteSpan]| -> Result<String> {
        let f = fairness(spans)?;
        Ok(format!(
            "<tr><td>{label}</td><td>{:.4}</td><td>{:.4}</td><td>{}</td><td>{:.4}</td></tr>\n",
            f.bending_energy, f.kappa_variation, f.curvature_extrema, f.max_abs_kappa
        ))
    };
    let fair_head = "<table border=\"1\" cellpadding=\"4\"><tr><th>curve</th><th>∫κ²ds</th>\
                     <th>∫(dκ/ds)²ds</th><th>curvature extrema</th><th>max |κ|</th></tr>\n";
    html += "<h3>Nine points with the middle one raised: the five methods compared (S2 Fig. 8-12)</h3>\n<p>Nine points on a line, the middle one \
             raised to Y = 0..5; one picture per method with the six curves. Cubic spline A \
             (uniform parameters, natural ends) wiggles beside the raised point; cubic spline \
             B (chord-length parameters) overshoots; the Hermite curves (tangent length = \
             chord) and the pseudo-elastic spline stay close to the polygon. Fairness \
             numbers below the pictures: curvature extrema by the exact test inside the \
             spans plus sign changes of dκ/ds at the points.</p>\n";
    let ys: Vec<f64> = (0..=5).map(|y| y as f64).collect();
    let mut fair = String::from(fair_head);
    // Per Y: the lowest ∫κ²ds and ∫(dκ/ds)²ds and which curve has it.
    let mut best_energy = vec![(f64::INFINITY, 0usize); ys.len()];
    let mut best_variation = vec![(f64::INFINITY, 0usize); ys.len()];
    for (fig, (name, m)) in methods.iter().enumerate() {
        let mut series = Vec::new();
        let mut dots = Vec::new();
        for (k, &y) in ys.iter().enumerate() {
            let pts: Vec<Point> = (-4..=4)
                .map(|i| Point::new(i as f64, if i == 0 { y } else { 0.0 }))
                .collect();
            let spans = curve(&pts, *m)?;
            if y > 0.0 {
                fair += &fair_row(format!("{name}, Y = {y}"), &spans)?;
                let f = fairness(&spans)?;
                if f.bending_energy < best_energy[k].0 {
                    best_energy[k] = (f.bending_energy, fig);
                }
                if f.kappa_variation < best_variation[k].0 {
                    best_variation[k] = (f.kappa_variation, fig);
                }
            }
            let samples = span_samples(&spans, 24)?;
            series.push(plot::Series::nth(
                format!("Y = {y}"),
                samples.iter().map(|s| (s.0.x, s.0.y)).collect(),
                k,
            ));
            dots.extend(pts);
        }
        let file = format!("s2-fig{}.svg", 8 + fig);
        std::fs::write(
            out.join(&file),
            plot::curves_svg(&format!("S2 Fig. {}: {name}", 8 + fig), &series, &dots),
        )?;
        html += &format!(
            "<figure><img src=\"{file}\" alt=\"S2 Fig. {}\" width=\"70%\"><figcaption>Fig. {}: \
             {name} through the Table 1 points.</figcaption></figure>\n",
            8 + fig,
            8 + fig
        );
    }
    html += &fair;
    html += "</table>\n<p>Lowest bending energy ∫κ²ds, by Y: ";
    let names: Vec<&str> = methods.iter().map(|m| m.0).collect();
    let list = |best: &[(f64, usize)]| -> String {
        best.iter()
            .zip(&ys)
            .filter(|(_, y)| **y > 0.0)
            .map(|(b, y)| format!("Y = {y}: {}", names[b.1]))
            .collect::<Vec<_>>()
            .join("; ")
    };
    html += &list(&best_energy);
    html += ". Lowest ∫(dκ/ds)²ds: ";
    html += &list(&best_variation);
    html += ".</p>\n";
    // Table 2: a zig-zag of four points (S2 Fig. 13-17).
    let t2 = [
        Point::new(0.0, 0.0),
        Point::new(2.0, -0.1),
        Point::new(1.0, -0.1),
        Point::new(3.0, 0.0),
    ];
    html +=
        "<h3>Four points that double back (S2 Fig. 13-17)</h3>\n<p>Four points that double back: \
             (0, 0), (2, -0.1), (1, -0.1), (3, 0). Each curve with its curvature comb.</p>\n";
    let mut fair = String::from(fair_head);
    for (fig, (name, m)) in methods.iter().enumerate() {
        let spans = curve(&t2, *m)?;
        fair += &fair_row(name.to_string(), &spans)?;
        let file = format!("s2-fig{}.svg", 13 + fig);
        std::fs::write(
            out.join(&file),
            plot::comb_svg(
                &span_samples(&spans, 60)?,
                &t2,
                &[],
                &format!("S2 Fig. {}: {name}", 13 + fig),
            ),
        )?;
        html += &format!(
            "<figure><img src=\"{file}\" alt=\"S2 Fig. {}\" width=\"60%\"><figcaption>Fig. {}: \
             {name} through the Table 2 points, with its curvature comb.</figcaption></figure>\n",
            13 + fig,
            13 + fig
        );
    }
    html += &fair;
    html += "</table>\n";
    Ok(html)
}

enum LcgSource {
    Points(Vec<aesthetic_curves::Point>),
    Bezier(AnyBezier),
    Lac(aesthetic_curves::lac::LacSegment),
}

fn lcg(source: LcgSource, json: bool, output: &[PathBuf]) -> Result<()> {
    use aesthetic_curves::lcg;
    let (what, fit) = match &source {
        LcgSource::Points(p) => (
            format!("{} sampled points", p.len()),
            lcg::estimate_from_points(p)?,
        ),
        LcgSource::Bezier(b) => (
            "the Bézier curve (analytic)".to_string(),
            lcg::fit_line(lcg::curve_lcg(b.as_monotone(), 81))?,
        ),
        LcgSource::Lac(seg) => (
            format!("the LAC segment, alpha = {}", seg.standard.alpha()),
            lcg::fit_line(seg.lcg(81)?)?,
        ),
    };
    if json {
        println!(
            "{}",
            serde_json::json!({"alpha": fit.alpha, "r_squared": fit.r_squared,
                "intercept": fit.intercept, "rms_residual": fit.rms_residual,
                "graph": fit.graph.iter().map(|p| [p.log_rho, p.log_rho_ds_drho]).collect::<Vec<_>>()})
        );
    } else {
        println!("logarithmic curvature graph of {what}");
        println!("  alpha (slope)  {:.9}", fit.alpha);
        println!("  intercept      {:.9}", fit.intercept);
        println!("  r squared      {:.12}", fit.r_squared);
        println!("  rms residual   {:.3e}", fit.rms_residual);
        println!("  graph points   {}", fit.graph.len());
    }
    for path in output {
        plot::write_picture(path, &plot::lcg_chart(&fit, &format!("LCG of {what}")))?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

struct Example {
    name: &'static str,
    text: &'static str,
    points: Vec<(f64, f64)>,
    weights: Option<Vec<f64>>,
}

/// Control polygon whose edges are the previous edge scaled by `scale` and turned by `turn`.
fn class_a_polygon(degree: usize, scale: f64, turn: f64) -> Vec<(f64, f64)> {
    let mut p = (0.0, 0.0);
    let mut e = (1.0, 0.0);
    let mut out = vec![p];
    for _ in 0..degree {
        p = (p.0 + e.0, p.1 + e.1);
        out.push(p);
        let (c, s) = (turn.cos(), turn.sin());
        e = (scale * (c * e.0 - s * e.1), scale * (s * e.0 + c * e.1));
    }
    out
}

fn demo(out: &std::path::Path, quick: bool) -> Result<()> {
    std::fs::create_dir_all(out).with_context(|| format!("creating {}", out.display()))?;
    let pb = indicatif::ProgressBar::new(6);
    pb.set_style(
        indicatif::ProgressStyle::with_template("{bar:30} {pos}/{len} {msg}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    pb.set_message("curvature monotonicity examples");
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let examples = vec![
        Example {
            name: "bump",
            text: "A symmetric cubic: curvature peaks in the middle (t = 0.5), so it is not monotone.",
            points: vec![(0.0, 0.0), (1.0, 1.0), (2.0, 1.0), (3.0, 0.0)],
            weights: None,
        },
        Example {
            name: "spiral",
            text: "A cubic whose control polygon edges shrink by 0.6 and turn by 25 degrees: curvature increases monotonically.",
            points: class_a_polygon(3, 0.6, 25f64.to_radians()),
            weights: None,
        },
        Example {
            name: "quintic",
            text: "A wavy quintic: the exact test finds every curvature extremum (circled).",
            points: vec![(0.0, 0.0), (1.0, 0.8), (2.0, -0.4), (3.0, 1.2), (4.0, 0.2), (5.0, 1.0)],
            weights: None,
        },
        Example {
            name: "arc",
            text: "A rational quadratic quarter circle: dkappa/ds is identically zero, monotone (constant).",
            points: vec![(1.0, 0.0), (1.0, 1.0), (0.0, 1.0)],
            weights: Some(vec![1.0, h, 1.0]),
        },
    ];
    let mut html = String::from(
        "<!doctype html><html><head><meta charset=\"utf-8\"><title>aesthetic-curves demo</title>\
         <style>body{font-family:sans-serif;max-width:1000px;margin:auto}figure{margin:1em 0}\
         img{max-width:100%;border:1px solid #ddd}pre{background:#f6f6f6;padding:8px}</style>\
         </head><body><h1>aesthetic-curves: gallery</h1>\n\
         <p>Every picture and number on this page was computed by this build.</p>\n",
    );
    html += "<h2>Is the curvature monotone? The exact test on Bézier curves — Katayama, Yoshida &amp; Saito (S1)</h2>\n";
    for ex in &examples {
        let pts: Vec<_> = ex
            .points
            .iter()
            .map(|&(x, y)| aesthetic_curves::Point::new(x, y))
            .collect();
        let curve = AnyBezier::new(pts.clone(), ex.weights.clone())?;
        let r = curve.as_monotone().curvature_monotone()?;
        let verdict = if r.monotone {
            format!("monotone ({})", r.trend.map(|t| t.as_str()).unwrap_or(""))
        } else {
            format!(
                "not monotone; extrema at t = {}",
                r.extrema
                    .iter()
                    .map(|t| format!("{t:.6}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        };
        let file = format!("{}.svg", ex.name);
        std::fs::write(
            out.join(&file),
            plot::curve_with_comb(&curve, &pts, &r.extrema, &format!("{}: {verdict}", ex.name)),
        )?;
        html += &format!(
            "<figure><img src=\"{file}\" alt=\"{}\"><figcaption>{} Exact test: {verdict} \
             (Bernstein polynomial of degree {}). Blue: curvature comb; circles: curvature \
             extrema.</figcaption></figure>\n",
            ex.name, ex.text, r.test_degree
        );
    }
    pb.inc(1);
    pb.set_message("log-aesthetic segments");
    html += "<h2>Log-aesthetic segments of every alpha in one control triangle — Yoshida &amp; Saito 2006, S0 §3</h2>\n";
    let mut kappa_series = Vec::new();
    let tri = [
        aesthetic_curves::Point::new(0.0, 0.0),
        aesthetic_curves::Point::new(10.0, 0.0),
        aesthetic_curves::Point::new(16.0, 9.0),
    ];
    for alpha in [-1.0, 0.0, 1.0, 2.0] {
        let seg = aesthetic_curves::lac::LacSegment::new(alpha, tri)?;
        let (points, kappa) = seg.sample(121)?;
        let mut arc = 0.0;
        let mut series = Vec::with_capacity(points.len());
        for (i, k) in kappa.iter().enumerate() {
            if i > 0 {
                arc += (points[i] - points[i - 1]).hypot();
            }
            series.push((arc, *k));
        }
        let mut se = plot::Series::nth(format!("alpha = {alpha}"), series, kappa_series.len());
        se.markers = false;
        kappa_series.push(se);
        let file = format!("lac-alpha{alpha}.svg");
        let caption = format!("alpha = {alpha}: lambda = {:.6}", seg.lambda());
        std::fs::write(
            out.join(&file),
            plot::comb_svg(
                &plot::polyline_samples(&points, &kappa),
                &tri,
                &[],
                &caption,
            ),
        )?;
        html += &format!(
            "<figure><img src=\"{file}\" alt=\"LAC alpha {alpha}\"><figcaption>The log-aesthetic \
             segment of alpha = {alpha} through the control triangle (0,0), (10,0), (16,9): \
             lambda = {:.9}, arc length {:.6}; curvature falls monotonically from the start \
             (comb).</figcaption></figure>\n",
            seg.lambda(),
            seg.arc_length()?
        );
    }
    std::fs::write(
        out.join("lac-curvature.svg"),
        plot::fitted_chart(
            "Curvature along the four LAC segments",
            "arc length (length units of the triangle)",
            "curvature (1 / length unit)",
            &kappa_series,
        ),
    )?;
    html += "<figure><img src=\"lac-curvature.svg\" alt=\"curvature against arc length\">\
             <figcaption>Curvature against arc length of the four segments above: monotone \
             in every case; alpha = -1 (clothoid) is the straight line.</figcaption></figure>\n";
    pb.inc(1);
    pb.set_message("rational cubics for LAC segments");
    html += &approx_gallery(out)?;
    pb.inc(1);
    pb.set_message("pseudo-elastic splines");
    html += &spline_gallery(out, quick)?;
    pb.inc(1);
    pb.set_message("pen input to G2 aesthetic curves");
    html += &inflection_gallery(out)?;
    html += &sketch_gallery(out)?;
    html += &lac_fit_gallery(out)?;
    pb.inc(1);
    pb.set_message("timing the monotonicity tests");
    let cfg = if quick {
        bench::BenchConfig {
            curves: 200,
            rounds: 3,
            round_time: Duration::from_millis(10),
            ..Default::default()
        }
    } else {
        bench::BenchConfig::default()
    };
    let rows = bench::run(&cfg);
    pb.inc(1);
    pb.finish_and_clear();
    let conditions = bench::conditions(&cfg);
    std::fs::write(
        out.join("bench-monotone.svg"),
        bench::chart(&rows, &conditions),
    )?;
    html += &format!(
        "<h3>How long each test takes: exact test against sampling (S1 Fig. 4)</h3>\
         <figure><img src=\"bench-monotone.svg\" alt=\"timing chart\"><figcaption>Time per curve, \
         measured while this gallery was written: {conditions}; the same curves for every \
         method. The ratios in the table hold for this run on this machine only (compare them \
         within one run). The sampling test's cost grows with N and it still misjudges \
         curves whose extrema fall between samples (column 'disagreements').</figcaption>\
         </figure><pre>{}</pre>\n",
        bench::table(&rows)
    );
    html += "<h2 id=\"papers\">The papers cited on this page</h2>\n<ul>\
             <li><b>S0</b>: N. Yoshida and T. Saito, Approximation of an aesthetic curve segment \
             by a rational cubic Bézier curve segment (Japanese; English version: Quasi-aesthetic \
             curves in rational cubic Bézier forms, Computer-Aided Design and Applications 4, \
             2007).</li>\
             <li><b>S1</b>: R. Katayama, N. Yoshida and T. Saito, On the monotonicity of the \
             curvature of polynomial curves (Japanese).</li>\
             <li><b>S2</b>: H. Inoue and Y. Shibata, Pseudo-spline curve (Japanese, Gunma \
             University).</li>\
             <li><b>S3</b>: a short Japanese paper on the stable approximation of log-aesthetic \
             curves by rational cubic Bézier curves.</li>\
             <li><b>S4</b>: K. T. Miura, M. Yagi, Y. Kawata and M. Fujisawa, Input of aesthetic \
             curve segments with inflection end points and generation of aesthetic curves with \
             G2 continuity (Japanese).</li>\
             <li>Yoshida &amp; Saito 2006: Interactive aesthetic curve segments, The Visual \
             Computer 22, 896-905.</li>\
             <li>Graiff Zurita, Kajiwara &amp; Miura 2023: Fairing of planar curves to \
             log-aesthetic curves, Japan J. Indust. Appl. Math. 40, 1203-1219 (the Prius key \
             lines, MIT licence).</li></ul>\n<p>Full citations, and what the project takes from \
             each, in the repository's docs/bibliography.md; \"docs/math.md §N\" refers to \
             section N of docs/math.md.</p>\n";
    html += "</body></html>\n";
    let index = out.join("index.html");
    std::fs::write(&index, html)?;
    println!("gallery written: {}", index.display());
    Ok(())
}
