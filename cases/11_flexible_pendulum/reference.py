#!/usr/bin/python3
"""Planar reference for the flexible pendulum (cases/11_flexible_pendulum), independent of flexmbs:
a co-rotational Euler-Bernoulli beam FE model in SciPy.

The strip (L = 1 m, EI = 43.75 N m^2, EA = 2.1e7 N, rho A = 0.785 kg/m) is cut into N equal
two-node elements; node j has (x_j, y_j, theta_j) in the inertial plane. Each element follows its
chord (Crisfield, "Non-linear Finite Element Analysis of Solids and Structures" vol. 1, ch. 7;
Felippa's co-rotational notes): from its length l and angle beta,

  u = l - l0,   t_a = theta_a - beta,   t_b = theta_b - beta   (beta0 = 0: the strip starts along x),
  N = EA u / l0,   M_a = 2 EI / l0 (2 t_a + t_b),   M_b = 2 EI / l0 (t_a + 2 t_b),

the local strains being small while the chord turns by any angle: its energy
U = EA u^2 / (2 l0) + EI / l0 (2 t_a^2 + 2 t_a t_b + 2 t_b^2) is exact for a rigid motion, and the
nodal forces are its gradient, f = B^T (N, M_a, M_b) with B = d(u, t_a, t_b) / d(node
coordinates). The mass is lumped (rho A l0 / 2 on each end's x and y) and Euler-Bernoulli's beam
has no rotary inertia: the rotations follow from the positions by every node's moment balance,
dU/dtheta = 0 (a constant linear map theta = R beta), and by the envelope theorem the forces on
the positions are f's position rows at those rotations. The mass is constant in the inertial
frame, so M q'' = -f(q) + m g with no velocity terms; the lumping's error falls as h^2 (the
convergence is in `check`). Node 0's x and y are held (the pin). Started straight along x, at
rest. Integrated by SciPy's Radau (L-stable, order 5; the axial modes reach ~1e6 rad/s) with the
exact Jacobian: the condensed bending energy is (1/2) beta^T S beta with S constant
(S = dU/dbeta's matrix at theta = R beta), so the tangent stiffness is, per element, EA/l0 n n^T +
N (I - n n^T)/l + (S beta)_e d^2 beta_e/dd^2 on its chord d, plus G^T S G with G = dbeta/dq
(`check` compares it with central differences of the forces). The swing turns the stiff axial
directions during a step, so Radau's simplified Newton needs a fresh Jacobian nearly every step.
The finite differences' Jacobian (2 n vectorized columns) took 106 s of CPU to 0.5 s and did not
reach 2 s in 11 minutes of CPU (80 elements, loaded machine); the exact one takes 34 s to 2 s
(160 elements: 122 s; to 0.25 s at 80: 4.4 s against 5.7 s, 708 LU factorisations against 1084).
At 80 elements the two tables differ by 2.8e-6 m over 0.5 s, each within 1.7e-6 m of the exact
Jacobian's run at rtol 1e-9: the integration's own error.

Outputs at the requested times: the swing angle theta_0 (the pin section's turn, which the
reduced body's frame follows: its modes are clamped at the pin) and the tip deflection
w = (-sin theta_0, cos theta_0) . r_N (the tip's offset across the strip in the pin's frame).

Usage:
  reference.py [--elements N] [--rtol r] t1 t2 ...   JSON {"times", "angle", "tip", "energy_drift", ...}
  reference.py check                                 the deflection's convergence in N and rtol
  reference.py verify STORED.json END_TIME           reruns the stored table to END_TIME, exit 1 if it differs
"""
import argparse
import json
import math
import sys
import time

import numpy as np
import scipy.integrate
import scipy.sparse

LENGTH = 1.0                       # m
YOUNGS_MODULUS = 2.1e11            # Pa
DENSITY = 7850.0                   # kg/m^3
THICKNESS = 0.005                  # h, in the plane of the swing [m]
WIDTH = 0.02                       # b [m]
AREA = THICKNESS * WIDTH
SECOND_MOMENT = WIDTH * THICKNESS**3 / 12.0
GRAVITY = 9.81                     # m/s^2, along -y
# The tip deflection over 0 .. 0.3 s (`check`): 10, 20, 40, 80 elements differ from 160 by 6.0e-4,
# 2.0e-4, 4.6e-5, 9.3e-6 m (order 2: 160 within ~3e-6 m, 0.07 % of the largest tip); rtol 1e-9
# moves 40 elements' by 7.9e-7 m. Over the whole swing the lumped masses' moment of inertia about
# the pin, rho A L^3 (1/3 + 1/(6 N^2)), delays the swing, also at order 2 (`--elements N`, the
# output times to 2 s): in 1.5 .. 2 s 40 and 80 elements differ by 3.9e-4 m of tip and 1.2e-3 rad,
# 80 and 160 by 1.1e-4 m and 2.9e-4 rad (ratio 3.6 .. 4.3 over the swing), so 160 elements' own
# error is about a third of the latter: 3.7e-5 m (0.85 % of the largest tip) and 1e-4 rad.
ELEMENTS = 160
RELATIVE_TOLERANCE = 1e-8


class Pendulum:
    """The co-rotational strip, pinned at node 0: state z = (q, q'), q the nodes' free x, y; the
    rotations follow from them."""

    def __init__(self, elements):
        self.elements = elements
        self.nodes = elements + 1
        self.l0 = LENGTH / elements
        mass = np.zeros(self.nodes)
        mass[:-1] += 0.5 * DENSITY * AREA * self.l0
        mass[1:] += 0.5 * DENSITY * AREA * self.l0
        self.inverse_mass = 1.0 / np.repeat(mass[1:], 2)       # node 0 (x, y) held
        self.gravity = np.zeros(2 * elements)
        self.gravity[1::2] = -GRAVITY * mass[1:]
        self.size = 2 * elements
        # Moment equilibrium of every node, k = 2 EI / l0 from the elements on either side:
        # (theta_j-1 + 2 theta_j - 3 beta_j-1) + (2 theta_j + theta_j+1 - 3 beta_j) = 0, ends one-sided.
        A = np.zeros((self.nodes, self.nodes))
        C = np.zeros((self.nodes, elements))
        for e in range(elements):
            A[e, e] += 2.0
            A[e, e + 1] += 1.0
            A[e + 1, e] += 1.0
            A[e + 1, e + 1] += 2.0
            C[e, e] += 3.0
            C[e + 1, e] += 3.0
        self.rotations = np.linalg.solve(A, C)                 # theta = rotations @ beta
        # dU/dbeta_e = -3 k (t_a + t_b) at theta = R beta: (S beta)_e, S symmetric (the condensed
        # bending energy's Hessian in the chord angles).
        k = 2.0 * YOUNGS_MODULUS * SECOND_MOMENT / self.l0
        self.bending = -3.0 * k * (self.rotations[:-1] + self.rotations[1:] - 2.0 * np.eye(elements))

    def positions(self, q):
        """(nodes, 2, ...): x, y of every node, for q of shape (size, ...) (a column per state)."""
        return np.concatenate([np.zeros((2,) + q.shape[1:]), q]).reshape((self.nodes, 2) + q.shape[1:])

    def element_state(self, q):
        """Chords (dx, dy, length, beta, unwrapped along the strip) and the nodes' rotations theta."""
        p = self.positions(q)
        dx, dy = np.diff(p[:, 0], axis=0), np.diff(p[:, 1], axis=0)
        # The chord's angle measured from -y (+ pi/2 back): the branch cut of arctan2 then points
        # up, where the hanging strip never goes; at -x it would cut the swing's far end, and the
        # Jacobian's difference quotients across it would be 2 pi off.
        beta = np.unwrap(np.arctan2(dx, -dy), axis=0) - 0.5 * np.pi
        return dx, dy, np.hypot(dx, dy), beta, self.rotations @ beta

    def internal_force(self, q):
        """f = dU/dq [N] on the free coordinates, with theta at its equilibrium (dU/dtheta = 0);
        q of shape (size, ...)."""
        dx, dy, length, beta, theta = self.element_state(q)
        t_a, t_b = theta[:-1] - beta, theta[1:] - beta
        stretch = (length**2 - self.l0**2) / (length + self.l0)
        axial = YOUNGS_MODULUS * AREA * stretch / self.l0
        k = 2.0 * YOUNGS_MODULUS * SECOND_MOMENT / self.l0
        turn = k * 3.0 * (t_a + t_b) / length                 # (M_a + M_b) / l
        cos, sin = dx / length, dy / length
        # B rows for (x_a, y_a, x_b, y_b): u -> (-c, -s, c, s); t_a, t_b -> (-s/l, c/l, s/l, -c/l).
        fx = -axial * cos - turn * sin
        fy = -axial * sin + turn * cos
        f = np.zeros((self.nodes, 2) + q.shape[1:])
        f[:-1, 0] += fx
        f[:-1, 1] += fy
        f[1:, 0] -= fx
        f[1:, 1] -= fy
        return f[1:].reshape(q.shape)

    def stiffness(self, q):
        """K = df/dq [N/m] on the free coordinates at q (size,): the condensed energy's Hessian."""
        dx, dy, length, beta, _ = self.element_state(q)
        c, s = dx / length, dy / length
        axial = YOUNGS_MODULUS * AREA / self.l0
        force = axial * (length - self.l0)
        moment = self.bending @ beta
        # Per element the 2 x 2 Hessian in its chord d = (dx, dy): u'' n n^T + N (I - n n^T) / l +
        # (S beta)_e d^2 beta / dd^2, with d^2 beta / dd^2 = [[2cs, s^2 - c^2], [s^2 - c^2, -2cs]] / l^2.
        nn = np.stack([np.stack([c * c, c * s]), np.stack([c * s, s * s])])
        tt = np.stack([np.stack([s * s, -c * s]), np.stack([-c * s, c * c])])
        turn = np.stack([np.stack([2 * c * s, s * s - c * c]), np.stack([s * s - c * c, -2 * c * s])])
        local = axial * nn + force / length * tt + moment / length**2 * turn     # (2, 2, elements)
        n = 2 * self.nodes
        K = np.zeros((n, n))
        G = np.zeros((self.elements, n))
        for e in range(self.elements):
            a, b = 2 * e, 2 * e + 2
            block = local[:, :, e]
            K[a:a + 2, a:a + 2] += block
            K[b:b + 2, b:b + 2] += block
            K[a:a + 2, b:b + 2] -= block
            K[b:b + 2, a:a + 2] -= block
            grad = np.array([-s[e], c[e]]) / length[e]                           # dbeta_e / dd
            G[e, a:a + 2], G[e, b:b + 2] = -grad, grad
        K += G.T @ self.bending @ G
        return K[2:, 2:]

    def jacobian(self, t, z):
        """dz'/dz: [[0, I], [-M^-1 K, 0]]."""
        J = np.zeros((2 * self.size, 2 * self.size))
        J[:self.size, self.size:] = np.eye(self.size)
        J[self.size:, :self.size] = -self.inverse_mass[:, None] * self.stiffness(z[:self.size])
        return J

    def strain_energy(self, q):
        """U [J]."""
        _, _, length, beta, theta = self.element_state(q)
        t_a, t_b = theta[:-1] - beta, theta[1:] - beta
        return float(np.sum(0.5 * YOUNGS_MODULUS * AREA * (length - self.l0)**2 / self.l0
                            + YOUNGS_MODULUS * SECOND_MOMENT / self.l0 * 2.0 * (t_a**2 + t_a * t_b + t_b**2)))

    def energy(self, z):
        """Kinetic + strain + gravity [J] (gravity's zero at y = 0)."""
        q, v = z[:self.size], z[self.size:]
        return float(0.5 * np.sum(v * v / self.inverse_mass) + self.strain_energy(q) - self.gravity @ q)

    def rhs(self, t, z):
        """z' for z of shape (2 size,)."""
        q, v = z[:self.size], z[self.size:]
        return np.concatenate([v, self.inverse_mass * (self.gravity - self.internal_force(q))])

    def initial_state(self):
        q = np.zeros((self.elements, 2))
        q[:, 0] = self.l0 * np.arange(1, self.nodes)
        return np.concatenate([q.reshape(-1), np.zeros(self.size)])

    def outputs(self, z):
        """The swing angle theta_0 [rad] and the tip deflection in the pin's frame [m]."""
        q = z[:self.size]
        angle = self.element_state(q)[4][0]
        tip = self.positions(q)[-1]
        return angle, float(-math.sin(angle) * tip[0] + math.cos(angle) * tip[1])


def simulate(elements, times, rtol=RELATIVE_TOLERANCE):
    """Swing angle and tip deflection at `times`, the energy's largest drift and the statistics."""
    model = Pendulum(elements)
    # Absolute tolerances: 1e-8 m on coordinates, 1e-2 m/s on rates. Tighter ones make Radau
    # follow the mesh's highest bending and axial modes (to ~1e6 rad/s), which the release excites
    # by less than 1e-8 m, with ten times the steps: 1e-11 m moves the tip by 1.3e-6 m at 0.1 s
    # (80 elements), within the discretisation's error (`check`).
    atol = np.concatenate([np.full(model.size, 1e-8), np.full(model.size, 1e-2)])
    start = time.process_time()
    z0 = model.initial_state()
    solution = scipy.integrate.solve_ivp(model.rhs, (0.0, max(times)), z0, method="Radau", t_eval=times,
                                         rtol=rtol, atol=atol, jac=model.jacobian)
    if not solution.success:
        raise SystemExit(solution.message)
    cpu = time.process_time() - start
    angle, tip = zip(*(model.outputs(z) for z in solution.y.T))
    e0 = model.energy(z0)
    drift = max(abs(model.energy(z) - e0) for z in solution.y.T)
    return {"times": [float(t) for t in solution.t], "angle": [float(a) for a in angle], "tip": list(tip),
            "elements": elements, "rtol": rtol, "energy_drift_j": drift, "rhs_evaluations": int(solution.nfev),
            "cpu_seconds": round(cpu, 2)}


def stiffness_check(elements=80, step=1e-7):
    """The largest difference of stiffness() from central differences of the forces (all columns at
    once), relative to K's largest entry, at a bent strip turned by 1 rad and stretched."""
    model = Pendulum(elements)
    x = model.l0 * np.arange(1, model.nodes)
    y = 0.01 * np.sin(np.pi * x) + 1e-6 * x
    q = np.column_stack([x * math.cos(1.0) - y * math.sin(1.0), x * math.sin(1.0) + y * math.cos(1.0)]).reshape(-1)
    columns = np.eye(model.size) * step
    central = (model.internal_force(q[:, None] + columns) - model.internal_force(q[:, None] - columns)) / (2.0 * step)
    exact = model.stiffness(q)
    return float(np.max(np.abs(exact - central)) / np.max(np.abs(exact)))


def check():
    """The tip deflection's convergence over 0..0.3 s in the elements and the tolerance, and the
    Jacobian's stiffness against central differences; prints JSON."""
    times = [0.05 * k for k in range(7)]
    runs = {f"{n} elements": simulate(n, times) for n in (10, 20, 40, 80, ELEMENTS)}
    runs["40 elements, rtol 1e-9"] = simulate(40, times, 1e-9)
    finest = np.array(runs[f"{ELEMENTS} elements"]["tip"])
    report = {name: {"tip_mm": [round(w * 1e3, 6) for w in run["tip"]],
                     f"largest_tip_difference_to_{ELEMENTS}_m": float(np.max(np.abs(np.array(run["tip"]) - finest))),
                     "energy_drift_j": run["energy_drift_j"], "cpu_seconds": run["cpu_seconds"]}
              for name, run in runs.items()}
    report["stiffness_against_central_differences"] = stiffness_check()
    print(json.dumps(report, indent=1))


# `verify`: the stored table (reference.json, this script's output with its own settings) against a
# rerun of its first samples, relative to the window's largest |tip|. The rerun's steps end at the
# window's end, the table's did not: the two differ by the integration's tolerance (measured
# 4.8e-6 over 0.02 s, 1.7e-8 m; 2.4e-8 over 0.3 s). A larger difference means the script or the
# data changed.
VERIFY_TOLERANCE = 1e-4


def verify(stored, end_time):
    """Reruns the stored table to `end_time`; returns the exit status."""
    with open(stored) as f:
        table = json.load(f)
    times = [t for t in table["times"] if t <= end_time + 1e-12]
    rerun = simulate(table["elements"], times, table["rtol"])
    difference = max(abs(a - b) for a, b in zip(rerun["tip"], table["tip"]))
    largest = max(abs(b) for b in table["tip"][:len(times)])
    print(f"{stored}: {len(times)} samples to {times[-1]:g} s, largest tip difference {difference:.2e} m = "
          f"{difference / largest:.2e} of the largest |tip| {largest:.3e} m (limit {VERIFY_TOLERANCE:g})")
    return 0 if difference / largest <= VERIFY_TOLERANCE else 1


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("times", nargs="*", help="output times [s]; or `check`; or `verify STORED.json END_TIME`")
    parser.add_argument("--elements", type=int, default=ELEMENTS)
    parser.add_argument("--rtol", type=float, default=RELATIVE_TOLERANCE)
    args = parser.parse_args()
    if args.times[:1] == ["check"]:
        check()
        return
    if args.times[:1] == ["verify"]:
        sys.exit(verify(args.times[1], float(args.times[2])))
    print(json.dumps(simulate(args.elements, [float(t) for t in args.times], args.rtol)))


if __name__ == "__main__":
    main()
