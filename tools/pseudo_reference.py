#!/usr/bin/env python3
"""Independent reference for the pseudo-elastic spline through n equally spaced points on the
unit circle (S2 Tables 4 and 5), with mpmath at 40 digits.

By symmetry every tangent is the circle's tangent, so each span is the unit-chord segment with
end angles (-pi/n, pi/n), scaled by the chord 2 sin(pi/n). Its tangent lengths minimise
J = E L^2; the symmetric minimum r0 = r1 = r is found by solving dJ/dr = 0 (mpmath findroot,
tanh-sinh quadrature), and the Hessian in (r0, r1) is checked to be positive definite there.
Prints n, length, area, r, J. Used by crates/aesthetic-curves/tests/pseudo_spline_reference.rs.
"""
from mpmath import mp, mpf, quad, cos, sin, sqrt, pi, findroot, diff

mp.dps = 40


def seg(t0, t1, r0, r1):
    c0, s0, c1, s1 = r0 * cos(t0), r0 * sin(t0), r1 * cos(t1), r1 * sin(t1)

    def d(t):
        b1, c1_, d1 = 6 * t - 6 * t * t, 3 * t * t - 4 * t + 1, 3 * t * t - 2 * t
        b2, c2, d2 = 6 - 12 * t, 6 * t - 4, 6 * t - 2
        x1 = b1 + c1_ * c0 + d1 * c1
        y1 = c1_ * s0 + d1 * s1
        x2 = b2 + c2 * c0 + d2 * c1
        y2 = c2 * s0 + d2 * s1
        return x1, y1, x2, y2

    def pos_y(t):
        return (t**3 - 2 * t * t + t) * s0 + (t**3 - t * t) * s1

    def e_int(t):
        x1, y1, x2, y2 = d(t)
        return (x1 * y2 - y1 * x2) ** 2 / (x1 * x1 + y1 * y1) ** mpf(2.5)

    def l_int(t):
        x1, y1, _, _ = d(t)
        return sqrt(x1 * x1 + y1 * y1)

    def s_int(t):
        x1, _, _, _ = d(t)
        return pos_y(t) * x1

    return quad(e_int, [0, 0.5, 1]), quad(l_int, [0, 0.5, 1]), quad(s_int, [0, 1])


def main():
    for n in range(3, 11):
        th = pi / n
        J = lambda r0, r1: (lambda e: e[0] * e[1] ** 2)(seg(-th, th, r0, r1))
        r = findroot(lambda r: diff(lambda x: J(x, x), r), mpf(1))
        h00 = diff(J, (r, r), (2, 0))
        h01 = diff(J, (r, r), (1, 1))
        assert h00 > 0 and h00 * h00 - h01 * h01 > 0, "not a minimum"
        e, l, s = seg(-th, th, r, r)
        chord = 2 * sin(th)
        length = n * chord * l
        # The spans bulge outside the polygon: area = polygon + n chord^2 |S|.
        area = n * sin(2 * th) / 2 + n * chord**2 * abs(s)
        print(n, mp.nstr(length, 15), mp.nstr(area, 15), mp.nstr(r, 15), mp.nstr(e * l * l, 15))


if __name__ == "__main__":
    main()
