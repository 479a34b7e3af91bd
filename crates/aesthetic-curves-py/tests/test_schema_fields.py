"""Python's result classes against the protocol's schema (`aecurve schema`): every field of
an op's response is an attribute of the matching class under the same name, or is listed
below with where Python keeps it and why. A field added to the protocol and not to Python
(or the reverse rename) fails here.
"""

import json
import subprocess

import pytest

import aesthetic_curves as ac
from test_aesthetic_curves import AECURVE, needs_aecurve

# Every op's optional picture: Python draws from the curve itself.
DRAWING = {"drawing": "the protocol's picture: sample(n) or at(u) on the curve"}

# class -> (the schema's definition, {field: where Python keeps it instead})
PAIRS = {
    ac.MonotoneReport: ("MonotoneResult", {}),
    ac.EndCurvature: ("EndCurvatureJson", {}),
    ac.RationalCubicFit: (
        "RationalApproxResultDrawn",
        {
            **DRAWING,
            "arc_length": "the segment's: LacSegment.arc_length()",
            "spline": "LacSegment.rational_spline(tolerance), its own class",
        },
    ),
    ac.RationalSpline: (
        "RationalSplineJson",
        {
            "degree": "nurbs.degree",
            "knots": "nurbs.knots",
            "control_points": "nurbs.control_points",
            "weights": "nurbs.weights",
            "monotone": "each of pieces: pieces[i].monotone",
        },
    ),
    ac.PseudoSpline: (
        "PseudoSplineResultDrawn",
        {
            **DRAWING,
            "segments": "beziers(): the G1 cubics themselves, not their ends and tangents",
            "mode": "the argument of pseudo_elastic",
        },
    ),
    ac.LacSpline: ("LacSplineResultDrawn", DRAWING),
    ac.SplineSegment: ("SplinePieceJson", {}),
    ac.LacFit: ("LacFitResult", {}),
    ac.Sketch: ("SketchResultDrawn", DRAWING),
    ac.SketchSegment: ("SketchPieceJson", {}),
    ac.FairingReport: ("FairingJson", {}),
    ac.BSpline: ("BSplineJson", {}),
    ac.SketchContour: (
        "ContourResultDrawn",
        DRAWING,
    ),
    ac.Corner: ("CornerJson", {}),
    ac.SmoothJoin: ("SmoothJoinJson", {}),
    ac.Seam: ("SeamJson", {}),
}

# Same name, another shape: Python holds objects or tuples where the JSON holds records.
SHAPES_DIFFER = {
    ("SketchContour", "runs"): "Python: the runs' kinds; JSON: the runs as records",
    ("Corner", "point"): "a tuple",
    ("SmoothJoin", "point"): "a tuple",
    ("SketchContour", "pieces"): "Python: the cubics; JSON: their count",
    ("LacFit", "control"): "an array",
    ("SketchSegment", "control"): "an array",
    ("SketchSegment", "rational"): "a RationalBezier",
    ("SketchSegment", "end_curvatures"): "a tuple",
    ("SplineSegment", "control"): "an array",
    ("SplineSegment", "rational"): "a RationalBezier",
    ("SplineSegment", "end_curvatures"): "a tuple",
    ("BSpline", "control_points"): "an array",
}


@pytest.fixture(scope="module")
def schema():
    out = subprocess.run([AECURVE, "schema"], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def properties(schema, name):
    """The property names of a definition, through flattened parts (allOf) too."""
    d = schema["$defs"][name]
    names = set(d.get("properties", {}))
    for part in d.get("allOf", []):
        ref = part.get("$ref", "")
        if ref:
            names |= properties(schema, ref.rsplit("/", 1)[1])
        names |= set(part.get("properties", {}))
    return names


@needs_aecurve
@pytest.mark.parametrize("cls", list(PAIRS), ids=lambda c: c.__name__)
def test_python_fields_are_the_schema_fields(schema, cls):
    name, elsewhere = PAIRS[cls]
    fields = properties(schema, name)
    assert fields, f"{name} has no properties in the schema"
    python = {a for a in dir(cls) if not a.startswith("_")}
    missing = sorted(f for f in fields - python if f not in elsewhere)
    assert not missing, f"{cls.__name__} lacks the protocol's {missing}"
    stale = sorted(f for f in elsewhere if f in python or f not in fields)
    assert not stale, f"{cls.__name__}: listed as elsewhere, yet {stale}"


@needs_aecurve
def test_the_listed_shape_differences_are_real_fields(schema):
    for (cls, field) in SHAPES_DIFFER:
        name = PAIRS[getattr(ac, cls)][0]
        assert field in properties(schema, name), (cls, field)
        assert hasattr(getattr(ac, cls), field), (cls, field)


@needs_aecurve
def test_segments_hold_the_protocols_values(tmp_path):
    """The same stroke and the same points through Python and through `aecurve --json`
    (the protocol's types, printed to 10 digits): the segments' fields agree to 1e-8."""
    import math

    seed = [12345]

    def jitter():
        seed[0] = (seed[0] * 6364136223846793005 + 1442695040888963407) % 2**64
        return (seed[0] >> 11) / 2**53 * 1.4 - 0.7

    stroke = [(60 * math.cos(0.03 * i) + jitter(), 40 * math.sin(0.05 * i) + jitter())
              for i in range(120)]
    path = tmp_path / "stroke.csv"
    path.write_text("\n".join(f"{x!r},{y!r}" for x, y in stroke))
    out = subprocess.run([AECURVE, "sketch", str(path), "--json"], capture_output=True,
                         text=True, check=True)
    want = json.loads(out.stdout)
    got = ac.fit_sketch(stroke)
    assert got.tolerance == pytest.approx(want["tolerance"], rel=1e-12)
    assert len(got.segments) == len(want["segments"])
    for g, w in zip(got.segments, want["segments"]):
        assert g.kind == w["kind"]
        assert g.alpha == pytest.approx(w["alpha"], rel=1e-8, abs=1e-12)
        assert g.alpha_at_bound == w["alpha_at_bound"]
        flat = [v for q in w["control"] for v in q]
        assert g.control.ravel().tolist() == pytest.approx(flat, rel=1e-8, abs=1e-9)
        assert list(g.end_curvatures) == pytest.approx(w["end_curvatures"], rel=1e-8)
        assert g.rational.weights.tolist() == pytest.approx(w["rational"]["weights"], rel=1e-8)
    assert got.fairing.iterations == want["fairing"]["iterations"]
    assert got.bspline.degree == want["bspline"]["degree"]

    points = [(0, 0), (2, 1.5), (4, 1), (6, 3), (8, 2.5), (10, 4)]
    ppath = tmp_path / "points.csv"
    ppath.write_text("\n".join(f"{x},{y}" for x, y in points))
    out = subprocess.run([AECURVE, "spline", str(ppath), "--json"], capture_output=True,
                         text=True, check=True)
    want = json.loads(out.stdout)
    got = ac.lac_spline(points)
    assert [s.kind for s in got.segments] == [w["kind"] for w in want["segments"]]
    assert [s.span for s in got.segments] == [w["span"] for w in want["segments"]]
    for g, w in zip(got.segments, want["segments"]):
        assert list(g.end_curvatures) == pytest.approx(w["end_curvatures"], rel=1e-8, abs=1e-12)
