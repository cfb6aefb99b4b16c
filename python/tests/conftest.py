"""Shared helpers: where the checkout and the command are, and the
environment every vorball test gets (tests/CMakeLists.txt): program caches
inside the build tree, never a user's."""
import os
import re
import subprocess

import numpy as np
import pytest

ROOT = os.environ.get("VORBALL_SOURCE_DIR") or os.path.dirname(
    os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = os.environ.get("VORBALL_BUILD_DIR") or os.path.join(ROOT, "build")
CLI = os.path.join(BUILD, "cli", "vorball")
CORPUS = os.path.join(ROOT, "corpus")
os.environ.setdefault("XDG_CACHE_HOME", os.path.join(BUILD, "test-cache"))
os.environ.setdefault("POCL_CACHE_DIR", os.path.join(BUILD, "test-cache", "pocl"))
os.environ.setdefault("VORBALL_HOST_BELOW", "1")  # auto opens the device, as in tests/CMakeLists.txt


def corpus(*parts):
    return os.path.join(CORPUS, *parts)


def cli(*args, rc=0, stdin=None, provenance=False):
    """Runs the command; returns (stdout, stderr); fails unless it exits rc.
    The provenance lines of a vertex file's header ("# tool:", "# input:",
    "# options:", issue 35: the command's own line, which the package has
    none of) are left out unless provenance=True; every other byte stays."""
    if not os.access(CLI, os.X_OK):
        pytest.fail("no command at %s (set VORBALL_BUILD_DIR)" % CLI)
    p = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, input=stdin)
    assert p.returncode == rc, "vorball %s exited %d, expected %d:\n%s" % (
        " ".join(map(str, args)), p.returncode, rc, p.stderr)
    out = p.stdout
    if not provenance:
        out = "".join(line for line in out.splitlines(keepends=True)
                      if not line.startswith(("# tool: ", "# input: ", "# options: ")))
        # A vertex JSON file carries the same as its first keys.
        out = re.sub(r'^\{"tool":"(?:[^"\\]|\\.)*","input":"(?:[^"\\]|\\.)*",'
                     r'"spheres":\d+,"options":"(?:[^"\\]|\\.)*",', "{", out)
    return out, p.stderr


def parse_vertices(text):
    """(ids, xyz, t) of a tsv vertex file."""
    ids, xyz, t = [], [], []
    for line in text.splitlines():
        if line.startswith("#") or not line:
            continue
        f = line.split("\t")
        ids.append(np.array([int(v) for v in f[0].split(",")]))
        xyz.append([float(v) for v in f[1:4]])
        t.append(float(f[4]))
    return ids, np.array(xyz).reshape(-1, 3), np.array(t)


def same_vertices(result, text):
    """The package's arrays are the command's numbers, bit for bit."""
    ids, xyz, t = parse_vertices(text)
    assert len(result.ids) == len(ids)
    assert all(np.array_equal(a, b) for a, b in zip(result.ids, ids))
    assert np.array_equal(result.xyz, xyz) and np.array_equal(result.t, t)
