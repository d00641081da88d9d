#!/usr/bin/python3
"""The spur pair of cases/10_gear_pair by ISO 21771's closed forms, with no flexmbs code.

Module 2 mm, 19 (x = 0.3) and 31 (x = -0.1) teeth, 20 deg basic rack (h_a* = 1, h_f* = 1.25),
face width 20 mm, centre distance 50.5 mm. `geometry()` gives base radii, the working pressure
angle, the path of contact and the contact ratio; `iso_stiffness()` ISO 6336-1:2019's single-pair
stiffness c' = c'_th C_M C_R C_B (method B, Table 8's C1 ... C9; C_M = 0.8, C_R = 1 for solid
wheels). Run as a script it prints the wheel's angle [rad] at which the positive flanks touch
with the pinion at 0 (the gap a sin(alpha_w) - r_b1 t1 - r_b2 t2 closed; docs/contact.md's
search, derived again here from the involutes' roll angles).
"""
import math

from scipy.optimize import brentq

MODULE, ALPHA, FACE_WIDTH, CENTRE = 2e-3, math.radians(20.0), 0.02, 0.0505
TEETH, SHIFT = (19, 31), (0.3, -0.1)
ADDENDUM, DEDENDUM = 1.0, 1.25


def inv(a):
    return math.tan(a) - a


def geometry():
    """Dict of the pair's radii [m], angles [rad], path of contact [m] and contact ratio."""
    r = [MODULE * z / 2 for z in TEETH]
    rb = [ri * math.cos(ALPHA) for ri in r]
    ra = [ri + MODULE * (ADDENDUM + x) for ri, x in zip(r, SHIFT)]
    psi_b = [MODULE * (math.pi / 2 + 2 * x * math.tan(ALPHA)) / (2 * ri) + inv(ALPHA) for ri, x in zip(r, SHIFT)]
    alpha_w = math.acos((rb[0] + rb[1]) / CENTRE)
    line = CENTRE * math.sin(alpha_w)
    tan_a = [math.sqrt((rai / rbi) ** 2 - 1) for rai, rbi in zip(ra, rb)]
    s_a, s_e = line - rb[1] * tan_a[1], rb[0] * tan_a[0]
    p_b = math.pi * MODULE * math.cos(ALPHA)
    alpha_w0 = brentq(lambda a: inv(a) - inv(ALPHA) - 2 * math.tan(ALPHA) * sum(SHIFT) / sum(TEETH), 1e-3, 1.2)
    return {"rb": rb, "ra": ra, "psi_b": psi_b, "alpha_w": alpha_w, "alpha_w0": alpha_w0, "line": line,
            "s_a": s_a, "s_e": s_e, "p_b": p_b, "contact_ratio": (s_e - s_a) / p_b}


def iso_stiffness():
    """ISO 6336-1 method B single-pair stiffness c' [N/m per m of face width]."""
    c = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182)
    (z1, z2), (x1, x2) = TEETH, SHIFT
    q = (c[0] + c[1] / z1 + c[2] / z2 + c[3] * x1 + c[4] * x1 / z1 + c[5] * x2 + c[6] * x2 / z2
         + c[7] * x1 ** 2 + c[8] * x2 ** 2)                     # mm um / N
    c_b = (1 + 0.5 * (1.2 - DEDENDUM)) * (1 - 0.02 * (20.0 - math.degrees(ALPHA)))
    return 1e9 / q * 0.8 * 1.0 * c_b                           # N/(mm um) = 1e9 N/m^2


def touching_wheel_angle():
    """Wheel 2's angle with the positive flanks touching at pinion angle 0 (tooth 0 of wheel 1)."""
    g = geometry()
    t1 = g["alpha_w"] + g["psi_b"][0]
    t2 = (g["line"] - g["rb"][0] * t1) / g["rb"][1]
    phi2 = t2 - g["alpha_w"] - math.pi - g["psi_b"][1]
    pitch = 2 * math.pi / TEETH[1]
    return phi2 - pitch * math.floor(phi2 / pitch)


if __name__ == "__main__":
    print(f"{touching_wheel_angle():.17g}")
