#!/usr/bin/python3
"""The README's "while it runs" commands, run as a user copies them, in order, against the node of
`roslaunch nonsmooth_sim tippe_top.launch` (a master of its own on a free loopback port): each
exits 0 within its timeout, no service replies `success: False`, and the ones with an effect show
it (the step advances the time, the spawn adds models, the delete removes one, the solver change is
read back). A command that drifts from the code (a renamed field, a value rosservice refuses, a
call that hangs while paused) fails here.

Run by ctest: test/docs/readme_commands_test.py --build-dir BUILD
"""
import os
import re
import shlex
import subprocess
import sys
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from ros_session import NODE, Session, run_tests  # noqa: E402
BUILD_DIR = None  # the build folder, set by run_tests from --build-dir

TIMEOUT = 60.0  # [wall s] per command


def readme_block(after):
    """The commands of the first ```bash block after the line containing `after`."""
    text = open(os.path.join(ROOT, "README.md"), encoding="utf-8").read()
    start = text.index(after)
    block = re.search(r"```bash\n(.*?)```", text[start:], re.S).group(1)
    commands = []
    for line in block.splitlines():
        # a comment is "#" after two spaces or more (a # inside quotes is not one)
        code = re.split(r"\s{2,}#", line)[0].strip()
        if code and not code.startswith("#"):
            commands.append(code)
    return commands


class ReadmeCommands(unittest.TestCase):
    def test_while_it_runs(self):
        commands = readme_block("While it runs, one example per service")
        self.assertGreater(len(commands), 10)
        out_dir = os.path.join(BUILD_DIR, "test_out")
        os.makedirs(out_dir, exist_ok=True)
        session = Session(BUILD_DIR, out_dir,
                          os.path.join(out_dir, "readme_commands_%d.log" % os.getpid()))
        outputs = {}
        try:
            session.start_master()
            session.start("roslaunch", ["roslaunch", os.path.join(ROOT, "launch", "tippe_top.launch"),
                                        "rviz:=false"])
            subprocess.run([session.env_sh, "rosservice", "call", "--wait", NODE + "/get_state"],
                           env=session.env, stdout=subprocess.DEVNULL, timeout=TIMEOUT, check=True)
            for command in commands:
                argv = shlex.split(command)
                if argv[0].startswith("scripts/"):
                    argv[0] = os.path.join(ROOT, argv[0])
                run = subprocess.run([session.env_sh] + argv, env=session.env, cwd=ROOT,
                                     stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                     universal_newlines=True, timeout=TIMEOUT)
                self.assertEqual(run.returncode, 0, "%s:\n%s" % (command, run.stdout))
                self.assertNotIn("success: False", run.stdout, command)
                outputs[command] = run.stdout
        finally:
            session.stop()
        by_service = {c.split()[2] if c.startswith("rosservice call") else c.split()[0]: o
                      for c, o in outputs.items()}
        # the effects: a step returns the new time, the world lists the spawned tops but not the
        # deleted one, the solver change is read back by a later call
        self.assertIn("sim_time", by_service[NODE + "/step"])
        world = by_service[NODE + "/get_world_properties"]
        self.assertIn("top_1", world)
        self.assertNotIn("top_0", world)
        self.assertIn("big_sphere/ground", by_service["rostopic"])


if __name__ == "__main__":
    run_tests(globals())
