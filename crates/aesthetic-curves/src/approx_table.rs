//! The tables of the rational-cubic fits' optima (docs/math.md §4). The second, for the
//! inflection-end family, is at the end ([`inflection_table`]). The first: for a
//! grid of LAC segment shapes, every local minimum of the error surface over (f0, f1) that
//! could be the global one, so that [`crate::approx::fit_rational_cubic`] starts its local
//! refinements in every valley instead of searching the whole square.
//!
//! **Shape coordinates.** Up to a similarity a LAC segment is fixed by α, its turning angle
//! θ_d and the base angle φ at its high-curvature end, `θ_d/2 <= φ < θ_lim(α, θ_d)`. The
//! table uses
//! - α at 41 nodes, -5 to 5 in steps of 0.25;
//! - θ_d at 35 nodes, 5° to 175° in steps of 5°;
//! - `s` at 20 nodes, 0 to 0.95 in steps of 0.05, where
//!   `u = (φ - θ_d/2)/(θ_lim - θ_d/2) = 3s² - 2s³`: the nodes crowd towards the circle
//!   u = 0 (near-exact fits with narrow twin valleys) and the singular end u = 1 (where the
//!   optima move fastest); the last node is u = 0.99275.
//!
//! **What a node holds.** Each local minimum (in the ordering the generator found, best
//! first) within a factor 1000 of the node's best, at most [`MAX_PER_NODE`], as `(f_hi,
//! f_lo)`: the handle fractions at the high- and the low-curvature end, quantised to 16 bits
//! (1.5e-5; the fit refines every start anyway).
//!
//! **Generation.** `cargo run --release -p aecurve --example gen_approx_optima` runs
//! [`crate::approx::error_minima`] at every node (a 48 x 48 grid, the minima along every
//! grid row and column, Levenberg–Marquardt from each, duplicates merged) and writes
//! `data/approx_optima.bin`. The table is a source of starting points, never of results: a
//! query outside the grid clamps to its border, and whatever the table says, the returned
//! fit is refined, measured and proven monotone like any other. Its quality is judged by
//! `tests/approx_sweep.rs`: 1000 random segments, none of them a node, against an
//! independent exhaustive search.

use crate::error::{Error, Result};
use crate::lac::LacSegment;
use kurbo::Point;
use std::sync::OnceLock;

/// α nodes: first, step, count.
pub const ALPHA_AXIS: (f64, f64, usize) = (-5.0, 0.25, 41);
/// θ_d nodes (radians): first, step, count.
pub const THETA_AXIS: (f64, f64, usize) = (
    5.0 * std::f64::consts::PI / 180.0,
    5.0 * std::f64::consts::PI / 180.0,
    35,
);
/// s nodes: first, step, count (`u = 3s² - 2s³`).
pub const S_AXIS: (f64, f64, usize) = (0.0, 0.05, 20);
/// Largest number of minima a node keeps.
pub const MAX_PER_NODE: usize = 6;

const MAGIC: &[u8; 8] = b"AEOPT02\n";

/// The shape coordinate `s` of a base-angle position `u` in [0, 1] (the root in [0, 1] of
/// `3s² - 2s³ = u`: `s = 1/2 - sin(asin(1 - 2u)/3)`).
pub fn s_of_u(u: f64) -> f64 {
    0.5 - ((1.0 - 2.0 * u.clamp(0.0, 1.0)).asin() / 3.0).sin()
}

/// The base-angle position `u` of the shape coordinate `s`.
pub fn u_of_s(s: f64) -> f64 {
    s * s * (3.0 - 2.0 * s)
}

/// The value of node `i` on `axis`.
pub fn node(axis: (f64, f64, usize), i: usize) -> f64 {
    axis.0 + axis.1 * i as f64
}

/// Index of node (i, j, k) in the table's order (α slowest, s fastest).
pub fn node_index(i: usize, j: usize, k: usize) -> usize {
    (i * THETA_AXIS.2 + j) * S_AXIS.2 + k
}

/// Number of nodes.
pub fn node_count() -> usize {
    ALPHA_AXIS.2 * THETA_AXIS.2 * S_AXIS.2
}

/// The shape (α, θ_d, u) of node `idx`. The circle u = 0 fits exactly along a whole curve
/// of (f0, f1), whose points are all "minima": the first s node stands for the limit
/// u -> 0+ and is taken at u = 1e-3.
pub fn node_shape(idx: usize) -> (f64, f64, f64) {
    let k = idx % S_AXIS.2;
    let j = (idx / S_AXIS.2) % THETA_AXIS.2;
    let i = idx / (S_AXIS.2 * THETA_AXIS.2);
    (
        node(ALPHA_AXIS, i),
        node(THETA_AXIS, j),
        u_of_s(node(S_AXIS, k)).max(1e-3),
    )
}

/// The control triangle of the shape (α, θ_d, u): start (0, 0) at the high-curvature end,
/// tangent intersection (1, 0), base angle `φ = θ_d/2 + u (θ_lim - θ_d/2)` at the start.
pub fn shape_triangle(alpha: f64, theta_d: f64, u: f64) -> Result<[Point; 3]> {
    let lim = LacSegment::theta_lim(alpha, theta_d)?;
    let phi = 0.5 * theta_d + u * (lim - 0.5 * theta_d);
    let d = phi.sin() / (theta_d - phi).sin();
    Ok([
        Point::ZERO,
        Point::new(1.0, 0.0),
        Point::new(1.0 + d * theta_d.cos(), d * theta_d.sin()),
    ])
}

/// The decoded table.
pub struct OptimaTable {
    start: Vec<u32>,
    entries: Vec<[f32; 2]>,
}

fn quantise(f: f64) -> u16 {
    (f.clamp(0.0, 1.0) * 65536.0 - 0.5)
        .round()
        .clamp(0.0, 65535.0) as u16
}

fn dequantise(q: u16) -> f32 {
    ((q as f64 + 0.5) / 65536.0) as f32
}

/// The binary form of a table: for each node in [`node_index`] order, its minima
/// `(f_hi, f_lo)` (at most [`MAX_PER_NODE`] are kept).
pub fn encode(nodes: &[Vec<(f64, f64)>]) -> Result<Vec<u8>> {
    if nodes.len() != node_count() {
        return Err(Error::invalid(
            "nodes",
            format!("{} nodes, the grid has {}", nodes.len(), node_count()),
        ));
    }
    let mut out = MAGIC.to_vec();
    for n in [ALPHA_AXIS.2, THETA_AXIS.2, S_AXIS.2] {
        out.extend_from_slice(&(n as u16).to_le_bytes());
    }
    for m in nodes {
        let m = &m[..m.len().min(MAX_PER_NODE)];
        out.push(m.len() as u8);
        for &(a, b) in m {
            out.extend_from_slice(&quantise(a).to_le_bytes());
            out.extend_from_slice(&quantise(b).to_le_bytes());
        }
    }
    Ok(out)
}

/// Decode [`encode`]'s output.
pub fn decode(bytes: &[u8]) -> Result<OptimaTable> {
    let bad = |why: &str| Error::invalid("optima table", why.to_string());
    if bytes.len() < 14 || &bytes[..8] != MAGIC {
        return Err(bad("not an optima table"));
    }
    let dim = |k: usize| u16::from_le_bytes([bytes[8 + 2 * k], bytes[9 + 2 * k]]) as usize;
    if [dim(0), dim(1), dim(2)] != [ALPHA_AXIS.2, THETA_AXIS.2, S_AXIS.2] {
        return Err(bad("its grid is not this version's"));
    }
    let mut pos = 14;
    let mut start = Vec::with_capacity(node_count() + 1);
    let mut entries = Vec::new();
    for _ in 0..node_count() {
        start.push(entries.len() as u32);
        let &count = bytes.get(pos).ok_or_else(|| bad("truncated"))?;
        pos += 1;
        for _ in 0..count {
            let b = bytes.get(pos..pos + 4).ok_or_else(|| bad("truncated"))?;
            entries.push([
                dequantise(u16::from_le_bytes([b[0], b[1]])),
                dequantise(u16::from_le_bytes([b[2], b[3]])),
            ]);
            pos += 4;
        }
    }
    if pos != bytes.len() {
        return Err(bad("trailing bytes"));
    }
    start.push(entries.len() as u32);
    Ok(OptimaTable { start, entries })
}

static TABLE: OnceLock<OptimaTable> = OnceLock::new();
static TABLE_BYTES: &[u8] = include_bytes!("../data/approx_optima.bin");

/// The table shipped with the crate, decoded on first use.
pub fn table() -> &'static OptimaTable {
    TABLE.get_or_init(|| decode(TABLE_BYTES).expect("the shipped optima table is valid"))
}

/// The cell of `x` on `axis`: the index of its lower node, clamped into the grid.
fn cell(axis: (f64, f64, usize), x: f64) -> usize {
    let t = ((x - axis.0) / axis.1).floor();
    if t.is_nan() || t < 0.0 {
        0
    } else {
        (t as usize).min(axis.2 - 2)
    }
}

impl OptimaTable {
    /// The minima `(f_hi, f_lo)` stored at node `idx`.
    pub fn at(&self, idx: usize) -> &[[f32; 2]] {
        &self.entries[self.start[idx] as usize..self.start[idx + 1] as usize]
    }

    /// Total number of stored minima.
    pub fn entry_count(&self) -> usize {
        self.entries.len()
    }

    /// Starting points for the shape (α, θ_d, u) (clamped into the grid), as `(f_hi, f_lo)`:
    /// for each minimum of the nearest of the eight surrounding nodes, its valley followed to
    /// the other seven corners (their nearest minimum within 0.05) and interpolated
    /// trilinearly, then the minimum itself; then the minima of the other corners that lie in
    /// no such valley.
    pub fn candidates(&self, alpha: f64, theta_d: f64, u: f64, out: &mut Vec<[f64; 2]>) {
        out.clear();
        let s = s_of_u(u);
        let (i, j, k) = (
            cell(ALPHA_AXIS, alpha),
            cell(THETA_AXIS, theta_d),
            cell(S_AXIS, s),
        );
        let frac = |axis: (f64, f64, usize), x: f64, i: usize| {
            ((x - node(axis, i)) / axis.1).clamp(0.0, 1.0)
        };
        let (fa, ft, fs) = (
            frac(ALPHA_AXIS, alpha, i),
            frac(THETA_AXIS, theta_d, j),
            frac(S_AXIS, s, k),
        );
        let mut corners: [(f64, usize); 8] = [(0.0, 0); 8];
        for (c, slot) in corners.iter_mut().enumerate() {
            let (di, dj, dk) = (c >> 2, (c >> 1) & 1, c & 1);
            let w = |f: f64, bit: usize| if bit == 1 { f } else { 1.0 - f };
            *slot = (
                w(fa, di) * w(ft, dj) * w(fs, dk),
                node_index(i + di, j + dj, k + dk),
            );
        }
        corners.sort_by(|a, b| b.0.total_cmp(&a.0));
        let dist = |a: [f32; 2], b: [f32; 2]| (a[0] - b[0]).abs().max((a[1] - b[1]).abs());
        const FOLLOW: f32 = 0.05;
        let anchors = self.at(corners[0].1);
        for &m in anchors {
            let mut acc = [0.0f64; 2];
            let mut followed = true;
            for &(w, idx) in &corners {
                let near = self
                    .at(idx)
                    .iter()
                    .copied()
                    .min_by(|a, b| dist(*a, m).total_cmp(&dist(*b, m)));
                match near {
                    Some(e) if dist(e, m) <= FOLLOW => {
                        acc[0] += w * e[0] as f64;
                        acc[1] += w * e[1] as f64;
                    }
                    _ => {
                        followed = false;
                        break;
                    }
                }
            }
            if followed {
                out.push(acc);
            }
            out.push([m[0] as f64, m[1] as f64]);
        }
        for &(_, idx) in corners[1..].iter().filter(|c| c.0 > 1e-9) {
            for &e in self.at(idx) {
                if anchors.iter().all(|a| dist(*a, e) > FOLLOW) {
                    out.push([e[0] as f64, e[1] as f64]);
                }
            }
        }
    }
}

/// Inflection-end shapes (`approx::inflection_cubic`'s family): nodes of `r = α/(α - 1)`,
/// first, step, count (0.05 to 0.85: α from -0.053 to -5.67; inflection ends need α < 0,
/// and the optima move smoothly with r where they move fast with α near 0).
pub const INFLECTION_R_AXIS: (f64, f64, usize) = (0.05, 0.025, 33);
/// Inflection-end shapes: θ_d nodes, those of [`THETA_AXIS`].
pub const INFLECTION_THETA_AXIS: (f64, f64, usize) = THETA_AXIS;

const INFLECTION_MAGIC: &[u8; 8] = b"AEINF01\n";

/// Number of inflection-end nodes (α slowest).
pub fn inflection_node_count() -> usize {
    INFLECTION_R_AXIS.2 * INFLECTION_THETA_AXIS.2
}

/// The shape (α, θ_d) of inflection-end node `idx`.
pub fn inflection_node_shape(idx: usize) -> (f64, f64) {
    let j = idx % INFLECTION_THETA_AXIS.2;
    let i = idx / INFLECTION_THETA_AXIS.2;
    let r = node(INFLECTION_R_AXIS, i);
    (r / (r - 1.0), node(INFLECTION_THETA_AXIS, j))
}

/// The control triangle of the inflection-end shape (α, θ_d): the inflection end at
/// (0, 0), the tangent intersection at (1, 0).
pub fn inflection_triangle(alpha: f64, theta_d: f64) -> Result<[Point; 3]> {
    let phi = crate::lac::LacInflectionSegment::base_angle(alpha, theta_d)?;
    let t = phi.sin() / (theta_d - phi).sin();
    let c1 = Point::new(1.0, 0.0);
    Ok([
        Point::ZERO,
        c1,
        c1 + kurbo::Vec2::new(theta_d.cos(), theta_d.sin()) * t,
    ])
}

/// The optimum `(f0, ln w0)` of the inflection-end fit at every node, the best the
/// generator found (`cargo run --release -p aecurve --example gen_inflection_optima`):
/// starting points, like the LAC table's, never results.
pub struct InflectionOptima {
    nodes: Vec<[f64; 2]>,
}

/// The binary form of the inflection-end optima, in node order (None: no monotone cubic
/// was found there).
pub fn encode_inflection(nodes: &[Option<(f64, f64)>]) -> Result<Vec<u8>> {
    if nodes.len() != inflection_node_count() {
        return Err(Error::invalid(
            "nodes",
            format!(
                "{} nodes, the grid has {}",
                nodes.len(),
                inflection_node_count()
            ),
        ));
    }
    let mut out = INFLECTION_MAGIC.to_vec();
    for n in [INFLECTION_R_AXIS.2, INFLECTION_THETA_AXIS.2] {
        out.extend_from_slice(&(n as u16).to_le_bytes());
    }
    for m in nodes {
        let (a, b) = m.unwrap_or((f64::NAN, f64::NAN));
        out.extend_from_slice(&a.to_le_bytes());
        out.extend_from_slice(&b.to_le_bytes());
    }
    Ok(out)
}

/// Decode [`encode_inflection`]'s output.
pub fn decode_inflection(bytes: &[u8]) -> Result<InflectionOptima> {
    let bad = |why: &str| Error::invalid("inflection optima table", why.to_string());
    if bytes.len() < 12 || &bytes[..8] != INFLECTION_MAGIC {
        return Err(bad("not an inflection optima table"));
    }
    let dim = |k: usize| u16::from_le_bytes([bytes[8 + 2 * k], bytes[9 + 2 * k]]) as usize;
    if [dim(0), dim(1)] != [INFLECTION_R_AXIS.2, INFLECTION_THETA_AXIS.2] {
        return Err(bad("its grid is not this version's"));
    }
    let body = &bytes[12..];
    if body.len() != 16 * inflection_node_count() {
        return Err(bad("its length is not the grid's"));
    }
    let f = |b: &[u8]| f64::from_le_bytes(b.try_into().expect("8 bytes"));
    Ok(InflectionOptima {
        nodes: body
            .chunks_exact(16)
            .map(|c| [f(&c[..8]), f(&c[8..])])
            .collect(),
    })
}

static INFLECTION_TABLE: OnceLock<InflectionOptima> = OnceLock::new();
static INFLECTION_BYTES: &[u8] = include_bytes!("../data/inflection_optima.bin");

/// The inflection-end table shipped with the crate, decoded on first use.
pub fn inflection_table() -> &'static InflectionOptima {
    INFLECTION_TABLE.get_or_init(|| {
        decode_inflection(INFLECTION_BYTES).expect("the shipped inflection table is valid")
    })
}

impl InflectionOptima {
    /// The optimum stored at node `idx` (None where the generator found none).
    pub fn at(&self, idx: usize) -> Option<(f64, f64)> {
        let [a, b] = *self.nodes.get(idx)?;
        (a.is_finite() && b.is_finite()).then_some((a, b))
    }

    /// Starting points `(f0, ln w0)` for the shape (α, θ_d), clamped into the grid: the
    /// bilinear blend of the four surrounding nodes' optima where they lie within 0.05 of
    /// one another (one valley), then each node's own optimum, nearest node first (stored
    /// in full: an optimum on the monotone set's boundary, rounded, can leave it).
    pub fn candidates(&self, alpha: f64, theta_d: f64, out: &mut Vec<(f64, f64)>) {
        out.clear();
        let r = alpha / (alpha - 1.0);
        let (i, j) = (
            cell(INFLECTION_R_AXIS, r),
            cell(INFLECTION_THETA_AXIS, theta_d),
        );
        let frac = |axis: (f64, f64, usize), x: f64, i: usize| {
            ((x - node(axis, i)) / axis.1).clamp(0.0, 1.0)
        };
        let (fa, ft) = (
            frac(INFLECTION_R_AXIS, r, i),
            frac(INFLECTION_THETA_AXIS, theta_d, j),
        );
        let mut corners: Vec<(f64, Option<(f64, f64)>)> = (0..4)
            .map(|c| {
                let (di, dj) = (c >> 1, c & 1);
                let w = |f: f64, bit: usize| if bit == 1 { f } else { 1.0 - f };
                (
                    w(fa, di) * w(ft, dj),
                    self.at((i + di) * INFLECTION_THETA_AXIS.2 + j + dj),
                )
            })
            .collect();
        corners.sort_by(|a, b| b.0.total_cmp(&a.0));
        let found: Vec<(f64, (f64, f64))> = corners
            .iter()
            .filter_map(|&(w, x)| x.map(|x| (w, x)))
            .collect();
        let one_valley = found.len() == 4
            && found.iter().all(|a| {
                found
                    .iter()
                    .all(|b| (a.1 .0 - b.1 .0).abs().max((a.1 .1 - b.1 .1).abs()) <= 0.05)
            });
        if one_valley {
            let blend = found.iter().fold((0.0, 0.0), |acc, &(w, x)| {
                (acc.0 + w * x.0, acc.1 + w * x.1)
            });
            out.push(blend);
        }
        out.extend(found.iter().map(|c| c.1));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_and_shape_coordinates() {
        let mut nodes = vec![Vec::new(); node_count()];
        nodes[5] = vec![(0.25, 0.75), (0.5, 0.125)];
        let t = decode(&encode(&nodes).unwrap()).unwrap();
        assert_eq!(t.entry_count(), 2);
        assert!((t.at(5)[1][0] - 0.5).abs() < 2e-5 && (t.at(5)[0][1] - 0.75).abs() < 2e-5);
        assert!(decode(&encode(&nodes).unwrap()[..20]).is_err());
        for u in [0.0, 1e-6, 0.3, 0.5, 0.9, 0.999, 1.0] {
            assert!((u_of_s(s_of_u(u)) - u).abs() < 1e-12, "{u}");
        }
        assert!(s_of_u(0.3) > 0.0 && s_of_u(0.3) < s_of_u(0.9) && s_of_u(0.999) < 1.0);
    }

    #[test]
    fn shipped_table_covers_every_node_whose_segment_exists() {
        // A node without minima is one whose segment does not exist (α = 0 within a few
        // per cent of θ_lim: 38 nodes), never one the generator failed on.
        let t = table();
        let mut empty = 0;
        for idx in 0..node_count() {
            if t.at(idx).is_empty() {
                empty += 1;
                let (alpha, theta_d, u) = node_shape(idx);
                let exists = shape_triangle(alpha, theta_d, u)
                    .and_then(|tri| LacSegment::new(alpha, tri))
                    .is_ok();
                assert!(
                    !exists,
                    "node {idx} ({alpha}, {theta_d}, {u}) has a segment but no minimum"
                );
            }
        }
        assert!(empty < node_count() / 100, "{empty} empty nodes");
        assert!(t
            .entries
            .iter()
            .all(|e| e[0] > 0.0 && e[0] < 1.0 && e[1] > 0.0 && e[1] < 1.0));
    }

    #[test]
    fn inflection_table_round_trips_and_its_optima_are_monotone_cubics() {
        let mut nodes = vec![None; inflection_node_count()];
        nodes[7] = Some((0.3, -1.25));
        let t = decode_inflection(&encode_inflection(&nodes).unwrap()).unwrap();
        assert_eq!(t.at(7), Some((0.3, -1.25)));
        assert_eq!(t.at(8), None);
        assert!(decode_inflection(&encode_inflection(&nodes).unwrap()[..40]).is_err());
        // The shipped optima: each a curvature-monotone cubic of its node's segment (by the
        // exact test), f0 in (0, 1); nodes without one are few.
        use crate::approx::inflection_cubic;
        use crate::lac::LacInflectionSegment;
        use crate::monotone::CurvatureMonotone;
        let t = inflection_table();
        let mut empty = 0;
        for idx in 0..inflection_node_count() {
            let Some((f0, lw)) = t.at(idx) else {
                empty += 1;
                continue;
            };
            let (alpha, theta_d) = inflection_node_shape(idx);
            let seg =
                LacInflectionSegment::new(inflection_triangle(alpha, theta_d).unwrap()).unwrap();
            assert!(f0 > 0.0 && f0 < 1.0, "node {idx}: f0 {f0}");
            let c = inflection_cubic(&seg, f0, lw.exp()).unwrap();
            assert!(
                c.is_curvature_monotone().unwrap(),
                "node {idx} ({alpha}, {theta_d}): its optimum is not monotone"
            );
        }
        assert!(empty * 30 < inflection_node_count(), "{empty} empty nodes");
        // Between nodes: candidates, the nearest node's own among them.
        let mut out = Vec::new();
        let (alpha, theta_d) = inflection_node_shape(40);
        t.candidates(alpha, theta_d + 0.01, &mut out);
        assert!(out.contains(&t.at(40).unwrap()), "{out:?}");
    }
}
