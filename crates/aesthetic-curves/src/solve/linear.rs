//! Linear systems with the band of a chain of unknowns: [`Tridiagonal`], each equation
//! tied to its own unknown and its two neighbours, with the two corner entries of a closed
//! chain (cyclic). O(n) where a dense LU is O(n³): the G2 spline's Newton steps over 500
//! points spent two thirds of their time in a dense LU.

use nalgebra::{DMatrix, DVector};

/// An `n × n` matrix with entries on the three middle diagonals and, for a closed chain,
/// at `(0, n - 1)` and `(n - 1, 0)`; any other entry added is kept aside and the solve
/// falls back to a dense LU.
#[derive(Clone, Debug, PartialEq)]
pub struct Tridiagonal {
    /// `sub[i]` at `(i + 1, i)`.
    sub: Vec<f64>,
    /// `diag[i]` at `(i, i)`.
    diag: Vec<f64>,
    /// `sup[i]` at `(i, i + 1)`.
    sup: Vec<f64>,
    /// At `(0, n - 1)`.
    top_right: f64,
    /// At `(n - 1, 0)`.
    bottom_left: f64,
    /// Entries off the band (a dense solve then).
    other: Vec<(usize, usize, f64)>,
}

impl Tridiagonal {
    /// The zero matrix of size `n`.
    pub fn zeros(n: usize) -> Self {
        Tridiagonal {
            sub: vec![0.0; n.saturating_sub(1)],
            diag: vec![0.0; n],
            sup: vec![0.0; n.saturating_sub(1)],
            top_right: 0.0,
            bottom_left: 0.0,
            other: Vec::new(),
        }
    }

    /// The size.
    pub fn len(&self) -> usize {
        self.diag.len()
    }

    /// Whether the size is 0.
    pub fn is_empty(&self) -> bool {
        self.diag.is_empty()
    }

    /// Add `v` at `(r, c)`. Below size 3 the corners and the band overlap: every entry is
    /// kept aside (a dense solve).
    pub fn add(&mut self, r: usize, c: usize, v: f64) {
        let n = self.len();
        if n < 3 {
            self.other.push((r, c, v));
        } else if r == c {
            self.diag[r] += v;
        } else if r == c + 1 {
            self.sub[c] += v;
        } else if c == r + 1 {
            self.sup[r] += v;
        } else if (r, c) == (0, n - 1) {
            self.top_right += v;
        } else if (r, c) == (n - 1, 0) {
            self.bottom_left += v;
        } else {
            self.other.push((r, c, v));
        }
    }

    /// The matrix as a dense one.
    pub fn to_dense(&self) -> DMatrix<f64> {
        let n = self.len();
        let mut m = DMatrix::zeros(n, n);
        for i in 0..n {
            m[(i, i)] = self.diag[i];
        }
        for i in 0..n.saturating_sub(1) {
            m[(i + 1, i)] += self.sub[i];
            m[(i, i + 1)] += self.sup[i];
        }
        if n >= 3 {
            m[(0, n - 1)] += self.top_right;
            m[(n - 1, 0)] += self.bottom_left;
        }
        for &(r, c, v) in &self.other {
            m[(r, c)] += v;
        }
        m
    }

    /// `self · x`.
    fn mul(&self, x: &[f64]) -> Vec<f64> {
        let n = self.len();
        let mut y: Vec<f64> = (0..n).map(|i| self.diag[i] * x[i]).collect();
        for i in 0..n.saturating_sub(1) {
            y[i + 1] += self.sub[i] * x[i];
            y[i] += self.sup[i] * x[i + 1];
        }
        if n >= 3 {
            y[0] += self.top_right * x[n - 1];
            y[n - 1] += self.bottom_left * x[0];
        }
        for &(r, c, v) in &self.other {
            y[r] += v * x[c];
        }
        y
    }

    /// The solution of `self · x = b`, `None` for a singular matrix. The band by Gaussian
    /// elimination with partial pivoting (LAPACK's `dgtsv`); the corners by the
    /// Sherman–Morrison formula over it. Where that is not accurate (its residual above
    /// 1e-10 of `|b|` plus the matrix's scale times `|x|`) or entries lie off the band, a
    /// dense LU instead.
    pub fn solve(&self, b: &[f64]) -> Option<Vec<f64>> {
        let n = self.len();
        assert_eq!(b.len(), n, "right-hand side of the wrong length");
        if n == 0 {
            return Some(Vec::new());
        }
        let banded = if self.other.is_empty() {
            self.solve_banded(b)
        } else {
            None
        };
        if let Some(x) = banded.filter(|x| self.accurate(x, b)) {
            return Some(x);
        }
        let x = self.to_dense().lu().solve(&DVector::from_column_slice(b))?;
        x.iter()
            .all(|v| v.is_finite())
            .then(|| x.as_slice().to_vec())
    }

    /// Whether `x` solves the system to 1e-10 of its scale.
    fn accurate(&self, x: &[f64], b: &[f64]) -> bool {
        let r = self.mul(x);
        let big = |v: &[f64]| v.iter().fold(0.0f64, |m, e| m.max(e.abs()));
        let scale = self
            .diag
            .iter()
            .chain(&self.sub)
            .chain(&self.sup)
            .chain([&self.top_right, &self.bottom_left])
            .fold(0.0f64, |m, e| m.max(e.abs()));
        let miss = r
            .iter()
            .zip(b)
            .fold(0.0f64, |m, (r, b)| m.max((r - b).abs()));
        x.iter().all(|v| v.is_finite()) && miss <= 1e-10 * (big(b) + scale * big(x))
    }

    /// The band's solve, with the corners by Sherman–Morrison: `A = T + u vᵀ` with
    /// `u = (γ, 0, …, 0, c)`, `v = (1, 0, …, 0, d/γ)` (`d` top right, `c` bottom left,
    /// `γ = -A₀₀`, or 1 where that is 0) and `T` the band with `γ` taken from its first and
    /// `c d/γ` from its last diagonal entry.
    fn solve_banded(&self, b: &[f64]) -> Option<Vec<f64>> {
        let n = self.len();
        if self.top_right == 0.0 && self.bottom_left == 0.0 {
            return gtsv(&self.sub, &self.diag, &self.sup, b);
        }
        let gamma = if self.diag[0] != 0.0 {
            -self.diag[0]
        } else {
            1.0
        };
        let (c, d) = (self.bottom_left, self.top_right);
        let mut diag = self.diag.clone();
        diag[0] -= gamma;
        diag[n - 1] -= c * d / gamma;
        let y = gtsv(&self.sub, &diag, &self.sup, b)?;
        let mut u = vec![0.0; n];
        u[0] = gamma;
        u[n - 1] = c;
        let z = gtsv(&self.sub, &diag, &self.sup, &u)?;
        let vy = y[0] + d / gamma * y[n - 1];
        let vz = z[0] + d / gamma * z[n - 1];
        let den = 1.0 + vz;
        if den == 0.0 || !den.is_finite() {
            return None;
        }
        Some(y.iter().zip(&z).map(|(y, z)| y - z * vy / den).collect())
    }
}

/// LAPACK's `dgtsv` for one right-hand side: Gaussian elimination with partial pivoting of
/// the tridiagonal matrix (`sub`, `diag`, `sup`), where a row swap fills a second
/// superdiagonal. `None` for a zero pivot.
fn gtsv(sub: &[f64], diag: &[f64], sup: &[f64], b: &[f64]) -> Option<Vec<f64>> {
    let n = diag.len();
    let (mut dl, mut d, mut du, mut x) = (sub.to_vec(), diag.to_vec(), sup.to_vec(), b.to_vec());
    for i in 0..n.saturating_sub(1) {
        if d[i].abs() >= dl[i].abs() {
            if d[i] == 0.0 {
                return None;
            }
            let fact = dl[i] / d[i];
            d[i + 1] -= fact * du[i];
            x[i + 1] -= fact * x[i];
            // dl[i] now holds the second superdiagonal, zero without a swap.
            dl[i] = 0.0;
        } else {
            let fact = d[i] / dl[i];
            d[i] = dl[i];
            let temp = d[i + 1];
            d[i + 1] = du[i] - fact * temp;
            if i + 2 < n {
                dl[i] = du[i + 1];
                du[i + 1] = -fact * dl[i];
            }
            du[i] = temp;
            let t = x[i];
            x[i] = x[i + 1];
            x[i + 1] = t - fact * x[i + 1];
        }
    }
    if d[n - 1] == 0.0 {
        return None;
    }
    x[n - 1] /= d[n - 1];
    if n >= 2 {
        x[n - 2] = (x[n - 2] - du[n - 2] * x[n - 1]) / d[n - 2];
    }
    for i in (0..n.saturating_sub(2)).rev() {
        x[i] = (x[i] - du[i] * x[i + 1] - dl[i] * x[i + 2]) / d[i];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fixed-seed generator of values in [-1, 1).
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        }
    }

    /// Against nalgebra's dense LU (an oracle that does not share this code): random
    /// matrices, diagonally dominant or not (pivoting needed), open and cyclic, sizes 1 to
    /// 40, and the scale of the band varied over 12 orders; every solution within 1e-9 of
    /// the dense one relative to its size.
    #[test]
    fn tridiagonal_solves_agree_with_a_dense_lu() {
        let mut g = Lcg(7);
        for case in 0..600 {
            let n = 1 + case % 40;
            let cyclic = case % 2 == 1;
            let weak = case % 3 == 0;
            let scale = 10f64.powi((case % 13) as i32 - 6);
            let mut t = Tridiagonal::zeros(n);
            for i in 0..n {
                let dom = if weak { 0.1 } else { 4.0 };
                t.add(
                    i,
                    i,
                    scale * (dom * g.next() + if weak { 0.0 } else { 5.0 }),
                );
                if i + 1 < n {
                    t.add(i + 1, i, scale * g.next());
                    t.add(i, i + 1, scale * g.next());
                }
            }
            if cyclic && n >= 3 {
                t.add(0, n - 1, scale * g.next());
                t.add(n - 1, 0, scale * g.next());
            }
            let b: Vec<f64> = (0..n).map(|_| g.next()).collect();
            let dense = t.to_dense().lu().solve(&DVector::from_column_slice(&b));
            let Some(want) = dense else { continue };
            let got = t.solve(&b).expect("solved");
            let size = want.iter().fold(1e-300f64, |m, v| m.max(v.abs()));
            for (x, y) in got.iter().zip(want.iter()) {
                assert!((x - y).abs() <= 1e-9 * size, "case {case}: {x} vs {y}");
            }
        }
    }

    /// A zero on the diagonal is no zero pivot once rows swap; a singular band is `None`.
    #[test]
    fn pivoting_and_singular_matrices() {
        let mut t = Tridiagonal::zeros(3);
        for (r, c, v) in [
            (0, 1, 1.0),
            (1, 0, 1.0),
            (1, 2, 2.0),
            (2, 1, 3.0),
            (2, 2, 1.0),
        ] {
            t.add(r, c, v);
        }
        let x = t.solve(&[1.0, 2.0, 3.0]).unwrap();
        let back = t.mul(&x);
        assert!(back
            .iter()
            .zip([1.0, 2.0, 3.0])
            .all(|(a, b)| (a - b).abs() < 1e-14));
        let mut s = Tridiagonal::zeros(3);
        s.add(0, 0, 1.0);
        s.add(1, 0, 1.0);
        assert!(s.solve(&[1.0, 1.0, 1.0]).is_none());
    }
}
