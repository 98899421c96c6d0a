"""Shared fixtures of the Python tests (tests/python, README "Tests"): the module under test
comes from the build (PYTHONPATH set by CTest), trilab-cli from TRILAB_CLI, small meshes from
`trilab-cli generate` (and ../shared/meshes when present)."""
import os
import subprocess

import pytest

import trilab

SHARED_MESHES = os.path.join(os.path.dirname(__file__), "..", "..", "..", "shared", "meshes")


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("TRILAB_CLI")
    if not path or not os.path.exists(path):
        pytest.skip("TRILAB_CLI is not set to a built trilab-cli (run the tests through ctest)")
    return path


@pytest.fixture(scope="session")
def meshes(cli, tmp_path_factory):
    """Small generated meshes by name: a closed sphere, an open grid, a torus."""
    d = tmp_path_factory.mktemp("meshes")
    out = {}
    for name in ("default", "grid", "torus"):
        path = str(d / (name + ".ply"))
        subprocess.run([cli, "generate", name, path], check=True, capture_output=True)
        out[name] = path
    return out


def run_cli(cli, *args):
    r = subprocess.run([cli, *args], capture_output=True, text=True)
    return r.returncode, r.stdout, r.stderr
