"""A fontbakery profile with the exact curvature check (issue 34), so that a font project
can check its outlines' curvature in CI:

    fontbakery check-profile aesthetic_curves.fontbakery_profile MyFont.otf

Each glyph is drawn through :class:`aesthetic_curves.pens.CheckPen` (components resolved)
and checked on the font's integer grid. The check WARNs with the findings that matter most
in type design (a curvature hook at a segment's end, several curvature extrema in one
segment, a curvature jump at a smooth join between curves of one sign, a near-break),
each place once, worst first; a single smooth extremum inside a segment is the design more
often than not and is not reported. Needs fontbakery (and fontTools).
"""

from fontbakery.prelude import PASS, WARN, Message, check

from .pens import CheckPen

#: Finding kinds reported, with the smallest severity that counts.
REPORTED = {"hook": 0.1, "not-monotone": 0.1, "near-break": 0.0, "curvature-jump": 0.2}
#: How many findings the message lists.
LISTED = 25


def _findings(ttFont):
    glyphs = ttFont.getGlyphSet()
    seen = {}
    for name in ttFont.getGlyphOrder():
        pen = CheckPen(glyphs)
        glyphs[name].draw(pen)
        if not pen.contours:
            continue
        for f in pen.check(grid=1)["findings"]:
            least = REPORTED.get(f["kind"])
            if least is None or f["severity"] < least:
                continue
            key = (f["kind"], f["message"], round(f["point"][0], 3), round(f["point"][1], 3))
            if key in seen:
                seen[key]["also"].append(name)
            else:
                seen[key] = dict(f, glyph=name, also=[])
    return sorted(seen.values(), key=lambda f: -f["severity"])


@check(
    id="aesthetic_curves/curvature",
    rationale="""
        Curvature combs show where an outline's curvature turns or jumps, but only to an
        eye that looks at every glyph. This check decides it exactly (the aesthetic-curves
        library's proof, not sampling): a curvature hook at the end of a segment, several
        curvature extrema in one segment, a curvature jump at a smooth join, and tangent
        breaks under 3 degrees that were probably meant smooth.
    """,
    # The project has no public tracker yet: its issue 34 asked for this check.
    proposal="aesthetic-curves issue 34",
)
def check_curvature(ttFont):
    """Curvature hooks, wobbles and jumps at smooth joins, decided exactly."""
    found = _findings(ttFont)
    if not found:
        yield PASS, "No curvature hooks, wobbles, jumps at smooth joins or near-breaks."
        return
    lines = []
    for f in found[:LISTED]:
        also = f" (also in {len(f['also'])} more)" if f["also"] else ""
        x, y = f["point"]
        lines.append(f"* {f['glyph']}{also} at ({x:.0f}, {y:.0f}): {f['message']}")
    more = f"\n\n... and {len(found) - LISTED} more." if len(found) > LISTED else ""
    yield WARN, Message(
        "curvature",
        f"{len(found)} places where the curvature is worth a look, worst first:\n\n"
        + "\n".join(lines)
        + more,
    )


PROFILE = {
    "name": "aesthetic_curves",
    "check_definitions": ["aesthetic_curves.fontbakery_profile"],
    "sections": {"Curvature (aesthetic-curves)": ["aesthetic_curves/curvature"]},
}
