import os
from typing import Any, Optional, Sequence, Tuple, Union, final, type_check_only

import numpy as np
import numpy.typing as npt

_Points = Union[npt.NDArray[np.float64], Sequence[Tuple[float, float]]]
_Numbers = Union[npt.NDArray[np.float64], Sequence[float]]
_Params = Union[float, npt.NDArray[np.float64], Sequence[float]]
_Array1 = npt.NDArray[np.float64]
_Array2 = npt.NDArray[np.float64]

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
    "are_curvature_monotone",
    "check_outline",
    "fit_lac",
    "fit_sketch",
    "fit_contour",
    "SketchContour",
    "Corner",
    "SmoothJoin",
    "Seam",
    "SketchSegment",
    "SplineSegment",
    "harmonize",
    "index_contour",
    "lac_spline",
    "plot_comb",
    "pseudo_elastic",
]

class AestheticCurvesError(Exception): ...
class InvalidInputError(AestheticCurvesError): ...
class DegenerateError(AestheticCurvesError): ...
class NoSegmentError(AestheticCurvesError): ...
class NoConvergenceError(AestheticCurvesError): ...
class DeadlineError(AestheticCurvesError): ...

@type_check_only
class _Exportable:
    """(Stub only) the exports every curve class has."""

    def to_dxf(self, path: Optional[Union[str, "os.PathLike[str]"]] = None) -> Optional[bytes]:
        """A DXF drawing with the curve as one rational SPLINE (None when written to path)."""
    def to_step(self, path: Optional[Union[str, "os.PathLike[str]"]] = None, name: str = "curve") -> Optional[str]:
        """A STEP file with the curve as a rational B-spline (None when written to path)."""
    def to_iges(self, path: Optional[Union[str, "os.PathLike[str]"]] = None, name: str = "curve") -> Optional[str]:
        """An IGES file (entity 126) with the curve (None when written to path)."""
    def to_svg(self, path: Optional[Union[str, "os.PathLike[str]"]] = None, tolerance: float = 1e-3, caption: str = "curve") -> Optional[str]:
        """An SVG picture of the curve and its curvature comb (None when written to path)."""

@final
class Samples:
    """_Points, unit tangents and signed curvature of a curve."""

    points: _Array2
    tangents: _Array2
    kappa: _Array1
    def comb(self, scale: float) -> Tuple[_Array2, _Array2]:
        """The points and the tips of the comb's teeth (length ``scale * kappa``)."""
    def __len__(self) -> int: ...

@final
class CurveAt:
    """A curve at values of its parameter (``at``): one row per parameter."""

    points: _Array2
    d1: _Array2
    d2: _Array2
    kappa: _Array1
    dkappa_ds: _Array1
    def __len__(self) -> int: ...

@final
class MonotoneReport:
    monotone: bool
    trend: Optional[str]
    extrema: _Array1
    test_degree: int
    exact: bool
    @property
    def exact_arithmetic(self) -> bool: ...
    ends: Tuple[EndCurvature, EndCurvature]

@final
class EndCurvature:
    kind: str
    curvature: Optional[float]
    retracted_handles: int
    growth_rate: Optional[int]
    growth: Optional[str]
    sign: Optional[int]

@final
class Nurbs(_Exportable):
    @property
    def degree(self) -> int: ...
    @property
    def knots(self) -> _Array1: ...
    @property
    def control_points(self) -> _Array2: ...
    @property
    def weights(self) -> _Array1: ...
    def domain(self) -> Tuple[float, float]: ...
    def eval(self, u: _Params) -> npt.NDArray[np.float64]: ...
    def at(self, u: _Params) -> CurveAt:
        """Point, derivatives in the knot parameter, curvature and dκ/ds at ``u``."""
    def bezier_spans(self) -> list[RationalBezier]: ...

@type_check_only
class _BezierBase(_Exportable):
    """(Stub only) the methods both Bézier classes have."""

    @property
    def points(self) -> _Array2: ...
    @property
    def degree(self) -> int: ...
    def eval(self, t: _Params) -> npt.NDArray[np.float64]: ...
    def kappa(self, t: _Params) -> Union[float, _Array1]: ...
    def dkappa_ds(self, t: _Params) -> Union[float, _Array1]: ...
    def is_curvature_monotone(self) -> bool: ...
    def curvature_monotone(self) -> MonotoneReport: ...
    def curvature_monotone_sampled(self, samples: int) -> Tuple[bool, Optional[str]]: ...
    def sample(self, n: int) -> Samples: ...
    def arc_length(self) -> float: ...
    def end_curvatures(self) -> Tuple[float, float]: ...
    def domain(self) -> Tuple[float, float]: ...
    def at(self, t: _Params) -> CurveAt:
        """Point, derivatives, curvature and dκ/ds at ``t`` (clamped into (0, 1))."""
    def to_svg_path(self, accuracy: float = 1e-3) -> str: ...
    def to_nurbs(self) -> Nurbs: ...

@final
class Bezier(_BezierBase):
    """A polynomial Bézier curve of any degree."""

    def __new__(cls, points: _Points) -> "Bezier": ...

@final
class RationalBezier(_BezierBase):
    """A rational Bézier curve (positive weights)."""

    def __new__(cls, points: _Points, weights: _Numbers) -> "RationalBezier": ...
    @property
    def weights(self) -> _Array1: ...

def are_curvature_monotone(control: npt.NDArray[np.float64]) -> npt.NDArray[np.bool_]:
    """Exact verdicts of many Bézier curves: ``control`` has shape (m, n + 1, 2)."""

@final
class RationalCubicFit(_Exportable):
    curve: RationalBezier
    f0: float
    f1: float
    rms: float
    max_error: float
    monotone: bool
    converged: bool
    evaluations: int
    control_points: _Array2
    weights: _Array1

@final
class RationalSpline(_Exportable):
    nurbs: Nurbs
    pieces: list[RationalCubicFit]
    max_error: float

@type_check_only
class _LacBase(_Exportable):
    """(Stub only) the methods both LAC segment classes have."""

    @property
    def alpha(self) -> float: ...
    @property
    def theta_d(self) -> float: ...
    @property
    def control(self) -> _Array2: ...
    def domain(self) -> Tuple[float, float]: ...
    def at(self, s: _Params) -> CurveAt:
        """Point, unit tangent, second derivative, curvature and dκ/ds at arc length ``s``."""
    def arc_length(self) -> float: ...
    def end_curvatures(self) -> Tuple[float, float]: ...
    def sample(self, n: int) -> Samples: ...
    def rational_approx(self) -> RationalCubicFit: ...
    def rational_spline(self, tolerance: float, max_pieces: int = 64) -> RationalSpline: ...
    def to_svg_path(self, accuracy: float = 1e-3) -> str: ...
    def to_nurbs(self, tolerance: Optional[float] = None) -> Nurbs: ...

@final
class LacSegment(_LacBase):
    """A log-aesthetic curve segment of shape alpha in a control triangle."""

    def __new__(cls, alpha: float, control: _Points) -> "LacSegment": ...
    @staticmethod
    def exists(alpha: float, control: _Points) -> bool: ...
    @staticmethod
    def theta_lim(alpha: float, theta_d: float) -> float: ...
    def eval_turning(self, taus: _Numbers) -> Tuple[_Array2, _Array2, _Array1]: ...

@final
class LacInflectionSegment(_LacBase):
    """A log-aesthetic segment with zero curvature at control[0]."""

    def __new__(cls, control: _Points) -> "LacInflectionSegment": ...

@final
class PseudoSpline(_Exportable):
    @property
    def tangent_angles(self) -> _Array1: ...
    @property
    def length(self) -> float: ...
    @property
    def area(self) -> float: ...
    @property
    def energy(self) -> float: ...
    def beziers(self) -> list[Bezier]: ...
    def sample(self, n: int) -> Samples: ...
    def domain(self) -> Tuple[float, float]: ...
    def at(self, u: _Params) -> CurveAt:
        """Span ``floor(u)`` at its own t = u - floor(u) (clamped into (0, n))."""
    def to_nurbs(self) -> Nurbs: ...
    def __len__(self) -> int: ...

def pseudo_elastic(points: _Points, closed: bool = False, mode: str = "table") -> PseudoSpline: ...

@final
class SplineSegment:
    kind: str
    span: int
    alpha: Optional[float]
    control: _Array2
    end_curvatures: tuple[float, float]
    rational: RationalBezier
    rational_error: float
    monotone: bool

@final
class LacSpline(_Exportable):
    nurbs: Nurbs
    pieces: list[RationalBezier]
    segments: list[SplineSegment]
    kinds: list[str]
    spans: list[int]
    alphas: list[Optional[float]]
    tangents: list[tuple[float, float]]
    max_curvature_jump: float
    max_cubic_jump: float
    all_monotone: bool
    converged: bool
    iterations: int
    closed: bool
    g2: bool
    max_cubic_angle: float
    max_rational_error: float
    inflections: int
    curvature_extrema: int
    span_alphas: list[float]
    relaxed_spans: list[int]
    def domain(self) -> Tuple[float, float]: ...
    def at(self, u: _Params) -> CurveAt:
        """Piece ``floor(u)`` at its own t = u - floor(u) (clamped into (0, n))."""
    def __len__(self) -> int: ...

def lac_spline(
    points: _Points,
    alpha: float = ...,
    closed: bool = False,
    corners: list[int] = ...,
    alphas: Optional[list[float]] = None,
) -> LacSpline: ...

@final
class LacFit:
    segment: LacSegment
    alpha: float
    rms_deviation: float
    max_deviation: float
    converged: bool
    control: _Array2
    rms_correspondence: float
    objective: str
    max_curvature: float
    alpha_at_bound: bool
    curvature_cap: Optional[float]
    alpha_guess: Optional[float]

def fit_lac(points: _Points, alpha: Optional[float] = None, objective: str = "band", start: str = "scan") -> LacFit: ...

@final
class SketchSegment:
    kind: str
    alpha: float
    alpha_at_bound: bool
    alpha_range: Optional[tuple[float, float]]
    alpha_determined: bool
    alpha_estimate: Optional[float]
    control: _Array2
    end_curvatures: tuple[float, float]
    rational: RationalBezier
    rational_error: float
    monotone: bool

@final
class FairingReport:
    converged: bool
    iterations: int
    initial_jump: float
    final_jump: float

@final
class BSpline:
    degree: int
    knots: list[float]
    control_points: _Array2

@final
class Sketch(_Exportable):
    nurbs: Nurbs
    pieces: list[RationalBezier]
    alphas: list[float]
    segments: list[SketchSegment]
    fairing: FairingReport
    bspline: BSpline
    max_deviation: float
    rms_deviation: float
    max_curvature_jump: float
    g2: bool
    all_monotone: bool
    converged: bool
    tolerance: float
    inflections: int
    curvature_extrema: int
    def domain(self) -> Tuple[float, float]: ...
    def at(self, u: _Params) -> CurveAt:
        """Piece ``floor(u)`` at its own t = u - floor(u) (clamped into (0, n))."""

def fit_sketch(points: _Points, tolerance: Optional[float] = None) -> Sketch: ...

@final
class Corner:
    index: int
    point: tuple[float, float]
    angle_degrees: float
    run: int

@final
class SmoothJoin:
    run: int
    point: tuple[float, float]
    angle_degrees: float
    curvature_jump: float

@final
class Seam:
    angle_degrees: float
    curvature_jump: float

@final
class SketchContour(_Exportable):
    nurbs: Nurbs
    pieces: list[RationalBezier]
    runs: list[str]
    run_pieces: list[int]
    alphas: list[list[float]]
    corners: list[Corner]
    smooth_joins: list[SmoothJoin]
    closed: bool
    seam: Optional[Seam]
    tolerance: float
    max_deviation: float
    trimmed: int
    g2: bool
    all_monotone: bool
    def domain(self) -> Tuple[float, float]: ...
    def at(self, u: _Params) -> CurveAt:
        """Piece ``floor(u)`` at its own t = u - floor(u) (clamped into (0, n))."""

def fit_contour(
    points: _Points,
    tolerance: Optional[float] = None,
    closed: Optional[bool] = None,
    corner_angle: float = 35.0,
    resolution: Optional[float] = None,
) -> SketchContour: ...
def check_outline(
    contours: Any,
    grid: float = 0.0,
    g1_angle: float = 0.05,
    g2_jump: float = 0.05,
    near_break: float = 3.0,
    min_bump: float = 0.05,
) -> dict[str, Any]: ...
def index_contour(
    points: Sequence[tuple[float, float, Optional[str], bool]],
) -> tuple[Any, ...]: ...
def harmonize(
    segments: Any,
    closed: bool,
    smooth: Sequence[bool],
    tolerance: float = 2.0,
    grid: float = 0.0,
    bumps: bool = True,
) -> dict[str, Any]: ...
def plot_comb(curve: Any, ax: Any = None, samples: int = 200, scale: Optional[float] = None, **line_kwargs: Any) -> Any: ...
