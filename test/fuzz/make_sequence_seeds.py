#!/usr/bin/env python3
"""Writes the hand-made seeds of service_sequence_fuzz into corpus/service_sequence_fuzz/.

FuzzedDataProvider takes integers and booleans from the END of the input, one byte for a range
below 256, so a seed is the byte list of its choices, reversed. The choices follow the decoding in
service_sequence_fuzz.cpp (scene, then per request: the request, then its fields). Rerun after
changing that decoding: `test/fuzz/make_sequence_seeds.py`.
"""
import os

# request numbers (the switch in LLVMFuzzerTestOneInput)
STEP, RESET, RESET_WORLD, RESET_SIMULATION, SOLVER, SET_FRICTION, GET_FRICTION, WRENCH, \
    CLEAR_WRENCH, RAW_WRENCH, RAW_STATE, RAW_TIME, SPAWN, DELETE = 0, 3, 4, 5, 6, 7, 8, 9, 10, 11, \
    12, 13, 14, 15
# scenes (LLVMFuzzerInitialize)
TIPPE_TOP, DUEL, DIE, COIN = 0, 1, 2, 3
# HostileDouble's table (index)
ZERO, ONE, TENTH, BIG, INF, NAN, HUGE = 0, 2, 5, 22, 27, 29, 15


def table(index):
    return [0, index]  # HostileDouble: case 0 (the table), then the index


def steps(n):
    out = []
    while n > 0:
        out += [STEP, min(n, 8) - 1]
        n -= min(n, 8)
    return out


SEEDS = {
    "steps_tippe_top": [TIPPE_TOP] + steps(64),
    "steps_duel": [DUEL] + steps(40),
    "steps_die": [DIE] + steps(40),
    # ~reset with inclination 0.1 and spin 1e3 (index 15), then steps
    "reset_spin": [TIPPE_TOP, RESET, 0, 1] + table(TENTH) + [1] + table(15) + [0, 0, 0, 0] +
                  steps(24),
    # ~set_solver_properties: max_iterations 1 (table), jacobi, implicit_midpoint; steps
    "solver_jacobi_implicit": [COIN, SOLVER, 0, 0, 0, 0, 1, 1, 1, 1, 0, 1, 1] + steps(24),
    # ~set_friction_set "coulomb" (index 3) for "" (contact index 0), steps
    "friction_coulomb": [DUEL, SET_FRICTION, 1, 3, 0, 0, 1, 0] + steps(24),
    # ~apply_body_wrench on "die" (names: die, die), no reference frame, force (1, 0, 0), torque 0,
    # point 0, from now, for 0.05 s; steps; ~clear_body_wrenches; steps
    "wrench_die": [DIE, WRENCH, 1, 0, 0] + table(ONE) + table(ZERO) * 2 + table(ZERO) * 6 +
                  [0, 0] + steps(16) + [CLEAR_WRENCH, 1] + steps(8),
    # ~spawn_urdf_model of the die as "m1" (names: m1, 1m, a/b, "", tippe_top) in the world at
    # the default pose (0.5, 0, 0.1); steps; ~delete_model "m1" (models: tippe_top, m1); steps
    "spawn_delete": [TIPPE_TOP, SPAWN, DIE, 1, 0, 0, 0, 0] + steps(16) + [DELETE, 1, 1] +
                    steps(16),
    # SetState with a huge angular velocity (the fault path), steps, ~reset_world, steps
    "fault_then_reset": [TIPPE_TOP, RAW_STATE, 2] + table(HUGE) * 3 + [1] + steps(8) +
                        [RESET_WORLD] + steps(8) + [RESET_SIMULATION] + steps(4),
}


def main():
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus",
                       "service_sequence_fuzz")
    os.makedirs(out, exist_ok=True)
    for name, choices in SEEDS.items():
        with open(os.path.join(out, name + ".bin"), "wb") as f:
            f.write(bytes(reversed([c & 0xFF for c in choices])))


if __name__ == "__main__":
    main()
