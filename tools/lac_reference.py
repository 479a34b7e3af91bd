#!/usr/bin/env python3
"""Reference values of the standard-form log-aesthetic curve, P(theta) = integral_0^theta
rho(psi) e^{i psi} d psi, rho = ((alpha-1) Lambda psi + 1)^(1/(alpha-1)), computed with mpmath
at 40 significant digits (tanh-sinh quadrature, split every quarter turn). Independent of the
library: different variable (psi, not log u), different quadrature, extended precision.

Usage: python3 tools/lac_reference.py > crates/aesthetic-curves/tests/data/lac_reference.csv
(needs `pip install mpmath`)."""
import mpmath as mp

mp.mp.dps = 40


def point(alpha, lam, theta):
    a, l, t = mp.mpf(alpha), mp.mpf(lam), mp.mpf(theta)
    if a == 1:
        rho = lambda p: mp.e ** (l * p)
    else:
        rho = lambda p: ((a - 1) * l * p + 1) ** (1 / (a - 1))
    f = lambda p: rho(p) * mp.expjpi(p / mp.pi)
    n = max(2, int(abs(theta) / (mp.pi / 4)) + 2)
    pts = mp.linspace(0, t, n)
    return mp.quad(f, pts)


def cases():
    for alpha in [-20, -5, -1, -0.5, -0.01, 0, 0.3, 0.9, 0.999, 1, 1.001, 1.5, 2, 3, 7, 20]:
        for lam in [0.05, 0.5, 2.0]:
            c = (alpha - 1) * lam
            thetas = []
            if c < 0:
                tmax = -1 / c
                thetas += [min(0.3 * tmax, 25.0), min(0.9 * tmax, 25.0), -2.0]
                if alpha < 0 and tmax < 25:
                    thetas += [tmax * (1 - 1e-6)]
                elif tmax < 25:
                    thetas += [tmax * (1 - 1e-3)]
            elif c > 0:
                tmin = -1 / c
                thetas += [0.5, 3.0, 12.0]
                if tmin > -25:
                    thetas += [tmin * 0.5, tmin * (1 - 1e-6)]
                else:
                    thetas += [-25.0]
            else:
                thetas += [0.5, 3.0, 12.0, -2.0]
            for t in thetas:
                yield alpha, lam, t


print("alpha,lambda,theta,x,y")
for a, l, t in cases():
    p = point(a, l, t)
    print(f"{a!r},{l!r},{t!r},{mp.nstr(p.real, 25)},{mp.nstr(p.imag, 25)}")
