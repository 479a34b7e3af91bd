//! The solver layer: every iterative method of the library, each with its own options and a
//! report of how it ended, in one file per kind.
//!
//! - [`minimize`]: minimisers of a few variables: Nelder–Mead, a compass search that keeps
//!   to a feasible set, and a walk along that set's boundary.
//! - [`line_search`]: minimisers of one variable on an interval: golden sections, Brent,
//!   a safeguarded Newton.
//! - [`roots`]: roots of one variable: Illinois and Brent in a bracket, a bracketed Newton,
//!   an unbracketed safeguarded Newton, and bisection on a yes/no test.
//! - [`systems`]: systems of equations (damped Newton over an opaque state) and fixed
//!   points (block Gauss–Seidel sweeps).
//! - [`least_squares`]: Levenberg–Marquardt for small nonlinear least-squares problems
//!   (the rational-cubic fit and the single-LAC fit), with a [`least_squares::Stop`] reason.
//! - [`linear`]: the linear systems of Newton steps along a chain of unknowns
//!   ([`linear::Tridiagonal`], cyclic for a closed chain): O(n), a dense LU only as fallback.

pub mod least_squares;
pub mod line_search;
pub mod linear;
pub mod minimize;
pub mod roots;
pub mod systems;
