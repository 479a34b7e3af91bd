//! The JSON protocol of `aecurve batch` and the editor (`docs/protocol.md` in the repository).
//!
//! [`handle_line`] turns one request line into one response object and never panics: a line
//! that is not JSON gets a `parse` error, an unknown op `unknown_op`, a bad parameter
//! `invalid_input` naming the field, and library errors keep their own kind. Nothing in a
//! result is NaN or infinite (checked once more before a response leaves).

use crate::any_bezier::AnyBezier;
pub use crate::json_out::{end_curvature_json, finite_or_null, object};
use aesthetic_curves::curve::MAX_NURBS_PIECES;
use aesthetic_curves::{Curve, Error, Point, RationalBezier};
use serde_json::{json, Map, Value};

/// Largest number of divisions the sampling test accepts from a request.
pub const MAX_SAMPLES: u64 = 1_000_000;

/// A protocol error: kind and message for a person.
#[derive(Debug, Clone, PartialEq)]
pub struct ProtoError {
    /// `parse`, `unknown_op`, `invalid_input`, `degenerate`, `no_segment`, `no_convergence`.
    pub kind: &'static str,
    /// What went wrong.
    pub message: String,
}

impl ProtoError {
    /// An `invalid_input` error naming the field.
    pub fn invalid(field: &str, message: impl std::fmt::Display) -> Self {
        ProtoError {
            kind: "invalid_input",
            message: format!("{field}: {message}"),
        }
    }
}

impl From<Error> for ProtoError {
    fn from(e: Error) -> Self {
        ProtoError {
            kind: e.kind(),
            message: e.message(),
        }
    }
}

/// The ops this build answers (every op of batch-protocol.md).
pub const OPS: &[&str] = &[
    "bezier.curvature_monotone",
    "lac.point",
    "lac.segment",
    "lac.inflection_segment",
    "lcg.estimate",
    "lac.rational_approx",
    "spline.pseudo_elastic",
    "spline.lac",
    "lac.fit",
    "sketch.fit",
    "sketch.contour",
    "outline.check",
    "outline.fix",
];

/// Answer one request line (JSON text) with one response object.
pub fn handle_line(line: &str) -> Value {
    match serde_json::from_str::<Value>(line) {
        Ok(v) => handle_value(&v),
        Err(e) => {
            let msg = e.to_string();
            // serde_json rejects numbers beyond f64's range while parsing: to the protocol
            // that is an infinite number, i.e. invalid input, not malformed JSON.
            let kind = if msg.contains("number out of range") {
                "invalid_input"
            } else {
                "parse"
            };
            error_response(
                Value::Null,
                ProtoError {
                    kind,
                    message: format!("request is not valid JSON: {msg}"),
                },
            )
        }
    }
}

/// Answer one parsed request.
pub fn handle_value(v: &Value) -> Value {
    let Some(obj) = v.as_object() else {
        return error_response(
            Value::Null,
            ProtoError::invalid("request", "must be a JSON object"),
        );
    };
    let id = obj.get("id").cloned().unwrap_or(Value::Null);
    match dispatch(obj) {
        Ok(result) => {
            if let Some(path) = first_non_finite(&result, String::new()) {
                return error_response(
                    id,
                    ProtoError {
                        kind: "no_convergence",
                        message: format!("internal: the result has a non-finite value at {path}"),
                    },
                );
            }
            object([("id", id), ("ok", Value::Bool(true)), ("result", result)])
        }
        Err(e) => error_response(id, e),
    }
}

/// `{"id", "ok": false, "error": {"kind", "message"}}`.
pub fn error_response(id: Value, e: ProtoError) -> Value {
    json!({"id": id, "ok": false, "error": {"kind": e.kind, "message": e.message}})
}

fn dispatch(obj: &Map<String, Value>) -> Result<Value, ProtoError> {
    let op = match obj.get("op") {
        Some(Value::String(s)) => s.as_str(),
        Some(_) => return Err(ProtoError::invalid("op", "must be a string")),
        None => return Err(ProtoError::invalid("op", "missing")),
    };
    match op {
        "bezier.curvature_monotone" => curvature_monotone(obj),
        "lac.point" => lac_point(obj),
        "lac.segment" => lac_segment(obj),
        "lac.inflection_segment" => lac_inflection_segment(obj),
        "lcg.estimate" => lcg_estimate(obj),
        "lac.rational_approx" => lac_rational_approx(obj),
        "spline.pseudo_elastic" => spline_pseudo_elastic(obj),
        "spline.lac" => spline_lac(obj),
        "lac.fit" => lac_fit(obj),
        "sketch.fit" => sketch_fit(obj),
        "sketch.contour" => sketch_contour(obj),
        "outline.check" => outline_check(obj),
        "outline.fix" => outline_fix(obj),
        _ => Err(ProtoError {
            kind: "unknown_op",
            message: format!(
                "unknown op '{}'; known: {}",
                // A long name is not echoed whole.
                if op.chars().count() > 64 {
                    format!("{}...", op.chars().take(64).collect::<String>())
                } else {
                    op.to_string()
                },
                OPS.join(", ")
            ),
        }),
    }
}

fn finite_number(v: &Value, field: &str) -> Result<f64, ProtoError> {
    match v.as_f64() {
        Some(x) if x.is_finite() => Ok(x),
        Some(_) => Err(ProtoError::invalid(field, "must be a finite number")),
        None => Err(ProtoError::invalid(field, "must be a number")),
    }
}

/// A required array of `[x, y]` points with a count in `min..=max`.
pub fn points_param(
    obj: &Map<String, Value>,
    field: &str,
    min: usize,
    max: usize,
) -> Result<Vec<Point>, ProtoError> {
    let arr = match obj.get(field) {
        Some(Value::Array(a)) => a,
        Some(_) => {
            return Err(ProtoError::invalid(
                field,
                "must be an array of [x, y] points",
            ))
        }
        None => return Err(ProtoError::invalid(field, "missing")),
    };
    if arr.len() < min || arr.len() > max {
        return Err(ProtoError::invalid(
            field,
            format!("needs {min} to {max} points, got {}", arr.len()),
        ));
    }
    arr.iter()
        .enumerate()
        .map(|(i, p)| {
            let name = format!("{field}[{i}]");
            match p.as_array() {
                Some(xy) if xy.len() == 2 => Ok(Point::new(
                    finite_number(&xy[0], &name)?,
                    finite_number(&xy[1], &name)?,
                )),
                _ => Err(ProtoError::invalid(
                    &name,
                    "must be an [x, y] pair of numbers",
                )),
            }
        })
        .collect()
}

/// An optional array of `len` finite numbers.
pub fn numbers_param(
    obj: &Map<String, Value>,
    field: &str,
    len: usize,
) -> Result<Option<Vec<f64>>, ProtoError> {
    match obj.get(field) {
        None | Some(Value::Null) => Ok(None),
        Some(Value::Array(a)) => {
            if a.len() != len {
                return Err(ProtoError::invalid(
                    field,
                    format!(
                        "needs {len} numbers (one per control point), got {}",
                        a.len()
                    ),
                ));
            }
            a.iter()
                .enumerate()
                .map(|(i, v)| finite_number(v, &format!("{field}[{i}]")))
                .collect::<Result<Vec<_>, _>>()
                .map(Some)
        }
        Some(_) => Err(ProtoError::invalid(field, "must be an array of numbers")),
    }
}

/// An optional positive integer in `1..=max`.
pub fn count_param(
    obj: &Map<String, Value>,
    field: &str,
    default: u64,
    max: u64,
) -> Result<u64, ProtoError> {
    match obj.get(field) {
        None | Some(Value::Null) => Ok(default),
        Some(v) => match v.as_u64() {
            Some(n) if (1..=max).contains(&n) => Ok(n),
            _ => Err(ProtoError::invalid(
                field,
                format!("must be an integer from 1 to {max}"),
            )),
        },
    }
}

fn string_param<'a>(
    obj: &'a Map<String, Value>,
    field: &str,
    default: &'a str,
    allowed: &[&str],
) -> Result<&'a str, ProtoError> {
    let s = match obj.get(field) {
        None | Some(Value::Null) => default,
        Some(Value::String(s)) => s.as_str(),
        Some(_) => return Err(ProtoError::invalid(field, "must be a string")),
    };
    if allowed.contains(&s) {
        Ok(s)
    } else {
        Err(ProtoError::invalid(
            field,
            format!("must be one of {}", allowed.join(", ")),
        ))
    }
}

fn curvature_monotone(obj: &Map<String, Value>) -> Result<Value, ProtoError> {
    let points = points_param(obj, "control_points", 2, 21)?;
    let weights = numbers_param(obj, "weights", points.len())?;
    if let Some(w) = &weights {
        if let Some(i) = w.iter().position(|v| *v <= 0.0) {
            return Err(ProtoError::invalid(
                &format!("weights[{i}]"),
                "weights must be > 0",
            ));
        }
    }
    let method = string_param(obj, "method", "exact", &["exact", "sampling"])?;
    let draw = draw_param(obj)?;
    let curve = AnyBezier::new(points, weights)?;
    let c = curve.as_monotone();
    let mut out = if method == "exact" {
        if obj.get("samples").is_some_and(|v| !v.is_null()) {
            // Accepted and ignored would hide a mistake: say so.
            return Err(ProtoError::invalid(
                "samples",
                "only applies to method \"sampling\"",
            ));
        }
        monotone_json(&c.curvature_monotone()?)
    } else {
        let n = count_param(obj, "samples", 100, MAX_SAMPLES)?;
        sampled_json(&c.curvature_monotone_sampled(n as usize)?)
    };
    if let Some(n) = draw {
        let rational = match &curve {
            AnyBezier::Poly(b) => b.to_rational(),
            AnyBezier::Rational(r) => r.clone(),
        };
        let nurbs = aesthetic_curves::nurbs::Nurbs::from_bezier(&rational);
        let mut d = drawing_json(curve.as_curve(), n, Some(&nurbs))?;
        // The interior curvature extrema, where a picture circles them.
        let ts: Vec<f64> = out["extrema"]
            .as_array()
            .map(|a| a.iter().filter_map(|v| v.as_f64()).collect())
            .unwrap_or_default();
        d["marks"] = json!(ts
            .iter()
            .map(|&t| {
                let p = curve.eval(t);
                [p.x, p.y]
            })
            .collect::<Vec<_>>());
        out["drawing"] = d;
    }
    Ok(out)
}

/// The result of `bezier.curvature_monotone` (exact test), also `aecurve monotone --json`.
pub fn monotone_json(r: &aesthetic_curves::MonotoneReport) -> Value {
    json!({
        "monotone": r.monotone,
        "extrema": r.extrema,
        "test_degree": r.test_degree,
        "trend": r.trend.map(|t| t.as_str()),
        "exact_arithmetic": r.exact,
        "ends": r.ends.iter().map(end_curvature_json).collect::<Vec<_>>(),
    })
}

/// The result of `bezier.curvature_monotone` with `"method": "sampling"`.
pub fn sampled_json(r: &aesthetic_curves::SampledReport) -> Value {
    json!({
        "monotone": r.monotone,
        "samples": r.samples,
        "trend": r.trend.map(|t| t.as_str()),
    })
}

/// Largest number of parameters in one request.
pub const MAX_THETAS: usize = 100_000;

fn number_param(obj: &Map<String, Value>, field: &str) -> Result<f64, ProtoError> {
    match obj.get(field) {
        Some(v) => finite_number(v, field),
        None => Err(ProtoError::invalid(field, "missing")),
    }
}

fn lac_point(obj: &Map<String, Value>) -> Result<Value, ProtoError> {
    let alpha = number_param(obj, "alpha")?;
    let lambda = number_param(obj, "lambda")?;
    let thetas: Vec<f64> = match obj.get("theta") {
        Some(Value::Array(a)) => {
            if a.len() > MAX_THETAS {
                return Err(ProtoError::invalid(
                    "theta",
                    format!("at most {MAX_THETAS} values, got {}", a.len()),
                ));
            }
            a.iter()
                .enumerate()
                .map(|(i, v)| finite_number(v, &format!("theta[{i}]")))
                .collect::<Result<_, _>>()?
        }
        Some(v) if v.is_number() => vec![finite_number(v, "theta")?],
        Some(_) => return Err(ProtoError::invalid("theta", "must be an array of numbers")),
        None => return Err(ProtoError::invalid("theta", "missing")),
    };
    let c = aesthetic_curves::lac::LacStandard::new(alpha, lambda)?;
    let points = c.eval_many(&thetas)?;
    let arc: Vec<f64> = thetas
        .iter()
        .map(|t| c.arc_length(*t))
        .collect::<Result<_, _>>()?;
    let kappa: Vec<f64> = thetas
        .iter()
        .map(|t| c.kappa(*t))
        .collect::<Result<_, _>>()?;
    Ok(json!({
        "points": points.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>(),
        "arc_length": arc,
        "curvature": kappa,
    }))
}

/// Largest number of samples of a segment.
pub const MAX_SEGMENT_SAMPLES: u64 = 100_000;

fn lac_segment(obj: &Map<String, Value>) -> Result<Value, ProtoError> {
    let alpha = number_param(obj, "alpha")?;
    let control = points_param(obj, "control", 3, 3)?;
    let samples = count_param(obj, "samples", 65, MAX_SEGMENT_SAMPLES)?;
    if samples < 2 {
        return Err(ProtoError::invalid("samples", "must be at least 2"));
    }
    let draw = draw_param(obj)?;
    let seg = aesthetic_curves::lac::LacSegment::new(alpha, [control[0], control[1], control[2]])?;
    let mut out = lac_segment_json(&seg, samples as usize)?;
    if let Some(n) = draw {
        // No NURBS: a LAC segment has no exact rational form (lac.rational_approx gives one).
        out["drawing"] = drawing_json(&seg, n, None)?;
    }
    Ok(out)
}

/// The result of `lac.segment` (also `aecurve lac --json`): the segment's numbers and
/// `samples >= 2` points with their curvature.
pub fn lac_segment_json(
    seg: &aesthetic_curves::lac::LacSegment,
    samples: usize,
) -> Result<Value, aesthetic_curves::Error> {
    let (k0, k1) = seg.end_curvatures()?;
    let fields = json!({
        "lambda": seg.lambda(),
        "theta_d": seg.theta_d(),
        "arc_length": seg.arc_length()?,
        "curvature_start": k0,
        "curvature_end": k1,
    });
    Ok(with_samples(fields, seg.sample(samples)?))
}

/// The base result of `lac.inflection_segment` (also `aecurve lac --inflection --json`).
pub fn lac_inflection_json(
    seg: &aesthetic_curves::lac::LacInflectionSegment,
    samples: usize,
) -> Result<Value, aesthetic_curves::Error> {
    let fields = json!({
        "alpha": seg.alpha(),
        "theta_d": seg.theta_d(),
        "arc_length": seg.arc_length(),
        "curvature_end": seg.end_curvature(),
    });
    Ok(with_samples(fields, seg.sample(samples)?))
}

/// `fields` with a sampling's `points` and their `curvature`.
fn with_samples(mut fields: Value, samples: aesthetic_curves::Polyline) -> Value {
    fields["points"] = samples.points.iter().map(|p| [p.x, p.y]).collect();
    fields["curvature"] = samples.kappa.into();
    fields
}

fn lac_inflection_segment(obj: &Map<String, Value>) -> Result<Value, ProtoError> {
    let control = points_param(obj, "control", 3, 3)?;
    let samples = count_param(obj, "samples", 65, MAX_SEGMENT_SAMPLES)?;
    if samples < 2 {
        return Err(ProtoError::invalid("samples", "must be at least 2"));
    }
    let tolerance = optional_number(obj, "tolerance")?;
    if let Some(t) = tolerance {
        if t <= 0.0 {
            return Err(ProtoError::invalid("tolerance", "must be > 0"));
        }
    }
    let draw = draw_param(obj)?;
    let seg =
        aesthetic_curves::lac::LacInflectionSegment::new([control[0], control[1], control[2]])?;
    let mut out = lac_inflection_json(&seg, samples as usize)?;
    if let Some(n) = draw {
        out["drawing"] = drawing_json(&seg, n, None)?;
    }
    // Optional: the segment's rational cubic (κ = 0 at its start, G2 at its end, curvature
    // proven monotone), as `lac.rational_approx` gives for a LAC segment.
    if obj.get("rational") == Some(&Value::Bool(true)) {
        let fit = aesthetic_curves::approx::fit_inflection_cubic(
            &seg,
            &aesthetic_curves::approx::ApproxOptions::default(),
        )?;
        out["rational"] = json!({
            "control_points": fit.curve.points().iter().map(|p| [p.x, p.y]).collect::<Vec<_>>(),
            "weights": fit.curve.weights(),
            "max_error": fit.max_error,
            "monotone": fit.monotone,
        });
        if let Some(n) = draw {
            let nurbs = aesthetic_curves::nurbs::Nurbs::from_bezier(&fit.curve);
            out["rational"]["drawing"] = drawing_json(&fit.curve, n, Some(&nurbs))?;
        }
    }
    // Optional: rational cubics within `tolerance` (input units), G2, as one NURBS, as
    // `lac.rational_approx` gives with a tolerance.
    if let Some(t) = tolerance {
        let sp = aesthetic_curves::approx::fit_inflection_spline(
            &seg,
            t,
            MAX_NURBS_PIECES,
            &aesthetic_curves::approx::ApproxOptions::default(),
        )?;
        out["spline"] = rational_spline_json(&sp);
    }
    Ok(out)
}

/// The `spline` member of `lac.rational_approx` and `lac.inflection_segment`.
fn rational_spline_json(sp: &aesthetic_curves::approx::RationalSpline) -> Value {
    json!({
        "degree": sp.nurbs.degree,
        "knots": sp.nurbs.knots,
        "control_points": sp.nurbs.control_points.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>(),
        "weights": sp.nurbs.weights,
        "pieces": sp.pieces.len(),
        "max_error": sp.max_error,
        "monotone": sp.pieces.iter().all(|p| p.monotone),
    })
}

fn optional_number(obj: &Map<String, Value>, field: &str) -> Result<Option<f64>, ProtoError> {
    match obj.get(field) {
        None | Some(Value::Null) => Ok(None),
        Some(v) => finite_number(v, field).map(Some),
    }
}

/// Largest `draw` (points per piece).
pub const MAX_DRAW_SAMPLES: u64 = 2000;

/// The optional `draw` parameter: points per piece of the `drawing` member (None: absent).
fn draw_param(obj: &Map<String, Value>) -> Result<Option<usize>, ProtoError> {
    match obj.get("draw") {
        None | Some(Value::Null) => Ok(None),
        Some(v) => match v.as_u64() {
            Some(n) if (2..=MAX_DRAW_SAMPLES).contains(&n) => Ok(Some(n as usize)),
            _ => Err(ProtoError::invalid(
                "draw",
                format!("must be an integer from 2 to {MAX_DRAW_SAMPLES} (points per piece)"),
            )),
        },
    }
}

/// Most points one `drawing` member holds (pieces times points per piece): about 110 bytes
/// of JSON and up to 1 KB of memory each while the answer is built (measured), so a drawing
/// stays under about 200 MB. A screen is a few thousand pixels wide: no picture needs more.
pub const MAX_DRAWING_POINTS: usize = 200_000;

/// `invalid_input` on `draw` when `pieces` pieces at `n` points each are over
/// [`MAX_DRAWING_POINTS`]: checked before any work where the pieces are known from the
/// request (a spline's points, an outline's segments), and for `sketch.fit`, whose pieces
/// the fit decides, after the fit and before the drawing.
fn drawing_budget(pieces: usize, n: usize) -> Result<(), ProtoError> {
    if pieces.saturating_mul(n) > MAX_DRAWING_POINTS {
        let most = (MAX_DRAWING_POINTS / pieces.max(1)).max(1);
        return Err(ProtoError::invalid(
            "draw",
            format!(
                "{pieces} pieces at {n} points each is over the drawing budget of \
                 {MAX_DRAWING_POINTS} points: ask for at most {most} points per piece"
            ),
        ));
    }
    Ok(())
}

/// The `drawing` member (with `draw`): what a picture of the result needs, computed here so
/// that a client draws without evaluating curves itself: `n` points per piece with the
/// curve's unit left normal and signed curvature (consecutive pieces share their joint), the
/// number of pieces, and the curve as one NURBS (what an export writes).
pub fn drawing_json(
    curve: &dyn aesthetic_curves::Curve,
    n: usize,
    nurbs: Option<&aesthetic_curves::nurbs::Nurbs>,
) -> Result<Value, Error> {
    let pts = curve.curve_points(n)?;
    let pieces = (pts.len() - 1) / (n - 1);
    let mut out = json!({
        "points": pts.iter().map(|q| [q.p.x, q.p.y]).collect::<Vec<_>>(),
        "normals": pts.iter().map(|q| { let v = q.normal(); [v.x, v.y] }).collect::<Vec<_>>(),
        "curvature": pts.iter().map(|q| q.kappa).collect::<Vec<_>>(),
        "per_piece": n,
        "pieces": pieces,
    });
    if let Some(c) = nurbs {
        out["nurbs"] = crate::export::json_text(c);
    }
    Ok(out)
}

fn lac_rational_approx(obj: &Map<String, Value>) -> Result<Value, ProtoError> {
    use aesthetic_curves::approx;
    let alpha = number_param(obj, "alpha")?;
    let control = points_param(obj, "control", 3, 3)?;
    let tolerance = optional_number(obj, "tolerance")?;
    if let Some(t) = tolerance {
        if t <= 0.0 {
            return Err(ProtoError::invalid("tolerance", "must be > 0"));
        }
    }
    let draw = draw_param(obj)?;
    let seg = aesthetic_curves::lac::LacSegment::new(alpha, [control[0], control[1], control[2]])?;
    let opts = approx::ApproxOptions::default();
    let fit = approx::fit_rational_cubic(&seg, &opts)?;
    let spline = tolerance
        .map(|t| approx::fit_rational_spline(&seg, t, MAX_NURBS_PIECES, &opts))
        .transpose()?;
    let mut out = rational_approx_json(&seg, &fit, spline.as_ref())?;
    if let Some(n) = draw {
        let nurbs = aesthetic_curves::nurbs::Nurbs::from_bezier(&fit.curve);
        out["drawing"] = drawing_json(&fit.curve, n, Some(&nurbs))?;
    }
    Ok(out)
}

/// The result object of `lac.rational_approx` (the `spline` member only with a spline).
pub fn rational_approx_json(
    seg: &aesthetic_curves::lac::LacSegment,
    fit: &aesthetic_curves::approx::RationalCubicFit,
    spline: Option<&aesthetic_curves::approx::RationalSpline>,
) -> Result<Value, Error> {
    let pts = |p: &[aesthetic_curves::Point]| p.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>();
    let mut out = json!({
        "control_points": pts(fit.curve.points()),
        "weights": fit.curve.weights(),
        "f0": fit.f0,
        "f1": fit.f1,
        "rms": fit.rms,
        "max_error": fit.max_error,
        "monotone": fit.monotone,
        "converged": fit.converged,
        "evaluations": fit.evaluations,
        "arc_length": seg.arc_length()?,
    });
    if let Some(sp) = spline {
        out["spline"] = rational_spline_json(sp);
    }
    Ok(out)
}

/// Largest point sequence `lac.fit` accepts.
pub const MAX_FIT_POINTS: usize = 20_000;

fn lac_fit(obj: &Map<String, Value>) -> Result<Value, ProtoError> {
    let points = points_param(obj, "points", 6, MAX_FIT_POINTS)?;
    let alpha = optional_number(obj, "alpha")?;
    use aesthetic_curves::lac_fit::LacFitObjective;
    let objective = match obj.get("objective") {
        None | Some(Value::Null) => LacFitObjective::Band,
        Some(Value::String(s)) if s == "band" => LacFitObjective::Band,
        Some(Value::String(s)) if s == "arc_length" => LacFitObjective::ArcLength,
        Some(Value::String(s)) if s == "distance" => LacFitObjective::Distance,
        Some(_) => {
            return Err(ProtoError::invalid(
                "objective",
                "must be \"band\" (default: the narrowest band around the curve), \
                 \"distance\" (least squares) or \"arc_length\" (the paper's)",
            ))
        }
    };
    use aesthetic_curves::lac_fit::LacFitStart;
    let start = match obj.get("start") {
        None | Some(Value::Null) => LacFitStart::Scan,
        Some(Value::String(s)) if s == "scan" => LacFitStart::Scan,
        Some(Value::String(s)) if s == "paper" => LacFitStart::Paper,
        Some(_) => {
            return Err(ProtoError::invalid(
                "start",
                "must be \"scan\" (default: least squares over all alpha) or \"paper\" \
                 (alpha guessed from the curvature graph, kept within 10 %)",
            ))
        }
    };
    let f = aesthetic_curves::lac_fit::fit_lac(
        &points,
        aesthetic_curves::lac_fit::LacFitOptions {
            alpha,
            objective,
            start,
        },
    )?;
    let c = f.segment.control();
    let mut o = json!({
        "alpha": f.alpha,
        "control": c.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>(),
        "rms_deviation": f.rms_deviation,
        "max_deviation": f.max_deviation,
        "rms_correspondence": f.rms_correspondence,
        "converged": f.converged,
        "objective": objective.as_str(),
        "max_curvature": f.max_curvature,
        "alpha_at_bound": f.alpha_at_bound,
    });
    if let Some(c) = f.curvature_cap {
        o["curvature_cap"] = json!(c);
    }
    // The paper start's guess, where there is one (absent rather than null otherwise).
    if let Some(g) = f.alpha_guess {
        o["alpha_guess"] = json!(g);
    }
    Ok(o)
}

/// Largest point sequence `sketch.fit` accepts.
pub const MAX_SKETCH_POINTS: usize = 20_000;

fn sketch_fit(obj: &Map<String, Value>) -> Result<Value, ProtoError> {
    let points = points_param(obj, "points", 4, MAX_SKETCH_POINTS)?;
    let tolerance = sketch_tolerance(obj)?
        .unwrap_or_else(|| aesthetic_curves::sketch::default_tolerance(&points));
    let draw = draw_param(obj)?;
    let sk = aesthetic_curves::sketch::fit_sketch(
        &points,
        &aesthetic_curves::sketch::SketchOptions::with_tolerance(tolerance),
    )?;
    let mut out = sketch_json(&sk, tolerance);
    if let Some(n) = draw {
        out["drawing"] = pieces_drawing(&sk.as_curve(), n)?;
    }
    Ok(out)
}

/// The optional `tolerance` of the sketch ops: positive, or absent for the default.
fn sketch_tolerance(obj: &Map<String, Value>) -> Result<Option<f64>, ProtoError> {
    match optional_number(obj, "tolerance")? {
        Some(t) if t > 0.0 => Ok(Some(t)),
        Some(_) => Err(ProtoError::invalid("tolerance", "must be positive")),
        None => Ok(None),
    }
}

/// The drawing of a curve of rational cubics (a sketch, a contour), within the drawing
/// budget for its pieces.
fn pieces_drawing(
    curve: &aesthetic_curves::Pieces<aesthetic_curves::RationalBezier>,
    n: usize,
) -> Result<Value, ProtoError> {
    drawing_budget(curve.0.len(), n)?;
    let nurbs = curve.to_exact_nurbs()?;
    Ok(drawing_json(curve, n, Some(&nurbs))?)
}

fn sketch_contour(obj: &Map<String, Value>) -> Result<Value, ProtoError> {
    use aesthetic_curves::sketch::contour::{fit_contour, ContourOptions};
    let points = points_param(obj, "points", 2, MAX_SKETCH_POINTS)?;
    let tolerance = sketch_tolerance(obj)?;
    let closed = match obj.get("closed") {
        None | Some(Value::Null) => None,
        Some(Value::Bool(b)) => Some(*b),
        Some(_) => return Err(ProtoError::invalid("closed", "must be true, false or null")),
    };
    let mut opts = ContourOptions {
        tolerance,
        closed,
        ..Default::default()
    };
    if let Some(a) = optional_number(obj, "corner_angle_degrees")? {
        if !(a > 0.0 && a < 180.0) {
            return Err(ProtoError::invalid(
                "corner_angle_degrees",
                "must lie in (0, 180)",
            ));
        }
        opts.corner_angle = a.to_radians();
    }
    let draw = draw_param(obj)?;
    let c = fit_contour(&points, &opts)?;
    let mut out = contour_json(&c);
    if let Some(n) = draw {
        out["drawing"] = pieces_drawing(&c.as_curve()?, n)?;
    }
    Ok(out)
}

/// The `sketch.contour` result of a contour (shared with `aecurve sketch --contour --json`).
pub fn contour_json(c: &aesthetic_curves::sketch::contour::SketchContour) -> Value {
    use aesthetic_curves::sketch::contour::Run;
    let xy = |p: aesthetic_curves::Point| [p.x, p.y];
    let runs: Vec<Value> = c
        .runs
        .iter()
        .map(|r| match r {
            Run::Line { start, end } => {
                json!({"kind": "line", "start": xy(*start), "end": xy(*end)})
            }
            Run::Curve(sk) => {
                let mut o = sketch_json(sk, c.tolerance);
                o["kind"] = json!("curve");
                o
            }
        })
        .collect();
    let corners: Vec<Value> = c
        .corners
        .iter()
        .map(|k| json!({"index": k.index, "point": xy(k.point), "angle_degrees": k.angle.to_degrees(), "run": k.run}))
        .collect();
    let smooth: Vec<Value> = c
        .smooth_joins
        .iter()
        .map(|j| json!({"run": j.run, "point": xy(j.point), "angle_degrees": j.angle.to_degrees(), "curvature_jump": j.curvature_jump}))
        .collect();
    let mut out = json!({
        "runs": runs,
        "corners": corners,
        "smooth_joins": smooth,
        "closed": c.closed,
        "pieces": c.pieces(),
        "tolerance": c.tolerance,
        "max_deviation": c.max_deviation,
        "trimmed": c.trimmed,
    });
    if let Some(s) = c.seam {
        out["seam"] =
            json!({"angle_degrees": s.angle.to_degrees(), "curvature_jump": s.curvature_jump});
    }
    out
}

/// One piece of a sketch or a spline as both ops send it: its kind, control triangle, end
/// curvatures, rational cubic and monotone verdict (the callers add their own fields).
fn piece_json(
    kind: &str,
    control: &[aesthetic_curves::Point; 3],
    ends: (f64, f64),
    rational: &aesthetic_curves::RationalBezier,
    monotone: bool,
) -> Value {
    let pts = |ps: &[aesthetic_curves::Point]| ps.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>();
    json!({
        "kind": kind,
        "control": pts(control),
        "end_curvatures": [ends.0, ends.1],
        "rational": {
            "control_points": pts(rational.points()),
            "weights": rational.weights(),
        },
        "monotone": monotone,
    })
}

/// The `sketch.fit` result of a sketch (shared with `aecurve sketch --json`).
pub fn sketch_json(sk: &aesthetic_curves::sketch::Sketch, tolerance: f64) -> Value {
    // Absent rather than null where a number is undefined (protocol: no NaN, no infinity).
    let put = |o: &mut Value, key: &str, v: Option<f64>| {
        if let Some(v) = v.filter(|v| v.is_finite()) {
            o[key] = json!(v);
        }
    };
    let pts = |ps: &[aesthetic_curves::Point]| ps.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>();
    let segments: Vec<Value> = sk
        .pieces
        .iter()
        .map(|p| {
            let mut o = piece_json(
                p.kind.as_str(),
                &p.control,
                p.end_curvatures,
                &p.rational,
                p.monotone,
            );
            o["alpha"] = json!(p.alpha);
            o["alpha_at_bound"] = json!(p.alpha_at_bound);
            put(&mut o, "alpha_estimate", p.alpha_estimate);
            put(&mut o, "rational_error", Some(p.rational_error));
            o
        })
        .collect();
    let mut fairing = json!({
        "iterations": sk.fairing.iterations,
        "converged": sk.fairing.converged,
    });
    put(&mut fairing, "initial_jump", Some(sk.fairing.initial_jump));
    put(&mut fairing, "final_jump", Some(sk.fairing.final_jump));
    let mut o = json!({
        "segments": segments,
        "bspline": {
            "degree": sk.bspline.degree,
            "knots": sk.bspline.knots,
            "control_points": pts(&sk.bspline.control_points),
        },
        "tolerance": tolerance,
        "max_deviation": sk.max_deviation,
        "rms_deviation": sk.rms_deviation,
        "g2": sk.g2,
        "all_monotone": sk.all_monotone,
        "inflections": sk.inflections,
        "curvature_extrema": sk.curvature_extrema,
        "fairing": fairing,
    });
    put(&mut o, "max_curvature_jump", Some(sk.max_curvature_jump));
    o
}

/// An optional boolean (`default` when absent or null).
fn bool_param(obj: &Map<String, Value>, field: &str, default: bool) -> Result<bool, ProtoError> {
    match obj.get(field) {
        None | Some(Value::Null) => Ok(default),
        Some(Value::Bool(b)) => Ok(*b),
        Some(_) => Err(ProtoError::invalid(field, "must be true or false")),
    }
}

/// `outline.fix`: one contour of lines and cubics repaired as `aecurve fix` repairs an SVG
/// path (smooth joins by a tangent break of at most 0.5°; bumps first, then the joins), and
/// the result with what changed.
fn outline_fix(obj: &Map<String, Value>) -> Result<Value, ProtoError> {
    let Some(Value::Array(segs)) = obj.get("segments") else {
        return Err(ProtoError::invalid(
            "segments",
            "must be an array of segments, each with control_points",
        ));
    };
    if segs.is_empty() || segs.len() > MAX_OUTLINE_SEGMENTS {
        return Err(ProtoError::invalid(
            "segments",
            format!("must hold 1 to {MAX_OUTLINE_SEGMENTS} segments"),
        ));
    }
    let mut segments = Vec::with_capacity(segs.len());
    for (i, v) in segs.iter().enumerate() {
        let field = format!("segments[{i}].control_points");
        let o = v.as_object().ok_or_else(|| {
            ProtoError::invalid(
                &format!("segments[{i}]"),
                "must be an object with control_points",
            )
        })?;
        let pts = points_param(o, "control_points", 2, 4)
            .map_err(|e| ProtoError::invalid(&field, e.message))?;
        let weights = format!("segments[{i}].weights");
        let w = numbers_param(o, "weights", pts.len())
            .map_err(|e| ProtoError::invalid(&weights, e.message))?;
        if w.is_some_and(|w| w.iter().any(|x| *x != 1.0)) {
            return Err(ProtoError::invalid(
                &weights,
                "outline.fix repairs lines and polynomial cubics: weights must be 1",
            ));
        }
        if pts.len() == 3 {
            return Err(ProtoError::invalid(
                &field,
                "a quadratic: outline.fix repairs lines (2 points) and cubics (4)",
            ));
        }
        if let Some(prev) = segments.last().and_then(|s: &Vec<Point>| s.last()) {
            let size = (pts[0] - pts[pts.len() - 1]).hypot().max(1.0);
            if (*prev - pts[0]).hypot() > 1e-9 * size {
                return Err(ProtoError::invalid(
                    &format!("segments[{i}]"),
                    "must start where the previous segment ends",
                ));
            }
        }
        segments.push(pts);
    }
    let closed = bool_param(obj, "closed", false)?;
    let tolerance = finite_number(obj.get("tolerance").unwrap_or(&Value::Null), "tolerance")?;
    if tolerance <= 0.0 {
        return Err(ProtoError::invalid("tolerance", "must be a distance > 0"));
    }
    let grid = optional_number(obj, "grid")?.unwrap_or(0.0);
    if grid < 0.0 {
        return Err(ProtoError::invalid("grid", "must be a step >= 0 (0: none)"));
    }
    let opts = crate::fix::FixOptions {
        tolerance,
        grid,
        move_points: bool_param(obj, "move_points", false)?,
        repairs: aesthetic_curves::harmonize::Repairs {
            bumps: bool_param(obj, "bumps", true)?,
            ..Default::default()
        },
    };
    let (h, smooth) = crate::fix::fix_segments(&segments, closed, &opts)?;
    let pts = |v: &[Point]| v.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>();
    let joins: Vec<Value> = h
        .joins
        .iter()
        .map(|j| {
            let mut v = json!({"after_segment": j.after_segment, "smooth": smooth[j.after_segment],
                "outcome": format!("{:?}", j.outcome).to_lowercase(),
                "angle_degrees": [j.angle.0.to_degrees(), j.angle.1.to_degrees()]});
            // Undefined at a retracted handle: left out rather than null.
            if j.jump.0.is_finite() && j.jump.1.is_finite() {
                v["jump"] = json!([j.jump.0, j.jump.1]);
            }
            v
        })
        .collect();
    let changed = h
        .segments
        .iter()
        .zip(&segments)
        .filter(|(a, b)| a != b)
        .count();
    Ok(object([
        (
            "segments",
            Value::Array(
                h.segments
                    .iter()
                    .map(|s| json!({"control_points": pts(s)}))
                    .collect(),
            ),
        ),
        ("closed", json!(closed)),
        ("joins", Value::Array(joins)),
        ("changed_segments", json!(changed)),
        (
            "max_moved",
            json!(h.moved.iter().copied().fold(0.0, f64::max)),
        ),
        ("bumps_removed", json!(h.bumps.len())),
    ]))
}

/// Longest SVG path data `outline.check` accepts (characters).
pub const MAX_PATH_DATA: usize = 1 << 20;

/// Most segments `outline.check` checks and answers for in one request (as `segments`, or in
/// the shapes it checks of a path, an SVG or a file): each costs about 2 KB of answer and up
/// to 15 KB of memory while the answer is built, so an answer stays near 150 MB.
pub const MAX_OUTLINE_SEGMENTS: usize = 10_000;

/// `outline.check`: the exact check of one outline (`aecurve check` for one shape), given as
/// SVG path data (`path`; arcs become cubics, as usvg writes them) or as `segments` (each
/// `control_points` and optional `weights`, consecutive, with `closed`).
fn outline_check(obj: &Map<String, Value>) -> Result<Value, ProtoError> {
    use crate::outline_io::{check_shapes, finding_json, options_for, shape_json, Outlines};
    let outlines = match (obj.get("path"), obj.get("segments")) {
        (None, None) if obj.contains_key("svg") || obj.contains_key("file") => outline_file(obj)?,
        (Some(Value::String(d)), None) => {
            if d.len() > MAX_PATH_DATA {
                return Err(ProtoError::invalid(
                    "path",
                    format!("longer than {MAX_PATH_DATA} characters"),
                ));
            }
            let esc = d
                .replace('&', "&amp;")
                .replace('<', "&lt;")
                .replace('"', "&quot;");
            let doc = format!(
                r#"<svg xmlns="http://www.w3.org/2000/svg"><path id="path" d="{esc}"/></svg>"#
            );
            let o = crate::outline_io::read_svg(doc.as_bytes()).map_err(|e| {
                ProtoError::invalid("path", format!("{e:#} (SVG path data expected)"))
            })?;
            if o.shapes.is_empty() {
                let why = o
                    .unreadable
                    .first()
                    .map_or("it draws nothing", |u| u.1.as_str());
                return Err(ProtoError::invalid(
                    "path",
                    format!("the path data cannot be read: {why} (SVG path data expected)"),
                ));
            }
            o
        }
        (None, Some(Value::Array(segs))) => {
            if segs.is_empty() || segs.len() > MAX_OUTLINE_SEGMENTS {
                return Err(ProtoError::invalid(
                    "segments",
                    format!("must hold 1 to {MAX_OUTLINE_SEGMENTS} segments"),
                ));
            }
            let closed = match obj.get("closed") {
                None | Some(Value::Null) => false,
                Some(Value::Bool(b)) => *b,
                Some(_) => return Err(ProtoError::invalid("closed", "must be true or false")),
            };
            let mut segments = Vec::with_capacity(segs.len());
            for (i, v) in segs.iter().enumerate() {
                let Some(o) = v.as_object() else {
                    return Err(ProtoError::invalid(
                        &format!("segments[{i}]"),
                        "must be an object with control_points",
                    ));
                };
                let field = |f: &str| format!("segments[{i}].{f}");
                let pts = points_param(o, "control_points", 2, 21)
                    .map_err(|e| ProtoError::invalid(&field("control_points"), e.message))?;
                let w = numbers_param(o, "weights", pts.len())
                    .map_err(|e| ProtoError::invalid(&field("weights"), e.message))?
                    .unwrap_or_else(|| vec![1.0; pts.len()]);
                if w.iter().any(|v| *v <= 0.0) {
                    return Err(ProtoError::invalid(&field("weights"), "must be > 0"));
                }
                segments.push(RationalBezier::new(pts, w)?);
            }
            for (i, w) in segments.windows(2).enumerate() {
                let (a, b) = (w[0].points(), w[1].points());
                let gap = (a[a.len() - 1] - b[0]).hypot();
                let size = (a[0] - a[a.len() - 1]).hypot().max(1.0);
                if gap > 1e-9 * size {
                    return Err(ProtoError::invalid(
                        &format!("segments[{}]", i + 1),
                        "must start where the previous segment ends",
                    ));
                }
            }
            Outlines {
                kind: "segments",
                shapes: vec![crate::outline_io::Shape {
                    name: "outline".into(),
                    contours: vec![crate::outline_io::Contour { segments, closed }],
                }],
                unreadable: Vec::new(),
            }
        }
        _ => {
            return Err(ProtoError::invalid(
                "path",
                "give one of path (SVG path data), segments, svg (an SVG document) or file",
            ))
        }
    };
    let draw = draw_param(obj)?;
    let pick = match obj.get("shape") {
        None | Some(Value::Null) => None,
        Some(v) => match v.as_u64() {
            Some(i) if (i as usize) < outlines.shapes.len() => Some(i as usize),
            _ => {
                return Err(ProtoError::invalid(
                    "shape",
                    format!("must be a shape index below {}", outlines.shapes.len()),
                ))
            }
        },
    };
    let suggest = optional_number(obj, "suggest")?;
    if suggest.is_some_and(|t| t <= 0.0) {
        return Err(ProtoError::invalid("suggest", "must be > 0"));
    }
    let opts = aesthetic_curves::outline::OutlineOptions {
        suggest,
        ..options_for(&outlines)
    };
    // One shape (`shape`), or every shape.
    let shapes: Vec<_> = match pick {
        Some(i) => vec![&outlines.shapes[i]],
        None => outlines.shapes.iter().collect(),
    };
    // The answer's budget and the drawing's, before any work.
    let total: usize = shapes
        .iter()
        .flat_map(|s| s.contours.iter())
        .map(|c| c.segments.len())
        .sum();
    if total > MAX_OUTLINE_SEGMENTS {
        let field = if obj.contains_key("path") {
            "path"
        } else {
            "shape"
        };
        let what = match pick {
            Some(i) => format!("shape {i} holds {total} segments"),
            None => format!("the {} shapes hold {total} segments", shapes.len()),
        };
        return Err(ProtoError::invalid(
            field,
            format!(
                "{what}, over the {MAX_OUTLINE_SEGMENTS} one outline.check answers for: pick \
                 one shape with `shape` (an index into `shape_names`, which every answer \
                 holds), or check the whole file with `aecurve check --json`"
            ),
        ));
    }
    if let (Some(n), Some(first)) = (draw, shapes.first()) {
        let segments: usize = first.contours.iter().map(|c| c.segments.len()).sum();
        drawing_budget(segments, n)?;
    }
    let checked = check_shapes(&shapes, &opts, &|| {});
    // Past the deadline the rest was flagged, not checked: no answer from half a check.
    aesthetic_curves::deadline::check()?;
    let findings = checked
        .iter()
        .flat_map(|c| c.findings.iter().map(move |f| finding_json(c.name, f)));
    let mut out = object([
        (
            "shape_names",
            json!(outlines
                .shapes
                .iter()
                .map(|s| s.name.as_str())
                .collect::<Vec<_>>()),
        ),
        (
            "shape_segments",
            json!(outlines
                .shapes
                .iter()
                .map(|s| s.contours.iter().map(|c| c.segments.len()).sum::<usize>())
                .collect::<Vec<_>>()),
        ),
        (
            "shapes",
            Value::Array(checked.iter().map(shape_json).collect()),
        ),
        ("findings", Value::Array(findings.collect())),
    ]);
    if let (Some(n), Some(first)) = (draw, shapes.first()) {
        // The (first) shape's contours for a picture: their segments (what an editor drags)
        // and `n` points per segment with normals and curvature.
        let mut contours = Vec::new();
        for c in &first.contours {
            if c.segments.is_empty() {
                continue;
            }
            let pieces = aesthetic_curves::curve::Pieces(c.segments.clone());
            let segments = c.segments.iter().map(|b| {
                json!({
                    "control_points": b.points().iter().map(|p| [p.x, p.y]).collect::<Vec<_>>(),
                    "weights": b.weights(),
                })
            });
            contours.push(object([
                ("closed", Value::Bool(c.closed)),
                ("segments", Value::Array(segments.collect())),
                ("drawing", drawing_json(&pieces, n, None)?),
            ]));
        }
        out["drawing"] = object([
            ("name", Value::String(first.name.clone())),
            ("contours", Value::Array(contours)),
        ]);
    }
    Ok(out)
}

/// Most points an `outline.check` drawing holds (segments times `draw`).
pub const MAX_OUTLINE_DRAWING: usize = MAX_DRAWING_POINTS;

/// Largest file `outline.check` takes in `svg` or `file` (bytes).
pub const MAX_OUTLINE_FILE: usize = 3 << 20;

/// The outlines of an SVG document (`svg`: its text) or of a file (`file`: `{name, base64}`;
/// a font, an SVG or a DXF by the name's extension).
fn outline_file(obj: &Map<String, Value>) -> Result<crate::outline_io::Outlines, ProtoError> {
    use base64::Engine;
    let (name, bytes) = match (obj.get("svg"), obj.get("file")) {
        (Some(Value::String(t)), None) => ("drawing.svg".to_string(), t.as_bytes().to_vec()),
        (None, Some(Value::Object(f))) => {
            let name = f
                .get("name")
                .and_then(Value::as_str)
                .unwrap_or("")
                .to_lowercase();
            let Some(b64) = f.get("base64").and_then(Value::as_str) else {
                return Err(ProtoError::invalid(
                    "file",
                    "needs base64 (the file's bytes)",
                ));
            };
            if b64.len() > MAX_OUTLINE_FILE / 3 * 4 + 4 {
                return Err(ProtoError::invalid(
                    "file",
                    format!("larger than {MAX_OUTLINE_FILE} bytes"),
                ));
            }
            let bytes = base64::engine::general_purpose::STANDARD
                .decode(b64)
                .map_err(|e| ProtoError::invalid("file", format!("base64: {e}")))?;
            (name, bytes)
        }
        _ => {
            return Err(ProtoError::invalid(
                "svg",
                "give svg (text) or file, not both",
            ))
        }
    };
    if bytes.len() > MAX_OUTLINE_FILE {
        return Err(ProtoError::invalid(
            "file",
            format!("larger than {MAX_OUTLINE_FILE} bytes"),
        ));
    }
    let ext = name.rsplit_once('.').map_or("", |(_, e)| e);
    let read = match ext {
        "ttf" | "otf" | "ttc" | "otc" => crate::outline_io::read_font(&bytes),
        "dxf" => crate::outline_io::read_dxf(&bytes),
        "svg" => crate::outline_io::read_svg(&bytes),
        _ => {
            return Err(ProtoError::invalid(
                "file",
                format!(
                    "{name:?}: not a file outline.check reads (by its name's extension: .ttf, \
                     .otf, .ttc, .otc, .svg or .dxf)"
                ),
            ))
        }
    };
    read.map_err(|e| ProtoError::invalid("file", format!("{e:#}")))
}

/// Largest number of points `spline.pseudo_elastic` accepts in table mode (microseconds
/// per point, but about 3.5 KB of memory per point for the request and its answer: 20,000
/// points keep a request near 70 MB; the library itself has no limit).
pub const MAX_SPLINE_POINTS: usize = 20_000;

/// Largest number of points in exact mode: a minimisation per point, 1.2 to 2 s each on a
/// shared 2-core machine (measured: 16 closed points 22 s, 32 past the batch's 60 s
/// deadline), so that a request within the limit ends inside `batch`'s default deadline.
pub const MAX_EXACT_SPLINE_POINTS: usize = 16;

/// The spline mode named by a protocol string ("table" or "exact").
pub fn spline_mode(name: &str) -> aesthetic_curves::pseudo_spline::Mode {
    if name == "exact" {
        aesthetic_curves::pseudo_spline::Mode::Exact
    } else {
        aesthetic_curves::pseudo_spline::Mode::Table
    }
}

fn spline_pseudo_elastic(obj: &Map<String, Value>) -> Result<Value, ProtoError> {
    let closed = match obj.get("closed") {
        None | Some(Value::Null) => false,
        Some(Value::Bool(b)) => *b,
        Some(_) => return Err(ProtoError::invalid("closed", "must be true or false")),
    };
    let mode = string_param(obj, "mode", "table", &["table", "exact"])?;
    let max = if mode == "exact" {
        MAX_EXACT_SPLINE_POINTS
    } else {
        MAX_SPLINE_POINTS
    };
    let points = points_param(obj, "points", if closed { 3 } else { 2 }, max)?;
    let draw = draw_param(obj)?;
    if let Some(n) = draw {
        drawing_budget(points.len(), n)?;
    }
    let s = aesthetic_curves::pseudo_spline::pseudo_elastic(&points, closed, spline_mode(mode))?;
    let mut out = spline_json(&s, mode);
    if let Some(n) = draw {
        let curve = s.as_curve()?;
        let nurbs = curve.to_exact_nurbs()?;
        out["drawing"] = drawing_json(&curve, n, Some(&nurbs))?;
    }
    Ok(out)
}

/// Largest number of points `spline.lac` accepts: its Newton steps solve a dense system
/// in the smooth points (500 points: some 40 ms a step) and fit one or two cubics per span
/// (about half a millisecond each).
pub const MAX_LAC_SPLINE_POINTS: usize = 500;

/// The options of `spline.lac` (also `aecurve spline --kind lac`) from a request: `closed`,
/// `corners` (point indices), `alpha` (one number, default -1) or `alphas` (one per span).
pub fn lac_spline_options(
    obj: &Map<String, Value>,
) -> Result<aesthetic_curves::lac_spline::LacSplineOptions, ProtoError> {
    let closed = bool_param(obj, "closed", false)?;
    let corners = match obj.get("corners") {
        None | Some(Value::Null) => Vec::new(),
        Some(Value::Array(a)) => a
            .iter()
            .map(|v| {
                v.as_u64().map(|x| x as usize).ok_or_else(|| {
                    ProtoError::invalid("corners", "must be an array of point indices")
                })
            })
            .collect::<Result<_, _>>()?,
        Some(_) => {
            return Err(ProtoError::invalid(
                "corners",
                "must be an array of point indices",
            ))
        }
    };
    let alpha = optional_number(obj, "alpha")?.unwrap_or(-1.0);
    let span_alphas = match obj.get("alphas") {
        None | Some(Value::Null) => None,
        Some(Value::Array(a)) => Some(
            a.iter()
                .enumerate()
                .map(|(i, v)| finite_number(v, &format!("alphas[{i}]")))
                .collect::<Result<Vec<_>, _>>()?,
        ),
        Some(_) => return Err(ProtoError::invalid("alphas", "must be an array of numbers")),
    };
    Ok(aesthetic_curves::lac_spline::LacSplineOptions {
        alpha,
        span_alphas,
        closed,
        corners,
        ..Default::default()
    })
}

fn spline_lac(obj: &Map<String, Value>) -> Result<Value, ProtoError> {
    let opts = lac_spline_options(obj)?;
    let least = if opts.closed { 3 } else { 2 };
    let points = points_param(obj, "points", least, MAX_LAC_SPLINE_POINTS)?;
    let draw = draw_param(obj)?;
    let s = aesthetic_curves::lac_spline::lac_spline(&points, &opts)?;
    let mut out = lac_spline_json(&s);
    if let Some(n) = draw {
        out["drawing"] = pieces_drawing(&s.rationals(), n)?;
    }
    Ok(out)
}

/// The result of `spline.lac` (also `aecurve spline --kind lac --json`): the pieces as
/// `sketch.fit` gives its segments (kind, alpha, control, end curvatures, rational cubic,
/// monotone verdict), with the span each belongs to.
pub fn lac_spline_json(s: &aesthetic_curves::lac_spline::LacSpline) -> Value {
    let segments: Vec<Value> = s
        .pieces
        .iter()
        .map(|p| {
            let mut o = piece_json(
                p.kind.as_str(),
                &p.control,
                p.end_curvatures,
                &p.rational,
                p.monotone,
            );
            o["span"] = json!(p.span);
            o["rational_error"] = json!(p.rational_error);
            if let Some(a) = p.alpha {
                o["alpha"] = json!(a);
            }
            o
        })
        .collect();
    json!({
        "segments": segments,
        "tangents": s.tangents.iter().map(|t| [t.x, t.y]).collect::<Vec<_>>(),
        "closed": s.closed,
        "iterations": s.iterations,
        "converged": s.converged,
        "g2": s.converged && s.max_cubic_jump <= 1e-8,
        "max_curvature_jump": s.max_curvature_jump,
        "max_cubic_jump": s.max_cubic_jump,
        "max_cubic_angle": s.max_cubic_angle,
        "all_monotone": s.all_monotone,
        "max_rational_error": s.max_rational_error,
        "inflections": s.inflections,
        "curvature_extrema": s.curvature_extrema,
    })
}

/// The result object of `spline.pseudo_elastic`.
pub fn spline_json(s: &aesthetic_curves::pseudo_spline::PseudoSpline, mode: &str) -> Value {
    json!({
        "tangent_angles": s.tangent_angles,
        "segments": s.segments.iter().map(|g| json!({
            "p0": [g.p0.x, g.p0.y], "p1": [g.p1.x, g.p1.y],
            "d0": [g.d0.x, g.d0.y], "d1": [g.d1.x, g.d1.y],
        })).collect::<Vec<_>>(),
        "length": s.length,
        "area": s.area,
        "energy": s.energy,
        "mode": mode,
    })
}

/// Largest point sampling `lcg.estimate` accepts.
pub const MAX_LCG_POINTS: usize = 100_000;

fn lcg_estimate(obj: &Map<String, Value>) -> Result<Value, ProtoError> {
    let points = points_param(
        obj,
        "points",
        aesthetic_curves::lcg::MIN_POINTS,
        MAX_LCG_POINTS,
    )?;
    Ok(lcg_json(&aesthetic_curves::lcg::estimate_from_points(
        &points,
    )?))
}

/// The result of `lcg.estimate` (also `aecurve lcg --json`): the fitted line and the graph.
pub fn lcg_json(fit: &aesthetic_curves::lcg::LcgFit) -> Value {
    json!({
        "alpha": fit.alpha,
        "r_squared": fit.r_squared,
        "intercept": fit.intercept,
        "rms_residual": fit.rms_residual,
        "graph": fit.graph.iter().map(|p| [p.log_rho, p.log_rho_ds_drho]).collect::<Vec<_>>(),
    })
}

fn first_non_finite(v: &Value, path: String) -> Option<String> {
    match v {
        Value::Number(n) => match n.as_f64() {
            Some(x) if !x.is_finite() => Some(path),
            _ => None,
        },
        Value::Array(a) => a
            .iter()
            .enumerate()
            .find_map(|(i, x)| first_non_finite(x, format!("{path}[{i}]"))),
        Value::Object(o) => o
            .iter()
            .find_map(|(k, x)| first_non_finite(x, format!("{path}.{k}"))),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kind(v: &Value) -> &str {
        v["error"]["kind"].as_str().unwrap_or("")
    }

    #[test]
    fn draw_gives_points_normals_curvature_and_the_nurbs() {
        let f = |v: &Value| v.as_f64().unwrap();
        // A quarter circle of radius 2 as a rational quadratic: every drawn point on the
        // circle, normals towards its centre, curvature 1/2, and the NURBS to export.
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let req = format!(
            r#"{{"op": "bezier.curvature_monotone", "control_points": [[2, 0], [2, 2], [0, 2]], "weights": [1, {s}, 1], "draw": 9}}"#
        );
        let v = handle_line(&req);
        let d = &v["result"]["drawing"];
        assert_eq!(d["points"].as_array().unwrap().len(), 9);
        assert_eq!(d["pieces"], 1);
        for i in 0..9 {
            let (x, y) = (f(&d["points"][i][0]), f(&d["points"][i][1]));
            let (nx, ny) = (f(&d["normals"][i][0]), f(&d["normals"][i][1]));
            assert!((x.hypot(y) - 2.0).abs() < 1e-12);
            assert!((nx + x / 2.0).abs() < 1e-9 && (ny + y / 2.0).abs() < 1e-9);
            assert!((f(&d["curvature"][i]) - 0.5).abs() < 1e-9);
        }
        assert_eq!(d["nurbs"]["degree"], 2);
        // Pieces share their joints; a LAC segment has no NURBS; the count is checked.
        let v = handle_line(
            r#"{"op": "spline.pseudo_elastic", "points": [[0, 0], [2, 1], [4, 0], [6, 1]], "draw": 5}"#,
        );
        let d = &v["result"]["drawing"];
        assert_eq!(d["pieces"], 3);
        assert_eq!(d["points"].as_array().unwrap().len(), 3 * 4 + 1);
        assert_eq!(d["nurbs"]["control_points"].as_array().unwrap().len(), 10);
        let v = handle_line(
            r#"{"op": "lac.segment", "alpha": -1, "control": [[0, 0], [8, 0], [12, 5]], "draw": 3}"#,
        );
        assert!(v["result"]["drawing"]["nurbs"].is_null());
        for bad in ["1", "0", "2001", "-3", "2.5", "\"9\""] {
            let v = handle_line(&format!(
                r#"{{"op": "lac.segment", "alpha": -1, "control": [[0, 0], [8, 0], [12, 5]], "draw": {bad}}}"#
            ));
            assert_eq!(kind(&v), "invalid_input", "{bad}");
        }
    }

    #[test]
    fn outline_check_takes_documents_and_files_and_draws_one_shape() {
        use base64::Engine;
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg"><path id="a" d="M 0 0 L 10 0"/><g transform="translate(5 0)"><path id="b" d="M 0 0 C 3 4 7 4 10 0 Z"/></g></svg>"#;
        let req = json!({"op": "outline.check", "svg": svg, "shape": 1, "draw": 11});
        let v = handle_line(&req.to_string());
        let r = &v["result"];
        assert_eq!(r["shape_names"].as_array().unwrap().len(), 2, "{v}");
        assert_eq!(r["shapes"].as_array().unwrap().len(), 1, "{v}");
        let c = &r["drawing"]["contours"][0];
        assert_eq!(r["drawing"]["name"], "b");
        // The cubic and the closing line, in the document's coordinates (translated).
        assert_eq!(c["segments"][0]["control_points"][1], json!([8.0, 4.0]));
        assert_eq!(c["drawing"]["per_piece"], 11);
        assert_eq!(c["drawing"]["points"].as_array().unwrap().len(), 2 * 10 + 1);
        // The same document as a file; a bad index, bad base64 and a foreign file: errors.
        let b64 = base64::engine::general_purpose::STANDARD.encode(svg);
        let req = json!({"op": "outline.check", "file": {"name": "x.svg", "base64": b64}});
        let v = handle_line(&req.to_string());
        assert_eq!(v["result"]["shapes"].as_array().unwrap().len(), 2, "{v}");
        for bad in [
            json!({"op": "outline.check", "svg": svg, "shape": 2}),
            json!({"op": "outline.check", "file": {"name": "x.svg", "base64": "@@"}}),
            json!({"op": "outline.check", "file": {"name": "x.ttf", "base64": b64}}),
            json!({"op": "outline.check", "svg": "<svg"}),
        ] {
            let v = handle_line(&bad.to_string());
            assert_eq!(v["ok"], false, "{bad}: {v}");
            assert_eq!(v["error"]["kind"], "invalid_input", "{bad}: {v}");
        }
    }

    #[test]
    fn outline_check_takes_path_data_or_segments() {
        let v = handle_line(
            r#"{"op": "outline.check", "path": "M 0 0 L 10 0 L 19.9939 0.3490 C 25 5 30 -5 35 0"}"#,
        );
        let r = &v["result"];
        // The S with two curvature extrema (its detour 86 % of its curvature) ranks above the
        // 2° near-break (half of 2/3 of the threshold).
        assert_eq!(r["findings"][0]["kind"], "not-monotone", "{v}");
        assert_eq!(r["findings"][1]["kind"], "near-break", "{v}");
        let segs = &r["shapes"][0]["contours"][0]["segments"];
        assert_eq!(segs.as_array().unwrap().len(), 3);
        assert_eq!(segs[2]["inflections"].as_array().unwrap().len(), 1);
        let v = handle_line(
            r#"{"op": "outline.check", "segments": [{"control_points": [[2, 0], [2, 2], [0, 2]], "weights": [1, 0.7071067811865476, 1]}]}"#,
        );
        let s = &v["result"]["shapes"][0]["contours"][0]["segments"][0];
        assert!(
            (s["max_abs_curvature"].as_f64().unwrap() - 0.5).abs() < 1e-12,
            "{v}"
        );
        // The f64 weight is not 1/√2: exactly, an ellipse arc with its curvature extremum at
        // the middle (a relative change of 1e-16), and the check says so.
        assert_eq!(s["monotone"], false, "{v}");
        assert!(
            (s["extrema"][0]["t"].as_f64().unwrap() - 0.5).abs() < 1e-12,
            "{v}"
        );
        for bad in [
            r#"{"op": "outline.check"}"#,
            r#"{"op": "outline.check", "path": "M 0 0 Q"}"#,
            r#"{"op": "outline.check", "segments": []}"#,
            r#"{"op": "outline.check", "segments": [{"control_points": [[0, 0]]}]}"#,
            r#"{"op": "outline.check", "segments": [{"control_points": [[0, 0], [1, 0]]}, {"control_points": [[5, 5], [6, 0]]}]}"#,
            r#"{"op": "outline.check", "segments": [{"control_points": [[0, 0], [1, 0], [2, 1]], "weights": [1, -1, 1]}]}"#,
        ] {
            assert_eq!(kind(&handle_line(bad)), "invalid_input", "{bad}");
        }
    }

    #[test]
    fn ok_response_shape() {
        let r = handle_line(
            r#"{"id": 7, "op": "bezier.curvature_monotone", "control_points": [[0,0],[1,1],[2,1],[3,0]]}"#,
        );
        assert_eq!(r["id"], 7);
        assert_eq!(r["ok"], true);
        assert_eq!(r["result"]["monotone"], false);
        assert_eq!(r["result"]["test_degree"], 5);
        let e = r["result"]["extrema"].as_array().unwrap();
        assert_eq!(e.len(), 1);
        assert!((e[0].as_f64().unwrap() - 0.5).abs() < 1e-9);
    }

    #[test]
    fn error_kinds() {
        assert_eq!(kind(&handle_line("{not json")), "parse");
        assert_eq!(kind(&handle_line("[1,2]")), "invalid_input");
        assert_eq!(kind(&handle_line(r#"{"op": "nope"}"#)), "unknown_op");
        assert_eq!(
            kind(&handle_line(r#"{"op": "sketch.fit"}"#)),
            "invalid_input"
        );
        assert_eq!(kind(&handle_line(r#"{"op": "lac.fit"}"#)), "invalid_input");
        assert_eq!(
            kind(&handle_line(r#"{"op": "lac.segment"}"#)),
            "invalid_input"
        );
        let r =
            handle_line(r#"{"op": "lac.segment", "alpha": -1, "control": [[0,0],[1,0],[1,0.3]]}"#);
        assert_eq!(kind(&r), "no_segment");
        assert!(
            r["error"]["message"]
                .as_str()
                .unwrap()
                .contains("must lie in"),
            "{r}"
        );
        let r =
            handle_line(r#"{"op": "lac.segment", "alpha": -1, "control": [[0,0],[1,0],[2,0]]}"#);
        assert_eq!(kind(&r), "degenerate");
        assert_eq!(
            kind(&handle_line(r#"{"op": "lac.point"}"#)),
            "invalid_input"
        );
        let r =
            handle_line(r#"{"op": "lac.point", "alpha": -1, "lambda": 0.5, "theta": [0.5, 3.0]}"#);
        assert_eq!(kind(&r), "invalid_input");
        assert!(
            r["error"]["message"].as_str().unwrap().contains("domain"),
            "{r}"
        );
        assert_eq!(
            kind(&handle_line(r#"{"op": "bezier.curvature_monotone"}"#)),
            "invalid_input"
        );
        let r = handle_line(
            r#"{"id": "a", "op": "bezier.curvature_monotone", "control_points": [[0,0],[1,1e999]]}"#,
        );
        assert_eq!(kind(&r), "invalid_input");
        let r = handle_line(
            r#"{"id": "b", "op": "bezier.curvature_monotone", "control_points": [[0,0],[2,1],[0,1],[2,0]]}"#,
        );
        assert_eq!(kind(&r), "degenerate");
        assert_eq!(r["id"], "b");
        let r = handle_line(
            r#"{"op": "bezier.curvature_monotone", "control_points": [[0,0],[1,1],[2,0]], "weights": [1, -1, 1]}"#,
        );
        assert_eq!(kind(&r), "invalid_input");
        assert!(r["error"]["message"]
            .as_str()
            .unwrap()
            .contains("weights[1]"));
        let r = handle_line(
            r#"{"op": "bezier.curvature_monotone", "control_points": [[0,0],[1,1],[2,0]], "weights": [1, 1]}"#,
        );
        assert_eq!(kind(&r), "invalid_input");
        let r = handle_line(
            r#"{"op": "bezier.curvature_monotone", "control_points": [[0,0],[1,1],[2,0]], "method": "sampling", "samples": 0}"#,
        );
        assert_eq!(kind(&r), "invalid_input");
    }

    #[test]
    fn lac_point_values() {
        let r = handle_line(
            r#"{"id": 1, "op": "lac.point", "alpha": 2, "lambda": 0.5, "theta": [0, 1.5707963267948966]}"#,
        );
        assert_eq!(r["ok"], true, "{r}");
        let p = &r["result"]["points"][1];
        assert!((p[0].as_f64().unwrap() - (std::f64::consts::FRAC_PI_4 + 0.5)).abs() < 1e-13);
        assert!((p[1].as_f64().unwrap() - 1.5).abs() < 1e-13);
        assert_eq!(r["result"]["curvature"][0].as_f64().unwrap(), 1.0);
        assert_eq!(r["result"]["arc_length"][0].as_f64().unwrap(), 0.0);
    }

    #[test]
    fn lac_segment_values() {
        let r = handle_line(
            r#"{"id": "s", "op": "lac.segment", "alpha": -1, "control": [[0,0],[10,0],[16,9]], "samples": 5}"#,
        );
        assert_eq!(r["ok"], true, "{r}");
        let res = &r["result"];
        assert_eq!(res["points"].as_array().unwrap().len(), 5);
        assert_eq!(res["points"][0][0], 0.0);
        assert_eq!(res["points"][4][1], 9.0);
        assert!(res["lambda"].as_f64().unwrap() > 0.0);
        assert!(res["curvature_start"].as_f64().unwrap() > 0.0);
        assert!(res["arc_length"].as_f64().unwrap() > (16f64.hypot(9.0)));
    }

    #[test]
    fn lac_inflection_segment_values() {
        let r = handle_line(
            r#"{"op": "lac.inflection_segment", "control": [[0,0],[1,0],[1,0.5773502691896257]], "samples": 9}"#,
        );
        assert_eq!(r["ok"], true, "{r}");
        assert!((r["result"]["alpha"].as_f64().unwrap() + 1.066636984).abs() < 1e-8);
        assert_eq!(r["result"]["curvature"][0].as_f64().unwrap(), 0.0);
        let r = handle_line(r#"{"op": "lac.inflection_segment", "control": [[0,0],[1,0],[1,2]]}"#);
        assert_eq!(kind(&r), "no_segment");
        // The optional rational cubic and spline within a tolerance.
        let r = handle_line(
            r#"{"op": "lac.inflection_segment", "control": [[0,0],[1,0],[1,0.5773502691896257]], "samples": 9, "rational": true, "tolerance": 1e-7}"#,
        );
        assert_eq!(r["ok"], true, "{r}");
        let ra = &r["result"]["rational"];
        assert_eq!(ra["monotone"], true);
        assert!(ra["max_error"].as_f64().unwrap() < 1e-3);
        let sp = &r["result"]["spline"];
        let pieces = sp["pieces"].as_u64().unwrap() as usize;
        assert!(
            pieces >= 2 && sp["max_error"].as_f64().unwrap() <= 1e-7,
            "{sp}"
        );
        assert_eq!(
            sp["control_points"].as_array().unwrap().len(),
            3 * pieces + 1
        );
        assert_eq!(sp["knots"].as_array().unwrap().len(), 3 * pieces + 5);
        assert_eq!(sp["monotone"], true);
        for bad in ["0", "-1", "\"x\""] {
            let r = handle_line(&format!(
                r#"{{"op": "lac.inflection_segment", "control": [[0,0],[1,0],[1,0.5]], "tolerance": {bad}}}"#
            ));
            assert_eq!(kind(&r), "invalid_input", "{bad}: {r}");
        }
    }

    #[test]
    fn sampling_method() {
        let r = handle_line(
            r#"{"op": "bezier.curvature_monotone", "control_points": [[0,0],[1,1],[2,1],[3,0]], "method": "sampling", "samples": 200}"#,
        );
        assert_eq!(r["ok"], true, "{r}");
        assert_eq!(r["result"]["monotone"], false);
        assert_eq!(r["result"]["samples"], 200);
    }

    /// outline.fix: the jump at the smooth join of two cubics goes (under the tolerance,
    /// tangents kept, the corners left alone), and bad input is named.
    #[test]
    fn outline_fix_harmonizes_a_smooth_join_and_names_bad_input() {
        let ok = handle_line(
            r#"{"op": "outline.fix", "closed": true, "tolerance": 1, "segments": [{"control_points": [[0, 0], [0, 3], [2, 5], [5, 5]]}, {"control_points": [[5, 5], [9, 5], [10, 3], [10, 0]]}, {"control_points": [[10, 0], [0, 0]]}]}"#,
        );
        let r = &ok["result"];
        assert_eq!(r["changed_segments"], 2, "{ok}");
        let j = &r["joins"][0];
        assert_eq!(j["smooth"], true);
        assert!(
            j["jump"][1].as_f64().unwrap() < 1e-9 && j["jump"][0].as_f64().unwrap() > 0.4,
            "{j}"
        );
        assert!(r["max_moved"].as_f64().unwrap() <= 1.0);
        // The join's tangent stays horizontal: the moved handles keep y = 5.
        assert_eq!(r["segments"][0]["control_points"][2][1], 5.0);
        assert_eq!(r["segments"][1]["control_points"][1][1], 5.0);
        assert_eq!(r["joins"][1]["outcome"], "corner");
        for (bad, field) in [
            (r#"{"op": "outline.fix", "tolerance": 1}"#, "segments"),
            (
                r#"{"op": "outline.fix", "segments": [{"control_points": [[0, 0], [1, 0]]}]}"#,
                "tolerance",
            ),
            (
                r#"{"op": "outline.fix", "tolerance": 0, "segments": [{"control_points": [[0, 0], [1, 0]]}]}"#,
                "tolerance",
            ),
            (
                r#"{"op": "outline.fix", "tolerance": 1, "segments": [{"control_points": [[0, 0], [1, 1], [2, 0]]}]}"#,
                "segments[0].control_points",
            ),
            (
                r#"{"op": "outline.fix", "tolerance": 1, "segments": [{"control_points": [[0, 0], [1, 1], [2, 1], [3, 0]], "weights": [1, 2, 1, 1]}]}"#,
                "segments[0].weights",
            ),
            (
                r#"{"op": "outline.fix", "tolerance": 1, "segments": [{"control_points": [[0, 0], [1, 0]]}, {"control_points": [[5, 5], [6, 0]]}]}"#,
                "segments[1]",
            ),
            (
                r#"{"op": "outline.fix", "tolerance": 1, "grid": -1, "segments": [{"control_points": [[0, 0], [1, 0]]}]}"#,
                "grid",
            ),
            (
                r#"{"op": "outline.fix", "tolerance": 1, "closed": 3, "segments": [{"control_points": [[0, 0], [1, 0]]}]}"#,
                "closed",
            ),
        ] {
            let v = handle_line(bad);
            assert_eq!(kind(&v), "invalid_input", "{bad}");
            assert!(
                v["error"]["message"].as_str().unwrap().contains(field),
                "{bad}: {v}"
            );
        }
    }
}
