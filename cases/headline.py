"""The one machine-readable line each case's check script prints for bench/cases_summary.py, and
the rest those scripts share: their pass/fail lines and ending (Checks), their figures (pyplot,
save_figure).

    headline {"case": ..., "error": ..., "error_of": ..., "runtime_s": ..., "peer": ..., "peer_runtime_s": ...}

`error` is the case's headline error against its reference (relative unless `error_of` says
otherwise), `runtime_s` flexmbs' own time for the run it belongs to where the script knows it
(else None: the summary times the whole case), `peer` the independent code or closed form it
was checked against and `peer_runtime_s` that code's time where one ran.
"""
import json
import sys


def print_headline(case, error, error_of, runtime_s=None, peer=None, peer_runtime_s=None):
    """Prints the headline line (one line, `headline ` and a JSON object)."""
    print("headline " + json.dumps({"case": case, "error": float(error), "error_of": error_of,
                                    "runtime_s": runtime_s, "peer": peer, "peer_runtime_s": peer_runtime_s}))


def reduce_seconds(report):
    """flexmbs reduce --json's report -> its total time [s] (mesh, assembly, reduction, SID data)."""
    return sum(report["seconds"][part] for part in ("mesh", "assembly", "reduction", "sid"))


class Checks:
    """A check script's pass/fail lines and its end: the plot, then exit 1 if a check failed."""

    def __init__(self):
        self.failures = []

    def check(self, what, ok, detail):
        """Prints `ok   <what>: <detail>` or `FAIL <what>: <detail>`, remembering a failure."""
        print(f"{'ok  ' if ok else 'FAIL'} {what}: {detail}")
        if not ok:
            self.failures.append(what)

    def limits(self, values, limits):
        """One check a measure: values[name] <= limits[name]."""
        for name, value in values.items():
            self.check(name, value <= limits[name], f"{value:.3e} (limit {limits[name]:.1e})")

    def finish(self, plot_path=None, draw=None):
        """Draws the plot by draw(plot_path) where a path is given and says so; then, if any check
        failed, names them and exits 1, else says all passed."""
        if plot_path:
            draw(plot_path)
            print(f"wrote {plot_path}")
        if self.failures:
            print(f"{len(self.failures)} check(s) failed: {'; '.join(self.failures)}")
            sys.exit(1)
        print("all checks passed")


def pyplot():
    """matplotlib.pyplot on the Agg backend (PNG files, no display); imported when a plot is asked for."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def save_figure(fig, path, dpi=120):
    """Lays the figure out tightly and writes it to path."""
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
