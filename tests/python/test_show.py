"""Mesh.show(): the viewer on a mesh, and the mesh shown when it ends, with its history.

The viewer is the build's (TRILAB_VIEWER_BIN) under xvfb-run, through a wrapper script given as
TRILAB_VIEWER; a wrapper that adds an --op stands for a user's edit in the window."""
import os
import shutil
import stat

import numpy as np
import pytest

import trilab


def wrapper(tmp_path, extra=""):
    viewer = os.environ.get("TRILAB_VIEWER_BIN", "")
    if not viewer or not os.path.exists(viewer):
        pytest.skip("no viewer built (TRILAB_VIEWER_BIN)")
    if shutil.which("xvfb-run") is None:
        pytest.skip("xvfb-run is not installed")
    script = tmp_path / "viewer.sh"
    script.write_text('#!/bin/sh\nexec xvfb-run -a -s "-screen 0 800x600x24" "%s" "$@" %s\n'
                      % (viewer, extra))
    script.chmod(script.stat().st_mode | stat.S_IEXEC)
    return str(script)


def test_show_without_a_display_says_so_and_changes_nothing(monkeypatch):
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    m = trilab.Mesh(np.eye(3), np.array([[0, 1, 2]]))
    before = m.V.copy()
    with pytest.raises(RuntimeError, match="no display"):
        m.show()
    assert np.array_equal(m.V, before)


def test_show_returns_the_mesh_shown_bit_for_bit(monkeypatch, tmp_path):
    monkeypatch.setenv("TRILAB_VIEWER", wrapper(tmp_path))
    monkeypatch.setenv("DISPLAY", os.environ.get("DISPLAY", ":xvfb-run"))
    m = trilab.Mesh(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0 / 3]]),
                    np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]))
    shown = m.show(frames=3)
    assert np.array_equal(shown.V, m.V) and np.array_equal(shown.F, m.F)
    assert len(shown.session) == 1 and shown.session.current == 0
    assert m.session is None


def test_show_hands_back_the_edit_and_its_history(monkeypatch, tmp_path):
    monkeypatch.setenv("TRILAB_VIEWER",
                       wrapper(tmp_path, '--op "subdivide --iterations 1"'))
    monkeypatch.setenv("DISPLAY", os.environ.get("DISPLAY", ":xvfb-run"))
    m = trilab.Mesh(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]]),
                    np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]))
    shown = m.show(frames=5)
    assert shown.n_faces == 4 * m.n_faces  # the viewer's Loop step, as a user would apply it
    assert [e["label"] for e in shown.session.entries] == ["From Python", "Subdivide"]
    assert np.array_equal(shown.session.state(0).V, m.V)  # the history keeps the input
    assert m.n_faces == 4  # the input is unchanged


def test_a_viewer_that_fails_is_an_error_with_its_words(monkeypatch, tmp_path):
    monkeypatch.setenv("TRILAB_VIEWER", wrapper(tmp_path, "--no-such-option"))
    monkeypatch.setenv("DISPLAY", os.environ.get("DISPLAY", ":xvfb-run"))
    m = trilab.Mesh(np.eye(3), np.array([[0, 1, 2]]))
    with pytest.raises(RuntimeError, match="no-such-option"):
        m.show(frames=2)
