//! What `aecurve fix --json` prints: a file's (UFO, SVG) or a designspace's repair, in the
//! protocol's types (its joins are `outline.fix`'s [`FixJoinJson`]), so that the schema
//! (`aecurve schema`, `$defs`) describes it and a client reads both the same way.

use super::outline::FixJoinJson;
use crate::fix::{ContourFix, FixCounts, FixOptions};
use aesthetic_curves::harmonize::JoinOutcome;
use aesthetic_curves::Point;
use schemars::JsonSchema;
use serde::Serialize;
use std::path::Path;

/// What was asked: the files and the options.
#[derive(Debug, Serialize, JsonSchema)]
pub struct FixHead {
    /// The file read.
    pub input: String,
    /// The file written.
    pub output: String,
    /// How far the outline may move (font units).
    pub tolerance: f64,
    /// The grid the coordinates are rounded to (0: none).
    pub grid: f64,
    /// Whether on-curve points may move too.
    pub move_points: bool,
}

impl FixHead {
    /// The head of a fix of `input` into `output` with `opts`.
    pub fn new(input: &Path, output: &Path, opts: &FixOptions) -> Self {
        FixHead {
            input: input.display().to_string(),
            output: output.display().to_string(),
            tolerance: opts.tolerance,
            grid: opts.grid,
            move_points: opts.move_points,
        }
    }
}

/// The counts of one file's (or master's) repair.
#[derive(Debug, Serialize, JsonSchema)]
pub struct FixCountsJson {
    /// Smooth joins between two cubics.
    pub smooth_cubic_joins: usize,
    /// Of those, under a 1 % relative curvature jump before.
    pub under_1_percent_before: usize,
    /// Of those, under a 1 % relative curvature jump after.
    pub under_1_percent_after: usize,
    /// Joins worse after than before (jump or angle): 0 by construction.
    pub worse_joins: usize,
    /// Cubics with more curvature extrema after: 0 by construction.
    pub cubics_with_more_extrema: usize,
    /// Segments changed.
    pub changed_segments: usize,
    /// How far the outline moved, the largest over the segments.
    pub max_moved: f64,
    /// Contours left alone (quadratic or unreadable), each listed with its reason.
    pub skipped_contours: usize,
    /// Cubics with a hook (an extremum within 5 % of an end) or several extrema, before.
    pub bumps_before: usize,
    /// The same, after.
    pub bumps_after: usize,
}

impl From<&FixCounts> for FixCountsJson {
    fn from(c: &FixCounts) -> Self {
        FixCountsJson {
            smooth_cubic_joins: c.smooth_cubic_joins,
            under_1_percent_before: c.under_1_percent.0,
            under_1_percent_after: c.under_1_percent.1,
            worse_joins: c.worse,
            cubics_with_more_extrema: c.gained_extrema,
            changed_segments: c.changed_segments,
            max_moved: c.max_moved,
            skipped_contours: c.skipped_contours,
            bumps_before: c.bumps.0,
            bumps_after: c.bumps.1,
        }
    }
}

/// A changed segment of a contour.
#[derive(Debug, Serialize, JsonSchema)]
pub struct SegmentChangeJson {
    /// Its index in the contour.
    pub segment: usize,
    /// Its control points before.
    pub before: Vec<[f64; 2]>,
    /// Its control points after.
    pub after: Vec<[f64; 2]>,
    /// How far it moved (the largest distance between the two, as shapes).
    pub moved: f64,
    /// Its interior curvature extrema before and after (the exact test; null: not a cubic,
    /// or the test could not run).
    pub extrema: [Option<usize>; 2],
}

/// One contour of the file: what changed, or why it was left alone.
#[derive(Debug, Serialize, JsonSchema)]
pub struct ContourFixJson {
    /// The glyph's name (an SVG file: the path's index).
    pub glyph: String,
    /// The contour's index in the glyph.
    pub contour: usize,
    /// Why the contour was left alone (quadratic, unreadable), if it was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub skipped: Option<String>,
    /// The segments that changed.
    pub segments: Vec<SegmentChangeJson>,
    /// Every join that is not a corner, before and after.
    pub joins: Vec<FixJoinJson>,
}

impl From<&ContourFix> for ContourFixJson {
    fn from(f: &ContourFix) -> Self {
        let pts = |v: &[Point]| v.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>();
        let mut out = ContourFixJson {
            glyph: f.glyph.clone(),
            contour: f.contour,
            skipped: None,
            segments: Vec::new(),
            joins: Vec::new(),
        };
        let (h, c) = match (&f.result, &f.input) {
            (Err(why), _) => {
                out.skipped = Some(why.clone());
                return out;
            }
            (Ok(h), Some(c)) => (h, c),
            (Ok(_), None) => return out,
        };
        out.segments = (h.segments.iter().enumerate())
            .filter(|(i, s)| **s != c.segments[*i])
            .map(|(i, s)| SegmentChangeJson {
                segment: i,
                before: pts(&c.segments[i]),
                after: pts(s),
                moved: h.moved[i],
                extrema: [h.extrema[i].0, h.extrema[i].1],
            })
            .collect();
        out.joins = (h.joins.iter())
            // A corner is the one outcome of a join the input did not mark smooth.
            .filter(|j| !matches!(j.outcome, JoinOutcome::Corner))
            .map(|j| FixJoinJson::of(j, true))
            .collect();
        out
    }
}

/// `aecurve fix --json` on a UFO or an SVG file.
#[derive(Debug, Serialize, JsonSchema)]
pub struct FixFileResult {
    /// What was asked.
    #[serde(flatten)]
    pub head: FixHead,
    /// The counts.
    pub counts: FixCountsJson,
    /// Every contour, changed or not.
    pub contours: Vec<ContourFixJson>,
}

impl FixFileResult {
    /// The answer for `fixes` and their counts.
    pub fn new(head: FixHead, fixes: &[ContourFix], counts: &FixCounts) -> Self {
        FixFileResult {
            head,
            counts: counts.into(),
            contours: fixes.iter().map(ContourFixJson::from).collect(),
        }
    }
}

/// One master of a designspace's repair.
#[derive(Debug, Serialize, JsonSchema)]
pub struct MasterFixJson {
    /// The master's file name in the designspace.
    pub source: String,
    /// Its counts.
    pub counts: FixCountsJson,
    /// Its contours.
    pub contours: Vec<ContourFixJson>,
}

/// `aecurve fix --json` on a designspace.
#[derive(Debug, Serialize, JsonSchema)]
pub struct FixDesignspaceResult {
    /// What was asked.
    #[serde(flatten)]
    pub head: FixHead,
    /// Every master.
    pub masters: Vec<MasterFixJson>,
    /// Contours with the same structure in every master, held together.
    pub compatible_contours: usize,
    /// Segments given back in every master where an instance half way between two masters
    /// (or a master) ended worse.
    pub restored_segments: usize,
}
