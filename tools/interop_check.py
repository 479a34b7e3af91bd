#!/usr/bin/env python3
"""Interop check of aecurve's CAD exports with real readers.

Usage: interop_check.py DIR
DIR holds c.json (the exact NURBS: degree, knots, control_points, weights) and the exports
c.dxf, c.step, c.iges, c.svg of the same curve. Each CAD file is read back by a real reader
(ezdxf for DXF, OpenCASCADE via the cadquery-ocp-novtk wheel for STEP and IGES) and evaluated
at 101 parameters; the points must match this script's own de Boor evaluation of c.json to
1e-9 of the curve's size. The SVG path (cubic Béziers) must lie within 1e-4 of the size of
the curve. Exits non-zero on any failure."""
import json
import math
import re
import sys


def de_boor(c, u):
    p, k, P, W = c["degree"], c["knots"], c["control_points"], c["weights"]
    n = len(P)
    u = min(max(u, k[p]), k[n])
    s = p
    while s + 1 < n and k[s + 1] <= u:
        s += 1
    d = [[P[s - p + j][0] * W[s - p + j], P[s - p + j][1] * W[s - p + j], W[s - p + j]] for j in range(p + 1)]
    for r in range(1, p + 1):
        for j in range(p, r - 1, -1):
            i = s + j - p
            den = k[i + p + 1 - r] - k[i]
            a = (u - k[i]) / den if den > 0 else 0.0
            d[j] = [(1 - a) * d[j - 1][t] + a * d[j][t] for t in range(3)]
    return (d[p][0] / d[p][2], d[p][1] / d[p][2])


def check(name, got, want, size, tol):
    err = max(math.hypot(g[0] - w[0], g[1] - w[1]) for g, w in zip(got, want))
    ok = err <= tol * size
    print(f"{name}: max deviation {err:.3e} ({err / size:.3e} of the size) {'ok' if ok else 'FAIL'}")
    return ok


def main(d):
    c = json.load(open(f"{d}/c.json"))
    k = c["knots"]
    u0, u1 = k[0], k[-1]
    params = [u0 + (u1 - u0) * i / 100 for i in range(101)]
    want = [de_boor(c, u) for u in params]
    xs = [p[0] for p in c["control_points"]]
    ys = [p[1] for p in c["control_points"]]
    size = math.hypot(max(xs) - min(xs), max(ys) - min(ys))
    ok = True

    import ezdxf
    doc = ezdxf.readfile(f"{d}/c.dxf")
    splines = doc.modelspace().query("SPLINE")
    assert len(splines) == 1, "one SPLINE entity expected"
    sp = splines[0]
    assert sp.dxf.degree == c["degree"]
    assert len(sp.weights) == len(c["weights"]), "weights lost"
    bs = sp.construction_tool()
    got = [tuple(bs.point(u))[:2] for u in params]
    ok &= check("DXF (ezdxf)", got, want, size, 1e-9)

    from OCP.BRepAdaptor import BRepAdaptor_Curve
    from OCP.GeomAbs import GeomAbs_BSplineCurve
    from OCP.IFSelect import IFSelect_RetDone
    from OCP.IGESControl import IGESControl_Reader
    from OCP.STEPControl import STEPControl_Reader
    from OCP.TopAbs import TopAbs_EDGE
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopoDS import TopoDS

    for label, reader, path in [("STEP (OpenCASCADE)", STEPControl_Reader(), f"{d}/c.step"),
                                ("IGES (OpenCASCADE)", IGESControl_Reader(), f"{d}/c.iges")]:
        status = reader.ReadFile(path)
        assert status == IFSelect_RetDone, f"{label}: read status {status}"
        reader.TransferRoots()
        shape = reader.OneShape()
        # A reader may split the C0 joints of a piecewise spline into several edges, each
        # keeping its part of the parameter range: evaluate each u on the edge holding it.
        exp = TopExp_Explorer(shape, TopAbs_EDGE)
        edges = []
        while exp.More():
            edge = TopoDS.Edge(exp.Current()) if hasattr(TopoDS, "Edge") else TopoDS.Edge_s(exp.Current())
            ad = BRepAdaptor_Curve(edge)
            assert ad.GetType() == GeomAbs_BSplineCurve, f"{label}: not a B-spline ({ad.GetType()})"
            b = ad.BSpline()
            assert b.Degree() == c["degree"], f"{label}: degree {b.Degree()}"
            assert b.IsRational() or len(set(c["weights"])) == 1, f"{label}: weights lost"
            edges.append((ad.FirstParameter(), ad.LastParameter(), ad))
            exp.Next()
        assert edges, f"{label}: no edge"
        lo = min(e[0] for e in edges)
        hi = max(e[1] for e in edges)
        assert abs(lo - u0) < 1e-12 and abs(hi - u1) < 1e-12, f"{label}: domain {lo}, {hi}"
        got = []
        for u in params:
            ad = next(e[2] for e in edges if e[0] - 1e-12 <= u <= e[1] + 1e-12)
            p = ad.Value(u)
            got.append((p.X(), p.Y()))
        print(f"{label}: {len(edges)} edge(s)")
        ok &= check(label, got, want, size, 1e-9)

    # SVG: every point of the path within 1e-4 of the size of the curve.
    svg = open(f"{d}/c.svg").read()
    path = re.search(r'<path id="curve" d="([^"]+)"', svg).group(1)
    nums = [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?", path)]
    start, rest = nums[:2], nums[2:]
    m = 4000
    us = [u0 + (u1 - u0) * i / m for i in range(m + 1)]
    dense = [de_boor(c, u) for u in us]

    def distance(q):
        # Nearest sample, then golden-section search for the foot of the perpendicular.
        i = min(range(m + 1), key=lambda j: (q[0] - dense[j][0]) ** 2 + (q[1] - dense[j][1]) ** 2)
        a, b = us[max(i - 1, 0)], us[min(i + 1, m)]
        f = lambda u: math.hypot(q[0] - de_boor(c, u)[0], q[1] - de_boor(c, u)[1])
        r = (math.sqrt(5) - 1) / 2
        x1, x2 = b - r * (b - a), a + r * (b - a)
        for _ in range(60):
            if f(x1) < f(x2):
                b, x2 = x2, x1
                x1 = b - r * (b - a)
            else:
                a, x1 = x1, x2
                x2 = a + r * (b - a)
        return f(0.5 * (a + b))

    worst = 0.0
    cur = start
    for i in range(0, len(rest), 6):
        p1, p2, p3 = rest[i:i + 2], rest[i + 2:i + 4], rest[i + 4:i + 6]
        for j in range(11):
            t = j / 10
            s = 1 - t
            q = [s ** 3 * cur[a] + 3 * t * s * s * p1[a] + 3 * t * t * s * p2[a] + t ** 3 * p3[a] for a in range(2)]
            worst = max(worst, distance(q))
        cur = p3
    svg_ok = worst <= 1e-4 * size
    print(f"SVG path: max distance {worst:.3e} ({worst / size:.3e} of the size) {'ok' if svg_ok else 'FAIL'}")
    ok &= svg_ok
    return ok


if __name__ == "__main__":
    sys.exit(0 if main(sys.argv[1]) else 1)
