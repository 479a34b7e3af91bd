"""The Prius key line (Graiff Zurita, Kajiwara & Miura 2023, MIT licence; the repository's
crates/aesthetic-curves-data/data/prius): a measured line fitted by one LAC segment and by
a G2 chain of LAC pieces, each delivered as a curvature-monotone rational cubic; the
result drawn with its curvature comb (SVG, and PNG with matplotlib) and exported for CAD
(DXF, STEP).

    python examples/prius.py [out-dir]
"""

import sys
from pathlib import Path

import numpy as np

import aesthetic_curves as ac

here = Path(__file__).resolve().parent
data = here.parents[1] / "aesthetic-curves-data" / "data" / "prius" / "ps_3.csv"
out = Path(sys.argv[1] if len(sys.argv) > 1 else ".")
out.mkdir(parents=True, exist_ok=True)

# %% The measured line: an (n, 2) array in millimetres.
points = np.loadtxt(data, delimiter=",", skiprows=1)
print(f"ps_3: {len(points)} points")

# %% One LAC segment through all of it (alpha fitted).
fit = ac.fit_lac(points)
print(f"one LAC segment: alpha {fit.alpha:.3f}, max deviation {fit.max_deviation:.3f} mm")

# %% A G2 chain of LAC pieces within 0.3 mm, each a proven curvature-monotone rational cubic.
sketch = ac.fit_sketch(points, tolerance=0.3)
print(
    f"sketch: {len(sketch.pieces)} pieces, max deviation {sketch.max_deviation:.3f} mm, "
    f"G2 {sketch.g2}, every piece monotone {sketch.all_monotone}"
)
for i, (piece, alpha) in enumerate(zip(sketch.pieces, sketch.alphas)):
    k0, k1 = piece.end_curvatures()
    print(f"  piece {i}: alpha {alpha:7.3f}, curvature {k0:+.3e} -> {k1:+.3e} /mm")

# %% The curve and its curvature comb as arrays, written as an SVG picture.
samples = [p.sample(60) for p in sketch.pieces]
pts = np.concatenate([s.points for s in samples])
peak = max(np.abs(s.kappa).max() for s in samples)
scale = 0.08 * np.ptp(pts, axis=0).max() / peak
combs = [s.comb(-scale) for s in samples]  # teeth outside the curve
tips = np.concatenate([t for _, t in combs])
lo, hi = np.minimum(pts.min(0), tips.min(0)), np.maximum(pts.max(0), tips.max(0))
pad = 0.05 * (hi - lo).max()
w, h = hi - lo + 2 * pad


def xy(p):
    """SVG coordinates of a point (SVG's y axis points down)."""
    return p[0] - lo[0] + pad, hi[1] - p[1] + pad


teeth = "".join(
    '<line x1="%.4f" y1="%.4f" x2="%.4f" y2="%.4f" />' % (*xy(b), *xy(t)) for b, t in zip(pts, tips)
)
line = lambda q: " ".join("%.4f,%.4f" % xy(p) for p in q)
svg = (
    f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {w:.4f} {h:.4f}" width="900" '
    f'height="{900 * h / w:.0f}">'
    f'<g stroke="#999" stroke-width="{0.002 * w:.4f}">{teeth}</g>'
    f'<polyline fill="none" stroke="#777" stroke-width="{0.003 * w:.4f}" '
    f'points="{line(tips)}" />'
    f'<polyline fill="none" stroke="#1f5fa8" stroke-width="{0.006 * w:.4f}" '
    f'points="{line(pts)}" />'
    f'<text font-family="sans-serif" font-size="{0.032 * w:.4f}">'
    f'<tspan x="{0.2 * pad:.4f}" y="{0.35 * pad:.4f}">Prius key line ps_3 (blue): {len(sketch.pieces)} LAC pieces, G2,</tspan>'
    f'<tspan x="{0.2 * pad:.4f}" y="{0.5 * pad + 0.045 * w:.4f}">max deviation {sketch.max_deviation:.3f} mm; '
    f"grey: curvature comb</tspan></text></svg>"
)
(out / "prius-ps_3.svg").write_text(svg)
print(f"wrote {out / 'prius-ps_3.svg'}")

# %% The delivered curve for CAD: one rational NURBS, as DXF (SPLINE) and STEP.
sketch.to_dxf(out / "prius-ps_3.dxf")
sketch.to_step(out / "prius-ps_3.step", name="Prius key line ps_3")
print(f"wrote {out / 'prius-ps_3.dxf'} and {out / 'prius-ps_3.step'}")

# %% The same with matplotlib, when it is installed.
try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(5, 9))
    ax.plot(points[:, 0], points[:, 1], ".", color="C3", markersize=3, alpha=0.5, label="measured")
    for i, p in enumerate(sketch.pieces):
        ac.plot_comb(p, ax=ax, scale=-scale, zorder=3, label="fitted (comb in grey)" if i == 0 else None)
    ax.set_title(f"Prius key line ps_3: {len(sketch.pieces)} LAC pieces, G2, within 0.3 mm")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.08), fontsize="small")
    fig.savefig(out / "prius-ps_3.png", dpi=120, bbox_inches="tight")
    print(f"wrote {out / 'prius-ps_3.png'}")
except ImportError:
    print("(matplotlib not installed: no PNG)")
