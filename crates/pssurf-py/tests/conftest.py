"""Shared fixtures: random data, the command-line tool, a temporary directory."""

import os
import shutil

import numpy as np
import pytest


@pytest.fixture
def rng():
    return np.random.default_rng(20261125)


def quadratic(x, y):
    """A general quadratic and its exact derivatives (value, zx, zy, zxx, zxy, zyy)."""
    z = 0.3 + 1.2 * x - 0.7 * y + 0.9 * x * x - 1.1 * x * y + 0.4 * y * y
    return z, 1.2 + 1.8 * x - 1.1 * y, -0.7 - 1.1 * x + 0.8 * y, 1.8, -1.1, 0.8


@pytest.fixture
def cli():
    """The `pssurf` command-line tool: $PSSURF_CLI (run-tests.sh sets it), else on PATH.
    A test that needs it fails (does not skip) when it is missing."""
    path = os.environ.get("PSSURF_CLI") or shutil.which("pssurf")
    assert path and os.path.exists(path), "set PSSURF_CLI to the pssurf binary"
    return path
