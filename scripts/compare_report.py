#!/usr/bin/python3
"""Runs the Tippe-Top against the peer engines and writes docs/compare.md and its figure.

Called by scripts/compare (which installs the engines and builds bench/peers and `simulate`);
by hand:

    scripts/compare_report.py --simulate BIN --peers-dir DIR --scenes-dir DIR [options]

Three measurements, every run pinned to one core (taskset -c CPU), one process at a time, all of
them interleaved (round-robin over every configuration, R rounds), CPU time of the stepping
loop only, median of R, and the peak RSS of every run (/usr/bin/time -f %M):
  (a) one Tippe-Top, config/tippe_top.yaml start, DURATION s at DT: ours per friction set (the
      built-in scene, as scripts/speed runs it) and each peer engine per setting, with the
      physics (inversion, peg touchdown, energy);
  (b) N independent tops (bench/peers/multi_top_scene.py, StartOf() of
      bench/peers/tippe_top_scene.h) for SCALING_DURATION s (N >= LARGE_N: LARGE_N_DURATION s,
      and N = 1 at that duration too, to compare like with like): CPU per body-step against N;
  (c) the crowd: CROWD_N tops close together in a walled arena (multi_top_scene.py --crowd,
      CrowdStartOf()) for CROWD_DURATION s: CPU per body-step and the touches between tops and
      with the walls (the peers count them in their loop; ours from one more, untimed run with
      every step in its CSV, bench/peers/crowd_contacts.py, the same rule).
The scenes of (b) and (c) are written into SCENES_DIR here.
"""
import argparse
import collections
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
from multi_top_scene import (CROWD_SPACING, SPACING, TOUCH_GAP, crowd_half_width,  # noqa: E402
                             scene_paths, start_of)
import crowd_contacts  # noqa: E402  ours' touches, from the CSV
INVERTED = math.radians(150.0)

# one configuration: table "single" (n None), "tops" (N independent tops) or "crowd"
Cfg = collections.namedtuple("Cfg", "engine setting n duration table")

# (a): ours per friction set, and every peer setting (program, setting)
OUR_SETS = ["coulomb", "cylinder", "sphere", "exact"]
PEER_SETTINGS = [("ode", "world_step"), ("ode", "quick_step"),
                 ("mujoco", "elliptic"), ("mujoco", "pyramidal"), ("mujoco", "elliptic_condim3"),
                 ("mujoco", "elliptic_pgs"), ("bullet", "default"), ("bullet", "iter100_2dir")]
# (b) and (c): one configuration per engine, its default
SCALING = [("ours", "sphere"), ("ode", "world_step"), ("mujoco", "elliptic"), ("bullet", "default")]
TABLES = ["single", "scaling", "crowd"]

# what each setting is, for the table (the programs print the same in "settings")
DESCRIPTION = {
    ("ours", "coulomb"): "Coulomb, no drilling friction; Gauss–Seidel, tol 1e-5",
    ("ours", "cylinder"): "C_F: drilling limited separately (decoupled); Gauss–Seidel",
    ("ours", "sphere"): "S_F (E_F mapped): drilling coupled to sliding; Gauss–Seidel (default)",
    ("ours", "exact"): "B_F (Hertz disc, coupled), mapped; Gauss–Seidel",
    ("ours", "ellipsoid"): "E_F iterated on itself (the paper's reference; slow by design)",
    ("ode", "world_step"): "dWorldStep (LCP), box friction μ = 0.3 ∝ λ_N (Approx1), drilling row ρ_N = μR̄ (Approx1_N), no rolling rows (ρ = ρ₂ = −1), one top's pairs collided directly, ERP 0.2, CFM 1e-10",
    ("ode", "quick_step"): "dWorldQuickStep 20 iterations, otherwise as world_step",
    ("mujoco", "elliptic"): "elliptic cone, condim 4, friction (0.3, μR̄, 0), Newton, Euler, default solref/solimp",
    ("mujoco", "pyramidal"): "pyramidal cone (default), condim 4, friction (0.3, μR̄, 0), Newton, Euler",
    ("mujoco", "elliptic_condim3"): "check: elliptic cone, condim 3 = no torsional friction",
    ("mujoco", "elliptic_pgs"): "elliptic cone, condim 4, PGS instead of Newton (the same problem), otherwise as elliptic",
    ("bullet", "default"): "sequential impulse, 10 iterations, 1 friction direction, spinning friction μR̄ (rolling 1e-12 to enable it), split impulse",
    ("bullet", "iter100_2dir"): "sequential impulse, 100 iterations, 2 friction directions, otherwise as default",
}
ENGINE_NAME = {"ours": "nonsmooth_sim", "ode": "ODE", "mujoco": "MuJoCo", "bullet": "Bullet"}


def peer_binary(peers_dir, engine):
    return os.path.join(peers_dir, f"{engine}_tops")


def command(cfg, args, tmp, csv=None):
    """argv of one run and how to read it: (argv, summary path or None)."""
    engine, setting, n, duration, table = cfg
    if engine == "ours":
        summary = os.path.join(tmp, "summary.json")
        argv = [args.simulate, "--quiet", "--friction-set", setting, "--duration", repr(duration),
                "--dt", repr(args.dt), "--summary", summary]
        if n is not None:
            urdf, yaml = scene_paths(n, args.scenes_dir, crowd=table == "crowd")
            argv += ["--urdf", urdf, "--initial", yaml]
        if csv:
            argv += ["--csv", csv, "--decimate", "1"]
        return argv, summary
    argv = [peer_binary(args.peers_dir, engine), "--setting", setting, "--n", str(n or 1),
            "--duration", repr(duration), "--dt", repr(args.dt)]
    if table == "crowd":
        argv += ["--scene", "crowd"]
    return argv, None


def run_pinned(argv, cpu, tmp):
    """Runs argv pinned to one core; its stdout and its peak RSS in KiB. The RSS is GNU time's %M
    (ru_maxrss of its child, which taskset execs into the program): not wait4 of our own child,
    whose ru_maxrss would include the copy of this Python process it was forked (or vforked)
    from, ~35 MB, before the exec."""
    rss_file = os.path.join(tmp, "rss")
    out = subprocess.run(["/usr/bin/time", "-f", "%M", "-o", rss_file, "taskset", "-c", str(cpu)] + argv,
                         check=True, stdout=subprocess.PIPE, text=True).stdout
    with open(rss_file) as f:
        rss = int(f.read().split()[-1])
    return out, rss


def run(cfg, args, tmp, csv=None):
    argv, summary = command(cfg, args, tmp, csv)
    n = cfg.n
    out, rss = run_pinned(argv, args.cpu, tmp)
    if summary is None:
        line = [l for l in out.splitlines() if l.startswith("{")][-1]
        r = json.loads(line)
        r["rss_kb"] = rss
        return r
    with open(summary) as f:
        s = json.load(f)
    excursion = None
    if n is not None and cfg.table == "tops":  # ours keeps no excursion history: the final distance
        excursion = max(math.hypot(s["bodies"][f"top{i}"]["position"][0] - start_of(i, n)[0][0],
                                   s["bodies"][f"top{i}"]["position"][1] - start_of(i, n)[0][1])
                        for i in range(n))
    return {"max_excursion": excursion, "engine": "ours", "cpu_s": s["cpu_time_s"], "steps": s["steps"],
            "theta_max": s["theta_max"], "inverts": s["theta_max"] > INVERTED,
            "t_theta_above_2_4": s["t_theta_above_2_4"], "t_peg_touchdown": s["t_peg_touchdown"],
            "theta_final": s["theta_final"], "energy_initial": s["energy_initial"],
            "energy_final": s["energy_final"], "mean_iterations": s["mean_iterations"],
            "unconverged_steps": s["unconverged_steps"], "rss_kb": rss,
            "max_closed_contacts": s.get("max_closed_contacts"),
            "max_penetration": s.get("max_penetration"), "state_finite": s.get("state_finite", True),
            "final_bodies": s.get("bodies") if cfg.table == "crowd" else None}


def our_crowd_contacts(cfg, args, tmp):
    """One more run of ours' crowd, untimed, with every step in its CSV: the touches by the peers'
    rule (bench/peers/crowd_contacts.py), and its final state (to check it is the timed runs')."""
    csv = os.path.join(tmp, "crowd.csv")
    r = run(cfg, args, tmp, csv=csv)
    with open(csv) as f:
        touches = crowd_contacts.count(cfg.n, f)
    os.remove(csv)
    return {**touches, "final_bodies": r["final_bodies"]}


def version_of(engine, results):
    for cfg, runs in results.items():
        if cfg.engine == engine and runs and "version" in runs[0]:
            return runs[0]["version"]
    return "?"


def write_scenes(args, ns, crowd_n):
    """The scenes of (b) and (c) for simulate, into args.scenes_dir."""
    script = os.path.join(ROOT, "bench", "peers", "multi_top_scene.py")
    for n in ns:
        subprocess.run([sys.executable, script, str(n), args.scenes_dir], check=True,
                       stdout=subprocess.DEVNULL)
    if crowd_n:
        subprocess.run([sys.executable, script, str(crowd_n), args.scenes_dir, "--crowd"], check=True,
                       stdout=subprocess.DEVNULL)


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


def write_figure(path, scaling_rows, ns, large_rows=(), large_ns=(), duration=None,
                 large_duration=None):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    markers = {"ours": "o", "ode": "s", "mujoco": "^", "bullet": "D"}
    colours = {}
    for (engine, setting), costs in scaling_rows:
        label = f"{ENGINE_NAME[engine]} ({setting})"
        line, = ax.loglog(ns, costs, marker=markers.get(engine, "x"), label=label,
                          linewidth=2.2 if engine == "ours" else 1.4)
        colours[engine] = line.get_color()
    # the large N at their shorter duration, with N = 1 at that duration: hollow markers, dotted
    for (engine, setting), costs in large_rows:
        ax.loglog(large_ns, costs, marker=markers.get(engine, "x"), linestyle=":",
                  color=colours.get(engine), markerfacecolor="none",
                  linewidth=2.2 if engine == "ours" else 1.4)
    if large_rows:
        ax.plot([], [], linestyle=":", marker="o", markerfacecolor="none", color="gray",
                label=f"dotted, hollow: {large_duration:g} s runs (others {duration:g} s)")
    all_ns = sorted(set(ns) | set(large_ns))
    ax.set_xlabel("number of Tippe-Tops N")
    ax.set_ylabel("CPU µs per body-step")
    ax.set_xticks(all_ns)
    ax.set_xticklabels([str(n) for n in all_ns])
    values = [v for _, costs in list(scaling_rows) + list(large_rows) for v in costs]
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
    p.add_argument("--simulate", help="the simulate binary (required unless --from-log)")
    p.add_argument("--peers-dir", help="build directory of bench/peers (required unless --from-log)")
    p.add_argument("--scenes-dir", help="where the N-top scenes are (required unless --from-log)")
    p.add_argument("--from-log", metavar="LOG",
                   help="runs nothing: writes the page and figure again from the runs of LOG (a "
                        "--log of an earlier run, with the options that run had)")
    p.add_argument("--repetitions", type=int, default=5)
    p.add_argument("--n", type=int, nargs="+", default=[1, 4, 16, 64, 256, 1024],
                   help="(b), the numbers of tops")
    p.add_argument("--duration", type=float, default=8.0, help="(a), simulated s")
    p.add_argument("--scaling-duration", type=float, default=8.0, help="(b), simulated s")
    p.add_argument("--large-n", type=int, default=1024,
                   help="(b): N from this on run for --large-n-duration s (and N = 1 as well)")
    p.add_argument("--large-n-duration", type=float, default=0.5, help="(b), simulated s")
    p.add_argument("--large-n-repetitions", type=int, default=3,
                   help="(b): the runs at --large-n-duration take part in the first R rounds only")
    p.add_argument("--crowd-n", type=int, default=64, help="(c), the number of tops")
    p.add_argument("--crowd-duration", type=float, default=2.0, help="(c), simulated s")
    p.add_argument("--only", nargs="+", choices=TABLES, default=TABLES,
                   help="run and write only these tables (default: all three)")
    p.add_argument("--crowd-only", action="store_true", help="the same as --only crowd")
    p.add_argument("--dt", type=float, default=1e-4)
    p.add_argument("--cpu", type=int, default=1, help="the core every run is pinned to")
    p.add_argument("--our-sets", nargs="+", default=OUR_SETS,
                   help="friction sets of ours (simulate --list-friction-sets)")
    p.add_argument("--engines", nargs="+", default=["ode", "mujoco", "bullet"])
    p.add_argument("--doc", default=os.path.join(ROOT, "docs", "compare.md"))
    p.add_argument("--figure", default=os.path.join(ROOT, "docs", "figures", "compare_scaling.png"))
    p.add_argument("--log", help="write every run as a JSON line here")
    p.add_argument("--command", default="scripts/compare", help="the command, for the doc")
    args = p.parse_args()
    meta = None
    if args.from_log:
        with open(args.from_log) as f:
            meta = json.loads(f.readline())
        if meta.get("table") != "meta":
            p.error(f"--from-log: {args.from_log} has no meta line (written by an older version)")
        for k, v in meta["args"].items():  # the options of the run, except the outputs
            if k not in ("doc", "figure", "from_log", "log"):
                setattr(args, k, v)
    elif not (args.simulate and args.peers_dir and args.scenes_dir):
        p.error("--simulate, --peers-dir and --scenes-dir are required (or --from-log)")
    else:
        # the friction sets, from the program (the laws table)
        known = subprocess.run([args.simulate, "--list-friction-sets"], check=True,
                               capture_output=True, text=True).stdout.split()
        for s in args.our_sets:
            if s not in known:
                p.error("--our-sets: %r is not one of %s" % (s, ", ".join(known)))
    if args.repetitions < 1:
        p.error("--repetitions must be >= 1")
    if args.crowd_only:
        args.only = ["crowd"]
    if min(args.n) < 1 or args.crowd_n < 2:
        p.error("--n must be >= 1 and --crowd-n >= 2")
    tables = set(args.only)

    if meta:
        engines = meta["engines"]
    else:
        engines = [e for e in args.engines if os.access(peer_binary(args.peers_dir, e), os.X_OK)]
    missing = [e for e in args.engines if e not in engines]
    for e in missing:
        print(f"compare: {peer_binary(args.peers_dir, e)} not built, {e} skipped", file=sys.stderr)

    def scaling_duration(n):
        return args.large_n_duration if n >= args.large_n else args.scaling_duration

    ns = sorted(set(args.n))
    # N = 1 at the large-N duration too, when that differs: the like-for-like reference
    large = [n for n in ns if scaling_duration(n) != args.scaling_duration]
    scaling_points = [(n, scaling_duration(n)) for n in ns]
    if large and (1, args.large_n_duration) not in scaling_points:
        scaling_points.append((1, args.large_n_duration))
    active = [e for e in ["ours"] + engines]
    single, scaling, crowd = [], [], []
    if "single" in tables:
        single = [Cfg("ours", s, None, args.duration, "single") for s in args.our_sets]
        single += [Cfg(e, s, None, args.duration, "single") for e, s in PEER_SETTINGS if e in engines]
    if "scaling" in tables:
        scaling = [Cfg(e, s, n, d, "tops") for e, s in SCALING if e in active for n, d in scaling_points]
    if "crowd" in tables:
        crowd = [Cfg(e, s, args.crowd_n, args.crowd_duration, "crowd") for e, s in SCALING if e in active]
    if not meta:
        write_scenes(args, sorted({n for n, _ in scaling_points}) if scaling else [],
                     args.crowd_n if crowd else None)
    configs = single + scaling + crowd

    def is_large(cfg):  # a run at the large-N duration (the largest N and its N = 1 reference)
        return bool(large) and cfg.table == "tops" and cfg.duration == args.large_n_duration

    results = {cfg: [] for cfg in configs}
    our_touches = None
    start = datetime.datetime.now()
    load_start = loadavg()
    code = git_describe()
    log = open(args.log, "w") if args.log and not meta else None
    if log:
        log.write(json.dumps({"table": "meta", "start": start.isoformat(), "load_start": load_start,
                              "code": code, "cores": os.cpu_count(), "cpu_model": cpu_model(),
                              "engines": engines, "args": vars(args)}) + "\n")
    if meta:
        start = datetime.datetime.fromisoformat(meta["start"])
        load_start, code = meta["load_start"], meta["code"]
        with open(args.from_log) as f:
            for line in f:
                r = json.loads(line)
                table = r.pop("table")
                if table == "meta":
                    continue
                if table == "end":
                    minutes, load_end = r["minutes"], r["load_end"]
                elif table == "crowd_touches":
                    our_touches = {k: v for k, v in r.items()
                                   if k not in ("engine", "n", "duration")}
                else:
                    cfg = Cfg(r.pop("engine"), r.pop("setting"),
                              None if table == "single" else r["n"], r.pop("duration"), table)
                    r.pop("round")
                    r.pop("n")
                    if cfg in results:
                        results[cfg].append(r)
    with tempfile.TemporaryDirectory() as tmp:
        for rep in range(0 if meta else args.repetitions):
            # round-robin; each round starts one configuration later, so that no configuration
            # always runs right after the same neighbour
            order = configs[rep % len(configs):] + configs[:rep % len(configs)]
            if rep >= args.large_n_repetitions:
                order = [c for c in order if not is_large(c)]
            for k, cfg in enumerate(order):
                print(f"\rcompare: round {rep + 1}/{args.repetitions}, run {k + 1}/{len(order)}: "
                      f"{cfg.engine} {cfg.setting} {cfg.table} N={cfg.n or 1} {cfg.duration:g} s      ",
                      end="", file=sys.stderr, flush=True)
                r = run(cfg, args, tmp)
                results[cfg].append(r)
                if log:
                    log.write(json.dumps({"round": rep, "engine": cfg.engine, "setting": cfg.setting,
                                          "n": cfg.n or 1, "duration": cfg.duration,
                                          "table": cfg.table, **r}) + "\n")
                    log.flush()
        ours_crowd = [c for c in crowd if c.engine == "ours"]
        if ours_crowd and not meta:
            print("\rcompare: ours' crowd once more, untimed, every step into a CSV for its touches"
                  + " " * 30, end="", file=sys.stderr, flush=True)
            our_touches = our_crowd_contacts(ours_crowd[0], args, tmp)
            if log:
                log.write(json.dumps({"engine": "ours", "table": "crowd_touches", "n": args.crowd_n,
                                      "duration": args.crowd_duration,
                                      **our_touches}) + "\n")
    print(file=sys.stderr)
    if not meta:
        minutes = (datetime.datetime.now() - start).total_seconds() / 60.0
        load_end = loadavg()
        if log:
            log.write(json.dumps({"table": "end", "minutes": minutes, "load_end": load_end}) + "\n")

    def median_cpu(cfg):
        return statistics.median(r["cpu_s"] for r in results[cfg])

    def spread(cfg):
        cpus = [r["cpu_s"] for r in results[cfg]]
        return (max(cpus) - min(cpus)) / statistics.median(cpus)

    ours_ref = Cfg("ours", "sphere", None, args.duration, "single")
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
    cores, model = (meta["cores"], meta["cpu_model"]) if meta else (os.cpu_count(), cpu_model())
    w(f"on this repository's machine: {cores} cores ({model}), shared with other "
      f"jobs (load average {load_start} at the start, {load_end} at the end; the runs took "
      f"{minutes:.1f} min). Code: {code}. Engines: Debian 12's packages, "
      f"ODE {version_of('ode', results)} (double precision), MuJoCo "
      f"{version_of('mujoco', results)}, Bullet {version_of('bullet', results)}; ours is "
      "`simulate`, Release (`-O3`, no `-march=native`), the peers are built with the same flags "
      "(`bench/peers/CMakeLists.txt`).")
    w("")
    w("**Method.** Every run is one process pinned to one core (`taskset -c "
      f"{args.cpu}`), one at a time; all configurations of all tables are interleaved "
      f"(round-robin, {args.repetitions} rounds, each round starting one configuration later) "
      "and the tables show the median. Time is the CPU time of the stepping loop only (ours: "
      "the summary's `cpu_time_s`, the thread's CPU time of the loop with its per-step monitors; "
      "the peers: `std::clock()` around the loop, which also updates θ, the event times and the "
      "peg gap of every top each step, and in the crowd the pair monitor), not start-up or model "
      "building. **Peak RSS** is the largest resident set of the whole process (model building, "
      "output and all; `/usr/bin/time -f %M`, i.e. its `ru_maxrss`; median of the rounds). The "
      "machine is shared: `spread` is (max − min) / median of the runs; compare rows of one table, "
      "not across days.")
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
        # the ratio of the two runs of each round as well: the same round's runs are minutes
        # apart at most, so a slow drift of the shared machine's load cancels in it
        per_round = sorted(p["cpu_s"] / o["cpu_s"]
                           for p, o in zip(results[fastest], results[ours_ref]))
        text = (f"**In short.** One top, {args.duration:g} s: ours (`sphere`, the default) takes "
                f"{1e3 * ref_cpu:.0f} ms of CPU, the fastest peer ({ENGINE_NAME[fastest[0]]} "
                f"`{fastest[1]}`) {1e3 * median_cpu(fastest):.0f} ms, "
                f"{median_cpu(fastest) / ref_cpu:.1f}× ours (the ratio within each round: median "
                f"{statistics.median(per_round):.1f}×, {per_round[0]:.1f}–{per_round[-1]:.1f}× "
                f"over the {len(per_round)} rounds)")
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
    if single:
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
                cfg = Cfg(engine, setting, None, args.duration, "single")
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
            cfg = Cfg(engine, setting, None, args.duration, "single")
            if cfg not in results:
                return None
            r = results[cfg][0]
            return 100 * (1.0 - r["energy_final"] / r["energy_initial"])

        def inverts(engine, setting):
            cfg = Cfg(engine, setting, None, args.duration, "single")
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
          + outcome("mujoco", ["elliptic", "pyramidal", "elliptic_condim3", "elliptic_pgs"])
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
        w("### The settings: each peer's fastest that expresses the same physics")
        w("")
        w("Every peer gets the cheapest setting of its own that keeps the physics of the scene: hard "
          "(or, in MuJoCo, its soft) contact, μ = 0.3, a drilling limit μR̄λ_N, no rolling "
          "resistance, no restitution, Δt = 1e-4. Where an engine can only express a different law "
          "(ODE and Bullet: drilling decoupled from sliding), that is a difference the tables state, "
          "not one a setting hides.")
        w("")
        w("- **ODE** (`world_step`): `dWorldStep`, faster here than `dWorldQuickStep` with its 20 "
          "iterations (the table above). Rolling resistance is off by giving no "
          "rows, ρ = ρ₂ = −1 with `dContactAxisDep` (a negative coefficient adds no row; zero adds an "
          "empty row with zero bounds that the LCP still carries, 6 rows per contact instead of 4): "
          "the same contact law, and the printed θ(t), event times and energies are the same as with "
          "zero rows. One top has exactly two pairs, each sphere with the plane: they are collided "
          "directly (`dCollide`), as a user would for this scene; N tops and the crowd use a hash "
          "space, their broad phase.")
        w("- **MuJoCo**: condim 4 (normal, two tangents, torsion; 6 would add rolling resistance), "
          "the elliptic cone (the ellipsoid E_F; the pyramidal cone is a different, octahedral law), "
          "the Euler integrator (its cheapest), default `solref`/`solimp`. Newton (the default) and "
          "PGS solve the same convex problem: `elliptic_pgs` is the same physics up to the solvers' "
          "tolerances (compare its θ > 2.4 rad time and energy with `elliptic`'s above).")
        w("- **Bullet** (`default`): 10 sequential-impulse iterations, one friction direction along "
          "the slip, split impulse (its defaults and its cheapest; `iter100_2dir` is the accurate "
          "end), the dynamic AABB tree broad phase (`btDbvtBroadphase`, the usual one; one top has a "
          "single pair, so it costs little).")
        w("- **Ours** (`sphere`, the default): the coupled law of the reference.")
        w("")
    def median_of(cfg, key):
        values = [r[key] for r in results[cfg] if r.get(key) is not None]
        return statistics.median(values) if values else None

    def cost(cfg):  # CPU s per body-step
        return median_cpu(cfg) / (cfg.n * results[cfg][0]["steps"])

    def overflow_note(cfgs):
        bad = [c for c in cfgs if any(r.get("buffer_overflow") for r in results[c])]
        return ("**MuJoCo filled its contact or constraint buffer in: "
                + ", ".join(f"N = {c.n} ({c.table})" for c in bad)
                + "; contacts were dropped there, those figures are not valid.**") if bad else None

    if scaling:
        main_ns = [n for n in ns if scaling_duration(n) == args.scaling_duration]
        large_ns = [n for n in ns if scaling_duration(n) != args.scaling_duration]
        # columns: the N at the main duration, then N = 1 and the large N at the large-N duration
        columns = [(n, args.scaling_duration) for n in main_ns]
        if large_ns:
            columns += [(1, args.large_n_duration)] + [(n, args.large_n_duration) for n in large_ns]

        def label(n, d):
            return f"N = {n}" + (f" ({d:g} s)" if d != args.scaling_duration else "")

        w(f"## N independent Tippe-Tops, {args.scaling_duration:g} s each"
          + (f" ({args.large_n_duration:g} s from N = {args.large_n})" if large_ns else ""))
        w("")
        w(f"N tops (N = {', '.join(map(str, ns))}) on a square grid {SPACING:g} m apart, top 0 the reference start, "
          "the others with tilt 0.05–0.2 rad, varied tilt direction and spin 150–210 rad/s of "
          "either sense (`StartOf()` in `bench/peers/tippe_top_scene.h`; ours reads the same "
          "starts from the URDF and YAML that `bench/peers/multi_top_scene.py` writes). Each "
          "engine in its default setting of the table above. They never touch: a top's centre stays "
          f"within {SPACING / 2 - 0.015:.3f} m (= spacing / 2 − R1) of its start, see the largest "
          "excursion (the peers track it every step; ours: the final distance from the start). Cost = median CPU time / (N × "
          f"steps), in µs per body-step; {args.scaling_duration:g} s of simulated time "
          f"({round(args.scaling_duration / args.dt)} steps) per run"
          + (f", except N ≥ {args.large_n}: {args.large_n_duration:g} s "
             f"({round(args.large_n_duration / args.dt)} steps) in the first "
             f"{min(args.large_n_repetitions, args.repetitions)} of the {args.repetitions} rounds "
             "(median of those), to keep the whole run within about half an hour (one MuJoCo run "
             "of 1024 tops for 8 s alone would take about 15 min). "
             "A short run covers only the start of the motion (the reference top inverts from "
             "1.3 s on), whose contact phases cost differently, so N = 1 runs for "
             f"{args.large_n_duration:g} s as well, and the ratio column compares the largest N "
             "with N = 1 at the same duration" if large_ns else "") + ".")
        w("")
        head = "| engine | setting | " + " | ".join(label(n, d) for n, d in columns)
        head += f" | exponent k (CPU ∝ N^k, N ≤ {max(main_ns)})" if len(main_ns) > 1 else ""
        if large_ns:
            head += f" | N = {max(large_ns)} / N = 1 ({args.large_n_duration:g} s)"
        head += " | inverted tops at the largest N | largest excursion m |"
        w(head)
        w("|---|---|" + "---|" * (head.count("|") - 3))
        scaling_rows, large_rows = [], []
        costs_of = {}
        for engine, setting in SCALING:
            cfg_of = {(c.n, c.duration): c for c in scaling if c.engine == engine and c.setting == setting}
            if not cfg_of:
                continue
            costs = {key: cost(c) for key, c in cfg_of.items()}
            costs_of[engine] = costs
            main_costs = [costs[(n, args.scaling_duration)] for n in main_ns]
            scaling_rows.append(((engine, setting), [1e6 * c for c in main_costs]))
            row = (f"| {ENGINE_NAME[engine]} | `{setting}` | "
                   + " | ".join(f"{1e6 * costs[key]:.2f}" for key in columns))
            if len(main_ns) > 1:
                row += f" | {slope(main_ns, main_costs):.2f}"
            if large_ns:
                ratio = costs[(max(large_ns), args.large_n_duration)] / costs[(1, args.large_n_duration)]
                row += f" | {ratio:.2f}"
                large_rows.append(((engine, setting),
                                   [1e6 * costs[(n, args.large_n_duration)] for n in [1] + large_ns]))
            last = results[cfg_of[(ns[-1], scaling_duration(ns[-1]))]][0]
            inv = last.get("inverted_tops")
            dmin = max((r.get("max_excursion") or 0.0) for c in cfg_of.values() for r in results[c])
            row += (f" | {'–' if inv is None else f'{inv} of {ns[-1]}'} | {dmin:.3f} |")
            w(row)
        if "ours" in costs_of and len(costs_of) > 1:
            w("")
            w("Relative to ours (peer µs per body-step / ours):")
            w("")
            w("| engine | " + " | ".join(label(n, d) for n, d in columns) + " |")
            w("|---|" + "---|" * len(columns))
            ours = costs_of["ours"]
            for engine, setting in SCALING:
                if engine == "ours" or engine not in costs_of:
                    continue
                w(f"| {ENGINE_NAME[engine]} `{setting}` | "
                  + " | ".join(f"{costs_of[engine][key] / ours[key]:.2f}" for key in columns) + " |")
        w("")
        if large_ns and "ours" in costs_of:
            big = max(large_ns)
            ratio = costs_of["ours"][(big, args.large_n_duration)] / costs_of["ours"][(1, args.large_n_duration)]
            w(f"The scaling goal, ours at N = {big} within 1.5× of N = 1 per body-step (a benchmark, "
              f"not a test): {ratio:.2f}× at {args.large_n_duration:g} s"
              + (f" ({costs_of['ours'][(big, args.large_n_duration)] / costs_of['ours'][(1, args.scaling_duration)]:.2f}× "
                 f"the {args.scaling_duration:g} s run of N = 1)" if (1, args.scaling_duration) in costs_of["ours"] else "")
              + ".")
            w("")
        note = overflow_note(scaling)
        if note:
            w(note)
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
        write_figure(args.figure, scaling_rows, main_ns, large_rows, [1] + large_ns,
                     args.scaling_duration, args.large_n_duration)

        # peak memory
        w("### Peak memory (RSS)")
        w("")
        rss_columns = sorted({c.n for c in scaling})
        w(f"Peak RSS of the process in MB (10⁶ bytes; median of the rounds; at the duration of the "
          f"table above, N = 1 at {args.scaling_duration if 1 in main_ns else args.large_n_duration:g} s), "
          "and the memory per body: "
          f"(RSS(N = {rss_columns[-1]}) − RSS(N = 1)) / {rss_columns[-1] - 1}.")
        w("")
        w("| engine | " + " | ".join(f"N = {n}" for n in rss_columns)
          + " | KB per body |")
        w("|---|" + "---|" * (len(rss_columns) + 1))
        for engine, setting in SCALING:
            rss = {}
            for n in rss_columns:  # N = 1: the run at the main duration if there is one
                cfgs = sorted((c for c in scaling if (c.engine, c.setting, c.n) == (engine, setting, n)),
                              key=lambda c: c.duration != args.scaling_duration)
                if cfgs:
                    rss[n] = median_of(cfgs[0], "rss_kb")
            if not rss:
                continue
            per_body = ((rss[rss_columns[-1]] - rss[1]) / (rss_columns[-1] - 1) * 1.024
                        if 1 in rss and len(rss_columns) > 1 else None)
            w(f"| {ENGINE_NAME[engine]} `{setting}` | "
              + " | ".join(f"{rss[n] * 1.024e-3:.1f}" if n in rss else "–" for n in rss_columns)
              + f" | {'–' if per_body is None else f'{per_body:.1f}'} |")
        w("")
        w("MuJoCo 2.2 preallocates its contact and constraint buffers (`nconmax`, `njmax`; "
          "`bench/peers/mujoco_tops.cpp` sizes them to 2N + 64 contacts, each sphere on the "
          "ground, and their rows: smaller buffers drop contacts and tops fall through the floor), "
          "and among them dense njmax × njmax and njmax × nv arrays, so its memory grows with N²; "
          "later MuJoCo versions allocate on demand.")
        w("")

    if crowd:
        n = args.crowd_n
        half = crowd_half_width(n)
        w(f"## A crowd: {n} tops colliding in a walled arena, {args.crowd_duration:g} s")
        w("")
        w(f"{n} Tippe-Tops close together: on a square grid {1e3 * CROWD_SPACING:g} mm apart (big "
          f"spheres {1e3 * (CROWD_SPACING - 0.03):g} mm apart) centred in a square arena of "
          f"{2e3 * half:g} mm × {2e3 * half:g} mm bounded by four vertical wall planes, each top "
          "with the tilt, tilt direction and spin of `StartOf()` and moving at 0.1–0.3 m/s in a "
          "varied direction (`CrowdStartOf()`, `CrowdWalls()` in `bench/peers/tippe_top_scene.h`; "
          "ours: `bench/peers/multi_top_scene.py --crowd` writes the URDF, the walls `<plane/>` "
          "colliders of the world link, and the YAML). Every contact (top–ground, top–top, "
          "top–wall) has μ = 0.3, the drilling limit μR̄ and restitution 0: ours by its pair rule "
          "(μ = min, R̄ = max; the walls' own μ = 1, R = 0), MuJoCo by its rule (max), ODE with "
          "one surface for all, Bullet with its combining callbacks set to min friction and max "
          "spinning friction (its default products would give two tops μ = 0.09). Each engine in "
          "its default setting; Δt = "
          f"{args.dt:g} s, {round(args.crowd_duration / args.dt)} steps.")
        w("")
        w(f"**Touches**, counted by one rule for every engine: two tops touch in a step when a "
          f"sphere of one is within {1e6 * TOUCH_GAP:g} µm of a sphere of the other (a top and a "
          "wall: a sphere within that of the wall's plane). The peers count inside their stepping "
          "loop (`PairMonitor`, a sort-and-sweep, about 2 µs per step for 64 tops, i.e. 0.03 µs "
          "per body-step in their CPU time); ours from one more run of the same scene, "
          "untimed, with every step in its CSV (`bench/peers/crowd_contacts.py`). "
          "**steps touching** = steps with at least one touching pair; **onsets** = a pair "
          "touching that did not in the step before (a collision; a contact that chatters counts "
          "more than once); **pairs** = distinct pairs that touched; **most** = most pairs "
          "touching in one step; **largest |x|, |y|** = of any centre of mass during the run: "
          f"the walls hold the tops if it stays within {half - 0.012:.3f} m (the half-width "
          f"{half:g} m − (R1 − a1), a top lying with its peg away from the wall) plus the "
          "penetration.")
        w("")
        ours_crowd = [c for c in crowd if c.engine == "ours"]
        ref = cost(ours_crowd[0]) if ours_crowd else None
        # against the same engine's N independent tops, when those ran at the same N and duration
        with_independent = any(Cfg(c.engine, c.setting, n, args.crowd_duration, "tops") in results
                               for c in crowd)
        w("| engine | setting | CPU s | spread | µs per body-step | × ours | "
          + (f"× its {n} independent tops | " if with_independent else "")
          + "peak RSS MB | steps touching | onsets | pairs | most | wall onsets | "
          "largest \\|x\\|, \\|y\\| m | energy lost | notes |")
        w("|---|---|---|---|---|---|" + ("---|" if with_independent else "")
          + "---|---|---|---|---|---|---|---|---|")
        for cfg in crowd:
            r = results[cfg][0]
            t = our_touches if cfg.engine == "ours" else r
            independent = Cfg(cfg.engine, cfg.setting, n, args.crowd_duration, "tops")
            vs = (f"{cost(cfg) / cost(independent):.2f} | " if independent in results else "– | ") \
                if with_independent else ""
            lost = 1.0 - r["energy_final"] / r["energy_initial"]
            if cfg.engine == "ours":
                note = (f"solver: {r['mean_iterations']:.0f} iterations per step (summed over the "
                        f"islands), {r['unconverged_steps']} steps unconverged; at most "
                        f"{r['max_closed_contacts']} closed contacts; deepest penetration "
                        f"{1e3 * r['max_penetration']:.3f} mm")
            elif cfg.engine == "mujoco":
                note = (f"at most {r.get('max_contacts')} contacts (nconmax {r.get('nconmax')})"
                        + ("; **buffer full: contacts dropped**" if r.get("buffer_overflow") else ""))
            else:
                note = ""
            if not r.get("finite", r.get("state_finite", True)):
                note += "; **the state became non-finite**"
            steps = r["steps"]
            w(f"| {ENGINE_NAME[cfg.engine]} | `{cfg.setting}` | {median_cpu(cfg):.2f} | "
              f"{100 * spread(cfg):.0f} % | {1e6 * cost(cfg):.2f} | "
              + (f"{cost(cfg) / ref:.2f}" if ref else "–") + f" | {vs}"
              f"{median_of(cfg, 'rss_kb') * 1.024e-3:.1f} | "
              f"{t['touch_steps']} ({100 * t['touch_steps'] / steps:.0f} %) | "
              f"{t['pair_onsets']} | {t['pairs_touched']} | {t['max_touching_pairs']} | "
              f"{t['wall_onsets']} | {t.get('max_coordinate', float('nan')):.3f} | {100 * lost:.1f} % | "
              f"{note.lstrip('; ')} |")
        w("")
        if our_touches is not None and ours_crowd:
            timed = results[ours_crowd[0]][0]["final_bodies"]
            same = timed == our_touches["final_bodies"]
            w("Ours' touches come from the untimed run with the CSV; its final state is "
              + ("identical to the timed runs' (the output does not change the physics)." if same else
                 "**not** identical to the timed runs' (the figures may differ from the timed run's)."))
            w("")
        note = overflow_note(crowd)
        if note:
            w(note)
            w("")
        if with_independent:
            w(f"`× its {n} independent tops`: against the same engine's row of the table above at "
              "the same N and duration.")
            w("")
        w("The tops' paths differ between engines "
          "after the first collisions (the contact laws differ, and so does every later "
          "collision), so the touch counts measure that collisions happen and how often, not one "
          "shared trajectory.")
        w("")
    w("## Reproducing")
    w("")
    w("    scripts/compare                       # everything, as above (about "
      f"{max(1, round(minutes))} min here)")
    w("    scripts/compare --quick               # 1 round, N = 1 4 16, 0.5 s per scaling and crowd run,")
    w("                                          # into build-peers/compare_quick.md, not here")
    w("    scripts/compare --only scaling crowd --n 1 1024   # N = 1 and 1024 and the crowd alone,")
    w("    scripts/compare --crowd-only --crowd-duration 8   # the crowd alone; both into")
    w("                                          # build-peers/compare_partial.md, not here")
    w("    scripts/compare --repetitions 3 --n 1 16 256 --scaling-duration 1")
    w("")
    w("`scripts/compare` installs `libode-dev`, `libmujoco-dev` and `libbullet-dev` with apt if "
      "missing, builds `bench/peers` (its own CMake project, not part of the package) into "
      "`build-peers/` (or `$PEERS_BUILD_DIR`), builds `simulate` if it is missing or older than "
      "the sources (the target alone, `-j1`, in the build directory of `scripts/build`, or "
      "`$BUILD_DIR`) and runs `scripts/compare_report.py`, which writes the N-top and crowd scenes "
      "into the peers' build directory (`scenes/`), this page and the figure "
      "(`scripts/compare --help` lists the options: `--only`, `--large-n`, `--large-n-duration`, "
      "`--large-n-repetitions`, `--crowd-n`, `--crowd-duration`, …). One peer run by hand: "
      "`build-peers/mujoco_tops --setting elliptic --n 1 --duration 8` prints one JSON line "
      "(engine, settings, N, steps, CPU s, inverts, event times, energies, peak RSS); "
      "`--scene crowd --n 64` runs the crowd and adds its touch counts.")
    w("")
    os.makedirs(os.path.dirname(args.doc), exist_ok=True)
    with open(args.doc, "w") as f:
        f.write("\n".join(lines))
    print(f"compare: wrote {args.doc}" + (f" and {args.figure}" if scaling else ""), file=sys.stderr)
    if log:
        log.close()


if __name__ == "__main__":
    main()
