//! The gallery's check of real glyphs: a few letters of DejaVu Sans (the font the
//! pictures use) through `aecurve check`'s analysis, as its HTML report draws them.

use anyhow::Result;

/// The report of a few glyphs, written as `outline-check.html`, and its section.
pub(crate) fn outline_gallery(out: &std::path::Path) -> Result<String> {
    use aecurve::outline_io::{check_shapes, options_for, read_font};
    const FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");
    const GLYPHS: [&str; 8] = ["a", "e", "g", "o", "s", "S", "ampersand", "at"];
    let font = read_font(FONT)?;
    let shapes: Vec<_> = font
        .shapes
        .iter()
        .filter(|s| GLYPHS.contains(&s.name.as_str()))
        .collect();
    let opts = aesthetic_curves::outline::OutlineOptions {
        suggest: Some(4.0),
        ..options_for(&font)
    };
    let checked = check_shapes(&shapes, &opts, &|| {});
    let page = aecurve::report::outline_report(
        "aecurve check: eight glyphs of DejaVu Sans",
        true,
        &shapes,
        &checked,
        GLYPHS.len(),
    );
    std::fs::write(out.join("outline-check.html"), page)?;
    let segs: usize = checked
        .iter()
        .flat_map(|c| &c.contours)
        .map(|c| c.segments.len())
        .sum();
    let mono: usize = checked
        .iter()
        .flat_map(|c| &c.contours)
        .map(|c| c.monotone_count())
        .sum();
    let near: usize = checked
        .iter()
        .flat_map(|c| &c.contours)
        .map(|c| c.joins.iter().filter(|j| j.near_break).count())
        .sum();
    Ok(format!(
        "<h2>Checking curves people already have: glyphs of a real font</h2>\n<p>Eight \
         letters of DejaVu Sans (TrueType quadratics, in font units) through <code>aecurve \
         check</code>: {segs} segments, {mono} with monotone curvature by the exact test, \
         {near} joins whose tangents break by less than 3° (and by more than the integer \
         grid's rounding explains: probably meant smooth). Each quadratic whose parabola's \
         vertex lies inside it has one curvature extremum: that is most of a TrueType bowl. \
         <a href=\"outline-check.html\">The report</a> draws each glyph with its comb, the \
         extrema (blue), near-breaks (red rings) and smooth joins where the curvature jumps \
         (orange).</p>\n"
    ))
}
