#!/usr/bin/python3
"""Every path of this repository named in the docs, the build files, the message and service
definitions, the launch files and the comments of the code exists, so that a reader who follows one
finds the file (a renamed or deleted file is caught where it is still named).

A path is a token that starts with one of the repository's top folders (src/, include/, test/,
scripts/, docs/, config/, urdf/, launch/, cmake/, bench/, msg/, srv/, .ci/). Placeholders are not
paths: a token followed or preceded by `<`, `{`, `*`, `$`, or with an all-capitals part
(`urdf/NAME.urdf`, `config/S.yaml`). A few names are of files that are not in the source tree on
purpose; each is listed in NOT_IN_THE_TREE with the reason.

Run by ctest (no ROS needed): test/docs/paths_test.py
"""
import glob
import os
import re
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
TOP = r"(?:src|include|test|scripts|docs|config|urdf|launch|cmake|bench|msg|srv|\.ci)"
PATH = re.compile(r"(?<![\w/.-])(" + TOP + r"/[A-Za-z0-9_./-]*[A-Za-z0-9_])")
NOT_IN_THE_TREE = {
    # urdfdom's header (#include <urdf/model.h> is what the ROS-free check forbids)
    "urdf/model.h": "urdfdom",
}
# headers generated from msg/ and srv/ into the devel and install spaces
GENERATED = re.compile(r"^include/nonsmooth_sim/[A-Z]\w*\.h$")
SOURCES = ["README.md", "CMakeLists.txt", "package.xml", "docs/*.md", "cmake/*.cmake",
           "launch/*.launch", "msg/*", "srv/*", "include/**/*.h", "src/**/*.cpp", "src/**/*.h",
           "test/**/*.cpp", "test/**/*.h", "test/**/*.py", "test/**/*.test", "scripts/**/*",
           "bench/**/*.cpp", ".ci/*"]


def is_placeholder(token, before, after):
    if before in "<{$" or after in "<{*$":
        return True
    parts = re.split(r"[/.]", token)
    return any(len(p) > 0 and p.isupper() for p in parts[1:])


def named_paths():
    """{path: [files naming it]} of every path token in SOURCES."""
    found = {}
    for pattern in SOURCES:
        for path in glob.glob(os.path.join(ROOT, pattern), recursive=True):
            if os.path.isdir(path):
                continue
            try:
                with open(path, encoding="utf-8") as f:
                    text = f.read()
            except UnicodeDecodeError:
                continue
            for m in PATH.finditer(text):
                token = m.group(1).rstrip(".")
                before = text[m.start() - 1:m.start()] if m.start() > 0 else ""
                after = text[m.end():m.end() + 1]
                if is_placeholder(token, before, after):
                    continue
                found.setdefault(token, set()).add(os.path.relpath(path, ROOT))
    return found


def exists(token):
    path = os.path.join(ROOT, token)
    # a prefix of a file name is how prose names a family ("test/scenes/rattleback_test")
    return os.path.exists(path) or bool(glob.glob(path + "*"))


class PathsTest(unittest.TestCase):
    def test_every_named_path_exists(self):
        missing = {t: sorted(f) for t, f in named_paths().items()
                   if not exists(t) and t not in NOT_IN_THE_TREE and not GENERATED.match(t)}
        self.assertEqual(missing, {}, "paths named but not in the tree (path: where)")

    def test_it_finds_paths(self):
        # the scan is not vacuous: the README names scripts/demo and scripts/test
        found = named_paths()
        self.assertIn("scripts/demo", found)
        self.assertIn("README.md", found["scripts/test"])

    def test_it_would_catch_a_missing_one(self):
        self.assertFalse(exists("src/core/" + "no_such_file.cpp"))  # (not a path token here)
        self.assertTrue(is_placeholder("urdf/NAME.urdf", " ", " "))
        self.assertFalse(is_placeholder("urdf/tippe_top.urdf", " ", " "))


if __name__ == "__main__":
    unittest.main()
