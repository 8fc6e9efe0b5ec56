# Shared fixtures of the Python module's tests: the nimbus program to compare with, and a runner.
import os
import re
import subprocess

import pytest


@pytest.fixture(scope="session")
def program():
    """The nimbus program of the same build (CTest sets NIMBUS_PROGRAM)."""
    path = os.environ.get("NIMBUS_PROGRAM")
    if not path or not os.access(path, os.X_OK):
        pytest.fail("NIMBUS_PROGRAM must name the nimbus program of this build")
    return path


@pytest.fixture(scope="session")
def run(program):
    """Runs the program with arguments; returns (exit code, stdout, stderr)."""
    def runner(*args, check=True):
        done = subprocess.run([program, *map(str, args)], capture_output=True, text=True)
        if check and done.returncode != 0:
            raise AssertionError(f"nimbus {' '.join(map(str, args))} exited {done.returncode}: {done.stderr}")
        return done.returncode, done.stdout, done.stderr
    return runner


def cli_error(stderr):
    """The program's one-line error, without its "nimbus: " (and "error: ") prefix."""
    line = stderr.strip().splitlines()[-1]
    for prefix in ("nimbus: error: ", "nimbus: "):
        if line.startswith(prefix):
            return line[len(prefix):]
    return line


def python_words(message, names=None):
    """The program's message as the module says it: each flag (--voxel-size) as the argument it
    stands for (voxel_size, or names[flag])."""
    names = names or {}
    return re.sub(r"(?<![\w.-])--[a-z][a-z0-9-]*", lambda m: names.get(m.group(0), m.group(0)[2:].replace("-", "_")), message)
