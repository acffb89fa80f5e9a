#!/usr/bin/python3
"""A bag recorded by the launch file (through scripts/record) holds the five recorded topics, with
sample counts (stamps on /tf, steps on ~contacts, messages elsewhere) equal to the simulated
duration times each topic's publish rate, at the sim
times the rates promise, and a /clock that only advances and is never 0. ~contacts lists closed
contacts only, named "<first collision>/<second collision>" (the spinning top starts on
"big_sphere/ground"; an open peg is absent).

Run by ctest: test/node/bag_record_test.py --build-dir BUILD
"""
import os
import subprocess
import sys
import unittest

import rosbag

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from ros_session import run_tests, tf_samples  # noqa: E402
BUILD_DIR = None  # the build folder, set by run_tests from --build-dir

DURATION = 2.0       # [s] of simulated time
TIME_STEP = 1e-4     # the node's default ~time_step [s]
RATES = {            # the node's default publish rates [Hz of simulated time]
    "/tf": 1000.0,
    "/nonsmooth_sim/contacts": 1000.0,
    "/nonsmooth_sim/state": 100.0,
}
RECORDED = {"/tf", "/clock", "/nonsmooth_sim/contacts", "/nonsmooth_sim/state", "/diagnostics"}


def step_of(t):
    return round(t / TIME_STEP)


class RecordedBag(unittest.TestCase):
    bag_path = None

    @classmethod
    def setUpClass(cls):
        out_dir = os.path.join(BUILD_DIR, "test_out")
        name = "bag_record_test_%d" % os.getpid()
        result = subprocess.run(
            [os.path.join(ROOT, "scripts", "record"), "--build-dir", BUILD_DIR,
             "--out-dir", out_dir, "--name", name, "--duration", repr(DURATION), "--timeout", "90"],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True, timeout=110)
        print(result.stdout)
        cls.bag_path = os.path.join(out_dir, name + ".bag")
        assert result.returncode == 0, "scripts/record failed:\n" + result.stdout
        cls.bag = rosbag.Bag(cls.bag_path)

    @classmethod
    def tearDownClass(cls):
        cls.bag.close()
        os.remove(cls.bag_path)

    def messages(self, topic):
        return [m for _, m, _ in self.bag.read_messages(topics=[topic])]

    def samples(self, topic):
        """Per sample: a /tf sample's transforms, a ~contacts step, any other message."""
        if topic == "/tf":
            return [s for m in self.messages(topic) for s in tf_samples(m)]
        if topic == "/nonsmooth_sim/contacts":
            return [step for m in self.messages(topic) for step in m.steps]
        return self.messages(topic)

    def test_holds_exactly_the_recorded_topics(self):
        topics = set(self.bag.get_type_and_topic_info().topics)
        self.assertEqual(topics, RECORDED)

    def test_counts_match_the_publish_rates(self):
        info = self.bag.get_type_and_topic_info().topics
        for topic, rate in RATES.items():
            self.assertEqual(len(self.samples(topic)), round(DURATION * rate), topic)
        # /diagnostics is published at ~diagnostics_rate in wall time: at least one
        self.assertGreaterEqual(info["/diagnostics"].message_count, 1)

    def test_messages_come_at_the_promised_sim_times(self):
        # ~contacts every 10 steps, ~state every 100 steps, none missing, none repeated
        for topic in ("/nonsmooth_sim/contacts", "/nonsmooth_sim/state"):
            period = round(1.0 / (RATES[topic] * TIME_STEP))
            steps = [step_of(m.sim_time) for m in self.samples(topic)]
            self.assertEqual(steps, [period * (k + 1) for k in range(len(steps))], topic)
        stamps = [step_of(s[0].header.stamp.to_sec()) for s in self.samples("/tf")]
        self.assertEqual(stamps, [10 * (k + 1) for k in range(len(stamps))])

    def test_contacts_are_the_closed_ones_by_name(self):
        messages = self.samples("/nonsmooth_sim/contacts")
        self.assertTrue(messages)
        listed = 0
        for m in messages:
            for c in m.contacts:
                self.assertTrue(c.closed, (m.sim_time, c.name))
                self.assertIn(c.name, (c.collision + "/" + c.other_collision,
                                       c.other_collision + "/" + c.collision), m.sim_time)
                self.assertEqual(c.body, "tippe_top")
                if c.other_collision == "ground":
                    self.assertEqual(c.other_body, "")
                self.assertIn(c.frame, ("", c.collision + "_contact"), (m.sim_time, c.name))
                listed += 1
        self.assertGreater(listed, 0)
        # the launch file's start: spinning on the big sphere, the peg in the air
        self.assertEqual([c.name for c in messages[0].contacts], ["big_sphere/ground"])
        self.assertEqual(messages[0].contacts[0].other_collision, "ground")

    def test_clock_only_advances_and_is_never_zero(self):
        clock = [m.clock for m in self.messages("/clock")]
        self.assertGreaterEqual(len(clock), 2)
        self.assertFalse(clock[0].is_zero())
        for earlier, later in zip(clock, clock[1:]):
            self.assertLess(earlier, later)
        self.assertEqual(step_of(clock[-1].to_sec()), step_of(DURATION))


if __name__ == "__main__":
    run_tests(globals())
