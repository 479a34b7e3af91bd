//! `lcg.estimate`: the logarithmic curvature graph of sampled points and its fitted line.

use super::fields::Points;
use super::{Op, ProtoError, Request};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Largest point sampling `lcg.estimate` accepts.
pub const MAX_LCG_POINTS: usize = 100_000;

/// Points sampled along one curve.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LcgRequest {
    /// The points, in order along the curve.
    pub points: Points<{ aesthetic_curves::lcg::MIN_POINTS }, MAX_LCG_POINTS>,
}

impl Request for LcgRequest {}

/// The fitted line and the graph.
#[derive(Debug, Serialize, JsonSchema)]
pub struct LcgResult {
    /// The line's slope: the estimated α.
    pub alpha: f64,
    /// How straight the graph is (1: a line).
    pub r_squared: f64,
    /// The line's intercept.
    pub intercept: f64,
    /// Root-mean-square distance of the graph from the line.
    pub rms_residual: f64,
    /// The graph: `[log ρ, log(ρ ds/dρ)]` pairs.
    pub graph: Vec<[f64; 2]>,
}

/// The result of `lcg.estimate` (also `aecurve lcg --json`).
pub fn lcg_json(fit: &aesthetic_curves::lcg::LcgFit) -> LcgResult {
    LcgResult {
        alpha: fit.alpha,
        r_squared: fit.r_squared,
        intercept: fit.intercept,
        rms_residual: fit.rms_residual,
        graph: fit
            .graph
            .iter()
            .map(|p| [p.log_rho, p.log_rho_ds_drho])
            .collect(),
    }
}

/// `lcg.estimate`.
pub struct LcgEstimate;

impl Op for LcgEstimate {
    const NAME: &'static str = "lcg.estimate";
    type Request = LcgRequest;
    type Response = LcgResult;

    fn answer(req: LcgRequest) -> Result<LcgResult, ProtoError> {
        Ok(lcg_json(&aesthetic_curves::lcg::estimate_from_points(
            &req.points.0,
        )?))
    }
}
