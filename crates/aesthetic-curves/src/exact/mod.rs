//! Exact decisions about polynomials, and the floating-point filter in front of them.
//!
//! - [`ring`]: one arithmetic interface over floating point with rigorous error bounds
//!   ([`Bounded`]) and over big integers, and polynomials in scaled Bernstein form over
//!   either, so a formula is written once and runs in both;
//! - [`poly`]: integer polynomials and their sign changes in (0, 1), decided exactly
//!   (Descartes' rule, square-free parts, Sturm sequences, bisection on dyadic numbers);
//! - [`signs`]: the certified sign analysis, filter first and exact where it cannot decide.
//!
//! [`dyadic_integers`] turns f64 values into integers with one common power of two: f64
//! numbers are dyadic rationals, so this is exact.

pub mod poly;
pub mod ring;
pub mod signs;

pub use ring::{Bounded, Ring};
pub use signs::{certified_signs, Signs, Want};

use num_bigint::BigInt;

/// Integers `n_i` and one exponent `e` with `values[i] = n_i 2^e` exactly (finite values;
/// `e` is the smallest exponent among the nonzero ones, 0 when all are zero).
pub fn dyadic_integers(values: &[f64]) -> (Vec<BigInt>, i32) {
    let parts: Vec<(i64, i32)> = values.iter().map(|v| decompose(*v)).collect();
    let e = parts
        .iter()
        .filter(|(m, _)| *m != 0)
        .map(|(_, e)| *e)
        .min()
        .unwrap_or(0);
    let ints = parts
        .iter()
        .map(|(m, x)| BigInt::from(*m) << ((x - e) as usize))
        .collect();
    (ints, e)
}

/// The binomial coefficient C(n, k) as f64: exact for n <= 56 (all of them then fit in 53
/// bits), and within a few ulps beyond.
pub fn binomial(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    let k = k.min(n - k);
    let mut b = 1.0f64;
    for j in 0..k {
        b = b * (n - j) as f64 / (j + 1) as f64;
    }
    b.round()
}

/// `v = m 2^e` with an integer m (|m| < 2^53), for finite v.
fn decompose(v: f64) -> (i64, i32) {
    if v == 0.0 || !v.is_finite() {
        return (0, 0);
    }
    let bits = v.to_bits();
    let sign = if bits >> 63 == 1 { -1 } else { 1 };
    let exp = ((bits >> 52) & 0x7ff) as i32;
    let frac = (bits & ((1u64 << 52) - 1)) as i64;
    let (m, e) = if exp == 0 {
        (frac, -1074)
    } else {
        (frac | (1i64 << 52), exp - 1075)
    };
    let tz = m.trailing_zeros() as i32;
    (sign * (m >> tz), e + tz)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dyadic_integers_are_exact() {
        let vals = [0.75, -3.0, 1e-300, 5e-324, 1e300, 0.0];
        let (ints, e) = dyadic_integers(&vals);
        assert_eq!(e, -1074);
        for (v, n) in vals.iter().zip(&ints) {
            let back = num_rational::BigRational::new(n.clone(), BigInt::from(1))
                * num_rational::BigRational::from_float(2f64.powi(0)).unwrap();
            let want = num_rational::BigRational::from_float(*v).unwrap();
            let two = num_rational::BigRational::from_integer(BigInt::from(2));
            let scale = num_traits::pow::pow(two.recip(), 1074);
            assert_eq!(back * scale, want);
        }
    }
}
