#!/usr/bin/python3
"""One table of speed against error for every case in cases/, with the peer beside each row.

Runs each case's full mode (`cases/NN_name/run.sh FLEXMBS`, the main job's command) from the
repository's root, times it, keeps its output in cases/NN_name/out/summary.log and the time in
summary.json, and reads the one `headline` line its check script prints (cases/headline.py):
the headline error against the case's reference, flexmbs' own time where the script knows it,
the peer and the peer's time where one ran. With --reuse it reads the logs of an earlier run
instead of running. Prints a Markdown table; exit 1 if a case failed or printed no headline.

Usage: /usr/bin/python3 bench/cases_summary.py [--flexmbs build/bin/flexmbs] [--cases 01,09] [--reuse]
"""
import argparse
import json
import pathlib
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]


def run_case(folder, flexmbs, reuse):
    """(exit status, wall time [s], headline dict or None) of one case."""
    out = folder / "out"
    log, record = out / "summary.log", out / "summary.json"
    if reuse:
        if not record.exists():
            sys.exit(f"cases_summary.py: {record}: no earlier run to reuse (run without --reuse first)")
        status, seconds = json.loads(record.read_text()).values()
        text = log.read_text()
    else:
        out.mkdir(exist_ok=True)
        start = time.perf_counter()
        done = subprocess.run([str(folder / "run.sh"), flexmbs], cwd=ROOT, capture_output=True, text=True)
        status, seconds = done.returncode, time.perf_counter() - start
        text = done.stdout + done.stderr
        log.write_text(text)
        record.write_text(json.dumps({"status": status, "seconds": seconds}))
    lines = [line for line in text.splitlines() if line.startswith("headline ")]
    return status, seconds, json.loads(lines[-1][len("headline "):]) if lines else None


def seconds_cell(value):
    return "" if value is None else f"{value:.3g}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--flexmbs", default=str(ROOT / "build" / "bin" / "flexmbs"), help="the flexmbs binary")
    parser.add_argument("--cases", help="comma-separated case numbers (default: all)")
    parser.add_argument("--reuse", action="store_true", help="read the logs of an earlier run")
    args = parser.parse_args()
    flexmbs = str(pathlib.Path(args.flexmbs).resolve())
    folders = sorted(p for p in (ROOT / "cases").iterdir() if (p / "run.sh").is_file())
    if args.cases:
        wanted = set(args.cases.split(","))
        folders = [p for p in folders if p.name.split("_")[0] in wanted]
    print("| case | error | of | flexmbs [s] | case total [s] | peer | peer [s] | status |")
    print("|---|---:|---|---:|---:|---|---:|---|")
    failed = 0
    for folder in folders:
        status, seconds, headline = run_case(folder, flexmbs, args.reuse)
        ok = status == 0 and headline is not None
        failed += not ok
        h = headline or {}
        error = f"{h['error']:.2e}" if "error" in h else ""
        print(f"| {folder.name} | {error} | {h.get('error_of', 'no headline')} | {seconds_cell(h.get('runtime_s'))} | "
              f"{seconds:.3g} | {h.get('peer') or ''} | {seconds_cell(h.get('peer_runtime_s'))} | "
              f"{'ok' if ok else f'FAILED ({status})'} |", flush=True)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
