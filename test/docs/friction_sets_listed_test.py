#!/usr/bin/python3
"""Every place outside the code that lists the friction sets lists exactly the program's sets, in
its order: the message, service and launch comments, the docs, and the help text, compared with
`simulate --list-friction-sets` (the laws table, include/nonsmooth_sim/core/friction_law.h).

A listing is an enumeration of at least four of the sets ("a, b, c, d", "a, b, c or d", with or
without backticks; shorter ones name a group, e.g. "the ball sets (sphere, ellipsoid, coulomb)").
It must name every set, in the program's order. A new law that is missing from one of them, or a
removed one still listed, fails here and names the file and line.

Run by ctest: test/docs/friction_sets_listed_test.py --simulate BIN
"""
import argparse
import glob
import os
import re
import subprocess
import sys
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
SIMULATE = None
# the files that may list the sets for a reader (the scripts ask the program)
LISTING_FILES = ["msg/*.msg", "srv/*.srv", "launch/*.launch", "docs/*.md", "README.md",
                 "include/nonsmooth_sim/scene_io/*.h", "src/simulate/*.cpp"]


def program_sets():
    out = subprocess.run([SIMULATE, "--list-friction-sets"], check=True, capture_output=True,
                         text=True).stdout
    return out.split("\n")[:-1] if out.endswith("\n") else out.split("\n")


def listings(sets):
    """(path, line number, names in order) of every enumeration of ≥ 4 sets: names (optionally in
    backticks) separated by commas, "or" or "and"."""
    name = r"`?\b(?:" + "|".join(map(re.escape, sets)) + r")\b`?"
    separator = r"(?:\s*,\s*(?:or\s+|and\s+)?|\s+or\s+|\s+and\s+)"
    enumeration = re.compile(name + r"(?:" + separator + name + r")+")
    word = re.compile(r"\b(?:" + "|".join(map(re.escape, sets)) + r")\b")
    found = []
    for pattern in LISTING_FILES:
        for path in sorted(glob.glob(os.path.join(ROOT, pattern))):
            with open(path, encoding="utf-8") as f:
                for number, line in enumerate(f, 1):
                    for match in enumeration.finditer(line):
                        names = word.findall(match.group(0))
                        if len(names) >= 4:
                            found.append((os.path.relpath(path, ROOT), number, names))
    return found


class FrictionSetsListed(unittest.TestCase):
    def test_the_program_lists_the_sets_one_per_line(self):
        sets = program_sets()
        self.assertGreaterEqual(len(sets), 2)
        for name in sets:
            self.assertRegex(name, r"^[a-z_]+$")
        self.assertEqual(len(sets), len(set(sets)))
        # each name is accepted back by --friction-set (a 1-step run)
        for name in sets:
            run = subprocess.run([SIMULATE, "--quiet", "--friction-set", name, "--duration",
                                  "1e-4"], capture_output=True, text=True)
            self.assertEqual(run.returncode, 0, name + ": " + run.stderr)
        run = subprocess.run([SIMULATE, "--friction-set", "no_such_set"], capture_output=True,
                             text=True)
        self.assertEqual(run.returncode, 2)
        self.assertIn(", ".join(sets), run.stderr)

    def test_every_listing_names_every_set_in_order(self):
        sets = program_sets()
        found = listings(sets)
        # the shipped listings: msg, srv, launch, docs/ros.md, docs/urdf.md, the help text
        files = {path for path, _, _ in found}
        for expected in ["msg/ContactInfo.msg", "srv/SetFrictionSet.srv",
                         "launch/tippe_top.launch", "docs/ros.md", "docs/urdf.md"]:
            self.assertIn(expected, files)
        for path, number, names in found:
            self.assertEqual(names, sets, "%s:%d lists %s, the program %s"
                             % (path, number, ", ".join(names), ", ".join(sets)))

    def test_the_help_text_lists_the_sets(self):
        help_text = subprocess.run([SIMULATE, "--help"], check=True, capture_output=True,
                                   text=True).stdout
        self.assertIn(", ".join(program_sets()), help_text)
        self.assertIn("--list-friction-sets", help_text)


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("--simulate", required=True, help="the simulate binary")
    args, rest = parser.parse_known_args()
    SIMULATE = args.simulate
    unittest.main(argv=[sys.argv[0]] + rest)
