"""The study's grids and the run configurations they expand to."""
import math

SETS = []  # the friction sets, filled in by main from `simulate --list-friction-sets`
SOLVERS = ["jacobi", "modified_jacobi", "gauss_seidel"]
SOLVER_SHORT = {"jacobi": "J (43)", "modified_jacobi": "MJ (46)", "gauss_seidel": "GS"}

# The full grid of the study. Duration: the coupled laws touch down at ~1.3 s, the decoupled ones at
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
