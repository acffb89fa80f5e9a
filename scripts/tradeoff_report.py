#!/usr/bin/python3
"""The speed-accuracy trade study of the Tippe-Top, run by `scripts/tradeoff`.

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

Uses Debian's python3 with python3-matplotlib and numpy (never another interpreter).

usage: tradeoff_report.py --simulate BIN [--grid full|quick] [--jobs N] [--out DIR] [--docs DIR]
                          [--report-only] [--rerun]
"""
import argparse
import concurrent.futures
import csv
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
import numpy as np  # noqa: E402

SETS = []  # the friction sets, filled in by main from `simulate --list-friction-sets`
SOLVERS = ["jacobi", "modified_jacobi", "gauss_seidel"]
SOLVER_SHORT = {"jacobi": "J (43)", "modified_jacobi": "MJ (46)", "gauss_seidel": "GS"}

# The grid of the issue. Duration: the coupled laws touch down at ~1.3 s, the decoupled ones at
# dt = 1e-3 at 1.9-2.3 s; E is read at 2 s.
FULL = {
    "sets": SETS,
    "solvers": SOLVERS,
    "dts": [1e-3, 5e-4, 2e-4, 1e-4, 5e-5, 2e-5, 1e-5],
    "tolerances": [1e-4, 1e-6, 1e-8, 1e-10],
    "duration": 3.0,
    # reference: Gauss-Seidel, absolute tolerance off so that the drilling percussion
    # (~5e-10 N m s) is resolved to the relative tolerance too
    "reference": {"dt": 2e-7, "tolerance": 1e-12, "tolerance_abs": 1e-22, "max_iterations": 100000},
    "gyro_spins": [180.0, 500.0, 1000.0, 2000.0, 5000.0],
    "gyro_dts": [1e-5, 2e-5, 5e-5, 1e-4, 2e-4, 5e-4, 1e-3, 2e-3, 5e-3, 1e-2],
    "gyro_duration": 2.0,
    "decoupled_duration": 8.0,
    "long_duration": 3600.0,
}
# A tiny grid to develop the script with (same code paths, a minute of runs).
QUICK = {
    "sets": ["coulomb", "sphere", "exact"],
    "solvers": ["jacobi", "gauss_seidel"],
    "dts": [1e-3, 1e-4],
    "tolerances": [1e-4, 1e-8],
    "duration": 3.0,
    "reference": {"dt": 2e-5, "tolerance": 1e-10, "tolerance_abs": 1e-22, "max_iterations": 100000},
    "gyro_spins": [180.0, 1000.0],
    "gyro_dts": [1e-4, 1e-3],
    "gyro_duration": 0.5,
    "decoupled_duration": 3.0,
    "long_duration": 60.0,
}

SAMPLE_DT = 1e-3      # theta(t) and E(t) are compared on this common grid [s]
THETA_WINDOW = 0.5    # max |theta - theta_ref| over [0, THETA_WINDOW] s
ENERGY_TIME = 2.0     # energy compared at this time [s]
TOUCHDOWN = 2.4       # [rad], peg touchdown threshold (simulate's t_theta_above_2_4)
PLOT_DT = 0.01        # theta kept for the plots of the references [s]
FRONT_STEP = 0.1      # Pareto tables list a point when it cuts the error by this fraction
GYRO_CLIP = 1e6       # the gyroscopic plot draws energy gains (and blow-ups) above this at it
DIRECT_TOLERANCES = [1e-4, 1e-6]  # of the runs iterating exact and cylinder on their own sets
WORKER_TIMEOUT = 3600.0  # [s] per simulate process


# ------------------------------------------------------------------------------------------------
# Runs

def run_id(config):
    """A file name for a run configuration."""
    parts = [config["kind"], config["set"], config["solver"], "dt%g" % config["dt"],
             "tol%g" % config["tolerance"]]
    if config.get("tolerance_abs") is not None:
        parts.append("abs%g" % config["tolerance_abs"])
    if config.get("gyroscopic", "explicit") != "explicit":
        parts.append(config["gyroscopic"])
    if config.get("spin", 180.0) != 180.0:
        parts.append("spin%g" % config["spin"])
    if config.get("unmapped"):
        parts.append("unmapped")
    parts.append("T%g" % config["duration"])
    return "_".join(parts).replace("+", "").replace("-", "m")


def make_config(kind, friction_set, solver, dt, tolerance, duration, **extra):
    config = {"kind": kind, "set": friction_set, "solver": solver, "dt": dt,
              "tolerance": tolerance, "duration": duration, "tolerance_abs": None,
              "max_iterations": None, "gyroscopic": "explicit", "spin": 180.0, "csv": True,
              "unmapped": False}
    config.update(extra)
    config["id"] = run_id(config)
    return config


def plan(grid):
    """Every run of the study, as configurations."""
    runs = []
    for s in grid["sets"]:
        for solver in grid["solvers"]:
            for dt in grid["dts"]:
                for tol in grid["tolerances"]:
                    runs.append(make_config("grid", s, solver, dt, tol, grid["duration"]))
        ref = grid["reference"]
        for kind, factor in (("ref", 1.0), ("refhalf", 0.5)):
            runs.append(make_config(kind, s, "gauss_seidel", ref["dt"] * factor,
                                    ref["tolerance"] * factor, grid["duration"],
                                    tolerance_abs=ref["tolerance_abs"] * factor,
                                    max_iterations=ref["max_iterations"]))
    # exact and cylinder iterated on their own sets (37), as the paper timed B_F, instead of on
    # the A-mapped sets (40)-(47) that simulate uses by default
    for s in ("cylinder", "exact"):
        if s not in grid["sets"]:
            continue
        for dt in grid["dts"]:
            for tol in DIRECT_TOLERANCES:
                runs.append(make_config("unmapped", s, "gauss_seidel", dt, tol,
                                        grid["duration"], unmapped=True))
    # explicit against implicit-midpoint gyroscopic term over dt*|omega| (sphere, default solver)
    for spin in grid["gyro_spins"]:
        for dt in grid["gyro_dts"]:
            for scheme in ("explicit", "implicit_midpoint"):
                runs.append(make_config("gyro", "sphere", "gauss_seidel", dt, 1e-5,
                                        grid["gyro_duration"], gyroscopic=scheme, spin=spin,
                                        csv=False))
    # the decoupled laws over 8 s: does the top invert, and when, as a function of dt
    for s in ("coulomb", "cylinder"):
        if s not in grid["sets"]:
            continue
        for dt in grid["dts"]:
            runs.append(make_config("decoupled", s, "gauss_seidel", dt, 1e-6,
                                    grid["decoupled_duration"], csv=False))
    # an hour of simulated time at dt = 1e-3, both gyroscopic schemes
    for scheme in ("explicit", "implicit_midpoint"):
        runs.append(make_config("long", "sphere", "gauss_seidel", 1e-3, 1e-5,
                                grid["long_duration"], gyroscopic=scheme, csv=False))
    return runs


def estimated_cost(config):
    """Relative cost, to start the long runs first."""
    steps = config["duration"] / config["dt"]
    per_step = {"coulomb": 1.0, "sphere": 1.0, "ellipsoid": 10.0, "exact": 10.0,
                "cylinder": 30.0}.get(config["set"], 10.0)
    if config["solver"] == "jacobi":
        per_step *= 5.0
    return steps * per_step * (1.0 + 0.2 * -math.log10(config["tolerance"]))


def load_json(path):
    """simulate writes inf/nan as bare words when a run blew up: read them as numbers."""
    with open(path) as f:
        text = f.read()
    text = re.sub(r"(?<=[:\s])(-?)inf\b", r"\1Infinity", text)
    text = re.sub(r"(?<=[:\s])-?nan\b", "NaN", text)
    return json.loads(text)


def sample_csv(path, duration):
    """theta and energy on the common grid t = k*SAMPLE_DT (rows are written every step of the
    decimation, which is chosen so that they fall on it)."""
    theta = {}
    energy = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            k = round(float(row["t"]) / SAMPLE_DT)
            if abs(float(row["t"]) - k * SAMPLE_DT) > 1e-9:
                continue
            theta[k] = float(row["theta"])
            energy[k] = float(row["energy"])
    n_window = round(THETA_WINDOW / SAMPLE_DT)
    n_energy = round(ENERGY_TIME / SAMPLE_DT)
    stride = round(PLOT_DT / SAMPLE_DT)
    n_end = round(duration / SAMPLE_DT)
    return {
        "theta_window": [theta.get(k) for k in range(n_window + 1)],
        "energy_2": energy.get(n_energy),
        "theta_plot": [theta.get(k) for k in range(0, n_end + 1, stride)],
    }


def execute(simulate, config, out_dir):
    """Runs one configuration; returns the record stored in OUT/runs/<id>.json."""
    args = [simulate, "--quiet", "--friction-set", config["set"], "--solver", config["solver"],
            "--dt", repr(config["dt"]), "--duration", repr(config["duration"]),
            "--tolerance", repr(config["tolerance"]), "--gyroscopic", config["gyroscopic"],
            "--spin", repr(config["spin"])]
    if config["tolerance_abs"] is not None:
        args += ["--tolerance-abs", repr(config["tolerance_abs"])]
    if config["max_iterations"] is not None:
        args += ["--max-iterations", str(config["max_iterations"])]
    if config["unmapped"]:
        args.append("--unmapped-drilling-sets")
    with tempfile.TemporaryDirectory(dir=out_dir) as tmp:
        summary_path = os.path.join(tmp, "summary.json")
        args += ["--summary", summary_path]
        csv_path = os.path.join(tmp, "run.csv")
        if config["csv"]:
            decimate = max(1, round(SAMPLE_DT / config["dt"]))
            args += ["--csv", csv_path, "--decimate", str(decimate)]
        started = time.time()
        completed = subprocess.run(args, capture_output=True, text=True, timeout=WORKER_TIMEOUT)
        if completed.returncode != 0 and config["kind"] == "gyro" and "finite" in completed.stderr:
            # the explicit gyroscopic term blew the state up and the core refused the non-finite
            # contact problem: that is the datum of this sweep
            return {"config": config, "blown_up": completed.stderr.strip(),
                    "process_seconds": time.time() - started}
        if completed.returncode != 0:
            raise RuntimeError("%s failed (%d): %s" % (" ".join(args), completed.returncode,
                                                       completed.stderr.strip()))
        record = {"config": config, "summary": load_json(summary_path),
                  "process_seconds": time.time() - started}
        if config["csv"]:
            record.update(sample_csv(csv_path, config["duration"]))
    return record


def run_all(simulate, runs, out_dir, jobs, rerun):
    """Runs what is not cached yet, `jobs` processes at a time, longest first."""
    record_dir = os.path.join(out_dir, "runs")
    os.makedirs(record_dir, exist_ok=True)
    records = {}
    todo = []
    for config in runs:
        path = os.path.join(record_dir, config["id"] + ".json")
        if not rerun and os.path.exists(path):
            record = load_json(path)
            if record.get("config") == config:
                records[config["id"]] = record
                continue
        todo.append(config)
    todo.sort(key=estimated_cost, reverse=True)
    print("tradeoff: %d runs cached, %d to run (%d at a time)" % (len(records), len(todo), jobs),
          file=sys.stderr)
    started = time.time()
    failures = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = {pool.submit(execute, simulate, c, out_dir): c for c in todo}
        for done, future in enumerate(concurrent.futures.as_completed(futures), 1):
            config = futures[future]
            try:
                record = future.result()
            except (RuntimeError, subprocess.TimeoutExpired) as error:
                failures.append(str(error))
                print("tradeoff: %s" % error, file=sys.stderr)
                continue
            with open(os.path.join(record_dir, config["id"] + ".json"), "w") as f:
                json.dump(record, f)
            records[config["id"]] = record
            print("tradeoff: [%d/%d] %.0f s  %s (%.2f s)" % (done, len(todo), time.time() - started,
                                                           config["id"], record["process_seconds"]),
                  file=sys.stderr)
    return records, failures, time.time() - started


# ------------------------------------------------------------------------------------------------
# Figures

def touchdown_error(t, t_ref):
    """|t - t_ref|; 0 if neither touches down, inf if only one does."""
    if t is None and t_ref is None:
        return 0.0
    if t is None or t_ref is None:
        return math.inf
    return abs(t - t_ref)


def theta_error(theta, theta_ref):
    pairs = [(a, b) for a, b in zip(theta, theta_ref) if a is not None and b is not None]
    if not pairs or len(pairs) < len(theta_ref):
        return math.inf
    return max(abs(a - b) for a, b in pairs)


def jellett_drift(summary):
    j0 = summary["jellett_initial"]
    return abs(summary["jellett_final"] - j0) / abs(j0)


def figures(record, ref):
    """The accuracy figures of a run against a reference record."""
    s, r = record["summary"], ref["summary"]
    t_ref = r["t_theta_above_2_4"]
    err_td = touchdown_error(s["t_theta_above_2_4"], t_ref)
    e2, e2_ref = record["energy_2"], ref["energy_2"]
    return {
        "err_touchdown": err_td,
        "rel_err_touchdown": err_td / t_ref if t_ref else (0.0 if err_td == 0.0 else math.inf),
        "err_theta_05": theta_error(record["theta_window"], ref["theta_window"]),
        "err_energy_2": abs(e2 - e2_ref) / abs(e2_ref) if e2 is not None else math.inf,
        "err_jellett": abs(jellett_drift(s) - jellett_drift(r)),
    }


def unit_cost(summary):
    """CPU time of the stepping loop [s]: equals wall time on an idle core and is not inflated
    when the two processes of the study (or anything else) share the machine."""
    return summary.get("cpu_time_s", summary["wall_time_s"])


# ------------------------------------------------------------------------------------------------
# Report

def fmt(x, digits=3):
    if x is None:
        return "never"
    if isinstance(x, float) and math.isinf(x):
        return "inf"
    if isinstance(x, float) and math.isnan(x):
        return "nan"
    if x == 0:
        return "0"
    return "%.*g" % (digits, x)


def setting_text(row):
    return "%s, dt %g, tol %g" % (SOLVER_SHORT[row["solver"]], row["dt"], row["tolerance"])


def thin(front, rows):
    """The front points that improve the error of the last kept one by FRONT_STEP."""
    kept = []
    for i in front:
        error = rows[i]["err_theta_05"]
        if not kept or error <= (1.0 - FRONT_STEP) * rows[kept[-1]]["err_theta_05"]:
            kept.append(i)
    return kept


def pareto(points):
    """Indices of the points on the lower-left front of (cost, error)."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front, best = [], math.inf
    for i in order:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


def plot_pareto(rows, friction_set, ref_cost, path):
    """Two panels: theta error over the first 0.5 s and touchdown-time error against CPU time."""
    fig, axes = plt.subplots(1, 2, figsize=(9.0, 3.4), dpi=72)
    markers = {1e-4: "o", 1e-6: "s", 1e-8: "^", 1e-10: "D"}
    colors = {"jacobi": "tab:red", "modified_jacobi": "tab:orange", "gauss_seidel": "tab:blue"}
    for ax, key, label, floor in ((axes[0], "err_theta_05", "max |θ - θ_ref|, first 0.5 s [rad]",
                                   1e-12),
                                  (axes[1], "err_touchdown", "|t_touchdown - t_ref| [s]", 1e-6)):
        points = []
        for row in rows:
            error = row[key]
            if math.isinf(error):
                continue
            shown = max(error, floor)
            ax.scatter(row["cpu_time_s"], shown, s=14, marker=markers.get(row["tolerance"], "x"),
                       color=colors[row["solver"]], alpha=0.75, linewidths=0)
            points.append((row["cpu_time_s"], shown))
        front = pareto(points)
        if front:
            ax.step([points[i][0] for i in front], [points[i][1] for i in front], "k-", lw=0.8,
                    where="post")
        ax.axvline(ref_cost, color="0.6", lw=0.8, ls=":")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("CPU time for %g s simulated [s]" % rows[0]["duration"])
        ax.set_ylabel(label, fontsize=8)
        ax.grid(True, which="major", lw=0.3)
        ax.tick_params(labelsize=7)
    handles = [plt.Line2D([], [], ls="", marker="o", color=c, label=SOLVER_SHORT[s])
               for s, c in colors.items()]
    handles += [plt.Line2D([], [], ls="", marker=m, color="0.3", label="tol %g" % t)
                for t, m in markers.items()]
    handles.append(plt.Line2D([], [], color="k", lw=0.8, label="Pareto front"))
    handles.append(plt.Line2D([], [], color="0.6", lw=0.8, ls=":", label="reference cost"))
    fig.legend(handles=handles, loc="center right", fontsize=7, frameon=False)
    fig.suptitle("%s: cost against error (errors below the floor drawn at it)" % friction_set,
                 fontsize=9)
    fig.tight_layout(rect=(0, 0, 0.85, 0.95))
    fig.savefig(path, dpi=72)
    plt.close(fig)


def plot_references(refs, duration, path):
    fig, ax = plt.subplots(figsize=(7.0, 3.2), dpi=72)
    styles = ["-", "--", "-.", ":", "-"]
    for (s, record), style in zip(refs.items(), styles):
        theta = record["theta_plot"]
        t = [k * PLOT_DT for k in range(len(theta))]
        ax.plot(t, theta, style, lw=1.0, label=s)
    ax.axhline(TOUCHDOWN, color="0.6", lw=0.6, ls=":")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("θ [rad]")
    ax.set_xlim(0, duration)
    ax.legend(fontsize=7, frameon=False)
    ax.grid(True, lw=0.3)
    ax.set_title("converged references (dt %g s) of every friction law" %
                 refs[next(iter(refs))]["config"]["dt"], fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=72)
    plt.close(fig)


def plot_gyro(gyro_rows, path):
    """Largest E(t) - E(0) over the run, relative to E(0), against dt*|omega0|."""
    fig, ax = plt.subplots(figsize=(7.0, 3.2), dpi=72)
    for scheme, marker in (("explicit", "o"), ("implicit_midpoint", "x")):
        for spin in sorted({r["spin"] for r in gyro_rows}):
            pts = sorted((r["dt_omega0"], r["energy_above_rel"]) for r in gyro_rows
                         if r["gyroscopic"] == scheme and r["spin"] == spin)
            xs = [p[0] for p in pts]
            ys = [min(p[1], GYRO_CLIP) for p in pts]
            ax.plot(xs, [max(y, 1e-12) for y in ys], marker=marker, ms=4, lw=0.8,
                    ls="-" if scheme == "explicit" else ":",
                    label="%s, %g rad/s" % ("explicit" if scheme == "explicit" else "implicit",
                                            spin))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("Δt·|ω0|")
    ax.set_ylabel("max E(t) - E(0), / E(0)\n(≤ 0 drawn at 1e-12, ≥ 1e6 or blow-up at 1e6)",
                  fontsize=8)
    ax.legend(fontsize=6, ncol=2, frameon=False)
    ax.grid(True, lw=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=72)
    plt.close(fig)


def observed_order(rows, key):
    """Least-squares slope of log(error) against log(dt), finite positive errors only."""
    pts = [(math.log(r["dt"]), math.log(r[key])) for r in rows
           if math.isfinite(r[key]) and r[key] > 0]
    if len(pts) < 3:
        return None
    x = np.array([p[0] for p in pts])
    y = np.array([p[1] for p in pts])
    return float(np.polyfit(x, y, 1)[0])


def analyse(grid, records):
    """Grid rows with figures, the reference checks and the cross-law comparison."""
    rows, checks, cross = [], {}, {}
    refs = {}
    for s in grid["sets"]:
        ref_cfg = [r for r in records.values() if r["config"]["kind"] == "ref"
                   and r["config"]["set"] == s]
        half_cfg = [r for r in records.values() if r["config"]["kind"] == "refhalf"
                    and r["config"]["set"] == s]
        if not ref_cfg or not half_cfg:
            continue
        ref, half = ref_cfg[0], half_cfg[0]
        refs[s] = ref
        rs, hs = ref["summary"], half["summary"]
        theta_change = theta_error(half["theta_window"], ref["theta_window"])
        theta_scale = max(abs(x) for x in ref["theta_window"])
        checks[s] = {
            "ref": ref, "half": half,
            "touchdown": (rs["t_theta_above_2_4"], hs["t_theta_above_2_4"]),
            "energy_2": (ref["energy_2"], half["energy_2"]),
            "jellett_drift": (jellett_drift(rs), jellett_drift(hs)),
            "max_energy_increase": (rs["max_energy_increase"], hs["max_energy_increase"]),
            "theta_change": theta_change,
            "theta_change_rel": theta_change / theta_scale,
        }
        for record in records.values():
            c = record["config"]
            if c["kind"] != "grid" or c["set"] != s:
                continue
            summary = record["summary"]
            row = {
                "set": s, "solver": c["solver"], "dt": c["dt"], "tolerance": c["tolerance"],
                "duration": c["duration"], "steps": summary["steps"],
                "wall_time_s": summary["wall_time_s"], "cpu_time_s": unit_cost(summary),
                "steps_per_second": summary["steps_per_second"],
                "mean_iterations": summary["mean_iterations"],
                "max_iterations": summary["max_iterations"],
                "unconverged_steps": summary["unconverged_steps"],
                "t_touchdown": summary["t_theta_above_2_4"],
                "energy_2": record["energy_2"],
                "jellett_drift": jellett_drift(summary),
                "max_energy_increase": summary["max_energy_increase"],
                "min_gap": summary.get("min_gap"),
            }
            row.update(figures(record, ref))
            # the same figures against the halved reference: how much the reference's own error
            # moves each figure
            alt = figures(record, half)
            row["ref_sensitivity_theta"] = abs(alt["err_theta_05"] - row["err_theta_05"])
            row["ref_sensitivity_touchdown"] = (abs(alt["err_touchdown"] - row["err_touchdown"])
                                                if math.isfinite(row["err_touchdown"]) else 0.0)
            rows.append(row)
    unmapped_rows = []
    for record in records.values():
        c = record["config"]
        if c["kind"] != "unmapped" or c["set"] not in refs:
            continue
        summary = record["summary"]
        row = {"set": c["set"], "dt": c["dt"], "tolerance": c["tolerance"],
               "cpu_time_s": unit_cost(summary), "mean_iterations": summary["mean_iterations"],
               "max_iterations": summary["max_iterations"],
               "unconverged_steps": summary["unconverged_steps"], "steps": summary["steps"]}
        row.update(figures(record, refs[c["set"]]))
        unmapped_rows.append(row)
    unmapped_rows.sort(key=lambda r: (r["set"], -r["dt"], -r["tolerance"]))
    if "exact" in refs:
        for s, ref in refs.items():
            cross[s] = figures(ref, refs["exact"])
            cross[s]["t_touchdown"] = ref["summary"]["t_theta_above_2_4"]
            cross[s]["cpu_time_s"] = unit_cost(ref["summary"])
    rows.sort(key=lambda r: (SETS.index(r["set"]), SOLVERS.index(r["solver"]), -r["dt"],
                             -r["tolerance"]))
    return rows, checks, cross, refs, unmapped_rows


def write_csv(rows, path):
    columns = ["set", "solver", "dt", "tolerance", "duration", "steps", "wall_time_s",
               "cpu_time_s", "steps_per_second", "mean_iterations", "max_iterations",
               "unconverged_steps", "t_touchdown", "err_touchdown", "rel_err_touchdown",
               "err_theta_05", "energy_2", "err_energy_2", "jellett_drift", "err_jellett",
               "max_energy_increase", "min_gap", "ref_sensitivity_theta",
               "ref_sensitivity_touchdown"]
    with open(path, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(columns)
        for row in rows:
            writer.writerow(["" if row[c] is None else row[c] for c in columns])


def fastest(rows, predicate):
    candidates = [r for r in rows if predicate(r)]
    return min(candidates, key=lambda r: r["cpu_time_s"]) if candidates else None


def recommendation_lines(rows, grid, refs):
    lines = ["| friction set | reference touchdown | inversion time within 1 % (fastest) | "
             "within 10 % (fastest) | θ within 1e-3 rad over 0.5 s (fastest) |",
             "|---|---|---|---|---|"]
    for s in grid["sets"]:
        own = [r for r in rows if r["set"] == s]
        if not own:
            continue
        cells = []
        for predicate in (lambda r: r["rel_err_touchdown"] <= 0.01,
                          lambda r: r["rel_err_touchdown"] <= 0.10,
                          lambda r: r["err_theta_05"] <= 1e-3):
            best = fastest(own, predicate)
            if best is None:
                cells.append("none in the grid")
            else:
                cells.append("%s: %s s CPU (%s steps/s), %s unconverged" % (
                    setting_text(best), fmt(best["cpu_time_s"]), fmt(best["steps_per_second"]),
                    best["unconverged_steps"]))
        t_ref = refs[s]["summary"]["t_theta_above_2_4"]
        touchdown = fmt(t_ref, 5) + (" s" if t_ref else " (no inversion)")
        lines.append("| %s | %s | %s |" % (s, touchdown, " | ".join(cells)))
    return lines


def write_markdown(path, grid, rows, checks, cross, refs, gyro_rows, decoupled_rows, long_rows,
                   command, elapsed, failures, pngs, records, unmapped_rows):
    records_by_key = {(r["config"]["set"], r["config"]["solver"], r["config"]["dt"],
                       r["config"]["tolerance"]): r
                      for r in records.values() if r["config"]["kind"] == "grid"}
    L = []
    L.append("# Speed-accuracy trade study of the Tippe-Top (generated)")
    L.append("")
    L.append("Generated by `%s` (%s; %.0f s of runs on this machine, two `simulate` processes "
             "at a time). Do not edit: rerun the command." % (command, time.strftime("%Y-%m-%d"),
                                                             elapsed))
    L.append("")
    L.append("Scene and settings: the Tippe-Top of `../shared/reference/tippe-top.md` for %g s, "
             "`simulate` defaults otherwise (explicit gyroscopic term as in the paper, relaxation "
             "1, max 1000 iterations, absolute tolerance 1e-14 N s). Cost is the CPU time of the "
             "stepping loop (`cpu_time_s` of the summary: the wall time on an idle core, not "
             "inflated by the second process); `runs.csv` has the wall time too. Accuracy "
             "against the converged reference of the *same* friction law: Gauss-Seidel at dt "
             "%g s, tolerance %g (absolute %g). θ is compared every %g s." % (
                 grid["duration"], grid["reference"]["dt"], grid["reference"]["tolerance"],
                 grid["reference"]["tolerance_abs"], SAMPLE_DT))
    L.append("")
    if failures:
        L.append("**Runs that failed:** " + "; ".join(failures))
        L.append("")

    # headline
    L.append("## Recommendations")
    L.append("")
    L.extend(recommendation_lines(rows, grid, refs))
    L.append("")
    L.append("\"Inversion time\" is the peg touchdown, the first time θ > 2.4 rad; for a law whose "
             "reference does not invert within %g s, \"within x %%\" means the run does not "
             "invert either. Settings with unconverged steps are listed as they are: "
             "the count says whether the solver reached its tolerance." % grid["duration"])
    L.append("")

    # reference convergence
    L.append("## The references are converged")
    L.append("")
    L.append("Each reference rerun with dt and tolerance halved; relative change of each figure "
             "(must be < 1 %%). For θ(t): max |θ_ref - θ_half| over the first %g s, relative to "
             "max θ_ref, and in absolute terms next to the smallest θ error of the grid (the "
             "grid errors below ~100 times it are at the reference's resolution). The largest "
             "per-step energy increase has the exact value 0 and shrinks as dt²: its reference "
             "values show that, they are not a converged number." % THETA_WINDOW)
    L.append("")
    L.append("| set | touchdown ref / half [s] | change | E(2 s) ref / half [J] | change | "
             "θ change (rel / abs) | smallest grid θ error | Jellett drift ref / half | "
             "max ΔE per step ref / half [J] | CPU of ref [s] |")
    L.append("|---|---|---|---|---|---|---|---|---|---|")
    for s, c in checks.items():
        td, e2, jd, me = c["touchdown"], c["energy_2"], c["jellett_drift"], c["max_energy_increase"]
        td_change = (abs(td[1] - td[0]) / td[0]) if (td[0] and td[1]) else (
            0.0 if td[0] is None and td[1] is None else math.inf)
        e_change = abs(e2[1] - e2[0]) / abs(e2[0])
        own = [r["err_theta_05"] for r in rows if r["set"] == s and r["err_theta_05"] > 0]
        L.append("| %s | %s / %s | %s %% | %s / %s | %s %% | %s %% / %s rad | %s rad | %s / %s | "
                 "%s / %s | %s |" % (
                     s, fmt(td[0], 6), fmt(td[1], 6), fmt(100 * td_change, 2), fmt(e2[0], 7),
                     fmt(e2[1], 7), fmt(100 * e_change, 2), fmt(100 * c["theta_change_rel"], 2),
                     fmt(c["theta_change"], 2), fmt(min(own) if own else None, 2),
                     fmt(jd[0], 3), fmt(jd[1], 3), fmt(me[0], 2), fmt(me[1], 2),
                     fmt(unit_cost(c["ref"]["summary"]), 3)))
    L.append("")

    # cross-law
    if cross:
        L.append("## What each approximation costs: references against `exact`")
        L.append("")
        L.append("Each law's converged reference against the converged reference of the exact "
                 "Coulomb-Contensou set B_F (the paper's Fig. 4); same figures as above.")
        L.append("")
        L.append("| set | touchdown [s] | vs exact [s] | max |Δθ| first %g s [rad] | E(2 s) vs "
                 "exact | CPU of the reference [s] |" % THETA_WINDOW)
        L.append("|---|---|---|---|---|---|")
        for s, c in cross.items():
            L.append("| %s | %s | %s | %s | %s %% | %s |" % (
                s, fmt(c["t_touchdown"], 6), fmt(c["err_touchdown"], 3), fmt(c["err_theta_05"], 3),
                fmt(100 * c["err_energy_2"], 3), fmt(c["cpu_time_s"], 3)))
        L.append("")
        L.append("![references](tradeoff_references.png)")
        L.append("")

    # order of convergence
    L.append("## Observed order of convergence in dt")
    L.append("")
    tight = min(grid["tolerances"])
    L.append("Gauss-Seidel at tolerance %g: slope of log(error) against log(dt) (least squares "
             "over the dt of the grid), and the errors themselves." % tight)
    L.append("")
    header = "| set | order, θ first %g s | order, touchdown | " % THETA_WINDOW + " | ".join(
        "dt %g: θ err / td err" % dt for dt in grid["dts"]) + " |"
    L.append(header)
    L.append("|" + "---|" * (3 + len(grid["dts"])))
    for s in grid["sets"]:
        own = [r for r in rows if r["set"] == s and r["solver"] == "gauss_seidel"
               and r["tolerance"] == tight]
        if not own:
            continue
        by_dt = {r["dt"]: r for r in own}
        cells = []
        for dt in grid["dts"]:
            r = by_dt.get(dt)
            cells.append("%s / %s" % (fmt(r["err_theta_05"], 2), fmt(r["err_touchdown"], 2))
                         if r else "")
        orders = [observed_order(own, key) for key in ("err_theta_05", "err_touchdown")]
        L.append("| %s | %s | %s | %s |" % (s, *("n/a" if o is None else fmt(o, 2) for o in orders),
                                            " | ".join(cells)))
    L.append("")

    # what the solver tolerance changes at a fixed dt
    L.append("## What the solver tolerance changes")
    L.append("")
    L.append("Gauss-Seidel: the largest difference, over the dt of the grid, between a run at "
             "tolerance x and the run at tolerance %g with the same dt — in θ over the first %g s "
             "and in the touchdown time — and the mean iterations per step at dt 1e-4 s." % (
                 tight, THETA_WINDOW))
    L.append("")
    L.append("| set | " + " | ".join("tol %g: max Δθ / max Δt_touchdown / iterations" % t
                                     for t in grid["tolerances"] if t != tight) + " |")
    L.append("|---|" + "---|" * (len(grid["tolerances"]) - 1))
    for s in grid["sets"]:
        cells = []
        for tol in grid["tolerances"]:
            if tol == tight:
                continue
            d_theta, d_td, its = 0.0, 0.0, None
            for dt in grid["dts"]:
                a = records_by_key.get((s, "gauss_seidel", dt, tol))
                b = records_by_key.get((s, "gauss_seidel", dt, tight))
                if a is None or b is None:
                    continue
                d_theta = max(d_theta, theta_error(a["theta_window"], b["theta_window"]))
                d_td = max(d_td, touchdown_error(a["summary"]["t_theta_above_2_4"],
                                                 b["summary"]["t_theta_above_2_4"]))
                if dt == 1e-4:
                    its = a["summary"]["mean_iterations"]
            cells.append("%s rad / %s s / %s" % (fmt(d_theta, 2), fmt(d_td, 2), fmt(its, 3)))
        L.append("| %s | %s |" % (s, " | ".join(cells)))
    L.append("")

    # Pareto plots and per-set tables
    L.append("## Pareto fronts per friction set")
    L.append("")
    for s in grid["sets"]:
        own = [r for r in rows if r["set"] == s]
        if not own:
            continue
        L.append("### %s" % s)
        L.append("")
        if s in pngs:
            L.append("![%s](%s)" % (s, pngs[s]))
            L.append("")
        front = thin(pareto([(r["cpu_time_s"], r["err_theta_05"]) for r in own]), own)
        L.append("Pareto front (CPU time against θ error over the first %g s; a point is listed "
                 "when it improves the error of the previous one by at least %d %%):" % (
                     THETA_WINDOW, round(100 * FRONT_STEP)))
        L.append("")
        L.append("| setting | CPU [s] | steps/s | iterations mean / max | unconverged | θ err [rad]"
                 " | touchdown err [s] | E(2 s) err | max ΔE per step [J] |")
        L.append("|---|---|---|---|---|---|---|---|---|")
        for i in front:
            r = own[i]
            L.append("| %s | %s | %s | %s / %s | %s | %s | %s | %s | %s |" % (
                setting_text(r), fmt(r["cpu_time_s"]), fmt(r["steps_per_second"]),
                fmt(r["mean_iterations"]), r["max_iterations"], r["unconverged_steps"],
                fmt(r["err_theta_05"], 2), fmt(r["err_touchdown"], 2), fmt(r["err_energy_2"], 2),
                fmt(r["max_energy_increase"], 2)))
        L.append("")
        worst = max(own, key=lambda r: r["unconverged_steps"])
        L.append("Solver cost over the grid: mean iterations per step from %s to %s; most "
                 "unconverged steps: %s of %s (%s)." % (
                     fmt(min(r["mean_iterations"] for r in own)),
                     fmt(max(r["mean_iterations"] for r in own)), worst["unconverged_steps"],
                     worst["steps"], setting_text(worst)))
        if s == "coulomb":
            jd = [(r["dt"], r["jellett_drift"]) for r in own
                  if r["solver"] == "gauss_seidel" and r["tolerance"] == tight]
            L.append("")
            L.append("Jellett drift |J(%g s) - J0|/J0 (Gauss-Seidel, tol %g): %s." % (
                grid["duration"], tight,
                ", ".join("dt %g: %s" % (dt, fmt(d, 2)) for dt, d in sorted(jd, reverse=True))))
        L.append("")

    # exact and cylinder iterated unmapped
    if unmapped_rows:
        mapped = {(r["set"], r["dt"], r["tolerance"]): r for r in rows
                  if r["solver"] == "gauss_seidel"}
        L.append("## `exact` and `cylinder` iterated on their own sets")
        L.append("")
        L.append("`simulate` iterates B_F and C_F, like S_F, in the coordinates of the map A "
                 "(40)-(47) by default; `--unmapped-drilling-sets` iterates them on their original "
                 "sets (37), as the paper timed B_F. Gauss-Seidel; errors against the same law's "
                 "reference. The last columns are the default (mapped) run with the same dt and "
                 "tolerance.")
        L.append("")
        L.append("| set | dt | tol | unmapped: CPU [s] | iterations mean / max | unconverged | θ err "
                 "[rad] | touchdown err [s] | mapped: CPU [s] | iterations | θ err [rad] |")
        L.append("|---|---|---|---|---|---|---|---|---|---|---|")
        for r in unmapped_rows:
            m = mapped.get((r["set"], r["dt"], r["tolerance"]))
            L.append("| %s | %g | %g | %s | %s / %s | %s | %s | %s | %s | %s | %s |" % (
                r["set"], r["dt"], r["tolerance"], fmt(r["cpu_time_s"]),
                fmt(r["mean_iterations"]), r["max_iterations"], r["unconverged_steps"],
                fmt(r["err_theta_05"], 2), fmt(r["err_touchdown"], 2),
                fmt(m["cpu_time_s"]) if m else "", fmt(m["mean_iterations"]) if m else "",
                fmt(m["err_theta_05"], 2) if m else ""))
        L.append("")

    # decoupled laws
    if decoupled_rows:
        L.append("## Decoupled laws: inversion is a time-step artefact")
        L.append("")
        L.append("`coulomb` and `cylinder`, Gauss-Seidel, tolerance 1e-6, %g s: first time θ > "
                 "2.4 rad, and θ at the end." % grid["decoupled_duration"])
        L.append("")
        L.append("| set | " + " | ".join("dt %g" % dt for dt in grid["dts"]) + " |")
        L.append("|---|" + "---|" * len(grid["dts"]))
        for s in ("coulomb", "cylinder"):
            cells = []
            for dt in grid["dts"]:
                r = decoupled_rows.get((s, dt))
                cells.append("" if r is None else "%s / θ %s" % (
                    fmt(r["t_theta_above_2_4"], 4), fmt(r["theta_final"], 3)))
            if any(cells):
                L.append("| %s | %s |" % (s, " | ".join(cells)))
        L.append("")

    # gyroscopic scheme
    if gyro_rows:
        L.append("## Explicit against implicit-midpoint gyroscopic term")
        L.append("")
        L.append("`sphere`, Gauss-Seidel, %g s from spin ω0 about the tilted axis; the largest "
                 "E(t) - E(0) relative to E(0) (≤ 0: the run never gained energy overall) and the "
                 "largest per-step increase relative to E(0); \"blow-up\": the state left the "
                 "floating-point range." % grid["gyro_duration"])
        L.append("")
        L.append("![gyroscopic](tradeoff_gyroscopic.png)")
        L.append("")
        L.append("| ω0 [rad/s] | Δt [s] | Δt·ω0 | explicit: max E-E0 / E0 | max step / E0 | max "
                 "Δt·|ω| | implicit: max E-E0 / E0 | max step / E0 |")
        L.append("|---|---|---|---|---|---|---|---|")
        keyed = {(r["spin"], r["dt"], r["gyroscopic"]): r for r in gyro_rows}
        for spin in sorted({r["spin"] for r in gyro_rows}):
            for dt in sorted({r["dt"] for r in gyro_rows}):
                e = keyed.get((spin, dt, "explicit"))
                i = keyed.get((spin, dt, "implicit_midpoint"))
                if e is None or i is None:
                    continue
                L.append("| %g | %g | %s | %s | %s | %s | %s | %s |" % (
                    spin, dt, fmt(spin * dt, 2), gyro_text(e["energy_above_rel"]),
                    gyro_text(e["step_rel"]), gyro_text(e["max_dt_omega"]),
                    gyro_text(i["energy_above_rel"]), gyro_text(i["step_rel"])))
        L.append("")
        L.append(safe_range_text(gyro_rows))
        L.append("")

    if long_rows:
        L.append("## An hour of simulated time at dt = 1e-3 s")
        L.append("")
        L.append("| gyroscopic | CPU [s] | E(0) [J] | E(1 h) [J] | max E - E0 [J] | z_S(1 h) [m] | "
                 "smallest gap [m] | θ(1 h) | unconverged |")
        L.append("|---|---|---|---|---|---|---|---|---|")
        for r in long_rows:
            s = r["summary"]
            L.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                r["config"]["gyroscopic"], fmt(unit_cost(s)), fmt(s["energy_initial"], 5),
                fmt(s["energy_final"], 5), fmt(s["max_energy_above_initial"], 3),
                fmt(s["z_final"], 4), fmt(s["min_gap"], 3), fmt(s["theta_final"], 3),
                s["unconverged_steps"]))
        L.append("")
        L.append("After the top falls back off its peg it rolls on its side; every rolling step "
                 "lets the contact sink by an O(Δt²) curvature term that the velocity-level "
                 "constraint of (14) does not see, so the gap drifts linearly in time (z_S < 0 "
                 "means the centre of mass is below the floor): the step corrects velocities, "
                 "never positions. test/core/stability_long_test.cpp (LongRun) tracks this.")
        L.append("")

    with open(path, "w") as f:
        f.write("\n".join(L))


def gyro_text(x):
    if not math.isfinite(x):
        return "blow-up"
    return fmt(x, 2)


def safe_range_text(gyro_rows):
    """The largest dt*omega0 below which every explicit run never gained energy overall, and the
    smallest at which one did."""
    explicit = [r for r in gyro_rows if r["gyroscopic"] == "explicit"]
    gained = [r["spin"] * r["dt"] for r in explicit
              if not math.isfinite(r["energy_above_rel"]) or r["energy_above_rel"] > 0.0]
    first_bad = min(gained) if gained else None
    safe = [r["spin"] * r["dt"] for r in explicit
            if first_bad is None or r["spin"] * r["dt"] < first_bad]
    blow = [r["spin"] * r["dt"] for r in explicit if not math.isfinite(r["energy_above_rel"])]
    implicit_bad = [r for r in gyro_rows if r["gyroscopic"] == "implicit_midpoint"
                    and (not math.isfinite(r["energy_above_rel"]) or r["energy_above_rel"] > 0)]
    text = ("Safe range of the explicit term measured here: every explicit run with Δt·ω0 ≤ %s "
            "ended below its initial energy at all times; the smallest Δt·ω0 at which one gained "
            "energy overall is %s, the smallest that blew up %s. The implicit midpoint rule "
            "gained energy overall in %d of %d runs." % (
                fmt(max(safe), 2) if safe else "none", fmt(first_bad, 2), fmt(min(blow), 2)
                if blow else "none", len(implicit_bad),
                len([r for r in gyro_rows if r["gyroscopic"] == "implicit_midpoint"])))
    return text


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--simulate", required=True, help="the simulate executable")
    parser.add_argument("--grid", choices=["full", "quick"], default="full")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--out", default="out/tradeoff")
    parser.add_argument("--docs", default="docs")
    parser.add_argument("--report-only", action="store_true", help="use cached runs only")
    parser.add_argument("--rerun", action="store_true", help="ignore cached runs")
    parser.add_argument("--command", default="scripts/tradeoff", help="shown in the report")
    args = parser.parse_args()
    # the report names the command that regenerates it, runs included
    args.command = args.command.replace(" --report-only", "")
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

    pngs = {}
    for s in grid["sets"]:
        own = [r for r in rows if r["set"] == s]
        if own and s in refs:
            name = "tradeoff_%s.png" % s
            plot_pareto(own, s, unit_cost(refs[s]["summary"]), os.path.join(args.docs, name))
            pngs[s] = name
    if refs:
        plot_references(refs, grid["duration"], os.path.join(args.docs, "tradeoff_references.png"))

    gyro_rows = []
    for record in records.values():
        c = record["config"]
        if c["kind"] != "gyro":
            continue
        if "blown_up" in record:
            gyro_rows.append({"spin": c["spin"], "dt": c["dt"], "gyroscopic": c["gyroscopic"],
                              "dt_omega0": c["spin"] * c["dt"], "energy_above_rel": math.inf,
                              "step_rel": math.inf, "max_dt_omega": math.inf})
            continue
        s = record["summary"]
        e0 = s["energy_initial"]
        finite = all(math.isfinite(s[k]) for k in ("energy_final", "max_energy_above_initial",
                                                     "max_energy_increase"))
        gyro_rows.append({"spin": c["spin"], "dt": c["dt"], "gyroscopic": c["gyroscopic"],
                          "dt_omega0": c["spin"] * c["dt"],
                          "energy_above_rel": s["max_energy_above_initial"] / e0 if finite
                          else math.inf,
                          "step_rel": s["max_energy_increase"] / e0 if finite else math.inf,
                          "max_dt_omega": s["max_dt_omega"]})
    if gyro_rows:
        plot_gyro(gyro_rows, os.path.join(args.docs, "tradeoff_gyroscopic.png"))
    decoupled_rows = {(r["config"]["set"], r["config"]["dt"]): r["summary"]
                      for r in records.values() if r["config"]["kind"] == "decoupled"}
    long_rows = [r for r in records.values() if r["config"]["kind"] == "long"]

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
