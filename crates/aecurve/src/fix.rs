//! `aecurve fix`: a UFO source's smooth joins harmonized (the library's `harmonize`) and the
//! UFO written back with the same structure: same glyphs, contours, points, kinds, names,
//! identifiers, anchors and components; only off-curve coordinates move (and, with
//! `--move-points`, on-curve points of smooth joins, along their handles' line), never
//! further than the tolerance, on the grid.
//!
//! A contour is taken as the designer drew it: its segments are read from the points in
//! order (an open contour from its `move`, a closed one from its first on-curve point), and a
//! join is smooth where the on-curve point says `smooth="yes"`. Contours with quadratic
//! segments (`qcurve`, or one off-curve point) are left as they are and listed: `fix` works
//! on cubic outlines (convert a TrueType source to cubics first).

use aesthetic_curves::harmonize::{repair, HarmonizeOptions, Harmonized, JoinOutcome, Repairs};
use aesthetic_curves::Point;
use anyhow::{Context, Result};
use serde_json::{json, Value};
use std::path::Path;

/// One contour read for the fix: its segments' control points, the indices of those points
/// in the contour's point list, whether it is closed, and each join's smooth flag.
#[derive(Clone, Debug, PartialEq)]
pub struct IndexedContour {
    /// Control points per segment (2: a line, 4: a cubic).
    pub segments: Vec<Vec<Point>>,
    /// For each control point, its index in the UFO contour's points.
    pub indices: Vec<Vec<usize>>,
    /// Closed (no `move` point).
    pub closed: bool,
    /// Per join (after segment j): the designer's smooth flag at that on-curve point.
    pub smooth: Vec<bool>,
}

/// The segments of a UFO contour with the indices of their points; Err says why the contour
/// is not one `fix` works on.
pub fn index_contour(
    points: &[norad::ContourPoint],
) -> std::result::Result<IndexedContour, String> {
    use norad::PointType as T;
    let n = points.len();
    if n < 2 {
        return Err("fewer than two points".into());
    }
    let open = points[0].typ == T::Move;
    let start = if open {
        0
    } else {
        points
            .iter()
            .position(|q| q.typ != T::OffCurve)
            .ok_or("off-curve points only (implied quadratics): not a cubic outline")?
    };
    let at = |k: usize| (start + k) % n;
    let mut out = IndexedContour {
        segments: Vec::new(),
        indices: Vec::new(),
        closed: !open,
        smooth: Vec::new(),
    };
    let mut current = vec![at(0)];
    let steps = if open { n - 1 } else { n };
    for k in 1..=steps {
        let i = at(k);
        let q = &points[i];
        current.push(i);
        match q.typ {
            T::OffCurve => continue,
            T::QCurve => {
                return Err("a quadratic (qcurve) segment: fix works on cubic outlines".into())
            }
            _ => {}
        }
        match current.len() {
            2 | 4 => {}
            3 => {
                return Err(
                    "a curve with one off-curve point (a quadratic): fix works on cubic outlines"
                        .into(),
                )
            }
            m => {
                return Err(format!(
                    "a curve point after {} off-curve points (at most 2)",
                    m - 2
                ))
            }
        }
        out.segments.push(
            current
                .iter()
                .map(|&j| Point::new(points[j].x, points[j].y))
                .collect(),
        );
        out.indices.push(std::mem::replace(&mut current, vec![i]));
        out.smooth.push(q.smooth);
    }
    if current.len() > 1 {
        return Err("off-curve points after the last on-curve point of an open contour".into());
    }
    // An open contour has no join after its last segment.
    if open {
        out.smooth.pop();
    }
    Ok(out)
}

/// What `fix` does.
#[derive(Clone, Copy, Debug)]
pub struct FixOptions {
    /// How far a point may move (font units).
    pub tolerance: f64,
    /// The coordinates' grid (1: integer font units; 0: none).
    pub grid: f64,
    /// Also move the on-curve points of smooth joins along their handles' line.
    pub move_points: bool,
    /// Which repairs run (hooks and extra extrema first, then the joins).
    pub repairs: Repairs,
}

/// One contour's result, as JSON and as counts.
pub struct ContourFix {
    /// The glyph's name.
    pub glyph: String,
    /// The contour's index in the glyph.
    pub contour: usize,
    /// The contour as read (None: not one `fix` works on).
    pub input: Option<IndexedContour>,
    /// The harmonize result (Err: not a contour `fix` works on, with the reason).
    pub result: std::result::Result<Harmonized, String>,
}

/// The counts the summary and the tests use.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FixCounts {
    /// Smooth joins between two cubics.
    pub smooth_cubic_joins: usize,
    /// Of those, under 1 % relative curvature jump before, and after.
    pub under_1_percent: (usize, usize),
    /// Joins worse after than before (jump or angle): 0 by construction.
    pub worse: usize,
    /// Cubics with more curvature extrema after: 0 by construction.
    pub gained_extrema: usize,
    /// Segments changed.
    pub changed_segments: usize,
    /// Largest distance a point moved.
    pub max_moved: f64,
    /// Contours left alone (quadratic or unreadable).
    pub skipped_contours: usize,
    /// Cubics with a hook (an extremum within 5 % of an end) or several extrema, before and
    /// after (the exact test).
    pub bumps: (usize, usize),
}

impl FixCounts {
    fn add(&mut self, h: &Harmonized, c: &IndexedContour) {
        let input = &c.segments;
        let n = input.len();
        for j in &h.joins {
            let (a, b) = (j.after_segment, (j.after_segment + 1) % n);
            if !c.smooth[j.after_segment] || input[a].len() != 4 || input[b].len() != 4 {
                continue;
            }
            self.smooth_cubic_joins += 1;
            self.under_1_percent.0 += (j.jump.0 < 0.01) as usize;
            self.under_1_percent.1 += (j.jump.1 < 0.01) as usize;
            self.worse += (j.jump.1 > j.jump.0 * (1.0 + 1e-12) + 1e-15
                || j.angle.1 > j.angle.0 + 1e-12) as usize;
        }
        for (b, a) in &h.extrema {
            if let (Some(b), Some(a)) = (b, a) {
                self.gained_extrema += (a > b) as usize;
            }
        }
        let bump = |p: &[Point]| hook_or_wobble(p).unwrap_or(false) as usize;
        for (s, t) in input.iter().zip(&h.segments) {
            self.bumps.0 += bump(s);
            self.bumps.1 += bump(t);
        }
        self.changed_segments += h.segments.iter().zip(input).filter(|(a, b)| a != b).count();
        self.max_moved = h.moved.iter().copied().fold(self.max_moved, f64::max);
    }
}

/// Whether a cubic has a hook (an extremum within 5 % of an end) or several extrema (None:
/// not a cubic, or no verdict).
fn hook_or_wobble(p: &[Point]) -> Option<bool> {
    use aesthetic_curves::monotone::CurvatureMonotone;
    if p.len() != 4 {
        return None;
    }
    let r = aesthetic_curves::Bezier::new(p.to_vec())
        .ok()?
        .curvature_monotone()
        .ok()?;
    Some(r.extrema.len() > 1 || r.extrema.iter().any(|t| *t < 0.05 || *t > 0.95))
}

/// Fix every glyph of the UFO at `input`'s default layer and write the UFO to `output`:
/// the per-contour results and the counts.
pub fn fix_ufo(
    input: &Path,
    output: &Path,
    opts: &FixOptions,
) -> Result<(Vec<ContourFix>, FixCounts)> {
    crate::outline_io::read(input)
        .with_context(|| format!("{}: not a UFO `fix` reads", input.display()))?;
    let mut font =
        norad::Font::load(input).with_context(|| format!("loading {}", input.display()))?;
    let hopts = HarmonizeOptions {
        tolerance: opts.tolerance,
        grid: opts.grid,
        move_points: opts.move_points,
        ..HarmonizeOptions::default()
    };
    let mut fixes = Vec::new();
    let mut counts = FixCounts::default();
    for glyph in font.default_layer_mut().iter_mut() {
        let name = glyph.name().to_string();
        for (ci, contour) in glyph.contours.iter_mut().enumerate() {
            let indexed = index_contour(&contour.points);
            let result = indexed.as_ref().map_err(Clone::clone).and_then(|c| {
                let h = repair(&c.segments, c.closed, &c.smooth, &hopts, &opts.repairs)
                    .map_err(|e| e.to_string())?;
                write_back(&mut contour.points, c, &h);
                counts.add(&h, c);
                Ok(h)
            });
            counts.skipped_contours += result.is_err() as usize;
            fixes.push(ContourFix {
                glyph: name.clone(),
                contour: ci,
                input: indexed.ok(),
                result,
            });
        }
    }
    font.save(output)
        .with_context(|| format!("writing {}", output.display()))?;
    Ok((fixes, counts))
}

/// The harmonized coordinates into the contour's points (only those that moved).
fn write_back(points: &mut [norad::ContourPoint], c: &IndexedContour, h: &Harmonized) {
    for (idx, pts) in c.indices.iter().zip(&h.segments) {
        for (&i, p) in idx.iter().zip(pts) {
            points[i].x = p.x;
            points[i].y = p.y;
        }
    }
}

/// A contour's changes as JSON: per changed segment its old and new control points, what
/// moved and the verdict after; per join before and after.
pub fn fix_json(f: &ContourFix) -> Value {
    let pts = |v: &[Point]| v.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>();
    match (&f.result, &f.input) {
        (Err(why), _) => json!({"glyph": f.glyph, "contour": f.contour, "skipped": why}),
        (Ok(h), Some(c)) => {
            let segments: Vec<Value> = h
                .segments
                .iter()
                .enumerate()
                .filter(|(i, s)| **s != c.segments[*i])
                .map(|(i, s)| {
                    json!({"segment": i, "before": pts(&c.segments[i]), "after": pts(s),
                        "moved": h.moved[i], "extrema": [h.extrema[i].0, h.extrema[i].1]})
                })
                .collect();
            let joins: Vec<Value> = h
                .joins
                .iter()
                .filter(|j| !matches!(j.outcome, JoinOutcome::Corner))
                .map(|j| {
                    json!({"after_segment": j.after_segment, "outcome": format!("{:?}", j.outcome),
                        "jump": [crate::json_out::finite_or_null(j.jump.0), crate::json_out::finite_or_null(j.jump.1)],
                        "angle_degrees": [j.angle.0.to_degrees(), j.angle.1.to_degrees()]})
                })
                .collect();
            json!({"glyph": f.glyph, "contour": f.contour, "segments": segments, "joins": joins})
        }
        (Ok(_), None) => json!({"glyph": f.glyph, "contour": f.contour}),
    }
}
