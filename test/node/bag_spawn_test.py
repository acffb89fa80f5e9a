#!/usr/bin/python3
"""A rosbag of a run with a spawn and a delete replays what happened: the Tippe-Top of the launch
file, two tops spawned by scripts/spawn_tops (its rospy client of ~spawn_urdf_model and
~set_model_state) and one of them deleted by ~delete_model. In the bag's /tf, the deleted top's
frame appears after the spawn and stops at the deletion (its last stamp is the last publish before
it), the other spawned top's and the start-up top's go on to the end; every /tf sample is stamped
at a multiple of the 10-step tf period, and each top's frame moves (they spin and precess).

Run by ctest: test/node/bag_spawn_test.py --build-dir BUILD
"""
import os
import subprocess
import sys
import time
import unittest

import rosbag

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from ros_session import NODE, Session, run_tests, tf_samples, wait_for  # noqa: E402
BUILD_DIR = None  # the build folder, set by run_tests from --build-dir

TIME_STEP = 1e-4   # the node's default ~time_step [s]
TF_PERIOD = 10     # steps: /tf at 1 kHz of sim time
BEFORE = 2000      # steps before the spawn
WITH = 3000        # steps with both spawned tops
AFTER = 3000       # steps after the deletion
CHUNK = 100       # steps per ~step call
QUIET = 0.5        # [wall s] the /tf stream counts as drained after this long without a message


def step_of(t):
    return round(t / TIME_STEP)


class SpawnDeleteBag(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        out_dir = os.path.join(BUILD_DIR, "test_out")
        os.makedirs(out_dir, exist_ok=True)
        cls.bag_path = os.path.join(out_dir, "bag_spawn_test_%d.bag" % os.getpid())
        session = Session(BUILD_DIR, out_dir, cls.bag_path + ".log")
        try:
            session.start_master()
            import rospy  # after the session has set ROS_MASTER_URI
            from std_srvs.srv import Empty  # noqa: F401
            from tf2_msgs.msg import TFMessage
            from nonsmooth_sim.srv import DeleteModel, StepSimulation

            session.start("roslaunch", [
                "roslaunch", os.path.join(ROOT, "launch", "tippe_top.launch"),
                "record:=true", "bag:=" + cls.bag_path, "paused:=true", "rviz:=false",
                "real_time_factor:=0", "max_wall_publish_rate:=0"])
            rospy.init_node("bag_spawn_driver", anonymous=True, disable_signals=True)
            last = [time.monotonic()]
            latest = [0]  # step of the latest /tf stamp the driver received

            def on_tf(message):
                last[0] = time.monotonic()
                latest[0] = step_of(message.transforms[-1].header.stamp.to_sec())

            tf = rospy.Subscriber("/tf", TFMessage, on_tf, queue_size=100000)
            wait_for(lambda: ("/tf", "/record") in session.outgoing_links(NODE), 60,
                     "rosbag record did not connect to /tf")
            rospy.wait_for_service(NODE + "/step", timeout=30)
            step = rospy.ServiceProxy(NODE + "/step", StepSimulation)

            def run(steps):
                # in calls of CHUNK steps (CHUNK / TF_PERIOD samples), each once the driver has
                # received the last one's /tf: ~step publishes as fast as it steps, and rosbag
                # record (a parallel subscriber) drops beyond a queue of 100 messages
                for _ in range(steps // CHUNK):
                    reply = step(steps=CHUNK)
                    assert reply.success, reply.status_message
                    done = step_of(reply.sim_time)
                    wait_for(lambda: latest[0] >= done, 30, "/tf did not reach step %d" % done)

            def drained():
                wait_for(lambda: time.monotonic() - last[0] > QUIET, 60, "/tf never went quiet")

            run(BEFORE)
            spawned = subprocess.run(
                [session.env_sh, os.path.join(ROOT, "scripts", "spawn_tops"), "2",
                 "--radius", "0.4", "--node", NODE],
                env=session.env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                universal_newlines=True, timeout=60)
            assert spawned.returncode == 0, spawned.stdout
            run(WITH)
            deleted = rospy.ServiceProxy(NODE + "/delete_model", DeleteModel)(model_name="top_0")
            assert deleted.success, deleted.status_message
            run(AFTER)
            drained()
            tf.unregister()
            rospy.signal_shutdown("done")
        finally:
            session.stop()  # SIGINT: rosbag closes the bag
        assert os.path.isfile(cls.bag_path), "no bag (log: %s.log)" % cls.bag_path
        cls.frames = {}  # child frame -> [step of each stamp]
        cls.stamps = []
        with rosbag.Bag(cls.bag_path) as bag:
            for _, m, _ in bag.read_messages(topics=["/tf"]):
                for sample in tf_samples(m):
                    cls.stamps.append(step_of(sample[0].header.stamp.to_sec()))
                    for t in sample:
                        cls.frames.setdefault(t.child_frame_id, []).append(
                            (step_of(t.header.stamp.to_sec()), t.transform.translation.x,
                             t.transform.translation.y))

    @classmethod
    def tearDownClass(cls):
        os.remove(cls.bag_path)
        if os.path.exists(cls.bag_path + ".log"):
            os.remove(cls.bag_path + ".log")

    def test_every_tf_sample_is_at_a_tf_period(self):
        self.assertEqual(self.stamps, [TF_PERIOD * (k + 1) for k in range(len(self.stamps))])
        self.assertEqual(self.stamps[-1], BEFORE + WITH + AFTER)

    def test_the_deleted_top_stops_at_the_deletion(self):
        steps = [s for s, _, _ in self.frames["top_0/tippe_top"]]
        self.assertEqual(steps[0], BEFORE + TF_PERIOD)
        self.assertEqual(steps[-1], BEFORE + WITH)
        self.assertEqual(len(steps), WITH // TF_PERIOD)

    def test_the_others_go_on_to_the_end(self):
        end = BEFORE + WITH + AFTER
        self.assertEqual([s for s, _, _ in self.frames["top_1/tippe_top"]][-1], end)
        self.assertEqual([s for s, _, _ in self.frames["top_1/tippe_top"]][0], BEFORE + TF_PERIOD)
        self.assertEqual([s for s, _, _ in self.frames["tippe_top"]][-1], end)
        self.assertEqual(len(self.frames["tippe_top"]), end // TF_PERIOD)

    def test_each_top_moves(self):
        for frame in ("tippe_top", "top_0/tippe_top", "top_1/tippe_top"):
            xs = [x for _, x, _ in self.frames[frame]]
            self.assertGreater(max(xs) - min(xs), 1e-5, frame)


if __name__ == "__main__":
    run_tests(globals())
