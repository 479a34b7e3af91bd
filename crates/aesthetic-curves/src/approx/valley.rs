//! Searches along and across one valley of the error surface over (f0, f1).
//!
//! The error surfaces of near-exact fits are hairline valleys (S3): a local optimiser
//! reaches the floor at once and then either stops at the first dip of a floor that holds
//! several (twin minima a few hundredths apart, separated by low barriers) or crawls along a
//! floor that falls very slowly (Levenberg–Marquardt's straight steps leave a curved floor
//! within a short distance). [`along_valley`] follows the floor itself, predictor and
//! corrector: a step along the floor's secant, then a one-dimensional minimisation across
//! it, with a step that grows while the prediction holds. [`across_valley`] samples the
//! profile across the valley for a twin valley running beside it.

use super::problem::{Problem, Samples};
use crate::solve::least_squares::{levenberg_marquardt, LmOptions};

/// The Gauss–Newton matrix `JᵀJ` (entries a, b, c of `[[a, b], [b, c]]`) at `x`, by forward
/// differences; `None` where a residual vector cannot be evaluated.
pub(super) fn gauss_newton(
    prob: &Problem,
    x: (f64, f64),
    ts: &Samples,
    evals: &mut usize,
) -> Option<(f64, f64, f64)> {
    let mut r0 = Vec::new();
    prob.residuals(x.0, x.1, ts, &mut r0)?;
    let h = 1e-7;
    let mut ja = Vec::new();
    let mut jb = Vec::new();
    let sa = if x.0 + h < 1.0 { h } else { -h };
    let sb = if x.1 + h < 1.0 { h } else { -h };
    *evals += 3;
    prob.residuals(x.0 + sa, x.1, ts, &mut ja)?;
    prob.residuals(x.0, x.1 + sb, ts, &mut jb)?;
    let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
    for k in 0..r0.len() {
        let (u, v) = ((ja[k] - r0[k]) / sa, (jb[k] - r0[k]) / sb);
        a += u * u;
        b += u * v;
        c += v * v;
    }
    Some((a, b, c))
}

/// The condition number of a Gauss–Newton matrix ([`gauss_newton`]; infinite where it is
/// singular).
pub(super) fn condition((a, b, c): (f64, f64, f64)) -> f64 {
    let (trace, det) = (a + c, a * c - b * b);
    let large = 0.5 * trace + (0.25 * trace * trace - det).max(0.0).sqrt();
    let small = det / large;
    if small > 0.0 {
        large / small
    } else {
        f64::INFINITY
    }
}

/// The unit principal eigenvector of `[[a, b], [b, c]]` (the direction in which the error
/// rises fastest; its perpendicular runs along the valley).
fn principal(m: (f64, f64, f64)) -> (f64, f64) {
    let theta = 0.5 * (2.0 * m.1).atan2(m.0 - m.2);
    (theta.cos(), theta.sin())
}

/// Minimise the cost on the line `origin + s dir` over `|s| <= width` (and inside the open
/// square) from s = 0: Levenberg–Marquardt in one variable, at most `iterations`
/// iterations. Returns s, the cost and the evaluations spent.
pub(super) fn line_min_along(
    prob: &Problem,
    origin: (f64, f64),
    dir: (f64, f64),
    width: f64,
    ts: &Samples,
    iterations: usize,
    rel_progress: f64,
) -> (f64, f64, usize) {
    let at = |s: f64| (origin.0 + s * dir.0, origin.1 + s * dir.1);
    let inside = |s: f64| {
        let p = at(s);
        s.abs() <= width && (1e-9..=1.0 - 1e-9).contains(&p.0) && (1e-9..=1.0 - 1e-9).contains(&p.1)
    };
    let fit = levenberg_marquardt::<1>(
        &mut |x: &[f64; 1], out: &mut Vec<f64>| {
            let p = at(x[0]);
            prob.residuals(p.0, p.1, ts, out)
        },
        &|x| inside(x[0]),
        [0.0],
        &LmOptions {
            max_iterations: iterations,
            mu0: 1e-3,
            rel_progress,
            min_step: 1e-9,
            max_damping_tries: 8,
            ..LmOptions::default()
        },
    );
    (fit.x[0], fit.cost, fit.evaluations)
}

/// Longest step along a valley floor.
const MAX_STEP: f64 = 0.02;
/// First step along a valley floor, and the step at which a dip counts as resolved.
const FIRST_STEP: f64 = 2e-3;
/// Shortest step: below it the floor is lost.
const MIN_STEP: f64 = 1e-4;
/// Steps per direction.
const MAX_STEPS: usize = 60;
/// The walk ends where the floor rises above this many times the lowest cost seen: past
/// the barriers between twin minima (measured up to 7 times their cost) and short of the
/// far, worse regions of the floor.
const RISE: f64 = 30.0;

/// A point of the walk: position, unit direction of travel, cost.
#[derive(Clone, Copy)]
struct Stand {
    at: (f64, f64),
    dir: (f64, f64),
    cost: f64,
}

/// Walk the floor of the valley through the minimum `x` (cost `c`, Gauss–Newton matrix `gn`
/// there: [`gauss_newton`]) both ways, and return
/// the lowest floor point found if it is lower than `c` (a start for a local refinement
/// into another minimum of the same valley). A step that rises after a descent may have
/// stepped over a dip: the walk goes back two points and resumes with a quarter of the
/// step, until the dip is resolved at [`FIRST_STEP`]. Module documentation: the method.
pub(super) fn along_valley(
    prob: &Problem,
    x: (f64, f64),
    c: f64,
    gn: (f64, f64, f64),
    ts: &Samples,
    evals: &mut usize,
) -> Option<((f64, f64), f64)> {
    let across = principal(gn);
    let mut best = (x, c);
    for sign in [1.0, -1.0] {
        let start = Stand {
            at: x,
            dir: (-across.1 * sign, across.0 * sign),
            cost: c,
        };
        // The last three accepted points, newest last.
        let mut trail: Vec<Stand> = vec![start];
        let mut h = FIRST_STEP;
        let mut cap = MAX_STEP;
        let mut low = c;
        for _ in 0..MAX_STEPS {
            let here = *trail.last().expect("the trail starts with one point");
            let t = here.dir;
            let y = (here.at.0 + h * t.0, here.at.1 + h * t.1);
            let n = (-t.1, t.0);
            let (s, cy, e) = line_min_along(prob, y, n, h.max(0.01), ts, 6, 1e-9);
            *evals += e;
            if !cy.is_finite() {
                h *= 0.5;
                if h < MIN_STEP {
                    break;
                }
                continue;
            }
            let z = (y.0 + s * n.0, y.1 + s * n.1);
            let d = (z.0 - here.at.0).hypot(z.1 - here.at.1);
            if d == 0.0 {
                break;
            }
            let descended = trail.len() >= 2 && here.cost < trail[trail.len() - 2].cost;
            if cy > here.cost && descended && h > FIRST_STEP {
                // Down, then up: a dip lies between the point before `here` and z.
                trail.pop();
                h = (0.25 * h).max(0.5 * FIRST_STEP);
                cap = h;
                continue;
            }
            if cy > here.cost && descended {
                // A dip resolved at the fine step: climb out at the full pace.
                cap = MAX_STEP;
            }
            trail.push(Stand {
                at: z,
                dir: ((z.0 - here.at.0) / d, (z.1 - here.at.1) / d),
                cost: cy,
            });
            if trail.len() > 3 {
                trail.remove(0);
            }
            low = low.min(cy);
            if cy < best.1 {
                best = (z, cy);
            }
            if cy > RISE * low {
                break;
            }
            // The corrector moved the prediction by more than half a step: the floor bends
            // more than the step resolves.
            h = if s.abs() > 0.5 * h {
                (0.5 * h).max(MIN_STEP)
            } else {
                (1.5 * h).min(cap)
            };
        }
    }
    (best.1 < c).then_some(best)
}

/// Dips of the error across a valley through `x`: the direction in which the error rises
/// fastest (the Gauss–Newton matrix's principal eigenvector) is sampled every 5e-4 over
/// ±0.06, and the local minima of that profile away from `x` are returned (at most four,
/// lowest first).
pub(super) fn across_valley(
    prob: &Problem,
    x: (f64, f64),
    ts: &Samples,
    buf: &mut Vec<f64>,
    evals: &mut usize,
) -> Vec<(f64, f64)> {
    let Some(gn) = gauss_newton(prob, x, ts, evals) else {
        return Vec::new();
    };
    let dir = principal(gn);
    let m = 120;
    let step = 5e-4;
    let profile: Vec<(f64, (f64, f64))> = (-m..=m)
        .map(|i| {
            let s = i as f64 * step;
            let p = (x.0 + s * dir.0, x.1 + s * dir.1);
            (prob.cost(p.0, p.1, ts, buf), p)
        })
        .collect();
    *evals += profile.len();
    let mut dips: Vec<(f64, (f64, f64))> = (1..profile.len() - 1)
        .filter(|&i| {
            let (l, v, r) = (profile[i - 1].0, profile[i].0, profile[i + 1].0);
            v.is_finite() && v < l && v <= r && (i as i64 - m as i64).abs() > 4
        })
        .map(|i| profile[i])
        .collect();
    dips.sort_by(|p, q| p.0.total_cmp(&q.0));
    dips.truncate(4);
    dips.into_iter().map(|d| d.1).collect()
}

#[cfg(test)]
mod tests {
    use super::super::problem::{Problem, Samples};
    use super::super::search::refine;
    use super::*;
    use crate::lac::LacSegment;
    use kurbo::Point;

    /// The segment of shape (α, θ_d, base angle φ at the start) on the unit triangle.
    fn segment(alpha: f64, td: f64, phi: f64) -> LacSegment {
        let d = phi.sin() / (td - phi).sin();
        let tri = [
            Point::ZERO,
            Point::new(1.0, 0.0),
            Point::new(1.0 + d * td.cos(), d * td.sin()),
        ];
        LacSegment::new(alpha, tri).unwrap()
    }

    /// Walk from `from` (refined first), refine the walk's best point, and return its rms.
    fn walk_and_refine(seg: &LacSegment, from: (f64, f64)) -> f64 {
        let prob = Problem::new(seg, 256).unwrap();
        let ts = Samples::gauss(10);
        let no = |_: f64, _: f64| true;
        let (x, c, _) = refine(&prob, from, &ts, 60, &no, f64::INFINITY, true);
        let mut evals = 0;
        let gn = gauss_newton(&prob, x, &ts, &mut evals).unwrap();
        let (y, cy) = along_valley(&prob, x, c, gn, &ts, &mut evals).expect("a lower floor point");
        assert!(cy < c && evals < 2000, "{cy:e} {c:e} {evals}");
        let (z, _, _) = refine(&prob, y, &ts, 60, &no, f64::INFINITY, true);
        let curve = super::super::construct(seg, z.0, z.1).unwrap();
        super::super::approximation_error(seg, &curve, 201)
            .unwrap()
            .rms
    }

    #[test]
    fn the_walk_crosses_a_barrier_to_a_twin_minimum() {
        // Two minima 0.04 apart on one hairline floor (a hold-out case of
        // tests/approx_sweep.rs, seed 5): rms 7.95e-7 at (0.480, 0.782), and the exhaustive
        // search's optimum 6.4903e-7 at (0.5207, 0.7434) behind a barrier of 2.1e-6.
        let seg = segment(4.2647562654737055, 0.9802422818642444, 0.5164440164445387);
        let rms = walk_and_refine(&seg, (0.480, 0.782));
        assert!(rms < 1.01 * 6.4903e-7, "{rms:e}");
    }

    #[test]
    fn the_walk_follows_a_slowly_falling_floor() {
        // A floor falling from rms 2.0e-4 at (0.547, 0.771) to the exhaustive optimum
        // 1.1656e-4 at (0.955, 0.172), 0.7 away along a curved valley (seed 3), where
        // Levenberg–Marquardt alone crawls.
        let seg = segment(0.6614311511971014, 0.23259112843136198, 0.21922045004695223);
        let rms = walk_and_refine(&seg, (0.547, 0.771));
        assert!(rms < 1.01 * 1.1656e-4, "{rms:e}");
    }

    #[test]
    fn condition_of_a_round_bowl_and_of_a_hairline() {
        let ts = Samples::gauss(10);
        let no = |_: f64, _: f64| true;
        let at_minimum = |seg: &LacSegment, from: (f64, f64)| {
            let prob = Problem::new(seg, 256).unwrap();
            let (x, c, _) = refine(&prob, from, &ts, 60, &no, f64::INFINITY, true);
            let mut evals = 0;
            (
                condition(gauss_newton(&prob, x, &ts, &mut evals).unwrap()),
                c,
            )
        };
        let (k, c) = at_minimum(
            &segment(4.2647562654737055, 0.9802422818642444, 0.5164440164445387),
            (0.480, 0.782),
        );
        assert!(k > 1e4 && c < 1e-12, "{k:e} {c:e}");
        let (k, c) = at_minimum(&segment(-1.0, 1.2, 0.7), (0.5, 0.5));
        assert!(k < 1e4, "{k:e} {c:e}");
        let round = segment(-1.0, 1.2, 0.7);
        let prob = Problem::new(&round, 256).unwrap();
        let mut evals = 0;
        // No matrix outside the square; a singular one has an infinite condition.
        assert!(gauss_newton(&prob, (2.0, 0.5), &ts, &mut evals).is_none());
        assert_eq!(condition((1.0, 1.0, 1.0)), f64::INFINITY);
    }
}
