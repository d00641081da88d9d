"""What case 06's scripts read from a beam run's results file: the stop's impulse per output
interval and the tip's displacement (compare.py, planar.py, step_sweep.py)."""
import h5py
import numpy as np

from results_frames import rotation  # cases/results_frames.py (compare.py puts cases/ on the path)

MASS, SPEED, STEP = 7.536, 1.0, 1e-6     # the beam [kg] (rho V), its speed [m/s], the case's step [s]
P_CM_B = np.array([0.3, 0.02, 0.02])       # its centre of mass in B [m] (meshes/beam_stop.geo)
P_CM_B_PLANAR = np.array([0.3, 0.02, 0.0])  # the same beam posed for the plane (beam_planar.geo)


def momentum_impulses(f, p_cm_b=P_CM_B):
    """Per output interval, the beam's momentum gained along +y: the stop's impulse [N s]."""
    v = f["bodies/beam/velocity"][:]
    w = f["bodies/beam/angular_velocity"][:]
    e = f["bodies/beam/orientation"][:]
    v_cm = np.array([v[k] + rotation(e[k]) @ np.cross(w[k], p_cm_b) for k in range(len(v))])
    return MASS * np.diff(v_cm[:, 1])


def stop_impulses(f, formulation, p_cm_b=P_CM_B):
    """The stop's impulse per output interval [N s]: the LCP runs' own contact impulses, the
    penalty run's momentum change."""
    if formulation == "penalty":
        return momentum_impulses(f, p_cm_b)
    return f["contacts/stop/normal_impulse"][1:]


def history_error(a, b):
    """The largest difference of the impulse transferred up to an interval, in units of m v."""
    return np.abs(np.cumsum(a) - np.cumsum(b)).max() / (MASS * SPEED)


def tip_y(f, sid_path):
    """y_W [m] of the beam's tip per output: the mean over the pad's nodes at x = L (the far
    edge, mirror pairs on a posed mesh), rigid motion and the modes of the results file."""
    with h5py.File(sid_path, "r") as sid:
        nodes = sid["mesh/node_positions"][:]
        phi = sid["modes/phi"][:]
        sid_names = [n.decode() for n in sid["refmod/mode_names"][:]]
    pad = nodes[:, 0] > nodes[:, 0].max() - 1e-9
    pad &= np.abs(nodes[:, 1]) < 1e-9
    names = [n.decode() for n in f["bodies/beam/mode_names"][:]]
    columns = [sid_names.index(n) for n in names]
    p_tip_B = nodes[pad].mean(axis=0)
    phi_tip = phi.reshape(len(nodes), 3, -1)[pad][:, :, columns].mean(axis=0)
    q = f["bodies/beam/modal_coordinates"][:]
    r = f["bodies/beam/position"][:]
    e = f["bodies/beam/orientation"][:]
    return np.array([r[k, 1] + (rotation(e[k]) @ (p_tip_B + phi_tip @ q[k]))[1] for k in range(len(r))])
