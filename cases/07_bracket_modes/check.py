#!/usr/bin/python3
"""Checks what cases/07_bracket_modes/README.md says the case shows, on the files run.sh wrote.

Reads from OUT `flexmbs compare X.sid.h5 X.yaml --json` of both bodies (compare_modal.json,
compare_cb.json: each reduced body's system modes paired with the full FE model's, bolted at
base) and CalculiX's full model on the same mesh (full.ccx.json, tests/peers/ccx_modal.py). Checks:
- the full model's 12 frequencies (flexmbs) against CalculiX's;
- the modal body: its system modes are the full model's 12 lowest (frequency, MAC);
- the Craig-Bampton body: Rayleigh-Ritz upper bounds, the lowest five within 0.5 % and MAC >=
  0.999, the sixth within 2 %.
Writes a plot of each body's frequency error and MAC over the modes with --plot.

Usage: /usr/bin/python3 check.py OUT [--plot PNG]
Prints one line per check; exits 1 if any fails.
"""
import argparse
import json
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1]))
from headline import Checks, print_headline, pyplot, reduce_seconds, save_figure  # noqa: E402 (cases/headline.py)

# CalculiX prints 7 significant digits: measured 3.8e-7.
CALCULIX = 1e-6
# A modal body's system modes are its eigenpairs: measured 3.7e-12 (frequency), 1 - MAC < 1e-12.
MODAL = 1e-10
# Craig-Bampton, 6 constraint + 6 normal modes: modes 1-5 measured <= 1.74e-3 (MAC >= 0.99981),
# mode 6 9.1e-3.
CB_FIRST_FIVE, CB_FIRST_FIVE_MAC, CB_SIXTH = 5e-3, 0.999, 0.02


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("out", type=pathlib.Path)
    p.add_argument("--plot")
    a = p.parse_args()
    modal = json.loads((a.out / "compare_modal.json").read_text())["pairs"]
    cb = json.loads((a.out / "compare_cb.json").read_text())["pairs"]
    ccx = json.loads((a.out / "full.ccx.json").read_text())["frequencies_hz"]
    checks = Checks()
    check = checks.check

    full = [pair["frequency_b_hz"] for pair in modal]
    worst = max(abs(f / c - 1.0) for f, c in zip(full, ccx))
    check("full model = CalculiX", len(full) == len(ccx) == 12 and worst <= CALCULIX,
          f"12 modes {full[0]:.6g} .. {full[-1]:.6g} Hz, largest relative difference {worst:.1e}")
    worst = max(abs(pair["relative_error"]) for pair in modal)
    worst_mac = max(1.0 - pair["mac"] for pair in modal)
    check("modal body: the full model's 12 lowest modes", worst <= MODAL and worst_mac <= MODAL,
          f"largest frequency error {worst:.1e}, 1 - MAC {worst_mac:.1e}")
    errors = [pair["relative_error"] for pair in cb]
    check("Craig-Bampton: upper bounds of modes 1-9", min(errors[:9]) >= 0.0,
          ", ".join(f"{100 * e:+.3f} %" for e in errors[:9]))
    check("Craig-Bampton: modes 1-5", max(errors[:5]) <= CB_FIRST_FIVE
          and min(pair["mac"] for pair in cb[:5]) >= CB_FIRST_FIVE_MAC,
          f"largest error {100 * max(errors[:5]):.3f} %, smallest MAC {min(pair['mac'] for pair in cb[:5]):.5f}")
    check("Craig-Bampton: mode 6", errors[5] <= CB_SIXTH, f"{100 * errors[5]:+.2f} %")
    print_headline("07_bracket_modes", max(abs(e) for e in errors[:5]), "Craig-Bampton frequencies 1-5 against the full model",
                   runtime_s=reduce_seconds(json.loads((a.out / "bracket_cb.reduce.json").read_text())),
                   peer="CalculiX (C3D20), full model", peer_runtime_s=json.loads((a.out / "full.ccx.json").read_text())["seconds"])
    checks.finish(a.plot, lambda path: plot(path, modal, cb))


def plot(path, modal, cb):
    plt = pyplot()
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    n = range(1, len(cb) + 1)
    left.semilogy(n, [max(abs(pair["relative_error"]), 1e-16) for pair in modal], "o-", label="12 normal modes")
    left.semilogy(n, [max(abs(pair["relative_error"]), 1e-16) for pair in cb], "s-",
                  label="Craig-Bampton: 6 constraint + 6 normal")
    left.set_xlabel("mode of the full model (bolted at base)")
    left.set_ylabel("|frequency error|")
    left.legend(fontsize=8)
    left.grid(alpha=0.3, which="both")
    right.plot(n, [pair["mac"] for pair in modal], "o-", label="12 normal modes")
    right.plot(n, [pair["mac"] for pair in cb], "s-", label="Craig-Bampton")
    right.set_xlabel("mode")
    right.set_ylabel("MAC with the full model's mode")
    right.legend(fontsize=8)
    right.grid(alpha=0.3)
    fig.suptitle("L-bracket, hex20 14 583 DOF: reduced bodies of 12 columns against the full FE model")
    save_figure(fig, path)


if __name__ == "__main__":
    main()
