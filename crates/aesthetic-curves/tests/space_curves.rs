//! Space curves' exact verdicts (`space`) against oracles that share no code with them: the
//! plane's own exact test (`monotone`, a different formula and module) for planar curves in
//! any coordinate plane, dense sampling of curvature and torsion from a power-basis
//! evaluation written here, and exact identities (scaling by powers of two changes nothing).

use aesthetic_curves::monotone::CurvatureMonotone;
use aesthetic_curves::space::{SpaceBezier, SpaceShape};
use aesthetic_curves::{Bezier, Point};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Derivatives 1 to 3 at `t` from the power basis (binomial expansion), not de Casteljau.
fn derivs(p: &[[f64; 3]], t: f64) -> [[f64; 3]; 3] {
    let n = p.len() - 1;
    // Power-basis coefficients a_j of B(t) = Σ a_j t^j.
    let binom = |n: usize, k: usize| -> f64 {
        (0..k).fold(1.0, |c, i| c * (n - i) as f64 / (i + 1) as f64)
    };
    let mut a = vec![[0.0f64; 3]; n + 1];
    for (j, aj) in a.iter_mut().enumerate() {
        for (i, pi) in p.iter().enumerate().take(j + 1) {
            let s = if (j - i) % 2 == 0 { 1.0 } else { -1.0 };
            let c = binom(n, j) * binom(j, i) * s;
            for k in 0..3 {
                aj[k] += c * pi[k];
            }
        }
    }
    let mut out = [[0.0; 3]; 3];
    for (order, o) in out.iter_mut().enumerate() {
        let d = order + 1;
        for (j, aj) in a.iter().enumerate().skip(d) {
            let f = (0..d).fold(1.0, |f, i| f * (j - i) as f64) * t.powi((j - d) as i32);
            for k in 0..3 {
                o[k] += f * aj[k];
            }
        }
    }
    out
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Curvature and torsion sampled at `k + 1` even parameters.
fn sampled(p: &[[f64; 3]], k: usize) -> (Vec<f64>, Vec<f64>) {
    (0..=k)
        .map(|i| {
            let t = i as f64 / k as f64;
            let [d1, d2, d3] = derivs(p, t);
            let c = cross(d1, d2);
            let s = dot(d1, d1).sqrt();
            (dot(c, c).sqrt() / (s * s * s), dot(c, d3) / dot(c, c))
        })
        .unzip()
}

/// Whether sampled values clearly turn back: a rise and a fall each larger than `margin`
/// of the values' range, in order (a trend reversal the samples cannot owe to rounding).
fn turns_back(v: &[f64], margin: f64) -> bool {
    let range = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let eps = margin * range;
    let (mut lo, mut hi) = (v[0], v[0]);
    let (mut rose, mut fell) = (false, false);
    for &x in v {
        if x > lo + eps {
            rose = true;
        }
        if x < hi - eps {
            fell = true;
        }
        if rose && fell {
            return true;
        }
        lo = lo.min(x);
        hi = hi.max(x);
    }
    false
}

fn random_curve(rng: &mut ChaCha8Rng, n: usize, planar: Option<usize>) -> Vec<[f64; 3]> {
    (0..=n)
        .map(|_| {
            let mut q: [f64; 3] = std::array::from_fn(|_| rng.random_range(-100.0..100.0));
            if let Some(k) = planar {
                q[k] = 0.0;
            }
            q
        })
        .collect()
}

/// The control points of a conical spiral: turning by a random step, the radius growing by
/// a random factor, rising at a random pitch.
fn spiral(rng: &mut ChaCha8Rng, n: usize) -> Vec<[f64; 3]> {
    let (step, growth): (f64, f64) = (rng.random_range(0.15..0.5), rng.random_range(1.05..1.6));
    let (r0, pitch): (f64, f64) = (rng.random_range(5.0..50.0), rng.random_range(0.05..1.0));
    (0..=n)
        .map(|i| {
            let (a, r) = (step * i as f64, r0 * growth.powi(i as i32));
            [r * a.cos(), r * a.sin(), pitch * r0 * i as f64]
        })
        .collect()
}

/// A planar curve in each coordinate plane: planar, no torsion, and its curvature's
/// extrema (its zero-curvature points aside) those of the plane's exact test; monotone
/// exactly when the plane's test says so and it has no inflection.
#[test]
fn planar_curves_get_the_planes_verdict_in_every_coordinate_plane() {
    let mut rng = ChaCha8Rng::seed_from_u64(0x5bace);
    let mut with_inflection = 0;
    for case in 0..240 {
        let n = 2 + case % 5;
        let plane = case % 3;
        let p = random_curve(&mut rng, n, Some(plane));
        // Round typed coordinates for a third of them.
        let p: Vec<[f64; 3]> = if case % 3 == 1 {
            p.iter().map(|q| q.map(f64::round)).collect()
        } else {
            p
        };
        let (i, j) = ((plane + 1) % 3, (plane + 2) % 3);
        let flat: Vec<Point> = p.iter().map(|q| Point::new(q[i], q[j])).collect();
        let r2 = Bezier::new(flat).unwrap().curvature_monotone().unwrap();
        let r3 = SpaceBezier::new(p.clone()).unwrap().check();
        assert_eq!(r3.shape, SpaceShape::Planar, "{p:?}");
        assert!(r3.torsion.is_none());
        let rest: Vec<f64> = (r3.curvature.extrema.iter())
            .copied()
            .filter(|t| !r3.zero_curvature.contains(t))
            .collect();
        assert_eq!(rest.len(), r2.extrema.len(), "{p:?}: {r3:?} against {r2:?}");
        for (a, b) in rest.iter().zip(&r2.extrema) {
            assert!((a - b).abs() < 1e-9, "{p:?}: {a} against {b}");
        }
        with_inflection += usize::from(!r3.zero_curvature.is_empty());
        assert_eq!(
            r3.curvature.monotone,
            r2.monotone && r3.zero_curvature.is_empty(),
            "{p:?}"
        );
    }
    println!("{with_inflection} of 240 planar curves with an inflection");
    // The sweep has planar inflections (curvature touching zero) and curves without.
    assert!((20..200).contains(&with_inflection), "{with_inflection}");
}

/// Twisted curves of degree 3 to 6, wild and fair: the verdicts agree with 4,001 samples of the curvature
/// and the torsion wherever the samples decide (a clear turn back is never called monotone;
/// a verdict of an extremum has one where the samples rise and fall around it).
#[test]
fn twisted_curves_agree_with_dense_samples() {
    let mut rng = ChaCha8Rng::seed_from_u64(0x7e15);
    let (mut monotone_k, mut monotone_t, mut twisted) = (0, 0, 0);
    for case in 0..300 {
        let n = 3 + case % 4;
        // Half wild (random control points), half fair: the control polygon of a conical
        // spiral, its radius growing by a random factor per point.
        let p = if case % 2 == 0 {
            random_curve(&mut rng, n, None)
        } else {
            spiral(&mut rng, n)
        };
        let r = SpaceBezier::new(p.clone()).unwrap().check();
        assert_eq!(r.shape, SpaceShape::Twisted, "{p:?}");
        twisted += 1;
        let (k, tau) = sampled(&p, 4000);
        if turns_back(&k, 1e-6) {
            assert!(!r.curvature.monotone, "{p:?}: samples turn back");
        }
        monotone_k += usize::from(r.curvature.monotone);
        let torsion = r.torsion.as_ref().unwrap();
        if r.zero_curvature.is_empty() && tau.iter().all(|x| x.is_finite()) {
            if turns_back(&tau, 1e-6) {
                assert!(!torsion.monotone, "{p:?}: torsion samples turn back");
            }
            if torsion.monotone && !torsion.constant {
                // Monotone: the samples never clearly turn back.
                assert!(!turns_back(&tau, 1e-3), "{p:?}: {torsion:?}");
            }
        }
        monotone_t += usize::from(torsion.monotone);
        if r.curvature.monotone {
            assert!(!turns_back(&k, 1e-3), "{p:?}: {r:?}");
        }
        // Each extremum is one: κ there is below both neighbours or above both.
        let c = SpaceBezier::new(p.clone()).unwrap();
        for &t in &r.curvature.extrema {
            let h = 1e-4;
            if t < 2.0 * h || t > 1.0 - 2.0 * h {
                continue;
            }
            let (a, m, b) = (c.curvature(t - h), c.curvature(t), c.curvature(t + h));
            assert!(
                (m <= a && m <= b) || (m >= a && m >= b) || (a - b).abs() < 1e-9 * m,
                "{p:?}: no extremum at {t}: {a} {m} {b}"
            );
        }
    }
    println!("of 300: curvature monotone {monotone_k}, torsion monotone {monotone_t}");
    // Both answers occur for either.
    assert!(
        twisted == 300 && monotone_k > 20 && monotone_k < 280,
        "{monotone_k}"
    );
    assert!(monotone_t > 20 && monotone_t < 280, "{monotone_t}");
}

/// Scaling every coordinate by a power of two changes no verdict (the curve is the same
/// shape, and the numbers are exact), from 2^-600 to 2^600; straight control polygons are
/// straight; degree 20 is decided.
#[test]
fn verdicts_are_exact_identities() {
    let mut rng = ChaCha8Rng::seed_from_u64(0x1de);
    for case in 0..60 {
        let p = random_curve(&mut rng, 3 + case % 4, None);
        let base = SpaceBezier::new(p.clone()).unwrap().check();
        for e in [-600, -40, 40, 600] {
            let f = 2f64.powi(e);
            let q: Vec<[f64; 3]> = p.iter().map(|v| v.map(|x| x * f)).collect();
            let r = SpaceBezier::new(q).unwrap().check();
            assert_eq!(r.shape, base.shape);
            assert_eq!(r.curvature.monotone, base.curvature.monotone, "{p:?} {e}");
            assert_eq!(r.curvature.extrema.len(), base.curvature.extrema.len());
            for (a, b) in r.curvature.extrema.iter().zip(&base.curvature.extrema) {
                assert!((a - b).abs() < 1e-12, "{p:?} {e}");
            }
            let (rt, bt) = (r.torsion.unwrap(), base.torsion.clone().unwrap());
            assert_eq!(rt.monotone, bt.monotone, "{p:?} {e}");
        }
    }
    let line: Vec<[f64; 3]> = (0..5)
        .map(|i| [i as f64, 2.0 * i as f64 + 0.5, -3.0])
        .collect();
    assert_eq!(
        SpaceBezier::new(line).unwrap().check().shape,
        SpaceShape::Straight
    );
    let p = random_curve(&mut rng, 20, None);
    let r = SpaceBezier::new(p).unwrap().check();
    assert!(!r.curvature.undecided && r.torsion.is_some_and(|t| !t.undecided));
    assert!(SpaceBezier::new(vec![[0.0; 3]; 22]).is_err());
    assert!(SpaceBezier::new(vec![[0.0, f64::NAN, 0.0], [1.0; 3]]).is_err());
}

/// A cubic arc of a helix (Hermite data of x = cos s, y = sin s, z = s/2 over a quarter
/// turn): twisted, no zero curvature, with curvature and torsion near the helix's 0.8 and
/// 0.4 in the middle.
#[test]
fn a_helix_arc_is_twisted_with_the_helixs_curvature_and_torsion() {
    let q = std::f64::consts::FRAC_PI_2;
    let h = q / 3.0;
    let p = vec![
        [1.0, 0.0, 0.0],
        [1.0, h, 0.5 * h],
        [
            q.cos() + h * q.sin(),
            q.sin() - h * q.cos(),
            0.5 * q - 0.5 * h,
        ],
        [q.cos(), q.sin(), 0.5 * q],
    ];
    let c = SpaceBezier::new(p).unwrap();
    let r = c.check();
    assert_eq!(r.shape, SpaceShape::Twisted);
    // The cubic's handles (a third of the arc) make its middle a little flat.
    assert!((c.curvature(0.5) - 0.8).abs() < 0.1, "{}", c.curvature(0.5));
    assert!((c.torsion(0.5) - 0.4).abs() < 0.1, "{}", c.torsion(0.5));
    assert!(!r.curvature.undecided && r.zero_curvature.is_empty());
}

fn random_weights(rng: &mut ChaCha8Rng, n: usize, spread: f64) -> Vec<f64> {
    (0..=n)
        .map(|_| rng.random_range(1.0 / spread..spread))
        .collect()
}

/// Planar rational curves in each coordinate plane against the plane's exact test of a
/// rational curve: the same extrema (the inflections aside), no torsion.
#[test]
fn planar_rational_curves_get_the_planes_verdict() {
    use aesthetic_curves::RationalBezier;
    let mut rng = ChaCha8Rng::seed_from_u64(0x2a7);
    for case in 0..150 {
        let n = 2 + case % 4;
        let plane = case % 3;
        let p = random_curve(&mut rng, n, Some(plane));
        let w = random_weights(&mut rng, n, 4.0);
        let (i, j) = ((plane + 1) % 3, (plane + 2) % 3);
        let flat: Vec<Point> = p.iter().map(|q| Point::new(q[i], q[j])).collect();
        let r2 = RationalBezier::new(flat, w.clone())
            .unwrap()
            .curvature_monotone()
            .unwrap();
        let r3 = SpaceBezier::rational(p.clone(), w.clone()).unwrap().check();
        assert_eq!(r3.shape, SpaceShape::Planar, "{p:?} {w:?}");
        let rest: Vec<f64> = (r3.curvature.extrema.iter())
            .copied()
            .filter(|t| !r3.zero_curvature.contains(t))
            .collect();
        assert_eq!(
            rest.len(),
            r2.extrema.len(),
            "{p:?} {w:?}: {r3:?} against {r2:?}"
        );
        for (a, b) in rest.iter().zip(&r2.extrema) {
            assert!((a - b).abs() < 1e-9, "{p:?} {w:?}: {a} against {b}");
        }
    }
}

/// A rational curve is the same curve with its weights times `λ^i` (a reparametrization,
/// `t/(1-t) = λ s/(1-s)`) and with all weights scaled: the same verdicts, the extrema at the
/// mapped parameters; and it agrees with 4,001 samples where they decide.
#[test]
fn rational_space_curves_keep_their_verdicts_under_reparametrization() {
    let mut rng = ChaCha8Rng::seed_from_u64(0x3a7);
    let (mut monotone, mut decided) = (0, 0);
    for case in 0..120 {
        let n = 3 + case % 3;
        // Wild curves with weights from 1/4 to 4, fair spirals with weights near 1.
        let (p, w) = if case % 2 == 0 {
            let p = random_curve(&mut rng, n, None);
            (p, random_weights(&mut rng, n, 4.0))
        } else {
            let p = spiral(&mut rng, n);
            (p, random_weights(&mut rng, n, 1.1))
        };
        let r = SpaceBezier::rational(p.clone(), w.clone()).unwrap().check();
        assert_eq!(r.shape, SpaceShape::Twisted, "{p:?} {w:?}");
        let lambda: f64 = 2.0;
        let w2: Vec<f64> = (w.iter().enumerate())
            .map(|(i, v)| v * lambda.powi(i as i32) * 0.125)
            .collect();
        let r2 = SpaceBezier::rational(p.clone(), w2).unwrap().check();
        assert_eq!(r2.shape, r.shape);
        assert_eq!(r2.curvature.monotone, r.curvature.monotone, "{p:?} {w:?}");
        assert_eq!(r2.curvature.extrema.len(), r.curvature.extrema.len());
        for (s, t) in r2.curvature.extrema.iter().zip(&r.curvature.extrema) {
            let mapped = lambda * s / (1.0 - s + lambda * s);
            assert!(
                (mapped - t).abs() < 1e-9,
                "{p:?} {w:?}: {mapped} against {t}"
            );
        }
        let (t1, t2) = (r.torsion.clone().unwrap(), r2.torsion.unwrap());
        assert_eq!(t1.monotone, t2.monotone, "{p:?} {w:?}");
        assert_eq!(t1.extrema.len(), t2.extrema.len(), "{p:?} {w:?}");
        // Samples of the rational curve, from its homogeneous power basis.
        let c = SpaceBezier::rational(p.clone(), w.clone()).unwrap();
        let k: Vec<f64> = (0..=4000)
            .map(|i| rational_curvature(&p, &w, i as f64 / 4000.0))
            .collect();
        if turns_back(&k, 1e-6) {
            assert!(!r.curvature.monotone, "{p:?} {w:?}");
        }
        if r.curvature.monotone {
            assert!(!turns_back(&k, 1e-3), "{p:?} {w:?}");
        }
        // The library's own evaluation agrees with the test's.
        let mid = rational_curvature(&p, &w, 0.37);
        assert!(
            (c.curvature(0.37) - mid).abs() <= 1e-9 * mid.max(1e-300),
            "{p:?}"
        );
        monotone += usize::from(r.curvature.monotone);
        decided += usize::from(!r.curvature.undecided);
    }
    println!("of 120 rational curves: curvature monotone {monotone}, decided {decided}");
    assert!(
        monotone > 5 && monotone < 115 && decided == 120,
        "{monotone} {decided}"
    );
}

/// The curvature of the rational curve at `t` from the power basis of `P = Σ w_i b_i` and
/// `W` (quotient rule), not the library's.
fn rational_curvature(p: &[[f64; 3]], w: &[f64], t: f64) -> f64 {
    let weighted: Vec<[f64; 3]> = p.iter().zip(w).map(|(q, w)| q.map(|x| x * w)).collect();
    let ws: Vec<[f64; 3]> = w.iter().map(|v| [*v, 0.0, 0.0]).collect();
    let value = |pts: &[[f64; 3]]| -> [f64; 3] {
        let n = pts.len() - 1;
        let binom = |n: usize, k: usize| -> f64 {
            (0..k).fold(1.0, |c, i| c * (n - i) as f64 / (i + 1) as f64)
        };
        let mut out = [0.0; 3];
        for (i, q) in pts.iter().enumerate() {
            let b = binom(n, i) * t.powi(i as i32) * (1.0 - t).powi((n - i) as i32);
            for k in 0..3 {
                out[k] += b * q[k];
            }
        }
        out
    };
    let (p0, pd) = (value(&weighted), derivs(&weighted, t));
    let (w0, wd) = (value(&ws)[0], derivs(&ws, t).map(|v| v[0]));
    let r1: [f64; 3] = std::array::from_fn(|k| (pd[0][k] - wd[0] * p0[k] / w0) / w0);
    let r0: [f64; 3] = std::array::from_fn(|k| p0[k] / w0);
    let r2: [f64; 3] =
        std::array::from_fn(|k| (pd[1][k] - 2.0 * wd[0] * r1[k] - wd[1] * r0[k]) / w0);
    let c = cross(r1, r2);
    dot(c, c).sqrt() / dot(r1, r1).powf(1.5)
}

/// Weights a hair from equal (one of them 1 + 2^-30) give the polynomial curve's verdicts,
/// the directions of a monotone curvature and torsion included: the rational formula's
/// signs are the polynomial one's.
#[test]
fn nearly_equal_weights_give_the_polynomial_verdicts() {
    let mut rng = ChaCha8Rng::seed_from_u64(0x4a7);
    let mut compared = 0;
    for case in 0..80 {
        let n = 3 + case % 3;
        let p = spiral(&mut rng, n);
        let poly = SpaceBezier::new(p.clone()).unwrap().check();
        let mut w = vec![1.0; n + 1];
        w[case % (n + 1)] += 2f64.powi(-30);
        let rat = SpaceBezier::rational(p.clone(), w).unwrap().check();
        assert!(SpaceBezier::rational(p.clone(), vec![1.0; n + 1])
            .unwrap()
            .weights()
            .is_none());
        assert_eq!(rat.shape, poly.shape);
        if poly.curvature.monotone && poly.curvature.extrema.is_empty() {
            assert_eq!(rat.curvature.increasing, poly.curvature.increasing, "{p:?}");
            compared += 1;
        }
        let (pt, rt) = (poly.torsion.unwrap(), rat.torsion.unwrap());
        if pt.monotone && pt.extrema.is_empty() {
            assert_eq!(rt.increasing, pt.increasing, "{p:?}");
            compared += 1;
        }
    }
    assert!(compared > 40, "{compared}");
}
