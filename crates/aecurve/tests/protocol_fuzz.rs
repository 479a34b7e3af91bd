//! Property tests: the batch loop never panics, answers every non-blank line exactly once, in
//! order, with a well-formed response, whatever bytes or JSON it is fed.

use aecurve::batch;
use proptest::prelude::*;
use serde_json::{json, Value};

fn responses(input: &[u8]) -> Vec<Value> {
    let mut out = Vec::new();
    batch::run(input, &mut out, 4096).expect("io on memory buffers");
    String::from_utf8(out)
        .expect("responses are UTF-8")
        .lines()
        .map(|l| serde_json::from_str(l).expect("each response line is JSON"))
        .collect()
}

fn well_formed(v: &Value) {
    crate::schema::valid_response(v);
    let ok = v["ok"].as_bool().expect("ok is a bool");
    assert!(v.get("id").is_some(), "id present: {v}");
    if ok {
        assert!(v["result"].is_object(), "{v}");
    } else {
        let kind = v["error"]["kind"].as_str().expect("kind");
        assert!(
            [
                "parse",
                "unknown_op",
                "invalid_input",
                "degenerate",
                "no_segment",
                "no_convergence"
            ]
            .contains(&kind),
            "{kind}"
        );
        assert!(v["error"]["message"]
            .as_str()
            .is_some_and(|m| !m.is_empty()));
    }
}

fn arb_json() -> impl Strategy<Value = Value> {
    let leaf = prop_oneof![
        Just(Value::Null),
        any::<bool>().prop_map(Value::Bool),
        any::<f64>()
            .prop_filter("finite", |v| v.is_finite())
            .prop_map(|v| json!(v)),
        any::<i64>().prop_map(|v| json!(v)),
        "[a-z_.]{0,12}".prop_map(Value::String),
    ];
    leaf.prop_recursive(4, 40, 6, |inner| {
        prop_oneof![
            prop::collection::vec(inner.clone(), 0..6).prop_map(Value::Array),
            prop::collection::btree_map("[a-z_]{1,8}", inner, 0..6)
                .prop_map(|m| Value::Object(m.into_iter().collect())),
        ]
    })
}

fn arb_request() -> impl Strategy<Value = Value> {
    let point = (any::<f64>(), -1e3f64..1e3).prop_map(|(x, y)| {
        let x = if x.is_finite() { x % 1e6 } else { 0.5 };
        json!([x, y])
    });
    (
        prop::collection::vec(point, 0..24),
        prop::option::of(prop::collection::vec(-2.0f64..4.0, 0..24)),
        prop::option::of(prop_oneof![Just("exact"), Just("sampling"), Just("other")]),
        prop::option::of(0u64..2000),
        arb_json(),
    )
        .prop_map(|(pts, w, method, samples, id)| {
            let mut r = json!({"id": id, "op": "bezier.curvature_monotone", "control_points": pts});
            if let Some(w) = w {
                r["weights"] = json!(w);
            }
            if let Some(m) = method {
                r["method"] = json!(m);
            }
            if let Some(s) = samples {
                r["samples"] = json!(s);
            }
            r
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn arbitrary_bytes_never_panic(lines in prop::collection::vec(prop::collection::vec(any::<u8>(), 0..200), 1..8)) {
        let mut input = Vec::new();
        let mut expected = 0;
        for l in &lines {
            let l: Vec<u8> = l.iter().copied().filter(|b| *b != b'\n').collect();
            let blank = std::str::from_utf8(&l).map(|s| s.trim().is_empty()).unwrap_or(false);
            if !blank {
                expected += 1;
            }
            input.extend_from_slice(&l);
            input.push(b'\n');
        }
        let r = responses(&input);
        prop_assert_eq!(r.len(), expected);
        for v in &r {
            well_formed(v);
        }
    }

    #[test]
    fn arbitrary_json_never_panics(vals in prop::collection::vec(arb_json(), 1..6)) {
        let input: String = vals.iter().map(|v| format!("{v}\n")).collect();
        let r = responses(input.as_bytes());
        prop_assert_eq!(r.len(), vals.len());
        for v in &r {
            well_formed(v);
        }
    }

    #[test]
    fn arbitrary_requests_keep_their_ids(reqs in prop::collection::vec(arb_request(), 1..6)) {
        let input: String = reqs.iter().map(|v| format!("{v}\n")).collect();
        let mut out = Vec::new();
        batch::run(input.as_bytes(), &mut out, 1 << 20).unwrap();
        let r: Vec<Value> = String::from_utf8(out).unwrap().lines().map(|l| serde_json::from_str(l).unwrap()).collect();
        prop_assert_eq!(r.len(), reqs.len());
        for (q, a) in reqs.iter().zip(&r) {
            well_formed(a);
            prop_assert_eq!(&q["id"], &a["id"]);
        }
    }
}

/// A monotone test's report (`bezier.curvature_monotone`'s, or a segment of
/// `outline.check`'s) with the nulls it holds by design set to values: an end's curvature
/// where it is unbounded or beyond f64 (then with its sign; also in `end_curvatures`, and
/// `max_abs_curvature` with it), and the `trend` of a curve that is not monotone.
fn clear_designed_nulls(r: &mut Value) {
    let mut any = false;
    for i in 0..2 {
        let e = &r["ends"][i];
        if e["kind"] == "unbounded" || e["sign"].is_i64() {
            any = true;
            r["ends"][i]["curvature"] = json!(0.0);
            if r.get("end_curvatures").is_some() {
                r["end_curvatures"][i] = json!(0.0);
            }
        }
    }
    if any && r.get("max_abs_curvature").is_some() {
        r["max_abs_curvature"] = json!(0.0);
    }
    if r["monotone"] == false || r["trend"].is_null() {
        r["trend"] = json!("none");
    }
}

fn has_null(v: &Value) -> bool {
    match v {
        Value::Null => true,
        Value::Array(a) => a.iter().any(has_null),
        Value::Object(o) => o.values().any(has_null),
        _ => false,
    }
}

fn arb_number() -> impl Strategy<Value = f64> {
    prop_oneof![
        -30.0f64..30.0,
        -1e6f64..1e6,
        Just(0.0),
        Just(1.0),
        Just(-1.0),
        Just(2.0),
        Just(1e300),
        Just(-1e300),
        Just(1e-300),
    ]
}

fn arb_lac_request() -> impl Strategy<Value = Value> {
    (
        0usize..12,
        arb_number(),
        arb_number(),
        prop::collection::vec(arb_number(), 0..6),
        prop::collection::vec((arb_number(), arb_number()), 3..14),
        prop::option::of(0u64..300),
    )
        .prop_map(|(op, alpha, lambda, theta, control, samples)| {
            let control: Vec<Value> = control.iter().map(|(x, y)| json!([x, y])).collect();
            let mut r = match op {
                0 => json!({"id": 1, "op": "lac.point", "alpha": alpha, "lambda": lambda, "theta": theta}),
                1 => json!({"id": 2, "op": "lac.segment", "alpha": alpha, "control": control[..3]}),
                2 => json!({"id": 3, "op": "lac.inflection_segment", "control": control[..3]}),
                // Coordinates from 1e-300 to 1e300 in one curve: its end curvatures too.
                3 => {
                    let pts = &control[..control.len().min(5)];
                    let mut r = json!({"id": 12, "op": "bezier.curvature_monotone",
                        "control_points": pts});
                    // A rational one now and then: weights from the θ values, made positive.
                    if theta.len() >= pts.len() {
                        r["weights"] = json!(theta[..pts.len()]
                            .iter()
                            .map(|w| w.abs().max(1e-3))
                            .collect::<Vec<_>>());
                    }
                    r
                }
                4 => json!({"id": 5, "op": "lac.rational_approx", "alpha": alpha, "control": control[..3], "tolerance": lambda}),
                5 => json!({"id": 6, "op": "sketch.fit", "points": control, "tolerance": lambda}),
                6 => json!({"id": 7, "op": "spline.pseudo_elastic", "points": control}),
                7 => json!({"id": 8, "op": "spline.pseudo_elastic", "points": control, "closed": true}),
                8 => {
                    // Cubics end to end from the points (and a line for what is left).
                    let mut segs: Vec<Value> = control
                        .windows(4)
                        .step_by(3)
                        .map(|w| json!({"control_points": w}))
                        .collect();
                    if segs.is_empty() {
                        segs.push(json!({"control_points": control[..2]}));
                    }
                    json!({"id": 9, "op": "outline.fix", "segments": segs, "tolerance": lambda,
                        "closed": alpha > 0.0, "grid": theta.first().copied().unwrap_or(0.0),
                        "move_points": alpha < -1.0})
                }
                9 => json!({"id": 10, "op": "sketch.contour", "points": control, "tolerance": lambda,
                    "closed": if alpha > 1.0 { json!(true) } else if alpha < -1.0 { json!(false) } else { Value::Null },
                    "corner_angle_degrees": theta.first().copied().unwrap_or(35.0)}),
                10 => json!({"id": 11, "op": "spline.lac", "points": control, "alpha": alpha,
                    "closed": lambda > 0.0, "corners": [0, 2]}),
                11 if alpha > 0.0 => {
                    // The exact check of a contour, with suggestions (the handle search).
                    let segs: Vec<Value> = control
                        .windows(4)
                        .step_by(3)
                        .map(|w| json!({"control_points": w}))
                        .collect();
                    json!({"id": 13, "op": "outline.check", "closed": lambda > 0.0,
                        "segments": if segs.is_empty() { json!([{"control_points": control[..2]}]) } else { json!(segs) },
                        "suggest": theta.first().copied().unwrap_or(1.0)})
                }
                _ => json!({"id": 4, "op": "lcg.estimate", "points": control}),
            };
            if let Some(s) = samples {
                r["samples"] = json!(s);
            }
            r
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn lac_requests_never_panic_or_produce_non_finite(reqs in prop::collection::vec(arb_lac_request(), 1..4)) {
        let input: String = reqs.iter().map(|v| format!("{v}\n")).collect();
        let mut out = Vec::new();
        batch::run(input.as_bytes(), &mut out, 1 << 20).unwrap();
        let text = String::from_utf8(out).unwrap();
        let r: Vec<Value> = text.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
        prop_assert_eq!(r.len(), reqs.len());
        for a in &r {
            well_formed(a);
            // serde_json writes a non-finite number as null: results must have none (the
            // monotone test's report has two fields that are null by design).
            let mut result = a["result"].clone();
            if a["ok"] == true && a["id"] == 12 {
                clear_designed_nulls(&mut result);
            }
            if a["ok"] == true && a["id"] == 13 {
                for c in result["shapes"][0]["contours"].as_array_mut().unwrap() {
                    c["segments"]
                        .as_array_mut()
                        .unwrap()
                        .iter_mut()
                        .for_each(clear_designed_nulls);
                }
            }
            prop_assert!(!has_null(&result) || a["ok"] == false, "{}", a);
        }
    }
}
