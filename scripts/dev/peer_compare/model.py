"""What the comparison measures: the configurations, the peers' settings and what each is."""
import collections
import math
import os
import sys

ROOT = os.path.realpath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "bench", "peers"))
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
