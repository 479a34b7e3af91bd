//! The command line of `aecurve` (`clap` types and argument parsers).

use aecurve::batch;
use anyhow::Result;
use clap::{Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

#[derive(Parser)]
#[command(
    name = "aecurve",
    version,
    about = "Aesthetic curves: checks, batch protocol, benchmarks, plots",
    after_help = "Papers cited as S0-S4 and the sections cited as docs/math.md §N are in the \
                  repository's docs/ folder (bibliography.md, math.md); the JSON protocol is \
                  docs/protocol.md."
)]
pub(crate) struct Cli {
    #[command(subcommand)]
    pub(crate) cmd: Cmd,
}

#[derive(Subcommand)]
pub(crate) enum Cmd {
    /// JSON Lines requests on stdin, one response line per request on stdout.
    Batch {
        /// Largest accepted request line in bytes (1 to 1 GiB).
        #[arg(long, default_value_t = batch::DEFAULT_MAX_LINE, value_parser = count::<1, 1_073_741_824>)]
        max_line_bytes: usize,
        /// Wall-clock budget of one request in seconds (1 to 86,400): longer work stops
        /// and the request gets a `timeout` error.
        #[arg(long, default_value_t = batch::DEFAULT_TIMEOUT_SECS, value_parser = count::<1, 86_400>)]
        timeout_secs: usize,
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
        #[command(flatten)]
        out: CurveOutput,
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
        #[command(flatten)]
        out: CurveOutput,
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
        #[command(flatten)]
        out: CurveOutput,
        /// Write the error map over (f0, f1) with the monotone region (S3 Fig. 3 and 5).
        #[arg(long)]
        map: Option<PathBuf>,
        /// Cells per axis of the error map (2 to 2,000).
        #[arg(long, default_value_t = 100, value_parser = count::<2, 2000>)]
        map_cells: usize,
    },
    /// A spline through points from a file (CSV rows "x,y" or a JSON array of pairs): by
    /// default the G2 log-aesthetic spline (`--kind lac`: LAC pieces of one alpha, G2 at
    /// every smooth point, corners where asked), or S2's pseudo-elastic spline
    /// (`--kind pseudo-elastic`: G1, from its tables); -o writes the curve with its comb.
    Spline {
        /// The points file.
        input: PathBuf,
        /// Closed curve through all points.
        #[arg(long)]
        closed: bool,
        /// Which spline: the G2 log-aesthetic one or S2's pseudo-elastic (G1) one.
        #[arg(long, default_value = "lac", value_parser = ["lac", "pseudo-elastic"])]
        kind: String,
        /// Alpha of the log-aesthetic spline's pieces (-1: clothoids; within ±1000).
        #[arg(long, default_value_t = -1.0, allow_hyphen_values = true)]
        alpha: f64,
        /// Corner points of the log-aesthetic spline, by index ("0,4").
        #[arg(long, value_delimiter = ',')]
        corners: Vec<usize>,
        /// Pseudo-elastic segment values from the shipped tables (fast) or by direct
        /// minimisation.
        #[arg(long, default_value = "table", value_parser = ["table", "exact"])]
        mode: String,
        #[command(flatten)]
        out: CurveOutput,
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
        /// Take the stroke as a contour: corners found, straight runs as lines, a stroke
        /// that ends at its start closed (docs/math.md §6.1; the protocol's sketch.contour).
        #[arg(long)]
        contour: bool,
        #[command(flatten)]
        out: CurveOutput,
    },
    /// Benchmarks.
    Bench {
        #[command(subcommand)]
        what: BenchCmd,
    },
    /// Check the curves of a font (.ttf, .otf, a .ufo folder), an SVG or a DXF drawing
    /// exactly: per segment,
    /// curvature monotone or not, its extrema, inflections and largest curvature; per join,
    /// the tangent break and curvature jump; the places most worth a look first.
    Check {
        /// The file.
        file: PathBuf,
        /// Only these glyphs or SVG element ids (repeatable).
        #[arg(long = "select", alias = "glyphs")]
        select: Vec<String>,
        /// Print everything as JSON instead of the summary.
        #[arg(long)]
        json: bool,
        /// How many findings the summary lists.
        #[arg(long, default_value_t = 20)]
        top: usize,
        /// Write an HTML report: a picture per glyph or path (curve, comb, extrema,
        /// inflections, flagged joins), the worst first.
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Most pictures in the report.
        #[arg(long, default_value_t = 200)]
        pictures: usize,
        /// For every cubic whose curvature is not monotone, suggest handle lengths that make
        /// it monotone (end points and tangent directions kept), moving it by at most this
        /// (file units: font units for a font).
        #[arg(long)]
        suggest: Option<f64>,
        /// The thresholds of the verdicts and the findings.
        #[command(flatten)]
        thresholds: Thresholds,
    },
    /// Repair a UFO source, a designspace's masters or an SVG file and write it back: every
    /// smooth join between two cubics moved towards G2 by sliding its handles along their
    /// tangents (tangents, and so G1, kept), no outline further than the tolerance from
    /// the original, coordinates on the grid, and no join and no cubic left worse than it was (the exact
    /// test decides extrema). The same glyphs, contours and points are written; contours
    /// with quadratic segments are left alone and listed. In a designspace, the masters are
    /// held together: no instance half way between two masters ends worse either
    /// (interpolation compatibility kept).
    Fix {
        /// The UFO source (a .ufo folder), a .designspace file, or an SVG file.
        input: PathBuf,
        /// Where to write the result (a new .ufo folder, .svg file, or .designspace file:
        /// its masters are written beside it at the same relative paths).
        #[arg(short, long)]
        output: PathBuf,
        /// How far the outline may move (font units): every segment within this of the
        /// original at equal parameters. On-curve points move at most this much; a handle
        /// may move further (alone up to 9/4 of it: it pulls its cubic by at most 4/9 of
        /// its own move).
        #[arg(long, default_value_t = 2.0)]
        tolerance: f64,
        /// The coordinates' grid (default 1 for a UFO: integer font units; for an SVG
        /// 0.0001 user units, the precision moved numbers are written with).
        #[arg(long)]
        grid: Option<f64>,
        /// Leave curvature hooks and extra extrema alone (by default each cubic with a hook
        /// within 5 % of an end, or several extrema, gets monotone handle lengths first where
        /// they exist within the tolerance).
        #[arg(long)]
        no_bumps: bool,
        /// Leave the smooth joins alone (only the bumps).
        #[arg(long)]
        no_harmonize: bool,
        /// Also move the on-curve point of a smooth join along the line of its two handles
        /// (the handles stay, so the curvature elsewhere does not change; within the
        /// tolerance).
        #[arg(long)]
        move_points: bool,
        /// Print every change as JSON instead of the summary.
        #[arg(long)]
        json: bool,
        /// Also write an HTML page of the changed glyphs or paths, before and after side by
        /// side with their curvature combs and the moved points marked.
        #[arg(long, value_name = "HTML")]
        report: Option<PathBuf>,
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
pub(crate) fn count<const LO: usize, const HI: usize>(s: &str) -> Result<usize, String> {
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
pub(crate) fn millis(s: &str) -> Result<u64, String> {
    count::<1, 60_000>(s).map(|v| v as u64)
}

/// A positive finite number (a tolerance).
pub(crate) fn positive(s: &str) -> Result<f64, String> {
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
pub(crate) fn parse_timeout(s: &str) -> Result<f64, String> {
    let v: f64 = s
        .parse()
        .map_err(|_| format!("{s:?} is not a number of seconds"))?;
    if (0.1..=600.0).contains(&v) {
        Ok(v)
    } else {
        Err(format!("{v} s is outside 0.1 to 600 s"))
    }
}

/// The outputs of every command that makes one curve (`monotone`, `lac`, `approx`,
/// `spline`, `sketch`), written by [`crate::commands::CurveOutput::write`].
#[derive(clap::Args)]
pub(crate) struct CurveOutput {
    /// Print the protocol's JSON result instead of the summary.
    #[arg(long)]
    pub(crate) json: bool,
    /// Write the curve, by extension (repeatable): .svg (cubic Béziers within 1e-6 of its
    /// size, in its own coordinates, with its curvature comb); .png (a picture with the comb
    /// and the control polygon or input points); .dxf, .step/.stp, .iges/.igs, .json
    /// (the rational geometry of the command's curve, exactly: the Bézier curve, the
    /// rational fit, the spline, the sketch; `lac` writes its segment as G2 rational cubics
    /// within 1e-7 of its size, each proven monotone).
    #[arg(short, long)]
    pub(crate) output: Vec<PathBuf>,
    /// Also write the curve's curvature against arc length (.svg or .png).
    #[arg(long)]
    pub(crate) curvature_plot: Option<PathBuf>,
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
    /// The pseudo-elastic spline in table mode on the point sets, against a tenth of
    /// libspiro's times (the ratio itself: `cargo bench --features spiro-bench --bench
    /// spiro_compare` in crates/aesthetic-curves, with libspiro installed).
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

#[derive(Clone, Copy, ValueEnum, PartialEq)]
pub(crate) enum Method {
    Exact,
    Sampling,
}

/// `check`'s thresholds (the library's `OutlineOptions`).
#[derive(clap::Args, Debug, Clone, Copy)]
pub struct Thresholds {
    /// A join whose tangents differ by at most this (degrees) is G1 (plus what the
    /// integer grid's rounding can make, for a font).
    #[arg(long, default_value_t = 0.05)]
    pub g1_angle: f64,
    /// A G1 join whose relative curvature jump is under this is G2 (0.05: 5 %).
    #[arg(long, default_value_t = 0.05)]
    pub g2_jump: f64,
    /// Breaks above G1 and under this (degrees) are listed as probably meant smooth.
    #[arg(long, default_value_t = 3.0)]
    pub near_break: f64,
    /// Non-monotone segments whose curvature detour is under this share of their largest
    /// curvature are not listed (0.05: 5 %; a cubic standing for a circular arc varies by a
    /// few per cent).
    #[arg(long, default_value_t = 0.05)]
    pub min_bump: f64,
}

impl Thresholds {
    /// The library's options (the grid and the suggestion set apart).
    pub fn options(&self) -> anyhow::Result<aesthetic_curves::outline::OutlineOptions> {
        aesthetic_curves::outline::Thresholds {
            g1_angle_degrees: self.g1_angle,
            g2_jump: self.g2_jump,
            near_break_degrees: self.near_break,
            min_bump: self.min_bump,
        }
        .options(0.0)
        .map_err(|e| match e {
            aesthetic_curves::Error::InvalidInput { field, message } => {
                anyhow::anyhow!("--{}: {message}", field.replace('_', "-"))
            }
            e => e.into(),
        })
    }
}
