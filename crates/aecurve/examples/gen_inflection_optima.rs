//! Generates the table of the inflection-end fit's optima shipped in the library
//! (`crates/aesthetic-curves/data/inflection_optima.bin`; grid, format and use in
//! `aesthetic_curves::approx_table`). Every node is the inflection-end segment with that
//! (α, θ_d), fitted by the full search of `fit_inflection_cubic_from` (its grid,
//! Levenberg–Marquardt, compass search and boundary walk; the table itself not used); then,
//! until nothing improves, every neighbour's optimum is followed to this node (a search from
//! there), and the fit whose error on the exact segment is least is kept: a grid search can
//! miss a narrow valley that its neighbour found.
//!
//! `cargo run --release -p aecurve --example gen_inflection_optima` (about two minutes on
//! two cores, with a progress bar).

#[path = "common/parallel.rs"]
mod parallel;
use parallel::parallel;

use aesthetic_curves::approx::{fit_inflection_cubic_from, ApproxOptions};
use aesthetic_curves::approx_table::{
    encode_inflection, inflection_node_count, inflection_node_shape, inflection_triangle,
    INFLECTION_R_AXIS, INFLECTION_THETA_AXIS,
};
use aesthetic_curves::lac::LacInflectionSegment;

/// The segment of node `idx` (None where it does not exist).
fn segment(idx: usize) -> Option<LacInflectionSegment> {
    let (alpha, theta_d) = inflection_node_shape(idx);
    LacInflectionSegment::new(inflection_triangle(alpha, theta_d).ok()?).ok()
}

/// The nodes around `idx` (the eight neighbours inside the grid).
fn neighbours(idx: usize) -> Vec<usize> {
    let (na, nt) = (
        INFLECTION_R_AXIS.2 as isize,
        INFLECTION_THETA_AXIS.2 as isize,
    );
    let (i, j) = (idx as isize / nt, idx as isize % nt);
    let mut out = Vec::new();
    for di in -1..=1 {
        for dj in -1..=1 {
            let (a, b) = (i + di, j + dj);
            if (di, dj) != (0, 0) && (0..na).contains(&a) && (0..nt).contains(&b) {
                out.push((a * nt + b) as usize);
            }
        }
    }
    out
}

/// A node's best fit so far: its error on the exact segment (rms) and `(f0, ln w0)`.
type Best = Option<(f64, (f64, f64))>;

fn main() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../aesthetic-curves/data/inflection_optima.bin"
    );
    let opts = ApproxOptions {
        table: false,
        ..ApproxOptions::default()
    };
    let count = inflection_node_count();
    let mut best: Vec<Best> = parallel(count, None, "search", |idx| {
        let seg = segment(idx)?;
        let (fit, x) = fit_inflection_cubic_from(&seg, &opts, None, true).ok()?;
        fit.monotone.then_some((fit.rms, x))
    });
    for pass in 1..=8 {
        let prev = best.clone();
        best = parallel(count, None, &format!("follow {pass}"), |idx| {
            let mut mine = prev[idx];
            let Some(seg) = segment(idx) else {
                return mine;
            };
            for nb in neighbours(idx) {
                let Some((_, x)) = prev[nb] else { continue };
                let Ok((fit, y)) = fit_inflection_cubic_from(&seg, &opts, Some(x), true) else {
                    continue;
                };
                if fit.monotone && mine.is_none_or(|m| fit.rms < m.0 * (1.0 - 1e-9)) {
                    mine = Some((fit.rms, y));
                }
            }
            mine
        });
        // Improved by over 1 % (a polish of the same optimum gains far less).
        let improved = best
            .iter()
            .zip(&prev)
            .filter(|(a, b)| match (a, b) {
                (Some(a), Some(b)) => a.0 < 0.99 * b.0,
                (a, b) => a.is_some() != b.is_some(),
            })
            .count();
        println!("pass {pass}: {improved} nodes improved by over 1 % by a neighbour's optimum");
        if improved == 0 {
            break;
        }
    }
    let nodes: Vec<Option<(f64, f64)>> = best.iter().map(|b| b.map(|x| x.1)).collect();
    let bytes = encode_inflection(&nodes).expect("encode");
    std::fs::write(path, &bytes).expect("write the table");
    let empty = nodes.iter().filter(|v| v.is_none()).count();
    println!(
        "{count} nodes, {empty} without a monotone cubic; {} bytes -> {path}",
        bytes.len()
    );
}
