"""Shared by the Python module's tests: the voxcd tool they compare the module with, and the test scenes."""
import json
import os
import subprocess
from pathlib import Path

import pytest

SCENES = Path(__file__).resolve().parents[2] / "scenes"


@pytest.fixture(scope="session")
def voxcd_bin():
    path = os.environ.get("VOXCD_BIN")
    assert path, "VOXCD_BIN must name the voxcd tool (ctest sets it)"
    assert os.access(path, os.X_OK), f"VOXCD_BIN={path} is not an executable"
    return path


@pytest.fixture(scope="session")
def cli(voxcd_bin):
    """Runs `voxcd ARGS...` and returns its standard output; fails the test on a non-zero exit."""

    def run(*args, expect=0):
        proc = subprocess.run([voxcd_bin, *map(str, args)], capture_output=True, text=True)
        assert proc.returncode == expect, f"voxcd {' '.join(map(str, args))} exited {proc.returncode}:\n{proc.stderr}"
        return proc.stdout

    return run


@pytest.fixture(scope="session")
def cli_error(voxcd_bin):
    """Runs `voxcd ARGS...`, which must fail with exit code `expect`, and returns the first line of its standard
    error without the tool's "voxcd: error: " (the library's message)."""

    def run(*args, expect):
        proc = subprocess.run([voxcd_bin, *map(str, args)], capture_output=True, text=True)
        assert proc.returncode == expect, f"voxcd {' '.join(map(str, args))} exited {proc.returncode}:\n{proc.stderr}"
        return proc.stderr.splitlines()[0].removeprefix("voxcd: error: ")

    return run


@pytest.fixture(scope="session")
def cli_json(cli):
    return lambda *args: json.loads(cli(*args, "--json"))


@pytest.fixture(scope="session")
def scenes():
    return SCENES
