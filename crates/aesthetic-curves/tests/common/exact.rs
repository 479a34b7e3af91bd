//! Exact polynomial arithmetic over the integers and rationals: an independent reference for
//! the floating-point library. Power basis only (the library works in Bernstein form), so
//! both the basis and the arithmetic differ from the code under test.
#![allow(dead_code)]

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

/// Power-basis polynomial with rational coefficients, a[k] multiplies t^k.
#[derive(Clone, Debug, PartialEq)]
pub struct Poly(pub Vec<BigRational>);

pub fn q(v: f64) -> BigRational {
    BigRational::from_float(v).expect("finite")
}

impl Poly {
    pub fn zero() -> Poly {
        Poly(vec![])
    }
    pub fn c(v: BigRational) -> Poly {
        Poly(vec![v]).trim()
    }
    pub fn trim(mut self) -> Poly {
        while self.0.last().is_some_and(|v| v.is_zero()) {
            self.0.pop();
        }
        self
    }
    pub fn degree(&self) -> Option<usize> {
        if self.0.is_empty() {
            None
        } else {
            Some(self.0.len() - 1)
        }
    }
    pub fn add(&self, o: &Poly) -> Poly {
        let n = self.0.len().max(o.0.len());
        let z = BigRational::zero();
        Poly(
            (0..n)
                .map(|i| self.0.get(i).unwrap_or(&z) + o.0.get(i).unwrap_or(&z))
                .collect(),
        )
        .trim()
    }
    pub fn neg(&self) -> Poly {
        Poly(self.0.iter().map(|v| -v).collect())
    }
    pub fn sub(&self, o: &Poly) -> Poly {
        self.add(&o.neg())
    }
    pub fn scale(&self, s: &BigRational) -> Poly {
        Poly(self.0.iter().map(|v| v * s).collect()).trim()
    }
    pub fn mul(&self, o: &Poly) -> Poly {
        if self.0.is_empty() || o.0.is_empty() {
            return Poly::zero();
        }
        let mut out = vec![BigRational::zero(); self.0.len() + o.0.len() - 1];
        for (i, a) in self.0.iter().enumerate() {
            for (j, b) in o.0.iter().enumerate() {
                out[i + j] += a * b;
            }
        }
        Poly(out).trim()
    }
    pub fn deriv(&self) -> Poly {
        Poly(
            self.0
                .iter()
                .enumerate()
                .skip(1)
                .map(|(k, v)| v * BigRational::from_integer(BigInt::from(k)))
                .collect(),
        )
        .trim()
    }
    pub fn eval(&self, t: &BigRational) -> BigRational {
        let mut acc = BigRational::zero();
        for v in self.0.iter().rev() {
            acc = acc * t + v;
        }
        acc
    }
    /// Quotient and remainder.
    pub fn divrem(&self, d: &Poly) -> (Poly, Poly) {
        let dd = d.degree().expect("division by zero polynomial");
        let lead = d.0[dd].clone();
        let mut r = self.clone();
        let mut qv = vec![BigRational::zero(); self.0.len().saturating_sub(dd).max(1)];
        while let Some(rd) = r.degree() {
            if rd < dd {
                break;
            }
            let c = &r.0[rd] / &lead;
            let shift = rd - dd;
            qv[shift] = c.clone();
            for (i, v) in d.0.iter().enumerate() {
                r.0[i + shift] -= &c * v;
            }
            r = r.trim();
        }
        (Poly(qv).trim(), r)
    }
    /// Bernstein basis polynomial C(n,i) t^i (1-t)^(n-i), exactly.
    pub fn bernstein(n: usize, i: usize) -> Poly {
        let one = Poly::c(BigRational::one());
        let t = Poly(vec![BigRational::zero(), BigRational::one()]);
        let omt = Poly(vec![BigRational::one(), -BigRational::one()]);
        let mut p = one;
        for _ in 0..i {
            p = p.mul(&t);
        }
        for _ in 0..n - i {
            p = p.mul(&omt);
        }
        let mut c = BigInt::one();
        for k in 0..i {
            c = c * BigInt::from(n - k) / BigInt::from(k + 1);
        }
        p.scale(&BigRational::from_integer(c))
    }
    /// sum B_i^n(t) v_i.
    pub fn from_bernstein(v: &[BigRational]) -> Poly {
        let n = v.len() - 1;
        let mut acc = Poly::zero();
        for (i, c) in v.iter().enumerate() {
            acc = acc.add(&Poly::bernstein(n, i).scale(c));
        }
        acc
    }
}

/// Integer polynomial (primitive), for Sturm sequences without rational blow-up.
#[derive(Clone, Debug)]
pub struct IPoly(pub Vec<BigInt>);

/// The non-negative gcd (num-integer's: Stein's binary algorithm; Euclid's by big divisions
/// took 95 % of the slow oracles' time in the Sturm chains' primitive parts).
fn gcd(a: &BigInt, b: &BigInt) -> BigInt {
    num_integer::Integer::gcd(a, b)
}

impl IPoly {
    pub fn from_rational(p: &Poly) -> IPoly {
        let mut l = BigInt::one();
        for v in &p.0 {
            let d = v.denom().clone();
            let g = gcd(&l, &d);
            l = &l / &g * d;
        }
        IPoly(
            p.0.iter()
                .map(|v| (v * BigRational::from_integer(l.clone())).to_integer())
                .collect(),
        )
        .primitive()
    }
    fn trim(mut self) -> IPoly {
        while self.0.last().is_some_and(|v| v.is_zero()) {
            self.0.pop();
        }
        self
    }
    pub fn primitive(self) -> IPoly {
        let s = self.trim();
        let mut g = BigInt::zero();
        for v in &s.0 {
            g = gcd(&g, v);
        }
        if g.is_zero() || g.is_one() {
            return s;
        }
        IPoly(s.0.iter().map(|v| v / &g).collect())
    }
    pub fn degree(&self) -> Option<usize> {
        if self.0.is_empty() {
            None
        } else {
            Some(self.0.len() - 1)
        }
    }
    pub fn constant(v: i64) -> IPoly {
        IPoly(vec![BigInt::from(v)]).trim()
    }
    pub fn add(&self, o: &IPoly) -> IPoly {
        let n = self.0.len().max(o.0.len());
        let z = BigInt::zero();
        IPoly(
            (0..n)
                .map(|i| self.0.get(i).unwrap_or(&z) + o.0.get(i).unwrap_or(&z))
                .collect(),
        )
        .trim()
    }
    pub fn sub(&self, o: &IPoly) -> IPoly {
        self.add(&IPoly(o.0.iter().map(|v| -v).collect()))
    }
    pub fn scale(&self, s: i64) -> IPoly {
        let s = BigInt::from(s);
        IPoly(self.0.iter().map(|v| v * &s).collect()).trim()
    }
    pub fn mul(&self, o: &IPoly) -> IPoly {
        if self.0.is_empty() || o.0.is_empty() {
            return IPoly(vec![]);
        }
        let mut out = vec![BigInt::zero(); self.0.len() + o.0.len() - 1];
        for (i, a) in self.0.iter().enumerate() {
            for (j, b) in o.0.iter().enumerate() {
                out[i + j] += a * b;
            }
        }
        IPoly(out).trim()
    }
    /// sum B_i^n(t) v_i for integer v_i (binomials are integers: exact).
    pub fn from_bernstein(v: &[i64]) -> IPoly {
        let n = v.len() - 1;
        let mut acc = IPoly(vec![]);
        for (i, &c) in v.iter().enumerate() {
            let b = Poly::bernstein(n, i);
            let ib = IPoly(b.0.iter().map(|x| x.to_integer()).collect());
            acc = acc.add(&ib.scale(c));
        }
        acc
    }
    pub fn deriv(&self) -> IPoly {
        IPoly(
            self.0
                .iter()
                .enumerate()
                .skip(1)
                .map(|(k, v)| v * BigInt::from(k))
                .collect(),
        )
        .trim()
    }
    /// The pseudo-remainder lc(d)^(δ+1) · self mod d, δ = deg self - deg d (exact, not made
    /// primitive: the subresultant chain divides it by a known factor instead).
    pub fn prem_full(&self, d: &IPoly) -> IPoly {
        let delta = self.degree().unwrap() - d.degree().unwrap();
        let (mut r, iters) = self.prem_raw(d);
        let lead = d.0.last().unwrap();
        for _ in iters..delta as u32 + 1 {
            for v in r.0.iter_mut() {
                *v *= lead;
            }
        }
        r
    }
    /// Pseudo-remainder, made primitive (positive content), with the number of times the
    /// dividend was multiplied by the divisor's leading coefficient.
    pub fn prem(&self, d: &IPoly) -> (IPoly, u32) {
        let (r, iters) = self.prem_raw(d);
        (r.primitive(), iters)
    }
    fn prem_raw(&self, d: &IPoly) -> (IPoly, u32) {
        let dd = d.degree().unwrap();
        let lead = d.0[dd].clone();
        let mut r = self.clone();
        let mut iters = 0;
        while let Some(rd) = r.degree() {
            if rd < dd {
                break;
            }
            iters += 1;
            let c = r.0[rd].clone();
            let shift = rd - dd;
            for v in r.0.iter_mut() {
                *v *= &lead;
            }
            for (i, v) in d.0.iter().enumerate() {
                r.0[i + shift] -= &c * v;
            }
            r = r.trim();
        }
        (r, iters)
    }
}

pub fn sign_of(v: &BigInt) -> i32 {
    if v.is_positive() {
        1
    } else if v.is_negative() {
        -1
    } else {
        0
    }
}

/// Exact sign of an integer polynomial at num/2^k: the sign of
/// sum a_i num^i den^(d-i) (homogeneous Horner), den = 2^k.
pub fn sign_at(p: &IPoly, num: &BigInt, k: u32) -> i32 {
    let Some(d) = p.degree() else { return 0 };
    let den = BigInt::one() << (k as usize);
    let mut h = p.0[d].clone();
    for i in (0..d).rev() {
        h = h * num + &p.0[i] * pow(&den, d - i);
    }
    sign_of(&h)
}

fn pow(b: &BigInt, e: usize) -> BigInt {
    let mut r = BigInt::one();
    for _ in 0..e {
        r *= b;
    }
    r
}

/// Sturm chain of a square-free polynomial.
pub struct Sturm {
    pub chain: Vec<IPoly>,
}

impl Sturm {
    /// The chain p, p', -rem, ... up to positive factors, by Collins' subresultant
    /// pseudo-remainder sequence (Knuth, TAOCP 4.6.1, algorithm C): each pseudo-remainder is
    /// divided exactly by a factor known in advance, so coefficients grow no faster than in
    /// the primitive sequence and no gcd of long integers is taken. Each element is the
    /// subresultant times the sign that makes it a positive multiple of Sturm's -rem.
    pub fn new(p: &IPoly) -> Sturm {
        let sgn = |v: &BigInt| if v.is_negative() { -1 } else { 1 };
        let mut chain = vec![p.clone()];
        let (mut a, mut b) = (p.clone(), p.deriv());
        // Signs of the chain's last two elements relative to a and b.
        let (mut sa, mut sb) = (1, 1);
        let (mut g, mut h) = (BigInt::one(), BigInt::one());
        loop {
            if b.degree().is_none() {
                break;
            }
            chain.push(IPoly(b.0.iter().map(|v| v * sb).collect()));
            if b.degree() == Some(0) {
                break;
            }
            let delta = a.degree().unwrap() - b.degree().unwrap();
            let r = a.prem_full(&b);
            let divisor = &g * pow(&h, delta);
            let lead_b = b.0.last().unwrap().clone();
            let sign_lead = if delta % 2 == 0 { sgn(&lead_b) } else { 1 };
            let sc = -sa * sgn(&divisor) * sign_lead;
            debug_assert!(r.0.iter().all(|v| (v % &divisor).is_zero()));
            let next = IPoly(r.0.iter().map(|v| v / &divisor).collect()).trim();
            g = lead_b;
            // h = g^δ / h^(δ-1), exact.
            h = if delta == 0 {
                h
            } else {
                pow(&g, delta) / pow(&h, delta - 1)
            };
            a = b;
            b = next;
            sa = sb;
            sb = sc;
        }
        Sturm { chain }
    }

    /// The chain by primitive pseudo-remainders (gcds of long integers: slow); the check of
    /// [`Sturm::new`].
    pub fn new_primitive(p: &IPoly) -> Sturm {
        let mut chain = vec![p.clone(), p.deriv()];
        loop {
            let n = chain.len();
            if chain[n - 1].degree().is_none() {
                chain.pop();
                break;
            }
            if chain[n - 1].degree() == Some(0) {
                break;
            }
            // prem = lead^iters * rem (up to a positive content): the chain needs -rem.
            let (r, iters) = chain[n - 2].prem(&chain[n - 1]);
            let lead = chain[n - 1].0.last().unwrap().clone();
            let neg = if lead.is_negative() && iters % 2 == 1 {
                1
            } else {
                -1
            };
            let r = IPoly(r.0.into_iter().map(|v| v * neg).collect());
            if r.degree().is_none() {
                break;
            }
            chain.push(r);
        }
        Sturm { chain }
    }
    fn variations(&self, num: &BigInt, k: u32) -> usize {
        let mut last = 0;
        let mut v = 0;
        for p in &self.chain {
            let s = sign_at(p, num, k);
            if s != 0 {
                if last != 0 && s != last {
                    v += 1;
                }
                last = s;
            }
        }
        v
    }
    /// Distinct real roots in (a, b] with a = an/2^k, b = bn/2^k.
    pub fn count(&self, an: &BigInt, bn: &BigInt, k: u32) -> usize {
        self.variations(an, k)
            .saturating_sub(self.variations(bn, k))
    }
}

/// Roots in (0, 1) of an integer polynomial at which it changes sign, isolated exactly
/// (Sturm sequence; it counts distinct roots even when some are multiple) to depth `bits`
/// and refined by exact bisection to width 2^-min(bits, 64); also all distinct roots in
/// (0, 1), sign change or not.
pub fn sign_change_roots_int(ip: &IPoly, bits: u32) -> (Vec<f64>, Vec<f64>) {
    if ip.degree().unwrap_or(0) == 0 {
        return (vec![], vec![]);
    }
    // Sturm's theorem needs the square-free part where an interval end may be a root.
    let st0 = Sturm::new(ip);
    let g = st0.chain.last().unwrap();
    let st = if g.degree().unwrap_or(0) > 0 {
        let to_q = |p: &IPoly| {
            Poly(
                p.0.iter()
                    .map(|v| BigRational::from_integer(v.clone()))
                    .collect(),
            )
        };
        let sf = to_q(ip).divrem(&to_q(g)).0;
        Sturm::new(&IPoly::from_rational(&sf))
    } else {
        st0
    };
    let mut changes = Vec::new();
    let mut all = Vec::new();
    let one = BigInt::one();
    // Dyadic intervals (num/2^k, (num+1)/2^k].
    let mut stack: Vec<(BigInt, u32)> = vec![(BigInt::zero(), 0)];
    while let Some((num, k)) = stack.pop() {
        let hi = &num + &one;
        let c = st.count(&num, &hi, k);
        if c == 0 {
            continue;
        }
        if c > 1 && k < bits {
            let n2 = &num << 1usize;
            stack.push((&n2 + &one, k + 1));
            stack.push((n2, k + 1));
            continue;
        }
        // One distinct root r in (lo, hi].
        let (mut lo_n, mut hi_n, mut kk) = (num.clone(), hi.clone(), k);
        let mut exact: Option<(BigInt, u32)> = None;
        let slo = sign_at(ip, &lo_n, kk);
        let shi = sign_at(ip, &hi_n, kk);
        if shi == 0 {
            exact = Some((hi_n.clone(), kk));
        } else {
            let by_sign = slo * shi < 0;
            // Isolation may go as deep as `bits`; the position is wanted to 2^-64 at most.
            while kk < bits.min(64) {
                lo_n <<= 1usize;
                hi_n <<= 1usize;
                kk += 1;
                let mid = &lo_n + &one;
                let sm = sign_at(ip, &mid, kk);
                if sm == 0 {
                    exact = Some((mid, kk));
                    break;
                }
                let right = if by_sign {
                    sm != shi
                } else {
                    st.count(&mid, &hi_n, kk) == 1
                };
                if right {
                    lo_n = mid;
                } else {
                    hi_n = mid;
                }
            }
        }
        let (t, l, r) = match &exact {
            Some((n, k)) => {
                let (n, k) = (n, *k);
                let n20 = n << 20usize;
                (
                    dyadic(n, k),
                    sign_at(ip, &(&n20 - &one), k + 20),
                    sign_at(ip, &(&n20 + &one), k + 20),
                )
            }
            None => (
                0.5 * (dyadic(&lo_n, kk) + dyadic(&hi_n, kk)),
                sign_at(ip, &lo_n, kk),
                sign_at(ip, &hi_n, kk),
            ),
        };
        // A root exactly at an end is not inside; one strictly inside its interval is, even
        // where its f64 rounds to 0 or 1 (within 1e-300 of an end, on a curve whose
        // coordinates span hundreds of orders of magnitude).
        let at_end = exact
            .as_ref()
            .is_some_and(|(n, k)| n.is_zero() || *n == (BigInt::one() << (*k as usize)));
        if at_end || !(0.0..=1.0).contains(&t) {
            continue;
        }
        all.push(t);
        // p changes sign across r iff its multiplicity there is odd.
        if l * r < 0 {
            changes.push(t);
        }
    }
    changes.sort_by(|a, b| a.partial_cmp(b).unwrap());
    all.sort_by(|a, b| a.partial_cmp(b).unwrap());
    (changes, all)
}

/// [`sign_change_roots_int`] for a rational polynomial.
pub fn sign_change_roots(p: &Poly, bits: u32) -> (Vec<f64>, Vec<f64>) {
    sign_change_roots_int(&IPoly::from_rational(p), bits)
}

fn dyadic(num: &BigInt, k: u32) -> f64 {
    let r = BigRational::new(num.clone(), BigInt::one() << (k as usize));
    r.to_f64().unwrap()
}
