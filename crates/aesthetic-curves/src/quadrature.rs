//! Adaptive Gauss–Kronrod quadrature (7-point Gauss, 15-point Kronrod) for smooth real- and
//! complex-valued integrands.
//!
//! The error estimate of a panel is `|K15 - G7|`; the panel with the largest estimate is
//! bisected until the sum of the estimates is below `accuracy` (absolute; or below a few ulps
//! of the sum of the panels' magnitudes, the rounding floor) or the panel budget runs out, in which
//! case [`Error::NoConvergence`] is returned instead of a silently inaccurate value. Complex
//! values are [`kurbo::Vec2`] (x = real part, y = imaginary part).

use crate::error::{Error, Result};
use kurbo::Vec2;
use std::ops::{Add, Mul, Sub};

/// A value [`integrate`] can sum: a complex number ([`Vec2`]) or a [`Riding`] pair.
pub trait QuadValue:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<f64, Output = Self>
{
    /// Zero.
    const ZERO: Self;
    /// The magnitude the error control applies to.
    fn size(&self) -> f64;
    /// Whether every part is finite.
    fn finite(&self) -> bool;
}

impl QuadValue for Vec2 {
    const ZERO: Self = Vec2::ZERO;
    fn size(&self) -> f64 {
        self.hypot()
    }
    fn finite(&self) -> bool {
        self.is_finite()
    }
}

/// Two complex integrands summed on the same panels: the adaptivity follows `value` alone and
/// `rider` (a derivative of it, say, as smooth as it) comes along at the same nodes, for the
/// price of a multiplication or two per node instead of a second integral.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Riding {
    /// The integrand the accuracy is controlled on.
    pub value: Vec2,
    /// The integrand carried along.
    pub rider: Vec2,
}

impl Add for Riding {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Riding {
            value: self.value + o.value,
            rider: self.rider + o.rider,
        }
    }
}

impl Sub for Riding {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Riding {
            value: self.value - o.value,
            rider: self.rider - o.rider,
        }
    }
}

impl Mul<f64> for Riding {
    type Output = Self;
    fn mul(self, k: f64) -> Self {
        Riding {
            value: self.value * k,
            rider: self.rider * k,
        }
    }
}

impl QuadValue for Riding {
    const ZERO: Self = Riding {
        value: Vec2::ZERO,
        rider: Vec2::ZERO,
    };
    fn size(&self) -> f64 {
        self.value.hypot()
    }
    fn finite(&self) -> bool {
        self.value.is_finite() && self.rider.is_finite()
    }
}

#[allow(clippy::excessive_precision)]
const XGK: [f64; 8] = [
    0.991_455_371_120_812_639_206_854_697_526_329,
    0.949_107_912_342_758_524_526_189_684_047_851,
    0.864_864_423_359_769_072_789_712_788_640_926,
    0.741_531_185_599_394_439_863_864_773_280_788,
    0.586_087_235_467_691_130_294_144_845_693_013,
    0.405_845_151_377_397_166_906_606_412_076_961,
    0.207_784_955_007_898_467_600_689_403_773_245,
    0.0,
];
#[allow(clippy::excessive_precision)]
const WGK: [f64; 8] = [
    0.022_935_322_010_529_224_963_732_008_058_970,
    0.063_092_092_629_978_553_290_700_663_189_204,
    0.104_790_010_322_250_183_839_876_322_541_518,
    0.140_653_259_715_525_918_745_189_590_510_238,
    0.169_004_726_639_267_902_826_583_426_598_550,
    0.190_350_578_064_785_409_913_256_402_421_014,
    0.204_432_940_075_298_892_414_161_999_234_649,
    0.209_482_141_084_727_828_012_999_174_891_714,
];
// Gauss weights of the nodes XGK[1], XGK[3], XGK[5], XGK[7].
#[allow(clippy::excessive_precision)]
const WG: [f64; 4] = [
    0.129_484_966_168_869_693_270_611_432_679_082,
    0.279_705_391_489_276_667_901_467_771_423_780,
    0.381_830_050_505_118_944_950_369_775_488_975,
    0.417_959_183_673_469_387_755_102_040_816_327,
];

/// One Gauss–Kronrod panel on [a, b]: (Kronrod estimate, error estimate).
///
/// The error estimate is QUADPACK's (Piessens et al. 1983, `qk15`): the raw difference
/// `|K15 - G7|` rescaled as `resasc min(1, (200 |K15 - G7| / resasc)^1.5)`, where `resasc`
/// is the integral of |f - mean f|; K15 is exact to degree 22 against G7's 13, so the raw
/// difference overstates the error of K15 by orders of magnitude on smooth integrands.
pub fn gk15<V: QuadValue>(f: &mut impl FnMut(f64) -> V, a: f64, b: f64) -> (V, f64) {
    let c = 0.5 * (a + b);
    let h = 0.5 * (b - a);
    let fc = f(c);
    let mut k = fc * WGK[7];
    let mut g = fc * WG[3];
    let mut vals = [V::ZERO; 15];
    vals[14] = fc;
    for j in 0..7 {
        let dx = h * XGK[j];
        let (f1, f2) = (f(c - dx), f(c + dx));
        vals[2 * j] = f1;
        vals[2 * j + 1] = f2;
        let s = f1 + f2;
        k = k + s * WGK[j];
        if j % 2 == 1 {
            g = g + s * WG[j / 2];
        }
    }
    let mean = k * 0.5;
    let mut resasc = WGK[7] * (fc - mean).size();
    for j in 0..7 {
        resasc += WGK[j] * ((vals[2 * j] - mean).size() + (vals[2 * j + 1] - mean).size());
    }
    resasc *= h.abs();
    let raw = ((k - g) * h).size();
    let err = if resasc > 0.0 && raw > 0.0 {
        resasc * (200.0 * raw / resasc).powf(1.5).min(1.0)
    } else {
        raw
    };
    (k * h, err)
}

/// Options of [`integrate`].
#[derive(Clone, Copy, Debug)]
pub struct QuadOptions {
    /// Absolute accuracy of the result.
    pub accuracy: f64,
    /// Largest number of panels before giving up.
    pub max_panels: usize,
}

impl Default for QuadOptions {
    fn default() -> Self {
        QuadOptions {
            accuracy: 1e-14,
            max_panels: 4000,
        }
    }
}

/// Integral of `f` over [a, b] (oriented: b < a gives the negative), adaptively refined to
/// the requested absolute accuracy (of [`QuadValue::size`]).
pub fn integrate<V: QuadValue>(
    mut f: impl FnMut(f64) -> V,
    a: f64,
    b: f64,
    opts: QuadOptions,
) -> Result<V> {
    if a == b {
        return Ok(V::ZERO);
    }
    if !(a.is_finite() && b.is_finite()) {
        return Err(Error::invalid(
            "interval",
            "integration limits must be finite",
        ));
    }
    // Work list of panels; always split the panel with the largest error (global adaptivity).
    let (v, e) = gk15(&mut f, a, b);
    let mut panels = vec![(a, b, v, e)];
    let mut total_err = e;
    let mut total = v;
    // Error estimates below a few ulps of the panels' magnitudes are rounding, not
    // truncation: accept them even when `accuracy` asks for more.
    let mut total_abs = v.size();
    while total_err > opts.accuracy.max(32.0 * f64::EPSILON * total_abs) {
        if panels.len() >= opts.max_panels {
            return Err(Error::NoConvergence(format!(
                "adaptive quadrature: error estimate {total_err:.3e} above {:.3e} after {} panels",
                opts.accuracy, opts.max_panels
            )));
        }
        let (i, _) = panels
            .iter()
            .enumerate()
            .max_by(|x, y| x.1 .3.total_cmp(&y.1 .3))
            .expect("non-empty");
        let (pa, pb, pv, pe) = panels.swap_remove(i);
        let m = 0.5 * (pa + pb);
        if m == pa || m == pb {
            // Cannot split further: accept at rounding level.
            panels.push((pa, pb, pv, 0.0));
            total_err -= pe;
            continue;
        }
        let (lv, le) = gk15(&mut f, pa, m);
        let (rv, re) = gk15(&mut f, m, pb);
        total = total - pv + lv + rv;
        total_abs = total_abs - pv.size() + lv.size() + rv.size();
        total_err = total_err - pe + le + re;
        panels.push((pa, m, lv, le));
        panels.push((m, pb, rv, re));
        if !total_err.is_finite() || !total.finite() {
            return Err(Error::NoConvergence(
                "adaptive quadrature: the integrand is not finite".into(),
            ));
        }
    }
    // Re-sum the accepted panels to shed the running sum's rounding.
    let mut sum = V::ZERO;
    for p in &panels {
        sum = sum + p.2;
    }
    Ok(sum)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polynomials_are_exact_and_oscillations_converge() {
        let v = integrate(
            |x| Vec2::new(x.powi(20), 0.0),
            0.0,
            1.0,
            QuadOptions::default(),
        )
        .unwrap();
        assert!((v.x - 1.0 / 21.0).abs() < 1e-15);
        // integral_0^{20 pi} e^{i x} dx = -i (e^{i 20 pi} - 1) = 0; of cos^2: 10 pi.
        let w = integrate(
            |x| Vec2::new(x.cos() * x.cos(), x.sin()),
            0.0,
            20.0 * std::f64::consts::PI,
            QuadOptions::default(),
        )
        .unwrap();
        assert!((w.x - 10.0 * std::f64::consts::PI).abs() < 1e-12);
        assert!(w.y.abs() < 1e-12);
        // Oriented.
        let r = integrate(|x| Vec2::new(x, 0.0), 1.0, 0.0, QuadOptions::default()).unwrap();
        assert!((r.x + 0.5).abs() < 1e-16);
    }

    #[test]
    fn reports_failure_instead_of_looping() {
        // sin(1/x) oscillates ever faster towards 1e-3: 50 panels cannot resolve it.
        let r = integrate(
            |x| Vec2::new((1.0 / x).sin(), 0.0),
            1e-3,
            1.0,
            QuadOptions {
                accuracy: 1e-15,
                max_panels: 50,
            },
        );
        assert!(matches!(r, Err(Error::NoConvergence(_))));
    }
}

/// Nodes and weights of the `n`-point Gauss–Legendre rule on [0, 1] (weights sum to 1),
/// by Newton's method on the Legendre polynomial from the usual Chebyshev-like guesses;
/// rules of up to 64 points are computed once and copied afterwards.
pub fn gauss_legendre_01(n: usize) -> (Vec<f64>, Vec<f64>) {
    if n <= MAX_CACHED_RULE {
        gauss_legendre_01_ref(n).clone()
    } else {
        gauss_legendre_rule(n)
    }
}

/// The largest rule [`gauss_legendre_01`] keeps.
pub(crate) const MAX_CACHED_RULE: usize = 64;

/// The kept `n`-point rule itself (no copy), `n` at most [`MAX_CACHED_RULE`].
pub(crate) fn gauss_legendre_01_ref(n: usize) -> &'static (Vec<f64>, Vec<f64>) {
    static CACHE: [std::sync::OnceLock<(Vec<f64>, Vec<f64>)>; MAX_CACHED_RULE + 1] =
        [const { std::sync::OnceLock::new() }; MAX_CACHED_RULE + 1];
    CACHE[n].get_or_init(|| gauss_legendre_rule(n))
}

fn gauss_legendre_rule(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    for i in 0..n.div_ceil(2) {
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            // P_n(z) and P_n'(z) by the three-term recurrence.
            let (mut p0, mut p1) = (1.0, z);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * z * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            let pn = if n == 0 {
                1.0
            } else if n == 1 {
                z
            } else {
                p1
            };
            let pm = if n == 1 { 1.0 } else { p0 };
            dp = n as f64 * (z * pn - pm) / (z * z - 1.0);
            let dz = pn / dp;
            z -= dz;
            if dz.abs() < 1e-16 {
                break;
            }
        }
        let wi = 1.0 / ((1.0 - z * z) * dp * dp); // 2/((1-z²) P'²) on [-1, 1], halved
        x[i] = 0.5 * (1.0 - z);
        x[n - 1 - i] = 0.5 * (1.0 + z);
        w[i] = wi;
        w[n - 1 - i] = wi;
    }
    (x, w)
}

#[cfg(test)]
mod gauss_tests {
    use super::*;

    #[test]
    fn gauss_legendre_integrates_polynomials() {
        for n in [1, 2, 5, 12, 24, 48] {
            let (x, w) = gauss_legendre_01(n);
            assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-14, "{n}");
            assert!(x.windows(2).all(|p| p[0] < p[1]));
            // Exact for degree 2n - 1: ∫ t^k = 1/(k+1).
            for k in 0..2 * n {
                let v: f64 = x.iter().zip(&w).map(|(t, w)| w * t.powi(k as i32)).sum();
                assert!(
                    (v - 1.0 / (k as f64 + 1.0)).abs() < 1e-13,
                    "n {n} k {k}: {v}"
                );
            }
        }
    }
}
