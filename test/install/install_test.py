#!/usr/bin/python3
"""The package installs and runs the usual ROS ways.

- `cmake --install BUILD` gives a catkin install space in the configured CMAKE_INSTALL_PREFIX P
  (staged here under DESTDIR, as a packager does; catkin's setup.bash finds its own directory):
  after `source P/setup.bash` (in an environment that knows nothing of the build tree) `rospack find` names P, `rosrun` runs
  `simulate`, and `roslaunch nonsmooth_sim tippe_top.launch` runs the Tippe-Top to its ~duration.
- From the devel space (`source BUILD/devel/setup.bash`), `rosrun nonsmooth_sim nonsmooth_sim_node`
  serves the Tippe-Top.
- The launch files: a node that dies at start-up (a bad URDF) ends roslaunch (required="true"),
  with the node's one-line reason and roslaunch's "REQUIRED process ... has died" on its output
  (roslaunch 1.15 exits 0 even then: docs/ros.md says how a script tells), and a private parameter left on the master by an earlier run does not
  leak into the launched node (clear_params="true").

Each check waits with a timeout for what it expects (never a fixed sleep). Run by ctest:
test/install/install_test.py --build-dir BUILD
"""
import argparse
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
TIMEOUT = 60.0  # [s] for anything to happen
DURATION = 0.2  # [s] of simulated time a launched run lasts
BAD_URDF = os.path.join(ROOT, "test", "node", "fixtures", "negative_mass.urdf")


def free_port():
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Shell:
    """Commands run by bash after `source <setup.bash>`, in a clean environment (no trace of the
    build tree or of the caller's ROS variables), against a master on a port of its own."""

    def __init__(self, setup_bash, work_dir):
        self.setup_bash = setup_bash
        self.port = free_port()
        ros_home = os.path.join(work_dir, "ros_home")
        os.makedirs(ros_home, exist_ok=True)
        self.env = {
            "PATH": "/usr/bin:/bin",
            "HOME": work_dir,
            "ROS_HOME": ros_home,
            "ROS_IP": "127.0.0.1",
            "ROS_MASTER_URI": "http://127.0.0.1:%d" % self.port,
        }
        self.processes = []

    def argv(self, command):
        # setup.bash overwrites ROS_MASTER_URI with its default: restore ours after it
        return ["/bin/bash", "-c",
                'source "$0" && export ROS_MASTER_URI=%s && exec "$@"' % self.env["ROS_MASTER_URI"],
                self.setup_bash] + command

    def run(self, command, timeout=TIMEOUT):
        return subprocess.run(self.argv(command), env=self.env, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, universal_newlines=True, timeout=timeout)

    def start(self, command):
        process = subprocess.Popen(self.argv(command), env=self.env, stdout=subprocess.PIPE,
                                   stderr=subprocess.STDOUT, universal_newlines=True,
                                   start_new_session=True)
        self.processes.append(process)
        return process

    def stop_all(self):
        """SIGINT to each process group, newest first; SIGKILL after a timeout."""
        while self.processes:
            process = self.processes.pop()
            if process.poll() is None:
                os.killpg(process.pid, signal.SIGINT)
                try:
                    process.communicate(timeout=30)
                except subprocess.TimeoutExpired:
                    os.killpg(process.pid, signal.SIGKILL)
                    process.communicate()

    def start_master(self):
        self.start(["roscore", "-p", str(self.port)])
        self.wait_for(lambda: self.run(["rosparam", "get", "/rosversion"], timeout=10).returncode
                      == 0, "the master did not come up")

    def sim_time(self, node="/nonsmooth_sim"):
        """(sim_time, paused) from ~get_state, or None while the service is not there."""
        result = self.run(["rosservice", "call", node + "/get_state"], timeout=20)
        if result.returncode != 0:
            return None
        t = re.search(r"^\s*sim_time:\s*([-+0-9.eE]+)", result.stdout, re.M)
        paused = re.search(r"^\s*paused:\s*(True|False)", result.stdout, re.M)
        if not (t and paused):
            return None
        return float(t.group(1)), paused.group(1) == "True"

    def wait_for(self, condition, what, timeout=TIMEOUT):
        end = time.monotonic() + timeout
        while not condition():
            if time.monotonic() > end:
                raise AssertionError("timed out after %g s: %s" % (timeout, what))
            time.sleep(0.2)

    def wait_for_duration(self, process, duration=DURATION):
        """Until the node has paused at `duration` (its ~duration)."""
        def done():
            if process.poll() is not None:
                raise AssertionError("exited early with %d:\n%s" %
                                     (process.returncode, process.communicate()[0]))
            state = self.sim_time()
            return state is not None and state[1] and state[0] >= duration - 1e-9
        self.wait_for(done, "the node did not reach t = %g s" % duration)


class Installed(unittest.TestCase):
    prefix = None

    @classmethod
    def setUpClass(cls):
        cls.work = tempfile.mkdtemp(prefix="nonsmooth_sim_install_")
        # catkin writes the configured prefix into the install space's setup files, so the
        # prefix is chosen at configure time; DESTDIR stages the same tree elsewhere
        with open(os.path.join(BUILD_DIR, "CMakeCache.txt")) as f:
            cache = f.read()
        configured = re.search(r"^CMAKE_INSTALL_PREFIX:PATH=(.*)$", cache, re.M).group(1)
        assert configured != "/usr", "a /usr prefix is a binary package without setup files"
        stage = os.path.join(cls.work, "stage")
        cls.prefix = stage + configured
        env = dict(os.environ, DESTDIR=stage)
        result = subprocess.run(["cmake", "--install", BUILD_DIR], env=env,
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                universal_newlines=True, timeout=300)
        assert result.returncode == 0, "cmake --install failed:\n" + result.stdout
        assert stage in result.stdout and ": /" not in result.stdout.replace(": " + stage, ""), \
            "installed outside DESTDIR:\n" + result.stdout

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.work, ignore_errors=True)

    def setUp(self):
        self.shell = Shell(os.path.join(self.prefix, "setup.bash"), self.work)

    def tearDown(self):
        self.shell.stop_all()

    def test_layout(self):
        for path in ["setup.bash", "lib/nonsmooth_sim/nonsmooth_sim_node", "lib/nonsmooth_sim/simulate",
                     "lib/nonsmooth_sim/scene_report.py", "lib/libnonsmooth_sim_core.a",
                     "include/nonsmooth_sim/core/simulator.h",
                     "include/nonsmooth_sim/SimulationState.h",  # generated
                     "share/nonsmooth_sim/package.xml", "share/nonsmooth_sim/launch/scene.launch",
                     "share/nonsmooth_sim/urdf/euler_disk.urdf",
                     "share/nonsmooth_sim/config/euler_disk.yaml",
                     "share/nonsmooth_sim/cmake/nonsmooth_simConfig.cmake"]:
            self.assertTrue(os.path.exists(os.path.join(self.prefix, path)), path)
        for program in ["nonsmooth_sim_node", "simulate", "scene_report.py"]:
            self.assertTrue(os.access(os.path.join(self.prefix, "lib/nonsmooth_sim", program),
                                      os.X_OK), program)

    def test_rospack_finds_the_install_space(self):
        result = self.shell.run(["rospack", "find", "nonsmooth_sim"])
        self.assertEqual(result.returncode, 0, result.stdout)
        self.assertEqual(os.path.realpath(result.stdout.strip()),
                         os.path.realpath(os.path.join(self.prefix, "share", "nonsmooth_sim")))

    def test_rosrun_simulate(self):
        result = self.shell.run(["rosrun", "nonsmooth_sim", "simulate", "--duration", "0.01",
                                 "--quiet"])
        self.assertEqual(result.returncode, 0, result.stdout)

    def test_roslaunch_tippe_top(self):
        launch = self.shell.start(["roslaunch", "-p", str(self.shell.port), "nonsmooth_sim",
                                   "tippe_top.launch", "duration:=%g" % DURATION,
                                   "real_time_factor:=0"])
        self.shell.wait_for_duration(launch)

    def test_roslaunch_ends_when_the_node_dies(self):
        launch = self.shell.start(["roslaunch", "-p", str(self.shell.port), "nonsmooth_sim",
                                   "tippe_top.launch", "model:=" + BAD_URDF])
        try:
            output = launch.communicate(timeout=TIMEOUT)[0]
        except subprocess.TimeoutExpired:
            self.fail("roslaunch went on after the node died")
        # the node's one-line reason, and roslaunch's line a script can look for
        self.assertIn('link "tippe_top" > inertial > mass', output)
        self.assertRegex(output, r"REQUIRED process \[nonsmooth_sim-\d+\] has died")

    def test_a_stale_private_parameter_does_not_leak_into_a_launch(self):
        self.shell.start_master()
        # what `rosrun nonsmooth_sim nonsmooth_sim_node _urdf_file:=...` leaves on the master
        stale = self.shell.run(["rosparam", "set", "/nonsmooth_sim/urdf_file", BAD_URDF])
        self.assertEqual(stale.returncode, 0, stale.stdout)
        launch = self.shell.start(["roslaunch", "nonsmooth_sim", "tippe_top.launch",
                                   "duration:=%g" % DURATION, "real_time_factor:=0"])
        self.shell.wait_for_duration(launch)
        gone = self.shell.run(["rosparam", "get", "/nonsmooth_sim/urdf_file"])
        self.assertNotEqual(gone.returncode, 0, "the stale ~urdf_file is still set")


def other_build_trees_with(program):
    """The executables named `program` that rosrun would find below the package (ROOT) outside
    BUILD_DIR: like rosrun, skipping ROOT/build/."""
    found = []
    for directory, subdirs, files in os.walk(ROOT):
        real = os.path.realpath(directory)
        if real == BUILD_DIR or real == os.path.join(os.path.realpath(ROOT), "build"):
            subdirs[:] = []
            continue
        subdirs[:] = [d for d in subdirs if d != ".git"]
        path = os.path.join(directory, program)
        if program in files and os.access(path, os.X_OK):
            found.append(os.path.relpath(path, ROOT))
    return sorted(found)


class Devel(unittest.TestCase):
    def setUp(self):
        self.work = tempfile.mkdtemp(prefix="nonsmooth_sim_devel_")
        self.shell = Shell(os.path.join(BUILD_DIR, "devel", "setup.bash"), self.work)

    def tearDown(self):
        self.shell.stop_all()
        shutil.rmtree(self.work, ignore_errors=True)

    def test_rosrun_node(self):
        # rosrun skips everything below <package>/build/ (its find has ! -regex '<pkg>/build/'):
        # the default build directory is build-release/ for that reason (docs/building.md)
        others = other_build_trees_with("nonsmooth_sim_node")
        if others:
            # rosrun finds every executable of that name below the package and asks which one
            # (exit 127 without a terminal): e.g. build-asan/ next to build-release/
            self.skipTest("rosrun cannot choose: other build trees hold nonsmooth_sim_node: " +
                          ", ".join(others))
        self.shell.start_master()
        urdf = os.path.join(ROOT, "urdf", "tippe_top.urdf")
        node = self.shell.start(["rosrun", "nonsmooth_sim", "nonsmooth_sim_node",
                                 "_urdf_file:=" + urdf, "_duration:=%g" % DURATION,
                                 "_real_time_factor:=0"])
        self.shell.wait_for_duration(node)

        # what it advertises at run time is documented (test/docs/ros_docs_test.py reads the
        # sources; this asks the master)
        sys.path.insert(0, os.path.join(ROOT, "test", "docs"))
        from ros_docs_test import undocumented
        names = set()
        for lister in (["rosservice", "list"], ["rostopic", "list"]):
            result = self.shell.run(lister)
            self.assertEqual(result.returncode, 0, result.stdout)
            names |= set(result.stdout.split())
        ours = set()
        for name in names:
            if name.startswith("/nonsmooth_sim/"):
                local = name[len("/nonsmooth_sim/"):]
                if local in ("get_loggers", "set_logger_level"):  # every roscpp node's
                    continue
                ours.add("~wrench/<" if local.startswith("wrench/") else "~" + local)
            elif name in ("/clock", "/tf", "/diagnostics"):
                ours.add(name)
        self.assertIn("~wrench/<", ours)
        self.assertIn("~set_friction_set", ours)
        doc = open(os.path.join(ROOT, "docs", "ros.md"), encoding="utf-8").read()
        self.assertEqual(undocumented(ours, doc), [])


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--build-dir", required=True)
    args, rest = parser.parse_known_args()
    BUILD_DIR = os.path.realpath(args.build_dir)
    unittest.main(argv=[sys.argv[0]] + rest, verbosity=2)
