//! libspiro (Raph Levien's Spiro, Debian package `libspiro-dev`) as an independent oracle of
//! the G2 log-aesthetic spline at α = -1: the oracle test (`tests/spiro_oracle.rs`) and the
//! comparison bench (`benches/spiro_compare.rs`). Everything needs the feature `libspiro`
//! (and the library installed):
//!
//! ```sh
//! apt-get install libspiro-dev
//! cargo test --release --workspace --features spiro-oracle/libspiro --test spiro_oracle
//! cargo bench -p spiro-oracle --features libspiro --bench spiro_compare
//! ```

#[cfg(feature = "libspiro")]
pub mod ffi;
