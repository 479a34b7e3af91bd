//! α that means the shape: exact samples of a log-aesthetic curve (one segment, or two
//! mirrored segments joined at their curvature peak) come back with the α they were drawn
//! with, at any density, turning and tolerance; where the points cannot tell α apart, the
//! result says so.
//!
//! The samples come from this file's own generator (the curve's radius of curvature as a
//! function of arc length, integrated by Gauss–Legendre quadrature), which shares no code
//! with the library's LAC segments.

use aesthetic_curves::sketch::{default_tolerance, fit_sketch, SketchOptions};
use aesthetic_curves::Point;

/// A log-aesthetic curve by its natural equation: ρ(u)^α = 1 + α u (ρ = eᵘ at α = 0) with
/// u = Λ s, from the radius 1 at u = 0 to the radius `ratio` (> 1: the curvature falls).
struct Lac {
    alpha: f64,
    /// The end of u where ρ = ratio.
    u_end: f64,
    /// Λ: u per unit of arc length, chosen so that the curve turns `turning`.
    lambda: f64,
}

impl Lac {
    fn new(alpha: f64, ratio: f64, turning: f64) -> Self {
        let u_end = if alpha.abs() < 1e-12 {
            ratio.ln()
        } else {
            (ratio.powf(alpha) - 1.0) / alpha
        };
        let mut lac = Lac {
            alpha,
            u_end,
            lambda: 1.0,
        };
        // θ(u) = (1/Λ) ∫ du / ρ(u): the turning at Λ = 1, then Λ scales it.
        lac.lambda = lac.theta_unit(u_end) / turning;
        lac
    }

    fn rho(&self, u: f64) -> f64 {
        if self.alpha.abs() < 1e-12 {
            u.exp()
        } else {
            (1.0 + self.alpha * u).powf(1.0 / self.alpha)
        }
    }

    /// ∫₀ᵘ dv / ρ(v), in closed form.
    fn theta_unit(&self, u: f64) -> f64 {
        let a = self.alpha;
        if a.abs() < 1e-12 {
            1.0 - (-u).exp()
        } else if (a - 1.0).abs() < 1e-12 {
            (1.0 + u).ln()
        } else {
            ((1.0 + a * u).powf(1.0 - 1.0 / a) - 1.0) / (a - 1.0)
        }
    }

    /// Tangent angle at arc length s (θ(0) = 0).
    fn theta(&self, s: f64) -> f64 {
        self.theta_unit(self.lambda * s) / self.lambda
    }

    fn length(&self) -> f64 {
        self.u_end / self.lambda
    }

    /// Curvature at arc length s.
    fn kappa(&self, s: f64) -> f64 {
        self.lambda / self.rho(self.lambda * s)
    }

    /// Points at arc lengths `s` (increasing from 0), integrating (cos θ, sin θ) by 8-point
    /// Gauss–Legendre on 64 panels between neighbours.
    fn points(&self, s: &[f64]) -> Vec<Point> {
        const X: [f64; 4] = [
            0.183_434_642_495_649_8,
            0.525_532_409_916_329,
            0.796_666_477_413_626_7,
            0.960_289_856_497_536_3,
        ];
        const W: [f64; 4] = [
            0.362_683_783_378_362,
            0.313_706_645_877_887_3,
            0.222_381_034_453_374_5,
            0.101_228_536_290_376_3,
        ];
        let mut out = Vec::with_capacity(s.len());
        let (mut x, mut y, mut at) = (0.0, 0.0, 0.0);
        for &to in s {
            let panels = 64;
            let h = (to - at) / panels as f64;
            for k in 0..panels {
                let mid = at + h * (k as f64 + 0.5);
                for (xi, w) in X.iter().zip(W) {
                    for sgn in [-1.0, 1.0] {
                        let t = self.theta(mid + sgn * xi * h / 2.0);
                        x += w * h / 2.0 * t.cos();
                        y += w * h / 2.0 * t.sin();
                    }
                }
            }
            at = to;
            out.push(Point::new(x, y));
        }
        out
    }
}

/// A fixed-seed generator in [0, 1).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// Arc lengths of `n` samples over [0, len]: even, or jittered (a hand's uneven spacing).
fn stations(n: usize, len: f64, rng: &mut Lcg, even: bool) -> Vec<f64> {
    (0..n)
        .map(|k| {
            let j = if even || k == 0 || k + 1 == n {
                0.0
            } else {
                rng.range(-0.4, 0.4)
            };
            len * (k as f64 + j) / (n - 1) as f64
        })
        .collect()
}

/// One case: the points, and the α of each piece they were drawn with.
struct Case {
    name: String,
    points: Vec<Point>,
    alpha: f64,
    pieces: usize,
}

/// A single segment (curvature falling along the points, or rising: reversed), or a bump
/// (the segment mirrored across its normal at the curvature peak), rotated and placed.
fn case(rng: &mut Lcg, bump: bool) -> Case {
    let alpha = (rng.range(-3.0, 3.0) * 4.0).round() / 4.0;
    let turning = rng.range(10.0, 150.0).to_radians();
    let ratio = rng.range(1.5, 12.0);
    let n = [12, 25, 60, 200, 1000][(rng.next() * 5.0) as usize];
    let even = rng.next() < 0.5;
    let lac = Lac::new(alpha, ratio, if bump { turning / 2.0 } else { turning });
    let len = lac.length();
    let mut pts = if bump {
        let half = n / 2 + 1;
        let s = stations(half, len, rng, even);
        let right = lac.points(&s);
        let mut all: Vec<Point> = right
            .iter()
            .skip(1)
            .rev()
            .map(|q| Point::new(-q.x, q.y))
            .collect();
        all.extend(right);
        all
    } else {
        let s = stations(n, len, rng, even);
        let mut p = lac.points(&s);
        if rng.next() < 0.5 {
            p.reverse();
        }
        p
    };
    let scale = rng.range(20.0, 800.0) / len;
    let rot = rng.range(0.0, std::f64::consts::TAU);
    let (c, s) = (rot.cos(), rot.sin());
    let off = (rng.range(-500.0, 500.0), rng.range(-500.0, 500.0));
    for q in &mut pts {
        let (x, y) = (q.x * scale, q.y * scale);
        *q = Point::new(off.0 + c * x - s * y, off.1 + s * x + c * y);
    }
    let _ = lac.kappa(0.0);
    Case {
        name: format!(
            "{} alpha {alpha} turning {:.0} ratio {ratio:.1} n {} {}",
            if bump { "bump" } else { "single" },
            turning.to_degrees(),
            pts.len(),
            if even { "even" } else { "uneven" }
        ),
        points: pts,
        alpha,
        pieces: if bump { 2 } else { 1 },
    }
}

fn size(points: &[Point]) -> f64 {
    let (mut lo, mut hi) = (points[0], points[0]);
    for q in points {
        lo = Point::new(lo.x.min(q.x), lo.y.min(q.y));
        hi = Point::new(hi.x.max(q.x), hi.y.max(q.y));
    }
    (hi - lo).hypot()
}

/// How a piece's α stands against the truth.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Verdict {
    /// Said determined, and within 0.05 of the truth.
    Pinned,
    /// Said undetermined, with the truth inside its range (within 0.05).
    Undetermined,
    /// Said determined but off, or its range misses the truth.
    Wrong,
}

fn judge(p: &aesthetic_curves::sketch::SketchPiece, truth: f64) -> Verdict {
    let (lo, hi) = p.alpha_range.unwrap_or((p.alpha, p.alpha));
    let inside = truth >= lo - 0.05 && truth <= hi + 0.05;
    if (p.alpha - truth).abs() <= 0.05 && p.alpha_determined() {
        Verdict::Pinned
    } else if !p.alpha_determined() && inside {
        Verdict::Undetermined
    } else {
        Verdict::Wrong
    }
}

/// What a sweep found at one tolerance.
#[derive(Default, Debug)]
struct Tally {
    answered: usize,
    errors: usize,
    /// In as many pieces as drawn (1, or 2 for a bump).
    as_drawn: usize,
    /// Cases by their worst piece's verdict.
    pinned: usize,
    undetermined: usize,
    wrong: usize,
}

/// The tolerances of a sweep: the default, then 1e-3, 1e-4 and 1e-5 of the size.
const TOLERANCES: [&str; 4] = ["default", "1e-3 of the size", "1e-4", "1e-5"];

/// `count` cases from the seed, fitted at the first `tolerances` of [`TOLERANCES`];
/// `probe` prints one case's pieces.
fn sweep(count: usize, tolerances: usize, probe: Option<usize>) -> Vec<Tally> {
    let mut rng = Lcg(7);
    let mut tally: Vec<Tally> = (0..tolerances).map(|_| Tally::default()).collect();
    for k in 0..count {
        let c = case(&mut rng, k % 2 == 1);
        if probe.is_some_and(|p| p != k) {
            continue;
        }
        let d = size(&c.points);
        let all = [default_tolerance(&c.points), 1e-3 * d, 1e-4 * d, 1e-5 * d];
        for (ti, tol) in all.into_iter().take(tolerances).enumerate() {
            let t = &mut tally[ti];
            let sk = match fit_sketch(&c.points, &SketchOptions::with_tolerance(tol)) {
                Ok(sk) => sk,
                Err(e) => {
                    t.errors += 1;
                    println!("#{k} {} at {}: error {e}", c.name, TOLERANCES[ti]);
                    continue;
                }
            };
            let verdict = sk
                .pieces
                .iter()
                .map(|p| judge(p, c.alpha))
                .max()
                .unwrap_or(Verdict::Wrong);
            t.answered += 1;
            t.as_drawn += usize::from(sk.pieces.len() == c.pieces);
            match verdict {
                Verdict::Pinned => t.pinned += 1,
                Verdict::Undetermined => t.undetermined += 1,
                Verdict::Wrong => t.wrong += 1,
            }
            if verdict == Verdict::Wrong || probe.is_some() {
                let alphas: Vec<String> = sk
                    .pieces
                    .iter()
                    .map(|p| match p.alpha_range {
                        Some((lo, hi)) if !p.alpha_determined() => {
                            format!("{:.2} in [{lo:.2}, {hi:.2}]", p.alpha)
                        }
                        _ => format!("{:.2}", p.alpha),
                    })
                    .collect();
                println!(
                    "#{k} {} at {}: {} pieces, alpha {}",
                    c.name,
                    TOLERANCES[ti],
                    sk.pieces.len(),
                    alphas.join(", ")
                );
            }
        }
    }
    for (name, t) in TOLERANCES.iter().zip(&tally) {
        println!(
            "at {name}: {} answered ({} errors), {} in as many pieces as drawn; alpha: {} pinned \
             within 0.05, {} said undetermined with the truth inside, {} wrong",
            t.answered, t.errors, t.as_drawn, t.pinned, t.undetermined, t.wrong
        );
    }
    tally
}

/// 160 cases (80 single segments, 80 bumps; α from -3 to 3, turning 10° to 150°, 12 to
/// 1,001 points, even and uneven) at the default tolerance and at 1e-3 of the size: every
/// one answered, and every piece's α either within 0.05 of the truth and said determined,
/// or said undetermined with the truth inside its range, but for the measured few (3 and 2
/// of 160: the fit's cut or tangents off, its range then around another α). Before the α
/// ranges and the tight spline for a curve's coarse samples, 21 and 20 of 40 cases came
/// back with every α within 0.05 in as many pieces as drawn.
#[test]
fn exact_samples_come_back_with_their_alpha_or_say_it_is_undetermined() {
    let tally = sweep(160, 2, None);
    for (name, t, floor) in [(TOLERANCES[0], &tally[0], 3), (TOLERANCES[1], &tally[1], 2)] {
        assert_eq!(t.errors, 0, "at {name}");
        assert!(t.wrong <= floor, "at {name}: {} wrong", t.wrong);
        assert!(t.pinned >= t.undetermined, "at {name}: {t:?}");
    }
}

/// The whole sweep: `ALPHA_CASES` cases (default 300) at all four tolerances;
/// `ALPHA_PROBE=k` prints case k's pieces.
#[test]
#[ignore = "a report: the sketch fit's alpha on exact LAC samples at four tolerances"]
fn report_alpha_of_exact_samples() {
    let env = |name: &str| std::env::var(name).ok().and_then(|v| v.parse().ok());
    sweep(env("ALPHA_CASES").unwrap_or(300), 4, env("ALPHA_PROBE"));
}
