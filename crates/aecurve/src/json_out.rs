//! JSON values for answers (the protocol's and `check --json`'s): objects built by moving
//! their values in, numbers that are not finite as null, and the end-curvature record.

use serde_json::{json, Value};

/// A JSON object of `pairs`, their values moved in (`json!` copies every value it is given,
/// which doubles the memory of a large answer while it is built).
pub fn object<const N: usize>(pairs: [(&str, Value); N]) -> Value {
    Value::Object(pairs.into_iter().map(|(k, v)| (k.to_string(), v)).collect())
}

/// A number, or null where it is not finite (JSON has no infinities).
pub fn finite_or_null(v: f64) -> Value {
    if v.is_finite() {
        json!(v)
    } else {
        Value::Null
    }
}

/// One end's curvature: `{"kind": "regular" | "finite" | "unbounded", "curvature": value or
/// null, "retracted_handles": n, "growth": "1/t" (unbounded only), "sign"}`.
pub fn end_curvature_json(e: &aesthetic_curves::monotone::EndCurvature) -> Value {
    use aesthetic_curves::monotone::EndCurvature as E;
    match *e {
        E::Regular(k) => {
            json!({"kind": "regular", "curvature": finite_or_null(k), "retracted_handles": 0})
        }
        E::Finite { curvature, order } => json!({
            "kind": "finite",
            "curvature": finite_or_null(curvature),
            "retracted_handles": order,
        }),
        E::Unbounded {
            positive,
            order,
            rate,
        } => json!({
            "kind": "unbounded",
            "curvature": null,
            "retracted_handles": order,
            "growth": if rate == 1 { "1/t".to_string() } else { format!("1/t^{rate}") },
            "sign": if positive { 1 } else { -1 },
        }),
    }
}
