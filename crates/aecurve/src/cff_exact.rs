//! CFF and CFF2 outlines at the charstrings' own precision.
//!
//! A charstring's operands are integers, 16.16 fixed-point numbers (the `255` operator)
//! and their sums, so a CFF outline's coordinates are multiples of 1/65536 that `f64`
//! holds exactly. Drawn "unscaled" through skrifa (as through FreeType), they arrive
//! truncated to whole font units: a control point stored at (118.3193359375, 510.79...)
//! is drawn at (118, 510), and an exact verdict is then a verdict on a curve the font
//! does not hold. So the `check` of a CFF or CFF2 font evaluates the charstrings itself
//! (read-fonts' evaluator, flex and `seac` included, at the default location of a
//! variable font) and takes each 16.16 coordinate as it is: `bits / 65536`, exact.
//!
//! A font whose top or font DICT has a `FontMatrix` other than the identity (rare: some
//! CID-keyed fonts) is drawn through skrifa, which applies the matrix as FreeType does.

use aesthetic_curves::Point;
use skrifa::raw::ps::cff::CffFontRef;
use skrifa::raw::ps::cs::{CommandSink, NopFilterSink};
use skrifa::raw::ps::transform::FontMatrix;
use skrifa::raw::types::Fixed;
use skrifa::raw::TableProvider;
use skrifa::{FontRef, GlyphId, Tag};

/// Where the charstrings' commands go, in font units.
pub trait ExactPen {
    /// Start a contour at `p`.
    fn move_to(&mut self, p: Point);
    /// A line to `p`.
    fn line_to(&mut self, p: Point);
    /// A cubic with handles `a`, `b` to `p`.
    fn cubic_to(&mut self, a: Point, b: Point, p: Point);
    /// Close the contour.
    fn close(&mut self);
}

/// A font's CFF or CFF2 table, ready to draw glyphs exactly.
pub struct ExactCff<'a> {
    cff: CffFontRef<'a>,
}

impl<'a> ExactCff<'a> {
    /// The font's CFF (or CFF2) table, or None: no such table, or a table read-fonts does
    /// not parse (skrifa then says why).
    pub fn of(font: &FontRef<'a>) -> Option<ExactCff<'a>> {
        let upem = font.head().ok()?.units_per_em() as i32;
        let cff = if let Some(data) = font.table_data(Tag::new(b"CFF ")) {
            CffFontRef::new_cff(data.as_bytes(), 0, Some(upem)).ok()?
        } else {
            let data = font.table_data(Tag::new(b"CFF2"))?;
            CffFontRef::new_cff2(data.as_bytes(), Some(upem)).ok()?
        };
        Some(ExactCff { cff })
    }

    /// Draw glyph `gid` into `pen`: Ok(false) without drawing where the glyph's font
    /// matrix is not the identity (draw it through skrifa), Err why it cannot be drawn (a
    /// damaged charstring).
    pub fn draw(&self, gid: u32, pen: &mut impl ExactPen) -> Result<bool, String> {
        let gid = GlyphId::new(gid);
        let index = self
            .cff
            .subfont_index(gid)
            .ok_or("no subfont for the glyph")?;
        let subfont = (self.cff.subfont(index, &[])).map_err(|e| e.to_string())?;
        // What a reader applies to font units (FreeType's and skrifa's rule): nothing
        // where the normalized matrix is the identity at the font's own units per em.
        let t = self.cff.transform(&subfont, None);
        if t.matrix != FontMatrix::IDENTITY || t.scale.is_some() {
            return Ok(false);
        }
        let mut sink = Sink(pen);
        let mut filtered = NopFilterSink::new(&mut sink);
        (self
            .cff
            .evaluate_charstring(&subfont, gid, &[], &mut filtered))
        .map_err(|e| e.to_string())?;
        Ok(true)
    }
}

/// A 16.16 number as the `f64` it is (exact: 32 bits of mantissa at most).
fn exact(v: Fixed) -> f64 {
    v.to_bits() as f64 / 65536.0
}

/// The evaluator's commands into an [`ExactPen`].
struct Sink<'p, P>(&'p mut P);

impl<P: ExactPen> CommandSink for Sink<'_, P> {
    fn move_to(&mut self, x: Fixed, y: Fixed) {
        self.0.move_to(Point::new(exact(x), exact(y)));
    }

    fn line_to(&mut self, x: Fixed, y: Fixed) {
        self.0.line_to(Point::new(exact(x), exact(y)));
    }

    fn curve_to(&mut self, cx0: Fixed, cy0: Fixed, cx1: Fixed, cy1: Fixed, x: Fixed, y: Fixed) {
        self.0.cubic_to(
            Point::new(exact(cx0), exact(cy0)),
            Point::new(exact(cx1), exact(cy1)),
            Point::new(exact(x), exact(y)),
        );
    }

    fn close(&mut self) {
        self.0.close();
    }
}
