//! The rational-cubic fit's objective: a LAC segment's triangle, end curvatures and a table
//! of the LAC against turning angle (quintic Hermite, module documentation of `approx`), the
//! §4 cubic of (f0, f1), its residuals against the LAC at a set of parameter samples, with a
//! closed-form Jacobian, and the error summaries the fit reports.

use super::ApproximationError;
use crate::bezier::RationalBezier;
use crate::error::Result;
use crate::lac::LacSegment;
use kurbo::{Point, Vec2};

/// The homogeneous control points (w x, w y, w) of a rational cubic.
pub(super) fn homogeneous(b: &[Point], w: &[f64]) -> [(f64, f64, f64); 4] {
    std::array::from_fn(|i| (b[i].x * w[i], b[i].y * w[i], w[i]))
}

/// Quintic Hermite interpolation between two table nodes (values, first and second
/// derivatives in τ at both), at the fraction `x` of the cell of width `h`: error O(h⁶).
#[inline]
pub(super) fn quintic(a: &Node, b: &Node, x: f64, h: f64) -> Vec2 {
    let x2 = x * x;
    let x3 = x2 * x;
    let x4 = x3 * x;
    let x5 = x4 * x;
    let h0 = 1.0 - 10.0 * x3 + 15.0 * x4 - 6.0 * x5;
    let h1 = x - 6.0 * x3 + 8.0 * x4 - 3.0 * x5;
    let h2 = 0.5 * (x2 - 3.0 * x3 + 3.0 * x4 - x5);
    let h3 = 0.5 * (x3 - 2.0 * x4 + x5);
    let h4 = -4.0 * x3 + 7.0 * x4 - 3.0 * x5;
    let h5 = 10.0 * x3 - 15.0 * x4 + 6.0 * x5;
    let hh = h * h;
    a.p.to_vec2() * h0
        + a.d * (h1 * h)
        + a.dd * (h2 * hh)
        + b.dd * (h3 * hh)
        + b.d * (h4 * h)
        + b.p.to_vec2() * h5
}

/// A rational cubic's point and a positive multiple of its tangent at `t`, from the
/// homogeneous control points `h` = (w x, w y, w): x' ∝ H'_xy w - H_xy w' (the factor 3/w²
/// does not change the direction).
#[inline]
pub(super) fn cubic_point_tangent(h: &[(f64, f64, f64); 4], t: f64) -> (Point, Vec2) {
    let u = 1.0 - t;
    let (c0, c1, c2, c3) = (u * u * u, 3.0 * t * u * u, 3.0 * t * t * u, t * t * t);
    let hx = c0 * h[0].0 + c1 * h[1].0 + c2 * h[2].0 + c3 * h[3].0;
    let hy = c0 * h[0].1 + c1 * h[1].1 + c2 * h[2].1 + c3 * h[3].1;
    let hw = c0 * h[0].2 + c1 * h[1].2 + c2 * h[2].2 + c3 * h[3].2;
    let (e0, e1, e2) = (u * u, 2.0 * t * u, t * t);
    let dx = e0 * (h[1].0 - h[0].0) + e1 * (h[2].0 - h[1].0) + e2 * (h[3].0 - h[2].0);
    let dy = e0 * (h[1].1 - h[0].1) + e1 * (h[2].1 - h[1].1) + e2 * (h[3].1 - h[2].1);
    let dw = e0 * (h[1].2 - h[0].2) + e1 * (h[2].2 - h[1].2) + e2 * (h[3].2 - h[2].2);
    (
        Point::new(hx / hw, hy / hw),
        Vec2::new(dx * hw - hx * dw, dy * hw - hy * dw),
    )
}

/// The turning angle of direction `d` from `d0`, in the segment's turning sense.
pub(super) fn turning(d0: Vec2, d: Vec2, sign: f64) -> f64 {
    (sign * d0.cross(d)).atan2(d0.dot(d))
}

pub(super) fn turn_sign(seg: &LacSegment) -> f64 {
    let c = seg.control;
    (c[1] - c[0]).cross(c[2] - c[1]).signum()
}

/// The optimisation problem of one segment: its triangle, end curvatures and a table of
/// the LAC against turning angle (or, with `exact`, the segment itself).
pub(super) struct Problem<'a> {
    pub(super) seg: &'a LacSegment,
    pub(super) exact: bool,
    pub(super) p: [Point; 3],
    pub(super) k0: f64,
    pub(super) k1: f64,
    pub(super) w1: f64,
    pub(super) d0: Vec2,
    pub(super) sign: f64,
    pub(super) len: f64,
    /// The LAC at the table nodes (uniform in the variable of [`TableVar`]).
    pub(super) table: Vec<Node>,
    /// Per sample set (by its size): each sample's table cell at the last evaluation, the
    /// hint of the next (between iterations a sample's angle moves little).
    pub(super) cells: std::cell::RefCell<Vec<(usize, Vec<usize>)>>,
}

impl Problem<'_> {
    /// Run `f` with the cell hints of a sample set of `n` samples.
    pub(super) fn with_cells<T>(&self, n: usize, f: impl FnOnce(&mut [usize]) -> T) -> T {
        let mut all = self.cells.borrow_mut();
        let i = match all.iter().position(|c| c.0 == n) {
            Some(i) => i,
            None => {
                all.push((n, vec![usize::MAX; n]));
                all.len() - 1
            }
        };
        f(&mut all[i].1)
    }
}

/// One node of the LAC table: turning angle, point, dP/dτ, d²P/dτ² and the unit tangent.
#[derive(Clone, Copy)]
pub(super) struct Node {
    pub(super) tau: f64,
    pub(super) p: Point,
    pub(super) d: Vec2,
    pub(super) dd: Vec2,
    pub(super) u: Vec2,
}

/// The variable the LAC table is uniform in. Near a singular end of the domain ρ varies
/// like a power of U = 1 + cθ, which no uniform τ grid interpolates well; in x = ln U the
/// curve is smooth (the w of [`crate::lac`]), so the table is uniform in x whenever c ≠ 0.
#[derive(Clone, Copy)]
pub(super) enum TableVar {
    /// x = τ (circle, logarithmic spiral).
    Tau,
    /// x = ln(1 + c θ(τ)), θ(τ) = θ_start + dir τ.
    LogU { c: f64, theta_start: f64, dir: f64 },
}

impl TableVar {
    pub(super) fn x(&self, tau: f64) -> f64 {
        match *self {
            TableVar::Tau => tau,
            TableVar::LogU {
                c,
                theta_start,
                dir,
            } => (c * (theta_start + dir * tau)).ln_1p(),
        }
    }
    pub(super) fn tau(&self, x: f64) -> f64 {
        match *self {
            TableVar::Tau => x,
            TableVar::LogU {
                c,
                theta_start,
                dir,
            } => (x.exp_m1() / c - theta_start) * dir,
        }
    }
}

impl<'a> Problem<'a> {
    pub(super) fn new(seg: &'a LacSegment, table_intervals: usize) -> Result<Problem<'a>> {
        let (k0, k1) = seg.end_curvatures()?;
        let theta_d = seg.theta_d;
        let m = table_intervals;
        let c = (seg.standard.alpha() - 1.0) * seg.standard.lambda();
        let var = if c == 0.0 || seg.standard.alpha() == 1.0 {
            TableVar::Tau
        } else if seg.reversed {
            TableVar::LogU {
                c,
                theta_start: seg.interval.1,
                dir: -1.0,
            }
        } else {
            TableVar::LogU {
                c,
                theta_start: seg.interval.0,
                dir: 1.0,
            }
        };
        let table = if m > 0 {
            let (x0, x1) = (var.x(0.0), var.x(theta_d));
            let mut taus: Vec<f64> = (0..=m)
                .map(|i| var.tau(x0 + (x1 - x0) * i as f64 / m as f64))
                .collect();
            taus[0] = 0.0;
            taus[m] = theta_d;
            let at = seg.eval_turning(&taus)?;
            // d²P/dτ² = ρ' T + ρ dT/dτ, with dT/dτ = ±N (the tangent turns by dτ) and, from
            // ρ_std = U^(1/(α-1)) (e^{Λθ} for α = 1) and θ = θ_start + dir τ,
            // ρ'/ρ = dir Λ / U: the same similarity scales ρ and ρ'.
            let lambda = seg.standard.lambda();
            let (theta_start, dir) = if seg.reversed {
                (seg.interval.1, -1.0)
            } else {
                (seg.interval.0, 1.0)
            };
            let sign = turn_sign(seg);
            taus.iter()
                .zip(at.points)
                .zip(at.tangents.into_iter().zip(at.radii))
                .map(|((tau, p), (u, rho))| {
                    let d = u * rho;
                    let big_u = 1.0 + c * (theta_start + dir * tau);
                    let drho = rho * dir * lambda / big_u;
                    Node {
                        tau: *tau,
                        p,
                        d,
                        dd: u * drho + Vec2::new(-u.y, u.x) * (sign * rho),
                        u,
                    }
                })
                .collect()
        } else {
            Vec::new()
        };
        Ok(Problem {
            seg,
            exact: false,
            p: seg.control,
            k0,
            k1,
            w1: (2.0 * (0.5 * theta_d).cos() + 1.0) / 3.0,
            d0: seg.control[1] - seg.control[0],
            sign: turn_sign(seg),
            len: seg.arc_length()?,
            table,
            cells: Default::default(),
        })
    }

    /// Control points and weights for (f0, f1); None outside (0, 1)² or where a weight is
    /// not positive and finite.
    pub(super) fn cubic(&self, f0: f64, f1: f64) -> Option<([Point; 4], [f64; 4])> {
        if !(f0 > 0.0 && f0 < 1.0 && f1 > 0.0 && f1 < 1.0) {
            return None;
        }
        let [p0, p1, p2] = self.p;
        let b = [p0, p0 + (p1 - p0) * f0, p2 + (p1 - p2) * f1, p2];
        let (v0, v1, v2) = (b[1] - b[0], b[2] - b[1], b[3] - b[2]);
        let w1 = self.w1;
        // κ0 = (2/3) (w0 w2 / w1²) det(v0, v1) / |v0|³ with w1 = w2.
        let w0 = 1.5 * self.k0 * w1 * v0.hypot().powi(3) / v0.cross(v1);
        let w3 = 1.5 * self.k1 * w1 * v2.hypot().powi(3) / v1.cross(v2);
        if !(w0 > 0.0 && w3 > 0.0 && w0.is_finite() && w3.is_finite()) {
            return None;
        }
        Some((b, [w0, w1, w1, w3]))
    }

    /// The LAC point whose tangent has the direction of `v`, from the table: the node
    /// interval is found by galloping from the hint `k` (the same sample's cell in the
    /// previous evaluation, or the previous sample's; `usize::MAX`: by bisection),
    /// the angle past the node from a short arctangent series, the point by cubic Hermite
    /// interpolation in τ. No atan2 and no logarithm per sample.
    pub(super) fn lac_at_dir(&self, v: Vec2, k: &mut usize) -> Point {
        let (a, b, x, h) = self.lac_cell(v, k);
        quintic(&a, &b, x, h).to_point()
    }

    /// [`Self::lac_at_dir`] and the interpolant's derivative in τ there.
    pub(super) fn lac_at_dir_d(&self, v: Vec2, k: &mut usize) -> (Point, Vec2) {
        let (a, b, x, h) = self.lac_cell(v, k);
        let q = quintic(&a, &b, x, h);
        // d/dx of the six basis functions of `quintic`, then d/dτ = (d/dx) / h.
        let (x2, x3, x4) = (x * x, x * x * x, x * x * x * x);
        let g05 = 30.0 * x2 - 60.0 * x3 + 30.0 * x4;
        let dq = (b.p - a.p) * (g05 / h)
            + a.d * (1.0 - 18.0 * x2 + 32.0 * x3 - 15.0 * x4)
            + a.dd * (0.5 * (2.0 * x - 9.0 * x2 + 12.0 * x3 - 5.0 * x4) * h)
            + b.dd * (0.5 * (3.0 * x2 - 8.0 * x3 + 5.0 * x4) * h)
            + b.d * (-12.0 * x2 + 28.0 * x3 - 15.0 * x4);
        (q.to_point(), dq)
    }

    /// The table cell of the LAC point whose tangent has the direction of `v`: its nodes,
    /// the position x in it (0 to 1, a little beyond at inner cells) and its width in τ.
    pub(super) fn lac_cell(&self, v: Vec2, k: &mut usize) -> (Node, Node, f64, f64) {
        let t = &self.table;
        let m = t.len() - 1;
        let s = self.sign;
        let before = |j: usize| s * t[j].u.cross(v) > 0.0;
        // The last node "before v" in (lo, hi), given that lo is one (or the start) and hi is
        // not (or the end): bisection.
        let bisect = |mut lo: usize, mut hi: usize| {
            while hi - lo > 1 {
                let mid = (lo + hi) / 2;
                if before(mid) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            lo
        };
        if *k == usize::MAX {
            // No hint: bisection over the node directions (they turn by less than π, so
            // "before v" holds for a prefix of them), where a walk would cross the table.
            *k = bisect(0, m);
        } else {
            *k = (*k).min(m - 1);
            if *k > 0 && !before(*k) {
                // Backward by galloping from the hint, then bisection.
                let (mut hi, mut step) = (*k, 1);
                let lo = loop {
                    if step > hi {
                        break 0;
                    }
                    let next = hi - step;
                    if before(next) {
                        break next;
                    }
                    hi = next;
                    step *= 2;
                };
                *k = bisect(lo, hi);
            }
        }
        // Forward by galloping (the samples are some nodes apart), then bisection.
        if *k + 1 < m && before(*k + 1) {
            let (mut lo, mut step) = (*k + 1, 1);
            let hi = loop {
                let next = lo + step;
                if next >= m || !before(next) {
                    break next.min(m);
                }
                lo = next;
                step *= 2;
            };
            *k = bisect(lo, hi);
        }
        while *k > 0 && s * t[*k].u.cross(v) < 0.0 {
            *k -= 1;
        }
        let (a, b) = (t[*k], t[*k + 1]);
        let z = s * a.u.cross(v) / a.u.dot(v);
        let delta = if z.abs() <= 0.01 {
            // atan z = z - z³/3 + z⁵/5 - z⁷/7 (|z| <= 0.01, the usual step between nodes:
            // truncation below z⁹/9, 1.2e-17 of z).
            let z2 = z * z;
            z * (1.0 - z2 * (1.0 / 3.0 - z2 * (1.0 / 5.0 - z2 * (1.0 / 7.0))))
        } else if z.abs() <= 0.1 {
            // The same to z¹⁷ (|z| <= 0.1: truncation below 1e-20).
            const INV: [f64; 7] = [
                1.0 / 15.0,
                1.0 / 13.0,
                1.0 / 11.0,
                1.0 / 9.0,
                1.0 / 7.0,
                1.0 / 5.0,
                1.0 / 3.0,
            ];
            let z2 = z * z;
            let mut acc = 1.0 / 17.0;
            for c in INV {
                acc = c - z2 * acc;
            }
            z * (1.0 - z2 * acc)
        } else {
            (s * a.u.cross(v)).atan2(a.u.dot(v))
        };
        let h = b.tau - a.tau;
        let x = (delta / h).clamp(
            if *k == 0 { 0.0 } else { -0.5 },
            if *k + 1 == m { 1.0 } else { 1.5 },
        );
        (a, b, x, h)
    }

    /// Residuals (x(t) - LAC(τ(t))) / length at `ts`, appended to `out`; None for an
    /// invalid (f0, f1).
    pub(super) fn residuals(
        &self,
        f0: f64,
        f1: f64,
        smp: &Samples,
        out: &mut Vec<f64>,
    ) -> Option<()> {
        let ts = &smp.t;
        let (b, w) = self.cubic(f0, f1)?;
        let h = homogeneous(&b, &w);
        out.clear();
        let mut pts = Vec::new();
        let mut taus = Vec::new();
        if self.exact {
            for &t in ts {
                let (p, tangent) = cubic_point_tangent(&h, t);
                pts.push(p);
                taus.push(turning(self.d0, tangent, self.sign));
            }
        } else {
            self.with_cells(ts.len(), |cells| {
                let mut k = usize::MAX;
                for ((&t, &sw), cell) in ts.iter().zip(&smp.sw).zip(cells.iter_mut()) {
                    let (p, tangent) = cubic_point_tangent(&h, t);
                    if *cell != usize::MAX {
                        k = *cell;
                    }
                    let q = self.lac_at_dir(tangent, &mut k);
                    *cell = k;
                    let f = sw / self.len;
                    out.push((p.x - q.x) * f);
                    out.push((p.y - q.y) * f);
                }
            });
        }
        if self.exact {
            let lac = self.seg.eval_turning(&taus).ok()?.points;
            for ((p, q), sw) in pts.iter().zip(&lac).zip(&smp.sw) {
                let f = sw / self.len;
                out.push((p.x - q.x) * f);
                out.push((p.y - q.y) * f);
            }
        }
        Some(())
    }

    /// [`Self::residuals`] (table mode) and their derivatives in f0 and f1 in closed form:
    /// with b1 = P0 + e0 f0, b2 = P2 + e1 f1 (e0 = P1 - P0, e1 = P1 - P2) the end weights
    /// are w0 = K0 f0² |e0|³ / (e0 × (b2 - P0)) and w3 = K1 f1² |e1|³ / ((b1 - P2) × e1), so
    /// the homogeneous control points, and with them the point, the tangent, its turning
    /// angle τ and the LAC point at τ (the table interpolant's dq/dτ), differentiate
    /// directly.
    pub(super) fn residuals_jac(
        &self,
        f0: f64,
        f1: f64,
        smp: &Samples,
        out: &mut Vec<f64>,
        jac: &mut [Vec<f64>; 2],
    ) -> Option<()> {
        if self.exact {
            return None;
        }
        let (b, w) = self.cubic(f0, f1)?;
        let [p0, p1, p2] = self.p;
        let (e0, e1) = (p1 - p0, p1 - p2);
        let cross01 = e0.cross(e1);
        let a0 = e0.cross(b[2] - p0);
        let a1 = (b[1] - p2).cross(e1);
        // ∂w/∂f for w0 and w3 (w1 = w2 are constant).
        let (dw0, dw3) = (
            [2.0 * w[0] / f0, -w[0] * cross01 / a0],
            [-w[3] * cross01 / a1, 2.0 * w[3] / f1],
        );
        type H = [(f64, f64, f64); 4];
        let h: H = homogeneous(&b, &w);
        let hom = |p: Point, dw: f64| (p.x * dw, p.y * dw, dw);
        let dh: [H; 2] = [
            [
                hom(p0, dw0[0]),
                (e0.x * w[1], e0.y * w[1], 0.0),
                (0.0, 0.0, 0.0),
                hom(p2, dw3[0]),
            ],
            [
                hom(p0, dw0[1]),
                (0.0, 0.0, 0.0),
                (e1.x * w[2], e1.y * w[2], 0.0),
                hom(p2, dw3[1]),
            ],
        ];
        out.clear();
        for j in jac.iter_mut() {
            j.clear();
        }
        self.with_cells(smp.t.len(), |cells| {
            let mut k = usize::MAX;
            for (i, (&t, &sw)) in smp.t.iter().zip(&smp.sw).enumerate() {
                if cells[i] != usize::MAX {
                    k = cells[i];
                }
                let u = 1.0 - t;
                let c = [u * u * u, 3.0 * t * u * u, 3.0 * t * t * u, t * t * t];
                let e = [u * u, 2.0 * t * u, t * t];
                // (x, y, w) and their t-derivatives (up to the factor 3) of homogeneous points.
                let sums = |h: &H| {
                    let mut v = [0.0; 6];
                    for i in 0..4 {
                        v[0] += c[i] * h[i].0;
                        v[1] += c[i] * h[i].1;
                        v[2] += c[i] * h[i].2;
                    }
                    for i in 0..3 {
                        v[3] += e[i] * (h[i + 1].0 - h[i].0);
                        v[4] += e[i] * (h[i + 1].1 - h[i].1);
                        v[5] += e[i] * (h[i + 1].2 - h[i].2);
                    }
                    v
                };
                let [hx, hy, hw, dx, dy, dw] = sums(&h);
                let p = Point::new(hx / hw, hy / hw);
                let v = Vec2::new(dx * hw - hx * dw, dy * hw - hy * dw);
                let (q, dq) = self.lac_at_dir_d(v, &mut k);
                cells[i] = k;
                let f = sw / self.len;
                out.push((p.x - q.x) * f);
                out.push((p.y - q.y) * f);
                let v2 = v.hypot2();
                for (dhj, col) in dh.iter().zip(jac.iter_mut()) {
                    let [gx, gy, gw, gdx, gdy, gdw] = sums(dhj);
                    let dp = Vec2::new((gx - p.x * gw) / hw, (gy - p.y * gw) / hw);
                    let dv = Vec2::new(
                        gdx * hw + dx * gw - gx * dw - hx * gdw,
                        gdy * hw + dy * gw - gy * dw - hy * gdw,
                    );
                    let dtau = self.sign * v.cross(dv) / v2;
                    col.push((dp.x - dq.x * dtau) * f);
                    col.push((dp.y - dq.y * dtau) * f);
                }
            }
        });
        Some(())
    }

    /// [`approximation_error`] of `curve` (a rational cubic) with the LAC points from the
    /// table instead of the exact LAC: the same samples and the same correspondence, no
    /// integration (a third of the time).
    pub(super) fn table_report(&self, curve: &RationalBezier, n: usize) -> ApproximationError {
        let h = homogeneous(curve.points(), curve.weights());
        let mut k = usize::MAX;
        ApproximationError::of((0..n).map(|i| {
            let (p, tangent) = cubic_point_tangent(&h, i as f64 / (n - 1) as f64);
            (p - self.lac_at_dir(tangent, &mut k)).hypot() / self.len
        }))
    }

    /// Weighted mean square residual (infinite for an invalid (f0, f1)).
    pub(super) fn cost(&self, f0: f64, f1: f64, ts: &Samples, buf: &mut Vec<f64>) -> f64 {
        match self.residuals(f0, f1, ts, buf) {
            Some(()) => buf.iter().map(|r| r * r).sum::<f64>(),
            None => f64::INFINITY,
        }
    }

    /// Whether the cubic at `(f0, f1)` is proven curvature-monotone by the certified
    /// floating-point filter. A candidate only exact arithmetic could decide lies on the
    /// monotone set's boundary to within rounding and counts as outside it: the searches
    /// test thousands of candidates, and exact Sturm sequences on a near-boundary one cost
    /// up to seconds (a pen stroke's piece took minutes at its default tolerance). A `true`
    /// is a proof: the filter only answers when its rounding bound decides every sign.
    pub(super) fn is_monotone(&self, f0: f64, f1: f64) -> bool {
        self.cubic(f0, f1)
            .and_then(|(b, w)| crate::monotone::filtered_verdict(&b, Some(&w)).ok())
            .flatten()
            .unwrap_or(false)
    }
}

/// Parameters t of the error samples and the square roots of their weights (the weights sum
/// to 1, so the weighted sum of squares is a mean square).
pub(super) struct Samples {
    pub(super) t: Vec<f64>,
    pub(super) sw: Vec<f64>,
}

impl Samples {
    /// Gauss–Legendre nodes: the weighted sum approximates ∫_0^1 |x(t) - LAC|² dt, the
    /// quantity the uniform reported mean also approximates, far better than as many
    /// uniform samples would (the search uses few samples).
    pub(super) fn gauss(n: usize) -> Samples {
        let (t, w) = crate::quadrature::gauss_legendre_01(n);
        Samples {
            t,
            sw: w.iter().map(|w| w.sqrt()).collect(),
        }
    }
    /// `n` uniform t with both ends, equal weights: the reported measure.
    pub(super) fn uniform(n: usize) -> Samples {
        Samples {
            t: (0..n).map(|i| i as f64 / (n - 1) as f64).collect(),
            sw: vec![(1.0 / n as f64).sqrt(); n],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::TABLE_INTERVALS;
    use super::*;

    #[test]
    fn the_lac_table_interpolates_to_its_stated_accuracy() {
        // The table's point for the tangent direction at turning angle τ against the exact
        // LAC point (relative to the length), over shapes from near the circle to 0.999 of
        // θ_lim, in three groups: [regular, near θ_lim, α in [0, 1) (ill-conditioned where
        // the low-curvature end is nearly straight: module documentation)].
        let mut worst = [0.0f64; 3];
        for alpha in [-4.0, -1.0, 0.0, 0.5, 2.0, 4.0] {
            for td in [0.3f64, 1.0, 2.0] {
                for u in [0.05, 0.5, 0.9, 0.999] {
                    let slot = if (0.0..1.0).contains(&alpha) {
                        2
                    } else if u > 0.99 {
                        1
                    } else {
                        0
                    };
                    let Ok(tri) = crate::approx_table::shape_triangle(alpha, td, u) else {
                        continue;
                    };
                    let Ok(seg) = LacSegment::new(alpha, tri) else {
                        continue;
                    };
                    let prob = Problem::new(&seg, TABLE_INTERVALS).unwrap();
                    let taus: Vec<f64> = (0..=997).map(|i| td * i as f64 / 997.0).collect();
                    let at = seg.eval_turning(&taus).unwrap();
                    let mut k = usize::MAX;
                    for (p, d) in at.points.iter().zip(&at.tangents) {
                        let q = prob.lac_at_dir(*d, &mut k);
                        worst[slot] = worst[slot].max((q - *p).hypot() / prob.len);
                    }
                }
            }
        }
        println!(
            "table error / length: {:.1e} {:.1e} {:.1e}",
            worst[0], worst[1], worst[2]
        );
        assert!(worst[0] < 1e-13, "{worst:?}");
        assert!(worst[1] < 1e-10, "{worst:?}");
        assert!(worst[2] < 1e-8, "{worst:?}");
    }

    #[test]
    fn closed_form_jacobian_matches_central_differences() {
        let tri = [
            Point::new(0.0, 0.0),
            Point::new(10.0, 0.0),
            Point::new(16.0, 9.0),
        ];
        for alpha in [-1.5, 0.5, 2.0] {
            let seg = LacSegment::new(alpha, tri).unwrap();
            let prob = Problem::new(&seg, 256).unwrap();
            let smp = Samples::gauss(16);
            for (f0, f1) in [(0.3, 0.4), (0.55, 0.62), (0.7, 0.2)] {
                let (mut r, mut j) = (Vec::new(), [Vec::new(), Vec::new()]);
                prob.residuals_jac(f0, f1, &smp, &mut r, &mut j).unwrap();
                let mut plain = Vec::new();
                prob.residuals(f0, f1, &smp, &mut plain).unwrap();
                assert_eq!(r, plain);
                let h = 1e-6;
                let (mut a, mut b) = (Vec::new(), Vec::new());
                for (axis, col) in j.iter().enumerate() {
                    let (d0, d1) = if axis == 0 { (h, 0.0) } else { (0.0, h) };
                    prob.residuals(f0 + d0, f1 + d1, &smp, &mut a).unwrap();
                    prob.residuals(f0 - d0, f1 - d1, &smp, &mut b).unwrap();
                    let scale = col.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                    for ((x, y), c) in a.iter().zip(&b).zip(col) {
                        let fd = (x - y) / (2.0 * h);
                        assert!(
                            (fd - c).abs() <= 1e-5 * scale,
                            "alpha {alpha} ({f0}, {f1}) axis {axis}: {c} vs {fd}"
                        );
                    }
                }
            }
        }
    }
}
