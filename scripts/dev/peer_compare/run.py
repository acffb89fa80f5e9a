"""Running: the plan of configurations, the pinned, interleaved runs and their log."""
import collections
import datetime
import json
import math
import os
import platform
import subprocess
import sys
import tempfile

import crowd_contacts  # bench/peers: ours' touches, from the CSV
from multi_top_scene import scene_paths, start_of

from .model import INVERTED, PEER_SETTINGS, ROOT, SCALING, Cfg, peer_binary

# what to run: the configurations of each table and the N of the scaling table
Plan = collections.namedtuple("Plan", "tables engines ns large single scaling crowd configs")


def make_plan(args, engines):
    """The configurations of the tables args.only asks for, over the peers that are built."""
    tables = set(args.only)
    ns = sorted(set(args.n))
    large = [n for n in ns if scaling_duration(args, n) != args.scaling_duration]
    points = scaling_points(args, ns)
    active = ["ours"] + engines
    single, scaling, crowd = [], [], []
    if "single" in tables:
        single = [Cfg("ours", s, None, args.duration, "single") for s in args.our_sets]
        single += [Cfg(e, s, None, args.duration, "single") for e, s in PEER_SETTINGS if e in engines]
    if "scaling" in tables:
        scaling = [Cfg(e, s, n, d, "tops") for e, s in SCALING if e in active for n, d in points]
    if "crowd" in tables:
        crowd = [Cfg(e, s, args.crowd_n, args.crowd_duration, "crowd") for e, s in SCALING if e in active]
    return Plan(tables, engines, ns, large, single, scaling, crowd, single + scaling + crowd)


def scaling_duration(args, n):
    return args.large_n_duration if n >= args.large_n else args.scaling_duration


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

def write_scenes(args, ns, crowd_n):
    """The scenes of (b) and (c) for simulate, into args.scenes_dir."""
    script = os.path.join(ROOT, "bench", "peers", "multi_top_scene.py")
    for n in ns:
        subprocess.run([sys.executable, script, str(n), args.scenes_dir], check=True,
                       stdout=subprocess.DEVNULL)
    if crowd_n:
        subprocess.run([sys.executable, script, str(crowd_n), args.scenes_dir, "--crowd"], check=True,
                       stdout=subprocess.DEVNULL)

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



def open_log(args, engines, start, load_start, code):
    """The log of every run, one JSON line each, after a first line with the run's options."""
    if not args.log:
        return None
    log = open(args.log, "w")
    log.write(json.dumps({"table": "meta", "start": start.isoformat(), "load_start": load_start,
                          "code": code, "cores": os.cpu_count(), "cpu_model": cpu_model(),
                          "engines": engines, "args": vars(args)}) + "\n")
    return log


def run_rounds(args, plan, results, log, tmp):
    """Every configuration once per round, round-robin, each round starting one later."""
    configs = plan.configs

    def is_large(cfg):  # a run at the large-N duration (the largest N and its N = 1 reference)
        return bool(plan.large) and cfg.table == "tops" and cfg.duration == args.large_n_duration

    for rep in range(args.repetitions):
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


def run_all(args, plan):
    """Runs the plan; (results per configuration, ours' crowd touches, the run's facts)."""
    if plan.scaling or plan.crowd:
        write_scenes(args, sorted({n for n, _ in scaling_points(args, plan.ns)}) if plan.scaling
                     else [], args.crowd_n if plan.crowd else None)
    results = {cfg: [] for cfg in plan.configs}
    our_touches = None
    start = datetime.datetime.now()
    facts = {"start": start, "load_start": loadavg(), "code": git_describe(),
             "cores": os.cpu_count(), "cpu_model": cpu_model()}
    log = open_log(args, plan.engines, start, facts["load_start"], facts["code"])
    with tempfile.TemporaryDirectory() as tmp:
        run_rounds(args, plan, results, log, tmp)
        ours_crowd = [c for c in plan.crowd if c.engine == "ours"]
        if ours_crowd:
            print("\rcompare: ours' crowd once more, untimed, every step into a CSV for its touches"
                  + " " * 30, end="", file=sys.stderr, flush=True)
            our_touches = our_crowd_contacts(ours_crowd[0], args, tmp)
            if log:
                log.write(json.dumps({"engine": "ours", "table": "crowd_touches", "n": args.crowd_n,
                                      "duration": args.crowd_duration,
                                      **our_touches}) + "\n")
    print(file=sys.stderr)
    facts["minutes"] = (datetime.datetime.now() - start).total_seconds() / 60.0
    facts["load_end"] = loadavg()
    if log:
        log.write(json.dumps({"table": "end", "minutes": facts["minutes"],
                              "load_end": facts["load_end"]}) + "\n")
        log.close()
    return results, our_touches, facts


def scaling_points(args, ns):
    """(N, duration) of the scaling table; N = 1 at the large-N duration too, when that differs:
    the like-for-like reference."""
    points = [(n, scaling_duration(args, n)) for n in ns]
    large = [n for n in ns if scaling_duration(args, n) != args.scaling_duration]
    if large and (1, args.large_n_duration) not in points:
        points.append((1, args.large_n_duration))
    return points


def read_meta(path):
    """The first line of a log: the run's options and facts, or None (an older log)."""
    with open(path) as f:
        meta = json.loads(f.readline())
    return meta if meta.get("table") == "meta" else None


def read_log(path, plan, meta):
    """The runs of a log, as run_all returns them."""
    results = {cfg: [] for cfg in plan.configs}
    our_touches = None
    facts = {"start": datetime.datetime.fromisoformat(meta["start"]),
             "load_start": meta["load_start"], "code": meta["code"], "cores": meta["cores"],
             "cpu_model": meta["cpu_model"]}
    with open(path) as f:
        for line in f:
            r = json.loads(line)
            table = r.pop("table")
            if table == "meta":
                continue
            if table == "end":
                facts["minutes"], facts["load_end"] = r["minutes"], r["load_end"]
            elif table == "crowd_touches":
                our_touches = {k: v for k, v in r.items() if k not in ("engine", "n", "duration")}
            else:
                cfg = Cfg(r.pop("engine"), r.pop("setting"),
                          None if table == "single" else r["n"], r.pop("duration"), table)
                r.pop("round")
                r.pop("n")
                if cfg in results:
                    results[cfg].append(r)
    return results, our_touches, facts
