"""Shared fixtures of the Python module's tests (run by ctest: tests/CMakeLists.txt sets PYTHONPATH to the build
tree's package, SKINSPEC_PROGRAM to the command-line program and SKINSPEC_BUILD_DIR to the build folder)."""
import json
import os
import subprocess

import pytest

REFERENCE_DIR = os.path.join(os.path.dirname(__file__), "..", "reference")


@pytest.fixture
def cli():
    """Runs the skinspec program with arguments; returns its parsed --json output (or raises with its stderr)."""
    program = os.environ["SKINSPEC_PROGRAM"]

    def run(*args):
        done = subprocess.run([program, *args, "--json"], capture_output=True, text=True)
        if done.returncode != 0:
            raise AssertionError(f"skinspec {' '.join(args)} exited {done.returncode}: {done.stderr}")
        return json.loads(done.stdout)

    return run
