#!/usr/bin/python3
"""The speed-accuracy trade study of the Tippe-Top, run by `scripts/dev/tradeoff`.

Runs the headless `simulate` over a grid friction set x solver x dt x tolerance, a converged
reference per friction law (and the same reference with dt and tolerance halved, to show it is
converged), a sweep of the explicit against the implicit-midpoint gyroscopic term over dt*|omega|,
and two hour-long runs; then writes

    OUT/runs.csv              one row per run: settings, cost, accuracy figures
    OUT/runs/<id>.json        per run: settings, simulate's JSON summary, sampled theta(t)
    DOCS/tradeoff.md          the generated report
    DOCS/tradeoff_*.png       Pareto plots (time vs error) per friction set, reference curves

Accuracy figures of a grid run, against the reference of the SAME friction law, on common time
points (theta sampled every SAMPLE_DT from simulate's CSV):
    err_touchdown   |t(theta > 2.4 rad) - t_ref| [s] (peg touchdown; both absent counts 0)
    err_theta_05    max |theta - theta_ref| over the first THETA_WINDOW s [rad]
    err_energy_2    |E(2 s) - E_ref(2 s)| / E_ref(2 s)
    jellett_drift   |J(end) - J0| / |J0| at the end of the run (meaningful for coulomb: conserved
                    while only the big sphere touches); err_jellett = |drift - drift_ref|
    max_energy_increase  largest E(t+dt) - E(t) [J] (exact value 0)

Uses Debian's python3 with python3-matplotlib and numpy (never another interpreter). The work
is in scripts/dev/tradeoff_study/: grid.py (the grids, the run configurations), run.py (the runs and
their cache), analyse.py (accuracy, cost, orders, Pareto fronts), plots.py and report.py (runs.csv
and the page); this file reads the options and calls them in that order.

usage: tradeoff_report.py --simulate BIN [--grid full|quick] [--jobs N] [--out DIR] [--docs DIR]
                          [--report-only] [--rerun]
"""
import argparse
import os
import subprocess
import sys

from tradeoff_study.analyse import analyse, decoupled_and_long, gyro_rows_of
from tradeoff_study.grid import FULL, QUICK, SETS, plan
from tradeoff_study.plots import draw_all
from tradeoff_study.report import write_csv, write_markdown
from tradeoff_study.run import load_json, run_all


def parse_args():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--simulate", required=True, help="the simulate executable")
    parser.add_argument("--grid", choices=["full", "quick"], default="full")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--out", default="out/tradeoff")
    parser.add_argument("--docs", default="docs")
    parser.add_argument("--report-only", action="store_true", help="use cached runs only")
    parser.add_argument("--rerun", action="store_true", help="ignore cached runs")
    parser.add_argument("--command", default="scripts/dev/tradeoff", help="shown in the report")
    args = parser.parse_args()
    # the report names the command that regenerates it, runs included
    args.command = args.command.replace(" --report-only", "")
    return args


def main():
    args = parse_args()
    # the friction sets, from the program (the laws table)
    SETS[:] = subprocess.run([args.simulate, "--list-friction-sets"], check=True,
                             capture_output=True, text=True).stdout.split()
    grid = FULL if args.grid == "full" else QUICK
    os.makedirs(args.out, exist_ok=True)
    os.makedirs(args.docs, exist_ok=True)

    runs = plan(grid)
    if args.report_only:
        records, failures, elapsed = run_all(args.simulate, [], args.out, args.jobs, False)
        for config in runs:
            path = os.path.join(args.out, "runs", config["id"] + ".json")
            if os.path.exists(path):
                records[config["id"]] = load_json(path)
    else:
        records, failures, elapsed = run_all(args.simulate, runs, args.out, args.jobs, args.rerun)
    elapsed_total = sum(r.get("process_seconds", 0.0) for r in records.values()) / args.jobs
    wanted = {c["id"] for c in runs}
    records = {k: v for k, v in records.items() if k in wanted}

    rows, checks, cross, refs, unmapped_rows = analyse(grid, records)
    write_csv(rows, os.path.join(args.out, "runs.csv"))
    gyro_rows = gyro_rows_of(records)
    pngs = draw_all(grid, rows, refs, gyro_rows, args.docs)
    decoupled_rows, long_rows = decoupled_and_long(records)

    write_markdown(os.path.join(args.docs, "tradeoff.md"), grid, rows, checks, cross, refs,
                   gyro_rows, decoupled_rows, long_rows, args.command,
                   elapsed_total if args.report_only else elapsed, failures, pngs, records,
                   unmapped_rows)
    print("tradeoff: wrote %s, %s and %d plots" % (os.path.join(args.out, "runs.csv"),
                                                   os.path.join(args.docs, "tradeoff.md"),
                                                   len(pngs) + 2), file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
