"""NaN and ±inf in coordinates: every entry point of rbfsurf refuses them with an RbfError naming
the argument and the row, queries included (rbfsurf._checks says why).

`ENTRY_POINTS` lists every public callable that takes coordinates, with a call that puts a bad
number in each such argument; `NO_COORDINATES` lists every other public callable. A new public
callable must go in one of them, or `test_every_public_callable_is_listed` fails.
"""

import inspect
import re

import numpy as np
import pytest

import rbfsurf
from conftest import sphere_points

TETRA_V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [0.3, 0.3, 0.3]], float)
TETRA_F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
ROW = 3


def _sphere_model():
    p = sphere_points(40)
    return rbfsurf.from_oriented_points(p, p)


def _interpolator():
    y = np.random.default_rng(0).uniform(-1, 1, (30, 3))
    return rbfsurf.RBFInterpolator(y, y[:, 0] + y[:, 1] ** 2)


def _queries():
    return np.random.default_rng(1).uniform(-1, 1, (10, 3))


def _cloud():
    return sphere_points(40)


# entry point -> {name in the message: call with the bad array in that argument}
ENTRY_POINTS = {
    "RBFInterpolator": {
        "y": lambda a: rbfsurf.RBFInterpolator(a, np.arange(len(a), dtype=float)),
    },
    "RBFInterpolator.__call__": {"x": lambda a: _interpolator()(a)},
    "RBFInterpolator.gradient": {"x": lambda a: _interpolator().gradient(a)},
    "fit": {
        "boundary": lambda a: rbfsurf.fit(boundary=a, interior=[[0.0, 0.0, 0.0]]),
        "interior": lambda a: rbfsurf.fit(boundary=_cloud(), interior=a * 0.1),
        "exterior": lambda a: rbfsurf.fit(boundary=_cloud(), exterior=(a * 3, -1.0)),
        "normals": lambda a: rbfsurf.fit(normals=(a, _cloud())),
        "normal vectors": lambda a: rbfsurf.fit(normals=(_cloud(), a)),
    },
    "from_oriented_points": {
        "points": lambda a: rbfsurf.from_oriented_points(a, _cloud()),
        "normals": lambda a: rbfsurf.from_oriented_points(_cloud(), a),
    },
    "convert": {"vertices": lambda a: rbfsurf.convert(a[: len(TETRA_V)], TETRA_F)},
    "voxelize": {"vertices": lambda a: rbfsurf.voxelize(a[: len(TETRA_V)], TETRA_F)},
    "signed_distance": {
        "vertices": lambda a: rbfsurf.signed_distance(a[: len(TETRA_V)], TETRA_F),
    },
    "write_mesh": {
        "vertices": lambda a: rbfsurf.write_mesh("/nonexistent/never.obj", a[: len(TETRA_V)], TETRA_F),
    },
    "reconstruct": {
        "points": lambda a: rbfsurf.reconstruct(a),
        "normals": lambda a: rbfsurf.reconstruct(_cloud(), a),
    },
    "Model.__call__": {"x": lambda a: _sphere_model()(a)},
    "Model.gradient": {"x": lambda a: _sphere_model().gradient(a)},
}

# The bad number's place in a text command (the session's commands are text).
SESSION_LINES = {
    "Session.run": lambda s, bad: s.run(f"add 0 {bad} 1.3"),
    "Session.run_script": lambda s, bad: s.run_script(f"add 0 0 1.3\nadd 0 {bad} 1.3\n"),
}

NO_COORDINATES = {
    # Files and text: their readers check what they read (tests in test_files.py).
    "load", "loads", "read_mesh", "Model.from_json", "Model.to_json", "Model.save",
    # Settings only.
    "Model.polygonize", "Model.render", "Session", "Session.model",
    # Exceptions and results.
    "RbfError", "RbfFileNotFoundError", "VoxelGrid", "Model",
}


def _arguments(label):
    """A valid array for the argument `label` of an entry point."""
    return _queries() if label in ("x", "y") else _cloud() if label != "vertices" else TETRA_V


CASES = [
    (entry, label, bad)
    for entry, arguments in ENTRY_POINTS.items()
    for label in arguments
    for bad in (np.nan, np.inf, -np.inf)
]


@pytest.mark.parametrize("entry,label,bad", CASES, ids=lambda v: str(v))
def test_a_bad_number_is_named_by_argument_and_row(entry, label, bad):
    a = np.array(_arguments(label), dtype=float)
    a[ROW, 1] = bad
    with pytest.raises(rbfsurf.RbfError, match=re.escape(f"{label}[{ROW}] = [")) as e:
        ENTRY_POINTS[entry][label](a)
    assert "finite" in str(e.value)


@pytest.mark.parametrize("entry", sorted(SESSION_LINES))
@pytest.mark.parametrize("bad", ["nan", "inf", "-inf", "NaN"])
def test_a_bad_number_in_a_command_is_named(entry, bad):
    session = rbfsurf.Session()
    with pytest.raises(rbfsurf.RbfError, match=re.escape(bad)) as e:
        SESSION_LINES[entry](session, bad)
    if entry == "Session.run_script":
        # As documented: the lines before the refused one stay applied, and its number is named.
        assert str(e.value).startswith("line 2: ")
        assert len(session) == 13
    else:
        assert len(session) == 12


def test_nothing_is_kept_from_a_refused_call():
    m = _sphere_model()
    x = _queries()
    before = m(x)
    bad = x.copy()
    bad[ROW, 2] = np.nan
    with pytest.raises(rbfsurf.RbfError):
        m(bad)
    assert np.array_equal(m(x), before)


def _public_callables():
    inherited = set(dir(tuple)) | set(dir(Exception)) | set(dir(object))
    for name in rbfsurf.__all__:
        obj = getattr(rbfsurf, name)
        if not callable(obj):
            continue
        yield name
        if inspect.isclass(obj):
            for member in dir(obj):
                if member not in inherited and not member.startswith("_"):
                    if callable(getattr(obj, member)):
                        yield f"{name}.{member}"
            if "__call__" in vars(obj):
                yield f"{name}.__call__"


def test_every_public_callable_is_listed():
    listed = set(ENTRY_POINTS) | set(SESSION_LINES) | NO_COORDINATES
    missing = sorted(set(_public_callables()) - listed)
    assert not missing, f"say whether these take coordinates: {missing}"


def test_smoothing_per_point_is_named_too():
    y = np.random.default_rng(0).uniform(size=(20, 3))
    for bad in (np.nan, np.inf, -1.0):
        smoothing = np.ones(20)
        smoothing[17] = bad
        with pytest.raises(rbfsurf.RbfError, match=r"smoothing\[17\] = "):
            rbfsurf.RBFInterpolator(y, np.ones(20), smoothing=smoothing)
