use super::constants::FLAT_STRETCH_SHARE;
use crate::bernstein::sign_change_roots;
use crate::bezier::{Bezier, PlanarCurve};
use crate::bspline::BSpline;
use crate::error::Result;
use kurbo::{Point, Vec2};
use std::sync::atomic::{AtomicBool, Ordering};

/// The B-spline as Bézier spans over its knot intervals, for derivatives at any u.
pub(super) struct Track {
    pub(super) spans: Vec<Bezier>,
    pub(super) breaks: Vec<f64>,
    /// The tangent each end of the curve is fitted with, where it is not the spline's own
    /// there ([`Track::with_flat_ends`]); released when no piece forms a triangle with it
    /// ([`Track::release_end`]).
    end_dirs: [Option<Vec2>; 2],
    /// Which of `end_dirs` were released (the track is shared by the fit's threads).
    released: [AtomicBool; 2],
}

impl Track {
    pub(super) fn new(s: &BSpline) -> Result<Track> {
        let spans = s.to_beziers()?;
        let n = spans.len();
        let p = s.degree;
        let breaks = (0..=n).map(|i| s.knots[p + i]).collect();
        Ok(Track {
            spans,
            breaks,
            end_dirs: [None, None],
            released: [AtomicBool::new(false), AtomicBool::new(false)],
        })
    }

    /// The track whose free ends leave a flat end stretch crossed by noise: where the
    /// curvature next to an end stays below [`FLAT_STRETCH_SHARE`] of the curve's largest and
    /// changes sign there (a pen stroke or a measured line that ends at zero curvature,
    /// as an S does), the segmentation drops that inflection as noise, so the end takes the
    /// tangent at its last sign change instead of the spline's at the end, which leans the
    /// noise's way (a piece from there would turn both ways and form no triangle).
    pub(super) fn with_flat_ends(mut self) -> Self {
        let (u0, u1) = self.domain();
        let n = 256;
        let us: Vec<f64> = (0..=n)
            .map(|k| u0 + (u1 - u0) * k as f64 / n as f64)
            .collect();
        let ks: Vec<f64> = us.iter().map(|&u| self.derivs(u).kappa()).collect();
        let flat = FLAT_STRETCH_SHARE * ks.iter().fold(0.0f64, |m, k| m.max(k.abs()));
        let last_crossing = |order: &mut dyn Iterator<Item = usize>| {
            let mut prev: Option<usize> = None;
            let mut found = None;
            for i in order {
                if ks[i].abs() >= flat {
                    break;
                }
                if let Some(j) = prev {
                    if ks[i] * ks[j] < 0.0 {
                        found = Some(i);
                    }
                }
                prev = Some(i);
            }
            found
        };
        self.end_dirs = [
            last_crossing(&mut (0..=n)).map(|i| self.direction(us[i])),
            last_crossing(&mut (0..=n).rev()).map(|i| self.direction(us[i])),
        ];
        self
    }

    /// Give the end at `u` (the curve's start or end) back its spline tangent; whether it
    /// had another ([`Track::with_flat_ends`]). A piece from a split inside the flat
    /// stretch to that end has the same tangent at both ends and forms no triangle.
    pub(super) fn release_end(&self, u: f64) -> bool {
        self.end_side(u).is_some_and(|side| {
            self.end_dirs[side].is_some() && !self.released[side].swap(true, Ordering::Relaxed)
        })
    }

    /// Which end of the curve `u` is (0: the start, 1: the end), if either.
    fn end_side(&self, u: f64) -> Option<usize> {
        if u <= self.breaks[0] {
            Some(0)
        } else if u >= *self.breaks.last().unwrap() {
            Some(1)
        } else {
            None
        }
    }

    /// The tangent the curve's start (0) or end (1) is fitted with, if not the spline's.
    fn end_dir(&self, side: usize) -> Option<Vec2> {
        self.end_dirs[side].filter(|_| !self.released[side].load(Ordering::Relaxed))
    }

    /// The parameter range: its first and last breaks.
    pub(super) fn domain(&self) -> (f64, f64) {
        (self.breaks[0], *self.breaks.last().unwrap())
    }

    pub(super) fn locate(&self, u: f64) -> (usize, f64) {
        // The last span whose start is at or before u (the first span before the domain).
        let n = self.spans.len();
        let i = self.breaks[1..n].partition_point(|b| *b <= u);
        let (a, b) = (self.breaks[i], self.breaks[i + 1]);
        (i, ((u - a) / (b - a)).clamp(0.0, 1.0))
    }

    pub(super) fn point(&self, u: f64) -> Point {
        let (i, t) = self.locate(u);
        self.spans[i].eval(t)
    }

    pub(super) fn derivs(&self, u: f64) -> crate::bezier::Derivs {
        let (i, t) = self.locate(u);
        self.spans[i].derivs(t)
    }

    /// The unit tangent at `u`; at an end of the curve the one it is fitted with.
    pub(super) fn direction(&self, u: f64) -> Vec2 {
        let end = self.end_side(u).and_then(|side| self.end_dir(side));
        end.unwrap_or_else(|| {
            let d = self.derivs(u).d1;
            d / d.hypot()
        })
    }

    /// Inflection parameters and curvature-maximum (of |κ|) parameters, sorted.
    pub(super) fn events(&self) -> (Vec<f64>, Vec<f64>) {
        let (mut infl, mut maxima) = (Vec::new(), Vec::new());
        for (i, b) in self.spans.iter().enumerate() {
            let (x, y) = b.components();
            let (x1, y1) = (x.deriv(), y.deriv());
            let (x2, y2) = (x1.deriv(), y1.deriv());
            let g = x1.mul(&y2).sub(&y1.mul(&x2));
            let f = x1.mul(&x1).add(&y1.mul(&y1));
            let h = g
                .deriv()
                .mul(&f)
                .scale(2.0)
                .sub(&g.mul(&f.deriv()).scale(3.0));
            let (a, w) = (self.breaks[i], self.breaks[i + 1] - self.breaks[i]);
            for t in sign_change_roots(&g) {
                infl.push(a + w * t);
            }
            for t in sign_change_roots(&h) {
                // A maximum of |κ|: d|κ|/ds goes from + to -; sign(h) = sign(dκ/ds).
                let e = 1e-6;
                let before = h.eval((t - e).max(0.0)) * g.eval(t).signum();
                let after = h.eval((t + e).min(1.0)) * g.eval(t).signum();
                if before > 0.0 && after < 0.0 {
                    maxima.push(a + w * t);
                }
            }
        }
        (infl, maxima)
    }

    /// Signed turning of the tangent from `ua` to `ub`, accumulated over 64 steps (each
    /// taken to turn less than π).
    pub(super) fn angle_between(&self, ua: f64, ub: f64) -> f64 {
        self.turns(ua, ub, 64).sum()
    }

    /// The signed turning of each of `n` equal steps from `ua` to `ub` (each taken to turn
    /// less than π, so that their sum is the unwrapped turning).
    pub(super) fn turns(&self, ua: f64, ub: f64, n: usize) -> impl Iterator<Item = f64> + '_ {
        let mut prev = self.direction(ua);
        (1..=n).map(move |k| {
            let d = self.direction(ua + (ub - ua) * k as f64 / n as f64);
            let t = turn(prev, d);
            prev = d;
            t
        })
    }

    /// |κ| at u.
    pub(super) fn abs_kappa(&self, u: f64) -> f64 {
        self.derivs(u).kappa().abs()
    }
}

/// Signed angle from the unit vector `a` to `b`, in (-π, π].
fn turn(a: Vec2, b: Vec2) -> f64 {
    a.cross(b).atan2(a.dot(b))
}

/// The parameter where the curve has turned by `target` (in [0, total]) from `ua`: the
/// step of 64 from `ua` to `ub` where the turning passes `target`, then bisection inside
/// it (the turning there: the steps before it and the angle from the step's start).
pub(super) fn u_at_turn(track: &Track, ua: f64, ub: f64, target: f64) -> f64 {
    let n = 64;
    let at = |k: usize| ua + (ub - ua) * k as f64 / n as f64;
    let steps: Vec<f64> = track.turns(ua, ub, n).collect();
    let sgn = steps.iter().sum::<f64>().signum();
    // The last step start still short of the target.
    let mut before = 0.0;
    let mut k = 0;
    while k + 1 < n && sgn * (before + steps[k]) < target {
        before += steps[k];
        k += 1;
    }
    let start = track.direction(at(k));
    let b = crate::solve::roots::bisect_by(
        |mid| (sgn * (before + turn(start, track.direction(mid))) < target).then_some(()),
        at(k),
        at(k + 1),
        |a, b| 0.5 * (a + b),
        |_, _| false,
        60,
    );
    0.5 * (b.inside + b.outside)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bspline::{fit, FitOptions};

    /// An arc of 5 rad (more than π: the turning must be unwrapped) fitted by a spline:
    /// the parameter `u_at_turn` returns for a target has the tangent turned by that
    /// target from the start, measured independently (the angle of the tangent, unwrapped
    /// over 20,000 steps); `angle_between` over the whole arc is its turning, to the fit's
    /// accuracy (a fit within 1e-3 of the radius 30 leans its end tangents by 1e-3).
    #[test]
    fn u_at_turn_finds_the_turning_asked_for_beyond_pi() {
        let pts: Vec<Point> = (0..=400)
            .map(|i| {
                let a = 5.0 * i as f64 / 400.0;
                Point::new(30.0 * a.cos(), 30.0 * a.sin())
            })
            .collect();
        let opts = FitOptions {
            tolerance: 1e-3,
            max_segments: 100,
        };
        let track = Track::new(&fit(&pts, opts).unwrap().spline).unwrap();
        let (u0, u1) = track.domain();
        let total = track.angle_between(u0, u1);
        assert!((total - 5.0).abs() < 5e-3, "{total}");
        let unwrapped = |u: f64| {
            let n = 20_000;
            let mut prev = track.direction(u0);
            let mut total = 0.0;
            for k in 1..=n {
                let d = track.direction(u0 + (u - u0) * k as f64 / n as f64);
                total += prev.cross(d).atan2(prev.dot(d));
                prev = d;
            }
            total
        };
        for target in [0.01, 1.0, 3.3, 4.9] {
            let u = u_at_turn(&track, u0, u1, target);
            assert!(
                (unwrapped(u) - target).abs() < 1e-9,
                "{target}: {}",
                unwrapped(u)
            );
        }
    }

    /// y = x³ from x = -0.025: its curvature changes sign at x = 0, and before it stays
    /// below 9 % of its largest (about 1.76 at x = 0.45), so the start is a flat stretch
    /// crossed by noise; the start takes the tangent at the sign change (horizontal), not
    /// the spline's there (slope 0.0019). The far end, curved, keeps the spline's own.
    #[test]
    fn a_flat_end_crossing_zero_takes_the_tangent_of_its_sign_change() {
        let pts: Vec<Point> = (0..=410)
            .map(|i| {
                let x = -0.025 + i as f64 / 400.0;
                Point::new(x, x * x * x)
            })
            .collect();
        let s = fit(
            &pts,
            FitOptions {
                tolerance: 1e-6,
                max_segments: 50,
            },
        )
        .unwrap();
        let plain = Track::new(&s.spline).unwrap();
        let (u0, u1) = plain.domain();
        let flat = Track::new(&s.spline).unwrap().with_flat_ends();
        assert!(plain.direction(u0).y > 1.5e-3);
        let d = flat.direction(u0);
        assert!(d.y.abs() < 2e-4 && d.x > 0.0, "{d:?}");
        assert_eq!(flat.direction(u1), plain.direction(u1));
        assert_eq!(
            flat.direction(0.5 * (u0 + u1)),
            plain.direction(0.5 * (u0 + u1))
        );
    }
}
