#!/usr/bin/python3
"""An independent evaluation of the IVP Test Set problem 'crank' (B. Simeon's flexible slider
crank) for tests/validation/simeon_crank_test.cc. Written here from the equations of crank.f
(the Test Set's source; copies in tpetzoldt/deSolve pkg/daeSolve/src/Ex_crank.f and, with the
reference solution SOLN and the initial values INIT, fons/JavaOdeInt
fodeint/mebdfi/txt/cranki.f), not ported from it.

The model (crank.f, default ipar = (0, 0): linear stiffness, no damping). Coordinates
p = (phi1, phi2, x3, q1, q2, q3, q4): crank angle, rod angle, slider position, modal
coordinates of the rod in a frame with its origin at the crank pin A and x along phi2 (the
rod's other end B lies on that axis: both lateral shapes vanish there). Shapes over
xi = x / L2: lateral sin(pi xi), sin(2 pi xi) (q1, q2); axial quadratic 4 xi (1 - xi),
xi (2 xi - 1) (q3: the midpoint's, q4: B's axial displacement). Constraints: B on the x axis,
(L2 + q4) sin(phi2) + L1 sin(phi1) = 0; the slider at B, x3 = L1 cos(phi1) + (L2 + q4) cos(phi2);
phi1 = 150 t. Kinetic energy: the crank's J1 phi1'^2 / 2, the slider's M3 x3'^2 / 2 and the rod's
int |v_A + w x (r + u) + u'|^2 dm / 2 (a slender rod, dm = rho A dx; J2 holds its section's
rotary inertia M2 H^2 / 12 too); elastic energy q^T KQ q / 2.

It prints:
1. the rod's integrals from the shapes by Gauss quadrature against crank.f's closed forms:
   crank.f evaluates pi as 3.1415927 and its axial mass block MQ(3:4, 3:4) = rho A L2 [8 1; 1 2]
   is 15 times the consistent one (rho A L2 [8 1; 1 2] / 15), while its first moments c1, c12
   and the coupling BQ are the consistent integrals;
2. crank.f's mass matrix and forces against Lagrange's equations of that kinetic energy
   (sympy): equal to round-off, so the model is an exact planar floating-frame body with full
   inertia coupling, for the integrals as crank.f gives them;
3. INIT's consistency: it violates the slider's position constraint by 2.03e-10 m
   (x3 - L1 - L2 - q4, INIT being rounded to 9 digits) and the velocity constraint by
   1.19e-8 m/s; and the solution at t = 0.1 s from INIT projected like flexmbs does (positions,
   then velocities, onto the constraints by the smallest change in the kinetic metric), by
   DOP853 (index-1 form, rtol 1e-13), against SOLN: the 16-digit values the C++ test compares
   flexmbs with;
4. how far other choices move that solution: the consistent axial mass, the true pi, and
   another repair of INIT (x3 alone moved onto the constraint).

Usage: simeon_crank_reference.py   (about 5 minutes)
"""
import numpy as np
import sympy as sp
from numpy.polynomial.legendre import leggauss
from scipy.integrate import solve_ivp

PI_S = 3.1415927  # crank.f's PI
M1, M2, M3 = 0.36, 0.151104, 0.075552
L1, L2 = 0.15, 0.30
J1, J2 = 0.002727, 0.0045339259
E, B, H, RHO = 0.2e12, 0.008, 0.008, 7870.0
OMEGA = 150.0
A = B * H
MU = RHO * A

INIT = np.array([0.0, 0.0, .450016933, 0.0, 0.0, .103339863e-04, .169327969e-04,
                 150.0, -.749957670e+02, -.268938672e-05, .444896105e+00, .463434311e-02, -.178591076e-05,
                 -.268938672e-05,
                 0.0, -1.344541576008661e-03, -5.062194923138079e+03, -6.833142732779555e-05,
                 1.449382650173157e-08, -4.268463211410861e+00, 2.098334687947376e-01,
                 -6.397251492537153e-08, 3.824589508329281e+02, -4.376060460948886e-09])
SOLN = np.array([1.500000000000000e+01, -3.311734987910881e-01, 1.697373326718410e-01, 1.893192460247178e-04,
                 2.375751865617931e-05, -5.323907988763734e-06, -8.363283141616840e-06, 1.500000000000000e+02,
                 6.025346682645789e+01, -8.753116989887888e+00, -3.005536801092212e-02, -5.500488291932075e-03,
                 4.978243404809343e-04, 1.104933470696396e-03, 0.0, 6.488722210234531e+03, 2.167924253080623e+03,
                 3.391435115267547e+01, 1.699107480197843e-01, -1.415799354959001e+00, 9.903251655235532e-01,
                 -6.232893262533717e+01, -1.637910131687472e+02, 2.529853213732781e+01])
NAMES = ["phi1", "phi2", "x3", "q1", "q2", "q3", "q4", "phi1'", "phi2'", "x3'", "q1'", "q2'", "q3'", "q4'",
         "phi1''", "phi2''", "x3''", "q1''", "q2''", "q3''", "q4''", "lambda1", "lambda2", "lambda3"]


def quadrature_integrals(pi=np.pi, points=40):
    """The rod's integrals over the shapes (per unit rho where crank.f has them so)."""
    x, w = leggauss(points)
    xi, w = 0.5 * (x + 1), 0.5 * w
    z = np.zeros_like(xi)
    ax = np.array([z, z, 4 * xi * (1 - xi), xi * (2 * xi - 1)])
    la = np.array([np.sin(pi * xi), np.sin(2 * pi * xi), z, z])
    return dict(MQ=MU * L2 * ((ax * w) @ ax.T + (la * w) @ la.T), c1=A * L2 * (ax @ w), c2=A * L2 * (la @ w),
                c12=A * L2**2 * (ax @ (w * xi)), c21=A * L2**2 * (la @ (w * xi)),
                BQ=A * L2 * ((ax * w) @ la.T - (la * w) @ ax.T))


def crank_integrals(pi=PI_S, axial_mass_scale=15.0):
    """crank.f's closed forms; axial_mass_scale 15 is crank.f's axial mass block, 1 the consistent one."""
    facm, fack, facb = RHO * A * L2, E * A / L2, A * L2
    MQ, KQ, BQ = np.zeros((4, 4)), np.zeros((4, 4)), np.zeros((4, 4))
    MQ[0, 0] = MQ[1, 1] = 0.5 * facm
    MQ[2:, 2:] = axial_mass_scale * facm * np.array([[8, 1], [1, 2]]) / 15.0
    KQ[0, 0] = fack * pi**4 / 24 * (H / L2)**2
    KQ[1, 1] = fack * pi**4 * 2 / 3 * (H / L2)**2
    KQ[2:, 2:] = fack * np.array([[16 / 3, -8 / 3], [-8 / 3, 7 / 3]])
    BQ[0, 2] = -facb * 16 / pi**3
    BQ[0, 3] = facb * (8 / pi**3 - 1 / pi)
    BQ[1, 3] = facb * 0.5 / pi
    return dict(MQ=MQ, KQ=KQ, BQ=BQ - BQ.T, c1=facb * np.array([0, 0, 2 / 3, 1 / 6]),
                c2=facb * np.array([2 / pi, 0, 0, 0]), c12=L2 * facb * np.array([0, 0, 1 / 3, 1 / 6]),
                c21=L2 * facb * np.array([1 / pi, -0.5 / pi, 0, 0]))


def mass_and_forces(p, v, inv):
    """crank.f's M(p) and f(p, v) (M a = f - G^T lambda)."""
    MQ, KQ, BQ, c1, c2, c12, c21 = (inv[k] for k in ("MQ", "KQ", "BQ", "c1", "c2", "c12", "c21"))
    q, qd = p[3:], v[3:]
    w1, w2 = v[0], v[1]
    s, c = np.sin(p[0] - p[1]), np.cos(p[0] - p[1])
    M = np.zeros((7, 7))
    M[0, 0] = J1 + M2 * L1**2
    M[0, 1] = 0.5 * L1 * L2 * M2 * c + RHO * L1 * (s * c2 @ q + c * c1 @ q)
    M[1, 1] = J2 + q @ MQ @ q + 2 * RHO * c12 @ q
    M[2, 2] = M3
    M[0, 3:] = RHO * L1 * (-s * c1 + c * c2)
    M[1, 3:] = RHO * c21 + RHO * (q @ BQ)
    M[3:, 3:] = MQ
    M = np.triu(M) + np.triu(M, 1).T
    f = np.zeros(7)
    f[0] = (-0.5 * L1 * L2 * M2 * w2**2 * s + RHO * L1 * w2**2 * (-s * c1 @ q + c * c2 @ q)
            - 2 * RHO * L1 * w2 * (c * c1 @ qd + s * c2 @ qd))
    f[1] = (0.5 * L1 * L2 * M2 * w1**2 * s + RHO * L1 * w1**2 * (s * c1 @ q - c * c2 @ q)
            - 2 * RHO * w2 * c12 @ qd - 2 * w2 * qd @ MQ @ q - RHO * qd @ BQ @ qd)
    f[3:] = (w2**2 * MQ @ q + RHO * (w2**2 * c12 + L1 * w1**2 * (c * c1 + s * c2) + 2 * w2 * BQ @ qd) - KQ @ q)
    return M, f


def position_constraints(p, t):
    return np.array([L1 * np.sin(p[0]) + (L2 + p[6]) * np.sin(p[1]),
                     p[2] - L1 * np.cos(p[0]) - (L2 + p[6]) * np.cos(p[1]), p[0] - OMEGA * t])


def constraint_jacobian(p, v):
    """G (3 x 7), g_t and the bias of g'': G a + bias = 0 on the motion."""
    G = np.zeros((3, 7))
    G[0, 0], G[0, 1], G[0, 6] = L1 * np.cos(p[0]), (L2 + p[6]) * np.cos(p[1]), np.sin(p[1])
    G[1, 0], G[1, 1], G[1, 2], G[1, 6] = L1 * np.sin(p[0]), (L2 + p[6]) * np.sin(p[1]), 1.0, -np.cos(p[1])
    G[2, 0] = 1.0
    w1, w2, q4d = v[0], v[1], v[6]
    bias = np.array([-L1 * np.sin(p[0]) * w1**2 - (L2 + p[6]) * np.sin(p[1]) * w2**2 + 2 * w2 * np.cos(p[1]) * q4d,
                     L1 * np.cos(p[0]) * w1**2 + (L2 + p[6]) * np.cos(p[1]) * w2**2 + 2 * w2 * np.sin(p[1]) * q4d,
                     0.0])
    return G, np.array([0.0, 0.0, -OMEGA]), bias


def accelerations(p, v, inv):
    M, f = mass_and_forces(p, v, inv)
    G, _, bias = constraint_jacobian(p, v)
    sol = np.linalg.solve(np.block([[M, G.T], [G, np.zeros((3, 3))]]), np.concatenate([f, -bias]))
    return sol[:7], sol[7:]


def project(y, inv, t=0.0):
    """Positions onto g = 0 (Gauss-Newton), then velocities onto G v + g_t = 0, each by the
    smallest change in the kinetic metric M (flexmbs's MakeConsistent)."""
    p, v = y[:7].copy(), y[7:].copy()
    for _ in range(6):
        M, _ = mass_and_forces(p, v, inv)
        G, _, _ = constraint_jacobian(p, v)
        MiGt = np.linalg.solve(M, G.T)
        p -= MiGt @ np.linalg.solve(G @ MiGt, position_constraints(p, t))
    M, _ = mass_and_forces(p, v, inv)
    G, g_t, _ = constraint_jacobian(p, v)
    MiGt = np.linalg.solve(M, G.T)
    v -= MiGt @ np.linalg.solve(G @ MiGt, G @ v + g_t)
    return np.concatenate([p, v])


def lagrange_check(inv, trials=5, seed=1):
    """Largest difference of crank.f's M and f from Lagrange's equations of the kinetic energy."""
    pos = list(sp.symbols("ph1 ph2 x3 q1:5"))
    vel = list(sp.symbols("w1 w2 x3d qd1:5"))
    ph1, ph2, w1, w2, x3d = pos[0], pos[1], vel[0], vel[1], vel[2]
    q, qd = sp.Matrix(pos[3:]), sp.Matrix(vel[3:])
    MQ, BQ = sp.Matrix(inv["MQ"]), sp.Matrix(inv["BQ"])
    c1, c2, c12, c21 = (sp.Matrix(inv[k]) for k in ("c1", "c2", "c12", "c21"))
    vA = L1 * w1 * sp.Matrix([-sp.sin(ph1), sp.cos(ph1)])
    R = sp.Matrix([[sp.cos(ph2), -sp.sin(ph2)], [sp.sin(ph2), sp.cos(ph2)]])
    Jm = sp.Matrix([[0, -1], [1, 0]])
    first = sp.Matrix([M2 * L2 / 2 + RHO * (c1.T * q)[0], RHO * (c2.T * q)[0]])   # int (r + u) dm in the frame
    first_rate = sp.Matrix([RHO * (c1.T * qd)[0], RHO * (c2.T * qd)[0]])          # int u' dm
    polar = J2 + 2 * RHO * (c12.T * q)[0] + (q.T * MQ * q)[0]                      # int |r + u|^2 dm
    half = sp.Rational(1, 2)
    T = (half * J1 * w1**2 + half * M2 * (vA.T * vA)[0] + (vA.T * R * (w2 * Jm * first + first_rate))[0]
         + half * w2**2 * polar + w2 * (RHO * (c21.T * qd)[0] + RHO * (q.T * BQ * qd)[0])
         + half * (qd.T * MQ * qd)[0] + half * M3 * x3d**2)
    V = half * (q.T * sp.Matrix(inv["KQ"]) * q)[0]
    Mexpr = sp.Matrix(7, 7, lambda i, j: sp.diff(T, vel[i], vel[j]))
    dTdv = [sp.diff(T, a) for a in vel]
    fexpr = [-(sum(sp.diff(dTdv[i], pos[j]) * vel[j] for j in range(7)) - sp.diff(T, pos[i])) - sp.diff(V, pos[i])
             for i in range(7)]
    Mf, ff = sp.lambdify([pos, vel], Mexpr, "numpy"), sp.lambdify([pos, vel], fexpr, "numpy")
    rng = np.random.default_rng(seed)
    worst_M = worst_f = 0.0
    for _ in range(trials):
        p = np.concatenate([rng.uniform(-3, 3, 3), rng.uniform(-1e-3, 1e-3, 4)])
        v = np.concatenate([rng.uniform(-150, 150, 3), rng.uniform(-1, 1, 4)])
        M, f = mass_and_forces(p, v, inv)
        M_l, f_l = np.array(Mf(p, v), float), np.array(ff(p, v), float)
        worst_M = max(worst_M, np.abs(M - M_l).max() / np.abs(M_l).max())
        worst_f = max(worst_f, np.abs(f - f_l).max() / np.abs(f_l).max())
    return worst_M, worst_f


def integrate(inv, y0, rtol=1e-13, atol=1e-16, t_end=0.1):
    """Index-1 form by DOP853; returns the 24 components at t_end (accelerations and
    multipliers from the equations there) and the number of steps."""
    def rhs(t, y):
        a, _ = accelerations(y[:7], y[7:], inv)
        return np.concatenate([y[7:], a])
    sol = solve_ivp(rhs, (0.0, t_end), y0, method="DOP853", rtol=rtol, atol=atol)
    y = sol.y[:, -1]
    a, lam = accelerations(y[:7], y[7:], inv)
    return np.concatenate([y, a, lam]), sol.t.size


def relative(a, b):
    return np.array([abs(a[k] - b[k]) / abs(b[k]) if b[k] != 0 else abs(a[k]) for k in range(24)])


def main():
    crank = crank_integrals()
    print("1. the rod's integrals by 40-point Gauss quadrature of the shapes (true pi) against crank.f "
          "(largest difference / largest entry):")
    quad = quadrature_integrals()
    for k in ("MQ", "BQ", "c1", "c2", "c12", "c21"):
        print(f"   {k:4s} {np.abs(quad[k] - crank[k]).max() / np.abs(crank[k]).max():.2e}")
    print("   crank.f's axial mass block / the consistent one:", (crank["MQ"][2:, 2:] / quad["MQ"][2:, 2:]).ravel())
    print(f"   crank.f's pi {PI_S} - pi = {PI_S - np.pi:.2e}: lateral stiffness x (1 + "
          f"{crank['KQ'][0, 0] / crank_integrals(pi=np.pi)['KQ'][0, 0] - 1:.2e})")
    for label, inv in (("crank.f", crank), ("consistent axial mass", crank_integrals(axial_mass_scale=1.0))):
        lam = np.linalg.eigvals(np.linalg.solve(inv["MQ"], inv["KQ"]))
        print(f"   rod frequencies with B held ({label}) [rad/s]:", np.sort(np.sqrt(lam.real)))

    worst_M, worst_f = lagrange_check(crank)
    print(f"2. crank.f against Lagrange's equations of the planar floating-frame kinetic energy: "
          f"M {worst_M:.1e}, f {worst_f:.1e} (relative to the largest entry)")

    a0, l0 = accelerations(INIT[:7], INIT[7:14], crank)
    G0, g_t0, _ = constraint_jacobian(INIT[:7], INIT[7:14])
    print("3. INIT: g =", position_constraints(INIT[:7], 0.0), " G v + g_t =", G0 @ INIT[7:14] + g_t0)
    print("   INIT's accelerations and multipliers against the equations' (largest difference):",
          np.abs(a0 - INIT[14:21]).max(), np.abs(l0 - INIT[21:]).max())
    y0 = project(INIT[:14], crank)
    print("   projected - INIT:", " ".join(f"{NAMES[k]}:{y0[k] - INIT[k]:.9e}" for k in range(14)))
    full, steps = integrate(crank, y0)
    coarse, _ = integrate(crank, y0, rtol=1e-12, atol=1e-15)
    step_error = relative(coarse, full)
    print(f"   t = 0.1 s (DOP853 rtol 1e-13, {steps} steps; 'step' = relative change from rtol 1e-12):")
    rel = relative(full, SOLN)
    for k in range(24):
        print(f"   {NAMES[k]:8s} {full[k]: .16e}  SOLN {SOLN[k]: .16e}  relative {rel[k]:.2e}  step {step_error[k]:.1e}")
    print("   constraints at t = 0.1 s: here", position_constraints(full[:7], 0.1)[:2],
          " SOLN", position_constraints(SOLN[:7], 0.1)[:2])

    variants = (("consistent axial mass (crank.f's block / 15)", crank_integrals(axial_mass_scale=1.0), y0),
                ("true pi in the integrals", crank_integrals(pi=np.pi), y0),
                ("INIT repaired by moving x3 alone, then velocities projected", crank,
                 project(np.concatenate([INIT[:2], [L1 + L2 + INIT[6]], INIT[3:14]]), crank)))
    for label, inv, start in variants:
        other, _ = integrate(inv, start, rtol=1e-12, atol=1e-15)
        change, vs_soln = relative(other, full), relative(other, SOLN)
        print(f"4. {label}: relative change / relative difference from SOLN")
        print("   " + " ".join(f"{NAMES[k]}:{change[k]:.1e}/{vs_soln[k]:.1e}" for k in range(24) if SOLN[k] != 0))


if __name__ == "__main__":
    main()
