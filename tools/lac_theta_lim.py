#!/usr/bin/env python3
"""Reference values of theta_lim(alpha, theta_d) (docs/math.md §3.1): the base angle at the
high-curvature end of the limiting segment Lambda = Lambda_max = 1/(|alpha-1| theta_d),
computed with mpmath at 40 digits (tanh-sinh quadrature, which handles the singular end of
the domain). alpha < 0: interval [0, theta_d], end rho -> infinity; alpha > 1: interval
[-theta_d, 0], start rho -> 0.

Usage: python3 tools/lac_theta_lim.py > crates/aesthetic-curves/tests/data/lac_theta_lim.csv"""
import mpmath as mp

mp.mp.dps = 40


def theta_lim(alpha, theta_d):
    """The chord integral_{ta}^{tb} rho e^{i psi} d psi, written in v = u^{p1} with
    u = 1 + c psi, p1 = alpha/(alpha-1) > 0: rho d psi = u^(p1-1) du / c = dv / (c p1), so the
    integrand e^{i (v^(1/p1) - 1)/c} / (c p1) is bounded at the singular end v = 0."""
    a, td = mp.mpf(alpha), mp.mpf(theta_d)
    lam = 1 / (abs(a - 1) * td)
    c = (a - 1) * lam
    p1 = a / (a - 1)
    ta, tb = (mp.mpf(0), td) if a <= 1 else (-td, mp.mpf(0))
    # The regular end has u = 1 (psi = 0), v = 1; the singular end u = 0 exactly.
    va, vb = (mp.mpf(1), mp.mpf(0)) if a <= 1 else (mp.mpf(0), mp.mpf(1))
    f = lambda v: mp.expj((v ** (1 / p1) - 1) / c) / (c * p1)
    chord = mp.quad(f, mp.linspace(va, vb, 6))
    return mp.atan2(chord.imag, chord.real) - ta


print("alpha,theta_d,theta_lim")
for alpha in [-20, -5, -2, -1, -0.5, -0.1, 1.1, 1.5, 2, 3, 5, 20]:
    for theta_d in [0.2, 1.0, mp.pi / 2, 2.5, 3.0]:
        v = theta_lim(alpha, theta_d)
        print(f"{alpha!r},{mp.nstr(mp.mpf(theta_d), 25)},{mp.nstr(v, 25)}")
