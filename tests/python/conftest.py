"""Fixtures of the Python module's tests (CTest runs them: python_tests). The gonio package comes
from build/python (PYTHONPATH), the command-line binary from GONIO_BINARY."""
import os
import subprocess
import sys

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tests"))  # compare_results.py


@pytest.fixture(scope="session")
def gonio_binary():
    path = os.environ.get("GONIO_BINARY", os.path.join(ROOT, "build", "gonio"))
    assert os.path.exists(path), f"{path}: no gonio binary (set GONIO_BINARY)"
    return path


@pytest.fixture(scope="session")
def root():
    return ROOT


@pytest.fixture
def cli(gonio_binary):
    """Runs the gonio command line; returns its completed process (checked)."""
    def call(*args, cwd=None):
        return subprocess.run([gonio_binary, *args], cwd=cwd, check=True, capture_output=True,
                              text=True)
    return call
