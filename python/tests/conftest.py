"""Shared set-up of the pytest suite (run by ctest as python.pytest with PYTHONPATH at the build
tree's python/ folder).  Seeds are fixed and printed; tolerances are named in tolerances.py."""
import os
import pathlib
import subprocess
import zlib

import numpy as np
import pytest

import inbetween  # noqa: F401  (fails loudly when the module is not on sys.path)

SOURCE_DIR = pathlib.Path(os.environ.get("INBETWEEN_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


def cli_path():
    """The inbetween tool of the same build (INBETWEEN_CLI, set by ctest), or None."""
    p = os.environ.get("INBETWEEN_CLI", "")
    return p if p and os.access(p, os.X_OK) else None


@pytest.fixture
def cli():
    p = cli_path()
    if p is None:
        pytest.skip("the inbetween tool is not built (INBETWEEN_CLI unset)")

    def run(*args, check=True):
        r = subprocess.run([p, *map(str, args)], capture_output=True, text=True)
        if check and r.returncode != 0:
            raise AssertionError(f"inbetween {' '.join(map(str, args))} failed: {r.stderr}")
        return r
    return run


@pytest.fixture
def source_dir():
    return SOURCE_DIR


@pytest.fixture
def rng(request):
    """A NumPy generator seeded from the test's name (deterministic across runs, unlike hash());
    the seed is printed so a failure can be replayed with INBETWEEN_SEED."""
    if os.environ.get("INBETWEEN_SEED"):
        seed = int(os.environ["INBETWEEN_SEED"])
    else:
        seed = zlib.crc32(request.node.name.encode())
    print(f"seed {seed} (INBETWEEN_SEED={seed} replays)")
    return np.random.default_rng(seed)
