#!/usr/bin/python3
"""scripts/dev/mesh_tippe_top (docs/urdf.md, "Bodies of revolution") as a user runs it: it writes
the Tippe-Top as an STL and two URDFs; `simulate --urdf revolution.urdf` inverts when
urdf/tippe_top.urdf's two spheres do (the summary's t_theta_above_2_4, within 2 ms), and the
plain hull's URDF loads and runs.

  simulate_mesh_tippe_top_test.py <simulate executable> <source dir>
"""
import json
import os
import subprocess
import sys
import tempfile
import unittest

SIMULATE = sys.argv[1] if len(sys.argv) > 1 else "build-release/devel/lib/nonsmooth_sim/simulate"
SOURCE = sys.argv[2] if len(sys.argv) > 2 else "."


class MeshTippeTop(unittest.TestCase):
    def summary(self, folder, urdf):
        path = os.path.join(folder, os.path.basename(urdf) + ".json")
        subprocess.run([SIMULATE, "--quiet", "--urdf", urdf, "--initial",
                        os.path.join(SOURCE, "config", "tippe_top.yaml"), "--duration", "1.5",
                        "--summary", path], check=True, timeout=120)
        with open(path) as f:
            return json.load(f)

    def test_the_body_of_revolution_inverts_with_the_two_spheres(self):
        with tempfile.TemporaryDirectory() as folder:
            subprocess.run(["/usr/bin/python3", os.path.join(SOURCE, "scripts", "dev",
                                                             "mesh_tippe_top"), folder],
                           check=True, stdout=subprocess.DEVNULL, timeout=60)
            spheres = self.summary(folder, os.path.join(SOURCE, "urdf", "tippe_top.urdf"))
            mesh = self.summary(folder, os.path.join(folder, "revolution.urdf"))
            hull = self.summary(folder, os.path.join(folder, "hull.urdf"))
        self.assertIsNotNone(spheres["t_theta_above_2_4"])
        self.assertIsNotNone(mesh["t_theta_above_2_4"])
        self.assertAlmostEqual(mesh["t_theta_above_2_4"], spheres["t_theta_above_2_4"],
                               delta=2e-3)
        self.assertTrue(hull["state_finite"])
        print("t(theta > 2.4): two spheres %.4f s, body of revolution %.4f s, plain hull %s"
              % (spheres["t_theta_above_2_4"], mesh["t_theta_above_2_4"],
                 hull["t_theta_above_2_4"]))


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
