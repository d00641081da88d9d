#!/usr/bin/python3
"""Reference for contact::WeberFlattening (tests/contact/gear_teeth_test.cc), independent of
flexmbs: the approach of a tooth's contact point and a point at depth h below it, integrated from
the stress field of a Hertzian line contact in plane strain along the load axis (McEwen 1949;
Johnson, Contact Mechanics, eq. 4.49):

  sigma_y = -p0 a / sqrt(a^2 + y^2),
  sigma_x = -p0 ((a^2 + 2 y^2) / (a sqrt(a^2 + y^2)) - 2 y / a),
  eps_y = ((1 - nu^2) sigma_y - nu (1 + nu) sigma_x) / E,   delta(h) = -int_0^h eps_y dy,

with a = sqrt(8 w R (1 - nu^2) / (pi E)), p0 = 2 w / (pi a); the two teeth's approaches add.
Prints the inputs and delta_1 + delta_2 [m] as JSON; with --stdin, delta_1 + delta_2 for each line
"w rho1 rho2 h1 h2" read (SI units).
"""
import json
import sys

import numpy as np
from scipy.integrate import quad

E, NU = 2.1e11, 0.3
W = 3e5                  # N/m
RHO1, RHO2 = 10e-3, 20e-3
H1, H2 = 3e-3, 4e-3


def approach(h, a, p0):
    def eps_y(y):
        s = np.sqrt(a * a + y * y)
        sy = -p0 * a / s
        sx = -p0 * ((a * a + 2 * y * y) / (a * s) - 2 * y / a)
        return ((1 - NU**2) * sy - NU * (1 + NU) * sx) / E
    return -quad(eps_y, 0.0, h, epsabs=0.0, epsrel=1e-13, limit=400)[0]


def flattening(w, rho1, rho2, h1, h2):
    r = rho1 * rho2 / (rho1 + rho2)
    a = np.sqrt(8 * w * r * (1 - NU**2) / (np.pi * E))
    p0 = 2 * w / (np.pi * a)
    return a, approach(h1, a, p0) + approach(h2, a, p0)


if len(sys.argv) > 1 and sys.argv[1] == "--stdin":
    # One "w rho1 rho2 h1 h2" a line (tests/contact/gear_teeth_test.cc's load-dependent pairs):
    # prints delta_1 + delta_2 [m] a line.
    for line in sys.stdin:
        if line.split():
            print("%.17g" % flattening(*(float(v) for v in line.split()))[1])
else:
    A, DELTA = flattening(W, RHO1, RHO2, H1, H2)
    print(json.dumps({"w": W, "rho": [RHO1, RHO2], "h": [H1, H2], "half_width": A,
                      "delta": DELTA}))
