"""RBFInterpolator agrees with scipy's on the problems both solve."""

import numpy as np
import pytest
from scipy.interpolate import RBFInterpolator as ScipyRBF

import rbfsurf


def data(n, dim, seed):
    rng = np.random.default_rng(seed)
    y = rng.uniform(-1, 1, (n, dim)) * 1.7 + 0.4
    d = np.sin(2 * y[:, 0]) + y[:, 1] ** 2 - 0.5
    x = rng.uniform(-1.5, 2.3, (300, dim))
    return y, d, x


def relative(a, b):
    return np.abs(a - b).max() / np.abs(b).max()


@pytest.mark.parametrize("kernel", ["cubic", "linear", "thin_plate_spline"])
@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("smoothing", [0.0, 1e-3, 0.5])
def test_values_agree_with_scipy(kernel, dim, smoothing):
    y, d, x = data(250, dim, seed=dim * 10 + len(kernel))
    ours = rbfsurf.RBFInterpolator(y, d, kernel=kernel, smoothing=smoothing)
    # scipy's default degree for the linear kernel is 0; rbf's polynomial is always linear.
    theirs = ScipyRBF(y, d, kernel=kernel, smoothing=smoothing, degree=1)
    assert relative(ours(x), theirs(x)) < 1e-8
    assert relative(ours(y), theirs(y)) < 1e-8


def test_smoothing_per_point_epsilon_and_vector_values():
    y, d, x = data(200, 3, seed=5)
    rng = np.random.default_rng(6)
    s = rng.uniform(0, 1e-2, len(y))
    dd = np.stack([d, np.cos(y[:, 2]), y[:, 0] * y[:, 1]], axis=1).reshape(len(y), 3, 1)
    ours = rbfsurf.RBFInterpolator(y, dd, kernel="cubic", smoothing=s, epsilon=2.0)
    theirs = ScipyRBF(y, dd, kernel="cubic", smoothing=s, epsilon=2.0)
    a, b = ours(x), theirs(x)
    assert a.shape == b.shape == (len(x), 3, 1)
    assert relative(a, b) < 1e-8


@pytest.mark.parametrize(
    "convert",
    [
        lambda a: a.astype(np.float32),
        np.asfortranarray,
        lambda a: a.tolist(),
        lambda a: np.repeat(a, 2, axis=0)[::2],  # a strided view
    ],
    ids=["float32", "fortran", "list", "strided"],
)
def test_inputs_of_other_dtypes_and_orders(convert):
    y, d, x = data(150, 3, seed=9)
    as64 = lambda a: np.asarray(convert(a), dtype=np.float64)  # noqa: E731
    theirs = ScipyRBF(as64(y), as64(d), kernel="cubic")
    ours = rbfsurf.RBFInterpolator(convert(y), convert(d), kernel="cubic")
    expected = theirs(as64(x))
    assert relative(ours(convert(x)), expected) < 1e-8


def test_columns_of_zeros_interpolate_to_zero():
    y, d, x = data(60, 2, seed=3)
    dd = np.stack([np.zeros_like(d), d], axis=1)
    ours = rbfsurf.RBFInterpolator(y, dd)
    theirs = ScipyRBF(y, dd, kernel="cubic")
    assert np.array_equal(ours(x)[:, 0], np.zeros(len(x)))
    assert relative(ours(x), theirs(x)) < 1e-8
    assert ours.gradient(x).shape == (len(x), 2, 2)


@pytest.mark.parametrize("kernel", ["cubic", "linear", "thin_plate_spline"])
@pytest.mark.parametrize("dim", [2, 3])
def test_gradients_match_central_differences(kernel, dim):
    y, d, x = data(120, dim, seed=11)
    f = rbfsurf.RBFInterpolator(y, d, kernel=kernel)
    x = x[:50]
    g = f.gradient(x)
    assert g.shape == (len(x), dim)
    h = 1e-6
    for k in range(dim):
        e = np.zeros(dim)
        e[k] = h
        fd = (f(x + e) - f(x - e)) / (2 * h)
        assert np.abs(fd - g[:, k]).max() < 1e-5 * (1 + np.abs(g).max())


def test_models_save_like_any_model(tmp_path):
    y, d, x = data(100, 3, seed=2)
    f = rbfsurf.RBFInterpolator(y, d)
    path = tmp_path / "scattered.json"
    f.models[0].save(path)
    assert np.array_equal(rbfsurf.load(path)(x), f(x))
