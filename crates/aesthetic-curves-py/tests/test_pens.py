"""The fontTools pen and the in-place fix (issue 34), on glyphs made here and on a UFO of a
real font when ufo-extractor and a TeX Gyre font are there."""

import glob
import math

import pytest

pens = pytest.importorskip("aesthetic_curves.pens")
ufoLib2 = pytest.importorskip("ufoLib2")

K = 0.5523


def draw_circle(pen, r=100.0):
    q = [(r, 0), (0, r), (-r, 0), (0, -r), (r, 0)]
    pen.moveTo(q[0])
    for (ax, ay), (bx, by) in zip(q, q[1:]):
        pen.curveTo((ax - K * ay, ay + K * ax), (bx + K * by, by - K * bx), (bx, by))
    pen.closePath()


def test_a_cubic_circle_is_not_monotone_but_no_finding():
    pen = pens.CheckPen()
    draw_circle(pen)
    r = pen.check()
    segs = r["contours"][0]["segments"]
    assert len(segs) == 4
    assert all(s["monotone"] is False and 0 < s["bump"] < 0.05 for s in segs)
    assert r["findings"] == []
    assert len(pen.check(min_bump=0)["findings"]) == 4
    # Joins: G1 and G2 (the circle is symmetric).
    assert all(j["g1"] and j["g2"] for j in r["contours"][0]["joins"])


def test_quadratics_and_lines_are_checked_too():
    pen = pens.CheckPen()
    pen.moveTo((0, 0))
    pen.lineTo((100, 0))
    pen.qCurveTo((150, 0), (150, 50))
    pen.qCurveTo((150, 100), (100, 150), (50, 100))  # an implied on-curve point
    pen.closePath()
    r = pen.check(grid=1)
    degrees = [s["degree"] for s in r["contours"][0]["segments"]]
    assert degrees == [1, 2, 2, 2, 1]
    kinds = {f["kind"] for f in r["findings"]}
    assert kinds <= {"hook", "not-monotone", "curvature-extremum", "near-break", "curvature-jump", "degenerate"}


def o_glyph():
    font = ufoLib2.Font()
    g = font.newGlyph("o")
    pts = [(600, 0, "curve"), (600, 265, None), (330, 400, None), (0, 400, "curve"),
           (-290, 400, None), (-600, 200, None), (-600, 0, "curve"), (-600, -250, None),
           (-360, -400, None), (0, -400, "curve"), (300, -400, None), (600, -190, None)]
    c = ufoLib2.objects.Contour()
    for x, y, t in pts:
        c.points.append(ufoLib2.objects.Point(x, y, t, smooth=t is not None))
    g.contours.append(c)
    return g


def jumps(glyph):
    pen = pens.CheckPen()
    glyph.draw(pen)
    return [j["curvature_jump"] for j in pen.check(grid=1)["contours"][0]["joins"]]


def test_fix_glyph_moves_handles_only_within_the_tolerance_and_nothing_worse():
    g = o_glyph()
    before = [(p.x, p.y, p.type, p.smooth) for p in g.contours[0].points]
    j0 = jumps(g)
    report = pens.fix_glyph(g, tolerance=40, grid=1)
    after = [(p.x, p.y, p.type, p.smooth) for p in g.contours[0].points]
    assert len(after) == len(before)
    for (x0, y0, t0, s0), (x1, y1, t1, s1) in zip(before, after):
        assert (t0, s0) == (t1, s1)
        if t0 is not None:
            assert (x0, y0) == (x1, y1), "an on-curve point moved"
        assert float(x1).is_integer() and float(y1).is_integer()
    # Each cubic's shape within the tolerance of the original's (every sampled point of
    # each within 40 of the other curve: nearest of 801 samples, refined by golden
    # sections); a handle may move further.
    n = len(before)

    def at(pts, t):
        w = [(1 - t) ** 3, 3 * t * (1 - t) ** 2, 3 * t * t * (1 - t), t ** 3]
        return (sum(wi * p[0] for wi, p in zip(w, pts)), sum(wi * p[1] for wi, p in zip(w, pts)))

    def one_way(a, b):
        grid = [at(a, s / 800) for s in range(801)]
        worst = 0.0
        for k in range(101):
            q = at(b, k / 100)
            d = lambda s: math.dist(at(a, s), q)
            best = min(range(801), key=lambda i: math.dist(grid[i], q)) / 800
            lo, hi = max(best - 1 / 800, 0.0), min(best + 1 / 800, 1.0)
            for _ in range(50):
                x1, x2 = lo + 0.382 * (hi - lo), lo + 0.618 * (hi - lo)
                if d(x1) < d(x2):
                    hi = x2
                else:
                    lo = x1
            worst = max(worst, min(d((lo + hi) / 2), d(best)))
        return worst

    for k in range(n):
        if before[k][2] is None or before[(k + 1) % n][2] is not None:
            continue
        seg = [(k + i) % n for i in range(4)]
        a = [before[i][:2] for i in seg]
        b = [after[i][:2] for i in seg]
        worst = max(one_way(a, b), one_way(b, a))
        assert worst <= 40 + 1e-9, (k, worst)
    j1 = jumps(g)
    assert all(b <= a * (1 + 1e-9) for a, b in zip(j0, j1)), (j0, j1)
    # Down by more than 40 % (all the way would push the extrema into hooks at the joins).
    assert sum(j1) < 0.6 * sum(j0), (j0, j1)
    assert report[0]["contour"] == 0 and len(report[0]["joins"]) == 4


def test_fix_glyph_leaves_quadratic_contours_and_says_so():
    font = ufoLib2.Font()
    g = font.newGlyph("q")
    c = ufoLib2.objects.Contour()
    for x, y, t in [(0, 0, "qcurve"), (100, 0, None), (100, 100, "qcurve"), (0, 100, None)]:
        c.points.append(ufoLib2.objects.Point(x, y, t))
    g.contours.append(c)
    before = [(p.x, p.y) for p in c.points]
    report = pens.fix_glyph(g)
    assert "quadratic" in report[0]["skipped"]
    assert [(p.x, p.y) for p in c.points] == before


def test_a_real_font_checks_through_the_pen():
    fonts = sorted(glob.glob("/usr/share/texmf/fonts/opentype/public/tex-gyre/texgyreheros-regular.otf"))
    if not fonts:
        pytest.skip("no TeX Gyre Heros")
    from fontTools.ttLib import TTFont
    font = TTFont(fonts[0])
    gs = font.getGlyphSet()
    pen = pens.CheckPen(gs)
    gs["a"].draw(pen)
    r = pen.check(grid=1)
    assert len(r["contours"]) == 2
    assert sum(len(c["segments"]) for c in r["contours"]) > 10
    assert all(f["severity"] >= g["severity"] for f, g in zip(r["findings"], r["findings"][1:]))


def test_the_fontbakery_profile_runs_on_a_real_font():
    pytest.importorskip("fontbakery")
    import subprocess
    import sys
    fonts = glob.glob("/usr/share/texmf/fonts/opentype/public/tex-gyre/texgyreheros-regular.otf")
    if not fonts:
        pytest.skip("no TeX Gyre Heros")
    r = subprocess.run([sys.executable, "-m", "fontbakery", "check-profile",
                        "aesthetic_curves.fontbakery_profile", fonts[0]],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stdout[-2000:] + r.stderr[-2000:]
    assert "aesthetic_curves/curvature" in r.stdout
    assert "places where the curvature is worth a look" in r.stdout
    assert "ERROR: 0" in r.stdout and "WARN: 1" in r.stdout


def test_fix_glyph_removes_a_hook_first_and_can_be_told_not_to():
    """A cubic whose curvature has an extremum at t = 0.96 (a hook at its end): fixed to
    monotone within 8 units, the check of the result says so; with bumps=False it stays."""
    def glyph():
        font = ufoLib2.Font()
        g = font.newGlyph("h")
        c = ufoLib2.objects.Contour()
        for x, y, t in [(0, 0, "curve"), (0, 164, None), (86, 286, None), (200, 300, "curve"),
                        (300, 300, None), (300, 0, None)]:
            c.points.append(ufoLib2.objects.Point(x, y, t))
        g.contours.append(c)
        return g

    def first_extrema(g):
        pen = pens.CheckPen()
        g.draw(pen)
        return pen.check(grid=1)["contours"][0]["segments"][0]["extrema"]

    g = glyph()
    assert [t > 0.95 for t in first_extrema(g)] == [True]
    report = pens.fix_glyph(g, tolerance=8, grid=1)
    assert report[0]["bumps"] == [0]
    assert first_extrema(g) == []
    for p, q in zip(glyph().contours[0].points, g.contours[0].points):
        assert math.hypot(p.x - q.x, p.y - q.y) <= 8
    g = glyph()
    assert pens.fix_glyph(g, tolerance=8, grid=1, bumps=False)[0]["bumps"] == []
    assert len(first_extrema(g)) == 1


def test_index_contour_reads_point_lists_as_aecurve_fix_does():
    import aesthetic_curves as ac
    segs, idx, closed, smooth = ac.index_contour(
        [(0, 10, None, False), (5, 12, None, False), (10, 10, "curve", True), (10, 0, "line", False),
         (0, 0, "line", False)])
    assert closed and idx == [[2, 3], [3, 4], [4, 0, 1, 2]] and smooth == [False, False, True]
    assert segs[2] == [(0, 0), (0, 10), (5, 12), (10, 10)]
    none, why = ac.index_contour([(0, 0, "qcurve", False), (1, 0, None, False), (1, 1, "qcurve", False)])
    assert none is None and "quadratic" in why
    with pytest.raises(ValueError, match="points\\[1\\]"):
        ac.index_contour([(0, 0, "move", False), (1, 0, "spline", False)])
