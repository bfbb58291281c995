"""Model files: saved, loaded, pickled, and read by the rbf command."""

import pickle
import subprocess

import numpy as np

import rbfsurf
from conftest import sphere_points


def test_save_load_round_trip_and_pickle(tmp_path):
    p = sphere_points(150)
    m = rbfsurf.from_oriented_points(p, p, smoothing=1e-8)
    path = tmp_path / "sphere.json"
    m.save(path)
    loaded = rbfsurf.load(path)
    x = np.random.default_rng(0).uniform(-1.5, 1.5, (500, 3))
    assert np.array_equal(loaded(x), m(x))
    assert loaded.report == m.report
    assert rbfsurf.loads(m.to_json()).to_json() == m.to_json()
    assert np.array_equal(pickle.loads(pickle.dumps(m))(x), m(x))
    assert "3D, cubic kernel, 300 centres" in repr(m)


def test_the_rbf_command_reads_a_saved_model(tmp_path, rbf_binary):
    p = sphere_points(150)
    path = tmp_path / "sphere.json"
    rbfsurf.from_oriented_points(p, p).save(path)
    info = subprocess.run([rbf_binary, "info", str(path)], capture_output=True, text=True)
    assert info.returncode == 0, info.stderr
    assert "300" in info.stdout and "cubic" in info.stdout, info.stdout
    # And the other way: a model written by `rbf fit` loads here.
    points = tmp_path / "tet.txt"
    points.write_text("1 1 1 0\n1 -1 -1 0\n-1 1 -1 0\n-1 -1 1 0\n0 0 0 1\n")
    out = tmp_path / "tet.json"
    fit = subprocess.run([rbf_binary, "fit", str(points), "-o", str(out), "-q"])
    assert fit.returncode == 0
    assert abs(rbfsurf.load(out)([[0, 0, 0]])[0] - 1) < 1e-9
