"""A headless ROS session for scripts/record and scripts/screenshot (and the bag tests).

Starts a master of its own on a free loopback port (ROS_IP=127.0.0.1, never reachable from other
machines), runs commands inside the build's catkin environment (devel/env.sh) with argument lists
(never through a shell), and stops what it started by PID, newest first, with SIGINT (rosbag
closes its bag, rviz its window), SIGKILL only after a timeout.
"""
import os
import signal
import socket
import subprocess
import sys
import time
import xmlrpc.client

ROOT = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
NODE = "/nonsmooth_sim"  # the node's name in launch/tippe_top.launch
STOP_TIMEOUT = 30.0  # [s] per process, after SIGINT


def check_friction_set(parser, build_dir, name):
    """parser.error unless `name` is one of the friction sets of the build's program
    (`simulate --list-friction-sets`: the laws table); without a simulate in build_dir the node
    checks it."""
    for simulate in (os.path.join(build_dir, "devel", "lib", "nonsmooth_sim", "simulate"),
                     os.path.join(build_dir, "bin", "simulate")):
        if os.access(simulate, os.X_OK):
            sets = subprocess.run([simulate, "--list-friction-sets"], check=True,
                                  capture_output=True, text=True).stdout.split()
            if name not in sets:
                parser.error("--friction-set: %r is not one of %s" % (name, ", ".join(sets)))
            return


def fail(script, message):
    print("%s: %s" % (script, message), file=sys.stderr)
    sys.exit(1)


def free_port():
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def wait_for(condition, timeout, what):
    """Polls `condition` until it holds; TimeoutError(what) after `timeout` seconds."""
    end = time.monotonic() + timeout
    while not condition():
        if time.monotonic() > end:
            raise TimeoutError(what)
        time.sleep(0.01)


def tf_samples(message):
    """The samples of a /tf message, oldest first: one list of transforms per run of equal stamps
    (the node sends several stamps in one message, ~max_samples_per_message)."""
    samples = []
    for t in message.transforms:
        if not samples or samples[-1][-1].header.stamp != t.header.stamp:
            samples.append([])
        samples[-1].append(t)
    return samples


def run_tests(module_globals):
    """The entry of a unittest file that ctest runs with --build-dir BUILD: sets the file's
    BUILD_DIR (realpath), hands the other arguments to unittest (its tests are in __main__)."""
    import argparse
    import unittest
    parser = argparse.ArgumentParser()
    parser.add_argument("--build-dir", required=True)
    args, rest = parser.parse_known_args()
    module_globals["BUILD_DIR"] = os.path.realpath(args.build_dir)
    unittest.main(module="__main__", argv=[sys.argv[0]] + rest, verbosity=2)


def inside(folder, name):
    """folder/name, refusing anything that would leave `folder`."""
    path = os.path.realpath(os.path.join(folder, name))
    if os.path.dirname(path) != os.path.realpath(folder):
        raise ValueError("%s would leave the output folder %s" % (name, folder))
    return path


class Session:
    def __init__(self, build_dir, out_dir, log_path):
        self.env_sh = os.path.join(os.path.realpath(build_dir), "devel", "env.sh")
        if not os.path.isfile(self.env_sh):
            raise FileNotFoundError("%s not found: build first (scripts/build)" % self.env_sh)
        self.port = free_port()
        ros_home = os.path.join(out_dir, "ros_home")
        os.makedirs(ros_home, exist_ok=True)
        self.env = dict(os.environ)
        self.env.update({
            "PATH": "/usr/bin:" + self.env.get("PATH", ""),  # Debian's python, not pyenv's
            "ROS_MASTER_URI": "http://127.0.0.1:%d" % self.port,
            "ROS_IP": "127.0.0.1",
            "ROS_HOME": ros_home,
        })
        self.env.pop("ROS_HOSTNAME", None)
        os.environ.update(self.env)  # for this process's own rospy
        self.log = open(log_path, "w")
        self.processes = []
        self.master = None

    def start(self, name, command, extra_env=None, in_catkin_env=True):
        env = dict(self.env)
        env.update(extra_env or {})
        argv = ([self.env_sh] if in_catkin_env else []) + command
        process = subprocess.Popen(argv, env=env, stdout=self.log, stderr=self.log)
        self.processes.append((name, process))
        return process

    def start_master(self):
        import rosgraph
        self.start("roscore", ["roscore", "-p", str(self.port)])
        self.master = rosgraph.Master("/script_driver")
        wait_for(self.master.is_online, 30, "the master did not come up")

    def outgoing_links(self, publisher):
        """(topic, subscriber node) pairs the publisher has connected (its getBusInfo): a
        subscriber registered with the master may still be connecting."""
        import rosgraph
        try:
            uri = self.master.lookupNode(publisher)
        except rosgraph.MasterError:
            return set()
        code, _, info = xmlrpc.client.ServerProxy(uri).getBusInfo("/script_driver")
        return {(c[4], c[1]) for c in info if code == 1 and c[2] == "o" and c[5]}

    def stop(self):
        """SIGINT newest first, SIGKILL what does not stop."""
        while self.processes:
            name, process = self.processes.pop()
            if process.poll() is None:
                process.send_signal(signal.SIGINT)
                try:
                    process.wait(timeout=STOP_TIMEOUT)
                except subprocess.TimeoutExpired:
                    print("%s did not stop on SIGINT, killed" % name, file=self.log)
                    process.kill()
                    process.wait()
        self.log.close()
