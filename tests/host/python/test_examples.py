"""The example scripts of docs/examples/python run and print what they say. contacts.py and world.py are
docs/examples/cpp's contacts.cpp and world.cpp in Python: the same names and defaults, the same output (world.cpp
prints the same state hash)."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

import voxcd

EXAMPLES = Path(__file__).resolve().parents[3] / "docs" / "examples" / "python"


@pytest.mark.parametrize("script, expect", [
    ("contacts.py", ["(0.554, 0.989, 0.326) depth 0.000"]),
    ("world.py", ["8 bodies, 4 touching pairs over 100 frames, state hash d0f2add1681c787a",
                  "0.88 s: bodies 1 and 2 began touching", "1.92 s: bodies 1 and 2 stopped touching",
                  "the probe is at x = 64.00"]),
    ("errors.py", ["MeshError ", "ObjectFileError ", "RangeError ", "CapacityError ", "BodyError "]),
    ("collide.py", [" hits; deepest contact at "]),
    ("pairs.py", ["torus: 57x57x17 voxels of 0.05", " hits, ", "torus in cube: point "]),
    ("sweep.py", ["x = -3.00:     0 hits", "x = +0.00: "]),
    ("events.py", ["s: ring and probe began touching", "s: ring and probe stopped touching",
                   "the probe is at x = 64.00"]),
])
def test_example_runs(tmp_path, script, expect):
    env = dict(os.environ, PYTHONPATH=str(Path(voxcd.__file__).resolve().parent))  # the module under test
    proc = subprocess.run([sys.executable, str(EXAMPLES / script)], capture_output=True, text=True, cwd=tmp_path,
                          env=env)
    assert proc.returncode == 0, proc.stderr
    for text in expect:
        assert text in proc.stdout, proc.stdout
    assert not list(tmp_path.iterdir()), "an example wrote into the working directory"
