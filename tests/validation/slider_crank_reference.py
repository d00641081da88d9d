#!/usr/bin/python3
"""Reference midpoint deflection of the flexible slider-crank (Simo & Vu-Quoc, "On the dynamics
of flexible beams under large overall motions - the plane case, Part II", J. Appl. Mech. 53,
1986), planar and independent of flexmbs: the floating-frame counterpart of slider_crank_exact.py,
which takes the benchmark data and the crank law from here.

A rigid crank of length r turns about the origin with the prescribed angle

  theta(t) = (Omega / T) (t^2 / 2 + (T / (2 pi))^2 (cos(2 pi t / T) - 1))   for t < T,
             Omega (t - T / 2)                                               after,

and carries at its tip A(t) = r (cos theta, sin theta) the root of a uniform Euler-Bernoulli
rod of length L (pinned there); the rod's other end is pinned to a slider of mass m_s on the
x axis. Floating frame: origin at A, angle phi, x' along the undeformed rod (root tangent);
the rod's deflection v(x', t) = psi(x')^T q in the frame, with psi the lowest MODES bending
modes of the rod clamped at its root (cubic Hermite elements, M-orthonormal): the modes of a
fixed-interface reduction. Kane's equations of the rod and the slider (a point mass at x' = L),
first order in q in the elastic row ("modified linear"; the kinetic energy is exact in q):

  phi row:  (J0 + q^T Mq q) phi'' + d^T q'' - a_x c^T q + a_y S + 2 phi' q^T Mq q' = G_phi lam
  q rows:   d phi'' + Mq q'' + c a_y + (Kq - phi'^2 Mq + s KG) q               = G_q lam

with a = R(phi)^T A'' (the root's acceleration in the frame), J0 = int x^2 dm, S = int x dm,
c = int psi dm, d = int x psi dm, Mq = int psi psi^T dm (dm: the rod's rho A dx and m_s at
x = L), Kq = EI int psi'' psi''^T dx, and the slider's constraint
g = A_y + L sin(phi) + v(L) cos(phi) = 0 (G = dg/d(phi, q)). Geometric stiffening (s = 1):
the axial force of the rod's own inertia with the rod held at its root,
P(x) = rho A (phi'^2 (L^2 - x^2) / 2 - a_x (L - x)), KG = int P psi' psi'^T dx -- the
stiffening flexmbs takes from SID's K0 matrices (the frame's acceleration and angular
velocity); the share of the axial force that the joint at the slider transmits is left out
on both sides (docs/mbs.md: joint reactions do not stiffen). The centrifugal part of the
stiffening, phi'^2 q^T Ts q with Ts = int rho A (L^2 - x^2) / 2 psi' psi'^T dx, is the
kinetic energy -phi'^2 q^T Ts q / 2 of the rod's axial foreshortening (mbs/stiffening_inertia.h);
its partner in the phi row, -d/dt(phi' q^T Ts q) = -phi'' q^T Ts q - 2 phi' q^T Ts q', is
chosen by --partner: none (the elastic row only), gyroscopic (the velocity term alone, as
flexmbs: the default) or full (both: the Lagrangian of the foreshortening's kinetic energy).
The constraint is eliminated:
phi'' = (gamma - G_q q'') / G_phi (gamma from g'' = 0), phi and phi' from g = 0 and g' = 0,
leaving an ODE in (q, q') integrated by SciPy's DOP853 at tight tolerances.

Output: the midpoint deflection w = ((L, v_L) x (L/2, v_mid)) / |(L, v_L)|: the distance of the
rod's midpoint from the chord through its ends, positive along the frame's y' (z x x').

Usage: slider_crank_reference.py [--partner=none|gyroscopic|full] MODES STIFFENING(0|1) t1 t2 ...
Prints JSON: {"times": [...], "mid": [w in m ...], "frequencies_hz": the clamped rod's,
"elements": n}.
       slider_crank_reference.py table > table.json
Prints a table: 4 modes, every 0.5 ms to 0.4 s, stiffening on and off. (No test reads one: the
tests compare with slider_crank_exact.py's table; this floating-frame model is the planar
counterpart docs/mbs.md cites, and supplies slider_crank_exact.py's benchmark data and crank law.)
"""
import json
import math
import sys

import numpy as np
import scipy.integrate
import scipy.linalg

# The benchmark (tests/validation/slider_crank_model.h states where each number comes from).
CRANK = 0.15               # r [m]
LENGTH = 0.3               # L [m]
DIAMETER = 6e-3            # [m]
YOUNGS_MODULUS = 2.0e11    # [Pa]
DENSITY = 7870.0           # [kg/m^3]
SLIDER_MASS = 0.033        # m_s [kg]
SPIN = 150.0               # Omega [rad/s]
RAMP_TIME = 0.15           # T [s]
AREA = math.pi * DIAMETER**2 / 4
BENDING = YOUNGS_MODULUS * math.pi * DIAMETER**4 / 64   # EI [N m^2]
MASS_PER_LENGTH = DENSITY * AREA                        # rho A [kg/m]
# The deflection is converged to 1e-9 m (4 modes, to 0.4 s): 80 elements change it by < 1e-10 m,
# tolerances 1e-12 by < 1e-11 m.
ELEMENTS = 40
RELATIVE_TOLERANCE = 1e-10
ABSOLUTE_TOLERANCE = 1e-13


def crank_angle(t):
    """theta, theta', theta'' [rad, rad/s, rad/s^2]."""
    if t >= RAMP_TIME:
        return SPIN * (t - RAMP_TIME / 2), SPIN, 0.0
    phase = 2.0 * math.pi * t / RAMP_TIME
    c = RAMP_TIME / (2.0 * math.pi)
    return ((SPIN / RAMP_TIME) * (t * t / 2 + c * c * (math.cos(phase) - 1.0)),
            (SPIN / RAMP_TIME) * (t - c * math.sin(phase)), (SPIN / RAMP_TIME) * (1.0 - math.cos(phase)))


def hermite(s, h):
    """Cubic Hermite shape functions on an element of length h at s in [0, 1] (DOF v, v' per
    node) and their first and second derivatives along x."""
    N = np.array([1 - 3 * s**2 + 2 * s**3, h * (s - 2 * s**2 + s**3), 3 * s**2 - 2 * s**3, h * (s**3 - s**2)])
    dN = np.array([6 * s**2 - 6 * s, h * (1 - 4 * s + 3 * s**2), 6 * s - 6 * s**2, h * (3 * s**2 - 2 * s)]) / h
    d2N = np.array([12 * s - 6, h * (6 * s - 4), 6 - 12 * s, h * (6 * s - 2)]) / h**2
    return N, dN, d2N


def assemble():
    """On the DOF of the rod clamped at x = 0: K = EI int N''N''^T, M = rho A int N N^T,
    T_spin = rho A int (L^2 - x^2) / 2 N'N'^T, T_acc = rho A int (L - x) N'N'^T (the axial force
    per unit phi'^2 and per unit -a_x), m0 = rho A int N, m1 = rho A int x N, and N at L, L/2."""
    h = LENGTH / ELEMENTS
    n = 2 * (ELEMENTS + 1)
    K, M, T_spin, T_acc = (np.zeros((n, n)) for _ in range(4))
    m0, m1 = np.zeros(n), np.zeros(n)
    points, weights = np.polynomial.legendre.leggauss(6)
    for e in range(ELEMENTS):
        dofs = np.arange(2 * e, 2 * e + 4)
        for p, w in zip(points, weights):
            s = 0.5 * (p + 1.0)
            x = (e + s) * h
            dx = 0.5 * w * h
            N, dN, d2N = hermite(s, h)
            K[np.ix_(dofs, dofs)] += dx * BENDING * np.outer(d2N, d2N)
            M[np.ix_(dofs, dofs)] += dx * MASS_PER_LENGTH * np.outer(N, N)
            T_spin[np.ix_(dofs, dofs)] += dx * MASS_PER_LENGTH * 0.5 * (LENGTH**2 - x * x) * np.outer(dN, dN)
            T_acc[np.ix_(dofs, dofs)] += dx * MASS_PER_LENGTH * (LENGTH - x) * np.outer(dN, dN)
            m0[dofs] += dx * MASS_PER_LENGTH * N
            m1[dofs] += dx * MASS_PER_LENGTH * x * N
    tip = np.zeros(n)
    tip[-2] = 1.0
    mid = np.zeros(n)
    mid[2 * (ELEMENTS // 2)] = 1.0
    free = slice(2, n)
    return (K[free, free], M[free, free], T_spin[free, free], T_acc[free, free], m0[free], m1[free], tip[free],
            mid[free])


PARTNERS = ("none", "gyroscopic", "full")


def midpoint_deflection(modes, stiffening, times, partner="gyroscopic"):
    """w(t) [m] at `times` and the clamped rod's frequencies [Hz]."""
    assert ELEMENTS % 2 == 0
    K, M, T_spin, T_acc, m0, m1, tip, mid = assemble()
    squares, Psi = scipy.linalg.eigh(K, M, subset_by_index=[0, modes - 1])
    psi_L, psi_mid = Psi.T @ tip, Psi.T @ mid
    # The rod's and the slider's integrals in modal coordinates.
    rod_mass = MASS_PER_LENGTH * LENGTH
    J0 = rod_mass * LENGTH**2 / 3 + SLIDER_MASS * LENGTH**2
    S = rod_mass * LENGTH / 2 + SLIDER_MASS * LENGTH
    c = Psi.T @ m0 + SLIDER_MASS * psi_L
    d = Psi.T @ m1 + SLIDER_MASS * LENGTH * psi_L
    Mq = np.eye(modes) + SLIDER_MASS * np.outer(psi_L, psi_L)
    Kq = np.diag(squares)
    Ts, Ta = Psi.T @ T_spin @ Psi, Psi.T @ T_acc @ Psi

    def root_motion(t):
        theta, rate, acceleration = crank_angle(t)
        A = CRANK * np.array([math.cos(theta), math.sin(theta)])
        A_dot = CRANK * rate * np.array([-math.sin(theta), math.cos(theta)])
        A_ddot = CRANK * acceleration * np.array([-math.sin(theta), math.cos(theta)]) - rate * rate * A
        return A, A_dot, A_ddot

    def frame(t, q, q_dot):
        """phi and phi' from g = 0 and g' = 0 (the slider on the positive x side)."""
        A, A_dot, _ = root_motion(t)
        v_L = psi_L @ q
        phi = math.asin(-A[1] / math.hypot(LENGTH, v_L)) - math.atan2(v_L, LENGTH)
        G_phi = LENGTH * math.cos(phi) - v_L * math.sin(phi)
        phi_dot = -(A_dot[1] + math.cos(phi) * (psi_L @ q_dot)) / G_phi
        return phi, phi_dot, G_phi

    def rhs(t, z):
        q, q_dot = z[:modes], z[modes:]
        phi, phi_dot, G_phi = frame(t, q, q_dot)
        _, _, A_ddot = root_motion(t)
        cos, sin = math.cos(phi), math.sin(phi)
        a_x, a_y = cos * A_ddot[0] + sin * A_ddot[1], -sin * A_ddot[0] + cos * A_ddot[1]
        v_L, v_L_dot = psi_L @ q, psi_L @ q_dot
        G_q = cos * psi_L
        gamma = -A_ddot[1] + (LENGTH * sin + v_L * cos) * phi_dot**2 + 2 * v_L_dot * sin * phi_dot
        # M s'' = f with s = (phi, q).
        Mass = np.zeros((modes + 1, modes + 1))
        Mass[0, 0] = J0 + q @ Mq @ q - (stiffening * (q @ Ts @ q) if partner == "full" else 0.0)
        Mass[0, 1:] = Mass[1:, 0] = d
        Mass[1:, 1:] = Mq
        stiffness = Kq - phi_dot**2 * Mq + stiffening * (phi_dot**2 * Ts - a_x * Ta)
        gyroscopic = 0.0 if partner == "none" else 2 * stiffening * phi_dot * (q @ Ts @ q_dot)
        f = np.concatenate([[a_x * (c @ q) - a_y * S - 2 * phi_dot * (q @ Mq @ q_dot) + gyroscopic],
                            -c * a_y - stiffness @ q])
        # s'' = N q'' + e_phi gamma / G_phi; N^T (M s'' - f) = 0 (the multiplier's work vanishes).
        N = np.vstack([-G_q / G_phi, np.eye(modes)])
        particular = np.zeros(modes + 1)
        particular[0] = gamma / G_phi
        q_ddot = np.linalg.solve(N.T @ Mass @ N, N.T @ (f - Mass @ particular))
        return np.concatenate([q_dot, q_ddot])

    solution = scipy.integrate.solve_ivp(rhs, (0.0, max(times)), np.zeros(2 * modes), method="DOP853",
                                         t_eval=times, rtol=RELATIVE_TOLERANCE, atol=ABSOLUTE_TOLERANCE)
    if not solution.success:
        raise SystemExit(solution.message)
    mid_deflection = []
    for z in solution.y.T:
        q = z[:modes]
        v_L, v_mid = psi_L @ q, psi_mid @ q
        mid_deflection.append(float((LENGTH * v_mid - 0.5 * LENGTH * v_L) / math.hypot(LENGTH, v_L)))
    return mid_deflection, [float(math.sqrt(s) / (2 * math.pi)) for s in squares]


def main():
    partner = "gyroscopic"
    if sys.argv[1].startswith("--partner="):
        partner = sys.argv.pop(1).split("=", 1)[1]
        if partner not in PARTNERS:
            raise SystemExit(f"--partner={partner}: not one of {', '.join(PARTNERS)}")
    if sys.argv[1] == "table":
        modes, times = 4, [0.0005 * k for k in range(801)]
        on, frequencies = midpoint_deflection(modes, 1.0, times, partner)
        off, _ = midpoint_deflection(modes, 0.0, times, partner)
        print(json.dumps({"modes": modes, "elements": ELEMENTS, "partner": partner, "frequencies_hz": frequencies, "times": times,
                          "stiffening_on": on, "stiffening_off": off}))
        return
    times = [float(a) for a in sys.argv[3:]]
    mid, frequencies = midpoint_deflection(int(sys.argv[1]), float(sys.argv[2]), times, partner)
    print(json.dumps({"times": times, "mid": mid, "frequencies_hz": frequencies, "elements": ELEMENTS}))


if __name__ == "__main__":
    main()
