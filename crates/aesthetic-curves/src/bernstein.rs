//! Polynomials in Bernstein form on [0, 1].
//!
//! `p(t) = sum_{i=0..m} c_i B_i^m(t)`, `B_i^m(t) = C(m,i) t^i (1-t)^(m-i)`.
//!
//! Everything here works on the coefficients directly and stays in Bernstein form, which is
//! numerically far better behaved on [0, 1] than the power basis: evaluation and subdivision
//! by de Casteljau (convex combinations only), products by the Bernstein product formula,
//! degree elevation by convex combinations.
//!
//! ## Sign analysis with rounding bounds
//!
//! [`analyze_signs`] decides where a polynomial is positive, negative or zero *up to
//! rounding*. It takes, beside the coefficients, a bound on the rounding error of each
//! coefficient (the caller computes it by running the same arithmetic on absolute values, see
//! [`Bernstein::abs`]). A coefficient within its bound counts as zero. The algorithm:
//!
//! 1. all coefficients `>= -noise`, or all `<= noise`: the sign is settled on the interval
//!    (convex hull property);
//! 2. the strict signs show exactly one variation and the zero-within-noise coefficients sit
//!    only between the two runs: exactly one sign change (Descartes' rule for the Bernstein
//!    basis); the root is refined by the Illinois method ([`crate::solve::roots::illinois`]) to
//!    `1e-15` in t;
//! 3. otherwise split at 1/2 (de Casteljau) and recurse, to a depth limit; a piece that is
//!    still undecided there is a piece where the polynomial is zero within rounding
//!    (a root of even multiplicity, a cluster of roots closer than `2^-depth`).
//!
//! Sign changes are reported only between strictly positive and strictly negative pieces, so a
//! polynomial that touches zero without changing sign has none.
//!
//! This is *numerical* root finding: "within its bound counts as zero" is a choice, not a
//! proof, and suits the places that only need where a floating-point function is near zero
//! (the sketch pipeline's split points). Every monotonicity verdict and every reported
//! extremum or inflection comes instead from [`crate::exact::certified_signs`], where a
//! coefficient within its bound has an unknown sign and exact arithmetic decides it.

use smallvec::SmallVec;

/// Coefficient storage: inline for the degrees that matter most (cubics to quintics),
/// on the heap beyond.
pub type Coeffs = SmallVec<[f64; 16]>;

/// The largest degree the binomial table supports.
pub const MAX_DEGREE: usize = 200;

const BINOM_N: usize = MAX_DEGREE + 1;

const fn build_binomials() -> [[f64; BINOM_N]; BINOM_N] {
    let mut t = [[0.0f64; BINOM_N]; BINOM_N];
    let mut n = 0;
    while n < BINOM_N {
        t[n][0] = 1.0;
        let mut k = 1;
        while k <= n {
            t[n][k] = t[n - 1][k - 1] + if k < n { t[n - 1][k] } else { 0.0 };
            k += 1;
        }
        n += 1;
    }
    t
}

static BINOM: [[f64; BINOM_N]; BINOM_N] = build_binomials();

/// Binomial coefficient C(n, k) as f64 (exact up to n = 56, correctly rounded-ish beyond).
#[inline]
pub fn binomial(n: usize, k: usize) -> f64 {
    if k > n {
        0.0
    } else {
        BINOM[n][k]
    }
}

/// A polynomial in Bernstein form on [0, 1]. The degree is the number of coefficients
/// minus one; there is always at least one coefficient.
#[derive(Clone, Debug, PartialEq)]
pub struct Bernstein {
    c: Coeffs,
}

impl Bernstein {
    /// A polynomial from its Bernstein coefficients. An empty slice gives the zero constant.
    pub fn new(coeffs: &[f64]) -> Self {
        if coeffs.is_empty() {
            return Self::constant(0.0);
        }
        Bernstein {
            c: Coeffs::from_slice(coeffs),
        }
    }

    /// A polynomial from owned coefficients (see [`Bernstein::new`]).
    pub fn from_coeffs(c: Coeffs) -> Self {
        if c.is_empty() {
            return Self::constant(0.0);
        }
        Bernstein { c }
    }

    /// The constant polynomial `v` (degree 0).
    pub fn constant(v: f64) -> Self {
        let mut c = Coeffs::new();
        c.push(v);
        Bernstein { c }
    }

    /// The nominal degree (number of coefficients minus one).
    #[inline]
    pub fn degree(&self) -> usize {
        self.c.len() - 1
    }

    /// The Bernstein coefficients.
    #[inline]
    pub fn coeffs(&self) -> &[f64] {
        &self.c
    }

    /// Value at `t` by de Casteljau's algorithm (stable for t in [0, 1]; extrapolates outside).
    pub fn eval(&self, t: f64) -> f64 {
        de_casteljau(&self.c, t)
    }

    /// The derivative, of degree m-1 (the zero constant for a constant).
    pub fn deriv(&self) -> Bernstein {
        let m = self.degree();
        if m == 0 {
            return Self::constant(0.0);
        }
        let mf = m as f64;
        Bernstein {
            c: self.c.windows(2).map(|w| mf * (w[1] - w[0])).collect(),
        }
    }

    /// The same polynomial written with degree `m + r`.
    pub fn elevate(&self, r: usize) -> Bernstein {
        if r == 0 {
            return self.clone();
        }
        let m = self.degree();
        let n = m + r;
        let mut out = Coeffs::with_capacity(n + 1);
        for k in 0..=n {
            let lo = k.saturating_sub(r);
            let hi = k.min(m);
            let mut s = 0.0;
            for i in lo..=hi {
                s += binomial(m, i) * binomial(r, k - i) * self.c[i];
            }
            out.push(s / binomial(n, k));
        }
        Bernstein { c: out }
    }

    /// The product, of degree m + n, by the Bernstein product formula.
    pub fn mul(&self, other: &Bernstein) -> Bernstein {
        let m = self.degree();
        let n = other.degree();
        let mut out: Coeffs = SmallVec::from_elem(0.0, m + n + 1);
        let bm = &BINOM[m];
        let bn = &BINOM[n];
        for (i, &a) in self.c.iter().enumerate() {
            let ai = a * bm[i];
            for (j, &b) in other.c.iter().enumerate() {
                out[i + j] += ai * bn[j] * b;
            }
        }
        let bmn = &BINOM[m + n];
        for (k, v) in out.iter_mut().enumerate() {
            *v /= bmn[k];
        }
        Bernstein { c: out }
    }

    /// `self * s`.
    pub fn scale(&self, s: f64) -> Bernstein {
        Bernstein {
            c: self.c.iter().map(|v| v * s).collect(),
        }
    }

    /// `self + s * other`, elevating the lower degree to the higher one.
    pub fn add_scaled(&self, other: &Bernstein, s: f64) -> Bernstein {
        let (m, n) = (self.degree(), other.degree());
        let a = if m < n {
            self.elevate(n - m)
        } else {
            self.clone()
        };
        let b = if n < m {
            other.elevate(m - n)
        } else {
            other.clone()
        };
        Bernstein {
            c: a.c.iter().zip(b.c.iter()).map(|(x, y)| x + s * y).collect(),
        }
    }

    /// `self + other`.
    pub fn add(&self, other: &Bernstein) -> Bernstein {
        self.add_scaled(other, 1.0)
    }

    /// `self - other`.
    pub fn sub(&self, other: &Bernstein) -> Bernstein {
        self.add_scaled(other, -1.0)
    }

    /// The polynomial whose coefficients are the absolute values of these. Running an
    /// expression on `abs()` operands (with every subtraction turned into an addition) bounds
    /// the magnitude of every term that went into each result coefficient, hence its rounding.
    pub fn abs(&self) -> Bernstein {
        Bernstein {
            c: self.c.iter().map(|v| v.abs()).collect(),
        }
    }

    /// Split at `t`: the polynomials on [0, t] and [t, 1], each reparametrised to [0, 1].
    pub fn subdivide(&self, t: f64) -> (Bernstein, Bernstein) {
        let (l, r) = subdivide_coeffs(&self.c, t);
        (Bernstein { c: l }, Bernstein { c: r })
    }

    /// The polynomial restricted to [a, b] and reparametrised to [0, 1].
    pub fn restrict(&self, a: f64, b: f64) -> Bernstein {
        // [a, b] = right part of [0, b] at a/b.
        let (left, _) = self.subdivide(b);
        if b == 0.0 {
            return Bernstein::new(&vec![self.eval(0.0); self.c.len()]);
        }
        let (_, mid) = left.subdivide(a / b);
        mid
    }

    /// The power-basis coefficients `a_k` with `p(t) = sum a_k t^k`.
    pub fn to_power(&self) -> Vec<f64> {
        let m = self.degree();
        (0..=m)
            .map(|k| {
                let mut s = 0.0;
                for i in 0..=k {
                    let sign = if (k - i) % 2 == 0 { 1.0 } else { -1.0 };
                    s += sign * binomial(k, i) * self.c[i];
                }
                binomial(m, k) * s
            })
            .collect()
    }

    /// From power-basis coefficients `a_k` (p(t) = sum a_k t^k) to Bernstein form of the
    /// same degree.
    pub fn from_power(a: &[f64]) -> Bernstein {
        if a.is_empty() {
            return Self::constant(0.0);
        }
        let m = a.len() - 1;
        Bernstein {
            c: (0..=m)
                .map(|i| {
                    (0..=i)
                        .map(|k| binomial(i, k) / binomial(m, k) * a[k])
                        .sum()
                })
                .collect(),
        }
    }

    /// Reduce the degree by one, assuming the polynomial's true degree is below its nominal
    /// one (its top power coefficient cancels analytically). Coefficients come from both ends
    /// (forward recurrence on the first half, backward on the second) to limit error growth.
    /// Returns the reduced polynomial and, when `noise` is given, the matching error bounds.
    pub fn reduce_degree_exact(&self, noise: Option<&Bernstein>) -> (Bernstein, Option<Bernstein>) {
        let m = self.degree();
        if m == 0 {
            return (self.clone(), noise.cloned());
        }
        let mf = m as f64;
        let mut d: Coeffs = SmallVec::from_elem(0.0, m);
        let mut e: Coeffs = SmallVec::from_elem(0.0, m);
        let nz = noise.map(|b| b.coeffs());
        let half = m / 2;
        // forward: c_i = (i/m) d_{i-1} + (1 - i/m) d_i
        for i in 0..half.max(1).min(m) {
            let prev = if i == 0 { 0.0 } else { d[i - 1] };
            let prev_e = if i == 0 { 0.0 } else { e[i - 1] };
            let fi = i as f64;
            d[i] = (mf * self.c[i] - fi * prev) / (mf - fi);
            if let Some(nz) = nz {
                e[i] = (mf * nz[i] + fi * prev_e) / (mf - fi);
            }
        }
        // backward: d_{i-1} = (m c_i - (m-i) d_i) / i
        let start = half.max(1).min(m);
        for i in (start + 1..=m).rev() {
            let next = if i == m { 0.0 } else { d[i] };
            let next_e = if i == m { 0.0 } else { e[i] };
            let fi = i as f64;
            d[i - 1] = (mf * self.c[i] - (mf - fi) * next) / fi;
            if let Some(nz) = nz {
                e[i - 1] = (mf * nz[i] + (mf - fi) * next_e) / fi;
            }
        }
        (Bernstein { c: d }, noise.map(|_| Bernstein { c: e }))
    }
}

/// de Casteljau evaluation of Bernstein coefficients at t.
pub fn de_casteljau(c: &[f64], t: f64) -> f64 {
    let n = c.len();
    if n == 0 {
        return 0.0;
    }
    if n <= 32 {
        let mut buf = [0.0f64; 32];
        buf[..n].copy_from_slice(c);
        casteljau_in_place(&mut buf[..n], t)
    } else {
        let mut buf = c.to_vec();
        casteljau_in_place(&mut buf, t)
    }
}

#[inline]
fn casteljau_in_place(b: &mut [f64], t: f64) -> f64 {
    let n = b.len();
    let s = 1.0 - t;
    for k in 1..n {
        for i in 0..n - k {
            b[i] = s * b[i] + t * b[i + 1];
        }
    }
    b[0]
}

/// Split coefficients at t into the coefficients on [0, t] and [t, 1].
pub fn subdivide_coeffs(c: &[f64], t: f64) -> (Coeffs, Coeffs) {
    let n = c.len();
    let mut work: Coeffs = Coeffs::from_slice(c);
    let mut left = Coeffs::with_capacity(n);
    let mut right: Coeffs = SmallVec::from_elem(0.0, n);
    let s = 1.0 - t;
    left.push(work[0]);
    right[n - 1] = work[n - 1];
    for k in 1..n {
        for i in 0..n - k {
            work[i] = s * work[i] + t * work[i + 1];
        }
        left.push(work[0]);
        right[n - 1 - k] = work[n - 1 - k];
    }
    (left, right)
}

/// Sign of a polynomial on a piece of [0, 1], up to rounding.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sign {
    /// Strictly positive somewhere, never below minus its rounding bound.
    Positive,
    /// Strictly negative somewhere, never above its rounding bound.
    Negative,
    /// Zero within rounding on the whole piece.
    Zero,
}

/// One piece of [0, 1] with a settled sign.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SignPiece {
    /// Start of the piece.
    pub a: f64,
    /// End of the piece.
    pub b: f64,
    /// The sign there.
    pub sign: Sign,
}

/// Result of [`analyze_signs`].
#[derive(Clone, Debug, Default)]
pub struct SignAnalysis {
    /// Pieces covering [0, 1] in order (adjacent pieces of the same sign are merged).
    pub pieces: Vec<SignPiece>,
    /// Parameters in (0, 1) where the sign changes between strictly positive and strictly
    /// negative, sorted.
    pub changes: Vec<f64>,
}

impl SignAnalysis {
    /// Whether some piece is strictly positive.
    pub fn has_positive(&self) -> bool {
        self.pieces.iter().any(|p| p.sign == Sign::Positive)
    }
    /// Whether some piece is strictly negative.
    pub fn has_negative(&self) -> bool {
        self.pieces.iter().any(|p| p.sign == Sign::Negative)
    }
}

/// Options of the subdivision.
#[derive(Clone, Copy, Debug)]
pub struct SignOptions {
    /// Subdivision depth limit (pieces of width `2^-max_depth` that are still undecided count
    /// as zero within rounding).
    pub max_depth: u32,
    /// Stop as soon as both strict signs were seen (no full root list).
    pub stop_at_both_signs: bool,
}

impl Default for SignOptions {
    fn default() -> Self {
        SignOptions {
            max_depth: 44,
            stop_at_both_signs: false,
        }
    }
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum CoefSign {
    Pos,
    Neg,
    Zero,
}

/// What the coefficients alone prove about a polynomial on its whole interval.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Classified {
    /// One sign (or zero within rounding) throughout.
    Settled(Sign),
    /// Exactly one sign change; the sign at the start of the interval.
    OneChange(Sign),
    /// Needs subdivision.
    Undecided,
}

/// Classify coefficients with rounding bounds without subdividing (the first step of
/// [`analyze_signs`]).
pub fn classify(c: &[f64], noise: &[f64]) -> Classified {
    let mut any_pos = false;
    let mut any_neg = false;
    for (v, e) in c.iter().zip(noise) {
        if *v > *e {
            any_pos = true;
        } else if *v < -*e {
            any_neg = true;
        }
    }
    match (any_pos, any_neg) {
        (false, false) => return Classified::Settled(Sign::Zero),
        (true, false) => return Classified::Settled(Sign::Positive),
        (false, true) => return Classified::Settled(Sign::Negative),
        _ => {}
    }
    let sg = |i: usize| -> CoefSign {
        if c[i] > noise[i] {
            CoefSign::Pos
        } else if c[i] < -noise[i] {
            CoefSign::Neg
        } else {
            CoefSign::Zero
        }
    };
    let m = c.len() - 1;
    let s0 = sg(0);
    let sm = sg(m);
    if s0 == CoefSign::Zero || sm == CoefSign::Zero || s0 == sm {
        return Classified::Undecided;
    }
    // Exactly one variation: a run of s0 (zeros allowed only after its last strict
    // coefficient), then a run of sm.
    let mut i = 0;
    while i <= m && sg(i) == s0 {
        i += 1;
    }
    while i <= m && sg(i) == CoefSign::Zero {
        i += 1;
    }
    while i <= m && sg(i) == sm {
        i += 1;
    }
    if i == m + 1 {
        Classified::OneChange(if s0 == CoefSign::Pos {
            Sign::Positive
        } else {
            Sign::Negative
        })
    } else {
        Classified::Undecided
    }
}

/// Refine the single sign change of `c` on [0, 1] (c(0) and c(1) of opposite strict sign)
/// with [`crate::solve::roots::illinois`]. It cannot fail: the bracket straddles the change and
/// every fourth step bisects, so 400 steps reach the tolerance.
fn refine_root(c: &[f64]) -> f64 {
    let (f0, f1) = (c[0], c[c.len() - 1]);
    crate::solve::roots::illinois(|x| Ok(de_casteljau(c, x)), (0.0, f0), (1.0, f1), 1e-15, 400)
        .unwrap_or(0.5)
}

fn opposite(s: Sign) -> Sign {
    match s {
        Sign::Positive => Sign::Negative,
        Sign::Negative => Sign::Positive,
        Sign::Zero => Sign::Zero,
    }
}

struct Walker {
    opts: SignOptions,
    pieces: Vec<SignPiece>,
    seen_pos: bool,
    seen_neg: bool,
}

impl Walker {
    fn push(&mut self, a: f64, b: f64, sign: Sign) {
        match sign {
            Sign::Positive => self.seen_pos = true,
            Sign::Negative => self.seen_neg = true,
            Sign::Zero => {}
        }
        if let Some(last) = self.pieces.last_mut() {
            if last.sign == sign && last.b == a {
                last.b = b;
                return;
            }
        }
        self.pieces.push(SignPiece { a, b, sign });
    }

    fn done(&self) -> bool {
        self.opts.stop_at_both_signs && self.seen_pos && self.seen_neg
    }

    fn walk(&mut self, c: &[f64], noise: &[f64], a: f64, b: f64, depth: u32) {
        if self.done() {
            return;
        }
        match classify(c, noise) {
            Classified::Settled(s) => self.push(a, b, s),
            Classified::OneChange(first) if self.opts.stop_at_both_signs => {
                // Both signs are present: the location does not matter for the verdict.
                self.push(a, 0.5 * (a + b), first);
                self.push(0.5 * (a + b), b, opposite(first));
            }
            Classified::OneChange(first) => {
                let r = refine_root(c);
                let t = a + (b - a) * r;
                self.push(a, t, first);
                self.push(t, b, opposite(first));
            }
            Classified::Undecided => {
                if depth >= self.opts.max_depth {
                    self.push(a, b, Sign::Zero);
                    return;
                }
                let (l, r) = subdivide_coeffs(c, 0.5);
                // Noise bounds subdivide as convex combinations; the new rounding (a few ulps
                // of the magnitudes) is covered by a small relative inflation.
                let (mut nl, mut nr) = subdivide_coeffs(noise, 0.5);
                for v in nl.iter_mut().chain(nr.iter_mut()) {
                    *v *= 1.0 + 1e-15;
                }
                let mid = 0.5 * (a + b);
                self.walk(&l, &nl, a, mid, depth + 1);
                self.walk(&r, &nr, mid, b, depth + 1);
            }
        }
    }
}

/// Settle the sign of a polynomial on [0, 1] piece by piece and locate its sign changes.
///
/// `noise[i]` bounds the rounding error of `c[i]` (same length as `c`); coefficients within
/// it count as zero. See the module documentation for the algorithm.
pub fn analyze_signs(c: &[f64], noise: &[f64], opts: SignOptions) -> SignAnalysis {
    assert_eq!(
        c.len(),
        noise.len(),
        "coefficients and noise bounds differ in length"
    );
    let mut w = Walker {
        opts,
        pieces: Vec::new(),
        seen_pos: false,
        seen_neg: false,
    };
    if !c.is_empty() {
        w.walk(c, noise, 0.0, 1.0, 0);
    }
    let changes = sign_changes(&w.pieces, c);
    SignAnalysis {
        pieces: w.pieces,
        changes,
    }
}

/// Where consecutive strict pieces have opposite signs. A piece is settled up to rounding, so
/// the crossing may sit near the boundary inside either piece (a coefficient within its bound
/// can still be of the other sign): it is located by bisection on the values of `c` between
/// the middles of the two pieces when the values there differ in sign, else at their common
/// end (or the middle of the zero-within-rounding stretch between them).
fn sign_changes(pieces: &[SignPiece], c: &[f64]) -> Vec<f64> {
    let mut out = Vec::new();
    let mut last: Option<SignPiece> = None;
    for p in pieces {
        if p.sign == Sign::Zero {
            continue;
        }
        if let Some(q) = last {
            if q.sign != p.sign {
                let guess = if q.b == p.a { q.b } else { 0.5 * (q.b + p.a) };
                // From the middle of one piece to the middle of the next: brackets of
                // successive changes never overlap.
                let (lo, hi) = (0.5 * (q.a + q.b), 0.5 * (p.a + p.b));
                out.push(bisect_values(c, lo, hi).unwrap_or(guess));
            }
        }
        last = Some(*p);
    }
    out
}

/// A sign change of the polynomial's values in [lo, hi] when the ends differ in sign: the
/// solver layer's bisection on "the value has the sign of the value at lo" (an exact zero
/// ends it there), to the resolution of f64.
fn bisect_values(c: &[f64], lo: f64, hi: f64) -> Option<f64> {
    let flo = de_casteljau(c, lo);
    let fhi = de_casteljau(c, hi);
    let prod = flo * fhi;
    if prod.is_nan() || prod >= 0.0 {
        return None;
    }
    let zero = std::cell::Cell::new(None);
    let b = crate::solve::roots::bisect_by(
        |t| {
            let v = de_casteljau(c, t);
            if v == 0.0 {
                zero.set(Some(t));
            }
            (v != 0.0 && (v > 0.0) == (flo > 0.0)).then_some(())
        },
        lo,
        hi,
        |a, b| 0.5 * (a + b),
        |_, _| zero.get().is_some(),
        80,
    );
    Some(zero.get().unwrap_or(0.5 * (b.inside + b.outside)))
}

/// Real roots of odd multiplicity in (0, 1) of a polynomial given exactly (noise bounds
/// taken as a few ulps of the coefficient magnitudes): a convenience over [`analyze_signs`].
pub fn sign_change_roots(p: &Bernstein) -> Vec<f64> {
    let scale = p.c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let noise = vec![8.0 * f64::EPSILON * scale; p.c.len()];
    analyze_signs(&p.c, &noise, SignOptions::default()).changes
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn binomials_are_exact_where_representable() {
        assert_eq!(binomial(10, 3), 120.0);
        assert_eq!(binomial(52, 26), 495918532948104.0);
        assert_eq!(binomial(3, 5), 0.0);
    }

    #[test]
    fn power_roundtrip_and_eval() {
        let a = [1.0, -2.0, 0.5, 3.0, -1.25];
        let b = Bernstein::from_power(&a);
        for i in 0..=20 {
            let t = i as f64 / 20.0;
            let direct: f64 = a
                .iter()
                .enumerate()
                .map(|(k, v)| v * t.powi(k as i32))
                .sum();
            assert!(close(b.eval(t), direct, 1e-13));
        }
        let back = b.to_power();
        for (x, y) in a.iter().zip(back) {
            assert!(close(*x, y, 1e-13));
        }
    }

    #[test]
    fn product_elevation_derivative_subdivision_agree_with_values() {
        let p = Bernstein::new(&[1.0, -3.0, 2.0, 5.0]);
        let q = Bernstein::new(&[0.5, 4.0, -1.0]);
        let pq = p.mul(&q);
        let pe = p.elevate(3);
        let dp = p.deriv();
        let (l, r) = p.subdivide(0.3);
        assert_eq!(pq.degree(), 5);
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            assert!(close(pq.eval(t), p.eval(t) * q.eval(t), 1e-12));
            assert!(close(pe.eval(t), p.eval(t), 1e-12));
            let h = 1e-6;
            let fd = (p.eval(t + h) - p.eval(t - h)) / (2.0 * h);
            assert!(close(dp.eval(t), fd, 1e-6));
            assert!(close(l.eval(t), p.eval(0.3 * t), 1e-12));
            assert!(close(r.eval(t), p.eval(0.3 + 0.7 * t), 1e-12));
        }
        let s = p.restrict(0.2, 0.6);
        assert!(close(s.eval(0.5), p.eval(0.4), 1e-12));
    }

    #[test]
    fn exact_degree_reduction() {
        let a = [0.3, -1.0, 2.0, 0.7, -0.2, 0.9];
        let p = Bernstein::from_power(&a).elevate(1);
        let (r, _) = p.reduce_degree_exact(None);
        assert_eq!(r.degree(), 5);
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            assert!(close(r.eval(t), p.eval(t), 1e-12));
        }
    }

    #[test]
    fn roots_simple_double_and_none() {
        // (t - 0.3)(t - 0.7)(t - 0.71)
        let p = Bernstein::from_power(&[-0.3 * 0.7 * 0.71, 0.21 + 0.213 + 0.497, -1.71, 1.0]);
        let r = sign_change_roots(&p);
        assert_eq!(r.len(), 3);
        for (x, y) in r.iter().zip([0.3, 0.7, 0.71]) {
            assert!(close(*x, y, 1e-12), "{x} vs {y}");
        }
        // (t - 0.4)^2 touches zero: no sign change
        let q = Bernstein::from_power(&[0.16, -0.8, 1.0]);
        assert!(sign_change_roots(&q).is_empty());
        // (t - 0.5)^3 changes sign at 0.5
        let q3 = Bernstein::from_power(&[-0.125, 0.75, -1.5, 1.0]);
        let r3 = sign_change_roots(&q3);
        assert_eq!(r3.len(), 1);
        assert!(close(r3[0], 0.5, 1e-9));
        // identically zero
        let z = Bernstein::new(&[0.0, 0.0, 0.0]);
        let a = analyze_signs(z.coeffs(), &[0.0; 3], SignOptions::default());
        assert!(a.changes.is_empty() && !a.has_positive() && !a.has_negative());
    }
}
