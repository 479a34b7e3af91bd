//! `bezier.curvature_monotone`: the exact (or sampled) monotone-curvature test of one
//! Bézier curve, polynomial or rational.

use super::drawing::{drawing_json, WithDrawing};
use super::fields::{check_weight_count, weights, Draw, IntIn, Points, Weights};
use super::{Op, ProtoError, Request};
use crate::any_bezier::AnyBezier;
use crate::json_out::EndCurvatureJson;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Largest number of divisions the sampling test accepts from a request.
pub const MAX_SAMPLES: u64 = 1_000_000;

/// How the test decides.
#[derive(Debug, Clone, Copy, PartialEq, Default, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// The exact test (a proof).
    #[default]
    Exact,
    /// Curvature compared at `samples` divisions (not a proof).
    Sampling,
}

/// A Bézier curve to test.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CurvatureMonotoneRequest {
    /// Control points (degree 1 to 20).
    pub control_points: Points<2, 21>,
    /// Positive weights, one per control point (a rational curve).
    #[serde(default)]
    pub weights: Option<Weights>,
    /// `exact` (default) or `sampling`.
    #[serde(default)]
    pub method: Option<Method>,
    /// Divisions of the sampling test (default 100); only with `sampling`.
    #[serde(default)]
    pub samples: Option<IntIn<1, MAX_SAMPLES>>,
    /// Points per piece of a `drawing`.
    #[serde(default)]
    pub draw: Option<Draw>,
}

impl Request for CurvatureMonotoneRequest {
    fn check(&self) -> Result<(), ProtoError> {
        if let Some(w) = &self.weights {
            check_weight_count("weights", self.control_points.0.len(), w.len())?;
        }
        if self.samples.is_some() && self.method.unwrap_or_default() == Method::Exact {
            // Accepted and ignored would hide a mistake: say so.
            return Err(ProtoError::invalid(
                "samples",
                "only applies to method \"sampling\"",
            ));
        }
        Ok(())
    }
}

/// The exact test's verdict (also `aecurve monotone --json`).
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct MonotoneResult {
    /// Whether the curvature is monotone (proven).
    pub monotone: bool,
    /// Parameters of the interior curvature extrema.
    pub extrema: Vec<f64>,
    /// Degree of the polynomial whose signs decide.
    pub test_degree: usize,
    /// `increasing`, `decreasing` or `constant`; null where not monotone.
    pub trend: Option<&'static str>,
    /// Whether exact arithmetic decided a sign floating point could not.
    pub exact_arithmetic: bool,
    /// The curvature at each end.
    pub ends: Vec<EndCurvatureJson>,
}

/// The sampling test's verdict.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct SampledResult {
    /// Whether the sampled curvatures are monotone.
    pub monotone: bool,
    /// Divisions compared.
    pub samples: usize,
    /// `increasing`, `decreasing` or `constant`; null where not monotone.
    pub trend: Option<&'static str>,
}

/// Either test's verdict.
#[derive(Debug, Clone, Serialize, JsonSchema)]
#[serde(untagged)]
pub enum Verdict {
    /// `method: exact`.
    Exact(MonotoneResult),
    /// `method: sampling`.
    Sampled(SampledResult),
}

/// The result of `bezier.curvature_monotone` (exact test), also `aecurve monotone --json`.
pub fn monotone_json(r: &aesthetic_curves::MonotoneReport) -> MonotoneResult {
    MonotoneResult {
        monotone: r.monotone,
        extrema: r.extrema.clone(),
        test_degree: r.test_degree,
        trend: r.trend.map(|t| t.as_str()),
        exact_arithmetic: r.exact,
        ends: r.ends.iter().map(EndCurvatureJson::from).collect(),
    }
}

/// The result of `bezier.curvature_monotone` with `"method": "sampling"`.
pub fn sampled_json(r: &aesthetic_curves::SampledReport) -> SampledResult {
    SampledResult {
        monotone: r.monotone,
        samples: r.samples,
        trend: r.trend.map(|t| t.as_str()),
    }
}

/// `bezier.curvature_monotone`.
pub struct CurvatureMonotone;

impl Op for CurvatureMonotone {
    const NAME: &'static str = "bezier.curvature_monotone";
    type Request = CurvatureMonotoneRequest;
    type Response = WithDrawing<Verdict>;

    fn answer(req: CurvatureMonotoneRequest) -> Result<Self::Response, ProtoError> {
        let curve = AnyBezier::new(req.control_points.0, req.weights.map(|w| weights(&w)))?;
        let c = curve.as_monotone();
        let (verdict, extrema) = match req.method.unwrap_or_default() {
            Method::Exact => {
                let r = c.curvature_monotone()?;
                (Verdict::Exact(monotone_json(&r)), r.extrema)
            }
            Method::Sampling => {
                let n = req.samples.map_or(100, |s| s.0) as usize;
                (
                    Verdict::Sampled(sampled_json(&c.curvature_monotone_sampled(n)?)),
                    Vec::new(),
                )
            }
        };
        let drawing = match req.draw {
            Some(Draw { 0: n }) => {
                let rational = match &curve {
                    AnyBezier::Poly(b) => b.to_rational(),
                    AnyBezier::Rational(r) => r.clone(),
                };
                let nurbs = aesthetic_curves::nurbs::Nurbs::from_bezier(&rational);
                let mut d = drawing_json(curve.as_curve(), n as usize, Some(&nurbs))?;
                // The interior curvature extrema, where a picture circles them.
                d.marks = Some(
                    extrema
                        .iter()
                        .map(|&t| {
                            let p = curve.eval(t);
                            [p.x, p.y]
                        })
                        .collect(),
                );
                Some(d)
            }
            None => None,
        };
        Ok(WithDrawing {
            result: verdict,
            drawing,
        })
    }
}
