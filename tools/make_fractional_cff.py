#!/usr/bin/env python3
"""Writes the test font crates/aecurve/tests/data/fractional.otf and, beside it,
fractional.json: fontTools' reading of every glyph (its contours' points, in font units).

The font is what fontmake, FontForge or an interpolation writes: CFF charstrings whose
operands are fractions (16.16 fixed-point numbers), one glyph drawn with `flex` and one
with `hflex`, and one whose closing segment ends 1/65536 from its start. The reader of
`aecurve check` must see the same numbers as fontTools (tests/readers.rs compares them
point for point).

    python3 tools/make_fractional_cff.py
"""
import json
import os

from fontTools.fontBuilder import FontBuilder
from fontTools.misc.psCharStrings import T2CharString
from fontTools.pens.recordingPen import RecordingPen
from fontTools.pens.t2CharStringPen import T2CharStringPen
from fontTools.ttLib import TTFont

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "crates", "aecurve", "tests", "data")


def pen_glyph(draw):
    pen = T2CharStringPen(500, None, roundTolerance=0)
    draw(pen)
    return pen.getCharString()


def o(pen):
    # The segment: (126, 513) (118.3193359375, 510.7978515625) (109, 504.80859375) (109, 496).
    pen.moveTo((126, 513))
    pen.curveTo((118.3193359375, 510.7978515625), (109, 504.80859375), (109, 496))
    pen.curveTo((109, 300.25), (200.5, 210.125), (300.0625, 210.125))
    pen.curveTo((420.75, 210.125), (470.5, 330.5), (470.5, 420.375))
    pen.curveTo((470.5, 500.0078125), (380.3330078125, 540.5), (300.0625, 540.5))
    pen.curveTo((200.5, 540.5), (150.25, 530.75), (126, 513))
    pen.closePath()


def nearly_closed(pen):
    # Ends 1/65536 away from the start: a closing line that a reader rounding to integers
    # loses.
    pen.moveTo((100, 100))
    pen.curveTo((200.5, 100), (300.25, 180.75), (300.25, 300.5))
    pen.curveTo((300.25, 420.5), (150.5, 450.5), (100.0000152587890625, 100))
    pen.closePath()


def flex_glyph():
    # rmoveto, then flex: two curves given by 12 deltas and a flex depth (fd), then hflex.
    prog = [
        100.5, 100.25, "rmoveto",
        30.5, 10.25, 40.125, 20.5, 50.75, 5.5,
        50.75, -5.5, 40.125, -20.5, 30.5, -10.25, 50, "flex",
        20.5, 30.25, 40.75, 10.5, 30.125, 40.5, 20.25, "hflex",
        -100.5, 150.75, "rlineto",
        "endchar",
    ]
    return T2CharString(program=[500] + prog)


def main():
    fb = FontBuilder(1000, isTTF=False)
    names = [".notdef", "o", "nearly", "flexed"]
    fb.setupGlyphOrder(names)
    fb.setupCharacterMap({ord("o"): "o", ord("n"): "nearly", ord("f"): "flexed"})
    notdef = pen_glyph(lambda p: None)
    charstrings = {
        ".notdef": notdef,
        "o": pen_glyph(o),
        "nearly": pen_glyph(nearly_closed),
        "flexed": flex_glyph(),
    }
    fb.setupCFF("Fractional", {"FullName": "Fractional"}, charstrings, {})
    fb.setupHorizontalMetrics({n: (500, 0) for n in names})
    fb.setupHorizontalHeader(ascent=800, descent=-200)
    fb.setupNameTable({"familyName": "Fractional", "styleName": "Regular"})
    fb.setupOS2()
    fb.setupPost()
    path = os.path.join(OUT, "fractional.otf")
    fb.save(path)
    font = TTFont(path)
    gs = font.getGlyphSet()
    out = {}
    for n in names[1:]:
        rec = RecordingPen()
        gs[n].draw(rec)
        out[n] = [[op, [list(map(float, pt)) for pt in pts]] for op, pts in rec.value]
    with open(os.path.join(OUT, "fractional.json"), "w") as f:
        json.dump(out, f, indent=1)
    print(f"wrote {path} and fractional.json")


if __name__ == "__main__":
    main()
