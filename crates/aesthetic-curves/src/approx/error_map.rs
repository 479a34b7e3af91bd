//! The error of the §4 rational cubic over the whole (f0, f1) square (S3 Fig. 3 and 5).

use super::problem::{Problem, Samples};
use crate::error::{Error, Result};
use crate::lac::LacSegment;

/// The error map of S3 Fig. 3 and 5 (see [`error_map`]).
#[derive(Clone, Debug)]
pub struct ErrorMap {
    /// Cells per axis; cell (i, j) is centred at f0 = (i + 1/2)/n, f1 = (j + 1/2)/n.
    pub n: usize,
    /// Rms error of cell (i, j) at index `i * n + j` (infinite where no cubic exists).
    pub rms: Vec<f64>,
    /// Curvature monotonicity (exact test) of cell (i, j) at index `i * n + j`.
    pub monotone: Vec<bool>,
}

/// Rms error (table measure, `samples` Gauss–Legendre t) and exact curvature monotonicity at the
/// centres of an `n` x `n` grid over (f0, f1).
pub fn error_map(seg: &LacSegment, n: usize, samples: usize) -> Result<ErrorMap> {
    if !(2..=2000).contains(&n) || samples < 4 {
        return Err(Error::invalid(
            "grid",
            "needs 2 to 2000 cells per axis and 4 samples",
        ));
    }
    let prob = Problem::new(seg, 256)?;
    let ts = Samples::gauss(samples);
    let mut buf = Vec::new();
    let at = |i: usize| (i as f64 + 0.5) / n as f64;
    let mut rms = vec![0.0; n * n];
    let mut monotone = vec![false; n * n];
    for i in 0..n {
        for j in 0..n {
            rms[i * n + j] = prob.cost(at(i), at(j), &ts, &mut buf).sqrt();
            monotone[i * n + j] = prob.is_monotone(at(i), at(j));
        }
    }
    Ok(ErrorMap { n, rms, monotone })
}
