#!/usr/bin/python3
"""Reference tip deflection of the spin-up of a rotating cantilever (Kane, Ryan & Banerjee,
"Dynamics of a cantilever beam attached to a moving base", J. Guidance 10(2), 1987), 1-D and
independent of flexmbs, for tests/validation/spin_up_test.cc.

A uniform Euler-Bernoulli beam of length L, clamped at the hub axis (zero hub radius), is
driven about an axis perpendicular to it by the prescribed hub angle

  theta(t) = (Omega_s / T) (t^2 / 2 + (T / (2 pi))^2 (cos(2 pi t / T) - 1))   for t < T,
             Omega_s (t - T / 2)                                               after.

Its deflection v(x, t) in the plane of rotation, measured in the rotating frame, obeys the
linear ("modified linear", first order in v) equation of Kane et al. and Wu & Haug 1988, in
which the centrifugal tension T(x) = rho A theta'^2 (L^2 - x^2) / 2 enters by its geometric
stiffness (axial motion and its Coriolis coupling left out):

  rho A (v_tt - theta'^2 v + x theta'') + EI v'''' - s (T v')' = 0,   v(0) = v'(0) = 0,

s = 1 with the stiffening, s = 0 without it (the "conventional" linear theory, which diverges
once theta' exceeds the first bending frequency). Discretised by cubic Hermite elements
(rotating_beam_reference.assemble: x = L xi, DOF v and dv/dxi per node), divided by rho A L:

  M v'' + (EI / (rho A L^4) K + theta'^2 (s KT - M)) v = -theta'' L F,   F_i = int_0^1 xi N_i dxi,

projected on the lowest MODES bending modes of the non-rotating beam (far more than the
slowly varying load excites) and integrated by SciPy's Radau IIA (order 5) at tight tolerances.

Usage: spin_up_reference.py SPIN_RAD_S STIFFENING(0|1) t1 t2 ...
Prints JSON: {"times": [...], "tip": [v(L, t) in m ...], "elements": n, "modes": n,
              "first_frequency": the non-rotating beam's, rad/s}.
"""
import json
import math
import sys

import numpy as np
import scipy.integrate
import scipy.linalg

from rotating_beam_reference import assemble

LENGTH = 10.0              # m
BENDING_STIFFNESS = 1.4e4  # EI, N m^2
MASS_PER_LENGTH = 1.2      # rho A, kg/m
RAMP_TIME = 15.0           # T, s
# The tip deflection is converged to 1e-6 m (spin 6 rad/s, to 20 s): 80 elements change it by
# 2e-7 m, 20 modes by 9e-7 m, tolerances 1e-8 by 1e-12 m (4 modes: 1.6e-4 m).
ELEMENTS = 40
MODES = 12
RELATIVE_TOLERANCE = 1e-10
ABSOLUTE_TOLERANCE = 1e-12


def hub_rates(spin, t):
    """theta'(t) [rad/s] and theta''(t) [rad/s^2]."""
    if t >= RAMP_TIME:
        return spin, 0.0
    phase = 2.0 * math.pi * t / RAMP_TIME
    return (spin / RAMP_TIME) * (t - RAMP_TIME / (2.0 * math.pi) * math.sin(phase)), \
        (spin / RAMP_TIME) * (1.0 - math.cos(phase))


def load_vector(num_elements):
    """F_i = int_0^1 xi N_i dxi on the clamped DOF of assemble (Gauss-Legendre, exact)."""
    h = 1.0 / num_elements
    F = np.zeros(2 * (num_elements + 1))
    points, weights = np.polynomial.legendre.leggauss(4)
    for e in range(num_elements):
        for p, w in zip(points, weights):
            s = 0.5 * (p + 1.0)
            N = np.array([1 - 3 * s**2 + 2 * s**3, h * (s - 2 * s**2 + s**3), 3 * s**2 - 2 * s**3,
                          h * (s**3 - s**2)])
            F[2 * e:2 * e + 4] += 0.5 * w * h * (e + s) * h * N
    return F[2:]


def main():
    spin = float(sys.argv[1])
    stiffening = float(sys.argv[2])
    times = [float(a) for a in sys.argv[3:]]
    K, M, KT = assemble(ELEMENTS)
    F = load_vector(ELEMENTS)
    c = BENDING_STIFFNESS / (MASS_PER_LENGTH * LENGTH**4)
    # The lowest MODES bending modes of the non-rotating beam (M-orthonormal): v = Phi y.
    squares, Phi = scipy.linalg.eigh(c * K, M, subset_by_index=[0, MODES - 1])
    spin_matrix = Phi.T @ (stiffening * KT - M) @ Phi
    load = LENGTH * (Phi.T @ F)
    tip = Phi[-2]  # v at the free end (the last node's first DOF)

    def stiffness(t):
        rate, _ = hub_rates(spin, t)
        return np.diag(squares) + rate * rate * spin_matrix

    def rhs(t, z):
        _, acceleration = hub_rates(spin, t)
        return np.concatenate([z[MODES:], -stiffness(t) @ z[:MODES] - acceleration * load])

    def jacobian(t, _):
        J = np.zeros((2 * MODES, 2 * MODES))
        J[:MODES, MODES:] = np.eye(MODES)
        J[MODES:, :MODES] = -stiffness(t)
        return J

    solution = scipy.integrate.solve_ivp(rhs, (0.0, max(times)), np.zeros(2 * MODES), method="Radau", t_eval=times,
                                         jac=jacobian, rtol=RELATIVE_TOLERANCE, atol=ABSOLUTE_TOLERANCE)
    if not solution.success:
        raise SystemExit(solution.message)
    print(json.dumps({"times": times, "tip": [float(v) for v in tip @ solution.y[:MODES]], "elements": ELEMENTS,
                      "modes": MODES, "first_frequency": math.sqrt(squares[0])}))


if __name__ == "__main__":
    main()
