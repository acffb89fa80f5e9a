#!/usr/bin/python3
"""`simulate --schedule` runs the documented example (docs/simulate.md, config/die_schedule.yaml)
and each event has its effect in the CSV: the spawned die's columns are nan before it appears and
after it is deleted; the push gives it Δvx = F T / m exactly (it is in the air, gravity along z);
set_state puts it where asked, at rest. A refused event stops the run with one line (exit 2).

  simulate_schedule_test.py <simulate executable> <source dir>
"""
import csv
import math
import os
import subprocess
import sys
import tempfile
import unittest

SIMULATE = sys.argv[1] if len(sys.argv) > 1 else "build-release/devel/lib/nonsmooth_sim/simulate"
SOURCE = sys.argv[2] if len(sys.argv) > 2 else "."
FORCE, DURATION, MASS = 0.045, 0.01, 0.0045  # config/die_schedule.yaml, urdf/die.urdf


class SimulateSchedule(unittest.TestCase):
    def run_example(self, schedule, out):
        # the command of docs/simulate.md, with the CSV in a temporary folder
        return subprocess.run(
            [SIMULATE, "--quiet", "--urdf", os.path.join(SOURCE, "urdf/die.urdf"),
             "--initial", os.path.join(SOURCE, "config/die.yaml"), "--schedule", schedule,
             "--duration", "0.4", "--csv", out],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=120)

    def test_the_example_schedule_has_its_effects(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "die_schedule.csv")
            done = self.run_example(os.path.join(SOURCE, "config/die_schedule.yaml"), out)
            self.assertEqual(done.returncode, 0, done.stderr.decode())
            with open(out) as f:
                rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
        self.assertIn("die2/die/vx", rows[0])

        def at(t):
            return min(rows, key=lambda r: abs(r["t"] - t))

        self.assertTrue(math.isnan(at(0.05)["die2/die/x"]), "die2 before it is spawned")
        self.assertAlmostEqual(at(0.12)["die2/die/x"], 0.1, delta=1e-12)
        self.assertEqual(at(0.12)["die2/die/vx"], 0.0)
        pushed = at(0.2)["die2/die/vx"]
        self.assertAlmostEqual(pushed, FORCE * DURATION / MASS, delta=1e-12 * pushed)
        self.assertAlmostEqual(at(0.3)["die2/die/y"], 0.1, delta=1e-12)
        self.assertEqual(at(0.3)["die2/die/vx"], 0.0)
        self.assertTrue(math.isnan(at(0.38)["die2/die/x"]), "die2 after it is deleted")
        # the first die is not touched by any of it: it rests on the ground at the end
        self.assertLess(abs(rows[-1]["die/vz"]), 1e-6)

    def test_a_refused_event_stops_the_run_with_one_line(self):
        with tempfile.TemporaryDirectory() as tmp:
            schedule = os.path.join(tmp, "bad.yaml")
            with open(schedule, "w") as f:
                f.write("events:\n  - at: 0.01\n    delete: {model: nobody}\n")
            done = self.run_example(schedule, os.path.join(tmp, "out.csv"))
            err = done.stderr.decode().strip().splitlines()
            self.assertEqual(done.returncode, 2, err)
            self.assertEqual(len(err), 1, err)
            self.assertIn("schedule line 2 (at 0.01 s): no model \"nobody\"", err[0])
            with open(schedule, "w") as f:
                f.write("events:\n  - at: 0.01\n    wrench: {body: die, forse: [1, 0, 0]}\n")
            done = self.run_example(schedule, os.path.join(tmp, "out.csv"))
            err = done.stderr.decode().strip().splitlines()
            self.assertEqual(done.returncode, 2, err)
            self.assertIn("unknown key \"forse\"", err[0])
            # one document: a second one, or a token no document takes, is refused where it is
            for text, where in (("events: []\n---\nevents: []\n", "line 2, column 1"),
                                ("{events: []},\n", "line 1, column 13")):
                with open(schedule, "w") as f:
                    f.write(text)
                done = self.run_example(schedule, os.path.join(tmp, "out.csv"))
                err = done.stderr.decode().strip().splitlines()
                self.assertEqual(done.returncode, 2, err)
                self.assertEqual(len(err), 1, err)
                self.assertIn(where + ": a second YAML document", err[0])


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
