"""Where type designers script: a fontTools pen that checks what is drawn into it, and a
repair of a ufoLib2 / defcon / fontTools-style glyph in place (issue 34). Needs fontTools.

    from aesthetic_curves.pens import CheckPen, fix_glyph
    pen = CheckPen(font)            # any glyph set, for components
    font["a"].draw(pen)
    for f in pen.check(grid=1)["findings"]:
        print(f["kind"], f["point"], f["message"])
    report = fix_glyph(font["a"], tolerance=2, grid=1)

The check is the library's exact one (``aecurve check``): per segment whether the
curvature is monotone, its extrema and the size of its detour (``bump``); per join the
angle and the curvature jump; the findings worst first.
"""

from fontTools.pens.basePen import BasePen

from ._native import check_outline, harmonize, index_contour

__all__ = ["CheckPen", "fix_glyph"]


def _pt(p):
    return (float(p[0]), float(p[1]))


class CheckPen(BasePen):
    """A segment pen collecting contours of lines, quadratics and cubics (fontTools
    decomposes super-Béziers, implied on-curve points and components through the glyph
    set given). ``check()`` runs the exact check on what was drawn."""

    def __init__(self, glyphSet=None):
        super().__init__(glyphSet)
        self.contours = []
        self._segments = None

    def _moveTo(self, pt):
        self._segments = []

    def _lineTo(self, pt):
        self._segments.append([_pt(self._getCurrentPoint()), _pt(pt)])

    def _curveToOne(self, pt1, pt2, pt3):
        self._segments.append([_pt(self._getCurrentPoint()), _pt(pt1), _pt(pt2), _pt(pt3)])

    def _qCurveToOne(self, pt1, pt2):
        self._segments.append([_pt(self._getCurrentPoint()), _pt(pt1), _pt(pt2)])

    def _closePath(self):
        segs = self._segments or []
        if segs:
            start, end = segs[0][0], segs[-1][-1]
            if start != end:
                segs.append([end, start])
            self.contours.append((segs, True))
        self._segments = None

    def _endPath(self):
        if self._segments:
            self.contours.append((self._segments, False))
        self._segments = None

    def check(self, grid=0.0, g1_angle=0.05, g2_jump=0.05, near_break=3.0, min_bump=0.05):
        """The exact check of every contour drawn: a dict with ``contours`` (per segment
        ``degree``, ``monotone``, ``extrema``, ``bump``, ``flag``; per join
        ``after_segment``, ``angle_degrees``, ``g1``, ``g2``, ``curvature_jump``) and
        ``findings`` (worst first: ``contour``, ``segment``, ``kind``, ``point``,
        ``severity``, ``message``). ``grid=1`` for a font's integer units."""
        return check_outline(self.contours, grid=grid, g1_angle=g1_angle, g2_jump=g2_jump,
                             near_break=near_break, min_bump=min_bump)


def _point_type(p):
    t = getattr(p, "type", None)
    if t is None:
        t = getattr(p, "segmentType", None)
    return t


def _index_contour(points):
    """The segments of a UFO-style point list with the indices of their points, or the
    reason the contour is not a cubic outline ``fix_glyph`` works on (the library's reader,
    the one ``aecurve fix`` uses)."""
    found = index_contour(
        [(float(p.x), float(p.y), _point_type(p), bool(getattr(p, "smooth", False))) for p in points]
    )
    if found[0] is None:
        return None, found[1]
    return found, None


def fix_glyph(glyph, tolerance=2.0, grid=1.0, bumps=True):
    """Repair a glyph in place as ``aecurve fix`` repairs a UFO: with ``bumps``, cubics
    with a curvature hook near an end or several extrema first get monotone handle lengths
    where some exist; then every smooth join between two cubics (the points' ``smooth``
    flags, or G1 within rounding) moved towards G2 by sliding its handles along their
    tangents; no outline further than ``tolerance`` from the original (each segment's
    shape, both ways; a handle may move further), on the ``grid``, and no join or cubic
    left worse, no new hook (the library's ``harmonize::repair``). Works on glyphs whose
    ``contours`` hold ``points`` with ``x``, ``y``, ``type`` (or ``segmentType``) and
    ``smooth`` (ufoLib2, defcon). Returns one dict per contour: its index and either
    ``joins`` (``after_segment``, ``outcome``, ``jump`` and ``angle_degrees`` before and
    after), ``moved``, ``bumps`` (the segments whose bump was removed) and
    ``bumps_undecided`` (those whose repair search ran out of its budget for exact
    arithmetic: coordinates spanning hundreds of orders of magnitude), or ``skipped`` with
    the reason."""
    out = []
    for ci, contour in enumerate(glyph.contours):
        points = list(contour.points)
        indexed, why = _index_contour(points)
        if indexed is None:
            out.append({"contour": ci, "skipped": why})
            continue
        segments, indices, closed, smooth = indexed
        h = harmonize(segments, closed, smooth, tolerance=tolerance, grid=grid, bumps=bumps)
        for idx, pts in zip(indices, h["segments"]):
            for i, (x, y) in zip(idx, pts):
                points[i].x, points[i].y = x, y
        out.append(
            {
                "contour": ci,
                "joins": h["joins"],
                "moved": h["moved"],
                "bumps": h["bumps"],
                "bumps_undecided": h["bumps_undecided"],
            }
        )
    return out
