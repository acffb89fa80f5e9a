"""Analysing: accuracy against the reference of the same law, cost, orders, Pareto fronts."""
import math

import numpy as np

from .grid import FRONT_STEP, SETS, SOLVERS


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


def fastest(rows, predicate):
    candidates = [r for r in rows if predicate(r)]
    return min(candidates, key=lambda r: r["cpu_time_s"]) if candidates else None


def gyro_rows_of(records):
    """The gyroscopic sweep: per run its spin, dt, scheme and energy figures (inf: blown up)."""
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
    return gyro_rows


def decoupled_and_long(records):
    """The decoupled laws' runs by (set, dt), and the hour-long runs."""
    decoupled_rows = {(r["config"]["set"], r["config"]["dt"]): r["summary"]
                      for r in records.values() if r["config"]["kind"] == "decoupled"}
    long_rows = [r for r in records.values() if r["config"]["kind"] == "long"]
    return decoupled_rows, long_rows
