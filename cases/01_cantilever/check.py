"""Checks what cases/01_cantilever/README.md says the case shows, on the files run.sh wrote.

Reads `flexmbs mesh --json` of beam.yaml and `flexmbs info --json` of both reduced bodies (run.sh
writes them to OUT as beam.mesh.json, beam.info.json, beam_cb.info.json) and checks:
- mass, centre of mass and inertia about it against the box's closed form (rho L b h, ...);
- beam.sid.h5's clamped bending frequencies within 0.5 % of Euler-Bernoulli, and equal to the
  README's measured values to their printed digits;
- beam_cb.sid.h5: 14 modes, the 6-DOF `tip` marker at the tip centre, the `top` contact surface
  (2017 vertices, 3224 polygons, 0.01 m^2), 1 % modal damping, the geometric stiffening.

Usage: /usr/bin/python3 check.py OUT
Prints one line per check; exits 1 if any fails.
"""
import json
import math
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from headline import Checks, print_headline  # noqa: E402 (cases/headline.py)

E, RHO, LENGTH, SIDE = 2.1e11, 7850.0, 1.0, 0.01
# beta_n L of a clamped-free Euler-Bernoulli beam (roots of cos(x) cosh(x) = -1).
BETA_L = [1.8751040687, 4.6940911330, 7.8547574382, 10.9955407349]
# The README's bound: discretisation plus beam-theory modelling error (shear, rotary inertia).
EULER_BERNOULLI = 0.005
# The README's measured frequencies [Hz], each printed to 5 significant digits.
README_MEASURED_HZ = [8.3596, 52.365, 146.52, 286.81]
# Mass properties of a box meshed exactly: round-off of the element integration (measured
# 3e-12 relative, I_xx).
MASS_ROUND_OFF = 3e-11


def euler_bernoulli_hz(n):
    inertia, area = SIDE**4 / 12.0, SIDE * SIDE
    beta = BETA_L[n] / LENGTH
    return beta * beta / (2.0 * math.pi) * math.sqrt(E * inertia / (RHO * area))


def main():
    out = pathlib.Path(sys.argv[1])
    mesh = json.loads((out / "beam.mesh.json").read_text())
    beam = json.loads((out / "beam.info.json").read_text())
    cb = json.loads((out / "beam_cb.info.json").read_text())
    checks = Checks()
    check = checks.check

    mass = RHO * LENGTH * SIDE * SIDE
    inertia = [mass * 2 * SIDE**2 / 12.0, mass * (LENGTH**2 + SIDE**2) / 12.0, mass * (LENGTH**2 + SIDE**2) / 12.0]
    check("mass", abs(mesh["mass_kg"] / mass - 1.0) <= MASS_ROUND_OFF, f"{mesh['mass_kg']:.12g} kg, rho L b h = {mass:g}")
    com = [LENGTH / 2, SIDE / 2, SIDE / 2]
    check("centre of mass", all(abs(c - e) <= MASS_ROUND_OFF * LENGTH for c, e in zip(mesh["center_of_mass_m"], com)),
          f"{mesh['center_of_mass_m']} m")
    J = mesh["inertia_about_com_kg_m2"]
    check("inertia about the CoM",
          all(abs(J[i][i] / inertia[i] - 1.0) <= MASS_ROUND_OFF for i in range(3))
          and all(abs(J[i][j]) <= MASS_ROUND_OFF * inertia[1] for i in range(3) for j in range(3) if i != j),
          f"diagonal {[J[i][i] for i in range(3)]} kg m^2, closed form {inertia}")

    f = beam["frequency_hz"]
    check("beam.sid.h5 modes", len(f) == 8 and beam["modes"]["normal"] == 8, f"{len(f)} frequencies")
    for n in range(4):
        exact = euler_bernoulli_hz(n)
        for f_n in f[2 * n:2 * n + 2]:
            check(f"bending {n + 1} against Euler-Bernoulli", abs(f_n / exact - 1.0) <= EULER_BERNOULLI,
                  f"{f_n:.6g} Hz vs {exact:.6g} Hz: {100 * (f_n / exact - 1.0):+.3f} %")
        printed = README_MEASURED_HZ[n]
        digits = 5 - 1 - math.floor(math.log10(printed))
        check(f"bending {n + 1} as the README prints it", round(f[2 * n], digits) == printed,
              f"{f[2 * n]:.6g} Hz, README {printed}")

    print_headline("01_cantilever", max(abs(f[k] / euler_bernoulli_hz(k // 2) - 1.0) for k in range(8)),
                   "bending frequencies 1-4 against Euler-Bernoulli", peer="Euler-Bernoulli (closed form)")
    check("beam_cb.sid.h5 modes", cb["modes"]["total"] == 14, f"{cb['modes']}")
    tip = [m for m in cb["nodes"] if m["name"] == "tip"]
    check("tip marker", len(tip) == 1 and tip[0]["coupling"] == "rigid"
          and all(abs(p - e) <= 1e-12 for p, e in zip(tip[0]["position_m"], [LENGTH, SIDE / 2, SIDE / 2])),
          f"{tip}")
    top = [s for s in cb["surfaces"] if s["name"] == "top"]
    check("top contact surface", len(top) == 1 and top[0]["vertices"] == 2017 and top[0]["faces"] == 3224
          and abs(top[0]["area_m2"] / (LENGTH * SIDE) - 1.0) <= MASS_ROUND_OFF, f"{top}")
    check("damping", cb["damping"] == "modal 1 %", cb["damping"])
    check("geometric stiffening", cb["stiffening"] is True, str(cb["stiffening"]))
    checks.finish()


if __name__ == "__main__":
    main()
