"""Operations from Python against trilab-cli: the same files byte for byte, the same report,
the same errors; the input is never changed; Ctrl+C and progress callbacks stop a run."""
import json
import os
import re
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import trilab
from conftest import run_cli

# (operation, keyword options, the same on the command line, mesh names)
CASES = [
    ("smooth", dict(operator="curvature-flow", integration="implicit", step=5),
     ["--operator", "curvature-flow", "--integration", "implicit", "--step", "5"],
     ["default", "grid"]),
    ("smooth", dict(operator="taubin", iterations=3), ["--operator", "taubin", "--iterations", "3"],
     ["torus"]),
    ("subdivide", dict(scheme="loop", iterations=2), ["--scheme", "loop", "--iterations", "2"],
     ["default", "grid"]),
    ("subdivide", dict(scheme="sqrt3"), ["--scheme", "sqrt3"], ["torus"]),
    ("noise", dict(amount=2.5, seed=7), ["--amount", "2.5", "--seed", "7"], ["default"]),
    ("decimate", dict(percent=50), ["--percent", "50"], ["default", "torus"]),
    ("denoise", dict(normal_iterations=3, vertex_iterations=2),
     ["--normal-iterations", "3", "--vertex-iterations", "2"], ["default"]),
    ("remesh", dict(iterations=2), ["--iterations", "2"], ["grid"]),
    ("fill-holes", dict(max_edges=1000), ["--max-edges", "1000"], ["grid"]),
    ("flip", dict(), [], ["default"]),
    ("weld", dict(), [], ["grid"]),
    ("remove-components", dict(min_faces=10), ["--min-faces", "10"], ["torus"]),
    ("features", dict(), [], ["torus"]),
    ("sharpen", dict(edge=5, sharpness=2.0), ["--edge", "5", "--sharpness", "2"], ["torus"]),
    ("spectrum", dict(k=12, band=(0, 5)), ["--k", "12", "--band", "0:5"], ["default"]),
    ("smooth", dict(step=0.5, region="sphere:0,0,1,0.8"),
     ["--step", "0.5", "--region", "sphere:0,0,1,0.8"], ["default"]),
]


def without_times(report):
    """The report with its timings (which differ run to run) taken out: keys ending in "ms",
    "N ms" in the report's lines."""
    out = {k: v for k, v in report.items() if not k.endswith("ms")}
    out["report"] = [re.sub(r"[0-9.]+ ?ms\b", "T ms", line) for line in report["report"]]
    return out


def method_of(mesh, name):
    method = name.replace("-", "_")
    if method == "spectrum":
        method = "spectrum_op"  # Mesh.spectrum is the eigenpairs
    return getattr(mesh, method)


@pytest.mark.parametrize("op,kwargs,args,names", CASES)
def test_same_file_and_report_as_cli(cli, meshes, tmp_path, op, kwargs, args, names):
    for name in names:
        src = meshes[name]
        cli_out = str(tmp_path / ("cli_" + name + ".ply"))
        py_out = str(tmp_path / ("py_" + name + ".ply"))
        code, stdout, stderr = run_cli(cli, op, *args, src, cli_out, "--json")
        assert code == 0, stderr
        expected = json.loads(stdout)
        m = trilab.load(src)
        V0 = m.V.copy()
        r = method_of(m, op)(**kwargs)
        r.save(py_out)
        with open(cli_out, "rb") as a, open(py_out, "rb") as b:
            assert a.read() == b.read(), f"{op} {kwargs} on {name}: files differ"
        for key in ("input", "output", "ms"):
            expected.pop(key)
        assert without_times(r.report) == without_times(expected)
        assert np.array_equal(m.V, V0), "the input changed"
        assert m.report is None and m.ms is None and m.run_ms is None
        assert 0 <= r.ms <= r.run_ms
        assert r.n_faces == expected["faces"]


def test_every_operation_is_compared_with_the_cli():
    assert {case[0] for case in CASES} == set(trilab.operations())


def test_every_operation_is_a_method():
    m = trilab.Mesh(np.eye(3), [[0, 1, 2]])
    for name in trilab.operations():
        method = name.replace("-", "_")
        assert callable(getattr(m, method if method != "spectrum" else "spectrum_op")), name


def test_bad_option_raises_the_cli_message(cli, meshes):
    m = trilab.load(meshes["default"])
    for kwargs, args in [
        (dict(step="abc"), ["--step", "abc"]),
        (dict(operator="taubin", step=2), ["--operator", "taubin", "--step", "2"]),
        (dict(bogus=1), ["--bogus", "1"]),
        (dict(iterations=0), ["--iterations", "0"]),
    ]:
        code, _, stderr = run_cli(cli, "smooth", *args, meshes["default"], os.devnull)
        assert code != 0
        message = stderr.strip().removeprefix("trilab-cli smooth: ")
        with pytest.raises(ValueError) as e:
            m.smooth(**kwargs)
        assert str(e.value).removeprefix("smooth: ") == message


def test_region_as_weights_matches_spec(meshes):
    m = trilab.load(meshes["default"])
    w = np.zeros(m.n_vertices, dtype=np.float32)
    w[m.V[:, 2] > 0.5] = 1.0
    a = m.smooth(step=0.5, iterations=3, region=w)
    moved = np.linalg.norm(a.V - m.V, axis=1) > 0
    assert moved.any() and not moved[w == 0].any()
    with pytest.raises(ValueError, match="one weight per vertex"):
        m.smooth(region=w[:-1])
    with pytest.raises(ValueError, match="does not work on a region"):
        m.features(region=w)


def test_progress_callback_and_its_exception_stop_the_run(meshes):
    m = trilab.load(meshes["default"])
    calls = []
    m.smooth(iterations=50, progress=lambda f, stage: calls.append(f))
    assert calls, "the progress callback was never called"

    class Stop(Exception):
        pass

    def stop(fraction, stage):
        raise Stop()

    with pytest.raises(Stop):
        m.smooth(iterations=10000, progress=stop)


CTRL_C_SCRIPT = """
import sys, trilab
m = trilab.load(sys.argv[1]).subdivide(iterations=2)
print("running", flush=True)
try:
    m.smooth(iterations=10000)
    print("finished")
except KeyboardInterrupt:
    print("interrupted", m.smooth(iterations=1).n_faces == m.n_faces)
"""


def test_ctrl_c_cancels_a_running_operation(meshes):
    # In a process of its own: SIGINT while the smoothing runs with the GIL released.
    p = subprocess.Popen([sys.executable, "-c", CTRL_C_SCRIPT, meshes["default"]],
                         stdout=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "running"
    time.sleep(0.3)
    p.send_signal(signal.SIGINT)
    out, _ = p.communicate(timeout=20)
    assert out.strip() == "interrupted True"
    assert p.returncode == 0


def test_gil_is_released(meshes):
    m = trilab.load(meshes["default"]).subdivide(iterations=2)
    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(1)
            done.wait(0.005)

    t = threading.Thread(target=tick)
    t.start()
    m.smooth(iterations=300)
    done.set()
    t.join()
    assert len(ticks) > 3


def test_keep_partial_and_stopped_early(cli, meshes):
    # A diverging explicit step: the CLI exits 4, Python raises StoppedEarly.
    m = trilab.load(meshes["default"])
    code, _, _ = run_cli(cli, "smooth", "--operator", "curvature-flow", "--step", "50",
                         "--iterations", "50", meshes["default"], os.devnull)
    if code != 4:
        pytest.skip("this run does not stop early here")
    with pytest.raises(trilab.StoppedEarly):
        m.smooth(operator="curvature-flow", step=50, iterations=50)
