#!/usr/bin/python3
"""Runs the Tippe-Top against the peer engines and writes docs/compare.md and its figure.

Called by scripts/dev/compare (which installs the engines and builds bench/peers and `simulate`);
by hand:

    scripts/dev/compare_report.py --simulate BIN --peers-dir DIR --scenes-dir DIR [options]

Three measurements, every run pinned to one core (taskset -c CPU), one process at a time, all of
them interleaved (round-robin over every configuration, R rounds), CPU time of the stepping
loop only, median of R, and the peak RSS of every run (/usr/bin/time -f %M):
  (a) one Tippe-Top, config/tippe_top.yaml start, DURATION s at DT: ours per friction set (the
      built-in scene, as scripts/dev/speed runs it) and each peer engine per setting, with the
      physics (inversion, peg touchdown, energy);
  (b) N independent tops (bench/peers/multi_top_scene.py, StartOf() of
      bench/peers/tippe_top_scene.h) for SCALING_DURATION s (N >= LARGE_N: LARGE_N_DURATION s,
      and N = 1 at that duration too, to compare like with like): CPU per body-step against N;
  (c) the crowd: CROWD_N tops close together in a walled arena (multi_top_scene.py --crowd,
      CrowdStartOf()) for CROWD_DURATION s: CPU per body-step and the touches between tops and
      with the walls (the peers count them in their loop; ours from one more, untimed run with
      every step in its CSV, bench/peers/crowd_contacts.py, the same rule).
The scenes of (b) and (c) are written into SCENES_DIR here. With --from-log LOG nothing runs:
the page and figure are written again from the runs LOG holds (the --log of an earlier call).

The work is in scripts/dev/peer_compare/: run.py (the plan, the runs, the log), analyse.py
(medians, costs, ratios) and report.py (the page and the figure); this file reads the options.
"""
import argparse
import os
import subprocess
import sys

from peer_compare.analyse import Study
from peer_compare.model import OUR_SETS, ROOT, TABLES, peer_binary
from peer_compare.report import write_page
from peer_compare.run import make_plan, read_log, read_meta, run_all


def parse_args():
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
    p.add_argument("--command", default="scripts/dev/compare", help="the command, for the doc")
    args = p.parse_args()
    meta = None
    if args.from_log:
        meta = read_meta(args.from_log)
        if meta is None:
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
    return args, meta


def main():
    args, meta = parse_args()
    if meta:
        engines = meta["engines"]
    else:
        engines = [e for e in args.engines if os.access(peer_binary(args.peers_dir, e), os.X_OK)]
        for e in args.engines:
            if e not in engines:
                print(f"compare: {peer_binary(args.peers_dir, e)} not built, {e} skipped",
                      file=sys.stderr)
    plan = make_plan(args, engines)
    if meta:
        results, our_touches, facts = read_log(args.from_log, plan, meta)
    else:
        results, our_touches, facts = run_all(args, plan)
    write_page(Study(args, plan, results, our_touches, facts))


if __name__ == "__main__":
    main()
