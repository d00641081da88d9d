"""The one machine-readable line each case's check script prints for bench/cases_summary.py.

    headline {"case": ..., "error": ..., "error_of": ..., "runtime_s": ..., "peer": ..., "peer_runtime_s": ...}

`error` is the case's headline error against its reference (relative unless `error_of` says
otherwise), `runtime_s` flexmbs' own time for the run it belongs to where the script knows it
(else None: the summary times the whole case), `peer` the independent code or closed form it
was checked against and `peer_runtime_s` that code's time where one ran.
"""
import json


def print_headline(case, error, error_of, runtime_s=None, peer=None, peer_runtime_s=None):
    """Prints the headline line (one line, `headline ` and a JSON object)."""
    print("headline " + json.dumps({"case": case, "error": float(error), "error_of": error_of,
                                    "runtime_s": runtime_s, "peer": peer, "peer_runtime_s": peer_runtime_s}))


def reduce_seconds(report):
    """flexmbs reduce --json's report -> its total time [s] (mesh, assembly, reduction, SID data)."""
    return sum(report["seconds"][part] for part in ("mesh", "assembly", "reduction", "sid"))
