"""The checks every entry point makes of the arrays it is given, in one place.

Coordinates (points, normals, vertices, query points) must be finite: a NaN or an infinity in
any of them raises ``RbfError`` naming the argument and the first bad row, like the ``rbf``
command. Queries are refused too, rather than answered with NaN as scipy does: a NaN query is
almost always a bug upstream, and a silent NaN travels far before anyone sees it.
"""

from __future__ import annotations

from typing import Any, Iterable

import numpy as np

from ._native import RbfError


def floats(x: Any, name: str) -> np.ndarray:
    """``x`` as a float64 array (no copy when it is one), refusing complex numbers and what
    cannot be read as numbers."""
    if np.iscomplexobj(x):
        raise RbfError(f"{name}: complex numbers are not taken")
    try:
        return np.asarray(x, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise RbfError(f"{name}: cannot be read as an array of float64: {e}") from None


def points(x: Any, name: str, dims: Iterable[int] = (2, 3)) -> np.ndarray:
    """``x`` as an (n, dim) float64 array of finite numbers, dim in ``dims``.

    >>> points([[0, 1, 2]], "x").dtype
    dtype('float64')
    >>> try:
    ...     points([[0, float("nan"), 2]], "x")
    ... except ValueError as e:
    ...     print(e)
    x[0] = [0.0, nan, 2.0]: every coordinate must be a finite number
    """
    a = floats(x, name)
    dims = tuple(dims)
    if a.ndim != 2 or a.shape[1] not in dims:
        wanted = " or ".join(f"(n, {d})" for d in dims)
        raise RbfError(f"{name} must have shape {wanted}, not {a.shape}")
    finite_rows(a, name)
    return a


def finite_rows(a: np.ndarray, name: str) -> None:
    """Refuses the first row of a 2-dimensional array with a NaN or an infinity."""
    bad = np.flatnonzero(~np.isfinite(a).all(axis=1))
    if len(bad):
        i = int(bad[0])
        row = ", ".join(repr(float(v)) for v in a[i])
        raise RbfError(f"{name}[{i}] = [{row}]: every coordinate must be a finite number")
