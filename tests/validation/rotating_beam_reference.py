#!/usr/bin/python3
"""Reference frequencies of a rotating uniform Euler-Bernoulli cantilever (1-D, independent of
flexmbs), for tests/validation/rotating_cantilever_test.cc.

A beam of length L clamped at the hub axis (zero hub radius) spins at Omega about an axis
perpendicular to it. Its centrifugal tension is T(x) = rho A Omega^2 (L^2 - x^2) / 2, and small
vibrations about the straight beam obey (e.g. Wright, Smith, Thresher & Wang, "Vibration modes
of centrifugally stiffened beams", J. Appl. Mech. 49, 1982):

  flapping (out of the plane of rotation):  EI w'''' - (T w')' + rho A w_tt = 0
  lead-lag (in the plane of rotation):      EI v'''' - (T v')' - rho A Omega^2 v + rho A v_tt = 0

Both are solved by finite elements with cubic Hermite shape functions (exact for the beam
without rotation, converging as h^4 in the eigenvalues), with EI = rho A = L = 1 (the ratios
below do not depend on them), Gauss-Legendre quadrature exact for the quadratic tension.

Usage: rotating_beam_reference.py s1 s2 ...   (s = Omega / omega0 of the mode itself)
Prints JSON: {"s": [...], "flap": [omega/omega0 ...], "lag": [omega/omega0 ...],
              "southwell_flap": d(omega^2)/d(Omega^2) at Omega = 0 for the first flapping mode}.
"""
import json
import sys

import numpy as np
import scipy.linalg

ELEMENTS = 100  # eigenvalue ratios converged to ~1e-8 (checked against 50 elements)


def assemble(num_elements):
    """Stiffness EI int w''^2, mass rho A int w^2 and unit-spin tension int T w'^2 (Omega = 1),
    clamped at x = 0 (DOF w, w' per node; the first node's removed)."""
    h = 1.0 / num_elements
    n = 2 * (num_elements + 1)
    K, M, KT = (np.zeros((n, n)) for _ in range(3))
    points, weights = np.polynomial.legendre.leggauss(6)
    for e in range(num_elements):
        Ke, Me, Te = (np.zeros((4, 4)) for _ in range(3))
        for p, w in zip(points, weights):
            s = 0.5 * (p + 1.0)
            x = (e + s) * h
            dx = 0.5 * w * h
            N = np.array([1 - 3 * s**2 + 2 * s**3, h * (s - 2 * s**2 + s**3), 3 * s**2 - 2 * s**3,
                          h * (s**3 - s**2)])
            dN = np.array([6 * s**2 - 6 * s, h * (1 - 4 * s + 3 * s**2), 6 * s - 6 * s**2,
                           h * (3 * s**2 - 2 * s)]) / h
            d2N = np.array([12 * s - 6, h * (6 * s - 4), 6 - 12 * s, h * (6 * s - 2)]) / h**2
            tension = 0.5 * (1.0 - x * x)
            Ke += dx * np.outer(d2N, d2N)
            Me += dx * np.outer(N, N)
            Te += dx * tension * np.outer(dN, dN)
        dofs = np.arange(2 * e, 2 * e + 4)
        for A, Ae in ((K, Ke), (M, Me), (KT, Te)):
            A[np.ix_(dofs, dofs)] += Ae
    free = slice(2, n)
    return K[free, free], M[free, free], KT[free, free]


def lowest(A, M):
    return scipy.linalg.eigh(A, M, eigvals_only=True, subset_by_index=[0, 0])[0]


def main():
    ratios = [float(a) for a in sys.argv[1:]]
    K, M, KT = assemble(ELEMENTS)
    lambda0 = lowest(K, M)
    flap, lag = [], []
    for s in ratios:
        spin2 = s * s * lambda0
        flap.append(float(np.sqrt(lowest(K + spin2 * KT, M) / lambda0)))
        lag.append(float(np.sqrt(lowest(K + spin2 * (KT - M), M) / lambda0)))
    # Southwell coefficient: first-order perturbation, phi^T KT phi / phi^T M phi.
    _, vectors = scipy.linalg.eigh(K, M, subset_by_index=[0, 0])
    phi = vectors[:, 0]
    southwell = float(phi @ KT @ phi / (phi @ M @ phi))
    print(json.dumps({"s": ratios, "flap": flap, "lag": lag, "southwell_flap": southwell}))


if __name__ == "__main__":
    main()
