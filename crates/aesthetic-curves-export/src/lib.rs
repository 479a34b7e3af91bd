//! Curve exports by file extension: CAD formats with the exact rational geometry (DXF SPLINE,
//! STEP B_SPLINE_CURVE_WITH_KNOTS + RATIONAL_B_SPLINE_CURVE, IGES entity 126), JSON, and SVG
//! paths made of cubic Béziers within a stated tolerance (SVG has no rational curves).

use aesthetic_curves::nurbs::Nurbs;
use aesthetic_curves::{PlanarCurve, Point, RationalBezier};
use anyhow::{Context, Result};
use std::fmt::Write;
use std::path::Path;

/// The curve formats [`write_curve`] understands.
pub const CURVE_FORMATS: &[&str] = &["dxf", "step", "stp", "iges", "igs", "json"];

/// Lower-case extension of a path.
pub fn extension(path: &Path) -> Option<String> {
    path.extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase())
}

/// Whether a curve can be written: its extent must be finite (control points of ±1e308 are
/// finite, but the size of their box is not, and a file would carry `inf` or `NaN`).
pub fn check_exportable(curve: &Nurbs) -> Result<()> {
    let finite = curve.control_points.iter().all(|p| p.is_finite())
        && curve.weights.iter().all(|w| w.is_finite())
        && curve.size().is_finite();
    anyhow::ensure!(
        finite,
        "the curve's coordinates are too large to export: its extent overflows f64"
    );
    Ok(())
}

/// Write `curve` to `path` in the format its extension names (one of [`CURVE_FORMATS`]).
pub fn write_curve(path: &Path, curve: &Nurbs, name: &str) -> Result<()> {
    check_exportable(curve)?;
    let ext = extension(path).unwrap_or_default();
    match ext.as_str() {
        "dxf" => write_dxf(path, curve),
        "step" | "stp" => std::fs::write(path, step_text(curve, name))
            .with_context(|| format!("writing {}", path.display())),
        "iges" | "igs" => std::fs::write(path, iges_text(curve, name))
            .with_context(|| format!("writing {}", path.display())),
        "json" => std::fs::write(path, json_text(curve).to_string() + "\n")
            .with_context(|| format!("writing {}", path.display())),
        _ => anyhow::bail!(
            "{}: not a curve format ({})",
            path.display(),
            CURVE_FORMATS.join(", ")
        ),
    }
}

/// The NURBS as the protocol's JSON object.
pub fn json_text(c: &Nurbs) -> serde_json::Value {
    serde_json::json!({
        "degree": c.degree,
        "knots": c.knots,
        "control_points": c.control_points.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>(),
        "weights": c.weights,
    })
}

/// A DXF (R2000) drawing with one rational SPLINE entity.
pub fn write_dxf(path: &Path, c: &Nurbs) -> Result<()> {
    std::fs::write(path, dxf_bytes(c)?).with_context(|| format!("writing {}", path.display()))
}

/// The file text of [`write_dxf`].
pub fn dxf_bytes(c: &Nurbs) -> Result<Vec<u8>> {
    use dxf::entities::{Entity, EntityType, Spline};
    let mut drawing = dxf::Drawing::new();
    drawing.header.version = dxf::enums::AcadVersion::R2000;
    let mut s = Spline {
        degree_of_curve: c.degree as i32,
        knot_values: c.knots.clone(),
        weight_values: c.weights.clone(),
        control_points: c
            .control_points
            .iter()
            .map(|p| dxf::Point::new(p.x, p.y, 0.0))
            .collect(),
        ..Default::default()
    };
    s.set_is_rational(true);
    s.set_is_planar(true);
    drawing.add_entity(Entity::new(EntityType::Spline(s)));
    let mut out = Vec::new();
    drawing
        .save(&mut out)
        .map_err(|e| anyhow::anyhow!("writing DXF: {e}"))?;
    Ok(out)
}

/// A real for STEP (ISO 10303-21) and IGES: the shortest round-trip form (`{:?}`), with a
/// decimal point always and an upper-case exponent, as both formats require.
fn step_real(v: f64) -> String {
    let s = format!("{v:?}").replace('e', "E");
    if s.contains('.') {
        s
    } else if let Some(i) = s.find('E') {
        format!("{}.{}", &s[..i], &s[i..])
    } else {
        format!("{s}.")
    }
}

/// ISO 10303-21 (AP214) with the curve as a B_SPLINE_CURVE_WITH_KNOTS +
/// RATIONAL_B_SPLINE_CURVE complex entity in a geometrically bounded wireframe shape
/// representation of one product.
pub fn step_text(c: &Nurbs, name: &str) -> String {
    let mut d = String::new();
    let mut id = 0;
    let mut next = || {
        id += 1;
        id
    };
    let pts: Vec<usize> = c
        .control_points
        .iter()
        .map(|p| {
            let i = next();
            let _ = writeln!(
                d,
                "#{i}=CARTESIAN_POINT('',({},{},0.));",
                step_real(p.x),
                step_real(p.y)
            );
            i
        })
        .collect();
    // Distinct knots and multiplicities.
    let mut uniq: Vec<f64> = Vec::new();
    let mut mult: Vec<usize> = Vec::new();
    for &k in &c.knots {
        if uniq.last() == Some(&k) {
            *mult.last_mut().expect("non-empty") += 1;
        } else {
            uniq.push(k);
            mult.push(1);
        }
    }
    let join = |v: Vec<String>| v.join(",");
    let curve = next();
    let _ = writeln!(
        d,
        "#{curve}=(BOUNDED_CURVE() B_SPLINE_CURVE({},({}),.UNSPECIFIED.,.F.,.F.) \
         B_SPLINE_CURVE_WITH_KNOTS(({}),({}),.UNSPECIFIED.) CURVE() \
         GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_CURVE(({})) REPRESENTATION_ITEM(''));",
        c.degree,
        join(pts.iter().map(|i| format!("#{i}")).collect()),
        join(mult.iter().map(|m| m.to_string()).collect()),
        join(uniq.iter().map(|k| step_real(*k)).collect()),
        join(c.weights.iter().map(|w| step_real(*w)).collect()),
    );
    let set = next();
    let _ = writeln!(d, "#{set}=GEOMETRIC_CURVE_SET('',(#{curve}));");
    let (len, ang, sol, unc, ctx) = (next(), next(), next(), next(), next());
    let _ = writeln!(
        d,
        "#{len}=(LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.));"
    );
    let _ = writeln!(
        d,
        "#{ang}=(NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.));"
    );
    let _ = writeln!(
        d,
        "#{sol}=(NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT());"
    );
    let _ = writeln!(
        d,
        "#{unc}=UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-09),#{len},'distance_accuracy_value','');"
    );
    let _ = writeln!(
        d,
        "#{ctx}=(GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{unc})) \
         GLOBAL_UNIT_ASSIGNED_CONTEXT((#{len},#{ang},#{sol})) REPRESENTATION_CONTEXT('',''));"
    );
    let rep = next();
    let _ = writeln!(
        d,
        "#{rep}=GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION('{name}',(#{set}),#{ctx});"
    );
    let (app, apd, pc, prod, pdf, pdc, pd, pds, sdr) = (
        next(),
        next(),
        next(),
        next(),
        next(),
        next(),
        next(),
        next(),
        next(),
    );
    let _ = writeln!(d, "#{app}=APPLICATION_CONTEXT('automotive design');");
    let _ = writeln!(
        d,
        "#{apd}=APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#{app});"
    );
    let _ = writeln!(d, "#{pc}=PRODUCT_CONTEXT('',#{app},'mechanical');");
    let _ = writeln!(d, "#{prod}=PRODUCT('{name}','{name}','',(#{pc}));");
    let _ = writeln!(d, "#{pdf}=PRODUCT_DEFINITION_FORMATION('','',#{prod});");
    let _ = writeln!(
        d,
        "#{pdc}=PRODUCT_DEFINITION_CONTEXT('part definition',#{app},'design');"
    );
    let _ = writeln!(d, "#{pd}=PRODUCT_DEFINITION('design','',#{pdf},#{pdc});");
    let _ = writeln!(d, "#{pds}=PRODUCT_DEFINITION_SHAPE('','',#{pd});");
    let _ = writeln!(d, "#{sdr}=SHAPE_DEFINITION_REPRESENTATION(#{pds},#{rep});");
    format!(
        "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('aesthetic-curves rational B-spline'),'2;1');\n\
         FILE_NAME('{name}','2026-01-01T00:00:00',('aesthetic-curves'),(''),'aecurve','aecurve','');\n\
         FILE_SCHEMA(('AUTOMOTIVE_DESIGN {{ 1 0 10303 214 1 1 1 1 }}'));\nENDSEC;\nDATA;\n{d}ENDSEC;\nEND-ISO-10303-21;\n"
    )
}

fn hollerith(s: &str) -> String {
    format!("{}H{s}", s.len())
}

/// Lines of at most `width` characters from comma-separated tokens (the last ends in ';').
fn pack(tokens: &[String], width: usize) -> Vec<String> {
    let mut lines = Vec::new();
    let mut cur = String::new();
    for (i, t) in tokens.iter().enumerate() {
        let sep = if i + 1 == tokens.len() { ";" } else { "," };
        let piece = format!("{t}{sep}");
        if !cur.is_empty() && cur.len() + piece.len() > width {
            lines.push(std::mem::take(&mut cur));
        }
        cur += &piece;
    }
    if !cur.is_empty() {
        lines.push(cur);
    }
    lines
}

/// IGES 5.3 with one rational B-spline curve (entity 126), millimetres.
pub fn iges_text(c: &Nurbs, name: &str) -> String {
    let n = c.control_points.len();
    let k = n - 1;
    let m = c.degree;
    let (u0, u1) = c.domain();
    let mut tok: Vec<String> = vec![
        "126".into(),
        k.to_string(),
        m.to_string(),
        "1".into(), // planar
        "0".into(), // open
        "0".into(), // rational
        "0".into(), // non-periodic
    ];
    tok.extend(c.knots.iter().map(|v| step_real(*v)));
    tok.extend(c.weights.iter().map(|v| step_real(*v)));
    for p in &c.control_points {
        tok.push(step_real(p.x));
        tok.push(step_real(p.y));
        tok.push("0.".into());
    }
    tok.extend([
        step_real(u0),
        step_real(u1),
        "0.".into(),
        "0.".into(),
        "1.".into(),
    ]);
    let p_lines = pack(&tok, 64);
    let size = c.size().max(1.0);
    let g_tok: Vec<String> = vec![
        "1H,".into(),
        "1H;".into(),
        hollerith(name),
        hollerith(&format!("{name}.igs")),
        hollerith("aesthetic-curves"),
        hollerith("aecurve"),
        "32".into(),
        "38".into(),
        "6".into(),
        "308".into(),
        "15".into(),
        hollerith(name),
        "1.".into(),
        "2".into(),
        hollerith("MM"),
        "1".into(),
        "0.".into(),
        hollerith("20260101.000000"),
        "1.E-9".into(),
        step_real(size * 10.0),
        hollerith("aesthetic-curves"),
        hollerith(""),
        "11".into(),
        "0".into(),
    ];
    // The global section's own delimiters are the first two parameters: pack by hand.
    let g_lines = pack(&g_tok, 72);
    let mut out = String::new();
    let start = "rational B-spline curve written by aecurve (aesthetic-curves)";
    let _ = writeln!(out, "{start:<72}S{:>7}", 1);
    for (i, l) in g_lines.iter().enumerate() {
        let _ = writeln!(out, "{l:<72}G{:>7}", i + 1);
    }
    let pl = p_lines.len();
    let _ = writeln!(
        out,
        "{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}D{:>7}",
        126, 1, 0, 0, 0, 0, 0, 0, "00000000", 1
    );
    let _ = writeln!(
        out,
        "{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}D{:>7}",
        126, 0, 0, pl, 0, "", "", "CURVE", 0, 2
    );
    for (i, l) in p_lines.iter().enumerate() {
        let _ = writeln!(out, "{l:<64} {:>7}P{:>7}", 1, i + 1);
    }
    let _ = writeln!(
        out,
        "S{:>7}G{:>7}D{:>7}P{:>7}{:>40}T{:>7}",
        1,
        g_lines.len(),
        2,
        pl,
        "",
        1
    );
    out
}

/// Cubic Bézier segments approximating a rational Bézier curve within `tol`: Hermite cubics
/// through the end points with the end derivatives, bisected until 33 samples of each lie
/// within `tol` of the curve (compared at equal parameters, which bounds the distance).
pub fn cubics_for(c: &RationalBezier, tol: f64) -> Vec<[Point; 4]> {
    cubic_pieces(c, tol).into_iter().map(|p| p.2).collect()
}

/// [`cubics_for`] with each cubic's parameter interval on the rational curve.
pub fn cubic_pieces(c: &RationalBezier, tol: f64) -> Vec<(f64, f64, [Point; 4])> {
    let mut out = Vec::new();
    type Piece = (f64, f64, [Point; 4]);
    fn rec(c: &RationalBezier, a: f64, b: f64, tol: f64, depth: u32, out: &mut Vec<Piece>) {
        let (pa, pb) = (c.eval(a), c.eval(b));
        let (da, db) = (c.eval_d(a) * (b - a), c.eval_d(b) * (b - a));
        let cub = [pa, pa + da / 3.0, pb - db / 3.0, pb];
        let ok = (1..32).all(|i| {
            let s = i as f64 / 32.0;
            let u = 1.0 - s;
            let q = (cub[0].to_vec2() * (u * u * u)
                + cub[1].to_vec2() * (3.0 * s * u * u)
                + cub[2].to_vec2() * (3.0 * s * s * u)
                + cub[3].to_vec2() * (s * s * s))
                .to_point();
            (q - c.eval(a + (b - a) * s)).hypot() <= tol
        });
        if ok || depth >= 20 {
            out.push((a, b, cub));
        } else {
            let m = 0.5 * (a + b);
            rec(c, a, m, tol, depth + 1, out);
            rec(c, m, b, tol, depth + 1, out);
        }
    }
    rec(c, 0.0, 1.0, tol, 0, &mut out);
    out
}

/// SVG path data `M x y C ...` (the curve's own coordinates) for the NURBS's Bézier spans.
pub fn svg_path_data(c: &Nurbs, tol: f64) -> Option<String> {
    let spans = c.bezier_spans()?;
    let mut d = String::new();
    for (i, s) in spans.iter().enumerate() {
        for (j, cub) in cubics_for(s, tol).iter().enumerate() {
            if i == 0 && j == 0 {
                let _ = write!(d, "M {:?} {:?}", cub[0].x, cub[0].y);
            }
            let _ = write!(
                d,
                " C {:?} {:?} {:?} {:?} {:?} {:?}",
                cub[1].x, cub[1].y, cub[2].x, cub[2].y, cub[3].x, cub[3].y
            );
        }
    }
    Some(d)
}

/// A sample of a curve for the comb: point, unit left normal, signed curvature.
pub type CombSample = (Point, aesthetic_curves::Vec2, f64);

/// Comb samples of any curve of the library ([`aesthetic_curves::Curve`]): `n` points per
/// piece with the exact tangent and curvature.
pub fn curve_samples(
    curve: &dyn aesthetic_curves::Curve,
    n: usize,
) -> aesthetic_curves::Result<Vec<CombSample>> {
    Ok(curve
        .curve_points(n)?
        .into_iter()
        .map(|q| (q.p, q.normal(), q.kappa))
        .collect())
}

/// An SVG document whose path is the curve (cubic Béziers within `tol`, in the curve's own
/// coordinates: a group transform flips y for display), with the curve's curvature comb
/// (`comb`: [`curve_samples`]) drawn in the same coordinates.
pub fn svg_document(c: &Nurbs, tol: f64, comb: &[CombSample], caption: &str) -> Option<String> {
    let d = svg_path_data(c, tol)?;
    let size = c.size().max(1e-300);
    // A curvature under 1e-9 of the size's is the rounding of zero (a line drawn as a
    // cubic): no tooth, and no comb scaled up from such noise.
    let flat = 1e-9 / size;
    let kmax = comb.iter().map(|s| s.2.abs()).fold(0.0, f64::max);
    let scale = if kmax > flat {
        -0.25 * size / kmax
    } else {
        0.0
    };
    let tips: Vec<Point> = comb
        .iter()
        .map(|(p, n, k)| *p + *n * (if k.abs() < flat { 0.0 } else { *k } * scale))
        .collect();
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for p in c.control_points.iter().chain(&tips) {
        x0 = x0.min(p.x);
        x1 = x1.max(p.x);
        y0 = y0.min(p.y);
        y1 = y1.max(p.y);
    }
    let m = 0.08 * size;
    let (x0, y0, w, h) = (x0 - m, y0 - m, x1 - x0 + 2.0 * m, y1 - y0 + 2.0 * m);
    let sw = 0.004 * size;
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"{x0:?} {:?} {w:?} {h:?}\" width=\"720\" height=\"{:.0}\">\n\
         <title>{}</title>\n<rect x=\"{x0:?}\" y=\"{:?}\" width=\"{w:?}\" height=\"{h:?}\" fill=\"white\"/>\n\
         <g transform=\"scale(1 -1)\">\n",
        -(y0 + h),
        720.0 * h / w,
        caption.replace('&', "&amp;").replace('<', "&lt;"),
        -(y0 + h),
    );
    for (i, (p, _, _)) in comb.iter().enumerate() {
        let q = tips[i];
        let _ = writeln!(
            s,
            "<line x1=\"{:?}\" y1=\"{:?}\" x2=\"{:?}\" y2=\"{:?}\" stroke=\"#9ecae1\" stroke-width=\"{:?}\"/>",
            p.x, p.y, q.x, q.y, sw * 0.4
        );
    }
    let poly: Vec<String> = c
        .control_points
        .iter()
        .map(|p| format!("{:?},{:?}", p.x, p.y))
        .collect();
    let _ = writeln!(
        s,
        "<polyline points=\"{}\" fill=\"none\" stroke=\"#999\" stroke-width=\"{:?}\" stroke-dasharray=\"{:?} {:?}\"/>",
        poly.join(" "),
        sw * 0.5,
        sw * 3.0,
        sw * 2.0
    );
    let _ = writeln!(
        s,
        "<path id=\"curve\" d=\"{d}\" fill=\"none\" stroke=\"#d62728\" stroke-width=\"{:?}\"/>\n</g>\n</svg>",
        sw * 1.5
    );
    Some(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Nurbs {
        let c = RationalBezier::new(
            vec![
                Point::new(0.0, 0.0),
                Point::new(6.0, 0.0),
                Point::new(12.0, 3.0),
                Point::new(16.0, 9.0),
            ],
            vec![0.98, 0.92, 0.92, 0.97],
        )
        .unwrap();
        Nurbs::from_bezier(&c)
    }

    #[test]
    fn iges_lines_are_80_columns_with_sections_in_order() {
        let t = iges_text(&sample(), "c");
        let mut last = ' ';
        for l in t.lines() {
            assert_eq!(l.len(), 80, "{l}");
            let sec = l.as_bytes()[72] as char;
            assert!("SGDPT".find(sec) >= "SGDPT".find(last).or(Some(0)), "{l}");
            last = sec;
        }
        assert!(t.contains("126,3,3,1,0,0,0,"));
    }

    #[test]
    fn step_has_the_rational_curve_and_round_trips_numbers() {
        let t = step_text(&sample(), "c");
        assert!(t.starts_with("ISO-10303-21;"));
        assert!(t.contains("B_SPLINE_CURVE_WITH_KNOTS((4,4),(0.0,1.0),.UNSPECIFIED.)"));
        assert!(t.contains("RATIONAL_B_SPLINE_CURVE((0.98,0.92,0.92,0.97))"));
        assert_eq!(step_real(1.0), "1.0");
        assert_eq!(step_real(1e-9), "1.E-9");
        assert_eq!(step_real(0.1).parse::<f64>().unwrap(), 0.1);
    }

    #[test]
    fn svg_cubics_stay_within_tolerance() {
        let n = sample();
        let spans = n.bezier_spans().unwrap();
        let tol = 1e-6;
        let pieces = cubic_pieces(&spans[0], tol);
        assert!(pieces.len() > 1);
        assert_eq!(pieces[0].0, 0.0);
        assert_eq!(pieces[pieces.len() - 1].1, 1.0);
        for (a, b, c) in &pieces {
            for j in 0..=50 {
                let s = j as f64 / 50.0;
                let u = 1.0 - s;
                let q = (c[0].to_vec2() * (u * u * u)
                    + c[1].to_vec2() * (3.0 * s * u * u)
                    + c[2].to_vec2() * (3.0 * s * s * u)
                    + c[3].to_vec2() * (s * s * s))
                    .to_point();
                let d = (spans[0].eval(a + (b - a) * s) - q).hypot();
                assert!(d <= 2.0 * tol, "[{a}, {b}] at {s}: {d}");
            }
        }
        assert!(svg_path_data(&n, tol).unwrap().starts_with("M 0.0 0.0 C"));
    }
}
