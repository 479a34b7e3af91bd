//! One rational cubic for a segment with an inflection end: zero curvature at the
//! inflection, G2 at the other end, proven monotone curvature.

use super::problem::{turning, Samples};
use super::search::{levenberg_marquardt, LM_FULL};
use super::{ApproxOptions, RationalCubicFit};
use crate::bezier::{PlanarCurve, RationalBezier};
use crate::error::{Error, Result};
use crate::lac::LacInflectionSegment;
use crate::monotone::CurvatureMonotone;
use crate::solve::least_squares::LmOptions;
use kurbo::{Point, Vec2};

/// The rational cubics of the inflection-end family for a [`LacInflectionSegment`] with
/// triangle C0 (inflection end), C1, C2: `b0 = C0`, `b1 = C0 + f0 (C1 - C0)`, `b2 = C1`,
/// `b3 = C2`, weights `(w0, 1, 1, w3)`. b0, b1, b2 are collinear, so the curvature at b0 is
/// zero for every (f0, w0); `w3` matches the segment's curvature at C2 (end curvature is
/// linear in w3). Two free parameters: f0 in (0, 1) and w0 > 0.
pub(crate) fn inflection_cubic(
    seg: &LacInflectionSegment,
    f0: f64,
    w0: f64,
) -> Option<RationalBezier> {
    if !(f0 > 0.0 && f0 < 1.0 && w0 > 0.0 && w0.is_finite()) {
        return None;
    }
    let c = seg.control;
    let b = vec![c[0], c[0] + (c[1] - c[0]) * f0, c[1], c[2]];
    let probe = RationalBezier::new(b.clone(), vec![w0, 1.0, 1.0, 1.0]).ok()?;
    let w3 = seg.end_curvature() / probe.kappa_end();
    if !(w3 > 0.0 && w3.is_finite()) {
        return None;
    }
    RationalBezier::new(b, vec![w0, 1.0, 1.0, w3]).ok()
}

/// The inflection-end segment tabulated against arc-length fraction σ (turning angle
/// `τ = θ_d σ^q`), where it is smooth: positions and derivatives, cubic Hermite between.
pub(super) struct InflectionTable {
    p: Vec<Point>,
    d: Vec<Vec2>,
    theta_d: f64,
    r: f64,
    sign: f64,
    d0: Vec2,
    len: f64,
}

impl InflectionTable {
    pub(super) fn new(seg: &LacInflectionSegment, n: usize) -> Result<InflectionTable> {
        let r = seg.alpha / (seg.alpha - 1.0);
        let taus: Vec<f64> = (0..=n)
            .map(|k| seg.theta_d * (k as f64 / n as f64).powf(1.0 / r))
            .collect();
        let crate::lac::TurningSamples {
            points: p,
            tangents: t,
            ..
        } = seg.eval_turning(&taus)?;
        let len = seg.arc_length();
        let c = seg.control;
        Ok(InflectionTable {
            p,
            d: t.iter().map(|v| *v * len).collect(),
            theta_d: seg.theta_d,
            r,
            sign: (c[1] - c[0]).cross(c[2] - c[1]).signum(),
            d0: c[1] - c[0],
            len,
        })
    }

    /// The tabulated point and dP/dσ at arc-length fraction σ in [0, 1].
    fn at_sigma(&self, sigma: f64) -> (Point, Vec2) {
        let n = self.p.len() - 1;
        let sigma = sigma.clamp(0.0, 1.0);
        let k = ((sigma * n as f64) as usize).min(n - 1);
        let h = 1.0 / n as f64;
        let x = (sigma - k as f64 * h) / h;
        let (x2, x3) = (x * x, x * x * x);
        let (p0, p1) = (self.p[k].to_vec2(), self.p[k + 1].to_vec2());
        let (m0, m1) = (self.d[k] * h, self.d[k + 1] * h);
        let p = p0 * (2.0 * x3 - 3.0 * x2 + 1.0)
            + m0 * (x3 - 2.0 * x2 + x)
            + p1 * (-2.0 * x3 + 3.0 * x2)
            + m1 * (x3 - x2);
        let d = p0 * (6.0 * x2 - 6.0 * x)
            + m0 * (3.0 * x2 - 4.0 * x + 1.0)
            + p1 * (-6.0 * x2 + 6.0 * x)
            + m1 * (3.0 * x2 - 2.0 * x);
        (p.to_point(), d / h)
    }

    /// The arc-length fraction of the point of the segment nearest to `q`, from a start
    /// `sigma`: Gauss–Newton on the tabulated curve (the foot of the perpendicular).
    fn nearest_sigma(&self, q: Point, sigma: f64) -> f64 {
        let opts = crate::solve::roots::Newton1d {
            max_iterations: 30,
            max_step: f64::INFINITY,
            abs_tol: 1e-15,
            rel_tol: 0.0,
            bounds: (0.0, 1.0),
            clamp: true,
        };
        let update = |s: f64| {
            let (p, d) = self.at_sigma(s);
            Some(-(p - q).dot(d) / d.hypot2())
        };
        // (Its last iterate either way: the fit measures the distance it gives.)
        crate::solve::roots::newton_1d(update, sigma, &opts).x
    }

    fn at_turning(&self, tau: f64) -> Point {
        let n = self.p.len() - 1;
        let sigma = (tau / self.theta_d).clamp(0.0, 1.0).powf(self.r);
        let k = ((sigma * n as f64) as usize).min(n - 1);
        let h = 1.0 / n as f64;
        let x = (sigma - k as f64 * h) / h;
        let (x2, x3) = (x * x, x * x * x);
        let h00 = 2.0 * x3 - 3.0 * x2 + 1.0;
        let h10 = x3 - 2.0 * x2 + x;
        let h01 = -2.0 * x3 + 3.0 * x2;
        let h11 = x3 - x2;
        (self.p[k].to_vec2() * h00
            + self.d[k] * (h10 * h)
            + self.p[k + 1].to_vec2() * h01
            + self.d[k + 1] * (h11 * h))
            .to_point()
    }

    /// The residuals of [`InflectionTable::cost`] (x and y of each weighted distance),
    /// appended to `out` after clearing it; None for an invalid cubic.
    fn residuals(
        &self,
        curve: Option<RationalBezier>,
        smp: &Samples,
        out: &mut Vec<f64>,
    ) -> Option<()> {
        let c = curve?;
        out.clear();
        for (&t, &sw) in smp.t.iter().zip(&smp.sw) {
            let tau = turning(self.d0, c.eval_d(t), self.sign);
            let d = (c.eval(t) - self.at_turning(tau)) * (sw / self.len);
            out.push(d.x);
            out.push(d.y);
        }
        Some(())
    }

    /// Weighted mean square distance (by turning-angle correspondence, over the length) of
    /// the cubic at the Gauss samples; infinite for an invalid cubic.
    pub(super) fn cost(&self, curve: Option<RationalBezier>, smp: &Samples) -> f64 {
        let Some(c) = curve else {
            return f64::INFINITY;
        };
        let mut sum = 0.0;
        for (&t, &sw) in smp.t.iter().zip(&smp.sw) {
            let tau = turning(self.d0, c.eval_d(t), self.sign);
            let q = self.at_turning(tau);
            sum += ((c.eval(t) - q).hypot() * sw / self.len).powi(2);
        }
        sum
    }
}

/// The table's start for `seg` ([`crate::approx_table::inflection_table`]): of its
/// candidates, the curvature-monotone one of least `cost`, with the number of costs
/// evaluated; None where no candidate is monotone.
fn table_start(
    seg: &LacInflectionSegment,
    cost: &dyn Fn((f64, f64)) -> f64,
    monotone: &dyn Fn((f64, f64)) -> bool,
) -> Option<((f64, f64), usize)> {
    let mut candidates = Vec::new();
    crate::approx_table::inflection_table().candidates(seg.alpha, seg.theta_d, &mut candidates);
    let scored: Vec<(f64, (f64, f64))> = candidates
        .iter()
        .filter(|x| monotone(**x))
        .map(|&x| (cost(x), x))
        .filter(|c| c.0.is_finite())
        .collect();
    let best = scored.iter().min_by(|a, b| a.0.total_cmp(&b.0))?;
    Some((best.1, scored.len()))
}

/// Levenberg–Marquardt iterations from the table's start, which lies near the optimum: 8
/// found the same optima as 60 on 300 random shapes, and cut the spline's cubics by a
/// sixth.
const TABLE_START_ITERATIONS: usize = 8;

/// The compass search of [`fit_inflection_cubic`] stops below this step in (f0, ln w0 / 6):
/// the cubic's distance from the segment changes by far less than its size times 1e-9 over
/// such a step, while halving on to 1e-9 took a third of the time of a sketch fit.
const INFLECTION_STEP_FLOOR: f64 = 1e-6;

/// The best curvature-monotone rational cubic of the inflection-end family (see
/// `inflection_cubic`) for an inflection-end segment: from the shipped table's optima for
/// the nearest shapes ([`crate::approx_table::inflection_table`], with `opts.table`), or,
/// where none of them is monotone, from the best curvature-monotone points of a grid over
/// (f0, ln w0); Levenberg–Marquardt, then a compass search, non-monotone steps refused;
/// where the optimum lies on the boundary of the monotone set, a walk along it ([`crate::solve::minimize::along_boundary`]). The error is
/// reported on the exact segment at `opts.report_samples` uniform t. Within 1 % of an
/// exhaustive search in the tests. The curve starts at the
/// inflection end (zero curvature) and matches the end point, tangent and curvature at C2:
/// G2 at both ends. Errors: [`Error::NoSegment`] when no candidate is curvature-monotone.
pub fn fit_inflection_cubic(
    seg: &LacInflectionSegment,
    opts: &ApproxOptions,
) -> Result<RationalCubicFit> {
    fit_inflection_cubic_from(seg, opts, None, true).map(|r| r.0)
}

/// [`fit_inflection_cubic`], optionally from a warm start `(f0, ln w0)` (the optimum of a
/// segment of nearly the same shape: the family is similarity-invariant, so shape means
/// (α, θ_d)): the grid is skipped and the compass search starts there with a small step.
/// A warm start that is not curvature-monotone falls back to the full search. `search =
/// false` takes a warm start as it is (the optimum of a segment of exactly this shape).
/// Returns the fit and its `(f0, ln w0)`.
pub fn fit_inflection_cubic_from(
    seg: &LacInflectionSegment,
    opts: &ApproxOptions,
    warm: Option<(f64, f64)>,
    search: bool,
) -> Result<(RationalCubicFit, (f64, f64))> {
    let table = InflectionTable::new(seg, 256)?;
    let tg = Samples::gauss(opts.grid_samples.max(4));
    let tr = Samples::gauss(opts.refine_samples.max(4));
    let n = opts.grid.clamp(3, 1000);
    let make = |x: (f64, f64)| inflection_cubic(seg, x.0, x.1.exp());
    // Proven by the floating-point filter: a candidate only exact arithmetic could decide
    // lies on the monotone set's boundary to within rounding, and counts as outside it
    // (the boundary walk's bisection met hundreds of them, at a millisecond each).
    let monotone = |x: (f64, f64)| {
        make(x)
            .and_then(|c| {
                crate::monotone::filtered_verdict(c.points(), Some(c.weights()))
                    .ok()
                    .flatten()
            })
            .unwrap_or(false)
    };
    let mut evals = 0;
    let mut grid = Vec::new();
    let given = warm.filter(|x| monotone(*x));
    // Without a start of its own, the fit starts from the shipped table's optima for the
    // nearest shapes (the best monotone one), searched from there.
    let from_table = match given {
        None if opts.table => table_start(seg, &|x| table.cost(make(x), &tr), &monotone),
        _ => None,
    };
    let (warm, search) = match from_table {
        Some((x, e)) => {
            evals += e;
            (Some(x), true)
        }
        None => (given, search),
    };
    let cells = if warm.is_some() { 0 } else { n };
    for i in 0..cells {
        for j in 0..n {
            let x = (
                (i as f64 + 0.5) / n as f64,
                -3.0 + 6.0 * (j as f64 + 0.5) / n as f64,
            );
            let c = table.cost(make(x), &tg);
            evals += 1;
            if c.is_finite() {
                grid.push((c, x));
            }
        }
    }
    grid.sort_by(|a, b| a.0.total_cmp(&b.0));
    let starts: Vec<(f64, f64)> = match warm {
        Some(x) => vec![x],
        None => grid
            .iter()
            .filter(|(_, x)| monotone(*x))
            .take(opts.starts.max(1) + 1)
            .map(|(_, x)| *x)
            .collect(),
    };
    let mut best: Option<(f64, (f64, f64), bool)> = None;
    let residuals = |x: (f64, f64), out: &mut Vec<f64>| table.residuals(make(x), &tr, out);
    let domain = |x: (f64, f64)| x.0 < 1.0;
    let feasible = |x: (f64, f64)| x.0 > 0.0 && x.0 < 1.0 && x.1.is_finite() && monotone(x);
    for s in starts {
        // Levenberg–Marquardt on the refine samples (monotone steps only) goes down the
        // valley; a compass search from there, monotone steps only, slides along the
        // monotone boundary when the optimum lies on it.
        let mut x = s;
        let h = match (warm, search) {
            (Some(_), false) => 0.0,
            _ => {
                let (y, _, e, _) = levenberg_marquardt(
                    &residuals,
                    &domain,
                    &feasible,
                    s,
                    LmOptions {
                        max_iterations: if from_table.is_some() {
                            opts.max_iter.min(TABLE_START_ITERATIONS)
                        } else {
                            opts.max_iter
                        },
                        ..LM_FULL
                    },
                );
                evals += e;
                x = y;
                0.02 / n as f64
            }
        };
        let opts = crate::solve::minimize::CompassSearch {
            scale: 6.0,
            step: h,
            floor: INFLECTION_STEP_FLOOR,
            max_evaluations: 20_000usize.saturating_sub(evals),
        };
        let r = crate::solve::minimize::compass_search(
            &mut |y| table.cost(make(y), &tr),
            &|y| monotone(y),
            (x, table.cost(make(x), &tr)),
            &opts,
        );
        evals += r.evaluations;
        let (mut cost, mut x, h) = (r.value, r.x, r.step);
        let converged = r.converged;
        // The compass stalls where the optimum lies on the monotone boundary and the
        // boundary runs between its directions: walk along it.
        // A start already half as far off again as the best one so far is not walked:
        // the walks measured gained under 10 %, and one walk can cost thousands of
        // verdicts (a wedge of the monotone set).
        let behind = best.is_some_and(|b| cost > 1.5 * b.0);
        if h > 0.0 && !behind {
            let c = |y: (f64, f64)| table.cost(make(y), &tr);
            if let Some((y, cy, e)) =
                crate::solve::minimize::along_boundary(&c, &feasible, x, (1.0, 6.0), 12)
            {
                evals += e;
                (cost, x) = (cy, y);
            }
        }
        if best.is_none_or(|b| cost < b.0) {
            best = Some((cost, x, converged));
        }
    }
    let Some((_, x, converged)) = best else {
        return Err(Error::NoSegment(
            "no rational cubic of the inflection-end family has monotone curvature for this segment"
                .into(),
        ));
    };
    let curve = make(x).ok_or_else(|| Error::NoConvergence("inflection cubic vanished".into()))?;
    // Report on the exact segment, by the distance to its nearest point. (Matching points of
    // equal tangent direction, the measure of S3 used for ordinary segments, is
    // ill-conditioned next to the inflection, where the direction hardly changes along the
    // curve: it overstated the error up to a thousandfold.) The foot of the perpendicular is
    // found on the table, then the exact segment is evaluated there.
    let nr = opts.report_samples.max(200);
    let ts: Vec<f64> = (0..nr).map(|i| i as f64 / (nr - 1) as f64).collect();
    let taus: Vec<f64> = ts
        .iter()
        .map(|&t| {
            let tau = turning(table.d0, curve.eval_d(t), table.sign).clamp(0.0, seg.theta_d);
            let start = (tau / seg.theta_d).powf(table.r);
            let sigma = table.nearest_sigma(curve.eval(t), start);
            seg.theta_d * sigma.powf(1.0 / table.r)
        })
        .collect();
    let exact = seg.eval_turning(&taus)?.points;
    let (mut sum, mut max) = (0.0f64, 0.0f64);
    for (&t, q) in ts.iter().zip(&exact) {
        let d = (curve.eval(t) - *q).hypot() / table.len;
        sum += d * d;
        max = max.max(d);
    }
    let monotone = curve.is_curvature_monotone()?;
    Ok((
        RationalCubicFit {
            f0: x.0,
            f1: 1.0,
            rms: (sum / nr as f64).sqrt(),
            max_error: max,
            monotone,
            evaluations: evals,
            converged,
            curve,
        },
        x,
    ))
}
