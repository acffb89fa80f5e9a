#!/usr/bin/python3
"""simulate --rolling-resistance METRES (docs/simulate.md): a bad value (negative, NaN, infinite,
not a number, beyond 1000 m) is refused with one line naming the option and what is allowed
(exit code 2); an accepted one gives the contacts of a rolling friction set their rolling
components, which the CSV then carries (<sphere>_lambda_r1, _lambda_r2), and which take energy
out of the Tippe-Top; without it, or with a set without rolling, the CSV has no such columns.

  simulate_rolling_resistance_test.py <simulate executable> <source dir>
"""
import csv
import os
import subprocess
import sys
import tempfile
import unittest

SIMULATE = sys.argv[1] if len(sys.argv) > 1 else "build-release/devel/lib/nonsmooth_sim/simulate"
SOURCE = sys.argv[2] if len(sys.argv) > 2 else "."


def run(args):
    """(exit code, stderr lines) of simulate with `args`."""
    done = subprocess.run([SIMULATE, "--quiet"] + args, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, timeout=120)
    return done.returncode, done.stderr.decode().splitlines()


def read_csv(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], [[float(x) for x in row] for row in rows[1:]]


class RollingResistanceOption(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.tmp.cleanup()

    def test_bad_values_are_refused_naming_what_is_allowed(self):
        for value in ["-1e-4", "nan", "inf", "abc", "", "2e3"]:
            code, lines = run(["--rolling-resistance", value, "--duration", "0.01"])
            self.assertEqual(code, 2, (value, lines))
            self.assertEqual(lines, ["simulate: invalid value '" + value +
                                     "' for --rolling-resistance: expected a "
                                     "rolling-resistance length in [0, 1000] m"], value)

    def run_top(self, extra):
        path = os.path.join(self.tmp.name, "top.csv")
        code, lines = run(["--integrator", "moreau", "--duration", "0.5", "--decimate", "100",
                           "--csv", path] + extra)
        self.assertEqual(code, 0, lines)
        return read_csv(path)

    def test_a_rolling_set_carries_the_rolling_percussion(self):
        header, rows = self.run_top(["--friction-set", "rolling", "--rolling-resistance", "1e-4"])
        self.assertIn("big_sphere_lambda_r1", header)
        self.assertIn("big_sphere_lambda_r2", header)
        r1 = header.index("big_sphere_lambda_r1")
        r2 = header.index("big_sphere_lambda_r2")
        n = header.index("big_sphere_lambda_n")
        # the rolling torque is bounded by mu_r lambda_N, and acts
        self.assertTrue(any(abs(row[r1]) + abs(row[r2]) > 0.0 for row in rows))
        for row in rows:
            self.assertLessEqual((row[r1] ** 2 + row[r2] ** 2) ** 0.5, 1e-4 * row[n] * (1 + 1e-6))
        # and it dissipates: less energy left than without it
        _, plain = self.run_top(["--friction-set", "rolling"])
        e = header.index("energy")
        self.assertLess(rows[-1][e], plain[-1][e])

    def test_without_rolling_there_are_no_rolling_columns(self):
        for extra in [["--friction-set", "rolling"],
                      ["--friction-set", "sphere", "--rolling-resistance", "1e-4"]]:
            header, _ = self.run_top(extra)
            self.assertFalse([c for c in header if "lambda_r" in c], extra)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
