#!/usr/bin/env python3
"""Every curved segment of real fonts: aecurve's verdict against an independent exact oracle.

    python3 tools/font_oracle.py AECURVE FONT...

Segments are read with fontTools (not the reader aecurve uses), sent to `aecurve batch` as
`bezier.curvature_monotone` requests (the polynomial path, and the same points with unit
weights: the rational path), and decided again here in exact integer arithmetic, in the
power basis, from the textbook numerator of dκ/ds,
`det(x',x''') |x'|² - 3 det(x',x'') (x'·x'')`: its sign changes in (0, 1) (roots of odd
multiplicity) by a Sturm sequence on its square-free part and exact bisection; degenerate
when |x'|² has a root in (0, 1). Exits 1 on any disagreement (verdict, degenerate or not,
number of extrema, an extremum more than 1e-9 away), and prints one line per font.
"""
import json
import multiprocessing
import subprocess
import sys
import threading
from fractions import Fraction
from math import comb, gcd

from fontTools.pens.basePen import BasePen
from fontTools.ttLib import TTFont


class Segments(BasePen):
    def __init__(self, glyphset):
        super().__init__(glyphset)
        self.segs = []
        self.cur = None

    def _moveTo(self, p):
        self.cur = p

    def _lineTo(self, p):
        self.cur = p

    def _qCurveToOne(self, p1, p2):
        self.segs.append([self.cur, p1, p2])
        self.cur = p2

    def _curveToOne(self, p1, p2, p3):
        self.segs.append([self.cur, p1, p2, p3])
        self.cur = p3

    def _closePath(self):
        pass

    def _endPath(self):
        pass


# Integer polynomials in t, lowest power first.
def trim(p):
    p = list(p)
    while p and p[-1] == 0:
        p.pop()
    return p


def add(a, b):
    n = max(len(a), len(b))
    return trim([(a[i] if i < len(a) else 0) + (b[i] if i < len(b) else 0) for i in range(n)])


def mul(a, b):
    if not a or not b:
        return []
    out = [0] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        for j, y in enumerate(b):
            out[i + j] += x * y
    return trim(out)


def scale(a, k):
    return trim([k * x for x in a])


def deriv(a):
    return trim([i * a[i] for i in range(1, len(a))])


def bernstein_to_power(c):
    n = len(c) - 1
    out = [0] * (n + 1)
    for i, ci in enumerate(c):
        # C(n,i) t^i (1-t)^(n-i) = C(n,i) sum_k C(n-i,k) (-1)^k t^(i+k)
        for k in range(n - i + 1):
            out[i + k] += ci * comb(n, i) * comb(n - i, k) * (-1) ** k
    return trim(out)


def sign(v):
    return (v > 0) - (v < 0)


def sign_at(p, x):
    """The sign of the integer polynomial p at the Fraction x = n/d (d > 0), in integers:
    p(x) d^deg = sum c_k n^k d^(deg-k) (Horner in n, powers of d alongside)."""
    if not p:
        return 0
    n, d = x.numerator, x.denominator
    acc = p[-1]
    dk = 1
    for c in reversed(p[:-1]):
        dk *= d
        acc = acc * n + c * dk
    return sign(acc)


def polydivmod(a, b):
    a = [Fraction(x) for x in a]
    q = [Fraction(0)] * max(len(a) - len(b) + 1, 1)
    while len(a) >= len(b) and a:
        c = a[-1] / b[-1]
        k = len(a) - len(b)
        q[k] = c
        for i, y in enumerate(b):
            a[i + k] -= c * y
        a = trim(a)
    return trim(q), a


def primitive(p):
    den = 1
    for x in p:
        den = den * Fraction(x).denominator // gcd(den, Fraction(x).denominator)
    ints = [int(Fraction(x) * den) for x in p]
    g = 0
    for x in ints:
        g = gcd(g, x)
    return [x // g for x in ints] if g else ints


def poly_gcd(a, b):
    while b:
        _, r = polydivmod(a, b)
        a, b = b, primitive(r) if r else []
    return primitive(a)


def sturm_chain(p):
    chain = [p, deriv(p)]
    while chain[-1] and len(chain[-1]) > 1:
        _, r = polydivmod(chain[-2], chain[-1])
        if not r:
            break
        # Scaled to integers by a positive factor: still a Sturm sequence.
        chain.append(primitive([-x for x in r]))
    return chain


def variations(chain, x):
    signs = [sign_at(p, x) for p in chain]
    signs = [s for s in signs if s]
    return sum(1 for a, b in zip(signs, signs[1:]) if a != b)


def roots_in_unit(p):
    """Distinct roots of p in the open (0, 1) with the sign of p on each side, isolated."""
    p = trim(p)
    while p and p[0] == 0:  # roots at t = 0
        p = p[1:]
    while p and sum(p) == 0:  # roots at t = 1: divide by (t - 1)
        p, _ = polydivmod(p, [-1, 1])
        p = primitive(p)
    if len(p) <= 1:
        return p, []
    g = poly_gcd(p, deriv(p))
    s = primitive(polydivmod(p, g)[0]) if len(g) > 1 else p
    chain = sturm_chain(s)
    out = []
    stack = [(Fraction(0), Fraction(1))]
    while stack:
        a, b = stack.pop()
        n = variations(chain, a) - variations(chain, b)
        if n == 0:
            continue
        if n == 1:
            out.append((a, b))
            continue
        m = (a + b) / 2
        k = 3
        while sign_at(s, m) == 0:
            m = a + (b - a) * Fraction(2 ** (k - 1) + 1, 2 ** k)
            k += 1
        stack += [(a, m), (m, b)]
    return p, out


def oracle(points):
    """('degenerate', None) or ('ok', [sign-change t...])."""
    xs = [Fraction(p[0]) for p in points]
    ys = [Fraction(p[1]) for p in points]
    den = 1
    for v in xs + ys:
        den = den * v.denominator // gcd(den, v.denominator)
    x = bernstein_to_power([int(v * den) for v in xs])
    y = bernstein_to_power([int(v * den) for v in ys])
    x1, y1 = deriv(x), deriv(y)
    x2, y2 = deriv(x1), deriv(y1)
    x3, y3 = deriv(x2), deriv(y2)
    speed2 = add(mul(x1, x1), mul(y1, y1))
    if not speed2:
        return "degenerate", None
    _, sr = roots_in_unit(speed2)
    if sr:
        return "degenerate", None
    cross13 = add(mul(x1, y3), scale(mul(y1, x3), -1))
    cross12 = add(mul(x1, y2), scale(mul(y1, x2), -1))
    dot12 = add(mul(x1, x2), mul(y1, y2))
    k = add(mul(cross13, speed2), scale(mul(cross12, dot12), -3))
    if not k:
        return "ok", []
    p, intervals = roots_in_unit(k)
    changes = []
    for a, b in intervals:
        if sign_at(p, a) != sign_at(p, b):
            # refine by bisection on the square-free part's sign (p changes sign here)
            sa = sign_at(p, a)
            for _ in range(40):
                m = (a + b) / 2
                sm = sign_at(p, m)
                if sm == 0:
                    a = b = m
                    break
                if sm == sa:
                    a = m
                else:
                    b = m
            changes.append(float((a + b) / 2))
    return "ok", sorted(changes)


def font_segments(path):
    font = TTFont(path, lazy=True)
    gs = font.getGlyphSet()
    segs = []
    for name in font.getGlyphOrder():
        pen = Segments(gs)
        try:
            gs[name].draw(pen)
        except Exception as e:  # noqa: BLE001 - a glyph fontTools cannot draw is skipped, said
            print(f"  {path}: glyph {name}: fontTools could not draw it: {e}")
            continue
        for s in pen.segs:
            # Only curved segments (three or more points not all on a line are left to the test).
            segs.append((name, [[float(p[0]), float(p[1])] for p in s]))
    return segs


def main():
    aecurve, fonts = sys.argv[1], sys.argv[2:]
    bad = 0
    for path in fonts:
        segs = font_segments(path)
        lines = []
        for i, (_, pts) in enumerate(segs):
            lines.append(json.dumps({"id": 2 * i, "op": "bezier.curvature_monotone", "control_points": pts}))
            lines.append(json.dumps({"id": 2 * i + 1, "op": "bezier.curvature_monotone", "control_points": pts,
                                     "weights": [1.0] * len(pts)}))
        # aecurve answers while the oracle decides the same segments in worker processes
        # (one per core: exact arithmetic in Python is the slow half).
        batch = subprocess.Popen([aecurve, "batch"], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
        sent = []
        feeder = threading.Thread(target=lambda: sent.append(batch.communicate("\n".join(lines) + "\n")[0]))
        feeder.start()
        with multiprocessing.Pool() as pool:
            verdicts = pool.map(oracle, [pts for _, pts in segs], chunksize=256)
        feeder.join()
        if batch.returncode != 0:
            print(f"font oracle: aecurve batch exited with {batch.returncode}")
            sys.exit(1)
        out = sent[0].splitlines()
        answers = {}
        for line in out:
            r = json.loads(line)
            answers[r["id"]] = r
        wrong = 0
        exact = 0
        nonmono = 0
        for i, ((name, pts), (kind, changes)) in enumerate(zip(segs, verdicts)):
            if kind == "ok" and changes:
                nonmono += 1
            for rid in (2 * i, 2 * i + 1):
                r = answers.get(rid)
                ok = r is not None
                if ok and kind == "degenerate":
                    ok = r.get("error", {}).get("kind") == "degenerate"
                elif ok:
                    res = r.get("result")
                    ok = res is not None and res["monotone"] == (not changes) and len(res["extrema"]) == len(changes) \
                        and all(abs(a - b) <= 1e-9 for a, b in zip(res["extrema"], changes))
                    if res is not None and res.get("exact_arithmetic"):
                        exact += 1
                if not ok:
                    wrong += 1
                    if wrong <= 10:
                        print(f"  WRONG {path} {name} {pts} ({'rational' if rid % 2 else 'polynomial'} path): "
                              f"oracle {kind} {changes}, aecurve {r}")
        print(f"{path}: {len(segs)} curved segments ({nonmono} not monotone), {2 * len(segs)} verdicts, "
              f"{wrong} wrong, {exact} decided in exact arithmetic")
        bad += wrong
    if bad:
        print(f"font oracle: {bad} wrong verdicts")
        sys.exit(1)


if __name__ == "__main__":
    main()
