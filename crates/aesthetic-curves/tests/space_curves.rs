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
