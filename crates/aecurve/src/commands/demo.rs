//! `aecurve demo`: the main job on built-in example data: every paper's gallery, written
//! as one HTML page with its pictures.

use crate::commands::Command;
use crate::gallery::{
    approx::approx_gallery,
    inflection::inflection_gallery,
    lac_fit::lac_fit_gallery,
    outline::outline_gallery,
    sketch::sketch_gallery,
    spline::{g1_g2_gallery, spline_gallery},
};
use aecurve::any_bezier::AnyBezier;
use aecurve::{bench, plot};
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use std::time::Duration;

pub(crate) struct Example {
    name: &'static str,
    text: &'static str,
    points: Vec<(f64, f64)>,
    weights: Option<Vec<f64>>,
}

/// Control polygon whose edges are the previous edge scaled by `scale` and turned by `turn`.
pub(crate) fn class_a_polygon(degree: usize, scale: f64, turn: f64) -> Vec<(f64, f64)> {
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

pub(crate) fn demo(out: &std::path::Path, quick: bool) -> Result<()> {
    std::fs::create_dir_all(out).with_context(|| format!("creating {}", out.display()))?;
    let pb = aecurve::progress::bar(6, "", true);
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
        let aesthetic_curves::Polyline { points, kappa } = seg.sample(121)?;
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
                &plot::curve_samples(&seg, points.len())?,
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
    html += &g1_g2_gallery(out)?;
    pb.inc(1);
    pb.set_message("pen input to G2 aesthetic curves");
    html += &inflection_gallery(out)?;
    html += &sketch_gallery(out)?;
    html += &lac_fit_gallery(out)?;
    html += &outline_gallery(out)?;
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

/// The arguments of `aecurve demo` (the command's help is its entry in `cli.rs`).
#[derive(clap::Args)]
pub(crate) struct Args {
    /// Output folder.
    #[arg(long, default_value = "demo-out")]
    out: PathBuf,
    /// Smaller benchmark (for CI smoke runs).
    #[arg(long)]
    quick: bool,
}

impl Command for Args {
    fn outputs(&self) -> Vec<&Path> {
        Vec::new()
    }

    fn run(self) -> Result<()> {
        demo(&self.out, self.quick)
    }
}
