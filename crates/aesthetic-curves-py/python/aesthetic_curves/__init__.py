"""Aesthetic curves: log-aesthetic curves, exact curvature-monotonicity tests, rational
approximations, the pseudo-elastic spline and sketch fitting, computed by the Rust library
``aesthetic-curves`` and returned as NumPy arrays.

Points go in as an ``(n, 2)`` float64 array (or a sequence of ``(x, y)`` pairs). Every
error the library reports is an :class:`AestheticCurvesError` (subclasses name the kind).
"""

from ._native import (
    AestheticCurvesError,
    Bezier,
    BSpline,
    CurveAt,
    DeadlineError,
    DegenerateError,
    EndCurvature,
    FairingReport,
    InvalidInputError,
    LacFit,
    LacSpline,
    LacInflectionSegment,
    LacSegment,
    MonotoneReport,
    NoConvergenceError,
    NoSegmentError,
    Nurbs,
    PseudoSpline,
    RationalBezier,
    RationalCubicFit,
    RationalSpline,
    Samples,
    Sketch,
    SketchContour,
    Corner,
    SmoothJoin,
    Seam,
    SketchSegment,
    SplineSegment,
    are_curvature_monotone,
    check_outline,
    fit_contour,
    fit_lac,
    fit_sketch,
    harmonize,
    index_contour,
    lac_spline,
    pseudo_elastic,
)

__all__ = [
    "AestheticCurvesError",
    "Bezier",
    "BSpline",
    "CurveAt",
    "DeadlineError",
    "DegenerateError",
    "EndCurvature",
    "FairingReport",
    "InvalidInputError",
    "LacFit",
    "LacSpline",
    "LacInflectionSegment",
    "LacSegment",
    "MonotoneReport",
    "NoConvergenceError",
    "NoSegmentError",
    "Nurbs",
    "PseudoSpline",
    "RationalBezier",
    "RationalCubicFit",
    "RationalSpline",
    "Samples",
    "Sketch",
    "SketchContour",
    "Corner",
    "SmoothJoin",
    "Seam",
    "SketchSegment",
    "SplineSegment",
    "are_curvature_monotone",
    "check_outline",
    "fit_contour",
    "fit_lac",
    "fit_sketch",
    "harmonize",
    "index_contour",
    "lac_spline",
    "plot_comb",
    "pseudo_elastic",
]


def plot_comb(curve, ax=None, samples=200, scale=None, **line_kwargs):
    """Draw `curve` (anything with ``sample(n)``) and its curvature comb with matplotlib.

    The comb's teeth stand on the normal, on the side the curve turns to, with length
    ``scale * kappa``; by default the longest tooth is a fifth of the curve's extent.
    Returns the axes. Needs matplotlib (``pip install aesthetic-curves[plot]``).
    """
    import numpy as np

    try:
        import matplotlib.pyplot as plt
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("plot_comb needs matplotlib: pip install matplotlib") from e
    s = curve.sample(samples)
    if scale is None:
        extent = np.ptp(s.points, axis=0).max()
        peak = np.abs(s.kappa).max()
        scale = 0.2 * extent / peak if peak > 0 else 0.0
    base, tips = s.comb(scale)
    if ax is None:
        _, ax = plt.subplots()
    for b, t in zip(base, tips):
        ax.plot([b[0], t[0]], [b[1], t[1]], color="0.6", linewidth=0.6)
    ax.plot(tips[:, 0], tips[:, 1], color="0.45", linewidth=0.8)
    ax.plot(s.points[:, 0], s.points[:, 1], **{"color": "C0", "linewidth": 2, **line_kwargs})
    ax.set_aspect("equal")
    return ax
