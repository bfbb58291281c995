"""rbfsurf: variational implicit surfaces, NumPy in and NumPy out.

Smooth functions that pass exactly through given points, built from radial basis
functions (Turk & O'Brien 2002; Yngve & Turk 2002), by the Rust library rbf:

- ``RBFInterpolator``: scipy's interface (``kernel="cubic" | "linear" |
  "thin_plate_spline"``, ``smoothing``), for scattered data in 2D and 3D;
- ``fit`` and ``from_oriented_points``: implicit surfaces from boundary, interior,
  exterior and normal constraints; ``convert``: a closed mesh to an implicit surface;
  ``reconstruct``: a scan (points, normals optional) to a closed surface;
- ``Model``: call it for f, ``.gradient``, ``.polygonize`` -> (V, F), ``.render`` -> image,
  ``.save`` / ``load`` in the JSON of the ``rbf`` command;
- ``voxelize`` and ``signed_distance``: volumes of meshes; ``Session``: sculpting with the
  command language of ``rbf sculpt -``.

Every heavy call releases the GIL and runs on every core. Bad input raises ``RbfError``
(a ``ValueError``) with the message the ``rbf`` command gives.

>>> import numpy as np, rbfsurf
>>> t = np.linspace(0, 2 * np.pi, 40, endpoint=False)
>>> circle = np.c_[np.cos(t), np.sin(t)]
>>> m = rbfsurf.from_oriented_points(circle, circle)   # outward normals
>>> bool(m([[0.0, 0.0]])[0] > 0 > m([[2.0, 0.0]])[0])
True
"""

from ._native import Model, RbfError, Session, write_mesh
from ._api import (
    RbfFileNotFoundError,
    VoxelGrid,
    convert,
    fit,
    from_oriented_points,
    load,
        loads,
    read_mesh,
    reconstruct,
    signed_distance,
    voxelize,
)
from ._interpolator import RBFInterpolator

__version__ = "0.1.0"

__all__ = [
    "Model",
    "RBFInterpolator",
    "RbfError",
    "RbfFileNotFoundError",
    "Session",
    "VoxelGrid",
    "convert",
    "fit",
    "from_oriented_points",
    "load",
    "loads",
    "read_mesh",
    "reconstruct",
    "signed_distance",
    "voxelize",
    "write_mesh",
]
