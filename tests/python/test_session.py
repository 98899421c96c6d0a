"""trilab.Session and trilab.replay against `trilab-cli session make|recipe` and `replay`."""
import json

import numpy as np
import pytest

import trilab
from conftest import run_cli


@pytest.fixture(scope="module")
def session(cli, meshes, tmp_path_factory):
    d = tmp_path_factory.mktemp("session")
    path = str(d / "s.trilab")
    code, _, err = run_cli(cli, "session", "make", meshes["default"], path, "--op",
                           "smooth --iterations 3", "--select", "sphere:0,0,1,0.8", "--op",
                           "noise --amount 2")
    assert code == 0, err
    return path


def test_session_entries_and_states(cli, session):
    s = trilab.Session(session)
    code, out, err = run_cli(cli, "session", "info", session, "--json")
    assert code == 0, err
    info = json.loads(out)
    assert len(s) == len(s.entries) == 4 and s.current == 3 and not s.journal
    assert [e["label"] for e in s.entries][1] == "Smooth"
    assert s.entries[1]["operation"] == "smooth" and s.entries[0]["operation"] is None
    assert len(s.entries[1]["steps"]) == 3
    assert s.state(-1).n_faces == s.entries[-1]["steps"][-1][1]
    assert info  # the CLI reads the same file
    with pytest.raises(IndexError):
        s.state(4)


def test_replay_gives_the_session_state_and_the_cli_file(cli, meshes, session, tmp_path):
    s = trilab.Session(session)
    recipe = s.recipe()
    last = trilab.replay(recipe, trilab.load(meshes["default"]))
    assert np.array_equal(last.V, s.state(-1).V) and np.array_equal(last.F, s.state(-1).F)
    path = str(tmp_path / "r.json")
    code, _, err = run_cli(cli, "session", "recipe", session, path)
    assert code == 0, err
    out = str(tmp_path / "cli.ply")
    code, _, err = run_cli(cli, "replay", path, meshes["default"], out)
    assert code == 0, err
    mine = str(tmp_path / "py.ply")
    trilab.replay(path, trilab.load(meshes["default"])).save(mine)
    with open(out, "rb") as a, open(mine, "rb") as b:
        assert a.read() == b.read()
    assert np.array_equal(trilab.replay(json.loads(recipe), trilab.load(meshes["default"])).V,
                          last.V)
    with pytest.raises(ValueError):
        trilab.replay('{"format": "trilab-recipe", "version": 2, "operations": [{"x": 1}]}',
                      trilab.load(meshes["default"]))
