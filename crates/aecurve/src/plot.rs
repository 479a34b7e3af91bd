//! SVG plots: line charts (curvature plots, the LCG, the timing comparison) drawn by
//! `plotters` with the shipped DejaVu Sans measuring the text; curves with their control
//! polygon and curvature comb, and the S3 error map, written as SVG directly.

use crate::any_bezier::AnyBezier;
use std::fmt::Write;

/// One line of a chart.
#[derive(Clone)]
pub struct Series {
    /// Legend text.
    pub name: String,
    /// (x, y) points, in order.
    pub points: Vec<(f64, f64)>,
    /// CSS colour.
    pub color: &'static str,
    /// Dashed line.
    pub dashed: bool,
    /// Draw the polyline through the points.
    pub line: bool,
    /// Draw a dot at each point.
    pub markers: bool,
}

impl Series {
    /// Series number `i` of a chart: its own colour ([`series_style`]).
    pub fn nth(name: impl Into<String>, points: Vec<(f64, f64)>, i: usize) -> Self {
        let (color, dashed) = series_style(i);
        Series {
            dashed,
            ..Series::new(name, points, color)
        }
    }

    /// A solid line with a dot at each point.
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>, color: &'static str) -> Self {
        Series {
            name: name.into(),
            points,
            color,
            dashed: false,
            line: true,
            markers: true,
        }
    }
}

/// Distinct colours for series (twelve, no two alike; charts with more series than
/// colours dash the second round).
pub const PALETTE: [&str; 12] = [
    "#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf",
    "#7f7f7f", "#bcbd22", "#393b79", "#000000",
];

/// The colour of series `i`, and whether it must be dashed to stay distinct.
pub fn series_style(i: usize) -> (&'static str, bool) {
    (PALETTE[i % PALETTE.len()], i >= PALETTE.len())
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

fn fmt_tick(v: f64) -> String {
    fmt_tick_in(v, 0.0)
}

/// [`fmt_tick`] on an axis that spans `span`: a tick within a billionth of the span of 0 is
/// the 0 that rounding in the tick placement missed (not "-3.3889e-18").
fn fmt_tick_in(v: f64, span: f64) -> String {
    if v == 0.0 || v.abs() <= 1e-9 * span.abs() {
        "0".into()
    } else if v.abs() >= 1e4 || v.abs() < 1e-2 {
        // Enough digits to tell neighbouring ticks apart (3.5e-4 next to 4e-4), no more.
        let s = format!("{v:.5e}");
        let (mant, exp) = s.split_once('e').unwrap_or((&s, "0"));
        let mant = mant.trim_end_matches('0').trim_end_matches('.');
        format!("{mant}e{exp}")
    } else {
        let s = format!("{v:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

/// A value with three significant digits, for labels.
fn fmt_sig(v: f64) -> String {
    if v != 0.0 && (v.abs() >= 1e4 || v.abs() < 1e-2) {
        format!("{v:.2e}")
    } else {
        format!("{}", (v * 1000.0).round() / 1000.0)
    }
}

/// A line chart with axes, ticks, grid and legend. `log_y` plots log10(y) with decade ticks;
/// otherwise a y range that is all positive starts at zero.
pub fn line_chart(
    title: &str,
    xlabel: &str,
    ylabel: &str,
    series: &[Series],
    log_y: bool,
) -> String {
    let axes = Axes {
        title,
        xlabel,
        ylabel,
        log_y,
        y_from_zero: true,
    };
    chart(&axes, series)
}

/// Like [`line_chart`], the y range fitted to the data (no forced zero).
pub fn fitted_chart(title: &str, xlabel: &str, ylabel: &str, series: &[Series]) -> String {
    let axes = Axes {
        title,
        xlabel,
        ylabel,
        log_y: false,
        y_from_zero: false,
    };
    chart(&axes, series)
}

/// The frame of a chart: title (its further lines are subtitles), axis labels, log10 y
/// (decade ticks), and whether an all-positive y range starts at zero.
struct Axes<'a> {
    title: &'a str,
    xlabel: &'a str,
    ylabel: &'a str,
    log_y: bool,
    y_from_zero: bool,
}

fn chart(axes: &Axes, series: &[Series]) -> String {
    let mut out = String::new();
    if let Err(e) = draw_chart(&mut out, axes, series) {
        return failed_chart(&*e);
    }
    out
}

/// The picture of a chart that could not be drawn: drawing into a string cannot fail on
/// finite data; the picture says so if it does.
fn failed_chart(e: &dyn std::error::Error) -> String {
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"720\" height=\"80\"><text x=\"10\" \
         y=\"40\" font-family=\"sans-serif\">chart failed: {}</text></svg>\n",
        esc(&e.to_string())
    )
}

/// Register the shipped DejaVu Sans as plotters' "sans-serif" (its text is measured with it).
fn register_chart_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        // The font is the crate's own: a failure here is a broken build, seen by every test.
        let _ =
            plotters::style::register_font("sans-serif", plotters::style::FontStyle::Normal, FONT);
    });
}

/// An "#rrggbb" colour for plotters.
fn rgb(hex: &str) -> plotters::style::RGBColor {
    let v = u32::from_str_radix(hex.trim_start_matches('#'), 16).unwrap_or(0);
    plotters::style::RGBColor((v >> 16) as u8, (v >> 8) as u8, v as u8)
}

/// The chart of [`chart`], drawn by plotters: title and subtitle lines on top, the plot with
/// its mesh, and the legend to the right of it.
fn draw_chart(
    out: &mut String,
    axes: &Axes,
    series: &[Series],
) -> Result<(), Box<dyn std::error::Error>> {
    let Axes {
        title,
        xlabel,
        ylabel,
        log_y,
        y_from_zero,
    } = *axes;
    use plotters::prelude::*;
    use plotters::style::text_anchor::{HPos, Pos, VPos};
    register_chart_font();
    let mut svg = String::new();
    let mut lines = title.lines();
    let (title, subtitle) = (lines.next().unwrap_or(""), lines.collect::<Vec<_>>());
    // Drawn K times larger than shown: plotters places everything on whole pixels, which
    // at the shown size puts visible steps into a slowly sloping line.
    const K: u32 = 4;
    let k = K as i32;
    let (w, h) = (720 * K, (460 + 16 * subtitle.len() as u32) * K);
    let top = (50 + 16 * subtitle.len() as u32) * K;
    let ty = |y: f64| if log_y { y.max(1e-300).log10() } else { y };
    let all: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|s| s.points.iter().map(|&(x, y)| (x, ty(y))))
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect();
    let (mut x0, mut x1, mut y0, mut y1) = all.iter().fold(
        (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ),
        |(a, b, c, d), &(x, y)| (a.min(x), b.max(x), c.min(y), d.max(y)),
    );
    if !x0.is_finite() {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    if x1 - x0 < 1e-12 {
        x0 -= 0.5;
        x1 += 0.5;
    }
    if log_y {
        y0 = y0.floor();
        y1 = y1.ceil().max(y0 + 1.0);
    } else {
        let pad = 0.05 * (y1 - y0).max(1e-12);
        y0 = if y0 >= 0.0 && y_from_zero {
            0.0
        } else {
            y0 - pad
        };
        y1 += pad;
    }
    {
        let root = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
        root.fill(&WHITE)?;
        // The legend's column, to the right of the plot: only where it tells something the
        // axes do not (more than one series, or a name that the title and the y label do
        // not already say).
        let said = |name: &str| {
            let name = name.to_lowercase();
            title.to_lowercase().contains(&name) || ylabel.to_lowercase().contains(&name)
        };
        let show_legend = series.len() > 1 || series.iter().any(|se| !said(&se.name));
        let legend_w = if show_legend { 190 } else { 20 };
        let centre = ((w as i32 - legend_w * k + 80 * k) / 2, 0);
        let middle = Pos::new(HPos::Center, VPos::Center);
        // The title at 20 px, smaller (down to 12 px) where it would not fit the picture.
        let room = (w as i32 - 2 * (centre.0 - w as i32 / 2).abs() - 20 * k).max(1) as f64;
        let wide = root
            .estimate_text_size(title, &("sans-serif", 20 * k).into_text_style(&root))
            .map_or(0.0, |(tw, _)| tw as f64);
        let size = if wide > room {
            (20.0 * room / wide).max(12.0)
        } else {
            20.0
        };
        root.draw(&Text::new(
            title.to_string(),
            (centre.0, 24 * k),
            ("sans-serif", size * k as f64)
                .into_font()
                .color(&BLACK)
                .pos(middle),
        ))?;
        for (i, line) in subtitle.iter().enumerate() {
            root.draw(&Text::new(
                line.to_string(),
                (w as i32 / 2, (44 + 16 * i as i32) * k),
                ("sans-serif", 14 * k)
                    .into_font()
                    .color(&RGBColor(0x44, 0x44, 0x44))
                    .pos(middle),
            ))?;
        }
        let (plot, legend) = root.split_horizontally(w - legend_w as u32 * K);
        let mut chart = ChartBuilder::on(&plot)
            .margin_top(top - 10 * K)
            .margin_right(10 * K)
            .margin_bottom(10 * K)
            .x_label_area_size(40 * K)
            .y_label_area_size(70 * K)
            .build_cartesian_2d(x0..x1, y0..y1)?;
        let integer_x = all.iter().all(|p| p.0.fract() == 0.0);
        let x_ticks = if integer_x {
            ((x1 - x0).round() as usize + 1).min(8)
        } else {
            8
        };
        let y_ticks = if log_y { (y1 - y0) as usize + 1 } else { 6 };
        let y_fmt = |v: &f64| {
            if log_y {
                fmt_tick(10f64.powf(*v))
            } else {
                fmt_tick_in(*v, y1 - y0)
            }
        };
        chart
            .configure_mesh()
            .x_labels(x_ticks)
            .y_labels(y_ticks)
            .x_label_formatter(&|v| fmt_tick_in(*v, x1 - x0))
            .y_label_formatter(&y_fmt)
            .x_desc(xlabel)
            .y_desc(ylabel)
            .label_style(("sans-serif", 16 * k))
            .axis_desc_style(("sans-serif", 16 * k))
            .bold_line_style(RGBColor(0xdd, 0xdd, 0xdd).stroke_width(K))
            .light_line_style(WHITE)
            .axis_style(RGBColor(0x33, 0x33, 0x33).stroke_width(K))
            .set_tick_mark_size(LabelAreaPosition::Left, 5 * k)
            .set_tick_mark_size(LabelAreaPosition::Bottom, 5 * k)
            .draw()?;
        for se in series {
            let colour = rgb(se.color);
            let pts: Vec<(f64, f64)> = se
                .points
                .iter()
                .map(|&(x, y)| (x, ty(y)))
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .collect();
            if se.line && se.dashed {
                chart.draw_series(DashedLineSeries::new(
                    pts.clone(),
                    6 * k,
                    4 * k,
                    colour.stroke_width(2 * K),
                ))?;
            } else if se.line {
                chart.draw_series(LineSeries::new(pts.clone(), colour.stroke_width(2 * K)))?;
            }
            if se.markers {
                chart.draw_series(
                    pts.iter()
                        .map(|&p| Circle::new(p, 3.5 * K as f64, colour.filled())),
                )?;
            }
        }
        // The legend: a sample of each series' line or dot, then its name.
        for (i, se) in series.iter().enumerate().filter(|_| show_legend) {
            let colour = rgb(se.color);
            let y = top as i32 + (20 + 22 * i as i32) * k;
            if se.line && se.dashed {
                for (a, b) in [(15, 21), (25, 31), (35, 40)] {
                    let dash = vec![(a * k, y), (b * k, y)];
                    legend.draw(&PathElement::new(dash, colour.stroke_width(2 * K)))?;
                }
            } else if se.line {
                let sample = vec![(15 * k, y), (40 * k, y)];
                legend.draw(&PathElement::new(sample, colour.stroke_width(2 * K)))?;
            } else {
                legend.draw(&Circle::new((27 * k, y), 3.5 * K as f64, colour.filled()))?;
            }
            legend.draw(&Text::new(
                se.name.clone(),
                (47 * k, y),
                ("sans-serif", 16 * k)
                    .into_font()
                    .color(&BLACK)
                    .pos(Pos::new(HPos::Left, VPos::Center)),
            ))?;
        }
        root.present()?;
    }
    // Shown at a quarter of the drawing's size.
    let shown = format!("width=\"{}\" height=\"{}\"", w / K, h / K);
    *out = svg.replacen(&format!("width=\"{w}\" height=\"{h}\""), &shown, 1);
    Ok(())
}

/// The curve, its control polygon and its curvature comb (normals scaled by curvature),
/// with a caption. `y` points up in the picture.
pub fn curve_with_comb(
    curve: &AnyBezier,
    control: &[aesthetic_curves::Point],
    extrema: &[f64],
    caption: &str,
) -> String {
    // A curve that does not move has no comb (curve_samples refuses it): drawn without.
    let samples = curve_samples(curve.as_curve(), 201).unwrap_or_default();
    let marks: Vec<aesthetic_curves::Point> = extrema.iter().map(|t| curve.eval(*t)).collect();
    comb_svg(&samples, control, &marks, caption)
}

/// Comb samples (point, unit left normal, signed curvature), shared with the exports' SVG
/// document and the Python package.
pub use crate::export::{curve_samples, CombSample};

/// (arc length, curvature) of comb samples: arc length as chord sums, samples whose
/// curvature is not finite left out.
pub fn curvature_series(samples: &[CombSample]) -> Vec<(f64, f64)> {
    let mut s = 0.0;
    let mut out = Vec::with_capacity(samples.len());
    for (i, (p, _, k)) in samples.iter().enumerate() {
        if i > 0 {
            s += (*p - samples[i - 1].0).hypot();
        }
        if k.is_finite() {
            out.push((s, *k));
        }
    }
    out
}

/// The curve (as comb samples), its control polygon, its curvature comb and circled marks.
/// Input units are unnamed; see [`comb_svg_in`].
pub fn comb_svg(
    samples: &[CombSample],
    control: &[aesthetic_curves::Point],
    marks: &[aesthetic_curves::Point],
    caption: &str,
) -> String {
    comb_svg_in(samples, control, marks, caption, "")
}

/// A "nice" length near `x` (1, 2 or 5 times a power of ten, not above `x`).
fn nice_length(x: f64) -> f64 {
    let mag = 10f64.powf(x.log10().floor());
    [5.0, 2.0, 1.0]
        .iter()
        .map(|m| m * mag)
        .find(|v| *v <= x)
        .unwrap_or(mag)
}

/// The value below which the share `q` of the total weight lies, of `(value, weight)`
/// pairs (a curvature and the arc length it holds for: the 90th percentile of |κ| by arc
/// length scales a comb); sorts `pairs` by value. `None` when empty.
pub fn weighted_quantile(pairs: &mut [(f64, f64)], q: f64) -> Option<f64> {
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let total: f64 = pairs.iter().map(|k| k.1).sum();
    let mut acc = 0.0;
    pairs
        .iter()
        .find(|k| {
            acc += k.1;
            acc >= q * total
        })
        .map(|k| k.0)
}

/// [`comb_svg`] with the unit of the coordinates (`"mm"`, or `""` when they have none),
/// shown on the scale bar.
///
/// The picture is fitted to the curve: a long shallow curve (its extent across the chord
/// of its ends under a fifth of the extent along it) is turned so that the chord is
/// horizontal, the caption says by how much, and the canvas takes the curve's aspect, so
/// the shape and the comb fill the picture instead of a sliver of it. The comb's longest
/// tooth is a quarter of the curve's extent, on the convex side; a scale bar gives the
/// size.
pub fn comb_svg_in(
    samples: &[CombSample],
    control: &[aesthetic_curves::Point],
    marks: &[aesthetic_curves::Point],
    caption: &str,
    unit: &str,
) -> String {
    use aesthetic_curves::{Point, Vec2};
    let pts_all = || {
        samples
            .iter()
            .map(|s| s.0)
            .chain(control.iter().copied())
            .filter(|p| p.is_finite())
    };
    let bbox = |it: &mut dyn Iterator<Item = Point>| {
        it.fold(
            (
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
            ),
            |(a, b, c, d), p| (a.min(p.x), b.max(p.x), c.min(p.y), d.max(p.y)),
        )
    };
    // Turn long shallow curves so that the chord of their ends is horizontal.
    let mut angle = 0.0;
    if let (Some(first), Some(last)) = (samples.first(), samples.last()) {
        let chord = last.0 - first.0;
        if chord.hypot() > 0.0 {
            let a = -chord.y.atan2(chord.x);
            let (c, s) = (a.cos(), a.sin());
            let rot = |p: Point| Point::new(c * p.x - s * p.y, s * p.x + c * p.y);
            let (x0, x1, y0, y1) = bbox(&mut pts_all().map(rot));
            if (y1 - y0) < (x1 - x0) / 5.0 {
                angle = a;
            }
        }
    }
    let (ca, sa) = (angle.cos(), angle.sin());
    let rot = |p: Point| Point::new(ca * p.x - sa * p.y, sa * p.x + ca * p.y);
    let rotv = |v: Vec2| Vec2::new(ca * v.x - sa * v.y, sa * v.x + ca * v.y);
    let samples: Vec<CombSample> = samples
        .iter()
        .map(|(p, n, k)| (rot(*p), rotv(*n), *k))
        .collect();
    let control: Vec<Point> = control.iter().map(|p| rot(*p)).collect();
    let marks: Vec<Point> = marks.iter().map(|p| rot(*p)).collect();
    let (mut x0, mut x1, mut y0, mut y1) = bbox(
        &mut samples
            .iter()
            .map(|s| s.0)
            .chain(control.iter().copied())
            .filter(|p| p.is_finite()),
    );
    if !x0.is_finite() {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    let size = (x1 - x0).max(y1 - y0).max(1e-9);
    // Comb teeth point away from the centre of curvature, the longest a quarter of the size.
    // A short stretch of far larger curvature than the rest (a hook) would flatten the rest
    // of the comb to nothing: when the largest curvature exceeds 8 times the 90th percentile
    // by arc length, the scale follows 4 times that percentile, and longer teeth are cut at
    // 1.5 times the nominal length and drawn in orange.
    let mut ks: Vec<(f64, f64)> = samples
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let next = samples.get(i + 1).map_or(s.0, |n| n.0);
            (s.2.abs(), (next - s.0).hypot())
        })
        .filter(|k| k.0.is_finite() && k.1.is_finite())
        .collect();
    let k90 = weighted_quantile(&mut ks, 0.9);
    let kmax = ks.last().map_or(0.0, |k| k.0);
    let k90 = k90.unwrap_or(kmax);
    let kscale = if kmax > 8.0 * k90 && k90 > 0.0 {
        4.0 * k90
    } else {
        kmax
    };
    // A curvature under 1e-9 of the size's is the rounding of zero (a line drawn as a
    // cubic): no tooth, and no comb scaled up from such noise.
    let flat = 1e-9 / size;
    let comb = if kscale > flat {
        -0.25 * size / kscale
    } else {
        0.0
    };
    let kclip = 1.5 * kscale;
    let tips: Vec<Point> = samples
        .iter()
        .map(|(p, nv, k)| {
            let k = if k.abs() < flat { 0.0 } else { *k };
            *p + *nv * (k.clamp(-kclip, kclip) * comb)
        })
        .collect();
    let clipped = kmax > kclip;
    for p in tips.iter().filter(|p| p.is_finite()) {
        x0 = x0.min(p.x);
        x1 = x1.max(p.x);
        y0 = y0.min(p.y);
        y1 = y1.max(p.y);
    }
    // Canvas: 900 wide, as tall as the drawing needs (220 to 640).
    let (w, m, top, bottom) = (900.0, 30.0, 44.0, 44.0);
    let (dx, dy) = ((x1 - x0).max(1e-12), (y1 - y0).max(1e-12));
    let sc = ((w - 2.0 * m) / dx).min((640.0 - top - bottom) / dy);
    let h = (top + bottom + dy * sc).max(220.0);
    let ox = (w - dx * sc) / 2.0;
    let oy = top + ((h - top - bottom) + dy * sc) / 2.0;
    let px = |p: Point| (ox + (p.x - x0) * sc, oy - (p.y - y0) * sc);
    let turned = if angle != 0.0 {
        format!(
            " (turned {:.1}° to lay its chord flat)",
            -angle.to_degrees()
        )
    } else {
        String::new()
    };
    let mut s = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h:.0}" viewBox="0 0 {w} {h:.0}" font-family="sans-serif" font-size="14">
<rect width="100%" height="100%" fill="white"/>
<text x="{}" y="24" text-anchor="middle">{}{}</text>
"#,
        w / 2.0,
        esc(caption),
        esc(&turned)
    );
    let step = (samples.len() / 60).max(1);
    for (i, (p, _, k)) in samples.iter().enumerate() {
        let cut = k.abs() > kclip;
        if i % step != 0 && !cut {
            continue;
        }
        let (a, b) = px(*p);
        let (c, d) = px(tips[i]);
        let color = if cut { "#ff7f0e" } else { "#9ecae1" };
        let _ = writeln!(
            s,
            r##"<line x1="{a:.1}" y1="{b:.1}" x2="{c:.1}" y2="{d:.1}" stroke="{color}"/>"##
        );
    }
    let coords = |pts: &mut dyn Iterator<Item = Point>| -> Vec<String> {
        pts.map(|p| {
            let (a, b) = px(p);
            format!("{a:.1},{b:.1}")
        })
        .collect()
    };
    let tip_pts = coords(&mut tips.iter().copied());
    let _ = writeln!(
        s,
        r##"<polyline points="{}" fill="none" stroke="#6baed6"/>"##,
        tip_pts.join(" ")
    );
    let poly = coords(&mut control.iter().copied());
    let _ = writeln!(
        s,
        r##"<polyline points="{}" fill="none" stroke="#999" stroke-dasharray="4 3"/>"##,
        poly.join(" ")
    );
    // Many control points (a point sequence): small dots.
    let r = if control.len() > 40 { 1.5 } else { 4.0 };
    for p in &control {
        let (a, b) = px(*p);
        let _ = writeln!(
            s,
            r##"<circle cx="{a:.1}" cy="{b:.1}" r="{r}" fill="#666"/>"##
        );
    }
    let cpts = coords(&mut samples.iter().map(|s| s.0));
    let _ = writeln!(
        s,
        r##"<polyline points="{}" fill="none" stroke="#d62728" stroke-width="2.5"/>"##,
        cpts.join(" ")
    );
    for &mk in &marks {
        let (a, b) = px(mk);
        let _ = writeln!(
            s,
            r##"<circle cx="{a:.1}" cy="{b:.1}" r="6" fill="none" stroke="#000" stroke-width="2"/>"##
        );
    }
    // Scale bar, bottom left: a round length of about a fifth of the width; the comb's scale
    // beside it in the same length.
    let len = nice_length(0.2 * (w - 2.0 * m) / sc);
    let (bx, by) = (m, h - 16.0);
    let (unit_text, per) = if unit.is_empty() {
        (String::new(), String::new())
    } else {
        (format!(" {unit}"), format!(" /{unit}"))
    };
    let comb_text = if comb != 0.0 {
        let mut t = format!(
            "; comb: a tooth of {}{unit_text} = curvature {}{per}",
            fmt_tick(len),
            fmt_sig(len / comb.abs())
        );
        if clipped {
            t += &format!(" (orange: cut, curvature up to {}{per})", fmt_sig(kmax));
        }
        t
    } else {
        String::new()
    };
    let _ = writeln!(
        s,
        r##"<line x1="{bx}" y1="{by}" x2="{:.1}" y2="{by}" stroke="#333" stroke-width="2"/><line x1="{bx}" y1="{:.1}" x2="{bx}" y2="{:.1}" stroke="#333"/><line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="#333"/><text x="{:.1}" y="{:.1}" font-size="13">{}{}{}</text>"##,
        bx + len * sc,
        by - 4.0,
        by + 4.0,
        bx + len * sc,
        by - 4.0,
        bx + len * sc,
        by + 4.0,
        bx + len * sc + 8.0,
        by + 5.0,
        fmt_tick(len),
        esc(&unit_text),
        esc(&comb_text)
    );
    s.push_str("</svg>\n");
    s
}

/// The logarithmic curvature graph (dots) with its fitted line.
pub fn lcg_chart(fit: &aesthetic_curves::lcg::LcgFit, title: &str) -> String {
    let pts: Vec<(f64, f64)> = fit
        .graph
        .iter()
        .map(|p| (p.log_rho, p.log_rho_ds_drho))
        .collect();
    let (lo, hi) = pts
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.0), b.max(p.0))
        });
    let line = vec![
        (lo, fit.alpha * lo + fit.intercept),
        (hi, fit.alpha * hi + fit.intercept),
    ];
    let mut dots = Series::new("graph points", pts, PALETTE[1]);
    dots.line = false;
    let mut fitted = Series::new(format!("fit: slope {:.4}", fit.alpha), line, PALETTE[0]);
    fitted.markers = false;
    fitted_chart(title, "log ρ", "log(ρ ds/dρ)", &[dots, fitted])
}

/// The font the PNG renderer uses for all text (DejaVu Sans, embedded: no system fonts needed).
const FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

/// Rasterise an SVG document to PNG bytes at `scale` (2.0: twice the SVG's pixel size).
pub fn svg_to_png(svg: &str, scale: f32) -> anyhow::Result<Vec<u8>> {
    use resvg::{tiny_skia, usvg};
    let mut opt = usvg::Options::default();
    opt.fontdb_mut().load_font_data(FONT.to_vec());
    opt.font_family = "DejaVu Sans".into();
    let tree = usvg::Tree::from_str(
        &svg.replace("font-family=\"sans-serif\"", "font-family=\"DejaVu Sans\""),
        &opt,
    )?;
    let size = tree
        .size()
        .to_int_size()
        .scale_by(scale)
        .ok_or_else(|| anyhow::anyhow!("image too large"))?;
    let mut pixmap = tiny_skia::Pixmap::new(size.width(), size.height()).ok_or_else(|| {
        anyhow::anyhow!("cannot allocate a {}x{} image", size.width(), size.height())
    })?;
    resvg::render(
        &tree,
        tiny_skia::Transform::from_scale(scale, scale),
        &mut pixmap.as_mut(),
    );
    Ok(pixmap.encode_png()?)
}

/// Fail early (before any computation) on an output path that is not `.svg` or `.png`.
pub fn check_picture_paths(paths: &[std::path::PathBuf]) -> anyhow::Result<()> {
    for p in paths {
        let ext = p
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase());
        if !matches!(ext.as_deref(), Some("svg") | Some("png")) {
            anyhow::bail!("{}: unknown picture format (use .svg or .png)", p.display());
        }
    }
    Ok(())
}

/// Write a picture: `.svg` as is, `.png` rasterised; any other extension is an error.
pub fn write_picture(path: &std::path::Path, svg: &str) -> anyhow::Result<()> {
    use anyhow::Context;
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase());
    let bytes = match ext.as_deref() {
        Some("svg") => svg.as_bytes().to_vec(),
        Some("png") => svg_to_png(svg, 2.0)?,
        _ => anyhow::bail!(
            "{}: unknown picture format (use .svg or .png)",
            path.display()
        ),
    };
    std::fs::write(path, bytes).with_context(|| format!("writing {}", path.display()))
}

/// A colour for `v` in [0, 1] on a perceptual blue-green-yellow ramp (viridis, 5 stops).
fn ramp(v: f64) -> plotters::style::RGBColor {
    const STOPS: [(f64, f64, f64); 5] = [
        (68.0, 1.0, 84.0),
        (59.0, 82.0, 139.0),
        (33.0, 145.0, 140.0),
        (94.0, 201.0, 98.0),
        (253.0, 231.0, 37.0),
    ];
    let v = if v.is_finite() {
        v.clamp(0.0, 1.0)
    } else {
        1.0
    };
    let x = v * 4.0;
    let i = (x as usize).min(3);
    let f = x - i as f64;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    let mix = |p: f64, q: f64| (p + (q - p) * f).round() as u8;
    plotters::style::RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// The hatching of the rectangle `[x0, x1] × [y0, y1]` (in data units of a square chart):
/// the pieces inside it of the lines x + y = k·gap, so that the hatching of neighbouring
/// rectangles runs on without a seam.
fn hatch_lines(x0: f64, x1: f64, y0: f64, y1: f64, gap: f64) -> Vec<[(f64, f64); 2]> {
    let first = ((x0 + y0) / gap).ceil() as i64;
    let last = ((x1 + y1) / gap).floor() as i64;
    (first..=last)
        .filter_map(|k| {
            let c = k as f64 * gap;
            let (xa, xb) = ((c - y1).max(x0), (c - y0).min(x1));
            (xb > xa).then_some([(xa, c - xa), (xb, c - xb)])
        })
        .collect()
}

/// S3 Fig. 3 and 5 in one picture: log10 of the rms error over (f0, f1) as colour, the
/// cells whose cubic is not curvature-monotone hatched grey, the returned optimum marked.
pub fn error_map_svg(
    map: &aesthetic_curves::approx::ErrorMap,
    chosen: (f64, f64),
    caption: &str,
) -> String {
    let mut out = String::new();
    if let Err(e) = draw_error_map(&mut out, map, chosen, caption) {
        return failed_chart(&*e);
    }
    out
}

fn draw_error_map(
    out: &mut String,
    map: &aesthetic_curves::approx::ErrorMap,
    chosen: (f64, f64),
    caption: &str,
) -> Result<(), Box<dyn std::error::Error>> {
    use plotters::prelude::*;
    use plotters::style::text_anchor::{HPos, Pos, VPos};
    register_chart_font();
    let n = map.n;
    let logs: Vec<f64> = map.rms.iter().map(|r| r.max(1e-300).log10()).collect();
    let finite: Vec<f64> = logs.iter().copied().filter(|v| v.is_finite()).collect();
    // Whole decades around the values (a power of ten computed as 1e-5 - 1 ulp still counts
    // as 1e-5); -1 to 0 when no cell has a cubic.
    let (lo, hi) = if finite.is_empty() {
        (-1.0, 0.0)
    } else {
        let lo = (finite.iter().copied().fold(f64::INFINITY, f64::min) + 1e-9).floor();
        let hi = (finite.iter().copied().fold(f64::NEG_INFINITY, f64::max) - 1e-9).ceil();
        (lo, hi.max(lo + 1.0))
    };
    // Drawn K times larger than shown, as the line charts.
    const K: u32 = 4;
    let k = K as i32;
    let (w, h) = (700 * K, 560 * K);
    let (size, top, left) = (440 * k, 50 * k, 70 * k);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
        root.fill(&WHITE)?;
        let font = |px: i32| ("sans-serif", px * k).into_font().color(&BLACK);
        let middle = Pos::new(HPos::Center, VPos::Center);
        root.draw(&Text::new(
            caption.to_string(),
            (left + size / 2, 24 * k),
            font(17).pos(middle),
        ))?;
        let area = root.margin(top as u32, (h as i32 - top - size - 60 * k) as u32, 0, 0);
        let (plot, _) = area.split_horizontally((left + size + 20 * k) as u32);
        // The colour bar's corner, in the picture.
        let (ox, oy) = (left + size + 20 * k, top);
        let mut chart = ChartBuilder::on(&plot)
            .margin_left((left - 60 * k) as u32)
            .margin_right(20 * k as u32)
            .y_label_area_size(60 * K)
            .x_label_area_size(60 * K)
            .build_cartesian_2d(0f64..1f64, 0f64..1f64)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_labels(6)
            .y_labels(6)
            .x_label_formatter(&|v| format!("{v:.1}"))
            .y_label_formatter(&|v| format!("{v:.1}"))
            .label_style(("sans-serif", 14 * k))
            .axis_style(RGBColor(0x33, 0x33, 0x33).stroke_width(K))
            .set_tick_mark_size(LabelAreaPosition::Left, 5 * k)
            .draw()?;
        let cell = 1.0 / n as f64;
        // One shown pixel of overlap, so that no background shows between cells.
        let over = 1.0 / (size as f64 / K as f64);
        chart.draw_series((0..n * n).map(|c| {
            let (i, j) = (c / n, c % n);
            let (x, y) = (i as f64 * cell, j as f64 * cell);
            Rectangle::new(
                [
                    (x, y),
                    ((x + cell + over).min(1.0), (y + cell + over).min(1.0)),
                ],
                ramp((logs[c] - lo) / (hi - lo)).filled(),
            )
        }))?;
        // The hatching, drawn per run of non-monotone cells along f0 (cell (i, j) is
        // f0 = i / n, f1 = j / n).
        // 6 px between the lines, as shown.
        let gap = 6.0 * std::f64::consts::SQRT_2 / (size as f64 / K as f64);
        let shade = RGBAColor(0xbb, 0xbb, 0xbb, 0.55);
        let hatch = RGBColor(0x55, 0x55, 0x55).stroke_width(3 * K / 2);
        for j in 0..n {
            let mut i = 0;
            while i < n {
                if map.monotone[i * n + j] {
                    i += 1;
                    continue;
                }
                let start = i;
                while i < n && !map.monotone[i * n + j] {
                    i += 1;
                }
                let (x0, x1) = (start as f64 * cell, i as f64 * cell);
                let (y0, y1) = (j as f64 * cell, (j + 1) as f64 * cell);
                chart.draw_series(std::iter::once(Rectangle::new(
                    [(x0, y0), (x1, y1)],
                    shade.filled(),
                )))?;
                chart.draw_series(
                    hatch_lines(x0, x1, y0, y1, gap)
                        .into_iter()
                        .map(|seg| PathElement::new(seg.to_vec(), hatch)),
                )?;
            }
        }
        // The frame, the optimum (ring and cross) and the axis names.
        chart.draw_series(std::iter::once(Rectangle::new(
            [(0.0, 0.0), (1.0, 1.0)],
            RGBColor(0x33, 0x33, 0x33).stroke_width(K),
        )))?;
        let red = RGBColor(0xe3, 0x1a, 0x1c);
        let arm = 11.0 / (size as f64 / K as f64);
        let (cx, cy) = chosen;
        chart.draw_series(std::iter::once(Circle::new(
            (cx, cy),
            7 * k,
            red.stroke_width(5 * K / 2),
        )))?;
        for seg in [
            [(cx - arm, cy), (cx + arm, cy)],
            [(cx, cy - arm), (cx, cy + arm)],
        ] {
            chart.draw_series(std::iter::once(PathElement::new(
                seg.to_vec(),
                red.stroke_width(2 * K),
            )))?;
        }
        let (px, py) = chart.backend_coord(&(0.5, 0.0));
        root.draw(&Text::new(
            "f0".to_string(),
            (px, py + 22 * k),
            font(14).pos(Pos::new(HPos::Center, VPos::Top)),
        ))?;
        let (_, py) = chart.backend_coord(&(0.0, 0.5));
        let (x_axis, _) = chart.backend_coord(&(0.0, 0.0));
        root.draw(&Text::new(
            "f1".to_string(),
            (x_axis - 45 * k, py),
            font(14).pos(middle),
        ))?;
        // The colour bar (decades of the rms) and the hatching's key.
        let (bx, bw) = (ox + 10 * k, 18 * k);
        for c in 0..100 {
            let (y0, y1) = (size * c / 100, size * (c + 1) / 100 + k);
            root.draw(&Rectangle::new(
                [(bx, oy + size - y1), (bx + bw, oy + size - y0)],
                ramp(c as f64 / 99.0).filled(),
            ))?;
        }
        let steps = (hi - lo) as i64;
        for e in 0..=steps {
            let y = oy + size - (size as f64 * e as f64 / steps as f64).round() as i32;
            root.draw(&Text::new(
                format!("1e{}", lo as i64 + e),
                (bx + bw + 5 * k, y),
                font(13).pos(Pos::new(HPos::Left, VPos::Center)),
            ))?;
        }
        root.draw(&Text::new(
            "rms".to_string(),
            (bx, oy - 8 * k),
            font(13).pos(Pos::new(HPos::Left, VPos::Bottom)),
        ))?;
        let key = (oy + size + 26 * k, oy + size + 40 * k);
        root.draw(&Rectangle::new(
            [(bx, key.0), (bx + bw, key.1)],
            shade.filled(),
        ))?;
        for [(x0, y0), (x1, y1)] in hatch_lines(
            0.0,
            bw as f64,
            0.0,
            (key.1 - key.0) as f64,
            6.0 * std::f64::consts::SQRT_2 * k as f64,
        ) {
            root.draw(&PathElement::new(
                vec![
                    (bx + x0 as i32, key.1 - y0 as i32),
                    (bx + x1 as i32, key.1 - y1 as i32),
                ],
                hatch,
            ))?;
        }
        root.draw(&Text::new(
            "not monotone".to_string(),
            (bx + bw + 5 * k, (key.0 + key.1) / 2),
            font(13).pos(Pos::new(HPos::Left, VPos::Center)),
        ))?;
        root.present()?;
    }
    let shown = format!("width=\"{}\" height=\"{}\"", w / K, h / K);
    *out = svg.replacen(&format!("width=\"{w}\" height=\"{h}\""), &shown, 1);
    Ok(())
}

/// Several curves (as polylines, equal x and y scale, y up) with a legend, and dots at
/// `points`.
pub fn curves_svg(caption: &str, curves: &[Series], points: &[aesthetic_curves::Point]) -> String {
    let all = curves
        .iter()
        .flat_map(|c| c.points.iter().copied())
        .chain(points.iter().map(|p| (p.x, p.y)))
        .filter(|p| p.0.is_finite() && p.1.is_finite());
    let (x0, x1, y0, y1) = all.fold(
        (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ),
        |(a, b, c, d), (x, y)| (a.min(x), b.max(x), c.min(y), d.max(y)),
    );
    let (w, h) = (720.0, 420.0);
    let (m, legend, top) = (30.0, 150.0, 40.0);
    let sc =
        ((w - 2.0 * m - legend) / (x1 - x0).max(1e-12)).min((h - m - top) / (y1 - y0).max(1e-12));
    // Centre the drawing in its box.
    let ox = m + ((w - 2.0 * m - legend) - (x1 - x0) * sc) / 2.0;
    let oy = h - m - ((h - m - top) - (y1 - y0) * sc) / 2.0;
    let px = |x: f64, y: f64| (ox + (x - x0) * sc, oy - (y - y0) * sc);
    let mut s = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="13">
<rect width="100%" height="100%" fill="white"/>
<text x="{}" y="24" text-anchor="middle" font-size="15">{}</text>
"#,
        (w - legend) / 2.0,
        esc(caption)
    );
    for (i, c) in curves.iter().enumerate() {
        let pts: Vec<String> = c
            .points
            .iter()
            .map(|&(x, y)| {
                let (a, b) = px(x, y);
                format!("{a:.1},{b:.1}")
            })
            .collect();
        let dash = if c.dashed {
            r#" stroke-dasharray="6 4""#
        } else {
            ""
        };
        let _ = writeln!(
            s,
            r#"<polyline points="{}" fill="none" stroke="{}" stroke-width="2"{dash}/>"#,
            pts.join(" "),
            c.color
        );
        let ly = top + 10.0 + 22.0 * i as f64;
        let lx = w - legend + 5.0;
        let _ = writeln!(
            s,
            r#"<line x1="{lx}" y1="{ly}" x2="{}" y2="{ly}" stroke="{}" stroke-width="2"{dash}/><text x="{}" y="{}">{}</text>"#,
            lx + 25.0,
            c.color,
            lx + 32.0,
            ly + 4.0,
            esc(&c.name)
        );
    }
    for p in points {
        let (a, b) = px(p.x, p.y);
        let _ = writeln!(
            s,
            r##"<circle cx="{a:.1}" cy="{b:.1}" r="3.5" fill="#333"/>"##
        );
    }
    s.push_str("</svg>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hatching_stays_in_its_cells_and_runs_on_across_them() {
        let gap = 0.07;
        let left = hatch_lines(0.0, 0.5, 0.2, 0.6, gap);
        let right = hatch_lines(0.5, 1.0, 0.2, 0.6, gap);
        assert!(!left.is_empty() && !right.is_empty());
        for (seg, (x0, x1)) in left
            .iter()
            .map(|s| (s, (0.0, 0.5)))
            .chain(right.iter().map(|s| (s, (0.5, 1.0))))
        {
            let c = seg[0].0 + seg[0].1;
            assert!((seg[1].0 + seg[1].1 - c).abs() < 1e-12, "one line: {seg:?}");
            assert!(
                ((c / gap) - (c / gap).round()).abs() < 1e-9,
                "on the global grid"
            );
            for &(x, y) in seg {
                assert!(
                    (x0 - 1e-12..=x1 + 1e-12).contains(&x)
                        && (0.2 - 1e-12..=0.6 + 1e-12).contains(&y)
                );
            }
        }
        // A line that crosses the shared side leaves the left cell where it enters the right.
        let ends: Vec<(f64, f64)> = left
            .iter()
            .flat_map(|s| s.iter().copied())
            .filter(|p| (p.0 - 0.5).abs() < 1e-12 && p.1 > 0.2 + 1e-9 && p.1 < 0.6 - 1e-9)
            .collect();
        assert!(!ends.is_empty());
        for e in ends {
            assert!(right.iter().any(|s| s
                .iter()
                .any(|q| (q.0 - e.0).abs() < 1e-12 && (q.1 - e.1).abs() < 1e-12)));
        }
    }

    #[test]
    fn the_ramp_runs_from_dark_blue_to_yellow() {
        use plotters::style::RGBColor;
        assert_eq!(ramp(0.0), RGBColor(68, 1, 84));
        assert_eq!(ramp(1.0), RGBColor(253, 231, 37));
        assert_eq!(ramp(f64::NAN), ramp(1.0));
        assert_eq!(ramp(-3.0), ramp(0.0));
    }

    #[test]
    fn ticks_show_enough_digits_and_no_more() {
        assert_eq!(fmt_tick(0.0), "0");
        assert_eq!(fmt_tick(0.25), "0.25");
        assert_eq!(fmt_tick(3.5e-4), "3.5e-4");
        assert_eq!(fmt_tick(12000.0), "1.2e4");
        assert_eq!(fmt_sig(1.23456), "1.235");
        // The zero tick of an axis from -0.04 to 0.03, placed with a rounding error.
        assert_eq!(fmt_tick_in(-3.3889e-18, 0.07), "0");
        assert_eq!(fmt_tick_in(-0.02, 0.07), "-0.02");
        assert_eq!(fmt_tick_in(3.5e-4, 1e-3), "3.5e-4");
    }

    #[test]
    fn a_chart_is_shown_at_its_size_with_its_title_and_line() {
        let mut s = Series::new("k", vec![(0.0, 1.0), (1.0, 2.0), (2.0, 1.5)], PALETTE[0]);
        s.markers = false;
        let svg = fitted_chart("the title", "x", "y", &[s.clone()]);
        assert!(svg.contains("width=\"720\""), "{}", &svg[..200]);
        assert!(svg.contains("the title") && svg.contains("<polyline"));
        // A legend where it names something: "k" is not in the title or the y label.
        assert!(svg.contains("\nk\n"));
        // Not where the y label says it already.
        let svg = fitted_chart("the title", "x", "k (1/mm)", &[s]);
        assert!(!svg.contains("\nk\n"));
    }

    #[test]
    fn the_error_map_hatches_exactly_its_non_monotone_cells() {
        let n = 4;
        let map = |monotone: Vec<bool>| aesthetic_curves::approx::ErrorMap {
            n,
            rms: (0..n * n).map(|c| 10f64.powi(-(c as i32) / 3)).collect(),
            monotone,
        };
        let lines = |svg: &str| svg.matches("<polyline").count();
        // Every cell monotone: no hatching in the map (the axes, the optimum's cross and the
        // key's sample are lines too).
        let all = error_map_svg(&map(vec![true; n * n]), (0.5, 0.5), "all");
        assert!(all.contains("width=\"700\"") && all.contains("not monotone"));
        // One cell (a quarter of the side: 110 px shown) not monotone: its hatching, lines
        // 6 px apart at 45°, adds 2 * 110 / (6 √2) = 26 lines; the decades 1e-5 .. 1e0
        // labelled.
        let mut m = vec![true; n * n];
        m[5] = false;
        let one = error_map_svg(&map(m), (0.5, 0.5), "one");
        let added = lines(&one) - lines(&all);
        assert!((25..=27).contains(&added), "{added} lines of hatching");
        for e in -5..=0 {
            assert!(one.contains(&format!("\n1e{e}\n")), "decade {e}");
        }
        assert!(!one.contains("\n1e-6\n") && !one.contains("\n1e1\n"));
        // No cell with a cubic: still a picture, with one decade.
        let none = aesthetic_curves::approx::ErrorMap {
            n,
            rms: vec![f64::INFINITY; n * n],
            monotone: vec![false; n * n],
        };
        let svg = error_map_svg(&none, (0.5, 0.5), "none");
        assert!(svg.contains("\n1e-1\n") && !svg.contains("NaN") && !svg.contains("failed"));
    }
}
