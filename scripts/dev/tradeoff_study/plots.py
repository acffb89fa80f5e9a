"""The figures: Pareto plots per friction set, the references, the gyroscopic sweep."""
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)

from .analyse import pareto, unit_cost  # noqa: E402
from .grid import GYRO_CLIP, PLOT_DT, SOLVER_SHORT, TOUCHDOWN  # noqa: E402


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


def draw_all(grid, rows, refs, gyro_rows, docs):
    """Every figure into docs; the Pareto plots' file names per friction set."""
    pngs = {}
    for s in grid["sets"]:
        own = [r for r in rows if r["set"] == s]
        if own and s in refs:
            name = "tradeoff_%s.png" % s
            plot_pareto(own, s, unit_cost(refs[s]["summary"]), os.path.join(docs, name))
            pngs[s] = name
    if refs:
        plot_references(refs, grid["duration"], os.path.join(docs, "tradeoff_references.png"))
    if gyro_rows:
        plot_gyro(gyro_rows, os.path.join(docs, "tradeoff_gyroscopic.png"))
    return pngs
