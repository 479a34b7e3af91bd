use super::*;
use std::sync::OnceLock;

/// Validators of the generated schema: any request line, any response line.
fn validators() -> &'static (jsonschema::Validator, jsonschema::Validator) {
    static V: OnceLock<(jsonschema::Validator, jsonschema::Validator)> = OnceLock::new();
    V.get_or_init(|| {
        (
            jsonschema::validator_for(&schema()).expect("the schema compiles"),
            jsonschema::validator_for(&response_line_schema())
                .expect("the response schema compiles"),
        )
    })
}

/// Every error of `v` against `validator`, one per line.
fn schema_errors(validator: &jsonschema::Validator, v: &Value) -> String {
    validator
        .iter_errors(v)
        .map(|e| format!("{} at {}", e, e.instance_path()))
        .collect::<Vec<_>>()
        .join("\n")
}

/// `handle_line` with the schema's word on both sides: every response is a valid
/// response line, and a request that was answered is a valid request line.
fn handle_line(line: &str) -> Value {
    let v = super::handle_line(line);
    let (requests, responses) = validators();
    let bad = schema_errors(responses, &v);
    assert!(bad.is_empty(), "response of {line}:\n{bad}\n{v}");
    if v["ok"] == true {
        let req: Value = serde_json::from_str(line).unwrap();
        let bad = schema_errors(requests, &req);
        assert!(
            bad.is_empty(),
            "answered, yet not a valid request: {line}:\n{bad}"
        );
    }
    v
}

/// The examples of docs/protocol.md: each request is answered as documented (ok or the
/// error kind), and both lines are valid by the schema ("..." marks an elision, taken
/// out; a request with an elision is not sent).
#[test]
fn protocol_md_examples_are_valid_by_the_schema() {
    let doc = include_str!("../../../../docs/protocol.md");
    let (requests, responses) = validators();
    let elide = |v: &mut Value| {
        fn walk(v: &mut Value) {
            match v {
                Value::Array(a) => {
                    a.retain(|x| x != "...");
                    a.iter_mut().for_each(walk);
                }
                Value::Object(o) => o.values_mut().for_each(walk),
                _ => {}
            }
        }
        walk(v)
    };
    let lines: Vec<&str> = doc.lines().collect();
    let mut checked = 0;
    for w in lines.windows(2) {
        let Some(doc_answer) = w[1].strip_prefix("-> ") else {
            continue;
        };
        let mut documented: Value = serde_json::from_str(doc_answer)
            .unwrap_or_else(|e| panic!("docs/protocol.md: {doc_answer}: {e}"));
        elide(&mut documented);
        let bad = schema_errors(responses, &documented);
        assert!(bad.is_empty(), "documented answer {doc_answer}:\n{bad}");
        let Ok(req) = serde_json::from_str::<Value>(w[0]) else {
            continue; // abbreviated or deliberately not JSON
        };
        let answer = handle_line(w[0]);
        assert_eq!(answer["ok"], documented["ok"], "{}: {answer}", w[0]);
        assert_eq!(
            answer["error"]["kind"], documented["error"]["kind"],
            "{}",
            w[0]
        );
        if answer["ok"] == true {
            assert!(schema_errors(requests, &req).is_empty());
        }
        checked += 1;
    }
    assert!(checked >= 12, "only {checked} examples checked");
}

/// Each op's schema names every field its request reads: a request with an unknown
/// field is refused, and the schema says so (`additionalProperties: false`).
#[test]
fn requests_refuse_unknown_fields_as_the_schema_does() {
    let s = schema();
    for op in OPS {
        let r = &s["x-ops"][op]["request"]["$ref"];
        let name = r.as_str().unwrap().rsplit('/').next().unwrap();
        let def = &s["$defs"][name];
        match def["oneOf"].as_array() {
            Some(kinds) => assert!(
                kinds.iter().all(|k| k["additionalProperties"] == false),
                "{op}"
            ),
            None => assert_eq!(def["additionalProperties"], false, "{op}"),
        }
        let v = super::handle_line(&format!(r#"{{"op": "{op}", "tolerence": 1}}"#));
        assert_eq!(kind(&v), "invalid_input", "{op}: {v}");
    }
    let v = super::handle_line(
        r#"{"op": "sketch.fit", "points": [[0,0],[1,1],[2,1],[3,0]], "tolerence": 1}"#,
    );
    let m = v["error"]["message"].as_str().unwrap();
    assert!(m.starts_with("tolerence: not a field"), "{m}");
}

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
    let r = handle_line(r#"{"op": "lac.segment", "alpha": -1, "control": [[0,0],[1,0],[1,0.3]]}"#);
    assert_eq!(kind(&r), "no_segment");
    assert!(
        r["error"]["message"]
            .as_str()
            .unwrap()
            .contains("must lie in"),
        "{r}"
    );
    let r = handle_line(r#"{"op": "lac.segment", "alpha": -1, "control": [[0,0],[1,0],[2,0]]}"#);
    assert_eq!(kind(&r), "degenerate");
    assert_eq!(
        kind(&handle_line(r#"{"op": "lac.point"}"#)),
        "invalid_input"
    );
    let r = handle_line(r#"{"op": "lac.point", "alpha": -1, "lambda": 0.5, "theta": [0.5, 3.0]}"#);
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

/// The protocol's option names are the library's (`as_str`): the serde enums and the
/// library's own names cannot drift apart.
#[test]
fn option_names_are_the_librarys() {
    use aesthetic_curves::lac_fit::{LacFitObjective, LacFitStart};
    use aesthetic_curves::pseudo_spline::Mode;
    for o in [
        LacFitObjective::Band,
        LacFitObjective::Distance,
        LacFitObjective::ArcLength,
    ] {
        serde_json::from_value::<lac::Objective>(json!(o.as_str())).unwrap();
        assert_eq!(LacFitObjective::from_name(o.as_str()).unwrap(), o);
    }
    for s in [LacFitStart::Scan, LacFitStart::Paper] {
        serde_json::from_value::<lac::Start>(json!(s.as_str())).unwrap();
    }
    for m in [Mode::Table, Mode::Exact] {
        let parsed: spline::SplineMode = serde_json::from_value(json!(m.as_str())).unwrap();
        assert_eq!(parsed.mode(), m);
        assert_eq!(json!(spline::SplineMode::from(m)), json!(m.as_str()));
    }
}
