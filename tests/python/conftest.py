# conftest.py: what the Python tests share: the `lucent` CLI they check the module against (LUCENT_CLI, set by
# ctest, see python/CMakeLists.txt), a folder for their files, and the scenes.
import os
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
CLI = os.environ.get("LUCENT_CLI", str(REPO / "build" / "lucent"))
SCENES = Path(os.environ.get("LUCENT_SCENES_DIR", str(REPO / "scenes")))


def run_cli(*args, check=True):
    """Runs `lucent ARGS...`; returns the completed process (stdout and stderr as text)."""
    result = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True, timeout=120)
    if check and result.returncode != 0:
        raise AssertionError(f"lucent {' '.join(map(str, args))} failed: {result.stderr}")
    return result


@pytest.fixture
def out_dir(tmp_path):
    return tmp_path
