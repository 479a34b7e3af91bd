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
    ac.LacSpline: (
        "LacSplineResultDrawn",
        {**DRAWING,
            "segments": "one list per field of a segment: pieces, kinds, spans, alphas"},
    ),
    ac.LacFit: ("LacFitResult", {}),
    ac.Sketch: (
        "SketchResultDrawn",
        {
            **DRAWING,
            "segments": "one list per field of a segment: pieces, alphas",
            "bspline": "not exposed (an intermediate of the fit)",
            "fairing": "converged (its iterations and jumps are not exposed)",
        },
    ),
    ac.SketchContour: (
        "ContourResultDrawn",
        DRAWING,
    ),
}

# Same name, another shape: Python holds objects or tuples where the JSON holds records.
SHAPES_DIFFER = {
    ("SketchContour", "runs"): "Python: the runs' kinds; JSON: the runs as records",
    ("SketchContour", "corners"): "Python: (x, y, degrees, index) tuples; JSON: records",
    ("SketchContour", "smooth_joins"): "Python: tuples; JSON: records",
    ("SketchContour", "pieces"): "Python: the cubics; JSON: their count",
    ("LacFit", "control"): "an array",
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
