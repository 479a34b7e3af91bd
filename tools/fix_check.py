#!/usr/bin/env python3
"""`aecurve fix` on real UFO sources, a designspace and SVG icons (CI step; needs
fonts-texgyre, fonts-cantarell and adwaita-icon-theme from Debian, fontTools, ufo-extractor
and ufoLib2 from PyPI). Issue 34.

For UFOs that ufo-extractor makes from TeX Gyre fonts (OpenType/CFF: cubic outlines):

- ufoLib2 reads the written UFO, with the same glyphs, contours, and points in the same
  order, of the same kinds, with the same smooth flags and names; on-curve points do not
  move (unless `--move-points`, the second run: then at most the tolerance); no segment's
  outline moves further than the tolerance (the Hausdorff distance of the two segments,
  sampled here); every coordinate is an integer (grid 1).
- `aecurve check --json` on the input and on the output (the exact test, which shares no
  code with the fix's float formulas for end curvatures): no segment has more curvature
  extrema after, no smooth join between cubics has a larger curvature jump or angle after;
  the share of those joins under a 1 % jump is printed before and after.
- `fix --json`'s counts agree with that check: 0 joins worse, 0 cubics with more extrema;
  its join outcomes agree with its jumps (`harmonized` exactly when under 1 %).
- The hooked cubics (an extremum within 5 % of an end) fall at least by half, counted in all
  glyphs and counted once per distinct input cubic; in both modes at least 80 % of the G1
  joins between two curves end under a 1 % curvature jump.

Exits non-zero on the first failure, printing what failed.
"""
import concurrent.futures
import glob
import json
import math
import multiprocessing
import os
import subprocess
import sys
import tempfile

import extractor
import numpy as np
import ufoLib2

AECURVE = sys.argv[1] if len(sys.argv) > 1 else "target/release/aecurve"
TOLERANCE = 2.0
scratch = tempfile.TemporaryDirectory(prefix="aecurve-fix-check-")


def fail(msg):
    print(f"FAIL: {msg}")
    sys.exit(1)


def check_json(path):
    out = subprocess.run([AECURVE, "check", "--json", path], capture_output=True, text=True)
    if out.returncode != 0:
        fail(f"check {path}: {out.stderr.strip()}")
    return json.loads(out.stdout)


def same_structure(a, b, name, points_move=False):
    if sorted(a.keys()) != sorted(b.keys()):
        fail(f"{name}: the glyph sets differ")
    moved = 0.0
    # The changed segments, measured together at the end (numpy in batches).
    changed = []
    for g in a.keys():
        ga, gb = a[g], b[g]
        if len(ga.contours) != len(gb.contours) or len(ga.components) != len(gb.components):
            fail(f"{name} {g}: contours or components differ")
        if [x.name for x in ga.anchors] != [x.name for x in gb.anchors]:
            fail(f"{name} {g}: anchors differ")
        for ci, (ca, cb) in enumerate(zip(ga.contours, gb.contours)):
            if len(ca.points) != len(cb.points):
                fail(f"{name} {g} contour {ci}: {len(ca.points)} points became {len(cb.points)}")
            for pa, pb in zip(ca.points, cb.points):
                if (pa.type, pa.smooth, pa.name) != (pb.type, pb.smooth, pb.name):
                    fail(f"{name} {g} contour {ci}: a point's kind, smooth flag or name changed")
                d = math.hypot(pa.x - pb.x, pa.y - pb.y)
                if pa.type is not None and d != 0 and not points_move:
                    fail(f"{name} {g} contour {ci}: an on-curve point moved by {d}")
                if pa.type is not None and d > TOLERANCE + 1e-9:
                    fail(f"{name} {g} contour {ci}: an on-curve point moved by {d} > {TOLERANCE}")
                if pb.x != int(pb.x) or pb.y != int(pb.y):
                    fail(f"{name} {g} contour {ci}: ({pb.x}, {pb.y}) is off the grid")
            for sa, sb in zip(segments_of(ca), segments_of(cb)):
                if sa != sb:
                    changed.append((sa, sb, f"{name} {g} contour {ci}"))
    for (sa, sb, where), d in zip(changed, outline_distances([(sa, sb) for sa, sb, _ in changed])):
        if d > TOLERANCE + 1e-9:
            fail(f"{where}: the outline moved by {d} > {TOLERANCE}: {sa} -> {sb}")
        moved = max(moved, d)
    return moved


def segments_of(contour):
    """The contour's segments as lists of (x, y), each from one on-curve point to the next
    (closed contours wrap around)."""
    pts = [(p.x, p.y, p.type) for p in contour.points]
    on = [i for i, p in enumerate(pts) if p[2] is not None]
    if not on:
        return []
    closed = pts[0][2] != "move"
    out = []
    for k, i in enumerate(on):
        if k + 1 < len(on):
            j = on[k + 1]
            out.append([pts[x][:2] for x in range(i, j + 1)])
        elif closed:
            idx = list(range(i, len(pts))) + list(range(0, on[0] + 1))
            out.append([pts[x][:2] for x in idx])
    return out


def power_form(p):
    """The power-basis coefficients of the Bézier curve with control points `p` (numpy,
    one row per power of t), from the Bernstein sums here, not aecurve's evaluation."""
    n = len(p) - 1
    q = np.asarray(p, dtype=float)
    return np.array([math.comb(n, k) * sum((-1) ** (k - i) * math.comb(k, i) * q[i] for i in range(k + 1))
                     for k in range(n + 1)])


def horner(c, t):
    """The polynomial curves with power coefficients `c` (batch, power, 2) at the parameters
    `t` (batch, samples): (batch, samples, 2)."""
    out = np.zeros(t.shape + (2,)) + c[:, -1][:, None, :]
    for k in range(c.shape[1] - 2, -1, -1):
        out = out * t[..., None] + c[:, k][:, None, :]
    return out


def one_way(a, b, samples=400, grid=100):
    """For each pair of curves (a batch of control points of one degree, `a` and `b` of shape
    (batch, points, 2)), the largest, over `samples` + 1 points of `b`, of the distance to
    the curve `a`: the nearest of `grid` + 1 samples of `a`, then Newton on
    (a(s) - q)·a'(s) inside the two intervals beside it (a point of `a` each way, so never
    less than the true distance)."""
    ca = np.stack([power_form(x) for x in a])
    cb = np.stack([power_form(x) for x in b])
    n = ca.shape[1]
    da = np.stack([k * ca[:, k] for k in range(1, n)], axis=1)
    dda = np.stack([k * da[:, k] for k in range(1, n - 1)], axis=1) if n > 2 else np.zeros((len(a), 1, 2))
    batch = len(a)
    pb = horner(cb, np.broadcast_to(np.linspace(0, 1, samples + 1), (batch, samples + 1)))
    ga = np.linspace(0, 1, grid + 1)
    qa = horner(ca, np.broadcast_to(ga, (batch, grid + 1)))
    # Squared distances from every point of b to every sample of a, |p|² - 2 p·q + |q|².
    d2 = (pb * pb).sum(-1)[:, :, None] - 2 * np.matmul(pb, qa.transpose(0, 2, 1)) + (qa * qa).sum(-1)[:, None, :]
    near = np.argmin(d2, axis=2)
    lo, hi, s = ga[np.maximum(near - 1, 0)], ga[np.minimum(near + 1, grid)], ga[near]
    dist = lambda s: np.hypot(*np.moveaxis(horner(ca, s) - pb, -1, 0))
    for _ in range(8):
        d, v, w = horner(ca, s) - pb, horner(da, s), horner(dda, s)
        f, df = (d * v).sum(-1), (v * v).sum(-1) + (d * w).sum(-1)
        step = np.where(df > 0, f / np.where(df > 0, df, 1.0), 0.0)
        s = np.clip(s - step, lo, hi)
    return np.minimum(dist(s), dist(ga[near])).max(axis=1)


def outline_distances(pairs, chunk=48):
    """How far the outline moved as a shape, per pair of segments (old, new): the Hausdorff
    distance of the two, both ways (sampled: each point's distance to the other curve),
    which the issue's "never further than the tolerance from the original outline" bounds.
    Pairs of one degree are measured together, `chunk` at a time."""
    out = np.zeros(len(pairs))
    by_len = {}
    for i, (a, b) in enumerate(pairs):
        by_len.setdefault(len(a), []).append(i)
    parts = [idx[k:k + chunk] for idx in by_len.values() for k in range(0, len(idx), chunk)]
    jobs = [(np.array([pairs[i][0] for i in part], dtype=float), np.array([pairs[i][1] for i in part], dtype=float))
            for part in parts]
    # The chunks in worker processes, one per core (numpy runs one core each).
    with multiprocessing.get_context("fork").Pool() as pool:
        for part, d in zip(parts, pool.map(both_ways, jobs)):
            out[part] = d
    return out


def both_ways(ab):
    """The sampled Hausdorff distance of each pair of a chunk: `one_way` both ways."""
    a, b = ab
    return np.maximum(one_way(a, b), one_way(b, a))


def compare_checks(before, after, name, slack=0.0):
    """Per segment extrema and per join jump/angle, before against after (`slack`: what
    the reader's own rounding may change, absolute: usvg reads SVG numbers as f32)."""
    sa = {s["name"]: s for s in before["shapes"]}
    sb = {s["name"]: s for s in after["shapes"]}
    if sa.keys() != sb.keys():
        fail(f"{name}: check read other shapes after the fix")
    joins = under = (0, 0)
    bumps = [0, 0]
    hooks = [0, 0]
    # Hooked cubics counted once each however many glyphs draw them (a component's cubic
    # in every composite, a contour copied into accented glyphs): told apart by the input
    # cubic's end curvatures and extrema, which a translation does not change (the output's
    # would tell one input cubic apart by the glyphs it was fixed in).
    distinct = [set(), set()]

    def key(s):
        return tuple(c if c is None else round(c, 9) for c in s["end_curvatures"]) + tuple(round(e["t"], 9) for e in s["extrema"])

    def hook(s):
        return s["degree"] == 3 and any(e["t"] < 0.05 or e["t"] > 0.95 for e in s["extrema"])

    def bump(s):
        ts = [e["t"] for e in s["extrema"]]
        return s["degree"] == 3 and (len(ts) > 1 or any(t < 0.05 or t > 0.95 for t in ts))
    for g in sa:
        for ca, cb in zip(sa[g]["contours"], sb[g]["contours"]):
            for k, (x, y) in enumerate(zip(ca["segments"], cb["segments"])):
                bumps[0] += bump(x)
                bumps[1] += bump(y)
                hooks[0] += hook(x)
                hooks[1] += hook(y)
                # Each distinct input cubic once: hooked before, and still hooked after
                # in any glyph that draws it.
                for side, seg in ((0, x), (1, y)):
                    if hook(seg):
                        distinct[side].add(key(x))
                if len(y["extrema"]) > len(x["extrema"]):
                    fail(f"{name} {g} segment {k}: {len(x['extrema'])} curvature extrema became {len(y['extrema'])}")
            n = len(ca["segments"])
            for ja, jb in zip(ca["joins"], cb["joins"]):
                if jb["angle_break_degrees"] > ja["angle_break_degrees"] + 1e-9 + 100 * slack:
                    fail(f"{name} {g} join after {ja['after_segment']}: angle {ja['angle_break_degrees']} -> {jb['angle_break_degrees']}")
                x, y = ja.get("curvature_jump"), jb.get("curvature_jump")
                if x is None or y is None:
                    continue
                if y > x * (1 + 1e-9) + 1e-12 + slack:
                    fail(f"{name} {g} join after {ja['after_segment']}: jump {x} -> {y}")
                k = ja["after_segment"]
                if ca["segments"][k]["degree"] < 2 or ca["segments"][(k + 1) % n]["degree"] < 2:
                    continue  # next to a line: G2 only with a flat end
                joins = (joins[0] + 1, 0)
                under = (under[0] + (x < 0.01), under[1] + (y < 0.01))
    if bumps[1] > bumps[0]:
        fail(f"{name}: more cubics with a hook or several extrema after ({bumps[1]}) than before ({bumps[0]})")
    if hooks[1] > hooks[0]:
        fail(f"{name}: more cubics with a hook (an extremum within 5 % of an end) after ({hooks[1]}) than before ({hooks[0]})")
    compare_checks.hooks = hooks
    compare_checks.distinct = [len(d) for d in distinct]
    return joins[0], under, bumps


def labels_agree(report, name):
    """Each join's outcome in `fix --json` says what was delivered: `harmonized` exactly
    when the jump after is under 1 % (among the joins the repair moves; no jump: a retracted
    handle)."""
    for c in report["contours"]:
        for j in c["joins"]:
            after = j.get("jump", [None, None])[1]
            if j["outcome"] == "harmonized" and not (after is not None and after < 0.01):
                fail(f"{name} {c['glyph']} contour {c['contour']}: harmonized with a jump of {after}")
            if j["outcome"] in ("limited", "partly", "reverted") and after is not None and after < 0.01:
                fail(f"{name} {c['glyph']} contour {c['contour']}: {j['outcome']} with a jump of {after} (under 1 %)")

def reviewable_diff(src, dst, what):
    """The diff a reviewer sees (`git diff` of the source against the fix, by `git
    diff --no-index --numstat`): the same files; only the .glif files of glyphs whose
    segments changed differ, in as many lines as they have, and every changed line is a
    `<point` line; every other file has its bytes and its modification time."""
    files = lambda root: sorted(os.path.relpath(os.path.join(d, f), root)
                                for d, _, fs in os.walk(root) for f in fs)
    if files(src) != files(dst):
        fail(f"{what}: the fix's files are not the source's")
    out = subprocess.run(["git", "diff", "--no-index", "--numstat", src, dst], capture_output=True, text=True)
    differ = [line.split("\t") for line in out.stdout.splitlines()]
    for added, removed, path in differ:
        if ".glif" not in path:
            fail(f"{what}: {path} differs (only glyph files may)")
        if added != removed:
            fail(f"{what}: {path}: {added} lines added, {removed} removed (only lines of moved points may change)")
    diff = subprocess.run(["git", "diff", "--no-index", "-U0", src, dst], capture_output=True, text=True).stdout
    for line in diff.splitlines():
        if line[:1] in "+-" and not line.startswith(("+++", "---")) and not line[1:].lstrip().startswith("<point"):
            fail(f"{what}: a changed line that is not a point's: {line!r}")
    same = [f for f in files(src) if os.path.getmtime(os.path.join(src, f)) == os.path.getmtime(os.path.join(dst, f))]
    if len(same) != len(files(src)) - len(differ):
        fail(f"{what}: {len(files(src)) - len(differ)} files unchanged, but {len(same)} keep their modification time")
    print(f"{what}: git diff shows {len(differ)} glyph files changed, only <point> lines; "
          f"{len(same)} of {len(files(src))} files keep their bytes and modification time")


fonts = sorted(glob.glob("/usr/share/texmf/fonts/opentype/public/tex-gyre/texgyre*-regular.otf"))[:2]
if not fonts:
    fail("no TeX Gyre fonts (apt install fonts-texgyre)")
for f in fonts:
    name = f.rsplit("/", 1)[1]
    src = f"{scratch.name}/{name}.ufo"
    ufo = ufoLib2.Font()
    extractor.extractUFO(f, ufo, doFeatures=False)  # features play no part in a fix
    ufo.save(src)
    before = check_json(src)
    for mode in ([], ["--move-points"]):
        dst = f"{scratch.name}/{name}-fixed{''.join(mode)}.ufo"
        out = subprocess.run([AECURVE, "fix", src, "-o", dst, "--tolerance", str(TOLERANCE), "--json", *mode],
                             capture_output=True, text=True)
        if out.returncode != 0:
            fail(f"fix {name} {mode}: {out.stderr.strip()}")
        report = json.loads(out.stdout)
        claims = report["counts"]
        labels_agree(report, f"{name} {mode}")
        moved = same_structure(ufoLib2.Font.open(src), ufoLib2.Font.open(dst), name, bool(mode))
        reviewable_diff(src, dst, f"{name} {' '.join(mode)}")
        joins, (u0, u1), bumps = compare_checks(before, check_json(dst), name)
        if (claims["bumps_before"], claims["bumps_after"]) != tuple(bumps):
            fail(f"{name}: fix claims {claims['bumps_before']} -> {claims['bumps_after']} hooks or wobbles, check counts {bumps}")
        if claims["worse_joins"] != 0 or claims["cubics_with_more_extrema"] != 0:
            fail(f"{name}: fix claims {claims}")
        if u1 < u0:
            fail(f"{name}: fewer joins under 1 % after ({u1}) than before ({u0})")
        d0, d1 = compare_checks.distinct
        if 2 * d1 > d0:
            fail(f"{name} {mode}: the distinct hooked cubics fell from {d0} to {d1} only, not by half")
        h0, h1 = compare_checks.hooks
        if 2 * h1 > h0:
            fail(f"{name} {mode}: the hooked cubics in all glyphs fell from {h0} to {h1} only, not by half")
        if u1 < 0.8 * joins:
            fail(f"{name} {mode}: {u1} of {joins} G1 joins between curves under a 1 % jump, "
                 f"fewer than 80 %")
        print(f"{name} {' '.join(mode) or '(handles only)'}: {claims['changed_segments']} segments changed, "
              f"largest move {moved:.2f}; of {joins} G1 joins between two curves, {u0} ({100 * u0 / max(joins, 1):.1f} %) "
              f"under a 1 % curvature jump before, {u1} ({100 * u1 / max(joins, 1):.1f} %) after; none worse, "
              f"no segment with more extrema; cubics with a hook or several extrema {bumps[0]} -> {bumps[1]}, "
              f"with a hook (an extremum within 5 % of an end) {compare_checks.hooks[0]} -> {compare_checks.hooks[1]} "
              f"in all glyphs, {d0} -> {d1} distinct (check --json on both)")
# Masters in a designspace: Cantarell's Thin and ExtraBold (fonts-cantarell: static
# instances of one variable design, so most glyphs agree point for point) as UFOs. After
# `fix` on the designspace: every master has the same structure as before and moved within
# the tolerance; fontTools' varLib.interpolatable finds no problem it did not find in the
# input; and the instance half way between the two masters, made here point by point from
# the written UFOs (not by aecurve), is no worse than the same instance of the input's
# masters by `check --json` (no join with a larger jump or angle, no cubic with more
# extrema).
from fontTools.designspaceLib import AxisDescriptor, DesignSpaceDocument, SourceDescriptor


def interpolatable_problems(paths):
    out = subprocess.run([sys.executable, "-m", "fontTools.varLib.interpolatable", "--json", *paths],
                         capture_output=True, text=True)
    found = json.loads(out.stdout or "{}")
    return {(g, p["type"]) for g, probs in found.items() for p in probs}


def halfway_ufo(a, b, path):
    """The instance half way between two UFO masters, glyph by glyph where every contour
    agrees point for point (others left out); components and anchors dropped."""
    fa, fb = ufoLib2.Font.open(a), ufoLib2.Font.open(b)
    out = ufoLib2.Font()
    out.info.unitsPerEm = fa.info.unitsPerEm
    kept = 0
    for name in fa.keys():
        if name not in fb:
            continue
        ga, gb = fa[name], fb[name]
        if not ga.contours or len(ga.contours) != len(gb.contours) or any(
                [p.type for p in ca.points] != [p.type for p in cb.points]
                for ca, cb in zip(ga.contours, gb.contours)):
            continue
        g = out.newGlyph(name)
        pen = g.getPointPen()
        for ca, cb in zip(ga.contours, gb.contours):
            pen.beginPath()
            for pa, pb in zip(ca.points, cb.points):
                pen.addPoint(((pa.x + pb.x) / 2, (pa.y + pb.y) / 2), pa.type, pa.smooth)
            pen.endPath()
        kept += 1
    out.save(path)
    return kept


weights = {"Thin": 100, "ExtraBold": 800}
if not all(glob.glob(f"/usr/share/fonts/opentype/cantarell/Cantarell-{w}.otf") for w in weights):
    fail("no Cantarell fonts (apt install fonts-cantarell)")
ds_dir = f"{scratch.name}/ds"
os.makedirs(f"{ds_dir}/masters")
doc = DesignSpaceDocument()
axis = AxisDescriptor()
axis.name, axis.tag, axis.minimum, axis.default, axis.maximum = "weight", "wght", 100, 100, 800
doc.addAxis(axis)
for w, v in weights.items():
    ufo = ufoLib2.Font()
    extractor.extractUFO(f"/usr/share/fonts/opentype/cantarell/Cantarell-{w}.otf", ufo, doFeatures=False)
    ufo.save(f"{ds_dir}/masters/Cantarell-{w}.ufo")
    src = SourceDescriptor()
    src.filename, src.location, src.name = f"masters/Cantarell-{w}.ufo", {"weight": v}, w
    doc.addSource(src)
doc.write(f"{ds_dir}/Cantarell.designspace")
out = subprocess.run([AECURVE, "fix", f"{ds_dir}/Cantarell.designspace", "-o", f"{ds_dir}/out/Cantarell.designspace",
                      "--tolerance", str(TOLERANCE), "--json"], capture_output=True, text=True)
if out.returncode != 0:
    fail(f"fix designspace: {out.stderr.strip()}")
report = json.loads(out.stdout)
ins = [f"{ds_dir}/masters/Cantarell-{w}.ufo" for w in weights]
outs = [f"{ds_dir}/out/masters/Cantarell-{w}.ufo" for w in weights]
for a, b, m in zip(ins, outs, report["masters"]):
    same_structure(ufoLib2.Font.open(a), ufoLib2.Font.open(b), a)
    if m["counts"]["worse_joins"] != 0 or m["counts"]["cubics_with_more_extrema"] != 0:
        fail(f"{a}: fix claims {m['counts']}")
new = interpolatable_problems(outs) - interpolatable_problems(ins)
if new:
    fail(f"interpolatable finds problems the input masters did not have: {sorted(new)[:10]}")
kept = halfway_ufo(*ins, f"{ds_dir}/half-in.ufo")
halfway_ufo(*outs, f"{ds_dir}/half-out.ufo")
joins, (u0, u1), bumps = compare_checks(check_json(f"{ds_dir}/half-in.ufo"), check_json(f"{ds_dir}/half-out.ufo"),
                                        "the instance half way")
for w, m in zip(weights, report["masters"]):
    c = m["counts"]
    print(f"Cantarell {w} master: of {c['smooth_cubic_joins']} smooth joins between cubics, "
          f"{c['under_1_percent_before']} under a 1 % curvature jump before, {c['under_1_percent_after']} after")
print(f"designspace: {report['restored_segments']} segments given back in both masters to keep instances no worse; "
      f"interpolatable: no new problem; the instance half way ({kept} glyphs): of {joins} G1 joins between two "
      f"curves, {u0} under 1 % before, {u1} after, none worse, no cubic with more extrema")

# SVG icons (Adwaita's scalable set, every fourth): written back with only the `d` of
# changed paths replaced; read by usvg (through check) with the same paths and segments,
# and nothing worse.
icons = sorted(glob.glob("/usr/share/icons/Adwaita/scalable/*/*.svg"))[::4]
changed = total = noise = 0


def fixed_icon(job):
    """Fix icon `job` = (index, path) into a file of its own and check both: the aecurve
    runs of one icon (the comparisons are made in order below)."""
    i, icon = job
    dst = f"{scratch.name}/icon-fixed-{i}.svg"
    out = subprocess.run([AECURVE, "fix", icon, "-o", dst, "--tolerance", "0.05"], capture_output=True, text=True)
    if out.returncode != 0:
        fail(f"fix {icon}: {out.stderr.strip()}")
    a, b = check_json(icon), check_json(dst)
    differs = open(icon, "rb").read() != open(dst, "rb").read()
    os.remove(dst)
    return icon, a, b, differs


# The aecurve runs of several icons at once (each run is short: its start dominates).
with concurrent.futures.ThreadPoolExecutor(max_workers=2 * (os.cpu_count() or 1)) as pool:
    runs = list(pool.map(fixed_icon, enumerate(icons)))
for icon, a, b, differs in runs:
    segs = lambda v: [[len(c["segments"]) for c in s["contours"]] for s in v["shapes"]]
    sa, sb = segs(a), segs(b)
    # A closing line of float-noise length (relative commands summed) that usvg keeps in the
    # input and the written absolute numbers no longer have: one segment less, at most.
    if [len(x) for x in sa] != [len(x) for x in sb] or any(
            not 0 <= p - q <= 1 for x, y in zip(sa, sb) for p, q in zip(x, y)):
        fail(f"{icon}: the fixed file's paths or segments differ: {sa} {sb}")
    for s, t in zip(a["shapes"], b["shapes"]):
        keep = [i for i, (c, d) in enumerate(zip(s["contours"], t["contours"]))
                if len(c["segments"]) == len(d["segments"])]
        noise += len(s["contours"]) - len(keep)
        s["contours"] = [s["contours"][i] for i in keep]
        t["contours"] = [t["contours"][i] for i in keep]
    compare_checks(a, b, icon, slack=1e-4)
    total += 1
    changed += differs
print(f"{total} Adwaita icons fixed and re-checked ({changed} changed): same paths and segments, nothing "
      f"worse ({noise} contours lost a closing line of float-noise length and are not compared join by join)")
print("fix check: ok")
