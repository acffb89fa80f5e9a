#!/usr/bin/python3
"""simulate refuses files that are not regular files or exceed the size bound with one line and
exit code 2, before reading them (a FIFO without a writer must not hang it, /dev/zero must not be
read until memory runs out); an exception the loader does not expect (out of memory) is one line
and exit code 4 (docs/simulate.md, "Exit codes"). A URDF the loader refuses (a link with mass on
a moving joint) is one line and exit code 2 as well; with --hold-joint it loads, and an unknown
joint name is one line and exit code 2.

  simulate_files_test.py <simulate executable> <source dir>
"""
import os
import resource
import subprocess
import sys
import tempfile
import unittest

SIMULATE = sys.argv[1] if len(sys.argv) > 1 else "build-release/devel/lib/nonsmooth_sim/simulate"
SOURCE = sys.argv[2] if len(sys.argv) > 2 else "."
URDF = os.path.join(SOURCE, "urdf", "coin.urdf")
INITIAL = os.path.join(SOURCE, "config", "coin.yaml")  # starts without an overlap warning
BOUND = 16 << 20


def run(args, limit_memory=None, timeout=60):
    """(exit code, stderr lines) of simulate with `args`; fails on a hang (timeout)."""
    def limit():
        if limit_memory:
            resource.setrlimit(resource.RLIMIT_AS, (limit_memory, limit_memory))
    done = subprocess.run([SIMULATE, "--quiet"] + args, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, timeout=timeout, preexec_fn=limit)
    return done.returncode, done.stderr.decode(errors="replace").splitlines()


class SimulateFiles(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.tmp.cleanup()

    def expect_refusal(self, args, *parts, code=2):
        returncode, lines = run(args)
        self.assertEqual(returncode, code, lines)
        self.assertEqual(len(lines), 1, lines)
        for part in parts:
            self.assertIn(part, lines[0])

    def test_devices_are_refused(self):
        for device in ("/dev/zero", "/dev/urandom"):
            self.expect_refusal(["--urdf", device], "simulate: urdf: " + device +
                                ": is a character device, not a regular file; allowed: a URDF "
                                "file, a regular file of at most 16777216 bytes (16 MiB)")
            self.expect_refusal(["--urdf", URDF, "--initial", device],
                                "simulate: initial state: " + device + ": is a character device")

    def test_fifo_does_not_hang(self):
        fifo = os.path.join(self.tmp.name, "scene.fifo")
        os.mkfifo(fifo)
        self.expect_refusal(["--urdf", fifo], "urdf: " + fifo + ": is a FIFO")
        self.expect_refusal(["--urdf", URDF, "--initial", fifo],
                            "initial state: " + fifo + ": is a FIFO")

    def test_oversize_files_are_refused(self):
        big = os.path.join(self.tmp.name, "big.urdf")
        with open(URDF) as f:
            text = f.read()
        with open(big, "w") as f:
            f.write(text.replace("</robot>", "<!--" + " " * BOUND + "--></robot>"))
        self.expect_refusal(["--urdf", big],
                            "more than the bound of 16777216 bytes (16 MiB)")
        yaml = os.path.join(self.tmp.name, "big.yaml")
        with open(yaml, "w") as f:
            f.write("#" * (BOUND + 1))
        self.expect_refusal(["--urdf", URDF, "--initial", yaml],
                            "initial state: " + yaml + ": has 16777217 bytes, more than the "
                            "bound")

    def test_second_yaml_document_is_refused(self):
        yaml = os.path.join(self.tmp.name, "two.yaml")
        with open(yaml, "w") as f:
            f.write("bodies: {}\n---\nbodies: {}\n")
        self.expect_refusal(["--urdf", URDF, "--initial", yaml],
                            "(line 2, column 1): a second YAML document")

    def test_a_link_with_mass_on_a_moving_joint_is_refused(self):
        # the loader's UrdfError is a bad file: one line, exit 2, nothing simulated without the
        # rotor's mass (the node's fixture, test/node/fixtures)
        gyroscope = os.path.join(SOURCE, "test", "node", "fixtures", "moving_joint.urdf")
        self.expect_refusal(["--urdf", gyroscope],
                            "simulate: urdf: " + gyroscope + ": joint \"rotor_joint\" "
                            "(continuous) moves link \"rotor\"",
                            "make it fixed to merge the link into its parent, or floating to "
                            "make it a body of its own")

    def test_hold_joint_holds_the_rotor_and_refuses_what_it_cannot_hold(self):
        # --hold-joint NAME (repeatable): the gyroscope that was refused above loads, its rotor
        # merged into the frame (one body in the CSV, one warning saying so); a name that is no
        # moving joint of the URDF is one line and exit 2, as is --hold-joint without --urdf
        gyroscope = os.path.join(SOURCE, "test", "node", "fixtures", "moving_joint.urdf")
        csv = os.path.join(self.tmp.name, "gyroscope.csv")
        returncode, lines = run(["--urdf", gyroscope, "--hold-joint", "rotor_joint",
                                 "--hold-joint=rotor_joint", "--duration", "0.002", "--dt",
                                 "1e-4", "--decimate", "1", "--csv", csv])
        self.assertEqual(returncode, 0, lines)
        held = [line for line in lines if "is held rigid" in line]
        self.assertEqual(held, ["simulate: warning: urdf: joint \"rotor_joint\" (continuous) is "
                                "held rigid at 0 rad by the option hold_joints: its link "
                                "\"rotor\" (0.1 kg and 1 collision) is merged into its parent "
                                "link \"frame\"; the simulator has no joints"])
        with open(csv) as f:
            header = f.readline().strip().split(",")
        self.assertIn("frame/x", header)
        self.assertFalse([column for column in header if column.startswith("rotor/")], header)
        self.expect_refusal(["--urdf", gyroscope, "--hold-joint", "rotor"],
                            "simulate: urdf: " + gyroscope + ": the option hold_joints: no joint "
                            "named \"rotor\"; allowed: a revolute, continuous, prismatic or "
                            "planar joint; the joints that move here: joint \"rotor_joint\" "
                            "(continuous)")
        self.expect_refusal(["--hold-joint", "rotor_joint"],
                            "simulate: --hold-joint needs --urdf")
        self.expect_refusal(["--urdf", gyroscope, "--hold-joint", ""],
                            "simulate: invalid value '' for --hold-joint: expected the name of a "
                            "joint of the --urdf that moves")
        self.expect_refusal(["--urdf", gyroscope, "--hold-joint"],
                            "simulate: missing value for --hold-joint")

    def test_out_of_memory_is_one_line_and_exit_4(self):
        # the CSV is reserved up front: 10^6 rows (decimate 10) of 20 columns, 160 MB, beyond
        # 100 MB of address space (the run alone needs about 20 MB). A sanitizer's runtime
        # reserves more address space than that before main (its report goes to a log file,
        # not to stderr), so a sanitized build (CMake passes NONSMOOTH_SIM_SANITIZE) skips it.
        if os.environ.get("NONSMOOTH_SIM_SANITIZE"):
            self.skipTest("a sanitizer's runtime needs more address space than the limit")
        csv = os.path.join(self.tmp.name, "run.csv")
        returncode, lines = run(["--urdf", URDF, "--initial", INITIAL, "--duration", "1000",
                                 "--csv", csv], limit_memory=100 << 20)
        self.assertEqual(returncode, 4, lines)
        self.assertEqual(lines, ["simulate: out of memory (the scene or the run needs more "
                                 "memory than the system gives)"])

if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0]])
