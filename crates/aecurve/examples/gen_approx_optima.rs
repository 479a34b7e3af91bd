//! Generates the table of the rational-cubic fit's local optima shipped in the library
//! (`crates/aesthetic-curves/data/approx_optima.bin`; grid, format and use in
//! `aesthetic_curves::approx_table`). Every node is the segment with that (α, θ_d, u),
//! searched by `approx::error_minima` (a 48 x 48 grid, line minima, Levenberg–Marquardt);
//! then every valley found at a neighbouring node is followed to this node (a multi-start
//! search can miss a narrow valley that its neighbour resolved) and the minima within a
//! factor 1000 of the node's best are kept.
//!
//! `cargo run --release -p aecurve --example gen_approx_optima` (minutes on two cores, with a
//! progress bar).

#[path = "common/parallel.rs"]
mod parallel;
use parallel::parallel;

use aesthetic_curves::approx::{error_minima, refine_minimum, ErrorMinimum};
use aesthetic_curves::approx_table::{
    encode, node_count, node_index, node_shape, shape_triangle, ALPHA_AXIS, MAX_PER_NODE, S_AXIS,
    THETA_AXIS,
};
use aesthetic_curves::lac::LacSegment;

/// The segment of node `idx` (None where it does not exist).
fn segment(idx: usize) -> Option<LacSegment> {
    let (alpha, theta_d, u) = node_shape(idx);
    LacSegment::new(alpha, shape_triangle(alpha, theta_d, u).ok()?).ok()
}

fn neighbours(idx: usize) -> Vec<usize> {
    let k = idx % S_AXIS.2;
    let j = (idx / S_AXIS.2) % THETA_AXIS.2;
    let i = idx / (S_AXIS.2 * THETA_AXIS.2);
    let mut out = Vec::new();
    for di in -1isize..=1 {
        for dj in -1isize..=1 {
            for dk in -1isize..=1 {
                let (a, b, c) = (i as isize + di, j as isize + dj, k as isize + dk);
                if (di, dj, dk) == (0, 0, 0)
                    || a < 0
                    || b < 0
                    || c < 0
                    || a >= ALPHA_AXIS.2 as isize
                    || b >= THETA_AXIS.2 as isize
                    || c >= S_AXIS.2 as isize
                {
                    continue;
                }
                out.push(node_index(a as usize, b as usize, c as usize));
            }
        }
    }
    out
}

fn main() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../aesthetic-curves/data/approx_optima.bin"
    );
    let count = node_count();
    let first = parallel(count, Vec::<ErrorMinimum>::new(), "search", |idx| {
        segment(idx)
            .and_then(|s| error_minima(&s, 48).ok())
            .unwrap_or_default()
    });
    let followed = parallel(count, Vec::new(), "follow", |idx| {
        let Some(seg) = segment(idx) else {
            return Vec::new();
        };
        let mut mine = first[idx].clone();
        for nb in neighbours(idx) {
            for o in &first[nb] {
                if mine
                    .iter()
                    .any(|m| (m.f0 - o.f0).abs().max((m.f1 - o.f1).abs()) < 2e-3)
                {
                    continue;
                }
                if let Ok(m) = refine_minimum(&seg, o.f0, o.f1) {
                    if mine
                        .iter()
                        .all(|x| (x.f0 - m.f0).abs().max((x.f1 - m.f1).abs()) > 2e-3)
                    {
                        mine.push(m);
                    }
                }
            }
        }
        mine.sort_by(|a, b| a.mean_square.total_cmp(&b.mean_square));
        let best = mine.first().map_or(f64::INFINITY, |m| m.mean_square);
        mine.retain(|m| m.mean_square <= 1e3 * best + 1e-300);
        mine.truncate(MAX_PER_NODE);
        mine
    });
    let nodes: Vec<Vec<(f64, f64)>> = followed
        .iter()
        .map(|v| v.iter().map(|m| (m.f0, m.f1)).collect())
        .collect();
    let bytes = encode(&nodes).expect("encode");
    std::fs::write(path, &bytes).expect("write the table");
    let total: usize = nodes.iter().map(|v| v.len()).sum();
    let empty = nodes.iter().filter(|v| v.is_empty()).count();
    let added: usize = followed
        .iter()
        .zip(&first)
        .map(|(a, b)| a.len().saturating_sub(b.len().min(MAX_PER_NODE)))
        .sum();
    let hist: Vec<usize> = (0..=MAX_PER_NODE)
        .map(|c| nodes.iter().filter(|v| v.len() == c).count())
        .collect();
    println!(
        "{count} nodes, {total} minima ({added} found by following a neighbour's valley), \
         {empty} empty; nodes by number of minima {hist:?}; {} bytes -> {path}",
        bytes.len()
    );
}
