#!/usr/bin/env python3
"""`aecurve check` on files made by other tools (CI step; needs fonts-texgyre and
adwaita-icon-theme from Debian, fontTools from PyPI).

- OpenType/CFF fonts (TeX Gyre): the glyphs read (plus those listed unreadable) are the
  font's own glyph order as fontTools reads it, names included; every segment has a verdict
  or a flag; the JSON has no NaN or infinity.
- SVG icons (Adwaita's scalable set): every file is read and checked, or refused with the
  clear "no path" error (icons that hold only images or text); the JSON is clean.

Exits non-zero on the first failure, printing what failed.
"""
import glob
import json
import subprocess
import sys

from fontTools.ttLib import TTFont

AECURVE = sys.argv[1] if len(sys.argv) > 1 else "target/release/aecurve"


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
sys.exit(1 if failures else 0)
