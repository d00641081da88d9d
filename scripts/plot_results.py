"""A one-page summary and the pictures of a `flexmbs simulate` results file.

Reads only the datasets docs/results.md documents. Prints the run's termination, duration and
samples, the energies at start and end with the largest rise between two outputs, the
constraints' drift (the largest position and velocity residual, and at the end), where the run's
time went (statistics/: wall and CPU seconds of setup, integration and output, the contact
solves' CPU seconds and their share of the integration's), per joint the
largest force and torque, per contact the outputs it was active and sliding in and its summed
normal impulse, the events by kind, and per gear the mean mesh force, the pairs in contact and
the transmission error's range. Writes PNG files named after the results file:

  <stem>_energy.png            kinetic, potential and total energy over time
  <stem>_constraints.png       the constraints' position and velocity residuals over time (with joints)
  <stem>_modes_<body>.png      a flexible body's modal coordinates over time
  <stem>_contact_<c>.png       a contact's gap and its normal impulse per output interval (a force)
  <stem>_gear_<g>.png          a gear mesh's force, tooth pairs in contact, transmission error
                               (and elastic teeth's deflections)

Usage: /usr/bin/python3 scripts/plot_results.py results.h5 [--out DIR]
  --out DIR   where the PNG files go (default: the results file's folder)
Prints each written file as `wrote <path>`; exits 1 with one line if the file is not HDF5 or not a
flexmbs results file.
"""
import argparse
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after the backend is chosen)
import numpy as np  # noqa: E402


def text(value):
    """An HDF5 string attribute (fixed-length: bytes in h5py) as str."""
    return value.decode() if isinstance(value, bytes) else str(value)


def sample_count(f):
    """The number of complete samples: the shortest time series (docs/results.md, a killed run)."""
    lengths = [len(f["time"])]

    def visit(name, obj):
        top = name.split("/")[0]
        if isinstance(obj, h5py.Dataset) and top in ("energy", "constraints", "bodies", "joints", "contacts", "gears") \
                and not name.endswith("mode_names"):
            lengths.append(obj.shape[0])

    f.visititems(visit)
    return min(lengths)


def series(group, name, n):
    """The first n rows of a time series."""
    return group[name][:n]


def members(f, group):
    """The names in a top-level group, or none if the file has no such group."""
    return list(f[group].keys()) if group in f else []


def summarise_run(f, n):
    """Lines on the file's state, the time span and the energies."""
    t = series(f, "time", n)
    lines = [f"termination: {text(f.attrs['termination'])} (complete {int(f.attrs['complete'])})",
             f"duration: {t[0]:.6g} .. {t[-1]:.6g} s, {n} samples"]
    total = series(f, "energy/total", n)
    for name in ("kinetic", "potential", "total"):
        e = series(f, "energy/" + name, n)
        lines.append(f"energy {name}: start {e[0]:.9g} J, end {e[-1]:.9g} J")
    if n > 1:
        rise = np.diff(total)
        k = int(np.argmax(rise))
        lines.append(f"energy largest rise between outputs: {rise[k]:.3g} J at t = {t[k + 1]:.6g} s")
    return lines


def summarise_constraints(f, n):
    """The constraints' drift: the largest position and velocity residuals, their times, the end's."""
    if "constraints" not in f or not members(f, "joints"):
        return []
    t = series(f, "time", n)
    lines = []
    for name, unit in (("position", "m or rad"), ("velocity", "m/s or rad/s")):
        r = series(f["constraints"], f"{name}_residual", n)
        k = int(np.argmax(r))
        lines.append(f"constraint drift {name}: largest {r[k]:.3g} {unit} at t = {t[k]:.6g} s, end {r[-1]:.3g}")
    return lines


def summarise_statistics(f):
    """Where the run's time went: wall and CPU seconds per part (statistics/)."""
    if "statistics" not in f:
        return []
    g = f["statistics"]
    parts = [text(p) for p in g["parts"][:]]
    wall, cpu = g["wall_seconds"][:], g["cpu_seconds"][:]
    lines = [f"time {part}: wall {w:.4g} s, cpu {c:.4g} s" for part, w, c in zip(parts, wall, cpu)]
    if "contact_solve_cpu_seconds" in g:  # files written before it have the parts alone
        contact, integration = float(g["contact_solve_cpu_seconds"][()]), cpu[parts.index("integration")]
        share = f"{contact / integration:.3g}" if integration > 0 else "nan"
        lines.append(f"time contact solves: cpu {contact:.4g} s, {share} of the integration's cpu")
    return lines


def summarise_bodies(f, n):
    """Per flexible body its modes and largest modal coordinate."""
    lines = []
    for b in members(f, "bodies"):
        if text(f["bodies"][b].attrs["kind"]) != "flexible":
            continue
        q = series(f["bodies"][b], "modal_coordinates", n)
        lines.append(f"flexible body {b}: {q.shape[1]} modes, largest |q| {np.abs(q).max():.4g}")
    return lines


def summarise_joints(f, n):
    """Per joint the largest force and torque it applies."""
    lines = []
    for j in members(f, "joints"):
        g = f["joints"][j]
        force = np.linalg.norm(series(g, "force", n), axis=1)
        torque = np.linalg.norm(series(g, "torque", n), axis=1)
        lines.append(f"joint {j} ({text(g.attrs['type'])}): largest |force| {force.max():.6g} N, "
                     f"largest |torque| {torque.max():.6g} N m")
    return lines


def summarise_contacts(f, n):
    """Per contact the outputs it was active and sliding in, its summed impulse and smallest gap."""
    lines = []
    for c in members(f, "contacts"):
        g = f["contacts"][c]
        active = int(np.count_nonzero(series(g, "active", n)))
        sliding = int(np.count_nonzero(series(g, "sliding", n)))
        lines.append(f"contact {c} ({text(g.attrs['type'])}): active in {active} of {n} outputs, "
                     f"sliding in {sliding}, summed normal impulse "
                     f"{series(g, 'normal_impulse', n).sum():.9g} N s, "
                     f"smallest gap {series(g, 'gap', n).min():.4g} m")
    return lines


def summarise_events(f):
    """The events by kind, with the names of `kind_values` (`1 impact, 2 separation`)."""
    if "events" not in f:
        return []
    names = {}
    for item in text(f["events"].attrs["kind_values"]).split(","):
        value, name = item.split()
        names[int(value)] = name
    kind = f["events/kind"][:]
    counts = ", ".join(f"{name} {int(np.count_nonzero(kind == value))}" for value, name in sorted(names.items()))
    return [f"events: {len(kind)} ({counts})"]


def summarise_gears(f, n):
    """Per gear mesh the mean force, the pairs in contact and the transmission error's range."""
    lines = []
    for name in members(f, "gears"):
        g = f["gears"][name]
        pairs = series(g, "active_pairs", n)
        te = series(g, "transmission_error", n)
        lines.append(f"gear {name} ({text(g.attrs['type'])}): mean mesh force "
                     f"{series(g, 'mesh_force', n).mean():.6g} N, pairs in contact "
                     f"{int(pairs.min())} .. {int(pairs.max())}, transmission error "
                     f"{te.min():.6g} .. {te.max():.6g} rad")
    return lines


def save(fig, path):
    """Writes a figure and closes it."""
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    print(f"wrote {path}")


def plot_energy(f, n, path):
    """Kinetic, potential and total energy over time."""
    t = series(f, "time", n)
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for name in ("kinetic", "potential", "total"):
        ax.plot(t, series(f, "energy/" + name, n), label=name)
    ax.set(xlabel="time [s]", ylabel="energy [J]", title="energy")
    ax.legend()
    ax.grid(True)
    save(fig, path)


def plot_constraints(f, n, path):
    """The constraints' position and velocity residuals over time (log scale)."""
    fig, ax = plt.subplots(figsize=(7, 3.8))
    t = series(f, "time", n)
    for name, unit in (("position", "m or rad"), ("velocity", "m/s or rad/s")):
        r = series(f["constraints"], f"{name}_residual", n)
        ax.semilogy(t, np.maximum(r, 1e-300), label=f"{name} residual [{unit}]")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("largest constraint residual")
    ax.set_title("constraint drift")
    ax.legend()
    save(fig, path)


def plot_modes(f, n, body, path):
    """A flexible body's modal coordinates over time, one line per mode."""
    g = f["bodies"][body]
    t, q = series(f, "time", n), series(g, "modal_coordinates", n)
    mode_names = [text(m) for m in g["mode_names"][:]]
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for i in range(q.shape[1]):
        ax.plot(t, q[:, i], label=mode_names[i] if i < len(mode_names) else str(i))
    ax.set(xlabel="time [s]", ylabel="q", title=f"modal coordinates of {body}")
    if q.shape[1] <= 12:
        ax.legend(fontsize="small")
    ax.grid(True)
    save(fig, path)


def plot_contact(f, n, contact, path):
    """A contact's gap and its normal impulse over each output interval divided by the interval."""
    g = f["contacts"][contact]
    t = series(f, "time", n)
    fig, (gap_ax, force_ax) = plt.subplots(2, 1, sharex=True, figsize=(8, 6))
    gap_ax.plot(t, series(g, "gap", n))
    gap_ax.set(ylabel="gap g_N [m]", title=f"contact {contact}")
    gap_ax.grid(True)
    if n > 1:
        force_ax.plot(t[1:], series(g, "normal_impulse", n)[1:] / np.diff(t))
    force_ax.set(xlabel="time [s]", ylabel="normal impulse / interval [N]")
    force_ax.grid(True)
    save(fig, path)


def plot_gear(f, n, gear, path):
    """A gear mesh's force, tooth pairs in contact, transmission error and, with elastic teeth,
    both wheels' tooth deflections per pair slot over time."""
    g = f["gears"][gear]
    t = series(f, "time", n)
    panels = [("mesh_force", "mesh force [N]"), ("active_pairs", "pairs in contact"),
              ("transmission_error", "transmission error [rad]")]
    elastic = "tooth1_deflection" in g and np.any(series(g, "tooth1_deflection", n) != 0.0)
    if elastic:
        panels.append(("tooth1_deflection", "tooth deflection [um]"))
    fig, axes = plt.subplots(len(panels), 1, sharex=True, figsize=(8, 2.5 * len(panels)))
    for ax, (name, label) in zip(axes, panels):
        if name == "tooth1_deflection":
            for wheel, style in (("tooth1_deflection", "-"), ("tooth2_deflection", "--")):
                slots = series(g, wheel, n) * 1e6
                for k in range(slots.shape[1]):
                    if np.any(slots[:, k] != 0.0):
                        ax.plot(t, slots[:, k], style, label=f"wheel {wheel[5]}, slot {k}")
            ax.legend(fontsize="small", ncol=2)
        else:
            ax.plot(t, series(g, name, n), drawstyle="steps-post" if name == "active_pairs" else "default")
        ax.set(ylabel=label)
        ax.grid(True)
    axes[0].set_title(f"gear {gear}")
    axes[-1].set_xlabel("time [s]")
    save(fig, path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("results")
    parser.add_argument("--out", help="folder for the PNG files (default: the results file's)")
    args = parser.parse_args()
    out = args.out or os.path.dirname(os.path.abspath(args.results))
    os.makedirs(out, exist_ok=True)
    stem = os.path.join(out, os.path.splitext(os.path.basename(args.results))[0])
    try:
        f = h5py.File(args.results, "r")
    except OSError as error:
        print(f"{args.results}: cannot open as HDF5 ({error})", file=sys.stderr)
        return 1
    with f:
        if text(f.attrs.get("format", "")) != "flexmbs-results":
            print(f"{args.results}: not a flexmbs results file (attribute format)", file=sys.stderr)
            return 1
        n = sample_count(f)
        print(f"results: {args.results} (schema {int(f.attrs['schema_version'])})")
        for line in (summarise_run(f, n) + summarise_constraints(f, n) + summarise_statistics(f)
                     + summarise_bodies(f, n) + summarise_joints(f, n) + summarise_contacts(f, n)
                     + summarise_events(f) + summarise_gears(f, n)):
            print(line)
        plot_energy(f, n, stem + "_energy.png")
        if "constraints" in f and members(f, "joints"):
            plot_constraints(f, n, stem + "_constraints.png")
        for b in members(f, "bodies"):
            if text(f["bodies"][b].attrs["kind"]) == "flexible":
                plot_modes(f, n, b, f"{stem}_modes_{b}.png")
        for c in members(f, "contacts"):
            plot_contact(f, n, c, f"{stem}_contact_{c}.png")
        for g in members(f, "gears"):
            plot_gear(f, n, g, f"{stem}_gear_{g}.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
