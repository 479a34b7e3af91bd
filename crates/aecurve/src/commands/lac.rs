//! `aecurve lac` and `aecurve lac --inflection`: a log-aesthetic segment (or one with an
//! inflection end) from its control triangle, with plots and exports.

use crate::cli::count;
use crate::cli::CurveOutput;
use crate::commands::control_triangle;
use crate::commands::Command;
use aecurve::plot;
use aesthetic_curves::approx::{self, ApproxOptions, RationalSpline};
use aesthetic_curves::curve::MAX_NURBS_PIECES;
use aesthetic_curves::lac::{LacInflectionSegment, LacSegment};
use aesthetic_curves::Curve;
use anyhow::Result;

/// The two kinds of segment the command makes.
enum Segment {
    Lac(LacSegment),
    Inflection(LacInflectionSegment),
}

impl Segment {
    fn as_curve(&self) -> &dyn Curve {
        match self {
            Segment::Lac(s) => s,
            Segment::Inflection(s) => s,
        }
    }

    /// The protocol's result (`lac.segment` or `lac.inflection_segment`).
    fn json(&self, samples: usize) -> Result<serde_json::Value> {
        Ok(match self {
            Segment::Lac(s) => {
                serde_json::to_value(aecurve::protocol::lac_segment_json(s, samples)?)?
            }
            Segment::Inflection(s) => {
                serde_json::to_value(aecurve::protocol::lac_inflection_json(s, samples)?)?
            }
        })
    }

    /// The summary's lines.
    fn summary(&self) -> Result<String> {
        Ok(match self {
            Segment::Lac(s) => {
                let (k0, k1) = s.end_curvatures()?;
                format!(
                    "log-aesthetic segment, alpha = {}\n  turning angle  {:.6} deg\n  \
                     lambda         {:.12}\n  arc length     {:.9}\n  \
                     curvature      {k0:.9} at the start, {k1:.9} at the end\n  \
                     high-curvature end at {}\n",
                    s.standard().alpha(),
                    s.theta_d().to_degrees(),
                    s.lambda(),
                    s.arc_length()?,
                    if s.reversed() {
                        "the end point"
                    } else {
                        "the start point"
                    }
                )
            }
            Segment::Inflection(s) => format!(
                "log-aesthetic segment with an inflection at the start point\n  \
                 alpha          {:.10}\n  turning angle  {:.6} deg\n  arc length     {:.9}\n  \
                 curvature      0 at the start, {:.9} at the end\n",
                s.alpha(),
                s.theta_d().to_degrees(),
                s.arc_length(),
                s.end_curvature()
            ),
        })
    }

    fn caption(&self) -> String {
        match self {
            Segment::Lac(s) => format!(
                "LAC alpha = {}, lambda = {:.6}",
                s.standard().alpha(),
                s.lambda()
            ),
            Segment::Inflection(s) => {
                format!("LAC with an inflection end, alpha = {:.6}", s.alpha())
            }
        }
    }

    /// Rational cubics within `tolerance`, G2 at the joints, every piece's curvature proven
    /// monotone: a LAC segment has no exact rational form. With an inflection end, the first
    /// cubic has zero curvature there and the rest is an ordinary LAC segment.
    fn rational_spline(&self, tolerance: f64) -> aesthetic_curves::Result<RationalSpline> {
        let opts = ApproxOptions::default();
        match self {
            Segment::Lac(s) => approx::fit_rational_spline(s, tolerance, MAX_NURBS_PIECES, &opts),
            Segment::Inflection(s) => {
                approx::fit_inflection_spline(s, tolerance, MAX_NURBS_PIECES, &opts)
            }
        }
    }
}

/// `aecurve lac`: with `alpha`, a LAC segment; without, the segment with an inflection at
/// the first control point (α < 0 from the triangle).
pub(crate) fn lac(
    alpha: Option<f64>,
    control: &str,
    samples: usize,
    out: &CurveOutput,
) -> Result<()> {
    let pts = control_triangle(control)?;
    let samples = samples.max(2);
    let seg = match alpha {
        Some(a) => Segment::Lac(LacSegment::new(a, pts)?),
        None => Segment::Inflection(LacInflectionSegment::new(pts)?),
    };
    if out.json {
        println!("{}", seg.json(samples)?);
    } else {
        print!("{}", seg.summary()?);
    }
    let caption = seg.caption();
    let comb = plot::curve_samples(seg.as_curve(), samples)?;
    // CAD formats get the segment as rational cubics within 1e-7 of its triangle's size:
    // the exact rational geometry of that approximation, reported on stderr.
    let tolerance = 1e-7
        * pts
            .iter()
            .map(|p| (*p - pts[0]).hypot())
            .fold(0.0, f64::max);
    let mut cad = || {
        let sp = seg.rational_spline(tolerance)?;
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
        Ok(sp.nurbs)
    };
    out.write(
        "log_aesthetic_segment",
        &mut cad,
        &comb,
        &caption,
        &mut || Ok(plot::comb_svg(&comb, &pts, &[], &caption)),
    )
}

/// The arguments of `aecurve lac` (the command's help is its entry in `cli.rs`).
#[derive(clap::Args)]
pub(crate) struct Args {
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
}

impl Command for Args {
    fn curve_output(&self) -> Option<&CurveOutput> {
        Some(&self.out)
    }

    fn run(self) -> Result<()> {
        // --inflection and --alpha exclude each other (clap): no alpha is the inflection
        // segment.
        let alpha = self.alpha.filter(|_| !self.inflection);
        lac(alpha, &self.control, self.samples, &self.out)
    }
}
