#!/usr/bin/python3
"""Geometrically exact reference for the flexible slider-crank (Simo & Vu-Quoc, "On the dynamics
of flexible beams under large overall motions - the plane case, Part II", J. Appl. Mech. 53,
1986): the same benchmark, crank law and output as slider_crank_reference.py (whose data and
spin-up law it imports), but the rod is NOT a floating frame with a few modes: it is a planar
Euler-Bernoulli beam with exact kinematics, so the axial force of every inertia load -- the
rod's own and the slider's, carried through the pins -- stiffens it, with no modal truncation.

Model: absolute nodal coordinate formulation (ANCF), gradient-deficient planar Euler-Bernoulli
elements (Berzeri & Shabana, "Development of simple models for the elastic forces in the
absolute nodal co-ordinate formulation", J. Sound Vib. 235, 2000; Shabana, "Dynamics of
Multibody Systems", ch. 7). Each node j at the reference arc length X_j carries its position r
and slope r_X (4 coordinates); inside an element r(X) = sum N_a(X) e_a with the cubic Hermite
functions. Chosen over co-rotational elements because its kinematics are exact for any rigid
motion (r is interpolated in the inertial frame), its mass matrix rho A int N N^T is constant
(no centrifugal or Coriolis terms: the inertia is exact for any rotation), and the elastic
energy is the exact one of the continuum rod,

  U = int_0^L (E A / 2 eps^2 + E I / 2 kappa^2) dX,   eps = (r_X . r_X - 1) / 2,
  kappa = (r_X x r_XX) / |r_X|^3   (the deformed centreline's exact curvature),

integrated by 5-point Gauss per element (eps^2 exactly). The cost: the cubic r cannot bend a
straight element without a spurious axial strain (membrane locking); here it is not visible:
w converges as h^4 from 4 elements on (its error against 32 elements falls 17-fold per
halving). kappa per deformed length couples bending to stretch (eps ~ kappa^2 I / A, < 1e-6 in
this benchmark), which `check`'s elastica shows apart from the discretisation error.

Boundary conditions: node 0's position is the crank tip A(t) = r (cos theta, sin theta)
(pinned: its slope is free), the last node's y is 0 (slider on the x axis) and the slider's
mass m_s is added to that node's x. These coordinates are eliminated, leaving with the free
coordinates q (M_ff constant, Cholesky-factored once)

  M_ff q'' = Q_f(q, A(t)) - M_fA A''(t),   Q = -dU/de,

an ODE in (q, q'), started at rest and undeformed along x (theta(0) = theta'(0) = theta''(0) = 0).
The axial waves make it stiff (a 16-element mesh has eigenfrequencies to ~400 kHz, rising as
1 / h: the axial ones; the axial fundamental is 2.9 kHz with the slider, 4.2 kHz without): the
default integrator is SciPy's Radau (L-stable, order 5) with the analytic Jacobian
[[0, I], [-M_ff^-1 K_t(q), 0]] (K_t the exact tangent stiffness, checked against finite
differences in `check`); DOP853 (explicit, undamped, step bound by the highest frequency) is
available to show that the result does not depend on the integrator (8 elements: the two agree
to 1.2e-11 m over 0..0.4 s).

Output: w = ((r_L - r_0) x (r_mid - r_0)) / |r_L - r_0|, the distance of the rod's midpoint
(X = L/2) from the chord through its ends, positive along z x chord: the sign convention of
slider_crank_reference.py.

Usage:
  slider_crank_exact.py run [--elements N] [--slider-mass m] [--end-time T] [--method M]
                            [--rtol r] [t1 t2 ...]
      JSON {"times", "mid", "peak": {"w", "time"}, ...}; with no times: every 0.5 ms to T.
  slider_crank_exact.py table > slider_crank_exact.json
      every 0.5 ms to 0.4 s, the benchmark's slider mass and m_s = 0.
  slider_crank_exact.py verify [--end-time T]
      reruns the start of the stored table (slider_crank_exact.json, both columns, to T,
      default 0.05 s) with its own settings and exits 1 unless it is this script's output to the
      integration tolerance
      (CTest `slider_crank_exact_regenerates`).
  slider_crank_exact.py check
      for 4 to 32 elements: the small-amplitude frequencies (bending pinned-pinned and
      clamped-free, axial fixed-free and with the slider's mass) against their closed forms,
      the elastica (a cantilever bent into a quarter circle by a tip moment) against this
      continuum's closed form, the force against finite differences of U and the tangent
      stiffness against those of the force.
"""
import argparse
import json
import math
import os
import sys
import time

import numpy as np
import scipy.integrate
import scipy.linalg
import scipy.optimize

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import slider_crank_reference as benchmark  # noqa: E402  (the benchmark data and crank law)

AXIAL = benchmark.YOUNGS_MODULUS * benchmark.AREA   # E A [N]
BENDING = benchmark.BENDING                         # E I [N m^2]
RHO_A = benchmark.MASS_PER_LENGTH                   # rho A [kg/m]
LENGTH = benchmark.LENGTH
GAUSS_POINTS = 5
# The table's w is converged to ~5e-8 m (1e-5 of its peak) over 0..0.4 s: 32 elements change it
# by 4.6e-8 m (8 elements by 8e-7 m), rtol 1e-7 by 6e-11 m; DOP853 (8 elements, explicit, no
# numerical damping) and Radau agree to 1.2e-11 m.
TABLE_ELEMENTS = 16
RELATIVE_TOLERANCE = 1e-8


class Rod:
    """The ANCF rod of `elements` equal elements: constant mass matrix, elastic forces and
    tangent stiffness as functions of the nodal coordinates e (shape (nodes, 2, 2): node,
    [r, r_X], [x, y])."""

    def __init__(self, elements):
        self.elements = elements
        self.nodes = elements + 1
        self.h = LENGTH / elements
        points, weights = np.polynomial.legendre.leggauss(GAUSS_POINTS)
        s = 0.5 * (points + 1.0)
        shapes = [benchmark.hermite(si, self.h) for si in s]
        self.N = np.array([n for n, _, _ in shapes])     # (g, 4): N_a at the Gauss points
        self.dN = np.array([d for _, d, _ in shapes])    # d/dX
        self.d2N = np.array([d for _, _, d in shapes])   # d^2/dX^2
        self.dX = 0.5 * weights * self.h                 # (g,) quadrature weights [m]
        element_mass = RHO_A * np.einsum("g,ga,gb->ab", self.dX, self.N, self.N)
        n = 4 * self.nodes
        M = np.zeros((n, n))
        for e in range(elements):
            for c in range(2):
                idx = 4 * e + c + 2 * np.arange(4)   # (r_j, r_X j, r_j+1, r_X j+1), component c
                M[np.ix_(idx, idx)] += element_mass
        self.M = M

    def element_coordinates(self, e):
        """(elements, 4, 2): e_a per element, a over (r_j, r_X j, r_j+1, r_X j+1)."""
        return np.concatenate([e[:-1], e[1:]], axis=1)

    def _gauss_kinematics(self, e):
        """r_X, r_XX (elements, 2, g) and g = r_X . r_X, c = r_X x r_XX (elements, g)."""
        E = self.element_coordinates(e).transpose(0, 2, 1)   # (elements, c, a)
        r_X = E @ self.dN.T
        r_XX = E @ self.d2N.T
        g = r_X[:, 0] ** 2 + r_X[:, 1] ** 2
        cross = r_X[:, 0] * r_XX[:, 1] - r_X[:, 1] * r_XX[:, 0]
        return r_X, r_XX, g, cross

    def _scatter(self, fe):
        """Element vectors (elements, c, a) summed into the shape of e."""
        fe = fe.transpose(0, 2, 1)
        F = np.zeros((self.nodes, 2, 2))
        F[:-1] += fe[:, 0:2]
        F[1:] += fe[:, 2:4]
        return F

    def strain_energy(self, e):
        """U [J]."""
        _, _, g, cross = self._gauss_kinematics(e)
        eps, kappa = 0.5 * (g - 1.0), cross / g**1.5
        return float(np.sum(self.dX * (0.5 * AXIAL * eps**2 + 0.5 * BENDING * kappa**2)))

    def elastic_force(self, e):
        """Q = -dU/de [N, N m], shape of e: per Gauss point dU/d r_X and dU/d r_XX (weights
        included), then through dN, d2N; d c/d r_X = P r_XX, d c/d r_XX = -P r_X with
        P (a, b) = (b, -a)."""
        r_X, r_XX, g, cross = self._gauss_kinematics(e)
        bend = self.dX * BENDING * cross / (g * g * g)        # dX EI kappa / g^1.5
        stretch = self.dX * AXIAL * 0.5 * (g - 1.0) - 3.0 * bend * cross / g
        d_r_X = stretch[:, None] * r_X + bend[:, None] * np.stack([r_XX[:, 1], -r_XX[:, 0]], axis=1)
        d_r_XX = bend[:, None] * np.stack([-r_X[:, 1], r_X[:, 0]], axis=1)
        return -self._scatter(d_r_X @ self.dN + d_r_XX @ self.d2N)

    def tangent_stiffness(self, e):
        """K_t = d^2 U / de^2 [N/m ...] (flattened like e.reshape(-1)): per Gauss point
        EA (eps_e eps_e^T + eps eps_ee) + EI (kappa_e kappa_e^T + kappa kappa_ee), with
        eps_e = g_e / 2, kappa = c g^-3/2 (g = r_X . r_X, c = r_X x r_XX) differentiated twice."""
        r_X, r_XX, g, cross = self._gauss_kinematics(e)
        eps = 0.5 * (g - 1.0)
        kappa = cross / g**1.5
        P = np.array([[0.0, 1.0], [-1.0, 0.0]])
        # S_X, S_XX (g, 2, 8) map an element's 8 coordinates (a, c) to r_X, r_XX.
        eye = np.eye(2)
        S_X = np.einsum("ga,cd->gcad", self.dN, eye).reshape(GAUSS_POINTS, 2, 8)
        S_XX = np.einsum("ga,cd->gcad", self.d2N, eye).reshape(GAUSS_POINTS, 2, 8)
        g_ee = 2.0 * np.einsum("gci,gcj->gij", S_X, S_X)
        c_ee = np.einsum("gci,cd,gdj->gij", S_X, P, S_XX)
        c_ee = c_ee + c_ee.transpose(0, 2, 1)
        g_e = 2.0 * np.einsum("gci,ecg->egi", S_X, r_X)
        c_e = (np.einsum("gci,cd,edg->egi", S_X, P, r_XX) + np.einsum("gci,dc,edg->egi", S_XX, P, r_X))
        G, C = g[..., None], cross[..., None]       # broadcast over a coordinate i
        k_e = c_e / G**1.5 - 1.5 * C * g_e / G**2.5
        G, C = G[..., None], C[..., None]           # over a pair (i, j)

        def outer(a, b):
            return np.einsum("egi,egj->egij", a, b)

        k_ee = (c_ee / G**1.5 - 1.5 * (outer(c_e, g_e) + outer(g_e, c_e)) / G**2.5
                + 3.75 * C * outer(g_e, g_e) / G**3.5 - 1.5 * C * g_ee / G**2.5)
        integrand = (AXIAL * (0.25 * outer(g_e, g_e) + 0.5 * eps[..., None, None] * g_ee)
                     + BENDING * (outer(k_e, k_e) + kappa[..., None, None] * k_ee))
        Ke = np.einsum("g,egij->eij", self.dX, integrand)
        n = 4 * self.nodes
        K = np.zeros((n, n))
        for el in range(self.elements):
            K[4 * el:4 * el + 8, 4 * el:4 * el + 8] += Ke[el]   # element (a, c) order == global order
        return K


def straight(rod, origin=(0.0, 0.0)):
    """The undeformed rod along x from `origin`."""
    e = np.zeros((rod.nodes, 2, 2))
    e[:, 0, 0] = origin[0] + rod.h * np.arange(rod.nodes)
    e[:, 0, 1] = origin[1]
    e[:, 1, 0] = 1.0
    return e


def crank_tip(t):
    """A, A', A'' [m, m/s, m/s^2]."""
    theta, rate, acceleration = benchmark.crank_angle(t)
    radial = np.array([math.cos(theta), math.sin(theta)])
    tangential = np.array([-math.sin(theta), math.cos(theta)])
    return (benchmark.CRANK * radial, benchmark.CRANK * rate * tangential,
            benchmark.CRANK * (acceleration * tangential - rate * rate * radial))


class SliderCrank:
    """The rod in the slider-crank: free coordinates, their constant mass matrix and the ODE."""

    def __init__(self, elements, slider_mass):
        if elements % 2:
            raise SystemExit("--elements must be even (the midpoint is a node)")
        self.rod = Rod(elements)
        n = 4 * self.rod.nodes
        last_y = 4 * elements + 1
        self.prescribed = np.array([0, 1, last_y])          # x_0, y_0 (the crank tip), y_L (= 0)
        self.free = np.setdiff1d(np.arange(n), self.prescribed)
        M = self.rod.M.copy()
        M[4 * elements, 4 * elements] += slider_mass        # x_L carries the slider
        M_ff = M[np.ix_(self.free, self.free)]
        self.M_inv = scipy.linalg.cho_solve(scipy.linalg.cho_factor(M_ff), np.eye(len(self.free)))
        # M_fA A'' is the prescribed root's inertia coupling (y_L'' = 0).
        self.root_coupling = self.M_inv @ M[np.ix_(self.free, [0, 1])]
        self.size = len(self.free)

    def coordinates(self, t, q):
        e = np.zeros(4 * self.rod.nodes)
        e[self.free] = q
        e[0:2] = crank_tip(t)[0]
        return e.reshape(self.rod.nodes, 2, 2)

    def rhs(self, t, z):
        q, q_dot = z[:self.size], z[self.size:]
        Q = self.rod.elastic_force(self.coordinates(t, q)).reshape(-1)[self.free]
        return np.concatenate([q_dot, self.M_inv @ Q - self.root_coupling @ crank_tip(t)[2]])

    def jacobian(self, t, z):
        K = self.rod.tangent_stiffness(self.coordinates(t, z[:self.size]))
        n = self.size
        J = np.zeros((2 * n, 2 * n))
        J[:n, n:] = np.eye(n)
        J[n:, :n] = -self.M_inv @ K[np.ix_(self.free, self.free)]
        return J

    def initial_state(self):
        e = straight(self.rod, crank_tip(0.0)[0])
        return np.concatenate([e.reshape(-1)[self.free], np.zeros(self.size)])

    def mid_deflection(self, t, q):
        e = self.coordinates(t, q)
        root, mid, end = e[0, 0], e[self.rod.elements // 2, 0], e[-1, 0]
        chord = end - root
        arm = mid - root
        return float((chord[0] * arm[1] - chord[1] * arm[0]) / np.hypot(*chord))


def simulate(elements, slider_mass, times, method="Radau", rtol=RELATIVE_TOLERANCE):
    """w(t) [m] at `times` and the integrator's statistics."""
    model = SliderCrank(elements, slider_mass)
    # Absolute tolerances: rtol mm on coordinates (m and slopes), rtol 100 m/s on their rates (the
    # rod's points move at up to ~25 m/s). Rates held to ~1e-9 m/s make Radau follow the axial
    # waves' tiny velocities with ~1e-6 s steps, for no change in w.
    options = dict(rtol=rtol, atol=np.concatenate([np.full(model.size, rtol * 1e-3),
                                                   np.full(model.size, rtol * 1e2)]))
    if method in ("Radau", "BDF"):
        options["jac"] = model.jacobian
    start = time.process_time()
    # An explicit method's trial steps beyond its stability limit overflow before it rejects them.
    with np.errstate(over="ignore", invalid="ignore"):
        solution = scipy.integrate.solve_ivp(model.rhs, (0.0, max(times)), model.initial_state(), method=method,
                                             t_eval=times, **options)
    if not solution.success:
        raise SystemExit(solution.message)
    mid = [model.mid_deflection(t, z[:model.size]) for t, z in zip(solution.t, solution.y.T)]
    stats = {"method": method, "rtol": rtol, "elements": elements, "slider_mass": slider_mass,
             "rhs_evaluations": int(solution.nfev), "jacobians": int(solution.njev),
             "cpu_seconds": round(time.process_time() - start, 1)}
    return mid, stats


def peak(times, mid):
    """The largest |w| [m] and its time [s], refined by a parabola through the grid's peak."""
    w = np.abs(np.asarray(mid))
    k = int(np.argmax(w))
    if 0 < k < len(w) - 1:
        a, b, c = w[k - 1], w[k], w[k + 1]
        dt = times[k + 1] - times[k]
        offset = 0.5 * (a - c) / (a - 2 * b + c)
        return float(np.sign(mid[k]) * (b - 0.25 * (a - c) * offset)), float(times[k] + offset * dt)
    return float(mid[k]), float(times[k])


def output_times(end_time, step=5e-4):
    """0, step, ... end_time [s]: the reference table's grid."""
    return [step * k for k in range(int(round(end_time / step)) + 1)]


def check():
    """Verification of the rod model against closed forms; prints JSON."""
    report = {}
    wave_speed = math.sqrt(AXIAL / RHO_A)
    beam_speed = math.sqrt(BENDING / RHO_A)
    # The slider's axial fundamental: a rod fixed at one end with the mass m_s at the other,
    # beta L tan(beta L) = rho A L / m_s, f = beta c / (2 pi).
    beta_L = scipy.optimize.brentq(lambda b: b * math.tan(b) - RHO_A * LENGTH / benchmark.SLIDER_MASS,
                                   1e-6, math.pi / 2 - 1e-9)
    slider_axial = beta_L * wave_speed / (2 * math.pi * LENGTH)
    for elements in (4, 8, 16, 32):
        rod = Rod(elements)
        e0 = straight(rod)
        K = rod.tangent_stiffness(e0)
        n = 4 * rod.nodes
        # The slider-crank's supports (root pinned, far end on the x axis): bending ~ (k pi / L)^2,
        # axial as fixed-free, or with the slider mass on the far end.
        pinned = np.setdiff1d(np.arange(n), [0, 1, n - 3])
        squares, vectors = scipy.linalg.eigh(K[np.ix_(pinned, pinned)], rod.M[np.ix_(pinned, pinned)])
        y_share = [float(np.sum(v[(pinned % 2) == 1] ** 2) / np.sum(v**2)) for v in vectors.T]
        bend_hz = [math.sqrt(s) / (2 * math.pi) for s, y in zip(squares, y_share) if y > 0.5][:3]
        axial_hz = [math.sqrt(s) / (2 * math.pi) for s, y in zip(squares, y_share) if y <= 0.5 and s > 1.0][0]
        M_slider = rod.M.copy()
        M_slider[n - 4, n - 4] += benchmark.SLIDER_MASS
        squares_slider, vectors = scipy.linalg.eigh(K[np.ix_(pinned, pinned)], M_slider[np.ix_(pinned, pinned)])
        y_share = [float(np.sum(v[(pinned % 2) == 1] ** 2) / np.sum(v**2)) for v in vectors.T]
        axial_slider_hz = [math.sqrt(s) / (2 * math.pi) for s, y in zip(squares_slider, y_share)
                           if y <= 0.5 and s > 1.0][0]
        entry = report[f"{elements}_elements"] = {
            "pinned_pinned_bending_hz": bend_hz,
            "bending_relative_error": [f / ((k + 1) ** 2 * math.pi * beam_speed / (2 * LENGTH**2)) - 1.0
                                       for k, f in enumerate(bend_hz)],
            "axial_hz": axial_hz,
            "axial_relative_error": axial_hz / (wave_speed / (4 * LENGTH)) - 1.0,
            "axial_with_slider_hz": axial_slider_hz,
            "axial_with_slider_relative_error": axial_slider_hz / slider_axial - 1.0,
            "highest_hz": math.sqrt(squares[-1]) / (2 * math.pi)}
        # Clamped-free (root position and slope held): 1.8751^2 sqrt(EI / rho A) / L^2.
        clamped = np.setdiff1d(np.arange(n), [0, 1, 2, 3])
        squares = scipy.linalg.eigh(K[np.ix_(clamped, clamped)], rod.M[np.ix_(clamped, clamped)], eigvals_only=True)
        cantilever = 1.8751040687**2 * beam_speed / (2 * math.pi * LENGTH**2)
        first = min((math.sqrt(s) / (2 * math.pi) for s in squares), key=lambda f: abs(f - cantilever))
        entry["cantilever_first_relative_error"] = first / cantilever - 1.0
        # The elastica: a tip moment M bends the clamped rod into a circle. Inextensible: of
        # curvature k0 = M / EI, tip at (sin(k0 L), 1 - cos(k0 L)) / k0. This model's continuum
        # (kappa is the curvature per deformed length) also stretches it uniformly by lam:
        # k = M lam^2 / EI (turn per reference length), EA (lam^2 - 1) / 2 = EI k^2 / lam^4
        # (no axial resultant), tip at lam (sin(k L), 1 - cos(k L)) / k. k0 L = pi / 2. The
        # root holds r and the direction of r_X (y_X = 0), not its length, which is lam.
        held = np.setdiff1d(np.arange(n), [0, 1, 3])
        moment = BENDING * math.pi / (2 * LENGTH)
        lam = 1.0
        for _ in range(50):
            turn = moment * lam**2 / BENDING
            lam = math.sqrt(1.0 + 2.0 * BENDING * turn**2 / (AXIAL * lam**4))

        def arc(k, stretch):
            return stretch * np.array([math.sin(k * LENGTH), 1.0 - math.cos(k * LENGTH)]) / k

        e = e0.copy()
        for load in np.linspace(0.0, 1.0, 9)[1:]:
            for _ in range(30):
                tip = e[-1, 1]
                a2 = tip @ tip
                F = rod.elastic_force(e)
                F[-1, 1] += load * moment * np.array([-tip[1], tip[0]]) / a2   # M d(angle)/d r_X
                Kt = rod.tangent_stiffness(e)
                H = np.array([[2 * tip[0] * tip[1], tip[1]**2 - tip[0]**2],
                              [tip[1]**2 - tip[0]**2, -2 * tip[0] * tip[1]]]) / a2**2
                Kt[-2:, -2:] -= load * moment * H
                step = np.linalg.solve(Kt[np.ix_(held, held)], F.reshape(-1)[held])
                flat = e.reshape(-1)
                flat[held] += step
                e = flat.reshape(e.shape)
                if np.max(np.abs(step)) < 1e-14:
                    break
        entry["elastica_tip_error_m"] = float(np.linalg.norm(e[-1, 0] - arc(turn, lam)))
        entry["elastica_stretch_shift_m"] = float(np.linalg.norm(arc(turn, lam) - arc(math.pi / (2 * LENGTH), 1.0)))
        # The force against central differences of U, the tangent stiffness against those of
        # the force, at a deformed state.
        rng = np.random.default_rng(1)
        trial = e + 0.01 * rng.standard_normal(e.shape)
        K = rod.tangent_stiffness(trial)
        Q = rod.elastic_force(trial).reshape(-1)
        step = 1e-7
        columns, gradient = [], []
        for i in range(e.size):
            d = np.zeros(e.size)
            d[i] = step
            plus = rod.elastic_force(trial + d.reshape(e.shape)).reshape(-1)
            minus = rod.elastic_force(trial - d.reshape(e.shape)).reshape(-1)
            columns.append(-(plus - minus) / (2 * step))
            gradient.append((rod.strain_energy(trial + d.reshape(e.shape))
                             - rod.strain_energy(trial - d.reshape(e.shape))) / (2 * step))
        entry["force_relative_error"] = float(np.max(np.abs(-np.array(gradient) - Q)) / np.max(np.abs(Q)))
        entry["tangent_relative_error"] = float(
            np.max(np.abs(np.array(columns).T - K)) / np.max(np.abs(K)))
    print(json.dumps(report, indent=1))


# `verify`: the stored table against a rerun of its first samples with its own settings,
# relative to the window's peak |w|. The rerun repeats the table's steps but the last ones,
# which end at the window's end: the two differ by the integration tolerance there (measured
# 6.6e-9 over 0.05 s; 1.6e-11 over 0.1 s). A larger difference means the script or the data
# changed.
VERIFY_TOLERANCE = 5e-8
VERIFY_END_TIME = 0.05  # [s]
TABLE_FILE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "slider_crank_exact.json")


def verify(end_time):
    """Reruns the stored table to `end_time` and compares; returns the exit status."""
    with open(TABLE_FILE) as f:
        table = json.load(f)
    times = [t for t in table["times"] if t <= end_time + 1e-12]
    worst = 0.0
    for column, slider_mass in (("mid", table["slider_mass"]), ("mid_no_slider_mass", 0.0)):
        mid, _ = simulate(table["elements"], slider_mass, times, table["method"], table["rtol"])
        difference = max(abs(a - b) for a, b in zip(mid, table[column][:len(times)]))
        peak = max(abs(b) for b in table[column][:len(times)])
        print(f"{column}: {len(times)} samples to {times[-1]:g} s, largest difference {difference:.2e} m = "
              f"{difference / peak:.2e} of the peak {peak:.3e} m (limit {VERIFY_TOLERANCE:g})")
        worst = max(worst, difference / peak)
    return 0 if worst <= VERIFY_TOLERANCE else 1


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("mode", choices=["run", "table", "check", "verify"])
    parser.add_argument("times", nargs="*", type=float)
    parser.add_argument("--elements", type=int, default=TABLE_ELEMENTS)
    parser.add_argument("--slider-mass", type=float, default=benchmark.SLIDER_MASS)
    parser.add_argument("--end-time", type=float, default=None, help="run: 0.4 s; verify: 0.05 s")
    parser.add_argument("--method", default="Radau", choices=["Radau", "BDF", "DOP853"])
    parser.add_argument("--rtol", type=float, default=RELATIVE_TOLERANCE)
    args = parser.parse_intermixed_args()
    if args.mode == "verify":
        sys.exit(verify(args.end_time or VERIFY_END_TIME))
    if args.mode == "check":
        check()
        return
    if args.mode == "table":
        times = output_times(0.4)
        with_slider, stats = simulate(args.elements, benchmark.SLIDER_MASS, times, args.method, args.rtol)
        without, _ = simulate(args.elements, 0.0, times, args.method, args.rtol)
        print(json.dumps({"elements": args.elements, "method": args.method, "rtol": args.rtol,
                          "slider_mass": benchmark.SLIDER_MASS, "times": times, "mid": with_slider,
                          "mid_no_slider_mass": without}))
        return
    times = args.times or output_times(args.end_time or 0.4)
    mid, stats = simulate(args.elements, args.slider_mass, times, args.method, args.rtol)
    w, t = peak(times, mid)
    print(json.dumps({"times": times, "mid": mid, "peak": {"w": w, "time": t}, **stats}))


if __name__ == "__main__":
    main()
