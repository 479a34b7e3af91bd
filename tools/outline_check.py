#!/usr/bin/env python3
"""`aecurve check` on files made by other tools (CI step; needs fonts-texgyre and
adwaita-icon-theme from Debian, fontTools, ufo-extractor, ufoLib2 and ezdxf from PyPI).

- OpenType/CFF fonts (TeX Gyre): the glyphs read (plus those listed unreadable) are the
  font's own glyph order as fontTools reads it, names included; every segment has a verdict
  or a flag; the JSON has no NaN or infinity.
- SVG icons (Adwaita's scalable set): every file is read and checked, or refused with the
  clear "no path" error (icons that hold only images or text); the JSON is clean.
- UFO sources made from two of those fonts by ufo-extractor: every glyph reads with the
  same segments and the same verdicts as the font itself.
- A DXF written by ezdxf with every entity type `check` reads (LINE, ARC, CIRCLE, LWPOLYLINE
  with bulges, a rational SPLINE, and a fit-point SPLINE it lists as unreadable): the
  curvature of every arc is 1/radius.

Exits non-zero on the first failure, printing what failed.
"""
import glob
import json
import math
import os
import subprocess
import sys
import tempfile

import extractor
import ezdxf
import ufoLib2

from fontTools.ttLib import TTFont

AECURVE = sys.argv[1] if len(sys.argv) > 1 else "target/release/aecurve"
# Every file this check writes (UFOs, the DXF) goes here and is removed at exit.
scratch = tempfile.TemporaryDirectory(prefix="aecurve-outline-check-")


def strict(s):
    return json.loads(s, parse_constant=lambda c: (_ for _ in ()).throw(ValueError(c)))


def check(path):
    r = subprocess.run([AECURVE, "check", path, "--json"], capture_output=True, text=True)
    return r.returncode, r.stdout, r.stderr


failures = 0
fonts = sorted(glob.glob("/usr/share/texmf/fonts/opentype/public/tex-gyre/texgyre*-regular.otf"))
if not fonts:
    sys.exit("no TeX Gyre fonts: install fonts-texgyre")
for f in fonts:
    code, out, err = check(f)
    if code != 0:
        print(f"FAIL {f}: {err.strip()}")
        failures += 1
        continue
    v = strict(out)
    order = TTFont(f).getGlyphOrder()
    read = [s["name"] for s in v["shapes"]] + [u["name"] for u in v["unreadable"]]
    if sorted(read) != sorted(order):
        print(f"FAIL {f}: {len(read)} glyphs read, fontTools has {len(order)}")
        failures += 1
        continue
    unjudged = sum(
        1
        for s in v["shapes"]
        for c in s["contours"]
        for g in c["segments"]
        if "monotone" not in g and "flag" not in g
    )
    if unjudged:
        print(f"FAIL {f}: {unjudged} segments without a verdict or a flag")
        failures += 1
        continue
    n = v["counts"]
    print(
        f"ok   {f.split('/')[-1]}: {n['shapes']} glyphs, {n['segments']} segments, "
        f"{n['monotone_segments']} monotone, {n['near_breaks']} near-breaks, "
        f"checked in {v['milliseconds']['check']:.0f} ms"
    )

icons = sorted(glob.glob("/usr/share/icons/Adwaita/scalable/**/*.svg", recursive=True))
if not icons:
    sys.exit("no Adwaita icons: install adwaita-icon-theme")
read = refused = 0
for f in icons:
    code, out, err = check(f)
    if code == 0:
        strict(out)
        read += 1
    elif "no path" in err:
        refused += 1
    else:
        print(f"FAIL {f}: {err.strip()}")
        failures += 1
print(f"ok   {read} Adwaita icons checked, {refused} refused as pathless, of {len(icons)}")

def verdicts(v):
    return {
        s["name"]: [[(g["degree"], g.get("monotone")) for g in c["segments"]] for c in s["contours"]]
        for s in v["shapes"]
    }


for f in [x for x in fonts if "heros-" in x or "adventor-" in x]:
    ufo_path = os.path.join(scratch.name, os.path.basename(f) + ".ufo")
    ufo = ufoLib2.Font()
    extractor.extractUFO(f, ufo)
    ufo.save(ufo_path)
    codes = [check(x) for x in (f, ufo_path)]
    if any(c[0] != 0 for c in codes):
        print(f"FAIL UFO of {f}: {[c[2].strip() for c in codes]}")
        failures += 1
        continue
    a, b = (verdicts(strict(c[1])) for c in codes)
    differ = [n for n in a if a[n] != b.get(n)]
    if differ or len(a) != len(b):
        print(f"FAIL UFO of {f}: {len(differ)} glyphs differ, e.g. {differ[:3]}")
        failures += 1
    else:
        print(f"ok   UFO of {f.split('/')[-1]}: {len(b)} glyphs, the same segments and verdicts")

dxf_path = os.path.join(scratch.name, "all.dxf")
doc = ezdxf.new("R2010")
msp = doc.modelspace()
msp.add_line((0, 0), (10, 0), dxfattribs={"layer": "line"})
msp.add_arc((20, 0), 5, 0, 120, dxfattribs={"layer": "r5"})
msp.add_circle((40, 0), 4, dxfattribs={"layer": "r4"})
msp.add_lwpolyline(
    [(50, 0, 0, 0, 0), (60, 0, 0, 0, 1), (60, 4, 0, 0, 0), (50, 4, 0, 0, 1)],
    format="xyseb", close=True, dxfattribs={"layer": "slot"},
)
msp.add_rational_spline(
    [(73, 0), (73, 3), (70, 3)], [1, math.sqrt(0.5), 1], degree=2, knots=[0, 0, 0, 1, 1, 1],
    dxfattribs={"layer": "r3"},
)
msp.add_spline(fit_points=[(80, 0), (82, 1), (84, 0), (86, 1)], dxfattribs={"layer": "fit"})
doc.saveas(dxf_path)
code, out, err = check(dxf_path)
if code != 0:
    print(f"FAIL ezdxf drawing: {err.strip()}")
    failures += 1
else:
    v = strict(out)
    radius = {"r5": 5, "r4": 4, "r3": 3, "slot": 2}
    bad = []
    for s in v["shapes"]:
        layer = s["name"].split(" #")[0]
        for g in s["contours"][0]["segments"]:
            if g["degree"] > 1 and abs(g["max_abs_curvature"] - 1 / radius[layer]) > 1e-9:
                bad.append((s["name"], g["max_abs_curvature"]))
    layers = sorted(s["name"].split(" #")[0] for s in v["shapes"])
    unread = [u["name"].split(" #")[0] for u in v["unreadable"]]
    if bad or layers != ["line", "r3", "r4", "r5", "slot"] or unread != ["fit"]:
        print(f"FAIL ezdxf drawing: {bad} {layers} {unread}")
        failures += 1
    else:
        print("ok   ezdxf drawing: every entity type read, every arc's curvature 1/radius")
sys.exit(1 if failures else 0)
