//! The JSON protocol of `aecurve batch` and the editor (`docs/protocol.md` in the repository).
//!
//! Every op is a type pair and a function ([`Op`]): a request type that reads and checks its
//! fields (serde, with the rules in the field types of [`fields`] and the rules between
//! fields in [`Request::check`]), a response type, and `answer`. The table in `ops!` names
//! every op once: the dispatch, the list of ops and the JSON Schema ([`schema`], printed by
//! `aecurve schema`) come from it.
//!
//! [`handle_line`] turns one request line into one response object and never panics: a line
//! that is not JSON gets a `parse` error, an unknown op `unknown_op`, a bad parameter
//! `invalid_input` naming the field (its path, as `segments[2].control_points`), and library
//! errors keep their own kind. Nothing in a result is NaN or infinite (checked once more
//! before a response leaves).

pub mod bezier;
pub mod drawing;
pub mod fields;
pub mod fix_file;
pub mod lac;
pub mod lcg;
pub mod outline;
pub mod piece;
pub mod region;
pub mod sketch;
pub mod spline;

pub use self::bezier::{monotone_json, sampled_json, MAX_SAMPLES};
pub use self::drawing::{drawing_json, Drawing, NurbsJson, MAX_DRAWING_POINTS, MAX_DRAW_SAMPLES};
pub use self::lac::{
    lac_inflection_json, lac_segment_json, rational_approx_json, MAX_FIT_POINTS,
    MAX_SEGMENT_SAMPLES, MAX_THETAS,
};
pub use self::lcg::{lcg_json, MAX_LCG_POINTS};
pub use self::outline::{
    MAX_OUTLINE_DRAWING, MAX_OUTLINE_FILE, MAX_OUTLINE_SEGMENTS, MAX_PATH_DATA,
};
pub use self::sketch::{contour_json, sketch_json, MAX_SKETCH_POINTS};
pub use self::spline::{
    lac_spline_json, spline_json, SplineMode, MAX_EXACT_SPLINE_POINTS, MAX_LAC_SPLINE_POINTS,
    MAX_SPLINE_POINTS,
};
pub use crate::json_out::{finite_or_null, object};
use aesthetic_curves::Error;
use schemars::generate::SchemaSettings;
use schemars::JsonSchema;
use serde::de::DeserializeOwned;
use serde::Serialize;
use serde_json::{json, Map, Value};

/// A protocol error: kind and message for a person.
#[derive(Debug, Clone, PartialEq)]
pub struct ProtoError {
    /// One of [`ERROR_KINDS`].
    pub kind: &'static str,
    /// What went wrong.
    pub message: String,
}

/// Every error kind a response can carry (docs/protocol.md, "Error kinds"): the six of the
/// requests themselves, `timeout` (the request's time ran out: the batch's and the
/// editor's deadline), `forbidden` (the editor's answer to a request from elsewhere) and
/// `internal` (the request made the program fail: a bug, reported instead of ending the
/// batch or the editor).
pub const ERROR_KINDS: [&str; 9] = [
    "parse",
    "unknown_op",
    "invalid_input",
    "degenerate",
    "no_segment",
    "no_convergence",
    "timeout",
    "forbidden",
    "internal",
];

impl ProtoError {
    /// An `invalid_input` error naming the field.
    pub fn invalid(field: &str, message: impl std::fmt::Display) -> Self {
        ProtoError {
            kind: "invalid_input",
            message: format!("{field}: {message}"),
        }
    }

    /// An `invalid_input` error from reading a request: the field's path and what serde says
    /// ("missing field `x`" becomes "x: missing" at its place).
    fn from_serde(e: serde_path_to_error::Error<serde_json::Error>) -> Self {
        let path = e.path().to_string();
        // serde names Rust types; a client reads JSON ones.
        let inner = e
            .into_inner()
            .to_string()
            .replace("expected f64", "expected a number")
            .replace("expected usize", "expected a whole number >= 0")
            .replace("expected u64", "expected a whole number >= 0");
        let at = |field: &str| match path.as_str() {
            "." => field.to_string(),
            p if field.is_empty() => p.to_string(),
            p => format!("{p}.{field}"),
        };
        let quoted = |s: &str| s.split('`').nth(1).unwrap_or("").to_string();
        if let Some(rest) = inner.strip_prefix("missing field ") {
            return ProtoError::invalid(&at(&quoted(rest)), "missing");
        }
        if let Some(rest) = inner.strip_prefix("unknown field ") {
            // The path ends with the unknown field's own name (an internally tagged
            // request, read from a buffer, has none: the name is in the message).
            let expected = rest.split_once(", expected ").map_or("", |(_, e)| e);
            let field = if path == "." {
                quoted(rest)
            } else {
                path.clone()
            };
            return ProtoError::invalid(
                &field,
                format!(
                    "not a field of this request (a typo?); expected {}",
                    expected.replace('`', "")
                ),
            );
        }
        ProtoError::invalid(&at(""), inner)
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

/// A request: read by serde (each field checks its own rule), then the rules between its
/// fields. A request that exists has passed both.
pub trait Request: DeserializeOwned + JsonSchema {
    /// The rules between fields (a count that depends on another field, a field that only
    /// applies with another): `invalid_input` naming the field.
    fn check(&self) -> Result<(), ProtoError> {
        Ok(())
    }
}

/// One op of the protocol: its name, request, response and answer.
pub trait Op {
    /// The `op` string of its requests.
    const NAME: &'static str;
    /// What one line asks (without `op` and `id`).
    type Request: Request;
    /// The `result` of an answer.
    type Response: Serialize + JsonSchema;
    /// The answer to a checked request.
    fn answer(req: Self::Request) -> Result<Self::Response, ProtoError>;
}

/// Read and check a request of type `T` (the ops' and the editor's own endpoints').
pub fn read<T: Request>(v: Value) -> Result<T, ProtoError> {
    let req: T = serde_path_to_error::deserialize(v).map_err(ProtoError::from_serde)?;
    req.check()?;
    Ok(req)
}

/// Read, check and answer one request's fields as op `O`.
fn run<O: Op>(fields: Map<String, Value>) -> Result<Value, ProtoError> {
    let result = O::answer(read(Value::Object(fields))?)?;
    serde_json::to_value(result).map_err(|e| ProtoError {
        kind: "no_convergence",
        message: format!("internal: the result cannot be written: {e}"),
    })
}

/// `op` (required, this op) and `id` (optional, anything) in a request object's schema.
fn add_op_and_id(def: &mut Value, op: &str) {
    def["properties"]["op"] = json!({"const": op});
    def["properties"]["id"] = json!({"description": "Echoed in the response."});
    match def["required"].as_array_mut() {
        Some(r) => r.insert(0, json!("op")),
        None => def["required"] = json!(["op"]),
    }
}

/// The request and response schemas of op `O`, their types' definitions in `defs`.
fn op_schemas<O: Op>(
    requests: &mut schemars::SchemaGenerator,
    responses: &mut schemars::SchemaGenerator,
) -> (Value, Value) {
    let mut req = requests.subschema_for::<O::Request>().to_value();
    // The request's own fields, with `op` (this op) and `id` (anything, echoed).
    let name = <O::Request as JsonSchema>::schema_name();
    if let Some(def) = requests.definitions_mut().get_mut(name.as_ref()) {
        // A request of several kinds (`oneOf`) takes `op` and `id` in each.
        match def.get_mut("oneOf").and_then(Value::as_array_mut) {
            Some(kinds) => kinds.iter_mut().for_each(|k| add_op_and_id(k, O::NAME)),
            None => add_op_and_id(def, O::NAME),
        }
        req = json!({"$ref": format!("#/$defs/{name}")});
    }
    let resp = responses.subschema_for::<O::Response>().to_value();
    (req, resp)
}

/// `Display` as compact JSON, for the response types the CLI's `--json` prints.
macro_rules! json_display {
    ($($t:ty),* $(,)?) => {$(
        impl std::fmt::Display for $t {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(&serde_json::to_string(self).map_err(|_| std::fmt::Error)?)
            }
        }
    )*};
}

json_display!(
    bezier::MonotoneResult,
    bezier::SampledResult,
    lac::RationalApproxResult,
    lcg::LcgResult,
    sketch::SketchResult,
    sketch::ContourResult,
    spline::PseudoSplineResult,
    spline::LacSplineResult,
);

/// The table of ops: the list, the dispatch and the schema come from it.
macro_rules! ops {
    ($($op:ty),* $(,)?) => {
        /// The ops this build answers (every op of docs/protocol.md).
        pub const OPS: &[&str] = &[$(<$op as Op>::NAME),*];

        fn answer_op(name: &str, fields: Map<String, Value>) -> Option<Result<Value, ProtoError>> {
            $(if name == <$op as Op>::NAME {
                return Some(run::<$op>(fields));
            })*
            None
        }

        fn all_op_schemas(
            requests: &mut schemars::SchemaGenerator,
            responses: &mut schemars::SchemaGenerator,
        ) -> Vec<(&'static str, Value, Value)> {
            vec![$({
                let (q, r) = op_schemas::<$op>(requests, responses);
                (<$op as Op>::NAME, q, r)
            }),*]
        }
    };
}

ops! {
    bezier::CurvatureMonotone,
    lac::LacPoint,
    lac::LacSegmentOp,
    lac::LacInflectionSegmentOp,
    lcg::LcgEstimate,
    lac::LacRationalApprox,
    spline::PseudoElastic,
    spline::SplineLac,
    lac::LacFitOp,
    sketch::SketchFit,
    sketch::SketchContourOp,
    outline::OutlineCheck,
    outline::OutlineFix,
    region::RegionMap,
}

/// The JSON Schema (draft 2020-12) of the protocol: the document validates one request line;
/// `$defs` holds every request and response type, `x-ops` names each op's pair, and
/// `$defs/Response` is any response line (an answer or an error).
pub fn schema() -> Value {
    let mut requests = SchemaSettings::draft2020_12()
        .for_deserialize()
        .into_generator();
    let mut responses = SchemaSettings::draft2020_12()
        .for_serialize()
        .into_generator();
    let ops = all_op_schemas(&mut requests, &mut responses);
    // What the CLI prints beyond the ops' answers (`aecurve check --json`, `fix --json`,
    // `bench --json`).
    let x_cli = json!({
        "bench": {
            "monotone": responses.subschema_for::<crate::bench::BenchMonotoneResult>().to_value(),
            "targets": responses.subschema_for::<crate::bench_targets::BenchTargetsResult>().to_value(),
        },
        "check": responses.subschema_for::<crate::check_json::CheckFileJson>().to_value(),
        "fix": {
            "file": responses.subschema_for::<fix_file::FixFileResult>().to_value(),
            "designspace": responses.subschema_for::<fix_file::FixDesignspaceResult>().to_value(),
        }
    });
    let mut defs = requests.take_definitions(true);
    for (k, v) in responses.take_definitions(true) {
        match defs.get(&k) {
            Some(d) if *d != v => panic!("schema: {k} differs between requests and responses"),
            _ => {
                defs.insert(k, v);
            }
        }
    }
    let answers: Vec<Value> = ops
        .iter()
        .map(|(_, _, r)| {
            json!({"type": "object", "required": ["id", "ok", "result"],
            "properties": {"id": {}, "ok": {"const": true}, "result": r}})
        })
        .collect();
    defs.insert(
        "Error".into(),
        json!({"type": "object", "required": ["id", "ok", "error"], "additionalProperties": false,
            "properties": {"id": {}, "ok": {"const": false},
                "error": {"type": "object", "required": ["kind", "message"], "additionalProperties": false,
                    "properties": {"kind": {"enum": ERROR_KINDS}, "message": {"type": "string", "minLength": 1}}}}}),
    );
    defs.insert(
        "Response".into(),
        json!({"oneOf": [{"$ref": "#/$defs/Error"}, {"anyOf": answers}]}),
    );
    let x_ops: Map<String, Value> = ops
        .iter()
        .map(|(n, q, r)| (n.to_string(), json!({"request": q, "response": r})))
        .collect();
    json!({
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": "aecurve protocol: one request line",
        "description": "Requests of `aecurve batch` and the editor's /api; see docs/protocol.md.",
        "oneOf": ops.iter().map(|(_, q, _)| q.clone()).collect::<Vec<_>>(),
        "x-ops": x_ops,
        "x-cli": x_cli,
        "$defs": defs,
    })
}

/// The schema of any response line (the document's `$defs` with `$defs/Response` at the
/// root): what the tests check every answer against.
pub fn response_line_schema() -> Value {
    let mut s = schema();
    s["oneOf"] = json!([{"$ref": "#/$defs/Response"}]);
    s
}

/// The JSON Schema of one response type `T` (a document of its own: what the CLI's `--json`
/// prints is checked against it).
pub fn response_schema<T: JsonSchema>() -> Value {
    SchemaSettings::draft2020_12()
        .for_serialize()
        .into_generator()
        .into_root_schema_for::<T>()
        .to_value()
}

/// Answer one request line (JSON text) with one response object.
pub fn handle_line(line: &str) -> Value {
    match serde_json::from_str::<Value>(line) {
        Ok(v) => answer(v),
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
    answer(v.clone())
}

/// Answer one parsed request, taken.
pub fn answer(v: Value) -> Value {
    let Value::Object(mut obj) = v else {
        return error_response(
            Value::Null,
            ProtoError::invalid("request", "must be a JSON object"),
        );
    };
    let id = obj.remove("id").unwrap_or(Value::Null);
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

fn dispatch(mut obj: Map<String, Value>) -> Result<Value, ProtoError> {
    let op = match obj.remove("op") {
        Some(Value::String(s)) => s,
        Some(_) => return Err(ProtoError::invalid("op", "must be a string")),
        None => return Err(ProtoError::invalid("op", "missing")),
    };
    answer_op(&op, obj).unwrap_or_else(|| {
        Err(ProtoError {
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
        })
    })
}

/// `[x, y]` of each point (how every response writes points).
pub fn xy(points: &[aesthetic_curves::Point]) -> Vec<[f64; 2]> {
    points.iter().map(|p| [p.x, p.y]).collect()
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
mod tests;
