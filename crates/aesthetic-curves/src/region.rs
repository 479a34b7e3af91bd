//! Regions of one control point: where, on a grid of cells over a box, a control point may
//! go and keep a property. These are the shaded regions of an interactive editor (Yoshida et
//! al.'s CurveToolWithCMRegion shades the curvature-monotone region of a cubic's control
//! point), computed from the library's own tests.
//!
//! - [`lac_existence`]: where the third control point of a LAC segment of shape α may go
//!   ([`LacSegment::exists`]: base angle below θ_lim; for α < 0 or α > 1 θ_lim is
//!   interpolated, with the exact value inside a measured guard band; for 0 <= α <= 1 every
//!   triangle has a segment).
//! - [`inflection_existence`]: the same for a segment with an inflection end
//!   ([`LacInflectionSegment::exists`], no integral).
//! - [`bezier_monotone`]: where one control point of a polynomial or rational Bézier curve
//!   keeps its curvature monotone, by the exact test of [`crate::monotone`].
//!
//! ## Contract
//!
//! Each cell is judged at its centre. The LAC and inflection regions judge every cell. The
//! Bézier region judges a lattice of every `block`-th cell first and then every cell of each
//! block whose lattice neighbourhood (its 4 corners and the 8 lattice points around them)
//! is not uniform; uniform blocks are filled. So its boundary is exact to the cell, and an
//! island or a sliver narrower than `block` cells that touches no lattice point can be
//! missed: `block = 1` judges every cell. Positions where the test reports an error
//! (coincident points, a cusp) count as outside.
//!
//! Work is split over `threads` scoped threads by rows.

use crate::error::{Error, Result};
use crate::lac::{LacInflectionSegment, LacSegment};
use crate::monotone::CurvatureMonotone;
use crate::{Bezier, RationalBezier};
use kurbo::Point;

/// Largest number of cells per side of a grid.
pub const MAX_CELLS_PER_SIDE: usize = 1000;

/// A grid of `nx` x `ny` cells over the box `[x0, x1] x [y0, y1]`; row `i` runs along x at
/// height `y0 + (i + 1/2) (y1 - y0) / ny`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grid {
    x0: f64,
    y0: f64,
    x1: f64,
    y1: f64,
    nx: usize,
    ny: usize,
}

impl Grid {
    /// A grid; the box must be finite with `x1 > x0`, `y1 > y0`, and the counts in
    /// `1..=MAX_CELLS_PER_SIDE`.
    pub fn new(x0: f64, y0: f64, x1: f64, y1: f64, nx: usize, ny: usize) -> Result<Grid> {
        if ![x0, y0, x1, y1].iter().all(|v| v.is_finite()) {
            return Err(Error::invalid("grid", "the box must be finite"));
        }
        if !(x1 > x0 && y1 > y0 && (x1 - x0).is_finite() && (y1 - y0).is_finite()) {
            return Err(Error::invalid(
                "grid",
                "needs x1 > x0 and y1 > y0 (and a finite size)",
            ));
        }
        for (name, n) in [("nx", nx), ("ny", ny)] {
            if !(1..=MAX_CELLS_PER_SIDE).contains(&n) {
                return Err(Error::invalid(
                    name,
                    format!("must be an integer in 1..={MAX_CELLS_PER_SIDE}"),
                ));
            }
        }
        Ok(Grid {
            x0,
            y0,
            x1,
            y1,
            nx,
            ny,
        })
    }

    /// Cells per row.
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Rows.
    pub fn ny(&self) -> usize {
        self.ny
    }

    /// Centre of the cell in row `i`, column `k`.
    pub fn centre(&self, i: usize, k: usize) -> Point {
        Point::new(
            self.x0 + (k as f64 + 0.5) * (self.x1 - self.x0) / self.nx as f64,
            self.y0 + (i as f64 + 0.5) * (self.y1 - self.y0) / self.ny as f64,
        )
    }
}

/// Which cells of a [`Grid`] hold a property.
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    grid: Grid,
    cells: Vec<bool>,
    judged: usize,
}

impl Region {
    /// The grid.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// Whether the cell in row `i`, column `k` holds the property.
    pub fn get(&self, i: usize, k: usize) -> bool {
        self.cells[i * self.grid.nx + k]
    }

    /// Number of cells inside.
    pub fn count(&self) -> usize {
        self.cells.iter().filter(|c| **c).count()
    }

    /// Number of cells whose centre was actually judged (the others were filled).
    pub fn judged(&self) -> usize {
        self.judged
    }

    /// One string per row from `y0` up: '1' inside, '0' outside.
    pub fn rows(&self) -> Vec<String> {
        self.cells
            .chunks(self.grid.nx)
            .map(|r| r.iter().map(|c| if *c { '1' } else { '0' }).collect())
            .collect()
    }
}

/// Run `judge` on the listed cells over `threads` threads; returns the verdicts in order.
fn judge_cells(
    cells: &[(usize, usize)],
    threads: usize,
    judge: &(dyn Fn(usize, usize) -> bool + Sync),
) -> Vec<bool> {
    let mut out = vec![false; cells.len()];
    let threads = threads.clamp(1, cells.len().max(1));
    let chunk = cells.len().div_ceil(threads).max(1);
    std::thread::scope(|s| {
        for (part, work) in out.chunks_mut(chunk).zip(cells.chunks(chunk)) {
            s.spawn(move || {
                for (o, &(i, k)) in part.iter_mut().zip(work) {
                    *o = judge(i, k);
                }
            });
        }
    });
    out
}

/// Every cell judged.
fn every_cell(grid: Grid, threads: usize, judge: &(dyn Fn(usize, usize) -> bool + Sync)) -> Region {
    let cells: Vec<(usize, usize)> = (0..grid.ny)
        .flat_map(|i| (0..grid.nx).map(move |k| (i, k)))
        .collect();
    let verdicts = judge_cells(&cells, threads, judge);
    Region {
        grid,
        judged: cells.len(),
        cells: verdicts,
    }
}

/// Lattice first, then the blocks whose neighbourhood is not uniform (module docs).
fn refined(
    grid: Grid,
    block: usize,
    threads: usize,
    judge: &(dyn Fn(usize, usize) -> bool + Sync),
) -> Region {
    let block = block.max(1);
    if block == 1 {
        return every_cell(grid, threads, judge);
    }
    // Lattice lines: every block-th index, plus the last one.
    let lines = |n: usize| -> Vec<usize> {
        let mut v: Vec<usize> = (0..n).step_by(block).collect();
        if *v.last().unwrap() != n - 1 {
            v.push(n - 1);
        }
        v
    };
    let (rows, cols) = (lines(grid.ny), lines(grid.nx));
    let lattice: Vec<(usize, usize)> = rows
        .iter()
        .flat_map(|&i| cols.iter().map(move |&k| (i, k)))
        .collect();
    let lv = judge_cells(&lattice, threads, judge);
    let at = |a: usize, b: usize| lv[a * cols.len() + b];
    let mut cells = vec![false; grid.nx * grid.ny];
    let mut known = vec![false; grid.nx * grid.ny];
    for (n, &(i, k)) in lattice.iter().enumerate() {
        cells[i * grid.nx + k] = lv[n];
        known[i * grid.nx + k] = true;
    }
    // Blocks between lattice lines a..a+1 (rows) and b..b+1 (columns).
    let mut todo = Vec::new();
    for a in 0..rows.len().saturating_sub(1) {
        for b in 0..cols.len().saturating_sub(1) {
            let v = at(a, b);
            let (ra, rb) = (a.saturating_sub(1), (a + 2).min(rows.len() - 1));
            let (ca, cb) = (b.saturating_sub(1), (b + 2).min(cols.len() - 1));
            let uniform = (ra..=rb).all(|r| (ca..=cb).all(|c| at(r, c) == v));
            for i in rows[a]..=rows[a + 1] {
                for k in cols[b]..=cols[b + 1] {
                    let j = i * grid.nx + k;
                    if known[j] {
                        continue;
                    }
                    if uniform {
                        cells[j] = v;
                        known[j] = true;
                    } else {
                        known[j] = true;
                        todo.push((i, k));
                    }
                }
            }
        }
    }
    // A single lattice row or column (ny or nx of 1) leaves cells outside every block.
    for i in 0..grid.ny {
        for k in 0..grid.nx {
            if !known[i * grid.nx + k] {
                todo.push((i, k));
            }
        }
    }
    let tv = judge_cells(&todo, threads, judge);
    for (&(i, k), v) in todo.iter().zip(tv) {
        cells[i * grid.nx + k] = v;
    }
    Region {
        grid,
        judged: lattice.len() + todo.len(),
        cells,
    }
}

/// Where the third control point of a LAC segment of shape `alpha` with start `p0` and
/// tangent intersection `p1` may go. Errors: `alpha` not finite or beyond
/// [`crate::lac::MAX_ABS_ALPHA`]; coincident or non-finite `p0`, `p1`.
///
/// Every cell is judged exactly by `θ_d/2 <= φ < θ_lim(α, θ_d)`. θ_lim (one integral) is
/// interpolated from [`THETA_LIM_NODES`] nodes over the grid's range of θ_d; the
/// interpolation error is measured at every midpoint, and a cell whose φ lies within a
/// guard band (8 times that error) of the interpolated θ_lim gets the exact θ_lim. So the
/// verdicts equal [`LacSegment::exists`] at every cell centre, at a fraction of the cost.
pub fn lac_existence(
    alpha: f64,
    p0: Point,
    p1: Point,
    grid: Grid,
    threads: usize,
) -> Result<Region> {
    check_base(p0, p1)?;
    // Surface a bad alpha as an error rather than an empty region.
    LacSegment::exists(alpha, [p0, p1, p1 + (p1 - p0).turn_90()])?;
    let angles: Vec<Option<(f64, f64)>> = (0..grid.ny)
        .flat_map(|i| (0..grid.nx).map(move |k| (i, k)))
        .map(|(i, k)| LacSegment::triangle_angles([p0, p1, grid.centre(i, k)]).ok())
        .collect();
    let exact = |a: &Option<(f64, f64)>| -> bool {
        a.is_some_and(|(td, phi)| LacSegment::exists_for_angles(alpha, td, phi).unwrap_or(false))
    };
    let table = if (0.0..=1.0).contains(&alpha) {
        None
    } else {
        let (lo, hi) = angles
            .iter()
            .flatten()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (td, _)| {
                (lo.min(*td), hi.max(*td))
            });
        ThetaLimTable::new(alpha, lo, hi)
    };
    let judge = |n: usize| -> bool {
        match (&table, angles[n]) {
            (_, None) => false,
            (None, _) => exact(&angles[n]),
            (Some(t), Some((td, phi))) => {
                let lim = t.at(td);
                if (phi - lim).abs() <= t.guard {
                    exact(&angles[n])
                } else {
                    phi < lim
                }
            }
        }
    };
    Ok(every_cell(grid, threads, &|i, k| judge(i * grid.nx + k)))
}

/// Nodes of the θ_lim interpolant of [`lac_existence`].
pub const THETA_LIM_NODES: usize = 48;

/// θ_lim(α, ·) on uniform nodes over [lo, hi] with 4-point Lagrange interpolation and a
/// guard band from the error measured at every midpoint.
struct ThetaLimTable {
    lo: f64,
    h: f64,
    vals: Vec<f64>,
    guard: f64,
}

impl ThetaLimTable {
    /// `None` when the range is empty or θ_lim fails at a node (then cells are judged exactly).
    fn new(alpha: f64, lo: f64, hi: f64) -> Option<ThetaLimTable> {
        if !(lo.is_finite() && hi.is_finite() && hi > lo) {
            return None;
        }
        let n = THETA_LIM_NODES;
        let h = (hi - lo) / (n - 1) as f64;
        let vals = (0..n)
            .map(|j| LacSegment::theta_lim(alpha, lo + j as f64 * h).ok())
            .collect::<Option<Vec<f64>>>()?;
        let mut t = ThetaLimTable {
            lo,
            h,
            vals,
            guard: 0.0,
        };
        let mut err: f64 = 0.0;
        for j in 0..n - 1 {
            let x = lo + (j as f64 + 0.5) * h;
            err = err.max((LacSegment::theta_lim(alpha, x).ok()? - t.at(x)).abs());
        }
        t.guard = 8.0 * err + 1e-12;
        Some(t)
    }

    fn at(&self, x: f64) -> f64 {
        let n = self.vals.len();
        let u = ((x - self.lo) / self.h).clamp(0.0, (n - 1) as f64);
        // Stencil j0..j0+3 around u, kept inside the table.
        let j0 = (u.floor() as isize - 1).clamp(0, n as isize - 4) as usize;
        let t = u - j0 as f64;
        let mut sum = 0.0;
        for a in 0..4 {
            let mut w = 1.0;
            for b in 0..4 {
                if a != b {
                    w *= (t - b as f64) / (a as f64 - b as f64);
                }
            }
            sum += w * self.vals[j0 + a];
        }
        sum
    }
}

/// Where the third control point of a segment with an inflection end at `p0` and tangent
/// intersection `p1` may go. Errors: coincident `p0`, `p1`.
pub fn inflection_existence(p0: Point, p1: Point, grid: Grid, threads: usize) -> Result<Region> {
    check_base(p0, p1)?;
    Ok(every_cell(grid, threads, &|i, k| {
        LacInflectionSegment::exists([p0, p1, grid.centre(i, k)]).unwrap_or(false)
    }))
}

fn check_base(p0: Point, p1: Point) -> Result<()> {
    if !(p0.is_finite() && p1.is_finite()) {
        return Err(Error::invalid("control", "control points must be finite"));
    }
    if p0 == p1 {
        return Err(Error::Degenerate(
            "the first two control points coincide: the start tangent is undefined".into(),
        ));
    }
    Ok(())
}

/// Where control point `index` of the Bézier curve `control` (rational with `weights`)
/// keeps the curvature monotone over the whole curve, by the exact test; `block` is the
/// lattice step of the refinement (module docs; 4 is a good default, 1 judges every cell).
/// Errors: an index out of range, a bad curve (degree, weights, non-finite points).
pub fn bezier_monotone(
    control: &[Point],
    weights: Option<&[f64]>,
    index: usize,
    grid: Grid,
    block: usize,
    threads: usize,
) -> Result<Region> {
    if index >= control.len() {
        return Err(Error::invalid(
            "index",
            format!("must name a control point (0..{})", control.len()),
        ));
    }
    // Validate the curve as given (degree, weights), so bad input is an error, not a blank.
    match weights {
        None => Bezier::new(control.to_vec()).map(|_| ())?,
        Some(w) => RationalBezier::new(control.to_vec(), w.to_vec()).map(|_| ())?,
    }
    Ok(refined(grid, block, threads, &|i, k| {
        let mut p = control.to_vec();
        p[index] = grid.centre(i, k);
        // The verdict alone: the same exact test, without locating the extrema.
        let verdict = match weights {
            None => Bezier::new(p).and_then(|b| b.is_curvature_monotone()),
            Some(w) => RationalBezier::new(p, w.to_vec()).and_then(|b| b.is_curvature_monotone()),
        };
        verdict.unwrap_or(false)
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_validates_and_places_centres() {
        assert!(Grid::new(0.0, 0.0, 1.0, 1.0, 0, 3).is_err());
        assert!(Grid::new(0.0, 0.0, 0.0, 1.0, 3, 3).is_err());
        assert!(Grid::new(f64::NAN, 0.0, 1.0, 1.0, 3, 3).is_err());
        assert!(Grid::new(-1e308, 0.0, 1e308, 1.0, 3, 3).is_err());
        assert!(Grid::new(0.0, 0.0, 1.0, 1.0, 3, MAX_CELLS_PER_SIDE + 1).is_err());
        let g = Grid::new(0.0, 0.0, 4.0, 2.0, 4, 2).unwrap();
        assert_eq!(g.centre(0, 0), Point::new(0.5, 0.5));
        assert_eq!(g.centre(1, 3), Point::new(3.5, 1.5));
    }

    #[test]
    fn lac_region_matches_theta_lim_and_every_cell_for_zero_to_one() {
        let (p0, p1) = (Point::new(0.0, 0.0), Point::new(1.0, 0.0));
        let g = Grid::new(-1.0, -1.5, 2.5, 1.5, 41, 37).unwrap();
        // Interpolated θ_lim with its guard band against the exact test at every cell, also
        // on a view zoomed onto the boundary (where the guard band decides).
        for alpha in [-3.0, -1.0, -0.3, 1.5, 2.0, 3.0] {
            let r = lac_existence(alpha, p0, p1, g, 2).unwrap();
            assert_eq!(r.judged(), 41 * 37);
            let mut edge = None;
            for i in 0..37 {
                for k in 0..41 {
                    let c = [p0, p1, g.centre(i, k)];
                    let want = LacSegment::exists(alpha, c).unwrap_or(false);
                    assert_eq!(r.get(i, k), want, "alpha {alpha}, cell {i} {k}");
                    if k > 0 && r.get(i, k) != r.get(i, k - 1) && g.centre(i, k).y > 0.3 {
                        edge = Some((g.centre(i, k - 1), g.centre(i, k)));
                    }
                }
            }
            let n = r.count();
            assert!(n > 100 && n < 41 * 37 - 100, "alpha {alpha}: {n}");
            // The boundary between the two cells, by bisection on the exact test.
            let (mut a, mut b) = edge.expect("a boundary crossing");
            let inside = |q: Point| LacSegment::exists(alpha, [p0, p1, q]).unwrap_or(false);
            let ia = inside(a);
            for _ in 0..60 {
                let m = a.midpoint(b);
                if inside(m) == ia {
                    a = m
                } else {
                    b = m
                }
            }
            let e = a;
            let z = Grid::new(e.x - 1e-3, e.y - 1e-3, e.x + 1e-3, e.y + 1e-3, 25, 25).unwrap();
            let rz = lac_existence(alpha, p0, p1, z, 1).unwrap();
            for i in 0..25 {
                for k in 0..25 {
                    let c = [p0, p1, z.centre(i, k)];
                    let want = LacSegment::exists(alpha, c).unwrap_or(false);
                    assert_eq!(rz.get(i, k), want, "zoomed, alpha {alpha}, cell {i} {k}");
                }
            }
            let nz = rz.count();
            assert!(
                nz > 0 && nz < 625,
                "the zoomed view straddles the boundary: {nz}"
            );
        }
        // 0 <= alpha <= 1: every non-degenerate triangle (all cells off the x axis).
        let g2 = Grid::new(-1.0, 0.05, 2.5, 1.5, 20, 10).unwrap();
        assert_eq!(lac_existence(0.5, p0, p1, g2, 1).unwrap().count(), 200);
        assert!(lac_existence(f64::NAN, p0, p1, g, 1).is_err());
        assert!(lac_existence(-1.0, p0, p0, g, 1).is_err());
        assert!(lac_existence(-1.0, p0, Point::new(f64::INFINITY, 0.0), g, 1).is_err());
        // Mirror symmetry about the tangent line: row i and row ny-1-i for a symmetric box.
        let gs = Grid::new(-1.0, -1.5, 2.5, 1.5, 30, 30).unwrap();
        let rs = lac_existence(2.0, p0, p1, gs, 2).unwrap();
        for i in 0..30 {
            for k in 0..30 {
                assert_eq!(rs.get(i, k), rs.get(29 - i, k), "{i} {k}");
            }
        }
    }

    #[test]
    fn inflection_region_is_the_wedge_below_half_the_turning() {
        let (p0, p1) = (Point::new(0.0, 0.0), Point::new(1.0, 0.0));
        let g = Grid::new(-1.0, -1.0, 3.0, 1.0, 40, 20).unwrap();
        let r = inflection_existence(p0, p1, g, 2).unwrap();
        for i in 0..20 {
            for k in 0..40 {
                let c = [p0, p1, g.centre(i, k)];
                let want = LacInflectionSegment::new(c).is_ok();
                assert_eq!(r.get(i, k), want, "{i} {k}");
            }
        }
        assert!(r.count() > 20);
    }

    #[test]
    fn refined_bezier_region_equals_every_cell() {
        // A cubic whose second control point moves: the refined region (block 4) must equal
        // the region judged at every cell on this smooth example.
        let ctrl = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(2.0, 0.6),
            Point::new(2.6, 1.6),
        ];
        let g = Grid::new(-0.5, -1.0, 2.5, 1.5, 45, 38).unwrap();
        let full = bezier_monotone(&ctrl, None, 1, g, 1, 2).unwrap();
        let fast = bezier_monotone(&ctrl, None, 1, g, 4, 2).unwrap();
        assert_eq!(full.rows(), fast.rows());
        assert!(fast.judged() < full.judged() / 2, "{}", fast.judged());
        let n = full.count();
        assert!(n > 50 && n < 45 * 38 - 50, "{n}");
        // Rational, every weight 1: the same region as the polynomial curve.
        let rat = bezier_monotone(&ctrl, Some(&[1.0; 4]), 1, g, 4, 2).unwrap();
        assert_eq!(rat.rows(), fast.rows());
        assert!(bezier_monotone(&ctrl, None, 4, g, 4, 1).is_err());
        assert!(bezier_monotone(&ctrl, Some(&[1.0, -1.0, 1.0, 1.0]), 1, g, 4, 1).is_err());
        // A grid of one row or one column still judges every cell.
        let thin = Grid::new(-0.5, 0.2, 2.5, 0.3, 17, 1).unwrap();
        let a = bezier_monotone(&ctrl, None, 1, thin, 4, 1).unwrap();
        let b = bezier_monotone(&ctrl, None, 1, thin, 1, 1).unwrap();
        assert_eq!(a.rows(), b.rows());
    }
}
