//! `aecurve fix` on a designspace: every master (source UFO) repaired, then held together
//! so that the masters stay interpolation-compatible and their instances no worse.
//!
//! The repair changes coordinates only, so the masters keep their structure (the same
//! contours, points and kinds in the same order) by construction. What it could spoil is
//! the instances between them: at a smooth point whose tangent turns from master to master,
//! an instance stays G1 only where every master divides its two handles in the same ratio,
//! and harmonizing each master alone changes that ratio (fontTools' `interpolatable` calls
//! the result a kink). So, contour by contour across the masters: the instance half way
//! between every two masters, of the input's masters and of the repaired ones, is checked
//! with the rule the repair keeps in each master ([`Baseline`]: no join with a larger
//! angle, no smooth or G1 join with a larger curvature jump, no cubic with more curvature
//! extrema by the exact test), each master against its own input too, and every segment
//! that fails anywhere gets its input back in every master, until none fails.
//!
//! Before that, the joins whose tangent direction turns from master to master are held in
//! every master (`held_joins`): their handles do not move, so their ratios, and the
//! instances' tangents, stay; the rest is harmonized freely.
//!
//! Sources in a layer of another UFO (`layer="..."`, sparse masters) are refused with a
//! message; a glyph whose contours differ in structure between masters is not
//! interpolatable anyway and is repaired per master.

use super::{
    counts_of, fix_font_holding, harmonize_options, index_contour, load_font, patched_glifs,
    write_tree, ContourFix, FixCounts, FixOptions, Held, IndexedContour,
};
use crate::atomic_out::{write_new, Staging};
use crate::outline_io::{read_regular_file, MAX_FILE_BYTES};
use crate::ufo_tree::UfoTree;
use aesthetic_curves::harmonize::{Baseline, Harmonized};
use aesthetic_curves::Point;
use anyhow::{bail, Context, Result};
use std::collections::{BTreeSet, HashMap};
use std::path::{Component, Path, PathBuf};

/// One master's results.
pub struct MasterFix {
    /// The source's `filename`, as the designspace says it (relative to it).
    pub filename: String,
    /// Per contour.
    pub fixes: Vec<ContourFix>,
    /// The counts.
    pub counts: FixCounts,
}

/// The whole designspace's results.
pub struct DesignspaceFix {
    /// Per master, in the designspace's order.
    pub masters: Vec<MasterFix>,
    /// Contours present in every master with the same structure (held together).
    pub compatible_contours: usize,
    /// Segments given back their input in every master because an instance or a master
    /// got worse.
    pub restored_segments: usize,
}

/// The sources' filenames of a designspace document, each a plain relative path below
/// the designspace's folder (a master that leaves it, or an absolute path, is refused:
/// nothing outside the folder is read, and the master could not be written back below the
/// output's folder).
fn sources(text: &str, path: &Path) -> Result<Vec<String>> {
    let doc = crate::contained::contained(|| {
        roxmltree::Document::parse(text)
            .with_context(|| format!("{}: not an XML document", path.display()))
    })?;
    let mut out = Vec::new();
    for s in doc.descendants().filter(|n| n.has_tag_name("source")) {
        let Some(file) = s.attribute("filename") else {
            bail!("{}: a <source> without a filename", path.display());
        };
        if let Some(layer) = s.attribute("layer") {
            bail!(
                "{}: source {file} is the layer {layer:?} of a UFO (a sparse master): fix \
                 repairs whole-UFO masters only",
                path.display()
            );
        }
        let plain = !file.is_empty()
            && Path::new(file)
                .components()
                .all(|c| matches!(c, Component::Normal(_) | Component::CurDir));
        if !plain {
            bail!(
                "{}: source {file:?} is not a path below the designspace's folder (it leaves \
                 it, or is absolute): refused; move the masters below the designspace's folder",
                path.display()
            );
        }
        out.push(file.to_string());
    }
    if out.is_empty() {
        bail!("{}: no <source> in the designspace", path.display());
    }
    Ok(out)
}

/// Fix every master of the designspace at `input` and write the designspace to `output`
/// (its text unchanged) with the repaired masters beside it at the same relative paths,
/// all of it moved into place when complete ([`Staging`]); refuses when any of them exists
/// unless `overwrite`.
pub fn fix_designspace(
    input: &Path,
    output: &Path,
    opts: &FixOptions,
    overwrite: bool,
) -> Result<DesignspaceFix> {
    let bytes = read_regular_file(input, MAX_FILE_BYTES)?;
    let text = String::from_utf8(bytes)
        .map_err(|_| anyhow::anyhow!("{}: not UTF-8 text", input.display()))?;
    let files = sources(&text, input)?;
    let here = input.parent().unwrap_or(Path::new(""));
    let master_paths: Vec<PathBuf> = files.iter().map(|f| here.join(f)).collect();
    let mut inputs: Vec<&Path> = master_paths.iter().map(PathBuf::as_path).collect();
    inputs.push(input);
    let mut staging = Staging::new(output, overwrite, &inputs)?;
    let mut targets = Vec::with_capacity(files.len());
    for f in &files {
        targets.push(
            staging
                .beside(f)
                .with_context(|| format!("{}: master {f}", input.display()))?,
        );
    }
    let mut trees = Vec::with_capacity(files.len());
    let mut fonts = Vec::with_capacity(files.len());
    for (f, path) in files.iter().zip(&master_paths) {
        let tree = UfoTree::read(path, MAX_FILE_BYTES)
            .with_context(|| format!("{}: master {f} not read", input.display()))?;
        fonts.push(
            load_font(&tree)
                .with_context(|| format!("{}: master {f} not read", input.display()))?,
        );
        trees.push(tree);
    }
    let held = held_joins(&fonts);
    let mut all: Vec<Vec<ContourFix>> = fonts
        .iter()
        .map(|f| fix_font_holding(f, opts, &held))
        .collect();
    let (compatible_contours, restored_segments) = hold_together(&mut all, opts);
    let mut masters = Vec::with_capacity(files.len());
    for (((tree, font), mut fixes), (file, target)) in trees
        .iter()
        .zip(&fonts)
        .zip(all)
        .zip(files.iter().zip(&targets))
    {
        let patched = patched_glifs(tree, font, &mut fixes)?;
        let counts = counts_of(&fixes);
        if target.exists() {
            bail!("{}: master {file} is named twice", input.display());
        }
        write_tree(tree, &patched, target)?;
        masters.push(MasterFix {
            filename: file.clone(),
            fixes,
            counts,
        });
    }
    write_new(&staging.output()?, text.as_bytes(), None)?;
    staging.commit()?;
    Ok(DesignspaceFix {
        masters,
        compatible_contours,
        restored_segments,
    })
}

/// Per contour present in every master with the same structure: the joins whose tangent
/// direction turns from master to master (on either side). Their handles stay where they
/// are in every master: an instance between masters is G1 there only while every master
/// divides the two handles in the ratio it has (where the direction is the same in all
/// masters, any lengths interpolate to collinear handles).
fn held_joins(fonts: &[norad::Font]) -> Held {
    let mut held = Held::new();
    let Some((first, rest)) = fonts.split_first() else {
        return held;
    };
    for glyph in first.default_layer().iter() {
        let name = glyph.name().as_str();
        let others: Option<Vec<&norad::Glyph>> = rest
            .iter()
            .map(|f| f.default_layer().get_glyph(name))
            .collect();
        let Some(others) = others else { continue };
        for (ci, contour) in glyph.contours.iter().enumerate() {
            let Ok(c0) = index_contour(&contour.points) else {
                continue;
            };
            let cs: Option<Vec<IndexedContour>> = others
                .iter()
                .map(|g| {
                    g.contours
                        .get(ci)
                        .and_then(|c| index_contour(&c.points).ok())
                        .filter(|c| c.indices == c0.indices && c.closed == c0.closed)
                })
                .collect();
            let Some(cs) = cs else { continue };
            let turns: Vec<bool> = (0..c0.smooth.len())
                .map(|j| cs.iter().any(|c| tangents_differ(&c0, c, j)))
                .collect();
            held.insert((name.to_string(), ci), turns);
        }
    }
    held
}

/// Whether the tangent directions on either side of join `j` differ between two masters'
/// contours of the same structure (beyond 1e-9 rad).
fn tangents_differ(a: &IndexedContour, b: &IndexedContour, j: usize) -> bool {
    let n = a.segments.len();
    let dirs = |c: &IndexedContour| {
        aesthetic_curves::harmonize::join_tangents(&c.segments[j], &c.segments[(j + 1) % n])
    };
    dirs(a).iter().zip(dirs(b)).any(|(u, v)| match (u, v) {
        (Some(u), Some(v)) => aesthetic_curves::harmonize::tangent_angle(*u, v) > 1e-9,
        _ => false,
    })
}

/// Every contour present in all masters with the same structure held together (see the
/// module documentation): how many such contours, and how many segments were given back.
fn hold_together(all: &mut [Vec<ContourFix>], opts: &FixOptions) -> (usize, usize) {
    // Where each (glyph, contour) of the first master sits in the others.
    let index: Vec<HashMap<(String, usize), usize>> = all
        .iter()
        .map(|m| {
            m.iter()
                .enumerate()
                .map(|(k, f)| ((f.glyph.clone(), f.contour), k))
                .collect()
        })
        .collect();
    let (mut compatible, mut restored) = (0, 0);
    for k in 0..all.first().map_or(0, Vec::len) {
        let key = (all[0][k].glyph.clone(), all[0][k].contour);
        let Some(at): Option<Vec<usize>> = index.iter().map(|ix| ix.get(&key).copied()).collect()
        else {
            continue;
        };
        // The contour of every master taken out, held together, and put back.
        let mut members: Vec<ContourFix> = at
            .iter()
            .enumerate()
            .map(|(m, &p)| std::mem::replace(&mut all[m][p], placeholder()))
            .collect();
        if let Some(n) = hold_contour(&mut members, opts) {
            compatible += 1;
            restored += n;
        }
        for ((m, &p), f) in at.iter().enumerate().zip(members) {
            all[m][p] = f;
        }
    }
    (compatible, restored)
}

/// What stands in a master's list while its contour is held together with the others'.
fn placeholder() -> ContourFix {
    ContourFix {
        glyph: String::new(),
        contour: 0,
        input: None,
        result: Err(String::new()),
    }
}

/// One contour across the masters (see the module documentation); None when the masters'
/// contours differ in structure or one was not repaired; else how many segments went back.
fn hold_contour(members: &mut [ContourFix], opts: &FixOptions) -> Option<usize> {
    let first = members.first()?.input.as_ref()?;
    let same = members.iter().all(|m| {
        m.result.is_ok()
            && m.input
                .as_ref()
                .is_some_and(|c| c.indices == first.indices && c.closed == first.closed)
    });
    if !same {
        return None;
    }
    let closed = first.closed;
    let hopts = harmonize_options(opts);
    let inputs: Vec<Vec<Vec<Point>>> = members
        .iter()
        .map(|m| {
            m.input
                .as_ref()
                .map(|c| c.segments.clone())
                .unwrap_or_default()
        })
        .collect();
    let smooth: Vec<Vec<bool>> = members
        .iter()
        .map(|m| {
            m.input
                .as_ref()
                .map(|c| c.smooth.clone())
                .unwrap_or_default()
        })
        .collect();
    // Each master's input and the input's half-way instance of every two masters, computed
    // once (their joins and the exact test of their cubics) and held to in every round.
    let masters: Vec<Baseline> = inputs
        .iter()
        .zip(&smooth)
        .map(|(s, f)| Baseline::new(s, closed, f, &hopts))
        .collect();
    let mut pairs = Vec::new();
    for k in 0..inputs.len() {
        for l in k + 1..inputs.len() {
            let either: Vec<bool> = smooth[k]
                .iter()
                .zip(&smooth[l])
                .map(|(a, b)| *a || *b)
                .collect();
            let before = halfway(&inputs[k], &inputs[l]);
            pairs.push((k, l, Baseline::new(&before, closed, &either, &hopts)));
        }
    }
    let mut restored = 0;
    let n = inputs[0].len();
    for _round in 0..=n {
        let results: Vec<&Harmonized> = members
            .iter()
            .filter_map(|m| m.result.as_ref().ok())
            .collect();
        let mut bad = BTreeSet::new();
        for (base, r) in masters.iter().zip(&results) {
            bad.extend(base.regressions(&r.segments));
        }
        for (k, l, base) in &pairs {
            bad.extend(base.regressions(&halfway(&results[*k].segments, &results[*l].segments)));
        }
        if bad.is_empty() {
            break;
        }
        let bad: Vec<usize> = bad.into_iter().collect();
        restored += bad.len();
        for (k, m) in members.iter_mut().enumerate() {
            if let Ok(h) = m.result.as_mut() {
                h.restore(&inputs[k], closed, &bad);
            }
        }
    }
    Some(restored)
}

/// The instance half way between two masters' segments (same structure).
fn halfway(a: &[Vec<Point>], b: &[Vec<Point>]) -> Vec<Vec<Point>> {
    a.iter()
        .zip(b)
        .map(|(s, t)| s.iter().zip(t).map(|(p, q)| p.midpoint(*q)).collect())
        .collect()
}
