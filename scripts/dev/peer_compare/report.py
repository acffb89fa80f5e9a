"""Reporting: the page (docs/compare.md) and its figure, one function per section."""
import math
import os
import statistics
import sys

from multi_top_scene import CROWD_SPACING, SPACING, TOUCH_GAP, crowd_half_width

from .model import ENGINE_NAME, DESCRIPTION, SCALING, Cfg


def fmt_time(t):
    return "never" if t is None else f"{t:.3f}"


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


def header(st, w):
    """The title, the machine and the code, the method and the scene."""
    args, facts = st.args, st.facts
    start, minutes = facts["start"], facts["minutes"]
    w("# Peer engines: the Tippe-Top in ODE, MuJoCo and Bullet")
    w("")
    w("Written by `scripts/dev/compare` (do not edit by hand: rerun it). Measured "
      f"{start:%Y-%m-%d} with")
    w("")
    w(f"    {args.command}")
    w("")
    w(f"on this repository's machine: {facts['cores']} cores ({facts['cpu_model']}), shared with "
      f"other jobs (load average {facts['load_start']} at the start, {facts['load_end']} at the "
      f"end; the runs took {minutes:.1f} min). Code: {facts['code']}. Engines: Debian 12's "
      f"packages, ODE {st.version_of('ode')} (double precision), MuJoCo "
      f"{st.version_of('mujoco')}, Bullet {st.version_of('bullet')}; ours is "
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


def headline(st, w):
    """In short: ours against the fastest peer."""
    args, median_cpu, ref_cpu = st.args, st.median_cpu, st.ref_cpu
    h = st.headline()
    if h:
        fastest, per_round, f2 = h["fastest"], h["per_round"], h["fastest_inverting"]
        text = (f"**In short.** One top, {args.duration:g} s: ours (`sphere`, the default) takes "
                f"{1e3 * ref_cpu:.0f} ms of CPU, the fastest peer ({ENGINE_NAME[fastest[0]]} "
                f"`{fastest[1]}`) {1e3 * median_cpu(fastest):.0f} ms, "
                f"{median_cpu(fastest) / ref_cpu:.1f}× ours (the ratio within each round: median "
                f"{statistics.median(per_round):.1f}×, {per_round[0]:.1f}–{per_round[-1]:.1f}× "
                f"over the {len(per_round)} rounds)")
        if f2:
            text += (f"; the fastest peer that inverts the top ({ENGINE_NAME[f2[0]]} `{f2[1]}`) "
                     f"takes {median_cpu(f2) / ref_cpu:.1f}× ours")
        inv = h["inverts"]
        if (inv.get(("ours", "sphere")) and not any(v for (e, _), v in inv.items()
                                                   if e in ("ode", "bullet"))
                and inv.get(("mujoco", "elliptic_condim3"))):
            text += (". Only ours inverts the top with hard contact and a coupled law; ODE and "
                     "Bullet (decoupled drilling friction) do not invert it, MuJoCo inverts it "
                     "even without torsional friction (soft contact; below)")
        w(text + ".")
        w("")


def single_table(st, w):
    """The table of one top: every setting, its cost and its physics."""
    args, results, single = st.args, st.results, st.plan.single
    ref_cpu = st.ref_cpu
    median_cpu, spread = st.median_cpu, st.spread
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


def outcome(st, engine, settings):
    """One sentence per engine from the measured runs."""
    parts = []
    for setting in settings:
        cfg = Cfg(engine, setting, None, st.args.duration, "single")
        if cfg not in st.results:
            continue
        r = st.results[cfg][0]
        lost = 100 * (1.0 - r["energy_final"] / r["energy_initial"])
        if r["inverts"]:
            parts.append(f"`{setting}` inverts (θ > 2.4 rad at {fmt_time(r['t_theta_above_2_4'])} s, "
                         f"θ max {math.degrees(r['theta_max']):.0f}°, {lost:.0f} % of the energy lost)")
        else:
            parts.append(f"`{setting}` does not invert (θ max {math.degrees(r['theta_max']):.1f}°, "
                         f"θ end {math.degrees(r['theta_final']):.1f}°, {lost:.0f} % of the energy lost)")
    return ("Measured: " + "; ".join(parts) + ".") if parts else "Not run."

def lost_of(st, engine, setting):
    cfg = Cfg(engine, setting, None, st.args.duration, "single")
    if cfg not in st.results:
        return None
    r = st.results[cfg][0]
    return 100 * (1.0 - r["energy_final"] / r["energy_initial"])

def inverts(st, engine, setting):
    cfg = Cfg(engine, setting, None, st.args.duration, "single")
    return cfg in st.results and st.results[cfg][0]["inverts"]


def inversions(st, w):
    """Which engines invert the top, and why."""
    args, results, single = st.args, st.results, st.plan.single
    inverting = [f"{ENGINE_NAME[c[0]]} `{c[1]}`" for c in single if results[c][0]["inverts"]]
    not_inverting = [f"{ENGINE_NAME[c[0]]} `{c[1]}`" for c in single if not results[c][0]["inverts"]]
    w("### Which engines invert the top, and why")
    w("")
    w("Inverts: " + (", ".join(inverting) or "none") + ". Does not invert: "
      + (", ".join(not_inverting) or "none") + ".")
    w("")
    w("- **ODE** has no coupled law. Its contact joint gives each row its own box: |f_1|, |f_2| "
      "≤ μλ_N (`dContactApprox1`; a square, not a disc) and, with `dContactRolling`, a drilling "
      "row |τ_n| ≤ ρ_N λ_N (`rhoN` = μR̄, `dContactApprox1_N`, no rolling resistance) clamped "
      "independently of the sliding rows: the decoupled cylinder C_F of the paper, with a box for "
      "its disc. " + outcome(st, "ode", ["world_step", "quick_step"])
      + (" The contact sticks and the top rolls back upright, as with our `cylinder`"
         + (f" ({lost_of(st, 'ours', 'cylinder'):.0f} % of the energy lost)"
            if lost_of(st, "ours", "cylinder") is not None else "") + "."
         if not inverts(st, "ode", "world_step") else ""))
    w("- **Bullet** likewise clamps its spinning-friction row (`setSpinningFriction`, μR̄) on its "
      "own, decoupled from the sliding friction. " + outcome(st, "bullet", ["default", "iter100_2dir"])
      + " Bullet adds the spinning row only when the combined rolling friction is positive: with "
      "rolling friction 0 the spinning friction is silently dropped (the energy is then almost "
      "conserved, as with our `coulomb`), so the top gets a rolling friction of 1e-12 m.")
    condim3 = inverts(st, "mujoco", "elliptic_condim3")
    w("- **MuJoCo** does couple the friction components: its elliptic cone with condim 4 is "
      "(f_1/μ)² + (f_2/μ)² + (τ/μR̄)² ≤ f_n², the paper's ellipsoid E_F, and its pyramidal cone "
      "is the convex hull of the edges f_n(n ± μ_i d_i), i.e. |f_1|/μ + |f_2|/μ + |τ|/μR̄ ≤ f_n, "
      "coupled as well. Its contacts are soft, though (a convex, regularized formulation; default "
      "`solref` 0.02 s, `solimp` 0.9 0.95 0.001). "
      + outcome(st, "mujoco", ["elliptic", "pyramidal", "elliptic_condim3", "elliptic_pgs"])
      + (" The check `elliptic_condim3` has no torsional friction at all and inverts too: the "
         "regularized friction lets the contact creep instead of sticking, so MuJoCo's inversion "
         "here is not evidence of the coupled law, and its inversion time differs from the "
         "hard-contact coupled laws' (ours: `sphere`, `exact`)." if condim3 else
         " The check `elliptic_condim3` (no torsional friction) does not invert: the inversion "
         "needs the torsional friction in the cone."))
    w("- **Ours**: " + outcome(st, "ours", args.our_sets) + " The coupled sets (`sphere` = E_F mapped "
      "to S_F, `exact` = B_F) invert; with the decoupled ones (`coulomb`, `cylinder`) hard contact "
      "sticks and the top rolls upright at this Δt, as the reference predicts "
      "([tradeoff.md](tradeoff.md) shows the Δt dependence).")
    w("")


def settings(st, w):
    """Each peer's setting and why it is the fastest with the same physics."""

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
      "the same contact law; θ(t), the event times and the energies print the same as with the "
      "zero rows (the LCP's size changes its rounding only: θ differs by at most 3e-13 rad over "
      "8 s). One top has exactly two pairs, each sphere with the plane: they are collided "
      "directly (`dCollide`), as a user would for this scene; N tops and the crowd use a "
      "sweep-and-prune space (`dSweepAndPruneSpaceCreate`, all three axes), their broad phase and "
      "ODE's fastest here (1.6–1.8× less CPU than a hash space at N = 16, 256 and in the crowd, "
      "with the same printed results).")
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


def scaling_table(st, w, sc):
    """The N-top table: cost per body-step against N."""
    args, ns = st.args, st.plan.ns
    large_ns, columns = sc["large_ns"], sc["columns"]
    main_ns = sc["main_ns"]
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
    head = "| engine | setting | " + " | ".join(label(args, n, d) for n, d in columns)
    head += f" | exponent k (CPU ∝ N^k, N ≤ {max(main_ns)})" if len(main_ns) > 1 else ""
    if large_ns:
        head += f" | N = {max(large_ns)} / N = 1 ({args.large_n_duration:g} s)"
    head += " | inverted tops at the largest N | largest excursion m |"
    w(head)
    w("|---|---|" + "---|" * (head.count("|") - 3))
    for row in sc["rows"]:
        engine, setting, costs = row["engine"], row["setting"], row["costs"]
        line = (f"| {ENGINE_NAME[engine]} | `{setting}` | "
                + " | ".join(f"{1e6 * costs[key]:.2f}" for key in columns))
        if row["slope"] is not None:
            line += f" | {row['slope']:.2f}"
        if large_ns:
            line += f" | {row['large_ratio']:.2f}"
        inv = row["inverted_tops"]
        line += (f" | {'–' if inv is None else f'{inv} of {ns[-1]}'} | {row['excursion']:.3f} |")
        w(line)


def overflow_note(st, cfgs):
    bad = st.overflow(cfgs)
    return ("**MuJoCo filled its contact or constraint buffer in: "
            + ", ".join(f"N = {c.n} ({c.table})" for c in bad)
            + "; contacts were dropped there, those figures are not valid.**") if bad else None


def label(args, n, d):
    return f"N = {n}" + (f" ({d:g} s)" if d != args.scaling_duration else "")


def scaling_notes(st, w, sc):
    """Relative to ours, the scaling goal, the notes and the figure."""
    args = st.args
    costs_of, columns, large_ns = sc["costs_of"], sc["columns"], sc["large_ns"]
    if "ours" in costs_of and len(costs_of) > 1:
        w("")
        w("Relative to ours (peer µs per body-step / ours):")
        w("")
        w("| engine | " + " | ".join(label(args, n, d) for n, d in columns) + " |")
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
    note = overflow_note(st, st.plan.scaling)
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


def scaling_figure(st, sc):
    """The figure: CPU per body-step against N, the large N at their duration dotted."""
    args, large_ns = st.args, sc["large_ns"]
    scaling_rows = [((r["engine"], r["setting"]), [1e6 * c for c in r["main_costs"]])
                    for r in sc["rows"]]
    large_rows = ([((r["engine"], r["setting"]),
                    [1e6 * r["costs"][(n, args.large_n_duration)] for n in [1] + large_ns])
                   for r in sc["rows"]] if large_ns else [])
    write_figure(args.figure, scaling_rows, sc["main_ns"], large_rows, [1] + large_ns,
                 args.scaling_duration, args.large_n_duration)


def memory(st, w, sc):
    """Peak RSS per N."""
    args, scaling, main_ns = st.args, st.plan.scaling, sc["main_ns"]
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
        rss = st.rss_of(engine, setting, rss_columns)
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


def crowd_intro(st, w):
    """The crowd: its scene and the touch rule."""
    args = st.args
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


def crowd_table(st, w):
    """The crowd table."""
    args, results, crowd = st.args, st.results, st.plan.crowd
    our_touches, n = st.our_touches, st.args.crowd_n
    median_cpu, spread, median_of, cost = st.median_cpu, st.spread, st.median_of, st.cost
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
    note = overflow_note(st, crowd)
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


def reproducing(st, w):
    """The commands that regenerate the page."""
    minutes = st.facts["minutes"]
    w("## Reproducing")
    w("")
    args = st.args
    w(f"    {args.command}")
    w(f"{'':42}# as above ({max(1, round(minutes))} min here)")
    if args.command != "scripts/dev/compare":
        w("    scripts/dev/compare                   # the defaults: N up to 1024, 8 s runs, a 2 s")
        w("                                          # crowd (about 35 min here)")
    w("    scripts/dev/compare --quick           # 1 round, N = 1 4 16, 0.5 s per scaling and crowd run,")
    w("                                          # into build-peers/compare_quick.md, not here")
    w("    scripts/dev/compare --only scaling crowd --n 1 1024   # N = 1 and 1024 and the crowd alone,")
    w("    scripts/dev/compare --crowd-only --crowd-duration 8   # the crowd alone; both into")
    w("                                          # build-peers/compare_partial.md, not here")
    w("    scripts/dev/compare --repetitions 3 --n 1 16 256 --scaling-duration 1")
    w("    scripts/dev/compare --from-log build-peers/compare_runs.jsonl   # no runs: this page again")
    w("                                          # from the runs the last full call logged")
    w("")
    w("`scripts/dev/compare` installs `libode-dev`, `libmujoco-dev` and `libbullet-dev` with apt if "
      "missing, builds `bench/peers` (its own CMake project, not part of the package) into "
      "`build-peers/` (or `$PEERS_BUILD_DIR`), builds `simulate` if it is missing or older than "
      "the sources (the target alone, `-j1`, in the build directory of `scripts/build`, or "
      "`$BUILD_DIR`) and runs `scripts/dev/compare_report.py` (its parts in `scripts/dev/peer_compare/`: "
      "`run.py`, `analyse.py`, `report.py`), which writes the N-top and crowd scenes into the "
      "peers' build directory (`scenes/`), every run into `build-peers/compare_runs.jsonl`, this "
      "page and the figure "
      "(`scripts/dev/compare --help` lists the options: `--only`, `--large-n`, `--large-n-duration`, "
      "`--large-n-repetitions`, `--crowd-n`, `--crowd-duration`, …). One peer run by hand: "
      "`build-peers/mujoco_tops --setting elliptic --n 1 --duration 8` prints one JSON line "
      "(engine, settings, N, steps, CPU s, inverts, event times, energies, peak RSS); "
      "`--scene crowd --n 64` runs the crowd and adds its touch counts.")
    w("")


def write_page(st):
    """Writes args.doc (and args.figure with the scaling table)."""
    lines = []
    w = lines.append
    header(st, w)
    headline(st, w)
    if st.plan.single:
        single_table(st, w)
        inversions(st, w)
        settings(st, w)
    if st.plan.scaling:
        sc = st.scaling_summary()
        scaling_table(st, w, sc)
        scaling_notes(st, w, sc)
        scaling_figure(st, sc)
        memory(st, w, sc)
    if st.plan.crowd:
        crowd_intro(st, w)
        crowd_table(st, w)
    reproducing(st, w)
    args = st.args
    os.makedirs(os.path.dirname(args.doc), exist_ok=True)
    with open(args.doc, "w") as f:
        f.write("\n".join(lines))
    print(f"compare: wrote {args.doc}" + (f" and {args.figure}" if st.plan.scaling else ""), file=sys.stderr)
