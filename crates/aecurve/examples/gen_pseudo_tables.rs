//! Generates the pseudo-elastic segment tables shipped in the library
//! (`crates/aesthetic-curves/data/pseudo_tables.bin`; format and use in
//! `aesthetic_curves::pseudo_table`). Every node is the exact mode: all local minima of
//! J(r0, r1) within a factor 2 of the best (`segment_minima`), and J(θ) = min over θ1
//! (`single_angle`).
//!
//! Then every cell that lookups use (the canonical wedge θ0 >= |θ1|, see
//! `PseudoTables::segment`) is checked: at five points inside it the interpolated J, L and S
//! are compared with the exact mode, and the cell is flagged where they are off by more than
//! `CHECK_TOLERANCE` (lookups in flagged cells minimise instead).
//!
//! `cargo run --release -p aecurve --example gen_pseudo_tables -- [N] [M]`
//! (defaults 288 and 2048: 1.25° and 0.18° steps). About 8 minutes on two cores.
//! `... -- --check-only` redoes only the check of the shipped table.

#[path = "common/parallel.rs"]
mod parallel;
use parallel::parallel;

use aesthetic_curves::pseudo_segment::{
    local_minimum, segment_minima, single_angle, SegmentOptimum,
};
use aesthetic_curves::pseudo_table::{
    decode, encode, q1, q2, Entry, PseudoTables, CHECK_TOLERANCE, TRACK,
};
use std::f64::consts::PI;

/// The node's angles: at the origin J / q is a limit, taken just beside (r0, r1 are
/// undefined there).
fn node_angles(a: f64, b: f64) -> (f64, f64) {
    if q2(a, b) == 0.0 {
        (1e-4, 0.0)
    } else {
        (a, b)
    }
}

fn entry(a: f64, b: f64, o: &SegmentOptimum) -> Entry {
    [
        o.r0.ln() as f32,
        o.r1.ln() as f32,
        (o.j / q2(a, b)) as f32,
        o.shape.length as f32,
        o.shape.area as f32,
    ]
}

/// Continuation: every valley present at a neighbouring node is followed to this node by a
/// local search from the neighbour's tangent lengths (the multi-start search can miss a
/// shallow valley); then the minima within twice the best are kept.
fn continue_valleys(
    n: usize,
    nodes: &[Vec<SegmentOptimum>],
    idx: usize,
    h: f64,
) -> Vec<SegmentOptimum> {
    let (i, k) = (idx / n, idx % n);
    let (a, b) = node_angles(-PI + i as f64 * h, -PI + k as f64 * h);
    let mut mine = nodes[idx].clone();
    if mine.is_empty() {
        return mine;
    }
    for di in [-1isize, 0, 1] {
        for dk in [-1isize, 0, 1] {
            if (di, dk) == (0, 0) {
                continue;
            }
            let ni = (i as isize + di).rem_euclid(n as isize) as usize;
            let nk = (k as isize + dk).rem_euclid(n as isize) as usize;
            for o in &nodes[ni * n + nk] {
                let near = |m: &SegmentOptimum| {
                    (m.r0.ln() - o.r0.ln())
                        .abs()
                        .max((m.r1.ln() - o.r1.ln()).abs())
                        < 0.5 * TRACK
                };
                if mine.iter().any(near) {
                    continue;
                }
                if let Some(m) = local_minimum(a, b, o.r0, o.r1) {
                    let dup = mine.iter().any(|x| {
                        (x.r0.ln() - m.r0.ln())
                            .abs()
                            .max((x.r1.ln() - m.r1.ln()).abs())
                            < 1e-3
                    });
                    if !dup {
                        mine.push(m);
                    }
                }
            }
        }
    }
    mine.sort_by(|x, y| x.j.total_cmp(&y.j));
    let best = mine[0].j;
    mine.retain(|m| m.j <= 2.0 * best);
    mine.truncate(4);
    mine
}

/// Check every cell of the canonical wedge against the exact mode; returns the flags (module
/// docs) and prints what it found.
fn check_cells(t: &PseudoTables) -> Vec<bool> {
    let n = t.size();
    let plain = t.without_flags();
    let h = 2.0 * PI / n as f64;
    // Cells meeting the wedge θ0 >= |θ1|, θ0 > 0 (lookups map every query into it).
    let cells: Vec<usize> = (0..n * n)
        .filter(|&c| {
            let (a0, b0) = (-PI + (c / n) as f64 * h, -PI + (c % n) as f64 * h);
            a0 + h > 0.0 && a0 + h >= b0.abs().min((b0 + h).abs())
        })
        .collect();
    let worst = parallel(cells.len(), 0.0f64, "check cells", |ci| {
        let c = cells[ci];
        let (a0, b0) = (-PI + (c / n) as f64 * h, -PI + (c % n) as f64 * h);
        let mut worst: f64 = 0.0;
        for (u, v) in [(0.5, 0.5), (0.2, 0.2), (0.8, 0.2), (0.2, 0.8), (0.8, 0.8)] {
            let (a, b) = (a0 + u * h, b0 + v * h);
            if !(a > 0.0 && a >= b.abs() && a <= PI) {
                continue;
            }
            let Ok(all) = segment_minima(a, b) else {
                continue;
            };
            let Ok(tb) = plain.segment(a, b) else {
                continue;
            };
            let e = all[0];
            let near: Vec<_> = all.iter().filter(|m| m.j <= e.j * (1.0 + 1e-3)).collect();
            let dl = near
                .iter()
                .map(|m| (tb.length - m.shape.length).abs() / m.shape.length)
                .fold(f64::MAX, f64::min);
            let ds = near
                .iter()
                .map(|m| (tb.area - m.shape.area).abs() / m.shape.area.abs().max(1e-2))
                .fold(f64::MAX, f64::min);
            let dj = (tb.j - e.j).abs() / e.j;
            // S counts a tenth: S-shaped segments have S near 0 and it is judged relative to
            // max(|S|, 0.01), so a full weight would flag cells (and slow common splines)
            // for area errors of 1e-6 of the chord squared.
            worst = worst.max(dj).max(dl).max(0.1 * ds);
        }
        worst
    });
    for tol in [1e-5, 2e-5, 5e-5, 1e-4, 1e-3] {
        let over = worst.iter().filter(|w| w.is_nan() || **w > tol).count();
        println!("cells off by more than {tol:.0e}: {over}");
    }
    if let Ok(dump) = std::env::var("PSEUDO_CHECK_DUMP") {
        let text: String = cells
            .iter()
            .zip(&worst)
            .map(|(c, w)| format!("{c} {w:e}\n"))
            .collect();
        std::fs::write(dump, text).expect("write the dump");
    }
    let mut flags = vec![false; n * n];
    for (ci, w) in worst.iter().enumerate() {
        // Flagged: off by more than the tolerance (a NaN counts as off).
        flags[cells[ci]] = w.is_nan() || *w > CHECK_TOLERANCE;
    }
    let count = flags.iter().filter(|f| **f).count();
    let inner = cells
        .iter()
        .filter(|&&c| flags[c])
        .filter(|&&c| {
            let (a0, b0) = (-PI + (c / n) as f64 * h, -PI + (c % n) as f64 * h);
            a0.abs()
                .max(b0.abs())
                .max((a0 + h).abs())
                .max((b0 + h).abs())
                <= 1.0
        })
        .count();
    println!(
        "checked {} cells: {count} flagged ({inner} of them within |θ| <= 1 rad)",
        cells.len()
    );
    flags
}

fn main() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../aesthetic-curves/data/pseudo_tables.bin");
    let raw: Vec<String> = std::env::args().skip(1).collect();
    if raw.iter().any(|a| a == "--check-only") {
        let old = decode(&std::fs::read(&path).expect("read the table")).expect("a table");
        let flags = check_cells(&old);
        std::fs::write(&path, old.encode_with_flags(&flags)).expect("write the table");
        println!("wrote {}", path.display());
        return;
    }
    let args: Vec<usize> = raw.iter().map(|a| a.parse().expect("N M")).collect();
    let n = args.first().copied().unwrap_or(288);
    let m = args.get(1).copied().unwrap_or(2048);
    let h = 2.0 * PI / n as f64;
    let mut nodes = parallel(n * n, Vec::new(), "J, r0, r1, L, S", |idx| {
        let (i, k) = (idx / n, idx % n);
        let (a, b) = node_angles(-PI + i as f64 * h, -PI + k as f64 * h);
        // Empty at the singular points (π, 0), (0, π), (π, π), where every segment has a cusp.
        segment_minima(a, b).unwrap_or_default()
    });
    for sweep in 1..=2 {
        let prev = nodes;
        nodes = parallel(n * n, Vec::new(), &format!("follow {sweep}"), |idx| {
            continue_valleys(n, &prev, idx, h)
        });
    }
    let entries: Vec<Vec<Entry>> = nodes
        .iter()
        .enumerate()
        .map(|(idx, v)| {
            let (a, b) = node_angles(-PI + (idx / n) as f64 * h, -PI + (idx % n) as f64 * h);
            v.iter().map(|o| entry(a, b, o)).collect()
        })
        .collect();
    // J(θ) is even in θ and θ1(-θ) = -θ1(θ): compute θ in [0, π] only.
    let hm = 2.0 * PI / m as f64;
    let half = m / 2 + 1;
    let upper = parallel(half, [0f32; 2], "J(θ)", |k| {
        let a = k as f64 * hm; // 0 ..= π
        if a == 0.0 {
            // J / q1 is a limit at 0 (taken just beside); the straight segment's θ1 is 0.
            let (j, _) = single_angle(1e-4).expect("single angle");
            return [(j / q1(1e-4)) as f32, 0.0];
        }
        let (j, t1) = single_angle(a).expect("single angle");
        [(j / q1(a)) as f32, t1 as f32]
    });
    let mut single = vec![[0f32; 2]; m];
    for (k, s) in single.iter_mut().enumerate() {
        // node k at -π + k hm; its mirror -(-π + k hm) = π - k hm = -π + (m - k) hm.
        let up = k as isize - (m / 2) as isize; // offset from θ = 0
        let u = upper[up.unsigned_abs()];
        *s = if up >= 0 { u } else { [u[0], -u[1]] };
    }
    let unchecked = decode(&encode(n, &entries, m, &single, &vec![false; n * n]))
        .expect("the table just encoded");
    let flags = check_cells(&unchecked);
    let bytes = encode(n, &entries, m, &single, &flags);
    std::fs::write(&path, &bytes).expect("write the table");
    let total: usize = nodes.iter().map(|v| v.len()).sum();
    let multi = nodes.iter().filter(|v| v.len() > 1).count();
    println!(
        "wrote {} ({} bytes): {n} x {n} nodes, {total} minima ({multi} nodes with more than one), {m} single-angle nodes",
        path.display(),
        bytes.len()
    );
}
