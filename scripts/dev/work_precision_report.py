#!/usr/bin/python3
"""The work-precision study per shipped scene, run by `scripts/dev/work_precision`.

For each shipped scene (the built-in Tippe-Top, and urdf/<scene>.urdf with config/<scene>.yaml)
it runs the headless `simulate` with both integrators over a range of time steps, and moreau2
with the accuracy knob (`--accuracy TOL`, steps chosen by step doubling) over a range of TOL, one
process at a time pinned to one core, measures the relative error of the quantity the scene is
known for against the scene's converged reference (moreau2 at dt = 1e-5), and prints markdown
tables: per scene (integrator, dt or TOL, value, error, CPU s, steps), the CPU time each series
needs for 1 % error, the cross-check of the references and the knob's honesty (achieved error /
TOL). It also runs Euler's disk rolling without slip (--mu 10 --contact-radius 0
--friction-set coulomb) for 60 s at dt = 1e-4 with both integrators.

The knob's runs write a CSV row every KNOB_SAMPLE s of simulated time (`--dt KNOB_SAMPLE
--decimate 1`); simulate lands on these times, so they cap the step (the coin's stop time is
the first sample below a threshold, resolved only to the spacing: its knob runs sample every
1e-4 s). Their repeated timings keep the CSV (without one simulate lands only every 0.1 s and
would take other steps).

Writes
    DOCS/accuracy_work_precision.png   error vs CPU time, one panel per scene, the three series
    DOCS/accuracy_disk.png             Euler's disk: E(t)/E0 - 1 and alpha(t)
    OUT/report.md                      what is printed on stdout
    OUT/runs/<key>.json                one cached run: settings, cost, the extracted quantities
A cached run is reused while the simulate binary, the scene's URDF and YAML and the settings are
byte-identical (the key is a hash of them); --rerun ignores the cache.

Cost is simulate's `cpu_time_s` (thread CPU time of the stepping loop, outputs excluded); runs
under MIN_TIMED s of CPU are repeated without CSV and the smallest time is kept.

Uses Debian's python3 with numpy and matplotlib (never another interpreter).

usage: work_precision_report.py --simulate BIN [--quick] [--out DIR] [--docs DIR] [--rerun]
                                [--command TEXT] [--cpu N]
"""
import argparse
import datetime
import hashlib
import json
import math
import os
import subprocess
import sys
import tempfile
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
import numpy as np  # noqa: E402

# simulate's JSON summaries with inf/nan read as numbers (this folder is on sys.path)
from tradeoff_report import load_json  # noqa: E402

DTS = {
    "moreau": [1e-3, 5e-4, 2e-4, 1e-4, 5e-5, 2e-5, 1e-5],
    "moreau2": [2e-3, 1e-3, 5e-4, 2e-4, 1e-4, 5e-5],
}
QUICK_DTS = {"moreau": [1e-3, 1e-4, 1e-5], "moreau2": [1e-3, 1e-4]}
KNOB = "moreau2 --accuracy"     # the third series: moreau2 with steps chosen for TOL
TOLS = [1e-2, 1e-3, 1e-4, 1e-5]
QUICK_TOLS = [1e-2, 1e-3]
GOAL_TOLS = [1e-6]              # also, for the scenes with a "goal" (not with --quick)
KNOB_SAMPLE = 2e-3              # [s] CSV sample spacing of the knob's runs (caps its step)
GOAL_CPU = 60.0                 # [s] a GOAL_TOLS run is reported only if its CPU stays below
HONEST = (0.1, 10.0)            # the goal band of achieved error / TOL
REF_MARGIN = 30.0               # a ratio is shown only where the reference's (and the sampling's)
ERR_MARGIN = 3.0                # error is below TOL / REF_MARGIN (3x below the band's 0.1 TOL)
                                # or below the achieved error / ERR_MARGIN
REFERENCE = ("moreau2", 1e-5)   # each scene's converged reference
CHECK = [("moreau2", 2e-5), ("moreau", 1e-5)]  # cross-checks of the reference
TARGET = 0.01                   # the error the cost is read at
TIMEOUT = 60.0                  # [s] per run; slower combinations are skipped
MIN_TIMED = 0.3                 # [s] CPU: shorter runs are timed 3 times, the minimum kept
SAMPLE = 1e-4                   # [s] CSV rows every SAMPLE (every step for dt >= SAMPLE)
REVERSAL = 0.05                 # [rad/s] the rattleback's reversal threshold (rattleback_test)
COIN_STOPPED = 1e-3             # [rad/s] the coin counts as stopped below this spin
DIE_ENERGY_TIME = 0.125         # [s] between the die's first impact (0.111 s) and its second
DISK = {"args": ["--mu", "10", "--contact-radius", "0", "--friction-set", "coulomb"],
        "dt": 1e-4, "duration": 60.0, "quick_duration": 10.0, "decimate": 100}


# ------------------------------------------------------------------------------------------------
# Quantities. Each takes (summary, columns) and returns a float or None (never happened).

def e3(c, body):
    """The body's z axis in the world, per CSV row."""
    if body is None:  # the built-in Tippe-Top: qw, qx, qy, qz
        qw, qx, qy, qz = c["qw"], c["qx"], c["qy"], c["qz"]
    else:
        qx, qy, qz, qw = (c[f"{body}/q{k}"] for k in "xyzw")
    return np.array([2 * (qx * qz + qw * qy), 2 * (qy * qz - qw * qx), 1 - 2 * (qx * qx + qy * qy)])


def inclination_end(body):
    return lambda s, c: float(np.arccos(np.clip(e3(c, body)[2][-1], -1.0, 1.0)))


def first_crossing(t, y, level):
    """First time y rises through level (linear interpolation), or None."""
    above = np.nonzero(y >= level)[0]
    if len(above) == 0:
        return None
    i = above[0]
    if i == 0:
        return float(t[0])
    return float(t[i - 1] + (t[i] - t[i - 1]) * (level - y[i - 1]) / (y[i] - y[i - 1]))


def rattleback_reversal(s, c):
    # started at w_z = -5: the first time w_z rises through +REVERSAL
    return first_crossing(c["t"], c["rattleback/wz"], REVERSAL)


def precession_angle(s, c):
    v = e3(c, "classic_top")
    phi = np.unwrap(np.arctan2(v[1], v[0]))
    return float(phi[-1] - phi[0])


def duel_distance(s, c):
    return float(math.dist([c[f"top1/{k}"][-1] for k in "xyz"],
                           [c[f"top2/{k}"][-1] for k in "xyz"]))


def coin_stop(s, c):
    stopped = np.nonzero(np.abs(c["coin/wz"]) < COIN_STOPPED)[0]
    return float(c["t"][stopped[0]]) if len(stopped) else None


def die_travel(s, c):
    return float(math.hypot(c["die/x"][-1] - c["die/x"][0], c["die/y"][-1] - c["die/y"][0]))


def die_face(c):
    """Which body axis points up at the end (+-1..3): the face the die shows."""
    qx, qy, qz, qw = (c[f"die/q{k}"][-1] for k in "xyzw")
    # third row of the rotation matrix: world z of each body axis
    up = [2 * (qx * qz - qw * qy), 2 * (qy * qz + qw * qx), 1 - 2 * (qx * qx + qy * qy)]
    k = int(np.argmax(np.abs(up)))
    return (k + 1) * (1 if up[k] > 0 else -1)


# Each scene: its simulate arguments, duration [s], and quantities (name, unit, function); the
# first quantity is the one plotted and costed, the others are extra columns. "goal": the indices
# of the quantities the knob is meant to hit within 10x of TOL (also in the honesty table, and run
# at GOAL_TOLS too); "knob_sample": the knob's CSV spacing if not KNOB_SAMPLE;
# "full_reference": the quantities the knob's runs are compared with the full reference for, not
# with the reference at the knob's sample times (see knob_reference); "first_sample_event": the
# first quantity is the first sample past a threshold (resolved to the sample spacing only).
SCENES = [
    {"name": "tippe_top", "title": "Tippe-Top (built in)", "urdf": None, "duration": 8.0,
     "quantities": [("peg touchdown t", "s", lambda s, c: s.get("t_peg_touchdown"))],
     "goal": [0]},
    {"name": "euler_disk", "title": "Euler's disk", "duration": 6.0,
     "quantities": [("inclination α(6 s)", "rad", inclination_end("euler_disk"))]},
    {"name": "rattleback", "title": "rattleback", "duration": 8.0,
     "quantities": [("peak reversed spin", "rad/s", lambda s, c: float(np.max(c["rattleback/wz"]))),
                    ("first reversal t", "s", rattleback_reversal)],
     "goal": [1], "full_reference": [0]},
    {"name": "spinning_egg", "title": "spinning egg", "duration": 6.0,
     "quantities": [("inclination θ(6 s)", "rad", inclination_end("spinning_egg"))]},
    {"name": "classic_top", "title": "classic top", "duration": 4.0,
     "quantities": [("tilt θ(4 s)", "rad", inclination_end("classic_top")),
                    ("precession angle φ(4 s)", "rad", precession_angle)]},
    {"name": "tippe_top_duel", "title": "Tippe-Top duel", "duration": 3.0,
     "quantities": [("distance of the centres (3 s)", "m", duel_distance),
                    ("energy (3 s)", "J", lambda s, c: float(c["energy"][-1]))]},
    {"name": "coin", "title": "coin", "duration": 0.3, "sample": 0.0, "knob_sample": 1e-4,
     "first_sample_event": True, "full_reference": [0],
     "quantities": [("spin stops at t", "s", coin_stop)]},
    {"name": "die", "title": "die", "duration": 2.0,
     "quantities": [("energy E(0.125 s)", "J",
                     lambda s, c: float(np.interp(DIE_ENERGY_TIME, c["t"], c["energy"]))),
                    ("distance travelled (2 s)", "m", die_travel)]},
]


# ------------------------------------------------------------------------------------------------
# Runs

def sha1_of(path):
    h = hashlib.sha1()
    with open(path, "rb") as f:
        h.update(f.read())
    return h.hexdigest()


def read_csv(path):
    with open(path) as f:
        header = f.readline().strip().split(",")
    m = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return {name: m[:, k] for k, name in enumerate(header)}


class Runner:
    def __init__(self, args, root):
        self.args = args
        self.root = root
        self.binary_sha = sha1_of(args.simulate)
        self.cache = os.path.join(args.out, "runs")
        os.makedirs(self.cache, exist_ok=True)
        self.scene_sha = {}
        self.fresh = 0
        self.cached = 0
        self.done = {}  # key: result of the runs made in this session (--rerun runs each once)
        self.seconds = 0.0

    def scene_args(self, scene):
        if scene.get("urdf", "") is None:
            return []
        name = scene["name"]
        return ["--urdf", os.path.join(self.root, "urdf", name + ".urdf"),
                "--initial", os.path.join(self.root, "config", name + ".yaml")]

    def key(self, scene, integrator, dt, duration, extra, decimate, subsample):
        files = [a for a in self.scene_args(scene) if a.endswith((".urdf", ".yaml"))]
        text = json.dumps([self.binary_sha, [sha1_of(f) for f in files], scene["name"],
                           integrator, dt, duration, extra, scene.get("sample", SAMPLE),
                           decimate, subsample])
        tol = "_tol%g" % float(extra[extra.index("--accuracy") + 1]) if "--accuracy" in extra else ""
        return "%s_%s_dt%g%s_%s" % (scene["name"], integrator, dt, tol,
                                    hashlib.sha1(text.encode()).hexdigest()[:12])

    def run(self, scene, integrator, dt, duration=None, extra=(), decimate=None, series=None,
            subsample=None):
        """One simulate run (cached): {'status', 'cpu', 'values', 'summary', ...}.
        subsample: a CSV spacing [s]; the quantities are also evaluated on the rows at its
        multiples ('values_subsampled'): the error that spacing alone makes."""
        duration = scene["duration"] if duration is None else duration
        sample = scene.get("sample", SAMPLE)
        if decimate is None:
            decimate = max(1, round(sample / dt)) if sample > 0 else 1
        key = self.key(scene, integrator, dt, duration, list(extra), decimate, subsample)
        path = os.path.join(self.cache, key + ".json")
        if key in self.done:
            return self.done[key]
        if os.path.exists(path) and not self.args.rerun:
            self.cached += 1
            return load_json(path)
        # the adaptive stepper lands on the CSV's sample times only while it writes one
        adaptive = "--accuracy" in extra
        base = [self.args.simulate, "--integrator", integrator, "--dt", repr(dt),
                "--duration", repr(duration), "--quiet"] + self.scene_args(scene) + list(extra)
        taskset = ["taskset", "-c", str(self.args.cpu)] if self.args.cpu >= 0 else []
        result = {"scene": scene["name"], "integrator": integrator, "dt": dt,
                  "duration": duration, "extra": list(extra)}
        start = time.time()
        with tempfile.TemporaryDirectory() as tmp:
            csv_path, summary_path = os.path.join(tmp, "run.csv"), os.path.join(tmp, "run.json")
            command = taskset + base + ["--csv", csv_path, "--decimate", str(decimate),
                                        "--summary", summary_path]
            try:
                proc = subprocess.run(command, timeout=TIMEOUT, stdout=subprocess.DEVNULL,
                                      stderr=subprocess.PIPE, text=True)
            except subprocess.TimeoutExpired:
                proc = None
            if proc is None:
                result["status"] = "timeout (> %g s)" % TIMEOUT
            elif proc.returncode == 3:
                result["status"] = "diverged"
            elif proc.returncode != 0:
                raise RuntimeError("simulate failed (%d): %s\n%s" % (
                    proc.returncode, " ".join(command), proc.stderr))
            else:
                summary = load_json(summary_path)
                columns = read_csv(csv_path)
                result["status"] = "ok"
                result["cpu"] = summary["cpu_time_s"]
                result["summary"] = {k: summary.get(k) for k in (
                    "cpu_time_s", "wall_time_s", "steps", "energy_initial", "energy_final",
                    "unconverged_steps", "max_penetration", "integrator", "t_peg_touchdown",
                    "accuracy", "accepted_steps", "rejected_steps", "forced_steps",
                    "simulator_steps", "smallest_step", "largest_step", "max_error_estimate",
                    "mean_error_estimate")}
                result["values"] = [q[2](summary, columns) for q in scene.get("quantities", [])]
                if subsample:
                    t = columns["t"]
                    keep = np.abs(t / subsample - np.round(t / subsample)) < 1e-6
                    keep[-1] = True
                    sub = {k: v[keep] for k, v in columns.items()}
                    result["values_subsampled"] = [q[2](summary, sub)
                                                   for q in scene.get("quantities", [])]
                if scene["name"] == "die":
                    result["face"] = die_face(columns)
                if series:
                    result["series"] = series(summary, columns)
        if result["status"] == "ok" and result["cpu"] < MIN_TIMED and not self.args.quick:
            with tempfile.TemporaryDirectory() as tmp:
                for _ in range(2):
                    summary_path = os.path.join(tmp, "run.json")
                    csv = (["--csv", os.path.join(tmp, "run.csv"), "--decimate", str(decimate)]
                           if adaptive else [])
                    subprocess.run(taskset + base + csv + ["--summary", summary_path], check=True,
                                   timeout=TIMEOUT, stdout=subprocess.DEVNULL)
                    again = load_json(summary_path)
                    if again["steps"] != result["summary"]["steps"]:
                        raise RuntimeError("a repeat of %s took %s steps, not %s" % (
                            key, again["steps"], result["summary"]["steps"]))
                    result["cpu"] = min(result["cpu"], again["cpu_time_s"])
        self.seconds += time.time() - start
        self.fresh += 1
        with open(path, "w") as f:
            json.dump(result, f)
        self.done[key] = result
        return result


# ------------------------------------------------------------------------------------------------
# Analysis

def relative_error(value, reference):
    if value is None or reference is None:
        return None if value is None and reference is None else float("inf")
    if reference == 0:
        return abs(value)
    return abs(value - reference) / abs(reference)


def cost_at(points, target=TARGET):
    """CPU time for `target` error along one integrator's runs, sorted by increasing CPU (log-log
    interpolation between the last run above and the first run below it).
    Returns (cpu, kind): kind '=' interpolated, '<=' already the cheapest run is within, '>'
    no run reaches it (cpu = the dearest run)."""
    points = sorted((p for p in points if p[1] is not None and math.isfinite(p[1])),
                    key=lambda p: p[0])
    if not points:
        return None, ">"
    # the first run from which on every dearer run is within the target
    k = len(points)
    while k > 0 and points[k - 1][1] <= target:
        k -= 1
    if k == len(points):
        return points[-1][0], ">"
    if k == 0:
        return points[0][0], "<="
    (c0, e0), (c1, e1) = points[k - 1], points[k]
    if e1 <= 0:
        return c1, "="
    w = (math.log(e0) - math.log(target)) / (math.log(e0) - math.log(e1))
    return math.exp(math.log(c0) + w * (math.log(c1) - math.log(c0))), "="


def format_cost(cost):
    cpu, kind = cost
    if cpu is None:
        return "—"
    return {"=": "%.3g s", "<=": "≤ %.3g s", ">": "> %.3g s"}[kind] % cpu


def format_ratio(slow, fast):
    """moreau's cost over moreau2's, with the bound the kinds allow."""
    (c1, k1), (c2, k2) = slow, fast
    if c1 is None or c2 is None:
        return "—"
    r = "%.2g×" % (c1 / c2)
    if k1 == "=" and k2 == "=":
        return r
    if k1 in ("=", ">") and k2 in ("=", "<="):
        return "≥ " + r
    if k1 == "<=" and k2 in ("=", ">"):
        return "≤ " + r
    return "n/a (both within at their cheapest run)" if k1 == "<=" else "n/a (neither reaches it)"


def fmt(x, digits=6):
    if x is None:
        return "never"
    if isinstance(x, float) and not math.isfinite(x):
        return str(x)
    return "%.*g" % (digits, x)


def fmt_tol(tol):
    """1e-3, not 0.001."""
    mantissa, exponent = ("%.0e" % tol).split("e")
    return "%se%d" % (mantissa, int(exponent))


def fmt_err(e):
    if e is None:
        return "—"
    if not math.isfinite(e):
        return "∞"
    return "%.2e" % e


def table(rows):
    lines = ["| " + " | ".join(rows[0]) + " |", "|" + "---|" * len(rows[0])]
    lines += ["| " + " | ".join(r) + " |" for r in rows[1:]]
    return "\n".join(lines)


# ------------------------------------------------------------------------------------------------
# The study

def knob_sample(scene):
    return scene.get("knob_sample", KNOB_SAMPLE)


def knob_tols(args, scene):
    if args.quick:
        return QUICK_TOLS
    return TOLS + (GOAL_TOLS if scene.get("goal") else [])


def series_of(run):
    """'moreau', 'moreau2' or KNOB."""
    return KNOB if "--accuracy" in run.get("extra", []) else run["integrator"]


def tol_of(run):
    extra = run.get("extra", [])
    return float(extra[extra.index("--accuracy") + 1]) if "--accuracy" in extra else None


def study(args, runner, out):
    dts = QUICK_DTS if args.quick else DTS
    results = {}
    for scene in SCENES:
        name = scene["name"]
        print("work_precision: %s, %g s ..." % (name, scene["duration"]), file=sys.stderr)
        ref = runner.run(scene, *REFERENCE, subsample=knob_sample(scene))
        if ref["status"] != "ok":
            raise RuntimeError("the reference of %s did not run: %s" % (name, ref["status"]))
        runs = []
        for integrator in ("moreau", "moreau2"):
            for dt in dts[integrator]:
                runs.append(runner.run(scene, integrator, dt))
        for tol in knob_tols(args, scene):
            runs.append(runner.run(scene, "moreau2", knob_sample(scene), decimate=1,
                                   extra=["--accuracy", repr(tol)]))
        checks = [runner.run(scene, i, dt) for i, dt in CHECK
                  if not (args.quick and (i, dt) == ("moreau2", 2e-5))]
        results[name] = {"scene": scene, "ref": ref, "runs": runs, "checks": checks}

    print("work_precision: Euler's disk rolling, %g s ..." % (
        DISK["quick_duration"] if args.quick else DISK["duration"]), file=sys.stderr)
    disk_scene = {"name": "euler_disk", "duration": DISK["duration"]}

    def disk_series(s, c):
        return {"t": c["t"].tolist(), "energy": c["energy"].tolist(),
                "alpha": np.degrees(np.arccos(np.clip(e3(c, "euler_disk")[2], -1, 1))).tolist()}
    disk = {}
    for integrator in ("moreau", "moreau2"):
        disk[integrator] = runner.run(
            disk_scene, integrator, DISK["dt"],
            duration=DISK["quick_duration"] if args.quick else DISK["duration"],
            extra=DISK["args"], decimate=DISK["decimate"], series=disk_series)
    return results, disk


def knob_reference(r):
    """The reference values the knob's runs are compared with: the reference's quantities from
    its CSV rows at the knob's sample times (both land on them, so the error of interpolating a
    crossing or a value between them cancels to leading order), except the scene's
    "full_reference" quantities: a stop time quantised to the spacing (the coin), or a sharp peak
    (the rattleback's spin, 0.15 % lower at a 2 ms spacing; its sampled value turns a shift in
    time into an error in value), for which the sampling error counts as a limit instead."""
    ref = r["ref"]
    values = list(ref.get("values_subsampled") or ref["values"])
    for k in r["scene"].get("full_reference", []):
        values[k] = ref["values"][k]
    return values


def honesty(r, checks, knob_runs, tols):
    """Rows of the honesty table for one scene: its first quantity and its goal quantities."""
    scene, ref = r["scene"], r["ref"]
    ref_values = ref["values"]
    knob_ref = knob_reference(r)
    rows = []
    for k in sorted(set([0] + scene.get("goal", []))):
        qname, unit, _ = scene["quantities"][k]
        check = checks.get(("moreau2", 2e-5))
        ref_err = (relative_error(check["values"][k], ref_values[k])
                   if check and check["status"] == "ok" else None)
        sub = ref.get("values_subsampled")
        sample_err = relative_error(sub[k], ref_values[k]) if sub else None
        if k == 0 and scene.get("first_sample_event") and ref_values[0]:
            sample_err = max(sample_err or 0.0, knob_sample(scene) / abs(ref_values[0]))
        sampled = k in scene.get("full_reference", [])
        row = [scene["title"], qname + (" (goal)" if k in scene.get("goal", []) else ""),
               fmt_err(ref_err), fmt_err(sample_err)]
        for tol in tols:
            run = knob_runs.get(tol)
            if run is None:
                row.append("—")
                continue
            if run["status"] != "ok":
                row.append(run["status"])
                continue
            if tol in GOAL_TOLS and run["cpu"] > GOAL_CPU:
                row.append("over %g s CPU" % GOAL_CPU)
                continue
            e = relative_error(run["values"][k], knob_ref[k])
            limits = [(x, label) for x, label in ((ref_err, "ref-limited"),
                                                  (sample_err if sampled else None,
                                                   "sample-limited"))
                      if x is not None and x > max(tol / REF_MARGIN, e / ERR_MARGIN)]
            if not math.isfinite(e):
                row.append("**∞**")
            elif limits:
                # the knob's own sampling error may be a few times the reference's (where the
                # peak falls between two samples)
                floor = sum(x * (ERR_MARGIN if label == "sample-limited" else 1.0)
                            for x, label in limits)
                if e - floor > HONEST[1] * tol:  # too large whatever the reference's error
                    row.append("**≥ %.2g**" % ((e - floor) / tol))
                else:
                    row.append(" / ".join(label for _, label in limits))
            else:
                ratio = e / tol
                cell = "%.2g" % ratio
                if not HONEST[0] <= ratio <= HONEST[1]:
                    cell = "**%s**" % cell
                row.append(cell + ("?" if ref_err is None else ""))
        rows.append(row)
    return rows


def report(args, results, disk, runner):
    out = []
    p = out.append
    p("Δt grid: moreau %s; moreau2 %s; reference moreau2 at Δt = %g (every scene). "
      "Error = |q − q_ref| / |q_ref|; CPU = `cpu_time_s` of the stepping (one core%s)." % (
          ", ".join("%g" % d for d in (QUICK_DTS if args.quick else DTS)["moreau"]),
          ", ".join("%g" % d for d in (QUICK_DTS if args.quick else DTS)["moreau2"]),
          REFERENCE[1], "" if args.quick else "; runs under %g s: the least of 3" % MIN_TIMED))
    p("")
    p("Accuracy knob: `moreau2 --accuracy TOL` for TOL = %s%s, defaults `--min-dt 1e-6 --max-dt "
      "1e-2`, a CSV row every %g s (`--dt %g --decimate 1`; the coin every %g s), which caps its "
      "step; in the tables its Δt column is the range of accepted steps. Its error is against the "
      "reference's quantity from the reference's CSV rows at the same sample times (a crossing "
      "between samples is then interpolated alike in both), except the rattleback's peak spin "
      "(a sharp maximum: its sampled value turns a shift in time into an error) and the coin's "
      "stop time (the first sample below the threshold), which are against the full reference "
      "and include the sampling error." % (
          ", ".join(fmt_tol(t) for t in (QUICK_TOLS if args.quick else TOLS)),
          "" if args.quick else " (and %s for the scenes with a goal, see the honesty table)" %
          ", ".join(fmt_tol(t) for t in GOAL_TOLS), KNOB_SAMPLE, KNOB_SAMPLE,
          next(knob_sample(r["scene"]) for r in results.values()
               if r["scene"]["name"] == "coin")))
    p("")
    summary_rows = [("scene", "quantity", "reference", "moreau err @1e-4", "moreau2 err @1e-4",
                     "CPU moreau2/moreau @1e-4", "moreau CPU for 1 %", "moreau2 CPU for 1 %",
                     "ratio moreau/moreau2", "ratio for 0.1 %", "knob CPU for 1 %",
                     "ratio moreau/knob")]
    all_tols = (QUICK_TOLS if args.quick else TOLS + GOAL_TOLS)
    honesty_rows = [["scene", "quantity", "reference error", "sampling error"] +
                    ["TOL %s" % fmt_tol(t) for t in all_tols]]
    check_rows = [("scene", "q_ref (moreau2, 1e-5)", "moreau2 2e-5 vs ref", "moreau 1e-5 vs ref",
                   "moreau extrapolated vs ref", "smallest moreau2 error plotted")]
    fig_data = {}
    for name, r in results.items():
        scene = r["scene"]
        quantities = scene["quantities"]
        ref_values = r["ref"]["values"]
        knob_ref = knob_reference(r)
        p("### %s (%g s)" % (scene["title"], scene["duration"]))
        p("")
        header = ["integrator", "Δt [s]"]
        for k, (qname, unit, _) in enumerate(quantities):
            header += ["%s [%s]" % (qname, unit), "error"]
        header += ["CPU [s]", "steps (accepted / rejected)"]
        if name == "die":
            header += ["face up"]
        rows = [header]
        points = {"moreau": [], "moreau2": [], KNOB: []}
        at_1e4 = {}
        knob_runs = {}
        for run in r["runs"] + [r["ref"]]:
            series = series_of(run)
            if series == KNOB:
                knob_runs[tol_of(run)] = run
                row = ["%s %s" % (KNOB, fmt_tol(tol_of(run)))]
                sm = run.get("summary", {})
                row.append("%.2g–%.2g" % (sm["smallest_step"], sm["largest_step"])
                           if run["status"] == "ok" else "")
            else:
                row = [run["integrator"] + (" (ref)" if run is r["ref"] else ""),
                       "%g" % run["dt"]]
            if run["status"] != "ok":
                rows.append(row + [run["status"]] + [""] * (len(header) - 3))
                continue
            errors = [relative_error(v, rv) for v, rv in
                      zip(run["values"], knob_ref if series == KNOB else ref_values)]
            for v, e in zip(run["values"], errors):
                row += [fmt(v), "ref" if run is r["ref"] else fmt_err(e)]
            row += ["%.4f" % run["cpu"]]
            sm = run["summary"]
            row += ["%d / %d" % (sm["accepted_steps"], sm["rejected_steps"]) if series == KNOB
                    else "%d" % sm["steps"]]
            if name == "die":
                row += ["%+d" % run["face"]]
            rows.append(row)
            if run is not r["ref"]:
                points[series].append((run["cpu"], errors[0],
                                       tol_of(run) if series == KNOB else run["dt"]))
                if run["dt"] == 1e-4 and series != KNOB:
                    at_1e4[run["integrator"]] = (errors[0], run["cpu"])
        p(table(rows))
        p("")
        costs = {i: cost_at([(c, e) for c, e, _ in points[i]]) for i in points}
        fine = {i: cost_at([(c, e) for c, e, _ in points[i]], TARGET / 10) for i in points}
        fig_data[name] = (scene, points)
        e1, c1 = at_1e4.get("moreau", (None, None))
        e2, c2 = at_1e4.get("moreau2", (None, None))
        summary_rows.append((scene["title"], quantities[0][0], fmt(ref_values[0]) + " " +
                             quantities[0][1], fmt_err(e1), fmt_err(e2),
                             "%.2f" % (c2 / c1) if c1 and c2 else "—",
                             format_cost(costs["moreau"]), format_cost(costs["moreau2"]),
                             format_ratio(costs["moreau"], costs["moreau2"]),
                             format_ratio(fine["moreau"], fine["moreau2"]),
                             format_cost(costs[KNOB]), format_ratio(costs["moreau"], costs[KNOB])))
        checks = {(c["integrator"], c["dt"]): c for c in r["checks"]}
        honesty_rows += honesty(r, checks, knob_runs, all_tols)
        smallest = min((e for _, e, dt in points["moreau2"] if e is not None), default=None)
        check = [scene["title"], fmt(ref_values[0], 8)]
        for key in CHECK:
            c = checks.get(key)
            check.append(fmt_err(relative_error(c["values"][0], ref_values[0]))
                         if c and c["status"] == "ok" else "—")
        # moreau is first order: 2 q(1e-5) - q(2e-5) cancels its leading error term
        m = {run["dt"]: run for run in r["runs"]
             if run["integrator"] == "moreau" and run["status"] == "ok"}
        if 1e-5 in m and 2e-5 in m and None not in (m[1e-5]["values"][0], m[2e-5]["values"][0]):
            extrapolated = 2 * m[1e-5]["values"][0] - m[2e-5]["values"][0]
            check.append(fmt_err(relative_error(extrapolated, ref_values[0])))
        else:
            check.append("—")
        check.append(fmt_err(smallest))
        check_rows.append(check)

    p("### Summary")
    p("")
    p(table(summary_rows))
    p("")
    p("CPU for 1 %%: interpolated log-log between the runs around %g %% error; “≤” the cheapest run "
      "is already within, “>” no run is. Ratio ≥ 10× is the goal. “ratio for 0.1 %%”: the same "
      "ratio for %g %% error. The knob's CPU for 1 %% is read the same way along its TOL series; "
      "ratio moreau/knob: moreau's CPU for 1 %% over the knob's." % (100 * TARGET, 10 * TARGET))
    p("")
    p("### Is the accuracy knob honest?")
    p("")
    p("Achieved relative error / TOL of `%s TOL` (goal: within %g–%g for the quantities marked "
      "“goal”; the others are as they come). Reference error: moreau2 at 2e-5 against the "
      "reference (see the next section), taken as the reference's own error; sampling error: the "
      "reference's quantity from its CSV rows every %g s (the coin: every %g s, and at least one "
      "spacing) against all of them, which the knob's error (against the former) leaves out, "
      "except for the rattleback's peak spin and the coin's stop time (compared with the full "
      "reference). Where the reference error (or those two's sampling error) is above both TOL/%g "
      "(3× below the band's %g TOL) and a third of the achieved error, the ratio cannot be told: "
      "“ref-limited” or “sample-limited”, unless the error exceeds %g TOL even after "
      "subtracting it (then “≥”). Bold: outside %g–%g." % (
          KNOB, HONEST[0], HONEST[1], KNOB_SAMPLE,
          next(knob_sample(r["scene"]) for r in results.values() if r["scene"]["name"] == "coin"),
          REF_MARGIN, HONEST[0], HONEST[1], HONEST[0], HONEST[1]) +
      (" “?”: the reference is not checked (--quick)." if args.quick else ""))
    p("")
    p(table(honesty_rows))
    p("")
    p("### Are the references converged?")
    p("")
    p("Relative differences from the reference q_ref of: moreau2 at 2e-5 (if moreau2 is second "
      "order the reference's own error is about a third of it), moreau at 1e-5, and moreau's "
      "first-order extrapolation 2 q(1e-5) − q(2e-5); last, the smallest moreau2 error in the "
      "figure. A reference is good where the first two or three are well below the last.")
    p("")
    p(table(check_rows))
    p("")

    # the disc
    p("### Euler's disk rolling without slip (%s, Δt = %g, %g s)" % (
        " ".join(DISK["args"]), DISK["dt"], disk["moreau"]["duration"]))
    p("")
    rows = [("integrator", "energy drift (fit) [1/s]", "E(end)/E0 − 1", "α(0) [deg]",
             "α(end) [deg]", "CPU [s]")]
    for integrator, run in disk.items():
        if run["status"] != "ok":
            rows.append((integrator, run["status"], "", "", "", ""))
            continue
        s = run["series"]
        t, E, alpha = np.array(s["t"]), np.array(s["energy"]), np.array(s["alpha"])
        rel = E / E[0] - 1
        slope = np.polyfit(t, rel, 1)[0]
        rows.append((integrator, "%+.2e" % slope, "%+.2e" % rel[-1], "%.4f" % alpha[0],
                     "%.4f" % alpha[-1], "%.3f" % run["cpu"]))
    p(table(rows))
    p("")
    return "\n".join(out), fig_data


def plot_work_precision(path, fig_data):
    n = len(fig_data)
    cols = 4
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(4.0 * cols, 3.4 * rows), squeeze=False)
    style = {"moreau": ("tab:blue", "o", "moreau (1st order)"),
             "moreau2": ("tab:red", "s", "moreau2 (2nd order)"),
             KNOB: ("tab:green", "^", "moreau2 --accuracy TOL")}
    for ax, (name, (scene, points)) in zip(axes.ravel(), fig_data.items()):
        floor = None
        for integrator, pts in points.items():
            pts = [p for p in pts if p[1] is not None]
            if not pts:
                continue
            color, marker, label = style[integrator]
            c = [p[0] for p in pts]
            e = [p[1] if p[1] > 0 else np.nan for p in pts]
            ax.loglog(c, e, marker=marker, color=color, label=label, ms=4)
            for cc, ee, dt in pts:
                if ee and ee > 0 and math.isfinite(ee):
                    ax.annotate(fmt_tol(dt) if integrator == KNOB else "%g" % dt, (cc, ee),
                                fontsize=6, color=color,
                                xytext=(3, 2), textcoords="offset points")
            floor = min([x for x in e if x == x] + ([floor] if floor else []))
        ax.axhline(TARGET, color="gray", lw=0.8, ls="--")
        ax.set_title("%s: %s" % (scene["title"], scene["quantities"][0][0]), fontsize=9)
        ax.set_xlabel("CPU time [s]", fontsize=8)
        ax.set_ylabel("relative error", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(True, which="major", alpha=0.3)
    for ax in axes.ravel()[n:]:
        ax.axis("off")
    axes[0][0].legend(fontsize=7)
    fig.suptitle("Work–precision per scene (labels: Δt [s], for --accuracy TOL; dashed: 1 %; "
                 "reference moreau2 at Δt = 1e-5)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_disk(path, disk):
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 3.8))
    for integrator, color in (("moreau", "tab:blue"), ("moreau2", "tab:red")):
        run = disk[integrator]
        if run["status"] != "ok":
            continue
        s = run["series"]
        t, E = np.array(s["t"]), np.array(s["energy"])
        a.plot(t, E / E[0] - 1, color=color, label=integrator)
        b.plot(t, s["alpha"], color=color, label=integrator)
    a.set_xlabel("t [s]")
    a.set_ylabel("E(t)/E0 − 1")
    a.set_title("energy (exact: constant)")
    b.set_xlabel("t [s]")
    b.set_ylabel("α [deg]")
    b.set_title("inclination α (exact: 30°)")
    for ax in (a, b):
        ax.grid(alpha=0.3)
        ax.legend()
    fig.suptitle("Euler's disk rolling without slip (μ = 10, coulomb, point contact), "
                 "Δt = %g" % DISK["dt"])
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--simulate", required=True, help="the simulate binary")
    parser.add_argument("--quick", action="store_true",
                        help="a reduced set (moreau at 1e-3, 1e-4, 1e-5; moreau2 at 1e-3, 1e-4; "
                             "the knob at TOL 1e-2, 1e-3; the disc for 10 s; no repeated timing)")
    parser.add_argument("--out", default=None, help="cache and report (default out/work_precision)")
    parser.add_argument("--docs", default=None,
                        help="where the PNGs go (default docs/; with --quick the --out folder, so "
                             "that a reduced study never replaces the figures of docs/)")
    parser.add_argument("--rerun", action="store_true", help="ignore cached runs")
    parser.add_argument("--command", default="scripts/dev/work_precision", help="for the header")
    parser.add_argument("--cpu", type=int, default=1, help="taskset core (-1: no pinning)")
    args = parser.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    args.out = args.out or os.path.join(root, "out", "work_precision")
    args.docs = args.docs or (args.out if args.quick else os.path.join(root, "docs"))
    os.makedirs(args.out, exist_ok=True)
    os.makedirs(args.docs, exist_ok=True)
    if shutil_which("taskset") is None:
        args.cpu = -1

    runner = Runner(args, root)
    start = time.time()
    results, disk = study(args, runner, args.out)
    if sha1_of(args.simulate) != runner.binary_sha:
        print("work_precision: WARNING: %s changed during the study; rerun" % args.simulate,
              file=sys.stderr)
    text, fig_data = report(args, results, disk, runner)
    plot_work_precision(os.path.join(args.docs, "accuracy_work_precision.png"), fig_data)
    plot_disk(os.path.join(args.docs, "accuracy_disk.png"), disk)

    try:
        commit = subprocess.run(["git", "-C", root, "rev-parse", "--short", "HEAD"],
                                capture_output=True, text=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", root, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True).stdout.strip()
    except OSError:
        commit, dirty = "?", ""
    mtime = datetime.datetime.fromtimestamp(os.path.getmtime(args.simulate))
    header = ("Generated by `%s` on %s, commit %s%s; simulate built %s (sha1 %s). "
              "%d runs (%d fresh, %d cached), %.0f s." % (
                  args.command, datetime.date.today().isoformat(), commit,
                  " (with uncommitted changes)" if dirty else "",
                  mtime.strftime("%Y-%m-%d %H:%M"), runner.binary_sha[:10],
                  runner.fresh + runner.cached, runner.fresh, runner.cached,
                  time.time() - start))
    text = header + "\n\n" + text
    with open(os.path.join(args.out, "report.md"), "w") as f:
        f.write(text + "\n")
    print(text)


def shutil_which(name):
    import shutil
    return shutil.which(name)


if __name__ == "__main__":
    main()
