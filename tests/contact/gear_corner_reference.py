#!/usr/bin/env python3
"""Independent reference for a spur pair's tip corners (tests/contact/gear_corner_test.cc).

The teeth are built here from ISO 21771's formulas alone, in polar form: wheel i's flank on side
sigma of tooth k at radius r (r_b <= r <= r_a) lies at the polar angle

    phi_i + 2 pi k / z_i + sigma (psi_b - inv(acos(r_b / r)))   (about the wheel's centre),

psi_b = (pi/2 + 2 x tan(alpha)) / z + inv(alpha) half the base thickness as an angle; wheel 1's
centre at the origin, wheel 2's at (a, 0); a tooth's tip corner is its flank at r = r_a.

Read from stdin, one item a line:
    pair m z1 x1 z2 x2 alpha h_a a
    corner side kind tooth1 tooth2 phi1 phi2     (kind 1: wheel 1's corner on wheel 2's flank,
                                                  2: wheel 2's on wheel 1's)
    start side kind tooth1 tooth2 delta phi1_lo phi1_hi
Prints per `corner`: the signed distance of the corner from the other tooth's flank (> 0 outside
the tooth), the nearest flank point and the flank's outward unit normal there, by brute force on
a polygon of 40001 points along the flank (the nearest point of its segments, the segment's
normal); per `start`: wheel 1's angle in [phi1_lo, phi1_hi] where the
corner meets the other flank (the tip circle cuts the involute: the polar angles agree at the
corner's radius, SciPy brentq), with wheel 2 lagging the rigid pair by delta along the line of
action (phi2 from the two involutes' crossings of the line of action, T1T2 = r_b1 t1 + r_b2 t2 +
delta, turning at -z1/z2 of wheel 1).
"""
import sys

import numpy as np
from scipy.optimize import brentq


def inv(angle):
    return np.tan(angle) - angle


class Wheel:
    def __init__(self, m, z, x, alpha, h_a):
        self.z = z
        self.r_b = m * z / 2.0 * np.cos(alpha)
        self.r_a = m * (z / 2.0 + h_a + x)
        self.psi_b = (np.pi / 2.0 + 2.0 * x * np.tan(alpha)) / z + inv(alpha)

    def flank_angle(self, r, sigma, tooth, phi):
        """The polar angle of the flank at radius r about the wheel's centre."""
        return (phi + 2.0 * np.pi * tooth / self.z +
                sigma * (self.psi_b - inv(np.arccos(np.clip(self.r_b / r, -1.0, 1.0)))))

    def flank(self, sigma, tooth, phi, centre, n=40001):
        # Radii spaced so that each segment turns the tangent by the same angle (the involute's
        # curvature 1 / (r_b t) at r = r_b sqrt(1 + t^2)): the chord's sag stays ~1e-12 m.
        t = np.linspace(0.0, np.sqrt((self.r_a / self.r_b) ** 2 - 1.0), n)
        r = self.r_b * np.sqrt(1.0 + t * t)
        theta = self.flank_angle(r, sigma, tooth, phi)
        return centre + np.column_stack((r * np.cos(theta), r * np.sin(theta)))

    def corner(self, sigma, tooth, phi, centre):
        theta = self.flank_angle(self.r_a, sigma, tooth, phi)
        return centre + self.r_a * np.array([np.cos(theta), np.sin(theta)])


def signed_distance(point, wheel, sigma, tooth, phi, centre):
    """Distance of `point` from the polygon of the flank; > 0 on the flank's outward side."""
    poly = wheel.flank(sigma, tooth, phi, centre)
    a, b = poly[:-1], poly[1:]
    d = b - a
    s = np.clip(np.einsum('ij,ij->i', point - a, d) / np.einsum('ij,ij->i', d, d), 0.0, 1.0)
    foot = a + s[:, None] * d
    dist = np.linalg.norm(point - foot, axis=1)
    k = int(np.argmin(dist))
    q = foot[k]
    rel = q - centre
    e_theta = np.array([-rel[1], rel[0]]) / np.linalg.norm(rel)  # +theta at the foot
    sign = 1.0 if np.dot(point - q, sigma * e_theta) > 0.0 else -1.0
    # The segment's normal (the corner may sit on the flank, where point - q has no direction),
    # turned out of the tooth.
    normal = np.array([-d[k][1], d[k][0]]) / np.linalg.norm(d[k])
    if np.dot(normal, sigma * e_theta) < 0.0:
        normal = -normal
    return sign * dist[k], q, normal


def lagged_phi2(w1, w2, a, sigma, tooth1, tooth2, phi1, delta):
    """Wheel 2's angle with tooth2's flank delta into tooth1's along the line of action."""
    alpha_w = np.arccos((w1.r_b + w2.r_b) / a)
    t1 = alpha_w + sigma * (phi1 + 2.0 * np.pi * tooth1 / w1.z) + w1.psi_b
    t1 = np.remainder(t1 + np.pi, 2.0 * np.pi) - np.pi  # the roll itself, not 2 pi on
    t2 = a * np.sin(alpha_w) + delta - w1.r_b * t1
    t2 /= w2.r_b
    # t2 = alpha_w + pi + sigma (phi2 + 2 pi k2 / z2) + psi_b2 (the involute's string on the line)
    return sigma * (t2 - alpha_w - np.pi - w2.psi_b) - 2.0 * np.pi * tooth2 / w2.z


def main():
    w1 = w2 = a = None
    out = []
    for line in sys.stdin:
        f = line.split()
        if not f:
            continue
        if f[0] == 'pair':
            m, z1, x1, z2, x2, alpha, h_a, a = (float(v) for v in f[1:])
            w1 = Wheel(m, int(z1), x1, alpha, h_a)
            w2 = Wheel(m, int(z2), x2, alpha, h_a)
            o2 = np.array([a, 0.0])
        elif f[0] == 'corner':
            sigma, kind, k1, k2 = (int(v) for v in f[1:5])
            phi1, phi2 = float(f[5]), float(f[6])
            if kind == 2:
                p = w2.corner(sigma, k2, phi2, o2)
                g, q, n = signed_distance(p, w1, sigma, k1, phi1, np.zeros(2))
            else:
                p = w1.corner(sigma, k1, phi1, np.zeros(2))
                g, q, n = signed_distance(p, w2, sigma, k2, phi2, o2)
            out.append('%.17g %.17g %.17g %.17g %.17g' % (g, q[0], q[1], n[0], n[1]))
        elif f[0] == 'start':
            sigma, kind, k1, k2 = (int(v) for v in f[1:5])
            delta, lo, hi = (float(v) for v in f[5:8])

            def meet(phi1):
                phi2 = lagged_phi2(w1, w2, a, sigma, k1, k2, phi1, delta)
                if kind == 2:  # wheel 2's corner against wheel 1's flank, about O1
                    p = w2.corner(sigma, k2, phi2, o2)
                    theta = np.arctan2(p[1], p[0])
                    flank = w1.flank_angle(np.linalg.norm(p), sigma, k1, phi1)
                else:  # wheel 1's corner against wheel 2's flank, about O2
                    p = w1.corner(sigma, k1, phi1, np.zeros(2)) - o2
                    theta = np.arctan2(p[1], p[0])
                    flank = w2.flank_angle(np.linalg.norm(p), sigma, k2, phi2)
                # > 0: the corner outside the flank (on its sigma side)
                return sigma * np.remainder(theta - flank + np.pi, 2.0 * np.pi) - sigma * np.pi

            out.append('%.17g' % brentq(meet, lo, hi, xtol=1e-16, rtol=1e-15))
    print('\n'.join(out))


if __name__ == '__main__':
    main()
