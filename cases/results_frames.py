"""Frames from a flexmbs results file, shared by the cases' compare scripts (06, 08).

`bodies/<b>/orientation` holds R_WB as Euler parameters (e0, e1, e2, e3) (docs/results.md).
"""
import numpy as np


def rotation(e):
    """R_WB of the Euler parameters e = (e0, e1, e2, e3) (unit norm)."""
    e0, e1, e2, e3 = e
    return np.array([
        [1 - 2 * (e2 * e2 + e3 * e3), 2 * (e1 * e2 - e0 * e3), 2 * (e1 * e3 + e0 * e2)],
        [2 * (e1 * e2 + e0 * e3), 1 - 2 * (e1 * e1 + e3 * e3), 2 * (e2 * e3 - e0 * e1)],
        [2 * (e1 * e3 - e0 * e2), 2 * (e2 * e3 + e0 * e1), 1 - 2 * (e1 * e1 + e2 * e2)]])
