use super::constants::{
    CURVE_SAMPLES_SCALING, EXTREME_CUT, EXTREME_FACTOR, FAIR_SHARE, FAIR_SHARE_LAST, NEAR_NOISE,
    NEAR_NOISE_SHARE, PRECISE_NOISE, PRECISE_SCALING, SPARSE_STEP, TIGHT_SHARE,
};
use super::resolution;
use super::slot::EndPoints;
use super::track::Track;
use super::types::SketchOptions;
use crate::bspline::{self, BSplineFit, FitOptions};
use crate::error::{Error, Result};
use kurbo::Point;

/// The points of a stroke checked: finite, their extent within f64, and (two or more) not
/// all one point; their bounding box's diagonal (0 for fewer than two).
pub(super) fn check_points(points: &[Point]) -> Result<f64> {
    if points.iter().any(|q| !q.is_finite()) {
        return Err(Error::invalid("points", "must be finite"));
    }
    if points.len() < 2 {
        return Ok(0.0);
    }
    let diagonal = bbox_diagonal(points);
    if !diagonal.is_finite() {
        return Err(Error::invalid(
            "points",
            "the coordinates are too large: their extent overflows f64",
        ));
    }
    if diagonal == 0.0 {
        return Err(Error::Degenerate(format!(
            "all {} points coincide: no curve runs through them",
            points.len()
        )));
    }
    Ok(diagonal)
}

/// Cumulative arc length along the points.
pub(super) fn arc_lengths(points: &[Point]) -> Vec<f64> {
    let mut s = vec![0.0; points.len()];
    for i in 1..points.len() {
        s[i] = s[i - 1] + (points[i] - points[i - 1]).hypot();
    }
    s
}

/// Diagonal of the points' bounding box.
pub(super) fn bbox_diagonal(points: &[Point]) -> f64 {
    let (mut lo, mut hi) = (
        Point::new(f64::MAX, f64::MAX),
        Point::new(f64::MIN, f64::MIN),
    );
    for q in points {
        lo = Point::new(lo.x.min(q.x), lo.y.min(q.y));
        hi = Point::new(hi.x.max(q.x), hi.y.max(q.y));
    }
    (hi - lo).hypot()
}

/// Robust estimate of the standard deviation of the noise across the stroke (the
/// component normal to it, the one a distance to the curve sees): at each point, a local
/// least-squares cubic in chord length over its 15 neighbours (the spacing may be
/// irregular) and the point's residual along the cubic's normal, divided by `√(1 - h)` with
/// `h` the point's leverage in that fit (the fit's own share of the noise); the root mean
/// square of the smallest 90 % of them (a corner's residuals are left out) over 0.7893,
/// which makes it σ for Gaussian noise. The trimmed mean varies half as much from stroke
/// to stroke as the median (over 79 hands of ±1.5 px: 6.5 % against 11 %, lowest 0.76 px
/// against 0.66 px for a true 0.87 px). The residual along the stroke is not used: the
/// chord length follows the points, so the fit absorbs it. 0 for fewer than 15 points.
pub(super) fn noise_level(points: &[Point]) -> f64 {
    sigma_of_residuals(points, 7)
}

/// σ of the noise as [`noise_level`] reads it, over `2 half + 1` points.
pub(super) fn sigma_of_residuals(points: &[Point], half: usize) -> f64 {
    trimmed_sigma(&mut residuals(points, half))
}

/// The half window over which a sparse stroke's noise is read ([`Noise::of`]).
const SPARSE_HALF: usize = 3;

/// The absolute residuals of [`noise_level`] with local cubics over `2 half + 1` points;
/// none for fewer than 15 points.
fn residuals(points: &[Point], half: usize) -> Vec<f64> {
    let n = points.len();
    if n < 15 {
        return Vec::new();
    }
    let s = arc_lengths(points);
    (half..n - half)
        .filter_map(|k| normal_residual(points, &s, k, half))
        .map(f64::abs)
        .collect()
}

/// σ from absolute residuals: their root mean square over the smallest 90 %, over
/// [`TRIMMED_GAUSSIAN`]; 0 for none.
fn trimmed_sigma(res: &mut [f64]) -> f64 {
    if res.is_empty() {
        return 0.0;
    }
    res.sort_unstable_by(f64::total_cmp);
    let kept = &res[..(res.len() * 9).div_ceil(10)];
    (kept.iter().map(|r| r * r).sum::<f64>() / kept.len() as f64).sqrt() / TRIMMED_GAUSSIAN
}

/// σ from absolute residuals: their median over 0.6745; 0 for none.
fn median_sigma(res: &mut [f64]) -> f64 {
    if res.is_empty() {
        return 0.0;
    }
    let mid = res.len() / 2;
    let (_, m, _) = res.select_nth_unstable_by(mid, f64::total_cmp);
    *m / 0.6745
}

/// The root mean square of a standard normal variable over its central 90 %.
const TRIMMED_GAUSSIAN: f64 = 0.789_313_3;

/// The noise of a stroke at two scales: [`noise_level`] (cubics over 15 points), and the
/// median residual over 15 and over 5 points. On noise all estimate σ; on points sampled
/// exactly from a curve the residuals are the cubics' own error, which falls as the fourth
/// power of the window (an arc sampled every 0.02 rad leaves 15-point residuals far above
/// rounding but 5-point ones 80 times smaller) and is largest where the curvature is: the
/// median sees the typical point, not the crest.
pub(super) struct Noise {
    /// Over 15 points: the noise of noisy input.
    pub(super) sigma: f64,
    /// The smallest of the three: the noise of precise input.
    pub(super) fine: f64,
    /// The median over 5 points against the median over 15, the window's effect: about 1
    /// on noise, `(5/15)⁴ ≈ 0.012` on a curve's own sampling.
    pub(super) scaling: f64,
    /// The noise's largest deviation: the largest residual over 15 points that is no more
    /// than [`EXTREME_CUT`] times `sigma` (larger ones are the local cubics missing a
    /// feature, a sharp bend or a corner, not noise). Every point must lie within the
    /// tolerance, so no fair curve meets a tolerance this close: the fair spline then
    /// follows the extremes (a stroke of 240 points with Gaussian-like noise of σ 0.034 has
    /// one at 2.8σ, above the 2.55σ its fair spline had at a tolerance of 3σ: 18 false
    /// inflections).
    pub(super) extreme: f64,
    /// Whether the stroke has enough points (15) for an estimate: fewer leave every field 0,
    /// and the stroke is taken as precise (a few clicked points), whether it is or not.
    pub(super) known: bool,
    /// The device's step ([`resolution::quantum`]), 0 if none is seen.
    pub(super) quantum: f64,
    /// The hand's slow wobble ([`resolution::wobble`]).
    pub(super) wobble: f64,
}

impl Noise {
    pub(super) fn of(points: &[Point]) -> Noise {
        let mut wide = residuals(points, 7);
        let known = !wide.is_empty();
        let median = median_sigma(&mut wide);
        // Sparse points (clicks) are read over 7 points: 15 of them span so much of the
        // shape that a cubic misses it by more than the noise (15 clicks on a 170° arc of
        // radius 300 with ±3 px: σ read as 4.9 for a true 1.7; over 7 points 2.0), and the
        // few residuals a short stroke has over 15 points (1 of 15 points) tell little.
        let mut sigma_from = if sparse(points) {
            residuals(points, SPARSE_HALF)
        } else {
            wide
        };
        let sigma = trimmed_sigma(&mut sigma_from);
        let narrow = median_sigma(&mut residuals(points, 2));
        // `sigma_from` is sorted by `trimmed_sigma`.
        let extreme = sigma_from
            .iter()
            .rev()
            .find(|r| **r <= EXTREME_CUT * sigma)
            .copied()
            .unwrap_or(0.0);
        Noise {
            sigma,
            fine: sigma.min(median).min(narrow),
            scaling: if median > 0.0 { narrow / median } else { 0.0 },
            extreme,
            known,
            quantum: resolution::quantum(points, bbox_diagonal(points)),
            wobble: resolution::wobble(points),
        }
    }

    /// The noise with the device's step `resolution` when the caller knows it (it
    /// replaces the one read from the points).
    pub(super) fn with_resolution(self, resolution: Option<f64>) -> Noise {
        match resolution {
            Some(r) => Noise { quantum: r, ..self },
            None => self,
        }
    }

    /// Whether the input, of size `size` (its bounding box's diagonal), is precise to
    /// rounding: 4 times its noise (at the finer scale) below [`PRECISE_NOISE`] of the
    /// size. The fit follows such input tightly.
    pub(super) fn precise(&self, size: f64) -> bool {
        self.quantum == 0.0 && 4.0 * self.fine <= PRECISE_NOISE * size
    }

    /// Whether the input is a curve's samples: [`Noise::precise`], or its residuals
    /// shrinking with the window as a sampled curve's do (a [`Noise::scaling`] below
    /// [`PRECISE_SCALING`]: a smooth curve sampled coarsely, whose 15-point residuals are
    /// well above rounding). Its default tolerance is a share of its size, not of a noise
    /// it does not have.
    pub(super) fn sampled(&self, size: f64) -> bool {
        self.precise(size) || (self.quantum == 0.0 && self.scaling < PRECISE_SCALING)
    }

    /// Whether enough points (15) show residuals that shrink with the window as a
    /// sampled curve's do, closely ([`CURVE_SAMPLES_SCALING`]), with no device step: a
    /// curve's samples, however coarse (25 samples of a 110° arc leave 15-point residuals
    /// of 4e-4 of the size, far above rounding), which the tight spline follows. A regular
    /// tremor can shrink too, less (0.03 to 0.08), and gets the fair spline.
    pub(super) fn curve_samples(&self) -> bool {
        self.known && self.quantum == 0.0 && self.scaling < CURVE_SAMPLES_SCALING
    }

    /// Whether the fit follows the input tightly: [`Noise::precise`] or
    /// [`Noise::curve_samples`] (the tight spline, and curvature extrema that are the
    /// data's).
    pub(super) fn followed_tightly(&self, size: f64) -> bool {
        self.precise(size) || self.curve_samples()
    }
}

/// The residual of point `k` along the normal of the least-squares cubic in chord length
/// `s` over its `half` neighbours on each side, scaled by `1/√(1 - h)` (`h` its leverage);
/// `None` where the fit is singular or has no tangent.
fn normal_residual(points: &[Point], s: &[f64], k: usize, half: usize) -> Option<f64> {
    let w = (s[k + half] - s[k - half]).max(f64::MIN_POSITIVE);
    let mut m = nalgebra::Matrix4::<f64>::zeros();
    let mut bx = nalgebra::Vector4::<f64>::zeros();
    let mut by = nalgebra::Vector4::<f64>::zeros();
    for j in k - half..=k + half {
        let t = (s[j] - s[k]) / w;
        let v = nalgebra::Vector4::new(1.0, t, t * t, t * t * t);
        m += v * v.transpose();
        bx += v * points[j].x;
        by += v * points[j].y;
    }
    let ch = m.cholesky()?;
    let (cx, cy) = (ch.solve(&bx), ch.solve(&by));
    let leverage = ch.solve(&nalgebra::Vector4::new(1.0, 0.0, 0.0, 0.0))[0];
    let tangent = kurbo::Vec2::new(cx[1], cy[1]);
    let len = tangent.hypot();
    let usable = len > 0.0 && leverage < 1.0;
    if !usable {
        return None;
    }
    let r = points[k] - Point::new(cx[0], cy[0]);
    Some(r.cross(tangent) / len / (1.0 - leverage).sqrt())
}

/// What every round of the fit reads, built once from the input: the options checked, the
/// fair B-spline and its track, the track the events are read from, the curve's ends.
pub(super) struct Context<'a> {
    pub(super) opts: &'a SketchOptions,
    /// The fair B-spline (its points and parameters are the input's, de-duplicated).
    pub(super) fit: BSplineFit,
    /// `fit` as Bézier spans.
    pub(super) track: Track,
    /// A smoother spline's track for the inflections and curvature maxima of precise input
    /// whose tolerance allows one (`None`: `track` serves).
    shape: Option<Track>,
    /// The curve runs from the first input point to the last.
    pub(super) ends: EndPoints,
    /// The unit directions of the lines its ends join, if any (the fair spline's tangent
    /// there, noisy, is not used for those ends' pieces).
    pub(super) line_ends: [Option<kurbo::Vec2>; 2],
    /// The input is precise to rounding ([`Noise::precise`]) or a curve's samples
    /// ([`Noise::curve_samples`]): its curvature extrema are the data's, wherever they lie.
    pub(super) precise: bool,
    /// The input's noise (σ) where it is not a curve's samples, 0 where it is, infinite
    /// where too few points (15) tell which: how closely the points can tell one curve from
    /// another.
    pub(super) noise: f64,
}

impl<'a> Context<'a> {
    /// Stage 1: the input checked, its noise estimated, the fair spline fitted, and a
    /// straight input refused (no LAC turns along it).
    #[cfg(test)]
    pub(super) fn new(points: &[Point], opts: &'a SketchOptions) -> Result<Self> {
        check_points(points)?;
        Self::with_noise(points, opts, &Noise::of(points))
    }

    /// [`Context::new`] with the points already checked ([`check_points`]) and their
    /// noise estimated.
    pub(super) fn with_noise(
        points: &[Point],
        opts: &'a SketchOptions,
        noise: &Noise,
    ) -> Result<Self> {
        Error::check_positive("tolerance", opts.tolerance)?;
        if !(opts.max_turn > 0.1 && opts.max_turn < 3.0) {
            return Err(Error::invalid("max_turn", "must lie in (0.1, 3) radians"));
        }
        let end_dirs = line_ends(opts)?;
        let precise = noise.followed_tightly(bbox_diagonal(points));
        let (fit, fit_tol) = fair_spline(points, opts.tolerance, noise)?;
        let track = Track::new(&fit.spline)?;
        check_turning(&track, opts.min_turn)?;
        let track = if opts.closed {
            track
        } else {
            track.with_flat_ends()
        };
        let shape = shape_track(points, opts.tolerance, fit_tol)?;
        let ends = (fit.points[0], *fit.points.last().unwrap());
        Ok(Context {
            opts,
            fit,
            track,
            shape,
            ends,
            line_ends: end_dirs,
            precise,
            noise: match (noise.known, precise) {
                (false, _) => f64::INFINITY,
                (true, true) => 0.0,
                (true, false) => noise.sigma,
            },
        })
    }

    /// The track whose events cut the pieces.
    pub(super) fn shape(&self) -> &Track {
        self.shape.as_ref().unwrap_or(&self.track)
    }
}

/// The options' line ends checked (open curves only, finite and non-zero directions) and
/// made unit vectors.
fn line_ends(opts: &SketchOptions) -> Result<[Option<kurbo::Vec2>; 2]> {
    let given = opts.line_ends;
    if opts.closed && given.iter().any(Option::is_some) {
        return Err(Error::invalid(
            "line_ends",
            "a closed curve has no ends to join lines",
        ));
    }
    let unit = |d: Option<kurbo::Vec2>| -> Result<Option<kurbo::Vec2>> {
        match d {
            None => Ok(None),
            Some(d) if d.is_finite() && d.hypot() > 0.0 => Ok(Some(d / d.hypot())),
            Some(_) => Err(Error::invalid(
                "line_ends",
                "a line's direction must be finite and non-zero",
            )),
        }
    };
    Ok([unit(given[0])?, unit(given[1])?])
}

/// The fair spline of the points and the tolerance it was fitted to. Precise data (noise
/// below [`PRECISE_NOISE`] of the size) get the tight least-squares fit, whose tangents
/// and curvature graphs are accurate: within 4 times their noise and at least
/// [`TIGHT_SHARE`] of the size, never looser than half the tolerance; noisy data
/// (measured lines, pen strokes) the smoothest spline within [`FAIR_SHARE`] of the
/// tolerance, which carries no hooks or wiggles the tolerance does not demand. Outliers the
/// noise estimate ignores can keep the tight fit from converging: then half the tolerance.
fn fair_spline(points: &[Point], tolerance: f64, noise: &Noise) -> Result<(BSplineFit, f64)> {
    let size = bbox_diagonal(points);
    let noisy = !noise.followed_tightly(size);
    let fit_tol = (4.0 * noise.fine)
        .max(TIGHT_SHARE * size)
        .min(0.5 * tolerance);
    let tight = |tolerance: f64| {
        let opts = FitOptions {
            tolerance,
            max_segments: 200,
        };
        bspline::fit(points, opts)
    };
    if noisy {
        return smoothing_spline(points, tolerance, noise);
    }
    // The tight spline's own error quotes its own tolerance, a share of the one asked for.
    let named = |e: Error, share: f64| match e {
        Error::NoConvergence(m) => Error::NoConvergence(format!(
            "the spline through the points, within {share:.3e} (part of the tolerance \
             {tolerance:.3e}, the rest left to the pieces): {m}; the points carry more noise \
             than this tolerance allows: a looser one"
        )),
        other => other,
    };
    let fit = match tight(fit_tol) {
        Err(Error::NoConvergence(_)) if fit_tol < 0.5 * tolerance => (
            tight(0.5 * tolerance).map_err(|e| named(e, 0.5 * tolerance))?,
            0.5 * tolerance,
        ),
        other => (other.map_err(|e| named(e, fit_tol))?, fit_tol),
    };
    // Sparse points (a dozen clicks) can leave the tight fit's knots where no point pins
    // the control points: it passes near every point and loops thousands of units away
    // between them. The smoothest spline within the tolerance does not.
    if !((sparse(points) && !noise.curve_samples()) || fit.0.swings_out()) {
        return Ok(fit);
    }
    let smooth = smoothing_spline(points, tolerance, noise)?;
    if smooth.0.swings_out() {
        // Too few points for a spline that stays near them within the tolerance: an
        // answer that loops far out between them would only look like one.
        return Err(Error::NoConvergence(format!(
            "no spline within {:.3e} of these {} points stays near them between them (its \
             control polygon is more than {} times as long as theirs): too few points for \
             this tolerance; a looser one, or more points",
            smooth.1,
            points.len(),
            bspline::SWING_POLYLINE
        )));
    }
    Ok(smooth)
}

/// Whether the points are sparse: their median step longer than [`SPARSE_STEP`] of their
/// size (some 50 points or fewer along the stroke).
pub(super) fn sparse(points: &[Point]) -> bool {
    let mut steps: Vec<f64> = points.windows(2).map(|w| (w[1] - w[0]).hypot()).collect();
    let mid = steps.len() / 2;
    !steps.is_empty()
        && *steps.select_nth_unstable_by(mid, f64::total_cmp).1
            > SPARSE_STEP * bbox_diagonal(points)
}

/// The smoothest spline within [`FAIR_SHARE`] of the tolerance ([`NEAR_NOISE_SHARE`] where
/// the tolerance is within [`NEAR_NOISE`] times the noise's σ, or where 3/4 of it would
/// leave less room above the noise's largest deviation than the near-noise share leaves at
/// the default tolerance: a share of 3/4 would put the spline at the noise's extremes,
/// which it would then follow; an arc with Gaussian noise of σ 1 px, 3.82 px from its
/// largest deviation of 2.83 px, came back in 21 pieces with 6 inflections, in 2 pieces
/// at 3.9 px), or, where the noise's
/// extremes leave no spline that close (dense points: the largest of many deviations),
/// within [`FAIR_SHARE_LAST`] of it; the spline and the tolerance it met. Sparse points
/// ([`sparse`]) get two spans per point ([`bspline::sparse_smoothing_fit`]).
fn smoothing_spline(points: &[Point], tolerance: f64, noise: &Noise) -> Result<(BSplineFit, f64)> {
    // The default tolerance leaves the near-noise share 15 % of room above the noise's
    // largest deviation (EXTREME_FACTOR); the fair share must not leave less.
    let near_extremes = FAIR_SHARE * tolerance < NEAR_NOISE_SHARE * EXTREME_FACTOR * noise.extreme;
    let share = if tolerance < NEAR_NOISE * noise.sigma || near_extremes {
        NEAR_NOISE_SHARE
    } else {
        FAIR_SHARE
    };
    let sparse = sparse(points);
    let smoothest = |tol: f64| {
        if sparse {
            fairer(
                bspline::smoothing_fit(points, tol),
                bspline::sparse_smoothing_fit(points, tol),
            )
        } else {
            bspline::smoothing_fit(points, tol)
        }
    };
    match smoothest(share * tolerance) {
        Err(Error::NoConvergence(_)) => {
            let fit_tol = FAIR_SHARE_LAST * tolerance;
            Ok((smoothest(fit_tol)?, fit_tol))
        }
        other => Ok((other?, share * tolerance)),
    }
}

/// Of two smoothing splines through the same points within the same deviation, the one
/// that turns less in all (its absolute turning over [`FAIRER_STEPS`] steps), or the one
/// there is. For sparse points the spline of two spans a point is the fairer one where the
/// default span count's only member within the deviation bulges between points (12 points
/// of a smooth walk: 54 units out between points 80 apart; 17.7 rad of turning against
/// 11.4 on one of 40 walks); where the points turn back (a zigzag), the finer spline
/// follows them round every turn and the coarser one, which cannot, is kept.
fn fairer(coarse: Result<BSplineFit>, fine: Result<BSplineFit>) -> Result<BSplineFit> {
    let turning = |f: &BSplineFit| -> Option<f64> {
        let track = Track::new(&f.spline).ok()?;
        let (u0, u1) = track.domain();
        Some(track.turns(u0, u1, FAIRER_STEPS).map(f64::abs).sum())
    };
    match (coarse, fine) {
        (Ok(c), Ok(f)) => match (turning(&c), turning(&f)) {
            (Some(tc), Some(tf)) if tc <= tf => Ok(c),
            (Some(_), None) => Ok(c),
            _ => Ok(f),
        },
        (Ok(c), Err(_)) => Ok(c),
        (Err(_), fine) => fine,
    }
}

/// Steps over which [`fairer`] sums a spline's turning.
const FAIRER_STEPS: usize = 2048;

/// A straight input refused: its absolute turning (summed over 256 intervals, each
/// signed turning over 8 steps) below `min_turn`.
fn check_turning(track: &Track, min_turn: f64) -> Result<()> {
    let (u0, u1) = track.domain();
    let steps: Vec<f64> = track.turns(u0, u1, 256 * 8).collect();
    let turns: f64 = steps.chunks(8).map(|c| c.iter().sum::<f64>().abs()).sum();
    if turns < min_turn {
        return Err(Error::Degenerate(format!(
            "the points lie on a straight line (total turning {:.3e} rad, total {:.3e}): \
             no log-aesthetic curve turns along them",
            turns,
            steps.iter().sum::<f64>()
        )));
    }
    Ok(())
}

/// The track of a smoother spline (a quarter of the tolerance) when that is more than twice
/// as loose as the fair spline (precise input: a fair spline at [`FAIR_SHARE`] or half of
/// the tolerance never is): wiggles of the tight fit's curvature are not features. Both
/// are parametrised by chord length (corrected), so a parameter carries over.
fn shape_track(points: &[Point], tolerance: f64, fit_tol: f64) -> Result<Option<Track>> {
    let shape_tol = 0.25 * tolerance;
    if shape_tol <= 2.0 * fit_tol {
        return Ok(None);
    }
    let opts = FitOptions {
        tolerance: shape_tol,
        max_segments: 200,
    };
    Ok(Some(Track::new(&bspline::fit(points, opts)?.spline)?))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An arc of radius `r` sampled at `n` points.
    fn arc(n: usize, r: f64) -> Vec<Point> {
        (0..n)
            .map(|i| {
                let a = 0.1 + 1.2 * i as f64 / (n - 1) as f64;
                Point::new(r * a.cos(), r * a.sin())
            })
            .collect()
    }

    #[test]
    fn straight_input_and_bad_options_are_refused_by_name() {
        let line: Vec<Point> = (0..40)
            .map(|i| Point::new(i as f64, 2.0 * i as f64))
            .collect();
        let opts = SketchOptions::with_tolerance(0.1);
        assert!(matches!(
            Context::new(&line, &opts),
            Err(Error::Degenerate(_))
        ));
        let bad = SketchOptions {
            max_turn: 5.0,
            ..SketchOptions::with_tolerance(0.1)
        };
        let err = Context::new(&arc(40, 100.0), &bad).err().expect("refused");
        assert!(
            matches!(&err, Error::InvalidInput { field, .. } if field.as_str() == "max_turn"),
            "{err:?}"
        );
        let none = SketchOptions::with_tolerance(0.0);
        assert!(Context::new(&arc(40, 100.0), &none).is_err());
    }

    #[test]
    fn precise_input_gets_the_tight_spline_and_noisy_input_the_fair_one() {
        let opts = SketchOptions::with_tolerance(1.0);
        // Dense exact samples (at 60 points the local cubics' residual on an exact arc
        // passes the noise test: a known limit).
        let clean = arc(300, 100.0);
        let cx = Context::new(&clean, &opts).unwrap();
        // Tight: within 1e-6 of the size (the noise is nil), far below the tolerance; the
        // events come from a looser spline of their own.
        assert!(cx.fit.max_deviation < 2e-3, "{}", cx.fit.max_deviation);
        assert!(!std::ptr::eq(cx.shape(), &cx.track));
        assert_eq!(cx.ends, (clean[0], clean[299]));
        // ±0.3 zigzag: the smoothest spline within FAIR_SHARE of the tolerance, which does
        // not follow the zigzag; its own track gives the events.
        let noisy: Vec<Point> = clean
            .iter()
            .enumerate()
            .map(|(i, q)| Point::new(q.x + if i % 2 == 0 { 0.3 } else { -0.3 }, q.y))
            .collect();
        let cx = Context::new(&noisy, &opts).unwrap();
        let d = cx.fit.max_deviation;
        assert!(d <= FAIR_SHARE * opts.tolerance + 1e-9 && d > 0.1, "{d}");
        assert!(std::ptr::eq(cx.shape(), &cx.track));
    }
}
