//! JSON values for answers (the protocol's and `check --json`'s): objects built by moving
//! their values in, numbers that are not finite as null, and the end-curvature record.

use serde_json::{json, Value};

/// A JSON object of `pairs`, their values moved in (`json!` copies every value it is given,
/// which doubles the memory of a large answer while it is built).
pub fn object<const N: usize>(pairs: [(&str, Value); N]) -> Value {
    Value::Object(pairs.into_iter().map(|(k, v)| (k.to_string(), v)).collect())
}

/// A number where it is finite, else None (absent or null in a response: JSON has no
/// infinities).
pub fn finite(v: f64) -> Option<f64> {
    Some(v).filter(|v| v.is_finite())
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
#[derive(Debug, Clone, serde::Serialize, schemars::JsonSchema)]
pub struct EndCurvatureJson {
    /// `regular`, `finite` (at retracted handles) or `unbounded`.
    pub kind: &'static str,
    /// The curvature there; null where it grows without bound, or where it is finite but
    /// beyond what an f64 holds (a curve spanning hundreds of orders of magnitude: `sign`
    /// then says its sign).
    pub curvature: Option<f64>,
    /// How many handles at this end are retracted onto their point.
    pub retracted_handles: usize,
    /// How fast an unbounded curvature grows (`1/t`, `1/t^2`, ...).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub growth: Option<String>,
    /// The sign of an unbounded curvature, or of one beyond the f64 range.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sign: Option<i8>,
}

impl From<&aesthetic_curves::monotone::EndCurvature> for EndCurvatureJson {
    fn from(e: &aesthetic_curves::monotone::EndCurvature) -> Self {
        use aesthetic_curves::monotone::EndCurvature as E;
        let (kind, curvature, retracted_handles) = match *e {
            E::Regular(k) => ("regular", finite(k), 0),
            E::Finite { curvature, order } => ("finite", finite(curvature), order),
            E::Unbounded { order, .. } => ("unbounded", None, order),
        };
        let (growth, sign) = match *e {
            E::Unbounded { positive, rate, .. } => (
                Some(if rate == 1 {
                    "1/t".to_string()
                } else {
                    format!("1/t^{rate}")
                }),
                Some(if positive { 1 } else { -1 }),
            ),
            // Finite, but beyond f64: its sign, the value null.
            E::Regular(k) | E::Finite { curvature: k, .. } if k.is_infinite() => {
                (None, Some(if k > 0.0 { 1 } else { -1 }))
            }
            _ => (None, None),
        };
        EndCurvatureJson {
            kind,
            curvature,
            retracted_handles,
            growth,
            sign,
        }
    }
}
