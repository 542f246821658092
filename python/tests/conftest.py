"""Fixtures shared by the package's tests: the suite character, read once, and the command-line tool to
compare with (ctest sets OMSK_CLI, OMSK_TEST_MODELS and PYTHONPATH; see python/CMakeLists.txt)."""

import os
import subprocess

import pytest

import openmeshskinned as oms

MODELS = os.environ.get("OMSK_TEST_MODELS", "/usr/share/assimp/models")
WUSON = os.path.join(MODELS, "X", "Testwuson.X")


def cli(*args):
    """Runs skinned-decimate; returns (exit status, stdout, stderr)."""
    exe = os.environ.get("OMSK_CLI")
    if not exe:
        pytest.skip("OMSK_CLI is not set (run through ctest)")
    r = subprocess.run([exe, *map(str, args)], capture_output=True, text=True, timeout=600)
    return r.returncode, r.stdout, r.stderr


def cli_error(*args):
    """The one-line message skinned-decimate prints for a failure, without its "skinned-decimate: " prefix."""
    status, _, err = cli(*args)
    assert status != 0, err
    lines = [line for line in err.splitlines() if not line.startswith("skinned-decimate: warning: ")]
    assert len(lines) == 1, err
    assert lines[0].startswith("skinned-decimate: ")
    return status, lines[0][len("skinned-decimate: "):]


@pytest.fixture(scope="session")
def wuson():
    return oms.load(WUSON)


@pytest.fixture(scope="session")
def wuson_lods(wuson):
    return oms.make_lods(wuson, ratios=[0.5, 0.25], poses=3)
