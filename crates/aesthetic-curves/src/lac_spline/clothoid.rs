//! The α = -1 span as one clothoid (docs/math.md §7): the fast path of the G2 solve.
//!
//! At α = -1 every span the general path builds ([`super::span::solve`]: a line, an arc,
//! one segment, or two inflection-end halves mirrored about their inflection, whose
//! curvature is linear in arc length on both sides with the same slope) is one arc of a
//! clothoid. In the chord frame (start at 0, end at 1) its tangent angle over the
//! normalised arc length t ∈ [0, 1] is `φ(t) = a + (δ - A) t + A t²`, δ = b - a, and the
//! end lands on the chord's line where `S(A) = ∫₀¹ sin φ dt = 0` (Bertolazzi and Frego,
//! "G1 fitting with clothoids", 2015); the length is then `L = 1 / C`, `C = ∫₀¹ cos φ dt`,
//! and the end curvatures `(δ ∓ A) / L`. The integrals are Gauss–Legendre sums whose
//! order the phase's variation picks (error bound below 1e-17), so one evaluation of the
//! span costs a few sines and cosines where the general path integrates a LAC three times;
//! the curvatures' derivatives in (a, b) come from the same sums (implicit
//! differentiation of `S(A; a, b) = 0`), which gives the solve its Jacobian without
//! forward differences.
//!
//! Where the phase varies too much for the rules kept here, or Newton's method on A does
//! not settle, there is no fast answer (`None`) and the caller takes the general path.

use super::span::MAX_TURN;
use crate::quadrature::gauss_legendre_01_ref;
use std::f64::consts::PI;

/// The Gauss–Legendre rules tried, each with the constant of its remainder on [0, 1],
/// `(n!)⁴ / ((2n+1) ((2n)!)³)`, which multiplies the largest |f⁽²ⁿ⁾|.
const RULES: [(usize, f64); 7] = [
    (8, 1.6973616714304124e-23),
    (10, 5.734017131339254e-31),
    (12, 8.816390890706909e-39),
    (16, 3.187492664611718e-55),
    (20, 1.5731835853690933e-72),
    (24, 1.5808848455335836e-90),
    (32, 3.6101308198679265e-128),
];

/// The quadrature error allowed (of the integrals, which are at most 1).
const QUAD_ERROR: f64 = 1e-17;

/// Newton steps on A at most.
const MAX_STEPS: usize = 12;

/// A clothoid span: its signed end curvatures (in units of one over the chord) and their
/// derivatives in the deviations: `d[0]` = ∂(κ₀, κ₁)/∂a, `d[1]` = ∂(κ₀, κ₁)/∂b.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Clothoid {
    pub(super) kappa: (f64, f64),
    pub(super) d: [(f64, f64); 2],
    /// The root A (a warm start for the span's next solve).
    pub(super) root: f64,
}

/// The sums of one rule at one A: `∫ tʲ cos φ` and `∫ tʲ sin φ` for j = 0, 1, 2.
struct Moments {
    cos: [f64; 3],
    sin: [f64; 3],
}

impl Moments {
    /// S(A) = ∫ sin φ.
    fn s(&self) -> f64 {
        self.sin[0]
    }

    /// ∂S/∂A = ∫ (t² - t) cos φ.
    fn s_a(&self) -> f64 {
        self.cos[2] - self.cos[1]
    }
}

/// The moments of the phase `φ(t) = a + (δ - A) t + A t²` by the rule `(x, w)`.
fn moments((x, w): (&[f64], &[f64]), a: f64, delta: f64, big_a: f64) -> Moments {
    let mut m = Moments {
        cos: [0.0; 3],
        sin: [0.0; 3],
    };
    for (&t, &wt) in x.iter().zip(w) {
        let (s, c) = (a + (delta - big_a + big_a * t) * t).sin_cos();
        let (wc, ws) = (wt * c, wt * s);
        m.cos[0] += wc;
        m.sin[0] += ws;
        m.cos[1] += wc * t;
        m.sin[1] += ws * t;
        m.cos[2] += wc * t * t;
        m.sin[2] += ws * t * t;
    }
    m
}

/// The start of Newton's method on A: Bertolazzi and Frego's fit of the root over the
/// deviations, `(a + b) (3.070645 + 0.947923 a b - 0.673029 (a² + b²))`.
fn guess(a: f64, b: f64) -> f64 {
    (a + b) * (3.070645 + 0.947923 * a * b - 0.673029 * (a * a + b * b))
}

/// The smallest rule whose remainder bound for `e^{iφ}` is below [`QUAD_ERROR`]: with
/// |φ'| <= w = |δ| + |A| and φ'' = 2A, Faà di Bruno's formula bounds the m-th derivative
/// by `Σ_k m! / (k! (m-2k)!) w^(m-2k) |A|^k` (k pairs of derivatives taken by φ'').
fn rule(delta: f64, big_a: f64) -> Option<(&'static [f64], &'static [f64])> {
    let (w, q) = (delta.abs() + big_a.abs(), big_a.abs());
    RULES
        .iter()
        .find(|(n, c)| c * derivative_bound(2 * n, w, q) <= QUAD_ERROR)
        .map(|(n, _)| {
            let (x, w) = gauss_legendre_01_ref(*n);
            (x.as_slice(), w.as_slice())
        })
}

/// `Σ_k m! / (k! (m-2k)!) w^(m-2k) q^k` for even `m`, term by term (each the last times
/// `(m-2k)(m-2k-1) q / ((k+1) w²)`; from the last term down where w is 0).
fn derivative_bound(m: usize, w: f64, q: f64) -> f64 {
    if w == 0.0 {
        // Only k = m/2: m! / (m/2)! q^(m/2).
        let h = m / 2;
        return ((h + 1)..=m).map(|i| i as f64).product::<f64>() * q.powi(h as i32);
    }
    let mut term = w.powi(m as i32);
    let mut sum = term;
    for k in 0..m / 2 {
        term *= ((m - 2 * k) * (m - 2 * k - 1)) as f64 * q / ((k + 1) as f64 * w * w);
        sum += term;
    }
    sum
}

/// The clothoid span whose tangents leave the chord by `a` at the start and `b` at the
/// end, or `None` where the fast path does not answer (module documentation). Newton's
/// method on A starts from `warm` (the root of a nearby span: the solve's previous
/// tangents) where given, else, or where that fails, from [`guess`].
pub(super) fn span(a: f64, b: f64, warm: Option<f64>) -> Option<Clothoid> {
    if !(a.is_finite() && b.is_finite()) {
        return None;
    }
    warm.filter(|w| w.is_finite())
        .and_then(|w| newton(a, b, w))
        .or_else(|| newton(a, b, guess(a, b)))
}

/// Newton's method on A from `big_a`.
fn newton(a: f64, b: f64, mut big_a: f64) -> Option<Clothoid> {
    let delta = b - a;
    for _ in 0..MAX_STEPS {
        let r = rule(delta, big_a)?;
        let m = moments(r, a, delta, big_a);
        let (s, s_a) = (m.s(), m.s_a());
        if !(s_a.is_finite() && s_a != 0.0) {
            return None;
        }
        let step = -s / s_a;
        // Newton's error after a step is about |S''/2S'| step², S'' = -∫ (t² - t)² sin φ
        // at most 1/30: where |S'| >= 0.01 (near a straight span S' is -1/6) a step of
        // 1e-9 leaves below 2e-18, and it is applied to first order (`finish`) without
        // taking the moments again; elsewhere the steps go on to 1e-14.
        let tol = if s_a.abs() >= 0.01 { 1e-9 } else { 1e-14 };
        if step.abs() <= tol * big_a.abs().max(1.0) {
            return finish(&m, (a, b, big_a), step);
        }
        big_a += step;
    }
    None
}

/// The span at the root: the last step `step` from `big_a` applied to first order (the
/// moments were taken before it), the curvatures and their derivatives.
fn finish(m: &Moments, (a, b, big_a): (f64, f64, f64), step: f64) -> Option<Clothoid> {
    let delta = b - a;
    // ∂S/∂A, ∂S/∂a, ∂S/∂b and ∂C/∂(A, a, b): ∂φ/∂A = t² - t, ∂φ/∂a = 1 - t, ∂φ/∂b = t.
    let s_a = m.s_a();
    let s_da = m.cos[0] - m.cos[1];
    let s_db = m.cos[1];
    let c_a = -(m.sin[2] - m.sin[1]);
    let c_da = -(m.sin[0] - m.sin[1]);
    let c_db = -m.sin[1];
    let big_a = big_a + step;
    let c = m.cos[0] + c_a * step;
    if !(c > 0.0 && c.is_finite() && principal(a, b, big_a)) {
        return None;
    }
    // A moves with the deviations along S = 0; C with both.
    let (ga, gb) = (-s_da / s_a, -s_db / s_a);
    let (dc_a, dc_b) = (c_da + c_a * ga, c_db + c_a * gb);
    let (lo, hi) = (delta - big_a, delta + big_a);
    Some(Clothoid {
        kappa: (lo * c, hi * c),
        root: big_a,
        d: [
            ((-1.0 - ga) * c + lo * dc_a, (-1.0 + ga) * c + hi * dc_a),
            ((1.0 - gb) * c + lo * dc_b, (1.0 + gb) * c + hi * dc_b),
        ],
    })
}

/// Whether the clothoid of root `big_a` is the general path's curve: an S (its curvature
/// zero inside, where φ' = 0) whose two sides each turn less than π, the pair's range,
/// where the pair is unique; a bend (no zero inside) that one segment takes (turning below
/// [`MAX_TURN`]). Other roots wind further.
fn principal(a: f64, b: f64, big_a: f64) -> bool {
    let delta = b - a;
    let t = if big_a != 0.0 {
        (big_a - delta) / (2.0 * big_a)
    } else {
        -1.0
    };
    if t > 0.0 && t < 1.0 {
        let at = a + (delta - big_a + big_a * t) * t;
        (at - a).abs() < PI && (b - at).abs() < PI
    } else {
        a * b < 0.0 && delta.abs() < MAX_TURN
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lac_spline::span;

    /// End curvatures of clothoid spans computed with mpmath at 40 digits (the root of
    /// S(A) by `findroot`, the integrals by `quad`): a bend whose low end is nearly flat,
    /// small bends and S-spans, tiny deviations, a wide S, an arc of 200° (2 sin b).
    #[test]
    #[allow(clippy::excessive_precision)] // mpmath's digits, as printed
    fn the_clothoid_span_matches_forty_digit_references() {
        let cases: [(f64, f64, f64, f64); 7] = [
            (
                0.813,
                -1.807,
                -0.0012965455250297380256,
                -3.8108185485924380668,
            ),
            (0.3, -0.2, -0.79025164698174622024, -0.19912036849988978681),
            (0.05, 0.4, -0.98654146260538623304, 1.6794827358444186249),
            (-1.2, 0.9, 2.4177991288980679398, 1.0462162430271357149),
            (
                1e-6,
                2e-6,
                -7.9999999999975234475e-6,
                9.9999999999969900237e-6,
            ),
            (2.0, 1.5, -7.8382083933049472831, 7.1008172865234616297),
            (-1.745, 1.745, 1.9697297472800363566, 1.9697297472800363566),
        ];
        for (a, b, k0, k1) in cases {
            let got = span(a, b, None).unwrap_or_else(|| panic!("{a} {b}")).kappa;
            let scale = k0.abs().max(k1.abs());
            assert!(
                (got.0 - k0).abs() <= 1e-14 * scale && (got.1 - k1).abs() <= 1e-14 * scale,
                "{a} {b}: {got:?}"
            );
        }
    }

    /// The fast path against the general one (an independent construction: LAC segments
    /// and inflection pairs at α = -1, their Λ solved by their own Newton's method) over a
    /// grid of deviations up to 2.5 rad either way: the same end curvatures to 1e-9 of
    /// their size wherever both answer (the general path's accuracy near the edge of a
    /// segment's existence region, where an end's curvature nears 0: at (0.813, -1.807)
    /// it is 7e-11 off the forty-digit value, the fast path 2e-16), and the fast path
    /// answers everywhere the general one does within 1.5 rad.
    #[test]
    fn the_clothoid_span_is_the_general_spans_curve_at_alpha_minus_one() {
        let mut compared = 0;
        for i in -25..=25 {
            for j in -25..=25 {
                let (a, b) = (0.1 * i as f64 + 0.013, 0.1 * j as f64 - 0.007);
                let Ok(general) = span::solve(-1.0, a, b, span::HALF_TURN) else {
                    continue;
                };
                let fast = span(a, b, None);
                if a.abs().max(b.abs()) <= 1.5 {
                    assert!(fast.is_some(), "{a} {b}");
                }
                let Some(fast) = fast else { continue };
                let size = general.kappa.0.abs().max(general.kappa.1.abs()).max(1.0);
                let err = (fast.kappa.0 - general.kappa.0)
                    .abs()
                    .max((fast.kappa.1 - general.kappa.1).abs());
                assert!(
                    err <= 1e-9 * size,
                    "{a} {b}: {:?} {:?}",
                    fast.kappa,
                    general.kappa
                );
                compared += 1;
            }
        }
        assert!(compared > 2000, "{compared}");
    }

    /// The derivatives against central differences of the general path (step 1e-6).
    #[test]
    fn the_clothoid_derivatives_are_the_general_paths_slopes() {
        let h = 1e-6;
        for (a, b) in [
            (0.3, -0.2),
            (0.05, 0.4),
            (-1.2, 0.9),
            (0.8, 0.7),
            (-0.01, 0.02),
        ] {
            let fast = span(a, b, None).unwrap();
            let k = |a: f64, b: f64| span::solve(-1.0, a, b, span::HALF_TURN).unwrap().kappa;
            let (pa, ma) = (k(a + h, b), k(a - h, b));
            let (pb, mb) = (k(a, b + h), k(a, b - h));
            let fd = [
                ((pa.0 - ma.0) / (2.0 * h), (pa.1 - ma.1) / (2.0 * h)),
                ((pb.0 - mb.0) / (2.0 * h), (pb.1 - mb.1) / (2.0 * h)),
            ];
            for (got, want) in fast.d.iter().zip(fd) {
                let scale = want.0.abs().max(want.1.abs()).max(1.0);
                assert!(
                    (got.0 - want.0).abs() < 1e-6 * scale && (got.1 - want.1).abs() < 1e-6 * scale,
                    "{a} {b}: {got:?} {want:?}"
                );
            }
        }
    }
}
