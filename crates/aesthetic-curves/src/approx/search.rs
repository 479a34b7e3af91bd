//! The rational-cubic fit's search over (f0, f1) (steps 2 to 4 of the module documentation
//! of `approx`): the table's starts refined by Levenberg–Marquardt, the walk along a
//! hairline valley's floor, the refinement that keeps to the curvature-monotone region, and
//! the search of the whole square.

use super::problem::{Problem, Samples};
use super::valley;
use super::ApproxOptions;
use crate::lac::LacSegment;
use crate::solve::least_squares::LmOptions;
use crate::solve::minimize::{compass_search as compass_search_in, CompassSearch};

/// Minimise the cost along one grid line: `axis` 0 fixes f0 = `fixed` and varies f1 from
/// `start` within `± width`, axis 1 the other way round ([`valley::line_min_along`] with
/// four iterations: enough to put the point on the valley floor well enough to rank it; the
/// 2-D refinement does the rest; the search of the whole square alone finds 980 of the
/// sweep's 1000 optima). Returns the minimiser, its cost and the evaluations spent.
pub(super) fn line_min(
    prob: &Problem,
    axis: usize,
    fixed: f64,
    start: f64,
    width: f64,
    ts: &Samples,
) -> (f64, f64, usize) {
    let (origin, dir) = if axis == 0 {
        ((fixed, start), (0.0, 1.0))
    } else {
        ((start, fixed), (1.0, 0.0))
    };
    let (s, c, e) = valley::line_min_along(prob, origin, dir, width, ts, 4, 0.0);
    (start + s, c, e)
}

/// Compass search from a feasible `start`: try the eight neighbours at distance `h`, move to
/// the best improvement, halve `h` when none improves, stop below 1e-9.
pub(super) fn compass_search(
    prob: &Problem,
    start: (f64, f64),
    ts: &Samples,
    feasible: &dyn Fn(f64, f64) -> bool,
    h: f64,
) -> ((f64, f64), f64, usize) {
    let mut buf = Vec::new();
    let value = prob.cost(start.0, start.1, ts, &mut buf);
    let opts = CompassSearch {
        scale: 1.0,
        step: h,
        floor: 1e-9,
        max_evaluations: 1999,
    };
    let r = compass_search_in(
        &mut |y| prob.cost(y.0, y.1, ts, &mut buf),
        &|y| feasible(y.0, y.1),
        (start, value),
        &opts,
    );
    (r.x, r.value, r.evaluations + 1)
}

/// The Levenberg–Marquardt rules of this module ([`crate::solve::least_squares`]): to
/// convergence at 1e-12 relative progress or a step under 1e-9, never abandoned, up to 12
/// damping retries, no damping floor; `max_iterations` is set by each caller.
pub(super) const LM_FULL: LmOptions = LmOptions {
    max_iterations: 0,
    mu0: 1e-3,
    rel_progress: 1e-12,
    min_step: 1e-9,
    max_damping_tries: 12,
    damping_floor: 0.0,
    fd_step: 1e-7,
    abandon_after: usize::MAX,
    abandon_above: f64::INFINITY,
    abandon_predicted_above: f64::INFINITY,
};

/// Levenberg–Marquardt on the residual vector from `start`; steps where `feasible` is false
/// are refused. A run still above `abandon_above` (mean square) after 8 iterations is
/// abandoned: it is crawling along a valley towards a minimum far worse than one already
/// found. Returns the point, its cost and the evaluations spent.
pub(super) fn refine(
    prob: &Problem,
    start: (f64, f64),
    ts: &Samples,
    max_iter: usize,
    feasible: &dyn Fn(f64, f64) -> bool,
    abandon_above: f64,
    closed_form: bool,
) -> ((f64, f64), f64, usize) {
    let opts = LmOptions {
        abandon_after: 8,
        abandon_above,
        ..LM_FULL
    };
    let (x, c, e, _) = refine_with(prob, start, ts, max_iter, feasible, opts, closed_form);
    (x, c, e)
}

/// [`refine`] with explicit stopping rules (`max_iter` overrides theirs); also says whether
/// it converged (stopped for lack of progress, not at the iteration limit or abandoned).
/// `closed_form`: the table's Jacobian in closed form ([`Problem::residuals_jac`]), else
/// forward differences (always for the exact LAC).
pub(super) fn refine_with(
    prob: &Problem,
    start: (f64, f64),
    ts: &Samples,
    max_iter: usize,
    feasible: &dyn Fn(f64, f64) -> bool,
    opts: LmOptions,
    closed_form: bool,
) -> ((f64, f64), f64, usize, bool) {
    let residuals = |x: (f64, f64), out: &mut Vec<f64>| prob.residuals(x.0, x.1, ts, out);
    let in_box = |x: (f64, f64)| x.0 > 0.0 && x.0 < 1.0 && x.1 > 0.0 && x.1 < 1.0;
    let opts = LmOptions {
        max_iterations: max_iter,
        ..opts
    };
    if prob.exact || !closed_form {
        return levenberg_marquardt(
            &residuals,
            &|x| x.0 < 1.0 && x.1 < 1.0,
            &|x| in_box(x) && feasible(x.0, x.1),
            start,
            opts,
        );
    }
    // The table's residuals have a closed-form Jacobian.
    let fit = crate::solve::least_squares::levenberg_marquardt_jac(
        &mut |x: &[f64; 2], out: &mut Vec<f64>| prob.residuals(x[0], x[1], ts, out),
        &mut |x: &[f64; 2], out: &mut Vec<f64>, jac: &mut [Vec<f64>; 2]| {
            prob.residuals_jac(x[0], x[1], ts, out, jac)
        },
        &|x| in_box((x[0], x[1])) && feasible(x[0], x[1]),
        [start.0, start.1],
        &opts,
    );
    as_pair(&fit)
}

/// A two-parameter run's result as (point, sum of squares, evaluations, converged).
pub(super) fn as_pair(
    fit: &crate::solve::least_squares::LeastSquares<2>,
) -> ((f64, f64), f64, usize, bool) {
    (
        (fit.x[0], fit.x[1]),
        fit.cost,
        fit.evaluations,
        fit.converged(),
    )
}

/// Residuals at a point of two parameters, written into the vector (None: invalid point).
pub(super) type Residuals<'a> = &'a dyn Fn((f64, f64), &mut Vec<f64>) -> Option<()>;

/// [`crate::solve::least_squares::levenberg_marquardt`] over two parameters given as a
/// pair: the forward-difference Jacobian steps backwards where the forward point is outside
/// `domain`; steps where `feasible` is false are refused. Returns the point, its sum of
/// squares, the evaluations and whether it converged.
pub(super) fn levenberg_marquardt(
    residuals: Residuals,
    domain: &dyn Fn((f64, f64)) -> bool,
    feasible: &dyn Fn((f64, f64)) -> bool,
    start: (f64, f64),
    opts: LmOptions,
) -> ((f64, f64), f64, usize, bool) {
    let fit = crate::solve::least_squares::levenberg_marquardt(
        &mut |x: &[f64; 2], out: &mut Vec<f64>| {
            let x = (x[0], x[1]);
            if domain(x) {
                residuals(x, out)
            } else {
                None
            }
        },
        &|x| feasible((x[0], x[1])),
        [start.0, start.1],
        &opts,
    );
    as_pair(&fit)
}

/// Mean square error (relative to the arc length) below which a fit counts as near-exact
/// (rms 1e-7): its valley is a hairline whose floor can hold several minima.
pub(super) const NEAR_EXACT: f64 = 1e-14;
/// Iteration limit of a table start's run: one that has not converged by then is crawling
/// along a valley floor (on the sweep and its hold-outs, 20 lost nothing against 60 and
/// took the mean time from 126 to 119 µs; 12 lost cases).
pub(super) const START_ITERATIONS: usize = 20;

/// A table minimum below this mean square (rms 1e-6 of the length) whose Gauss–Newton
/// matrix has a condition number above [`HAIRLINE_CONDITION`] lies in a hairline valley
/// whose floor can hold twin minima: its floor is walked ([`valley::along_valley`]).
pub(super) const HAIRLINE_COST: f64 = 1e-12;
/// See [`HAIRLINE_COST`].
pub(super) const HAIRLINE_CONDITION: f64 = 1e4;

/// A start's run is abandoned once its trusted Gauss–Newton model's minimum is above this
/// many times the best minimum found (or [`NEAR_EXACT`]): with 1.5 the sweep and the three
/// hold-out seeds lose no case the search without this rule finds, and the starts cost
/// about a fifth fewer evaluations.
pub(super) const MODEL_MARGIN: f64 = 1.5;

/// The minima refined from the table's starts ([`table_candidates`]).
#[derive(Default)]
pub(super) struct TableMinima {
    /// Point and cost, lowest first.
    pub(super) minima: Vec<((f64, f64), f64)>,
    /// The lowest one's refinement met its stopping test (false: it stopped still
    /// descending, or there is none).
    pub(super) best_converged: bool,
}

/// The table's starting points for `seg` ([`crate::approx_table`]), each refined by
/// Levenberg–Marquardt (starts within 1e-3 of one already refined, or of its result, are
/// skipped), best first.
pub(super) fn table_candidates(
    prob: &Problem,
    seg: &LacSegment,
    opts: &ApproxOptions,
    tr: &Samples,
    buf: &mut Vec<f64>,
    evals: &mut usize,
) -> TableMinima {
    let alpha = seg.standard.alpha();
    let theta_d = seg.theta_d;
    // The base angle at the high-curvature end (the larger one).
    let Ok((_, phi)) = LacSegment::triangle_angles(seg.control) else {
        return TableMinima::default();
    };
    let half = 0.5 * theta_d;
    let u = match LacSegment::theta_lim(alpha, theta_d) {
        Ok(lim) if lim > half => ((phi - half) / (lim - half)).clamp(0.0, 1.0),
        _ => 0.0,
    };
    let mut raw = Vec::new();
    crate::approx_table::table().candidates(alpha, theta_d, u, &mut raw);
    let mut starts: Vec<(f64, (f64, f64))> = Vec::with_capacity(raw.len());
    for [hi, lo] in raw {
        let x = if seg.reversed { (lo, hi) } else { (hi, lo) };
        if starts
            .iter()
            .all(|s| (s.1 .0 - x.0).abs().max((s.1 .1 - x.1).abs()) > 1e-3)
        {
            starts.push((prob.cost(x.0, x.1, tr, buf), x));
            *evals += 1;
        }
    }
    starts.retain(|s| s.0.is_finite());
    starts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut out: Vec<((f64, f64), f64)> = Vec::new();
    let mut best = f64::INFINITY;
    let mut best_converged = false;
    // Each start runs to 1e-6 relative progress (the finish refines the winner), lightly
    // damped (the starts lie near their valleys' floors), and is abandoned when after 5
    // iterations it is still above 100 times the best minimum so far, unless it is itself a
    // near-exact fit: near-exact valleys are hairline-narrow and curved, Levenberg–Marquardt
    // moves along them slowly but surely, and twin minima lie in them a few thousandths
    // apart (measured on the sweep: 1 of its misses).
    let stop = |best: f64| LmOptions {
        abandon_after: 5,
        abandon_above: (100.0 * best).max(NEAR_EXACT),
        abandon_predicted_above: (MODEL_MARGIN * best).max(NEAR_EXACT),
        rel_progress: 1e-6,
        mu0: 1e-8,
        ..LM_FULL
    };
    for (c0, x) in starts {
        // A start within 0.01 of a minimum already found that is at least as low lies in
        // that minimum's valley: skipped; within 0.003 for a near-exact minimum, whose
        // valley is too narrow to hold the start (3 of the sweep's misses were twin
        // minima 0.005 to 0.03 apart).
        let near = |p: (f64, f64), c: f64| {
            let r = if c < NEAR_EXACT { 3e-3 } else { 1e-2 };
            (p.0 - x.0).abs().max((p.1 - x.1).abs()) <= r
        };
        if out.iter().any(|r| near(r.0, r.1) && r.1 <= c0) {
            continue;
        }
        let iterations = opts.max_iter.min(START_ITERATIONS);
        let (y, c, e, converged) =
            refine_with(prob, x, tr, iterations, &|_, _| true, stop(best), true);
        *evals += e;
        if c < best {
            best = c;
            best_converged = converged;
        }
        out.push((y, c));
    }
    out.sort_by(|a, b| a.1.total_cmp(&b.1));
    TableMinima {
        minima: out,
        best_converged,
    }
}

/// The best of the two lowest curvature-monotone `candidates` after a refinement that
/// refuses steps out of the monotone region (towards the better, non-monotone minima).
pub(super) fn monotone_near(
    prob: &Problem,
    opts: &ApproxOptions,
    tr: &Samples,
    candidates: &[((f64, f64), f64)],
    evals: &mut usize,
) -> Option<((f64, f64), f64)> {
    let feasible = |a: f64, b: f64| prob.is_monotone(a, b);
    let mut best: Option<((f64, f64), f64)> = None;
    for &(x, _) in candidates
        .iter()
        .filter(|c| feasible(c.0 .0, c.0 .1))
        .take(2)
    {
        let lm = LmOptions {
            abandon_after: 8,
            ..LM_FULL
        };
        let (y, c, e, _) = refine_with(prob, x, tr, opts.max_iter, &feasible, lm, true);
        *evals += e;
        if c.is_finite() && best.is_none_or(|b| c < b.1) {
            best = Some((y, c));
        }
    }
    best
}

/// What the search of the whole square works with: the problem, the options, the
/// refinement's and the report's samples.
pub(super) struct Square<'a> {
    pub(super) prob: &'a Problem<'a>,
    pub(super) opts: &'a ApproxOptions,
    /// The refinement's samples.
    pub(super) tr: &'a Samples,
    /// The reported error measure's samples (the compass search on the region's boundary).
    pub(super) report_ts: &'a Samples,
}

/// The cost on the grid's cell centres, row by row (`n` = `opts.grid` per axis), on `tg`.
struct Grid {
    n: usize,
    costs: Vec<f64>,
}

impl Grid {
    /// The centre of cell `i` along an axis.
    fn at(&self, i: usize) -> f64 {
        (i as f64 + 0.5) / self.n as f64
    }
}

/// The search without the table (or when the table's best minimum is not curvature
/// monotone): the grid, valley floors, Levenberg–Marquardt, the scan across the best
/// valley, and the constrained search of the monotone region (module documentation).
/// `candidates`: minima already found (the table's). `evals` counts the cost evaluations.
pub(super) fn grid_search(
    sq: &Square,
    buf: &mut Vec<f64>,
    evals: &mut usize,
    mut candidates: Vec<((f64, f64), f64)>,
) -> Option<((f64, f64), f64)> {
    let tg = Samples::gauss(sq.opts.grid_samples);
    let grid = sq.grid(&tg, buf, evals);
    let points = sq.floor_points(&grid, &tg, evals);
    let minima = sq.distinct_minima(&points, grid.n);
    sq.refine_minima(&minima, &mut candidates, buf, evals);
    let best = candidates
        .iter()
        .find(|(x, c)| c.is_finite() && sq.prob.is_monotone(x.0, x.1))
        .copied();
    let unconstrained_best = candidates.first().map(|c| c.1).unwrap_or(f64::INFINITY);
    if best.is_none_or(|b| b.1 > unconstrained_best * (1.0 + 1e-9)) {
        // The best minimum is not curvature-monotone: search the monotone region.
        let starts = sq.monotone_starts(&points, grid.n, &tg, buf, evals);
        return sq.search_monotone(starts, grid.n, best, evals);
    }
    best
}

impl Square<'_> {
    /// The cost at every cell centre of the grid.
    fn grid(&self, tg: &Samples, buf: &mut Vec<f64>, evals: &mut usize) -> Grid {
        let n = self.opts.grid;
        let mut grid = Grid {
            n,
            costs: vec![f64::INFINITY; n * n],
        };
        for i in 0..n {
            for j in 0..n {
                grid.costs[i * n + j] = self.prob.cost(grid.at(i), grid.at(j), tg, buf);
                *evals += 1;
            }
        }
        grid
    }

    /// Points on the valley floors, lowest first: the minima of the cost along every grid
    /// row and column, and the dip between grid lines along the best valley of each family.
    ///
    /// Valleys narrower than a grid cell (near-exact fits form a curve of them, S3's error
    /// surface is such a valley) are found by minimising along every grid row and column:
    /// the profile minima lie on the valley floors, at the grid's spacing along them.
    fn floor_points(&self, grid: &Grid, tg: &Samples, evals: &mut usize) -> Vec<(f64, (f64, f64))> {
        let n = grid.n;
        let mut points: Vec<(f64, (f64, f64))> = Vec::new();
        let mut profile: [Vec<(f64, f64, f64)>; 2] = [Vec::new(), Vec::new()];
        for (axis, fam) in profile.iter_mut().enumerate() {
            for i in 0..n {
                let cell = |j: usize| {
                    if axis == 0 {
                        grid.costs[i * n + j]
                    } else {
                        grid.costs[j * n + i]
                    }
                };
                let Some(j) = (0..n)
                    .filter(|j| cell(*j).is_finite())
                    .min_by(|a, b| cell(*a).total_cmp(&cell(*b)))
                else {
                    continue;
                };
                let (x, c, e) =
                    line_min(self.prob, axis, grid.at(i), grid.at(j), 1.0 / n as f64, tg);
                *evals += e;
                let pt = if axis == 0 {
                    (grid.at(i), x)
                } else {
                    (x, grid.at(i))
                };
                points.push((c, pt));
                fam.push((c, grid.at(i), x));
            }
        }
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (axis, fam) in profile.iter().enumerate() {
            if let Some(dip) = self.valley_dip(axis, fam, n, tg, evals) {
                points.insert(0, dip);
            }
        }
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        points
    }

    /// Along the valley through the best profile point of a family (`fam`: cost, grid line,
    /// floor), the profile g(s) = min over the other coordinate is smooth: golden-section
    /// search on it finds the dip between two grid lines (a near-exact fit's valley floor
    /// is almost flat, where Levenberg–Marquardt would crawl).
    fn valley_dip(
        &self,
        axis: usize,
        fam: &[(f64, f64, f64)],
        n: usize,
        tg: &Samples,
        evals: &mut usize,
    ) -> Option<(f64, (f64, f64))> {
        let &(_, s0, x0) = fam.iter().min_by(|a, b| a.0.total_cmp(&b.0))?;
        let width = 1.0 / n as f64;
        // The profile's value at s, each line search started from the floor of the best
        // profile point so far.
        let mut floor = (f64::INFINITY, x0);
        let mut g = |sv: f64| {
            let (x, c, e) = line_min(self.prob, axis, sv, floor.1, width, tg);
            *evals += e;
            if c < floor.0 {
                floor = (c, x);
            }
            c
        };
        let lo = (s0 - width).max(1e-6);
        let hi = (s0 + width).min(1.0 - 1e-6);
        let (sv, c) = crate::solve::line_search::golden_section(&mut g, lo, hi, 8);
        let x = floor.1;
        let pt = if axis == 0 { (sv, x) } else { (x, sv) };
        c.is_finite().then_some((c, pt))
    }

    /// The lowest floor points at least 1.5 cells apart, at most `opts.starts` of them.
    fn distinct_minima(&self, points: &[(f64, (f64, f64))], n: usize) -> Vec<(f64, f64)> {
        let mut minima: Vec<(f64, f64)> = Vec::new();
        for &(_, pt) in points {
            if minima.len() >= self.opts.starts.max(1) {
                break;
            }
            let far = minima
                .iter()
                .all(|m| (m.0 - pt.0).abs().max((m.1 - pt.1).abs()) > 1.5 / n as f64);
            if far {
                minima.push(pt);
            }
        }
        minima
    }

    /// Every minimum refined by Levenberg–Marquardt, then the twins beside the best valley,
    /// all added to `candidates` (sorted, lowest first).
    fn refine_minima(
        &self,
        minima: &[(f64, f64)],
        candidates: &mut Vec<((f64, f64), f64)>,
        buf: &mut Vec<f64>,
        evals: &mut usize,
    ) {
        let mut best_cost = f64::INFINITY;
        for &start in minima {
            // The whole-square search keeps forward differences throughout: it is the
            // fallback (1 % of shapes), tuned with them, and with the exact Jacobian its
            // minima lead the constrained stage below into a crawl (measured: 37 ms instead
            // of 4 on one shape).
            let (x, c, e) = refine(
                self.prob,
                start,
                self.tr,
                self.opts.max_iter,
                &|_, _| true,
                100.0 * best_cost,
                false,
            );
            *evals += e;
            best_cost = best_cost.min(c);
            candidates.push((x, c));
        }
        candidates.sort_by(|a, b| a.1.total_cmp(&b.1));
        // A near-exact fit's valley can have a narrow twin running beside it, a few
        // hundredths away, too narrow for the grid: scan across the best valley (along the
        // direction in which the error rises fastest) and refine from every other dip of
        // that profile.
        let Some(&(x, c)) = candidates.first() else {
            return;
        };
        if !c.is_finite() {
            return;
        }
        let scan = Samples::gauss(6);
        let twins = valley::across_valley(self.prob, x, &scan, buf, evals);
        for start in twins {
            let (y, cy, e) = refine(
                self.prob,
                start,
                self.tr,
                self.opts.max_iter,
                &|_, _| true,
                100.0 * c,
                false,
            );
            *evals += e;
            candidates.push((y, cy));
        }
        candidates.sort_by(|a, b| a.1.total_cmp(&b.1));
    }

    /// Starts inside the monotone region, at most `opts.starts`: the floor points first,
    /// then ever finer grids (up to 8 times the grid's), each in order of increasing error.
    /// The region can be smaller than a grid cell (near the edge of the segment's
    /// existence region).
    fn monotone_starts(
        &self,
        points: &[(f64, (f64, f64))],
        n: usize,
        tg: &Samples,
        buf: &mut Vec<f64>,
        evals: &mut usize,
    ) -> Vec<(f64, f64)> {
        let mut starts: Vec<(f64, f64)> = Vec::new();
        let want = self.opts.starts.max(1);
        for &(_, pt) in points {
            if starts.len() < want && self.prob.is_monotone(pt.0, pt.1) {
                starts.push(pt);
            }
        }
        let mut m = n;
        while starts.len() < want && m <= 8 * n {
            let atm = |i: usize| (i as f64 + 0.5) / m as f64;
            let mut cells: Vec<(f64, (f64, f64))> = Vec::with_capacity(m * m);
            for i in 0..m {
                for j in 0..m {
                    let c = self.prob.cost(atm(i), atm(j), tg, buf);
                    if c.is_finite() {
                        cells.push((c, (atm(i), atm(j))));
                    }
                }
            }
            *evals += m * m;
            cells.sort_by(|a, b| a.0.total_cmp(&b.0));
            for (_, pt) in cells {
                if starts.len() >= want {
                    break;
                }
                let distinct = starts
                    .iter()
                    .all(|s| (s.0 - pt.0).abs().max((s.1 - pt.1).abs()) > 0.5 / m as f64);
                if distinct && self.prob.is_monotone(pt.0, pt.1) {
                    starts.push(pt);
                }
            }
            m *= 2;
        }
        starts
    }

    /// From each start, Levenberg–Marquardt refusing steps out of the monotone region, then
    /// a compass search along its boundary; the best of these and `best`.
    fn search_monotone(
        &self,
        starts: Vec<(f64, f64)>,
        n: usize,
        mut best: Option<((f64, f64), f64)>,
        evals: &mut usize,
    ) -> Option<((f64, f64), f64)> {
        let feasible = |a: f64, b: f64| self.prob.is_monotone(a, b);
        for s in starts {
            let lm = LmOptions {
                abandon_after: 8,
                ..LM_FULL
            };
            let (x, _, e, _) = refine_with(
                self.prob,
                s,
                self.tr,
                self.opts.max_iter,
                &feasible,
                lm,
                false,
            );
            *evals += e;
            // The constrained optimum usually lies on the region's boundary, where refused
            // steps stall Levenberg–Marquardt: finish with a compass search. There the
            // gradient does not vanish, so the optimum moves to first order with the error
            // measure: use the reported one (uniform t, both ends).
            let (x, c, e) = compass_search(self.prob, x, self.report_ts, &feasible, 0.5 / n as f64);
            *evals += e;
            if best.is_none_or(|b| c < b.1) {
                best = Some((x, c));
            }
        }
        best
    }
}

/// Step 3 of the module documentation of `approx`: the floor of the best table minimum's
/// valley is walked ([`valley::along_valley`]) when that valley is a hairline (cost below
/// [`HAIRLINE_COST`], condition above [`HAIRLINE_CONDITION`]) or its refinement stopped
/// still descending; a lower floor point is refined and, if it ends lower, becomes the best
/// of `minima` (lowest first).
pub(super) fn walk_best_valley(
    prob: &Problem,
    minima: &mut Vec<((f64, f64), f64)>,
    best_converged: bool,
    ts: &Samples,
    evals: &mut usize,
) {
    let Some(&(x, c)) = minima.first() else {
        return;
    };
    if !c.is_finite() || (best_converged && c >= HAIRLINE_COST) {
        return;
    }
    // The Gauss–Newton matrix decides a hairline and gives the walk its first direction.
    let Some(gn) = valley::gauss_newton(prob, x, ts, evals) else {
        return;
    };
    if best_converged && valley::condition(gn) <= HAIRLINE_CONDITION {
        return;
    }
    let Some((y, _)) = valley::along_valley(prob, x, c, gn, ts, evals) else {
        return;
    };
    let lm = LmOptions {
        abandon_after: 8,
        ..LM_FULL
    };
    let (z, cz, e, _) = refine_with(prob, y, ts, START_ITERATIONS, &|_, _| true, lm, true);
    *evals += e;
    if cz < c {
        minima.insert(0, (z, cz));
    }
}
