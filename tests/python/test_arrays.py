"""trilab.Mesh's arrays: V views the mesh's memory (read-only, shared), F, properties, the
constructor from any dtype and memory order, and bad input refused with a clear ValueError."""
import json

import numpy as np
import pytest

import trilab

TETRA_V = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
TETRA_F = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]


def test_version():
    assert isinstance(trilab.__version__, str) and trilab.__version__.count(".") == 2


def test_v_is_a_read_only_view_of_the_mesh(meshes):
    m = trilab.load(meshes["default"])
    a, b = m.V, m.V
    assert a.shape == (m.n_vertices, 3) and a.dtype == np.float64
    assert np.shares_memory(a, b), "two reads of V copy the positions"
    assert a.base is not None
    assert not a.flags.writeable
    with pytest.raises(ValueError):
        a[0, 0] = 1.0
    with pytest.raises(ValueError):
        a.flags.writeable = True
    del m  # the view keeps the mesh alive
    assert np.isfinite(a).all()


def test_arrays_round_trip_through_a_file(meshes, tmp_path):
    m = trilab.load(meshes["torus"])
    F = m.F
    assert F.dtype == np.int64 and F.shape == (m.n_faces, 3)
    assert F.min() >= 0 and F.max() < m.n_vertices
    copy = trilab.Mesh(m.V, F)
    assert np.array_equal(copy.V, m.V) and np.array_equal(copy.F, F)
    path = str(tmp_path / "t.off")
    copy.save(path)
    again = trilab.Mesh(trilab.load(path).V, trilab.load(path).F)
    assert np.array_equal(again.F, F)
    assert np.allclose(again.V, m.V)


@pytest.mark.parametrize("vdtype", [np.float32, np.float64, np.int32, np.int64])
@pytest.mark.parametrize("fdtype", [np.int32, np.int64, np.uint16, np.float64])
@pytest.mark.parametrize("order", ["C", "F"])
def test_any_dtype_and_memory_order(vdtype, fdtype, order):
    V = np.array(TETRA_V, dtype=vdtype, order=order)
    F = np.array(TETRA_F, dtype=fdtype, order=order)
    m = trilab.Mesh(V, F)
    assert np.array_equal(m.V, np.array(TETRA_V, dtype=float))
    assert np.array_equal(m.F, np.array(TETRA_F))
    assert m.load_report == []


def test_strided_input_is_read_correctly():
    V = np.zeros((4, 6))
    V[:, ::2] = TETRA_V
    m = trilab.Mesh(V[:, ::2], np.array(TETRA_F)[:, :])
    assert np.array_equal(m.V, np.array(TETRA_V, dtype=float))


@pytest.mark.parametrize("V,F,message", [
    (np.zeros((4, 2)), TETRA_F, r"V: expected shape \(n, 3\), got \(4, 2\)"),
    (np.zeros(12), TETRA_F, r"V: expected shape \(n, 3\), got \(12,\)"),
    (TETRA_V, np.zeros((4, 4), dtype=int), r"F: expected an \(m, 3\) array"),
    ([[0, 0, np.nan]] + TETRA_V[1:], TETRA_F, "vertex 0 has a non-finite coordinate"),
    ([[0, 0, np.inf]] + TETRA_V[1:], TETRA_F, "vertex 0 has a non-finite coordinate"),
    (TETRA_V, [[0, 1, 4]], "face 0 corner 2: vertex 4 is out of range"),
    (TETRA_V, [[0, -1, 2]], "face 0 corner 1: vertex -1 is out of range"),
    (TETRA_V, [[0, 1, 2.5]], "face 0 corner 2: 2.5 is not a whole number"),
    (TETRA_V, [[0, 1, np.nan]], "is not a whole number"),
    (TETRA_V, np.array([[True, False, True]]), "expected integer vertex indices"),
    ("abc", TETRA_F, "V: expected"),
])
def test_bad_input_is_refused(V, F, message):
    with pytest.raises(ValueError, match=message):
        trilab.Mesh(V, F)


def test_vertex_property_selection(cli, meshes, tmp_path):
    from conftest import run_cli
    out = str(tmp_path / "sel.ply")
    code, _, err = run_cli(cli, "select", meshes["default"], out, "--region", "sphere:0,0,1,0.8")
    assert code == 0, err
    m = trilab.load(out)
    sel = m.vertex_property("selection")
    assert np.array_equal(m.vertex_property("v:selection"), sel)
    inside = np.linalg.norm(m.V - [0, 0, 1], axis=1) <= 0.8
    assert sel.shape == (m.n_vertices,) and inside.any() and not inside.all()
    assert np.array_equal(sel > 0, inside)
    with pytest.raises(KeyError, match="no vertex property 'nothing'"):
        m.vertex_property("nothing")


def test_geodesic_matches_the_cli_distance(cli, meshes, tmp_path):
    from conftest import run_cli
    m = trilab.load(meshes["default"])
    d = m.geodesic([0])
    out = str(tmp_path / "g.ply")
    code, _, err = run_cli(cli, "geodesic", meshes["default"], out, "--from", "0")
    assert code == 0, err
    expected = trilab.load(out).vertex_property("distance")
    assert d.shape == (m.n_vertices,) and d[0] == 0
    assert np.allclose(d, expected, rtol=1e-12, atol=1e-12)
    with pytest.raises(ValueError, match="out of range"):
        m.geodesic([m.n_vertices])


def test_spectrum_eigenpairs(meshes):
    m = trilab.load(meshes["default"])
    values, vectors = m.spectrum(8, operator="curvature-flow", mass="barycentric")
    assert values.shape == (8,) and vectors.shape == (m.n_vertices, 8)
    assert np.all(np.diff(values) >= -1e-9) and abs(values[0]) < 1e-8
    # Independent check through the sparse matrices: K e = lambda S e.
    pytest.importorskip("scipy")
    K = m.laplacian("curvature-flow", mass="barycentric")
    assert K.shape == (m.n_vertices, m.n_vertices)
    assert abs(K - K.T).max() < 1e-12
    Ke = K @ vectors
    ratio = (vectors * Ke).sum(axis=0)  # e^T K e = lambda (S-orthonormal e)
    assert np.allclose(ratio, values, rtol=1e-6, atol=1e-8)


def test_spectrum_operation_reports_eigenvalues(meshes):
    m = trilab.load(meshes["default"])
    r = m.spectrum_op(k=10)
    values, _ = m.spectrum(10)
    assert np.allclose(r.report["eigenvalues"], np.maximum(values, 0), rtol=1e-8, atol=1e-10)


def test_inspect_matches_the_cli(cli, meshes):
    from conftest import run_cli
    m = trilab.load(meshes["torus"])
    for kind, i in (("vertex", 5), ("edge", 7), ("face", 3)):
        fields = m.inspect(**{kind: i})
        code, out, err = run_cli(cli, "inspect", meshes["torus"], "--" + kind, str(i), "--json")
        assert code == 0, err
        expected = json.loads(out)
        assert fields, kind
        for key, value in fields.items():
            assert expected[key] == value, (kind, key)
    with pytest.raises(ValueError, match="out of range"):
        m.inspect(vertex=m.n_vertices)
    with pytest.raises(ValueError, match="exactly one"):
        m.inspect(vertex=1, face=2)


def test_coloring_matches_the_inspector(meshes):
    m = trilab.load(meshes["torus"])
    mean = m.coloring("mean")
    gauss = m.coloring("gaussian")
    assert mean.shape == gauss.shape == (m.n_vertices,)
    for i in (0, 17, 101):
        fields = m.inspect(vertex=i)
        assert np.isclose(mean[i], fields["mean_curvature"], rtol=1e-9, atol=1e-12)
        assert np.isclose(gauss[i], fields["gaussian_curvature"], rtol=1e-9, atol=1e-12)
    with pytest.raises(ValueError):
        m.coloring("nothing")
    with pytest.raises(ValueError, match="no value per vertex"):
        m.coloring("normal")
