#!/usr/bin/python3
"""Every parameter, service and topic the node declares, and every argument of the launch files,
is documented in docs/ros.md, so that the reference cannot drift from the code again.

The names are read from the node's sources (src/node/*.cpp): parameters from the ParameterReader
calls (r.Number("time_step"), r.Numbers("initial/position", 3), r.Get("initial_state"), ...),
services from advertiseService("..."), topics from advertise<...>("..."); launch arguments from
<arg name="..."/> in launch/*.launch. A private name `x` must appear in docs/ros.md as `~x`, a
global one as `/x`, a launch argument as `x`, each in backticks (a table cell or the text).

Run by ctest (no ROS needed): test/docs/ros_docs_test.py
"""
import glob
import os
import re
import unittest
import xml.etree.ElementTree as ET

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
DOC = os.path.join(ROOT, "docs", "ros.md")

PARAMETER = re.compile(r'\br\.(?:Number|Numbers|String|Strings|Bool|Integer|Get)\(\s*"([^"]+)"')
SERVICE = re.compile(r'advertiseService\(\s*"([^"]+)"')
# advertise<T>("name", ...) or advertise<T>("prefix/" + something, ...)
TOPIC = re.compile(r'advertise<[^>]+>\(\s*"([^"]+)"(\s*\+)?')


def node_sources():
    sources = sorted(glob.glob(os.path.join(ROOT, "src", "node", "*.cpp")))
    return "\n".join(open(path, encoding="utf-8").read() for path in sources)


def declared(source):
    """{"parameters": {...}, "services": {...}, "topics": {...}} as documented names (`~x`, `/x`,
    `~prefix/<...>` for a topic name built at run time)."""
    def private(name):
        return name if name.startswith("/") else "~" + name
    topics = set()
    for name, built in TOPIC.findall(source):
        topics.add(private(name) + ("<" if built else ""))
    return {
        "parameters": {private(n) for n in PARAMETER.findall(source)},
        "services": {private(n) for n in SERVICE.findall(source)},
        "topics": topics,
    }


def launch_arguments():
    names = set()
    for path in sorted(glob.glob(os.path.join(ROOT, "launch", "*.launch"))):
        names |= {arg.get("name") for arg in ET.parse(path).getroot().iter("arg")}
    return names


def undocumented(names, doc):
    """The names that do not appear in backticks in `doc`. A name ending in "<" (a topic with a
    run-time suffix such as ~wrench/<collision>) must appear followed by "<"."""
    spans = [span for line in doc.splitlines() if not line.lstrip().startswith("```")
             for span in re.findall(r"`([^`]+)`", line)]
    missing = []
    for name in sorted(names):
        if name.endswith("<"):
            if not any(s.startswith(name) for s in spans):
                missing.append(name + "...>")
        elif name not in spans:
            missing.append(name)
    return missing


class RosDocs(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.doc = open(DOC, encoding="utf-8").read()
        cls.names = declared(node_sources())

    def test_the_sources_are_read(self):
        # the patterns above still match the code: a few names that have always been there
        self.assertIn("~time_step", self.names["parameters"])
        self.assertIn("~initial/position", self.names["parameters"])
        self.assertIn("~initial_state", self.names["parameters"])
        self.assertIn("~set_friction_set", self.names["services"])
        self.assertIn("/clock", self.names["topics"])
        self.assertIn("~wrench/<", self.names["topics"])
        self.assertGreaterEqual(len(self.names["parameters"]), 30)
        self.assertGreaterEqual(len(self.names["services"]), 11)
        self.assertGreaterEqual(len(self.names["topics"]), 6)

    def test_every_parameter_is_documented(self):
        self.assertEqual(undocumented(self.names["parameters"], self.doc), [])

    def test_every_service_is_documented(self):
        self.assertEqual(undocumented(self.names["services"], self.doc), [])

    def test_every_topic_is_documented(self):
        self.assertEqual(undocumented(self.names["topics"], self.doc), [])

    def test_every_launch_argument_is_documented(self):
        self.assertEqual(undocumented(launch_arguments(), self.doc), [])

    def test_a_missing_name_is_reported(self):
        doc = "| `~time_step` | 1e-4 |\n`~wrench/<collision>`"
        self.assertEqual(undocumented({"~time_step", "~wrench/<", "~gap_correction"}, doc),
                         ["~gap_correction"])
        self.assertEqual(undocumented({"~wrench/<"}, "`~wrench`"), ["~wrench/<...>"])


if __name__ == "__main__":
    unittest.main(verbosity=2)
