//! One file per paper's gallery section of `aecurve demo` (each returns its HTML and writes
//! its pictures).

pub(crate) mod approx;
pub(crate) mod inflection;
pub(crate) mod lac_fit;
pub(crate) mod outline;
pub(crate) mod sketch;
pub(crate) mod spline;
