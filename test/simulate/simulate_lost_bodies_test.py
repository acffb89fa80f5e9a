#!/usr/bin/python3
"""simulate never loses a body silently (docs/simulate.md, "Lost bodies"): a body whose only
has no collision at all warns once, at t = 0, that it never touches anything, and the JSON
summary lists it under "lost_bodies"; a scene whose bodies all keep their collisions lists none.

  simulate_lost_bodies_test.py <simulate executable> <source dir>
"""
import json
import os
import subprocess
import sys
import tempfile
import unittest

SIMULATE = sys.argv[1] if len(sys.argv) > 1 else "build-release/devel/lib/nonsmooth_sim/simulate"
SOURCE = sys.argv[2] if len(sys.argv) > 2 else "."

# a top with a mass and no collision at all
MESH_TOP = """<robot name="r"><link name="top"><inertial><origin xyz="0 0 0.1"/>
<mass value="0.1"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>
</link></robot>
"""


def run(args):
    """(exit code, stderr lines) of simulate with `args`."""
    done = subprocess.run([SIMULATE, "--quiet"] + args, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, timeout=120)
    return done.returncode, done.stderr.decode().splitlines()


class LostBodies(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.tmp.cleanup()

    def test_a_body_without_collision_is_warned_once_and_listed(self):
        urdf = os.path.join(self.tmp.name, "mesh_top.urdf")
        with open(urdf, "w") as f:
            f.write(MESH_TOP)
        summary = os.path.join(self.tmp.name, "s.json")
        code, lines = run(["--urdf", urdf, "--duration", "0.5", "--summary", summary])
        self.assertEqual(code, 0, lines)
        warned = [l for l in lines if "never touches anything" in l]
        self.assertEqual(warned, ['simulate: warning: body "top" has no collision: it never '
                                  'touches anything (found at t = 0 s)'], lines)
        with open(summary) as f:
            lost = json.load(f)["lost_bodies"]
        self.assertEqual(lost, {"top": {"t": 0, "why": "has no collision: it never touches "
                                                       "anything"}})

    def test_a_scene_that_keeps_its_collisions_lists_none(self):
        summary = os.path.join(self.tmp.name, "s.json")
        code, lines = run(["--urdf", os.path.join(SOURCE, "urdf", "coin.urdf"), "--initial",
                           os.path.join(SOURCE, "config", "coin.yaml"), "--duration", "0.3",
                           "--summary", summary])
        self.assertEqual(code, 0, lines)
        self.assertEqual([l for l in lines if "warning: body" in l], [], lines)
        with open(summary) as f:
            self.assertEqual(json.load(f)["lost_bodies"], {})


if __name__ == "__main__":
    unittest.main(argv=[sys.argv[0]])
