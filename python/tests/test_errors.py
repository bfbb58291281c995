"""Bad input raises RbfError (a ValueError) naming the culprit; nothing panics."""

import numpy as np
import pytest

import rbfsurf
from conftest import sphere_points


def test_nan_names_the_constraint():
    p = sphere_points(50)
    p[7, 1] = np.nan
    with pytest.raises(rbfsurf.RbfError, match=r"points\[7\] = \[.*nan.*\]: every coordinate must be a finite"):
        rbfsurf.from_oriented_points(p, p)
    y = np.random.default_rng(0).uniform(size=(20, 3))
    d = np.ones(20)
    d[3] = np.inf
    with pytest.raises(ValueError, match="row 3"):
        rbfsurf.RBFInterpolator(y, d)
    y[5, 0] = np.nan
    with pytest.raises(ValueError, match=r"y\[5\] = \[nan, "):
        rbfsurf.RBFInterpolator(y, np.ones(20))


def test_nan_in_the_data_is_refused_not_read_as_zero():
    y = np.random.default_rng(0).uniform(size=(20, 3))
    d = np.ones((20, 2))
    d[3, 1] = np.nan
    with pytest.raises(rbfsurf.RbfError, match="d: row 3 is not a finite number"):
        rbfsurf.RBFInterpolator(y, d)
    with pytest.raises(rbfsurf.RbfError, match="exterior\\[1\\]"):
        rbfsurf.fit(boundary=y[:10], exterior=(y[10:12], [-1.0, np.nan]))


def test_errors_name_the_users_argument_and_row():
    p = np.random.default_rng(4).uniform(size=(20, 3))
    p[15] = p[2]
    with pytest.raises(rbfsurf.RbfError, match=r"boundary\[2\] and normals\[5\]"):
        rbfsurf.fit(boundary=p[:10], normals=(p[10:], p[10:]), interior=[[0.5, 0.5, 0.5]])
    with pytest.raises(rbfsurf.RbfError, match=r"interior\[1\] \(interior\): value = -1"):
        rbfsurf.fit(boundary=np.eye(3), interior=([[0, 0, 0], [0.1, 0, 0]], [1, -1]))


def test_duplicate_points_are_named():
    y = np.random.default_rng(1).uniform(size=(30, 2))
    y[12] = y[4]
    with pytest.raises(rbfsurf.RbfError, match=r"4.*12|12.*4"):
        rbfsurf.RBFInterpolator(y, np.arange(30.0))


def test_mismatched_shapes():
    y = np.zeros((10, 3))
    with pytest.raises(ValueError, match="d must have 10 rows"):
        rbfsurf.RBFInterpolator(y, np.ones(9))
    f = rbfsurf.RBFInterpolator(np.random.default_rng(2).uniform(size=(10, 3)), np.arange(10.0))
    with pytest.raises(ValueError, match=r"x must have shape \(m, 3\)"):
        f(np.zeros((4, 2)))
    with pytest.raises(ValueError, match="2 or 3 dimensions"):
        rbfsurf.RBFInterpolator(np.zeros((10, 4)), np.ones(10))
    with pytest.raises(ValueError, match=r"shape \(n, 2\) or \(n, 3\)"):
        rbfsurf.fit(boundary=np.zeros((10, 4)))
    with pytest.raises(ValueError, match="normals"):
        rbfsurf.from_oriented_points(np.zeros((5, 3)), np.zeros((4, 3)))
    with pytest.raises(ValueError, match=r"smoothing must be a number or have shape \(10,\)"):
        rbfsurf.RBFInterpolator(np.zeros((10, 3)), np.ones(10), smoothing=np.ones(3))
    with pytest.raises(ValueError, match=r"x must have shape \(n, 3\)"):
        f.models[0](np.zeros(3))
    with pytest.raises(ValueError, match="uses vertex 9"):
        rbfsurf.voxelize(np.zeros((4, 3)), [[0, 1, 9]])


def test_coplanar_points_are_refused():
    rng = np.random.default_rng(3)
    y = np.c_[rng.uniform(size=(40, 2)), np.full(40, 0.5)]
    with pytest.raises(rbfsurf.RbfError, match="plane"):
        rbfsurf.RBFInterpolator(y, rng.uniform(size=40))


def test_a_missing_or_bad_file(tmp_path):
    with pytest.raises(FileNotFoundError, match="no-such.json"):
        rbfsurf.load(tmp_path / "no-such.json")
    with pytest.raises(ValueError):
        rbfsurf.load(tmp_path / "no-such.json")
    bad = tmp_path / "bad.json"
    bad.write_text('{"format": "something else"}')
    with pytest.raises(rbfsurf.RbfError, match="bad.json: .*format"):
        rbfsurf.load(bad)
    with pytest.raises(FileNotFoundError, match="no-mesh.obj"):
        rbfsurf.read_mesh(tmp_path / "no-mesh.obj")
    with pytest.raises(rbfsurf.RbfError, match="is a directory|Is a directory"):
        rbfsurf.load(tmp_path)


def box():
    v = [[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)]
    f = [[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
         [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]]
    return v, f


def test_bad_options_are_value_errors_not_panics():
    p = sphere_points(30)
    m = rbfsurf.from_oriented_points(p, p)
    for call in [
        lambda: rbfsurf.RBFInterpolator(p, p[:, 0], kernel="gaussian"),
        lambda: rbfsurf.RBFInterpolator(p, p[:, 0], degree=2),
        lambda: rbfsurf.from_oriented_points(p, p, method="magic"),
        lambda: rbfsurf.from_oriented_points(p, p, offset=-1.0),
        lambda: rbfsurf.fit(),
        lambda: rbfsurf.fit(boundary=[[0, 0, 0]]),
        lambda: rbfsurf.fit(interior=([[0, 0, 0]], [-1.0]), boundary=p),
        lambda: rbfsurf.fit(boundary=p, smoothing=-1.0),
        lambda: m.polygonize(0),
        lambda: m.polygonize(32, method="marching"),
        lambda: m.render(0, 10),
        lambda: m.render(10, 10, samples=0),
        lambda: m(["a", "b", "c"]),
        lambda: m([[1j, 0, 0]]),
        lambda: m.polygonize(-1),
        lambda: m.render(-5, 10),
        lambda: rbfsurf.voxelize(*box(), resolution=-1),
        lambda: rbfsurf.voxelize(*box(), supersampling=10**6),
        lambda: rbfsurf.voxelize(*box(), supersampling=0),
        lambda: rbfsurf.voxelize(box()[0], [[0, 1, 2.5]]),
        lambda: rbfsurf.convert(*box(), resolution=-8),
        lambda: rbfsurf.convert(*box(), max_iterations=-1),
        lambda: rbfsurf.Session(rbfsurf.from_oriented_points(p, p, smoothing=0.1)),
        lambda: rbfsurf.Session(rbfsurf.from_oriented_points(p, p, kernel="linear")),
        lambda: rbfsurf.convert(np.zeros((3, 3)), [[0, 1, 2]], method="other"),
        lambda: rbfsurf.reconstruct(p, max_centres=5),
        lambda: rbfsurf.reconstruct(p, max_centres=-1),
        lambda: rbfsurf.Session(rbfsurf.RBFInterpolator(p[:, :2], p[:, 2]).models[0]),
    ]:
        with pytest.raises(ValueError):
            call()
    with pytest.raises(NotImplementedError):
        rbfsurf.RBFInterpolator(p, p[:, 0], neighbors=10)


@pytest.mark.parametrize("bad", [0.0, -1e-3, float("nan"), float("inf"), 1e-20])
def test_an_impossible_accuracy_names_max_residual(bad):
    p = sphere_points(50)
    with pytest.raises(rbfsurf.RbfError, match=r"max_residual must be a finite fraction of max\|h\| ≥ 1e-15"):
        rbfsurf.from_oriented_points(p, p, max_residual=bad)
    with pytest.raises(rbfsurf.RbfError, match="max_residual"):
        rbfsurf.RBFInterpolator(p, np.ones(50), max_residual=bad)
