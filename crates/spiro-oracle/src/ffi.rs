//! libspiro (Raph Levien's Spiro, Debian package `libspiro-dev`) from Rust: its control
//! points, its segments and the two calls the oracle test and the comparison bench use.

use aesthetic_curves::Point;
use std::os::raw::{c_char, c_int};

/// libspiro's `spiro_cp`.
#[repr(C)]
#[derive(Clone, Copy)]
pub struct SpiroCp {
    pub x: f64,
    pub y: f64,
    pub ty: c_char,
}

/// libspiro's `spiro_seg` (spiro.h).
#[repr(C)]
#[derive(Clone, Copy)]
pub struct SpiroSeg {
    pub x: f64,
    pub y: f64,
    pub ty: c_char,
    pub bend_th: f64,
    pub ks: [f64; 4],
    pub seg_ch: f64,
    pub seg_th: f64,
    pub l: f64,
}

#[link(name = "spiro")]
extern "C" {
    fn run_spiro(src: *const SpiroCp, n: c_int) -> *mut SpiroSeg;
    fn free_spiro(s: *mut SpiroSeg);
}

/// Spiro control points through `pts`: corners ('v') at `corners`; an open curve starts
/// with '{' and ends with '}'; the rest are G2 points ('c').
pub fn control_points(pts: &[Point], closed: bool, corners: &[usize]) -> Vec<SpiroCp> {
    let n = pts.len();
    pts.iter()
        .enumerate()
        .map(|(i, p)| SpiroCp {
            x: p.x,
            y: p.y,
            ty: if corners.contains(&i) {
                b'v'
            } else if closed {
                b'c'
            } else if i == 0 {
                b'{'
            } else if i == n - 1 {
                b'}'
            } else {
                b'c'
            } as c_char,
        })
        .collect()
}

/// Spiro's segments for `cps` (one per point), or None when it fails.
pub fn run(cps: &[SpiroCp]) -> Option<Vec<SpiroSeg>> {
    // SAFETY: `cps` is a valid array of its length for the call's duration; the returned
    // array holds one segment per control point and is freed by libspiro's own call.
    unsafe {
        let s = run_spiro(cps.as_ptr(), cps.len() as c_int);
        if s.is_null() {
            return None;
        }
        let segs = std::slice::from_raw_parts(s, cps.len()).to_vec();
        free_spiro(s);
        Some(segs)
    }
}
