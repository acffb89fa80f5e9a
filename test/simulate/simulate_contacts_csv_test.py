#!/usr/bin/python3
"""simulate --contacts-csv FILE (docs/simulate.md): one row per closed contact per sample, for the
built-in Tippe-Top and for URDF scenes. A ball resting on the ground carries its weight: its
normal percussion over the step divided by dt is m g (to 1e-9), its tangential ones 0, the point
on the floor below its centre, the normal +z and the tangent t1 orthogonal to it, at the fixed
step and with --accuracy; the Tippe-Top's rows name its big sphere, then its peg as it inverts.

  simulate_contacts_csv_test.py <simulate executable> <source dir>
"""
import csv
import os
import subprocess
import sys
import tempfile
import unittest

SIMULATE = sys.argv[1] if len(sys.argv) > 1 else "build-release/devel/lib/nonsmooth_sim/simulate"
SOURCE = sys.argv[2] if len(sys.argv) > 2 else "."

MASS, RADIUS, G = 2.0, 0.1, 9.81
BALL = """<robot name="r">
  <link name="ball">
    <inertial><mass value="2"/><inertia ixx="0.008" ixy="0" ixz="0" iyy="0.008" iyz="0" izz="0.008"/></inertial>
    <collision name="shell"><geometry><sphere radius="0.1"/></geometry></collision>
  </link>
</robot>
"""
START = """bodies:
  ball:
    position: [0.3, -0.2, 0.1]
"""


def run(args):
    done = subprocess.run([SIMULATE, "--quiet"] + args, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, timeout=120)
    return done.returncode, done.stderr.decode()


def read_rows(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return rows


class ContactsCsv(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.urdf = os.path.join(self.tmp.name, "ball.urdf")
        self.start = os.path.join(self.tmp.name, "ball.yaml")
        with open(self.urdf, "w") as f:
            f.write(BALL)
        with open(self.start, "w") as f:
            f.write(START)

    def tearDown(self):
        self.tmp.cleanup()

    def check_resting_ball(self, rows, samples):
        self.assertEqual(len(rows), samples)
        for row in rows:
            self.assertEqual(row["contact"], "shell/ground")
            dt = float(row["dt"])
            self.assertAlmostEqual(float(row["lambda_n"]) / dt / (MASS * G), 1.0, delta=1e-9)
            for name in ["lambda_t1", "lambda_t2", "lambda_tau", "lambda_r1", "lambda_r2"]:
                self.assertLess(abs(float(row[name])) / dt, 1e-9, name)
            self.assertAlmostEqual(float(row["x"]), 0.3, delta=1e-12)
            self.assertAlmostEqual(float(row["y"]), -0.2, delta=1e-12)
            self.assertLess(abs(float(row["z"])), 1e-9)
            self.assertEqual([float(row[k]) for k in ["nx", "ny", "nz"]], [0.0, 0.0, 1.0])
            self.assertAlmostEqual(float(row["t1z"]), 0.0, delta=1e-15)

    def test_a_resting_ball_carries_its_weight(self):
        contacts = os.path.join(self.tmp.name, "contacts.csv")
        code, err = run(["--urdf", self.urdf, "--initial", self.start, "--duration", "0.1",
                         "--dt", "1e-3", "--decimate", "10", "--contacts-csv", contacts])
        self.assertEqual(code, 0, err)
        rows = read_rows(contacts)
        # the samples every 10 steps (at rest from the first step: one contact each)
        self.check_resting_ball(rows, 10)
        self.assertEqual([round(float(r["t"]), 9) for r in rows],
                         [round(0.01 * k, 9) for k in range(1, 11)])
        for row in rows:
            self.assertEqual(float(row["dt"]), 1e-3)

    def test_with_the_accuracy_knob_dt_is_the_last_steps(self):
        contacts = os.path.join(self.tmp.name, "contacts.csv")
        code, err = run(["--urdf", self.urdf, "--initial", self.start, "--duration", "0.1",
                         "--accuracy", "1e-3", "--decimate", "100", "--contacts-csv", contacts])
        self.assertEqual(code, 0, err)
        self.check_resting_ball(read_rows(contacts), 10)

    def test_the_tippe_tops_rows_name_its_spheres(self):
        contacts = os.path.join(self.tmp.name, "contacts.csv")
        series = os.path.join(self.tmp.name, "series.csv")
        code, err = run(["--duration", "2", "--decimate", "100", "--contacts-csv", contacts,
                         "--csv", series])
        self.assertEqual(code, 0, err)
        rows = read_rows(contacts)
        names = [r["contact"] for r in rows]
        self.assertEqual(names[0], "big_sphere/ground")
        self.assertIn("peg_sphere/ground", names)
        first_peg = names.index("peg_sphere/ground")
        self.assertTrue(all(n == "big_sphere/ground" for n in names[:first_peg]))
        # the time series still has its row per sample
        with open(series) as f:
            self.assertEqual(len(f.read().splitlines()), 1 + 201)

    def test_an_unwritable_file_is_exit_1(self):
        code, err = run(["--duration", "0.01", "--contacts-csv", "/nonexistent/dir/c.csv"])
        self.assertEqual(code, 1, err)
        self.assertIn("simulate: cannot write /nonexistent/dir/c.csv", err)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
