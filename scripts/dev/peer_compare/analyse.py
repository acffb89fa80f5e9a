"""Analysing: medians, spreads, costs per body-step and the ratios the page reports."""
import math
import statistics

from .model import SCALING, Cfg
from .run import scaling_duration


def slope(ns, costs):
    """Least-squares exponent of total CPU ~ N^k, from the per-body-step costs."""
    xs = [math.log(n) for n in ns]
    ys = [math.log(c * n) for n, c in zip(ns, costs)]
    if len(xs) < 2:
        return float("nan")
    mx, my = statistics.mean(xs), statistics.mean(ys)
    den = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / den if den else float("nan")


class Study:
    """The runs of one comparison and the figures derived from them."""

    def __init__(self, args, plan, results, our_touches, facts):
        self.args, self.plan, self.results = args, plan, results
        self.our_touches, self.facts = our_touches, facts
        self.ours_ref = Cfg("ours", "sphere", None, args.duration, "single")
        self.ref_cpu = self.median_cpu(self.ours_ref) if self.ours_ref in results else None

    def median_cpu(self, cfg):
        return statistics.median(r["cpu_s"] for r in self.results[cfg])

    def spread(self, cfg):
        cpus = [r["cpu_s"] for r in self.results[cfg]]
        return (max(cpus) - min(cpus)) / statistics.median(cpus)

    def median_of(self, cfg, key):
        values = [r[key] for r in self.results[cfg] if r.get(key) is not None]
        return statistics.median(values) if values else None

    def cost(self, cfg):  # CPU s per body-step
        return self.median_cpu(cfg) / (cfg.n * self.results[cfg][0]["steps"])

    def first(self, cfg):  # the physics of the first round
        return self.results[cfg][0]

    def version_of(self, engine):
        for cfg, runs in self.results.items():
            if cfg.engine == engine and runs and "version" in runs[0]:
                return runs[0]["version"]
        return "?"

    def overflow(self, cfgs):
        return [c for c in cfgs if any(r.get("buffer_overflow") for r in self.results[c])]

    def headline(self):
        """Ours against the fastest peer setting that is not a check, with the ratio within each
        round (the same round's runs are minutes apart at most, so a slow drift of the shared
        machine's load cancels in it), and the fastest peer that inverts the top."""
        peers = [c for c in self.plan.single if c[0] != "ours" and c[1] != "elliptic_condim3"]
        if not (self.ref_cpu and peers):
            return None
        fastest = min(peers, key=self.median_cpu)
        per_round = sorted(p["cpu_s"] / o["cpu_s"]
                           for p, o in zip(self.results[fastest], self.results[self.ours_ref]))
        inverting = [c for c in peers if self.first(c)["inverts"]]
        return {"fastest": fastest, "per_round": per_round,
                "fastest_inverting": min(inverting, key=self.median_cpu) if inverting else None,
                "inverts": {(c[0], c[1]): self.first(c)["inverts"] for c in self.plan.single}}

    def scaling_summary(self):
        """Per engine of the scaling table: its costs per (N, duration) and the derived columns."""
        args, ns = self.args, self.plan.ns
        main_ns = [n for n in ns if scaling_duration(args, n) == args.scaling_duration]
        large_ns = [n for n in ns if scaling_duration(args, n) != args.scaling_duration]
        # columns: the N at the main duration, then N = 1 and the large N at the large-N duration
        columns = [(n, args.scaling_duration) for n in main_ns]
        if large_ns:
            columns += [(1, args.large_n_duration)] + [(n, args.large_n_duration) for n in large_ns]
        rows = []
        for engine, setting in SCALING:
            cfg_of = {(c.n, c.duration): c for c in self.plan.scaling
                      if c.engine == engine and c.setting == setting}
            if not cfg_of:
                continue
            costs = {key: self.cost(c) for key, c in cfg_of.items()}
            main_costs = [costs[(n, args.scaling_duration)] for n in main_ns]
            last = self.first(cfg_of[(ns[-1], scaling_duration(args, ns[-1]))])
            rows.append({
                "engine": engine, "setting": setting, "costs": costs, "main_costs": main_costs,
                "slope": slope(main_ns, main_costs) if len(main_ns) > 1 else None,
                "large_ratio": (costs[(max(large_ns), args.large_n_duration)]
                                / costs[(1, args.large_n_duration)] if large_ns else None),
                "inverted_tops": last.get("inverted_tops"),
                "excursion": max((r.get("max_excursion") or 0.0)
                                 for c in cfg_of.values() for r in self.results[c])})
        return {"main_ns": main_ns, "large_ns": large_ns, "columns": columns, "rows": rows,
                "costs_of": {r["engine"]: r["costs"] for r in rows}}

    def rss_of(self, engine, setting, ns):
        """Median peak RSS in KiB per N; N = 1: the run at the main duration if there is one."""
        rss = {}
        for n in ns:
            cfgs = sorted((c for c in self.plan.scaling if (c.engine, c.setting, c.n) == (engine, setting, n)),
                          key=lambda c: c.duration != self.args.scaling_duration)
            if cfgs:
                rss[n] = self.median_of(cfgs[0], "rss_kb")
        return rss
