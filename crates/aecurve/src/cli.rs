//! The command line of `aecurve` (`clap` types and argument parsers).

use crate::commands::{
    approx, batch, bench, check, demo, editor, fix, lac, lcg, monotone, schema, sketch, spline,
    Command,
};
use anyhow::Result;
use clap::{Parser, Subcommand};
use std::path::{Path, PathBuf};

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

/// The commands: each one's help (its doc comment here), its name and its arguments, which
/// live in its own file under `commands/` with its [`Command`] impl. This list is the whole
/// dispatch: adding a command is its file and one entry here.
macro_rules! commands {
    ($($(#[$doc:meta])* $name:ident($args:ty),)*) => {
        #[derive(Subcommand)]
        pub(crate) enum Cmd {
            $($(#[$doc])* $name($args),)*
        }

        impl Cmd {
            /// Every file the command will write (their folders are made before it runs).
            pub(crate) fn outputs(&self) -> Vec<&Path> {
                match self {
                    $(Cmd::$name(a) => a.outputs(),)*
                }
            }

            /// Refuses what the command could not write, before any work.
            pub(crate) fn check(&self) -> Result<()> {
                match self {
                    $(Cmd::$name(a) => a.check(),)*
                }
            }

            /// Runs the command.
            pub(crate) fn run(self) -> Result<()> {
                match self {
                    $(Cmd::$name(a) => a.run(),)*
                }
            }
        }
    };
}

commands! {
    /// JSON Lines requests on stdin, one response line per request on stdout.
    Batch(batch::Args),
    /// Is the curvature of one Bézier curve monotone?
    Monotone(monotone::Args),
    /// A log-aesthetic segment in a control triangle: summary, and the curve with its
    /// curvature comb (SVG) with -o.
    Lac(lac::Args),
    /// The logarithmic curvature graph and alpha: of a point sequence (--points or
    /// --input), of a LAC segment (--alpha and --control) or of a Bézier curve (--bezier).
    Lcg(lcg::Args),
    /// One rational cubic (or, with --tolerance, a rational cubic B-spline) for a LAC
    /// segment: G2 ends, curvature proven monotone, globally optimal in its family.
    Approx(approx::Args),
    /// A spline through points from a file (CSV rows "x,y" or a JSON array of pairs): by
    /// default the G2 log-aesthetic spline (`--kind lac`: LAC pieces of one alpha, G2 at
    /// every smooth point, corners where asked), or S2's pseudo-elastic spline
    /// (`--kind pseudo-elastic`: G1, from its tables); -o writes the curve with its comb.
    Spline(spline::Args),
    /// Pen input to a G2 aesthetic curve (S4 §3): B-spline, pieces at inflections and
    /// curvature maxima, one LAC segment per piece, G2 fairing, one rational cubic per
    /// piece. Points from a file: CSV rows "x,y", a JSON array of pairs, or an SVG path
    /// (path data, or an SVG document whose first path is read).
    Sketch(sketch::Args),
    /// Benchmarks.
    Bench(bench::Args),
    /// Check the curves of a font (.ttf, .otf, a .ufo folder), an SVG or a DXF drawing
    /// exactly: per segment,
    /// curvature monotone or not, its extrema, inflections and largest curvature; per join,
    /// the tangent break and curvature jump; the places most worth a look first.
    Check(check::Args),
    /// Repair a UFO source, a designspace's masters or an SVG file and write it back: every
    /// smooth join between two cubics moved towards G2 by sliding its handles along their
    /// tangents (tangents, and so G1, kept), no outline further than the tolerance from
    /// the original, coordinates on the grid, and no join and no cubic left worse than it was (the exact
    /// test decides extrema). The same glyphs, contours and points are written; contours
    /// with quadratic segments are left alone and listed. In a designspace, the masters are
    /// held together: no instance half way between two masters ends worse either
    /// (interpolation compatibility kept).
    Fix(fix::Args),
    /// Write the gallery of examples (HTML + SVG) to a folder.
    Demo(demo::Args),
    /// The interactive editor in the browser: a local server on 127.0.0.1 only (LAC
    /// segments, inflection segments, pseudo-elastic splines, sketches, Bézier curves).
    Editor(editor::Args),
    /// The JSON Schema (draft 2020-12) of the protocol, from its request and response
    /// types: every op's request and response (`x-ops`), any request line (the document),
    /// any response line (`$defs/Response`).
    Schema(schema::Args),
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
