//! The library's integration tests, as one test binary (one link instead of one per file):
//! each file beside this one is a module, named for what it checks. Run one file's tests with
//! `cargo test --release -p aesthetic-curves --test integration FILE::` (for example
//! `sketch_reference::`). The comparison with libspiro is the crate `spiro-oracle`: it needs
//! Debian's libspiro.

#[path = "common/approx_cases.rs"]
mod approx_cases;
mod common;

mod approx_reference;
mod approx_sweep;
mod hand_strokes;
mod lac_fit_prius;
mod lac_properties;
mod lac_reference;
mod lac_spline;
mod module_graph;
mod monotone_exact;
mod monotone_properties;
mod monotone_reference;
mod pseudo_spline_reference;
mod pseudo_table_accuracy;
mod sketch_alpha;
mod sketch_contour;
mod sketch_reference;
mod space_curves;
