#!/usr/bin/python3
"""Runs the Tippe-Top against the peer engines and writes docs/compare.md and its figure.

Called by scripts/compare (which installs the engines, builds bench/peers and `simulate` and
writes the N-top scenes); by hand:

    scripts/compare_report.py --simulate BIN --peers-dir DIR --scenes-dir DIR [options]

Two measurements, every run pinned to one core (taskset -c CPU), one process at a time, all of
them interleaved (round-robin over every configuration, R rounds), CPU time of the stepping
loop only, median of R:
  (a) one Tippe-Top, config/tippe_top.yaml start, DURATION s at DT: ours per friction set (the
      built-in scene, as scripts/speed runs it) and each peer engine per setting, with the
      physics (inversion, peg touchdown, energy);
  (b) N independent tops (bench/peers/multi_top_scene.py, StartOf() of
      bench/peers/tippe_top_scene.h) for SCALING_DURATION s: CPU per body-step against N.
"""
import argparse
import datetime
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench", "peers"))
from multi_top_scene import SPACING, start_of  # noqa: E402  the starts of the N tops
INVERTED = math.radians(150.0)

# (a): ours per friction set, and every peer setting (program, setting)
OUR_SETS = ["coulomb", "cylinder", "sphere", "exact"]
PEER_SETTINGS = [("ode", "world_step"), ("ode", "quick_step"),
                 ("mujoco", "elliptic"), ("mujoco", "pyramidal"), ("mujoco", "elliptic_condim3"),
                 ("bullet", "default"), ("bullet", "iter100_2dir")]
# (b): one configuration per engine, its default
SCALING = [("ours", "sphere"), ("ode", "world_step"), ("mujoco", "elliptic"), ("bullet", "default")]

# what each setting is, for the table (the programs print the same in "settings")
DESCRIPTION = {
    ("ours", "coulomb"): "Coulomb, no drilling friction; Gauss–Seidel, tol 1e-5",
    ("ours", "cylinder"): "C_F: drilling limited separately (decoupled); Gauss–Seidel",
    ("ours", "sphere"): "S_F (E_F mapped): drilling coupled to sliding; Gauss–Seidel (default)",
    ("ours", "exact"): "B_F (Hertz disc, coupled), mapped; Gauss–Seidel",
    ("ours", "ellipsoid"): "E_F iterated on itself (the paper's reference; slow by design)",
    ("ode", "world_step"): "dWorldStep (LCP), box friction μ = 0.3 ∝ λ_N (Approx1), drilling row ρ_N = μR̄ (Approx1_N), ERP 0.2, CFM 1e-10",
    ("ode", "quick_step"): "dWorldQuickStep 20 iterations, otherwise as world_step",
    ("mujoco", "elliptic"): "elliptic cone, condim 4, friction (0.3, μR̄, 0), Newton, Euler, default solref/solimp",
    ("mujoco", "pyramidal"): "pyramidal cone (default), condim 4, friction (0.3, μR̄, 0), Newton, Euler",
    ("mujoco", "elliptic_condim3"): "check: elliptic cone, condim 3 = no torsional friction",
    ("bullet", "default"): "sequential impulse, 10 iterations, 1 friction direction, spinning friction μR̄ (rolling 1e-12 to enable it), split impulse",
    ("bullet", "iter100_2dir"): "sequential impulse, 100 iterations, 2 friction directions, otherwise as default",
}
ENGINE_NAME = {"ours": "nonsmooth_sim", "ode": "ODE", "mujoco": "MuJoCo", "bullet": "Bullet"}


def peer_binary(peers_dir, engine):
    return os.path.join(peers_dir, f"{engine}_tops")


def command(cfg, args, tmp):
    """argv of one run and how to read it: (argv, summary path or None)."""
    engine, setting, n, duration = cfg
    if engine == "ours":
        summary = os.path.join(tmp, "summary.json")
        argv = [args.simulate, "--quiet", "--friction-set", setting, "--duration", repr(duration),
                "--dt", repr(args.dt), "--summary", summary]
        if n is not None:
            base = os.path.join(args.scenes_dir, f"tippe_tops_{n}")
            argv += ["--urdf", base + ".urdf", "--initial", base + ".yaml"]
        return argv, summary
    argv = [peer_binary(args.peers_dir, engine), "--setting", setting, "--n", str(n or 1),
            "--duration", repr(duration), "--dt", repr(args.dt)]
    return argv, None


def run(cfg, args, tmp):
    argv, summary = command(cfg, args, tmp)
    n = cfg[2]
    pinned = ["taskset", "-c", str(args.cpu)] + argv
    out = subprocess.run(pinned, check=True, stdout=subprocess.PIPE, text=True).stdout
    if summary is None:
        line = [l for l in out.splitlines() if l.startswith("{")][-1]
        return json.loads(line)
    with open(summary) as f:
        s = json.load(f)
    excursion = None
    if n is not None:  # ours keeps no excursion history: the final distance from the start
        excursion = max(math.hypot(s["bodies"][f"top{i}"]["position"][0] - start_of(i, n)[0][0],
                                   s["bodies"][f"top{i}"]["position"][1] - start_of(i, n)[0][1])
                        for i in range(n))
    return {"max_excursion": excursion, "engine": "ours", "cpu_s": s["cpu_time_s"], "steps": s["steps"],
            "theta_max": s["theta_max"], "inverts": s["theta_max"] > INVERTED,
            "t_theta_above_2_4": s["t_theta_above_2_4"], "t_peg_touchdown": s["t_peg_touchdown"],
            "theta_final": s["theta_final"], "energy_initial": s["energy_initial"],
            "energy_final": s["energy_final"], "mean_iterations": s["mean_iterations"],
            "unconverged_steps": s["unconverged_steps"]}


def version_of(engine, results):
    for (e, _, _, _), runs in results.items():
        if e == engine and runs and "version" in runs[0]:
            return runs[0]["version"]
    return "?"


def fmt_time(t):
    return "never" if t is None else f"{t:.3f}"


def git_describe():
    try:
        head = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], check=True,
                              stdout=subprocess.PIPE, text=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no"],
                               check=True, stdout=subprocess.PIPE, text=True).stdout.strip()
        return head + (" with uncommitted changes" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def loadavg():
    try:
        with open("/proc/loadavg") as f:
            return " ".join(f.read().split()[:3])
    except OSError:
        return "?"


def slope(ns, costs):
    """Least-squares exponent of total CPU ~ N^k, from the per-body-step costs."""
    xs = [math.log(n) for n in ns]
    ys = [math.log(c * n) for n, c in zip(ns, costs)]
    if len(xs) < 2:
        return float("nan")
    mx, my = statistics.mean(xs), statistics.mean(ys)
    den = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / den if den else float("nan")


def write_figure(path, scaling_rows, ns):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    markers = {"ours": "o", "ode": "s", "mujoco": "^", "bullet": "D"}
    for (engine, setting), costs in scaling_rows:
        label = f"{ENGINE_NAME[engine]} ({setting})"
        ax.loglog(ns, costs, marker=markers.get(engine, "x"), label=label,
                  linewidth=2.2 if engine == "ours" else 1.4)
    ax.set_xlabel("number of Tippe-Tops N")
    ax.set_ylabel("CPU µs per body-step")
    ax.set_xticks(ns)
    ax.set_xticklabels([str(n) for n in ns])
    values = [v for _, costs in scaling_rows for v in costs]
    ticks = [t for t in (0.1, 0.2, 0.3, 0.5, 1, 2, 3, 5, 10, 20, 30, 50, 100)
             if min(values) / 1.5 <= t <= max(values) * 1.5]
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.set_yticks(ticks)
    ax.set_yticklabels([f"{t:g}" for t in ticks])
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    ax.set_title("Cost per body-step against N (median, one core)", fontsize=10)
    fig.tight_layout()
    os.makedirs(os.path.dirname(path), exist_ok=True)
    fig.savefig(path, dpi=110)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--simulate", required=True, help="the simulate binary")
    p.add_argument("--peers-dir", required=True, help="build directory of bench/peers")
    p.add_argument("--scenes-dir", required=True, help="where the N-top scenes are")
    p.add_argument("--repetitions", type=int, default=5)
    p.add_argument("--n", type=int, nargs="+", default=[1, 4, 16, 64, 256])
    p.add_argument("--duration", type=float, default=8.0, help="(a), simulated s")
    p.add_argument("--scaling-duration", type=float, default=8.0, help="(b), simulated s")
    p.add_argument("--dt", type=float, default=1e-4)
    p.add_argument("--cpu", type=int, default=1, help="the core every run is pinned to")
    p.add_argument("--our-sets", nargs="+", default=OUR_SETS,
                   choices=["coulomb", "cylinder", "ellipsoid", "sphere", "exact"])
    p.add_argument("--engines", nargs="+", default=["ode", "mujoco", "bullet"])
    p.add_argument("--doc", default=os.path.join(ROOT, "docs", "compare.md"))
    p.add_argument("--figure", default=os.path.join(ROOT, "docs", "figures", "compare_scaling.png"))
    p.add_argument("--log", help="write every run as a JSON line here")
    p.add_argument("--command", default="scripts/compare", help="the command, for the doc")
    args = p.parse_args()
    if args.repetitions < 1:
        p.error("--repetitions must be >= 1")

    engines = [e for e in args.engines if os.access(peer_binary(args.peers_dir, e), os.X_OK)]
    missing = [e for e in args.engines if e not in engines]
    for e in missing:
        print(f"compare: {peer_binary(args.peers_dir, e)} not built, {e} skipped", file=sys.stderr)

    single = [("ours", s, None, args.duration) for s in args.our_sets]
    single += [(e, s, None, args.duration) for e, s in PEER_SETTINGS if e in engines]
    scaling = [(e, s, n, args.scaling_duration) for e, s in SCALING
               if e == "ours" or e in engines for n in args.n]
    configs = single + scaling
    results = {cfg: [] for cfg in configs}
    start = datetime.datetime.now()
    load_start = loadavg()
    log = open(args.log, "w") if args.log else None
    with tempfile.TemporaryDirectory() as tmp:
        for rep in range(args.repetitions):
            # round-robin; each round starts one configuration later, so that no configuration
            # always runs right after the same neighbour
            order = configs[rep % len(configs):] + configs[:rep % len(configs)]
            for k, cfg in enumerate(order):
                print(f"\rcompare: round {rep + 1}/{args.repetitions}, run {k + 1}/{len(order)}: "
                      f"{cfg[0]} {cfg[1]} N={cfg[2] or 1}      ", end="", file=sys.stderr, flush=True)
                r = run(cfg, args, tmp)
                results[cfg].append(r)
                if log:
                    log.write(json.dumps({"round": rep, "engine": cfg[0], "setting": cfg[1],
                                          "n": cfg[2] or 1, "duration": cfg[3],
                                          "table": "single" if cfg[2] is None else "scaling",
                                          **r}) + "\n")
                    log.flush()
    print(file=sys.stderr)
    minutes = (datetime.datetime.now() - start).total_seconds() / 60.0
    load_end = loadavg()

    def median_cpu(cfg):
        return statistics.median(r["cpu_s"] for r in results[cfg])

    def spread(cfg):
        cpus = [r["cpu_s"] for r in results[cfg]]
        return (max(cpus) - min(cpus)) / statistics.median(cpus)

    ours_ref = ("ours", "sphere", None, args.duration)
    ref_cpu = median_cpu(ours_ref) if ours_ref in results else None

    lines = []
    w = lines.append
    w("# Peer engines: the Tippe-Top in ODE, MuJoCo and Bullet")
    w("")
    w("Written by `scripts/compare` (do not edit by hand: rerun it). Measured "
      f"{start:%Y-%m-%d} with")
    w("")
    w(f"    {args.command}")
    w("")
    w(f"on this repository's machine: {os.cpu_count()} cores ({cpu_model()}), shared with other "
      f"jobs (load average {load_start} at the start, {load_end} at the end; the runs took "
      f"{minutes:.1f} min). Code: {git_describe()}. Engines: Debian 12's packages, "
      f"ODE {version_of('ode', results)} (double precision), MuJoCo "
      f"{version_of('mujoco', results)}, Bullet {version_of('bullet', results)}; ours is "
      "`simulate`, Release (`-O3`, no `-march=native`), the peers are built with the same flags "
      "(`bench/peers/CMakeLists.txt`).")
    w("")
    w("**Method.** Every run is one process pinned to one core (`taskset -c "
      f"{args.cpu}`), one at a time; all configurations of both tables are interleaved "
      f"(round-robin, {args.repetitions} rounds, each round starting one configuration later) "
      "and the tables show the median. Time is the CPU time of the stepping loop only (ours: "
      "the summary's `cpu_time_s`, the thread's CPU time of the loop with its per-step monitors; "
      "the peers: `std::clock()` around the loop, which also updates θ, the event times and the "
      "peg gap of every top each step), not start-up or model building. The machine is shared: "
      "`spread` is (max − min) / median of the runs; compare rows of one table, not across days.")
    w("")
    w("**The scene** (the reference Tippe-Top of Leine & Glocker 2003, "
      "`urdf/tippe_top.urdf`, `config/tippe_top.yaml`; the peers' constants are in "
      "`bench/peers/tippe_top_scene.h`): one body, m = 6 g, A = 8e-7, C = 7e-7 kg m², a sphere "
      "R1 = 15 mm at a1 = 3 mm and a peg sphere R2 = 5 mm at a2 = 16 mm from the centre of mass on "
      "the axis — in every engine one body with two sphere geometries (ODE: two offset geoms; "
      "MuJoCo: two sphere geoms in one free body; Bullet: a compound of two spheres), ground "
      "plane z = 0, μ = 0.3, restitution 0, θ0 = 0.1 rad, spin 180 rad/s, the centre of mass at "
      f"rest; Δt = {args.dt:g} s. The drilling (torsional) friction of the URDF — contact radius "
      "R = 0.5 mm, R̄ = 3πR/16 — is a torque limit μR̄λ_N ≈ 8.84e-5 m × λ_N, given to each engine "
      "as its torsional coefficient. θ is the angle between the body's symmetry axis and the "
      "vertical; **inverts** = θ exceeds 150° (the reference: the peg touches down near 140°, "
      "then the top spins on it near θ = π); **θ > 2.4 rad** is `simulate`'s inversion time; "
      "**peg touchdown** = first time the peg sphere reaches the floor (peers: its lowest point at "
      "z ≤ 0; ours: its contact closes).")
    w("")
    # the headline: ours (sphere, the default) against the fastest peer setting that is not a check
    peers_single = [c for c in single if c[0] != "ours" and c[1] != "elliptic_condim3"]
    if ref_cpu and peers_single:
        fastest = min(peers_single, key=median_cpu)
        fastest_inverting = [c for c in peers_single if results[c][0]["inverts"]]
        text = (f"**In short.** One top, {args.duration:g} s: ours (`sphere`, the default) takes "
                f"{1e3 * ref_cpu:.0f} ms of CPU, the fastest peer ({ENGINE_NAME[fastest[0]]} "
                f"`{fastest[1]}`) {1e3 * median_cpu(fastest):.0f} ms, "
                f"{median_cpu(fastest) / ref_cpu:.1f}× ours")
        if fastest_inverting:
            f2 = min(fastest_inverting, key=median_cpu)
            text += (f"; the fastest peer that inverts the top ({ENGINE_NAME[f2[0]]} `{f2[1]}`) "
                     f"takes {median_cpu(f2) / ref_cpu:.1f}× ours")
        inv = {(c[0], c[1]): results[c][0]["inverts"] for c in single}
        if (inv.get(("ours", "sphere")) and not any(v for (e, _), v in inv.items()
                                                   if e in ("ode", "bullet"))
                and inv.get(("mujoco", "elliptic_condim3"))):
            text += (". Only ours inverts the top with hard contact and a coupled law; ODE and "
                     "Bullet (decoupled drilling friction) do not invert it, MuJoCo inverts it "
                     "even without torsional friction (soft contact; below)")
        w(text + ".")
        w("")
    w(f"## One Tippe-Top, {args.duration:g} s")
    w("")
    w("| engine | setting | what it is | CPU ms | spread | sim s per CPU s | × ours (sphere) | "
      "inverts | θ > 2.4 rad at s | peg touchdown s | θ max ° | θ end ° | energy lost |")
    w("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for cfg in single:
        engine, setting = cfg[0], cfg[1]
        r = results[cfg][0]
        cpu = median_cpu(cfg)
        ratio = f"{cpu / ref_cpu:.2f}" if ref_cpu else "–"
        lost = 1.0 - r["energy_final"] / r["energy_initial"]
        w(f"| {ENGINE_NAME[engine]} | `{setting}` | {DESCRIPTION[(engine, setting)]} | "
          f"{1e3 * cpu:.1f} | {100 * spread(cfg):.0f} % | {args.duration / cpu:.0f} | {ratio} | "
          f"{'**yes**' if r['inverts'] else 'no'} | {fmt_time(r['t_theta_above_2_4'])} | "
          f"{fmt_time(r['t_peg_touchdown'])} | {math.degrees(r['theta_max']):.1f} | "
          f"{math.degrees(r['theta_final']):.1f} | {100 * lost:.1f} % |")
    w("")
    # determinism: every round must give the same physics
    varying = [f"{c[0]} {c[1]}" for c in single
               if len({(r["t_theta_above_2_4"], round(r["theta_final"], 9)) for r in results[c]}) > 1]
    w("The physics columns are those of the first round; "
      + ("every round gave the same θ > 2.4 time and final θ." if not varying else
         "they varied between rounds for: " + ", ".join(varying) + "."))
    w("")
    inverting = [f"{ENGINE_NAME[c[0]]} `{c[1]}`" for c in single if results[c][0]["inverts"]]
    not_inverting = [f"{ENGINE_NAME[c[0]]} `{c[1]}`" for c in single if not results[c][0]["inverts"]]
    w("### Which engines invert the top, and why")
    w("")
    w("Inverts: " + (", ".join(inverting) or "none") + ". Does not invert: "
      + (", ".join(not_inverting) or "none") + ".")
    w("")
    def outcome(engine, settings):
        """One sentence per engine from the measured runs."""
        parts = []
        for setting in settings:
            cfg = (engine, setting, None, args.duration)
            if cfg not in results:
                continue
            r = results[cfg][0]
            lost = 100 * (1.0 - r["energy_final"] / r["energy_initial"])
            if r["inverts"]:
                parts.append(f"`{setting}` inverts (θ > 2.4 rad at {fmt_time(r['t_theta_above_2_4'])} s, "
                             f"θ max {math.degrees(r['theta_max']):.0f}°, {lost:.0f} % of the energy lost)")
            else:
                parts.append(f"`{setting}` does not invert (θ max {math.degrees(r['theta_max']):.1f}°, "
                             f"θ end {math.degrees(r['theta_final']):.1f}°, {lost:.0f} % of the energy lost)")
        return ("Measured: " + "; ".join(parts) + ".") if parts else "Not run."

    def lost_of(engine, setting):
        cfg = (engine, setting, None, args.duration)
        if cfg not in results:
            return None
        r = results[cfg][0]
        return 100 * (1.0 - r["energy_final"] / r["energy_initial"])

    def inverts(engine, setting):
        cfg = (engine, setting, None, args.duration)
        return cfg in results and results[cfg][0]["inverts"]

    w("- **ODE** has no coupled law. Its contact joint gives each row its own box: |f_1|, |f_2| "
      "≤ μλ_N (`dContactApprox1`; a square, not a disc) and, with `dContactRolling`, a drilling "
      "row |τ_n| ≤ ρ_N λ_N (`rhoN` = μR̄, `dContactApprox1_N`, no rolling resistance) clamped "
      "independently of the sliding rows: the decoupled cylinder C_F of the paper, with a box for "
      "its disc. " + outcome("ode", ["world_step", "quick_step"])
      + (" The contact sticks and the top rolls back upright, as with our `cylinder`"
         + (f" ({lost_of('ours', 'cylinder'):.0f} % of the energy lost)"
            if lost_of("ours", "cylinder") is not None else "") + "."
         if not inverts("ode", "world_step") else ""))
    w("- **Bullet** likewise clamps its spinning-friction row (`setSpinningFriction`, μR̄) on its "
      "own, decoupled from the sliding friction. " + outcome("bullet", ["default", "iter100_2dir"])
      + " Bullet adds the spinning row only when the combined rolling friction is positive: with "
      "rolling friction 0 the spinning friction is silently dropped (the energy is then almost "
      "conserved, as with our `coulomb`), so the top gets a rolling friction of 1e-12 m.")
    condim3 = inverts("mujoco", "elliptic_condim3")
    w("- **MuJoCo** does couple the friction components: its elliptic cone with condim 4 is "
      "(f_1/μ)² + (f_2/μ)² + (τ/μR̄)² ≤ f_n², the paper's ellipsoid E_F, and its pyramidal cone "
      "is the convex hull of the edges f_n(n ± μ_i d_i), i.e. |f_1|/μ + |f_2|/μ + |τ|/μR̄ ≤ f_n, "
      "coupled as well. Its contacts are soft, though (a convex, regularized formulation; default "
      "`solref` 0.02 s, `solimp` 0.9 0.95 0.001). "
      + outcome("mujoco", ["elliptic", "pyramidal", "elliptic_condim3"])
      + (" The check `elliptic_condim3` has no torsional friction at all and inverts too: the "
         "regularized friction lets the contact creep instead of sticking, so MuJoCo's inversion "
         "here is not evidence of the coupled law, and its inversion time differs from the "
         "hard-contact coupled laws' (ours: `sphere`, `exact`)." if condim3 else
         " The check `elliptic_condim3` (no torsional friction) does not invert: the inversion "
         "needs the torsional friction in the cone."))
    w("- **Ours**: " + outcome("ours", args.our_sets) + " The coupled sets (`sphere` = E_F mapped "
      "to S_F, `exact` = B_F) invert; with the decoupled ones (`coulomb`, `cylinder`) hard contact "
      "sticks and the top rolls upright at this Δt, as the reference predicts "
      "([tradeoff.md](tradeoff.md) shows the Δt dependence).")
    w("")
    if scaling:
        ns = sorted(set(c[2] for c in scaling))
        w(f"## N independent Tippe-Tops, {args.scaling_duration:g} s each")
        w("")
        w(f"N tops (N = {', '.join(map(str, ns))}) on a square grid {SPACING:g} m apart, top 0 the reference start, "
          "the others with tilt 0.05–0.2 rad, varied tilt direction and spin 150–210 rad/s of "
          "either sense (`StartOf()` in `bench/peers/tippe_top_scene.h`; ours reads the same "
          "starts from the URDF and YAML that `bench/peers/multi_top_scene.py` writes). Each "
          "engine in its default setting of the table above. They never touch: a top's centre stays "
          f"within {SPACING / 2 - 0.015:.3f} m (= spacing / 2 − R1) of its start, see the largest "
          "excursion (the peers track it every step; ours: the final distance from the start). Cost = median CPU time / (N × "
          f"steps), in µs per body-step; {args.scaling_duration:g} s of simulated time "
          f"({round(args.scaling_duration / args.dt)} steps) per run.")
        w("")
        w("| engine | setting | " + " | ".join(f"N = {n}" for n in ns)
          + " | exponent k (CPU ∝ N^k) | inverted tops at the largest N | largest excursion m |")
        w("|---|---|" + "---|" * len(ns) + "---|---|---|")
        scaling_rows = []
        ours_costs = None
        for engine, setting in SCALING:
            cfgs = [c for c in scaling if c[0] == engine and c[1] == setting]
            if not cfgs:
                continue
            costs = [median_cpu(c) / (c[2] * results[c][0]["steps"]) for c in cfgs]
            if engine == "ours":
                ours_costs = costs
            scaling_rows.append(((engine, setting), [1e6 * c for c in costs]))
            last = results[cfgs[-1]][0]
            inv = last.get("inverted_tops")
            dmin = max((r.get("max_excursion") or 0.0) for c in cfgs for r in results[c])
            w(f"| {ENGINE_NAME[engine]} | `{setting}` | "
              + " | ".join(f"{1e6 * c:.2f}" for c in costs)
              + f" | {slope(ns, costs):.2f} | {'–' if inv is None else f'{inv} of {cfgs[-1][2]}'} | "
              f"{dmin:.3f} |")
        if ours_costs:
            w("")
            w("Relative to ours (peer µs per body-step / ours):")
            w("")
            w("| engine | " + " | ".join(f"N = {n}" for n in ns) + " |")
            w("|---|" + "---|" * len(ns))
            for (engine, setting), costs in scaling_rows:
                if engine == "ours":
                    continue
                w(f"| {ENGINE_NAME[engine]} `{setting}` | "
                  + " | ".join(f"{c / (1e6 * o):.2f}" for c, o in zip(costs, ours_costs)) + " |")
        w("")
        w("`inverted tops` counts the tops whose θ exceeded 150° at some time (the peers' monitor; "
          "ours reports no per-top θ history in its summary, hence –). Only top 0 has the "
          "reference start; the others (larger or smaller tilt, other spins) are not bound by "
          "the reference's outcome, so a decoupled engine may invert some of them. The mix of "
          "starts, and with it the mix of contact phases (one or two closed contacts, sliding or "
          "sticking), changes with N, which moves the cost per body-step by itself; the "
          "exponent k is the least-squares slope of log CPU against log N.")
        w("")
        w("![CPU µs per body-step against N, log-log](figures/compare_scaling.png)")
        w("")
        write_figure(args.figure, scaling_rows, ns)
    w("## Reproducing")
    w("")
    w("    scripts/compare                       # everything, as above (about "
      f"{max(1, round(minutes))} min here)")
    w("    scripts/compare --quick               # 1 round, N = 1 4 16, 0.5 s per scaling run,")
    w("                                          # into build-peers/compare_quick.md, not here")
    w("    scripts/compare --repetitions 3 --n 1 16 256 --scaling-duration 1")
    w("")
    w("`scripts/compare` installs `libode-dev`, `libmujoco-dev` and `libbullet-dev` with apt if "
      "missing, builds `bench/peers` (its own CMake project, not part of the package) into "
      "`build-peers/` (or `$PEERS_BUILD_DIR`), builds `simulate` if it is missing or older than "
      "the sources (the target alone, `-j1`, in the build directory of `scripts/build`, or "
      "`$BUILD_DIR`), writes the N-top scenes into the peers' build directory and runs "
      "`scripts/compare_report.py`, which writes this page and the figure. One peer run by hand: "
      "`build-peers/mujoco_tops --setting elliptic --n 1 --duration 8` prints one JSON line "
      "(engine, settings, N, steps, CPU s, inverts, event times, energies).")
    w("")
    os.makedirs(os.path.dirname(args.doc), exist_ok=True)
    with open(args.doc, "w") as f:
        f.write("\n".join(lines))
    print(f"compare: wrote {args.doc} and {args.figure}", file=sys.stderr)
    if log:
        log.close()


if __name__ == "__main__":
    main()
