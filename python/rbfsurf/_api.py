"""Implicit surfaces from constraints and meshes; model files; voxels."""

from __future__ import annotations

import os
import re
from typing import Any, NamedTuple, Optional, Tuple, Union

import numpy as np

from . import _checks, _native
from ._native import Model, RbfError

ArrayLike = Any

_BOUNDARY, _INTERIOR, _EXTERIOR, _NORMAL = 0, 1, 2, 3


class RbfFileNotFoundError(RbfError, FileNotFoundError):
    """A model or mesh file that does not exist (both an ``RbfError`` and a
    ``FileNotFoundError``)."""


def _points_and_values(arg: Any, default: float, name: str) -> Tuple[np.ndarray, np.ndarray]:
    """``points`` or ``(points, values)`` -> arrays; values default to ``default``."""
    if isinstance(arg, tuple):
        if len(arg) != 2:
            raise RbfError(f"{name} must be points or a pair (points, values)")
        points = _checks.points(arg[0], name)
        try:
            values = np.broadcast_to(_checks.floats(arg[1], f"{name} values"), (len(points),))
        except ValueError:
            raise RbfError(f"{name}: give one value or one per point ({len(points)})") from None
    else:
        points = _checks.points(arg, name)
        values = np.full(len(points), default)
    return points, values


def fit(
    boundary: Optional[ArrayLike] = None,
    interior: Optional[Union[ArrayLike, Tuple[ArrayLike, ArrayLike]]] = None,
    exterior: Optional[Union[ArrayLike, Tuple[ArrayLike, ArrayLike]]] = None,
    normals: Optional[Tuple[ArrayLike, ArrayLike]] = None,
    *,
    kernel: Optional[str] = None,
    smoothing: float = 0.0,
    offset: Optional[float] = None,
    method: str = "auto",
    max_residual: Optional[float] = None,
    allow_unconverged: bool = False,
) -> Model:
    """Fits an implicit function to constraints of every kind (Turk & O'Brien 2002, §4).

    f is 0 on the surface, positive inside and negative outside:

    - ``boundary``: (n, dim) points on the surface (f = 0);
    - ``interior``: points inside, or ``(points, values)`` with values > 0 (default 1);
    - ``exterior``: points outside, or ``(points, values)`` with values < 0 (default -1);
    - ``normals``: ``(points, normals)``, points on the surface with outward normals
      (f = 0 there and f = 1 at ``offset`` inside, against the normal).

    ``kernel``: ``"cubic"`` (r³, default in 3D), ``"thin_plate_spline"`` (default in 2D) or
    ``"linear"``; ``smoothing``: λ ≥ 0 (0 interpolates exactly); ``offset``: the normal
    constraints' offset distance (default: 1% of the box's longest side); ``method``:
    ``"auto"`` (dense below 5000 rows, iterative above), ``"dense"`` or ``"fast"``;
    ``max_residual``: the largest accepted max|f(cᵢ) − hᵢ| / max|hᵢ| (by default 1e-6 by the
    dense method and 1e-5 by the iterative one; a stall at the rounding floor of strongly
    cancelling weights is accepted unless it is given).

    >>> import rbfsurf
    >>> m = rbfsurf.fit(boundary=[[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1]],
    ...                 interior=[[0, 0, 0]], exterior=([[3, 3, 3]], -2.0))
    >>> round(float(m([[0, 0, 0]])[0]), 9), round(float(m([[3, 3, 3]])[0]), 9)
    (1.0, -2.0)
    """
    parts = []
    if boundary is not None:
        p = _checks.points(boundary, "boundary")
        parts.append((p, np.zeros(len(p)), _BOUNDARY, None))
    if interior is not None:
        p, v = _points_and_values(interior, 1.0, "interior")
        parts.append((p, v, _INTERIOR, None))
    if exterior is not None:
        p, v = _points_and_values(exterior, -1.0, "exterior")
        parts.append((p, v, _EXTERIOR, None))
    if normals is not None:
        if not (isinstance(normals, tuple) and len(normals) == 2):
            raise RbfError("normals must be a pair (points, normals)")
        p = _checks.floats(normals[0], "normals")
        n = _checks.floats(normals[1], "normals")
        if p.ndim != 2 or n.shape != p.shape:
            raise RbfError(
                f"normals: points and normals must both have shape (n, dim), not {p.shape} and {n.shape}"
            )
        p = _checks.points(p, "normals")
        _checks.finite_rows(n, "normal vectors")
        parts.append((p, np.ones(len(p)), _NORMAL, n))
    if not parts:
        raise RbfError("no constraints: give boundary, interior, exterior or normals")
    dims = {p.shape[1] for p, _, _, _ in parts}
    if len(dims) != 1:
        raise RbfError(f"the constraints mix dimensions {sorted(dims)}")
    points = np.concatenate([p for p, _, _, _ in parts])
    values = np.concatenate([v for _, v, _, _ in parts])
    kinds = np.concatenate([np.full(len(p), k, dtype=np.float64) for p, _, k, _ in parts])
    all_normals = None
    if normals is not None:
        all_normals = np.concatenate(
            [n if n is not None else np.zeros_like(p) for p, _, _, n in parts]
        )
    if not np.isscalar(smoothing) and np.ndim(smoothing) != 0:
        raise RbfError("smoothing must be one number λ ≥ 0 (use RBFInterpolator for one per point)")
    names = {_BOUNDARY: "boundary", _INTERIOR: "interior", _EXTERIOR: "exterior", _NORMAL: "normals"}
    starts = np.cumsum([0] + [len(p) for p, _, _, _ in parts])
    try:
        return _fit_rows(points, kinds, values, all_normals, kernel, smoothing, offset, method, max_residual, allow_unconverged)
    except RbfError as e:
        # Name the user's argument and row, not the row of the concatenation.
        def name(found: "re.Match[str]") -> str:
            i = int(found.group(1))
            k = int(np.searchsorted(starts, i, side="right")) - 1
            return f"{names[parts[k][2]]}[{i - starts[k]}]"

        message, renamed = re.subn(r"constraint (\d+)", name, str(e))
        if not renamed:
            raise
        raise RbfError(message) from None


def _fit_rows(points, kinds, values, all_normals, kernel, smoothing, offset, method, max_residual, allow_unconverged):
    return _native._fit(
        points,
        kinds,
        values,
        all_normals,
        0.0,
        kernel=kernel,
        lam=float(smoothing),
        offset=offset,
        method=method,
        max_residual=max_residual,
        allow_unconverged=allow_unconverged,
    )


def from_oriented_points(
    points: ArrayLike,
    normals: ArrayLike,
    *,
    kernel: Optional[str] = None,
    smoothing: float = 0.0,
    offset: Optional[float] = None,
    method: str = "auto",
    max_residual: Optional[float] = None,
    allow_unconverged: bool = False,
) -> Model:
    """The implicit surface through oriented points (a scan with normals, a mesh's vertices):
    ``fit(normals=(points, normals), ...)``. Above 5000 rows (2500 points) the iterative
    solver takes every point.

    >>> import numpy as np, rbfsurf
    >>> z = np.linspace(-0.95, 0.95, 60); t = 2.4 * np.arange(60)
    >>> p = np.c_[np.sqrt(1 - z**2) * np.cos(t), np.sqrt(1 - z**2) * np.sin(t), z]
    >>> m = rbfsurf.from_oriented_points(p, p)
    >>> bool(abs(m(p)).max() < 1e-9)
    True
    """
    points = _checks.points(points, "points")
    normals = _checks.points(normals, "normals", dims=(points.shape[1],))
    return fit(
        normals=(points, normals),
        kernel=kernel,
        smoothing=smoothing,
        offset=offset,
        method=method,
        max_residual=max_residual,
        allow_unconverged=allow_unconverged,
    )


def convert(
    vertices: ArrayLike,
    faces: ArrayLike,
    *,
    method: str = "iterative",
    resolution: int = 128,
    max_constraints: Optional[int] = None,
    max_iterations: int = 30,
    smoothing: float = 0.0,
    offset: float = 0.01,
    return_report: bool = False,
) -> Union[Model, Tuple[Model, dict]]:
    """A closed triangle mesh as an implicit surface, as ``rbf convert`` does.

    ``method="iterative"`` (Yngve & Turk 2002): voxelize at ``resolution`` voxels along the
    longest side, fit, measure the two-way error, add constraints where it is largest, repeat
    (at most ``max_constraints``, default 4000, and ``max_iterations``); on a closed mesh, where
    that falls short of its topology or ends more than two voxels off, normal constraints at the
    vertices are fitted too and kept if they rank better (``rival_kept`` in the report, whose
    ``max_error_voxels`` and ``rms_error_voxels`` are then theirs). ``method="normals"``:
    a normal constraint at every vertex (``max_constraints`` thins them evenly), ``offset`` a
    fraction of the box. With ``return_report``, also a dict of the conversion's figures.
    """
    model, report = _native._convert(
        _checks.points(vertices, "vertices", dims=(3,)),
        faces,
        method=method,
        resolution=resolution,
        max_constraints=max_constraints,
        max_iterations=max_iterations,
        smoothing=smoothing,
        offset=offset,
    )
    return (model, report) if return_report else model


def reconstruct(
    points: ArrayLike,
    normals: Optional[ArrayLike] = None,
    *,
    tolerance: Optional[float] = None,
    smoothing: Optional[float] = None,
    max_centres: Optional[int] = None,
    keep_outliers: bool = False,
    resolution: Optional[int] = None,
    trim: Optional[float] = None,
    return_report: bool = False,
) -> Union[Tuple[np.ndarray, np.ndarray, Model], Tuple[np.ndarray, np.ndarray, Model, dict]]:
    """A closed surface from a scan, as ``rbf reconstruct`` makes it: ``(vertices, faces,
    model)``, and with ``return_report`` a dict of what was done (repeated points
    (``duplicates``) and outliers dropped, normals
    estimated and flipped (``reversed_by_winding``: by the winding number of the others;
    ``refuted``: reversed by fits; ``reversed_by_sight``: by lines of sight, on a clean scan
    only in a second attempt, made when the first fit strayed outside nearly everywhere or its
    mesh came out open: ``looked_again``;
    ``disagreeing``: left out; ``neighbours``: how many each normal was taken from, 16, or
    more for a cloud scanned in lines), noise (``smoothed``: whether the scan counted as
    noisy, its noise above 1e-3 of the box or above 4 % of its points' spacing, and its
    points were smoothed),
    centres (``added_where_sheets_close``: of them, the points a clean scan's spread gained
    where two of its sheets run close), ``lambda`` (0 for a greedy fit), outside constraints added, ``bubbles_dropped`` (pieces the scan cannot show),
    watertight, genus, components).

    ``points``: (n, 3); ``normals``: (n, 3) or None (estimated from local planes; a given
    normal of zero length is estimated too, counted as ``normals_filled``). A point
    given again at the same position is dropped; outliers (sparser than the cloud and than
    their neighbours) are dropped unless ``keep_outliers``; every normal is oriented consistently and outward.
    An even spread of the points then carries normal constraints in one smoothing fit, with
    λ = ``smoothing`` for a box whose longest side is 2 (larger is smoother; default: chosen
    from the measured noise: 3e-5 on a clean scan, which follows the points closely but does
    not close narrow crevices over; 1e-4 up to a noise of 6e-3 of the box, growing as its
    power 1.5 above): 1.5·10⁴ points of a clean scan (twice as fine where two sheets face
    each other closely), 10⁴ of a noisy one. With ``tolerance``
    (a fraction of the box's longest side) greedily chosen points carry the constraints
    instead, until the surface passes within it of every point. ``max_centres`` caps the
    points that carry constraints in either fit (default: the spreads above; 8000 greedy). Where f is not
    negative just outside the scan, outside constraints are added; the mesh is polygonized at
    ``resolution`` cubes across the box (default: about the points' spacing), without the
    bubbles that no point of the scan is near, crumbs, and closed cavities inside the solid
    (which no scanner sees: the inside of an opening narrower than a point spacing). For an open scan, ``trim`` (a distance in the
    points' units) keeps only the surface within it of the points: the mesh is then open.

    >>> import numpy as np, rbfsurf
    >>> i = np.arange(2000) + 0.5
    >>> z = 1 - 2 * i / 2000; t = np.pi * (1 + 5**0.5) * i; s = np.sqrt(1 - z * z)
    >>> v, f, model = rbfsurf.reconstruct(np.c_[s * np.cos(t), s * np.sin(t), z])
    >>> bool(model([[0, 0, 0]])[0] > 0 > model([[2, 0, 0]])[0]), f.shape[1]
    (True, 3)
    """
    points = _checks.points(points, "points", dims=(3,))
    if normals is not None:
        normals = _checks.points(normals, "normals", dims=(3,))
    v, f, model, report = _native._reconstruct(
        points,
        normals,
        tolerance=tolerance,
        smoothing=smoothing,
        max_centres=max_centres,
        keep_outliers=keep_outliers,
        resolution=resolution,
        trim=trim,
    )
    return (v, f, model, report) if return_report else (v, f, model)


class VoxelGrid(NamedTuple):
    """A volume: ``values[i, j, k]`` belongs to the voxel centred at
    ``origin + voxel_size * (i, j, k)``."""

    values: np.ndarray
    origin: np.ndarray
    voxel_size: float


def voxelize(
    vertices: ArrayLike,
    faces: ArrayLike,
    *,
    resolution: int = 64,
    supersampling: int = 4,
    method: str = "auto",
) -> VoxelGrid:
    """The fraction of each voxel inside a closed mesh (float32, ``supersampling``³ samples
    per voxel), ``resolution`` voxels along the box's longest side plus a margin.
    ``method``: ``"rays"`` (closed meshes), ``"winding"`` (generalized winding numbers:
    meshes with holes) or ``"auto"``.

    >>> import rbfsurf
    >>> v = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
    >>> f = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
    >>> g = rbfsurf.voxelize(v, f, resolution=16)
    >>> abs(float(g.values.sum()) * g.voxel_size**3 - 1 / 6) < 0.01
    True
    """
    return _grid(vertices, faces, resolution, supersampling, method, distance=False)


def signed_distance(
    vertices: ArrayLike,
    faces: ArrayLike,
    *,
    resolution: int = 64,
    supersampling: int = 4,
    method: str = "auto",
) -> VoxelGrid:
    """The signed distance to a closed mesh's surface at every voxel centre (float32, in the
    mesh's units, positive inside), from its voxels by an exact distance transform."""
    return _grid(vertices, faces, resolution, supersampling, method, distance=True)


def _grid(vertices, faces, resolution, supersampling, method, distance):
    values, origin, size = _native._voxelize(
        _checks.points(vertices, "vertices", dims=(3,)),
        faces,
        resolution=resolution,
        supersampling=supersampling,
        method=method,
        distance=distance,
    )
    return VoxelGrid(values, np.asarray(origin), size)


def read_mesh(path: Union[str, "os.PathLike[str]"]) -> Tuple[np.ndarray, np.ndarray]:
    """Reads a mesh file (OBJ, PLY, STL): ``(vertices, faces)``, (n, 3) float64 and (m, 3)
    int64 arrays."""
    path = os.fspath(path)
    if not os.path.exists(path):
        raise RbfFileNotFoundError(f"{path}: no such file")
    return _native.read_mesh(path)


def loads(text: str) -> Model:
    """A model from the JSON text of a model file."""
    return Model.from_json(text)


def load(path: Union[str, "os.PathLike[str]"]) -> Model:
    """Reads a model file written by ``Model.save`` or ``rbf fit``."""
    path = os.fspath(path)
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except FileNotFoundError:
        raise RbfFileNotFoundError(f"{path}: no such file") from None
    except (OSError, UnicodeDecodeError) as e:
        raise RbfError(f"{path}: {e}") from None
    try:
        return Model.from_json(text)
    except RbfError as e:
        raise RbfError(f"{path}: {e}") from None
