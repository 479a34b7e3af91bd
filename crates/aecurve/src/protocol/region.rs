//! `region.map`: which positions of one control point keep a property, on a grid over a
//! box: the existence region of a LAC segment's third control point (`kind: lac`), the same
//! for a segment with an inflection end (`kind: inflection`), the curvature-monotone region
//! of a Bézier control point (`kind: bezier`). The editor shades it behind the point being
//! dragged (`POST /api/region` answers this op).

use super::fields::{self, IntIn, Points, Weights};
use super::{Op, ProtoError, Request};
use aesthetic_curves::region::{self, Grid};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The work budget of a Bézier region request: cells times (Bernstein degree of the exact
/// test)^1.5, about 0.5 µs each on one core, so the worst case (every cell judged) stays near
/// 2 s; a cubic's region may have 200 x 200 cells, a degree-20 rational curve's about 42 x 42.
pub const REGION_WORK_BUDGET: f64 = 4.0e6;

/// Largest region grid (cells per side).
pub const MAX_REGION_CELLS: usize = 200;

/// Cells along one side of a region's grid.
type Cells = IntIn<1, { MAX_REGION_CELLS as u64 }>;

/// A grid over a box: `{"x0", "y0", "x1", "y1", "nx", "ny"}`; cells judged at their centres.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GridJson {
    /// The box's left.
    x0: f64,
    /// The box's bottom.
    y0: f64,
    /// The box's right.
    x1: f64,
    /// The box's top.
    y1: f64,
    /// Cells across.
    nx: Cells,
    /// Cells up.
    ny: Cells,
}

impl GridJson {
    /// The library's grid.
    pub fn grid(&self) -> Result<Grid, ProtoError> {
        let (nx, ny) = (self.nx.0 as usize, self.ny.0 as usize);
        Ok(Grid::new(self.x0, self.y0, self.x1, self.y1, nx, ny)?)
    }
}

/// What a region request asks, by its `kind`.
#[derive(Debug, Deserialize, JsonSchema)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum RegionRequest {
    /// Where `control[2]` may go for a LAC segment of this α to exist.
    Lac {
        /// The shape parameter α.
        alpha: f64,
        /// The control triangle (the third point is the one moved).
        control: Points<3, 3>,
        /// The grid of places tried for it.
        grid: GridJson,
    },
    /// Where `control[2]` may go for an inflection-end segment to exist.
    Inflection {
        /// The control triangle (the third point is the one moved).
        control: Points<3, 3>,
        /// The grid of places tried for it.
        grid: GridJson,
    },
    /// Where control point `index` keeps a Bézier curve's curvature monotone.
    Bezier {
        /// The curve's control points (degree 2 to 20).
        control_points: Points<3, 21>,
        /// Positive weights, one per control point (a rational curve).
        #[serde(default)]
        weights: Option<Weights>,
        /// The control point moved.
        index: usize,
        /// The grid of places tried for it.
        grid: GridJson,
    },
}

impl Request for RegionRequest {
    fn check(&self) -> Result<(), ProtoError> {
        if let RegionRequest::Bezier {
            control_points,
            weights,
            index,
            grid,
        } = self
        {
            let n = control_points.0.len();
            if *index >= n {
                return Err(ProtoError::invalid("index", "must name a control point"));
            }
            if let Some(w) = weights {
                fields::check_weight_count("weights", n, w.len())?;
            }
            // Work budget: the exact test costs about td^1.5 (td its Bernstein degree) per
            // judged cell; the budget holds the worst case (every cell judged) to a couple
            // of seconds.
            let td = aesthetic_curves::monotone::exact_test_degree(n - 1, weights.is_some()) as f64;
            let cells = (grid.nx.0 * grid.ny.0) as usize;
            let most = (REGION_WORK_BUDGET / td.powf(1.5)).floor() as usize;
            if cells > most {
                return Err(ProtoError::invalid(
                    "grid",
                    format!(
                        "{cells} cells exceed the region budget for a {} Bézier curve of degree \
                         {} (exact test of degree {td}): at most {most} cells",
                        if weights.is_some() {
                            "rational"
                        } else {
                            "polynomial"
                        },
                        n - 1
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// Threads for a region: half the cores, so the other half stays free for the interactive
/// requests.
fn region_threads() -> usize {
    (std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(2)
        / 2)
    .max(1)
}

/// The grid's rows, from y0 up: '1' where the property holds, '0' where not.
#[derive(Debug, Serialize, JsonSchema)]
pub struct RegionResult {
    /// One string per grid row from `y0` up, one character per cell from `x0` right.
    pub rows: Vec<String>,
    /// Cells actually tested (the others were decided from their neighbours).
    pub judged: usize,
}

/// `region.map`.
pub struct RegionMap;

impl Op for RegionMap {
    const NAME: &'static str = "region.map";
    type Request = RegionRequest;
    type Response = RegionResult;

    fn answer(req: RegionRequest) -> Result<RegionResult, ProtoError> {
        let threads = region_threads();
        let r = match req {
            RegionRequest::Lac {
                alpha,
                control: Points(c),
                grid,
            } => region::lac_existence(alpha, c[0], c[1], grid.grid()?, threads)?,
            RegionRequest::Inflection {
                control: Points(c),
                grid,
            } => region::inflection_existence(c[0], c[1], grid.grid()?, threads)?,
            RegionRequest::Bezier {
                control_points: Points(pts),
                weights,
                index,
                grid,
            } => {
                let w = weights.map(|w| fields::weights(&w));
                region::bezier_monotone(&pts, w.as_deref(), index, grid.grid()?, 4, threads)?
            }
        };
        Ok(RegionResult {
            rows: r.rows(),
            judged: r.judged(),
        })
    }
}
