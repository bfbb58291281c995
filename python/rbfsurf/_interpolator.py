"""scipy's ``RBFInterpolator``, on rbf's solvers and evaluator."""

from __future__ import annotations

from typing import Any, List, Optional

import numpy as np

from . import _checks, _native
from ._native import Model, RbfError

ArrayLike = Any

# φ(εr) = ε^β φ(r) (up to a polynomial the linear part absorbs), so a shape parameter ε only
# rescales the smoothing.
_SCALE_EXPONENT = {"cubic": 3, "linear": 1, "thin_plate_spline": 2}


class RBFInterpolator:
    """Radial basis function interpolation in 2D and 3D, with scipy's interface.

    ``RBFInterpolator(y, d, kernel="cubic", smoothing=0.0)`` solves what
    ``scipy.interpolate.RBFInterpolator`` solves for the same arguments and ``degree=1`` —
    the kernel block plus ``smoothing`` on its diagonal and a linear polynomial — and agrees
    with it to 1e-8 (the tests' bound; dense fits, up to 5000 points, agree to rounding).
    Two defaults differ: the kernel (scipy's is ``"thin_plate_spline"``) and, for
    ``kernel="linear"``, the degree (scipy's is 0).

    - ``y``: (n, dim) data points, dim 2 or 3; ``d``: (n, ...) data values;
    - ``kernel``: ``"cubic"`` (r³), ``"linear"`` (−r), ``"thin_plate_spline"`` (r² log r);
    - ``smoothing``: a number or one per point, ≥ 0; ``epsilon``: accepted as scipy does
      (for these kernels it only rescales ``smoothing``); ``degree``: 1 (or None);
      ``neighbors``: None (every point is used; rbf's iterative solver takes large sets);
    - beyond scipy: ``max_residual``, the largest accepted max|f(yᵢ) + λᵢwᵢ − dᵢ| relative
      to max|dᵢ| (a fit that misses it raises ``RbfError``), and ``method`` (``"auto"``,
      ``"dense"``, ``"fast"``).

    Calling it on (m, dim) points returns (m, ...) values; ``gradient`` returns
    (m, ..., dim). A NaN or an infinity in ``y`` or in the query points raises ``RbfError``
    naming the row (scipy returns NaN for such queries). ``models`` holds one ``rbfsurf.Model`` per column of ``d`` (None for a
    column of zeros).

    >>> import numpy as np, rbfsurf
    >>> rng = np.random.default_rng(0)
    >>> y = rng.uniform(-1, 1, (50, 2)); d = np.sin(3 * y[:, 0]) + y[:, 1]
    >>> f = rbfsurf.RBFInterpolator(y, d)
    >>> bool(np.abs(f(y) - d).max() < 1e-9)
    True
    """

    def __init__(
        self,
        y: ArrayLike,
        d: ArrayLike,
        neighbors: Optional[int] = None,
        smoothing: ArrayLike = 0.0,
        kernel: str = "cubic",
        epsilon: Optional[float] = None,
        degree: Optional[int] = None,
        *,
        max_residual: Optional[float] = None,
        method: str = "auto",
    ) -> None:
        if neighbors is not None:
            raise NotImplementedError(
                "neighbors: rbfsurf fits every point exactly; large sets go to its iterative "
                "solver (leave neighbors=None)"
            )
        if kernel not in _SCALE_EXPONENT:
            raise RbfError(
                f"kernel must be one of {sorted(_SCALE_EXPONENT)}, not {kernel!r}"
            )
        if degree is not None and degree != 1:
            raise RbfError(f"degree must be 1 (rbf's polynomial is linear), not {degree}")
        y = _checks.floats(y, "y")
        if y.ndim != 2:
            raise RbfError(f"y must be a 2-dimensional array, not of shape {y.shape}")
        n, dim = y.shape
        if dim not in (2, 3):
            raise RbfError(f"y has {dim} columns: rbfsurf interpolates in 2 or 3 dimensions")
        _checks.finite_rows(y, "y")
        d = np.asarray(d)
        if np.iscomplexobj(d):
            raise RbfError("d must be real: complex values are not supported")
        d = d.astype(np.float64, copy=False)
        if d.ndim == 0 or d.shape[0] != n:
            raise RbfError(f"d must have {n} rows, like y; its shape is {d.shape}")
        bad = np.flatnonzero(~np.isfinite(d.reshape(n, -1)).all(axis=1))
        if len(bad):
            raise RbfError(f"d: row {bad[0]} is not a finite number")
        smoothing = np.asarray(smoothing, dtype=np.float64)
        if smoothing.ndim == 0:
            smoothing = np.full(n, float(smoothing))
        elif smoothing.shape != (n,):
            raise RbfError(f"smoothing must be a number or have shape ({n},), not {smoothing.shape}")
        bad = np.flatnonzero(~(np.isfinite(smoothing) & (smoothing >= 0)))
        if len(bad):
            i = int(bad[0])
            raise RbfError(f"smoothing[{i}] = {float(smoothing[i])!r}: must be a finite number ≥ 0")
        if epsilon is not None:
            if not (np.isfinite(epsilon) and epsilon > 0):
                raise RbfError(f"epsilon must be a finite number > 0, not {epsilon}")
            smoothing = smoothing / float(epsilon) ** _SCALE_EXPONENT[kernel]
        self.y = y
        self.d = d
        self.kernel = kernel
        self.smoothing = smoothing
        self.epsilon = 1.0 if epsilon is None else float(epsilon)
        self.degree = 1
        self._value_shape = d.shape[1:]
        columns = d.reshape(n, -1)
        # One model per column; None for a column of zeros (its interpolant is 0).
        self.models: List[Optional[Model]] = []
        for k in range(columns.shape[1]):
            values = np.ascontiguousarray(columns[:, k])
            if not values.any():
                self.models.append(None)
                continue
            kinds = np.where(values > 0, 1.0, np.where(values < 0, 2.0, 0.0))
            self.models.append(
                _native._fit(
                    y,
                    kinds,
                    values,
                    None,
                    smoothing,
                    kernel=kernel,
                    lam=0.0,
                    method=method,
                    max_residual=max_residual,
                )
            )

    def _points(self, x: ArrayLike) -> np.ndarray:
        x = _checks.floats(x, "x")
        if x.ndim != 2 or x.shape[1] != self.y.shape[1]:
            raise RbfError(
                f"x must have shape (m, {self.y.shape[1]}), like y; its shape is {x.shape}"
            )
        _checks.finite_rows(x, "x")
        return x

    def __call__(self, x: ArrayLike) -> np.ndarray:
        """The interpolant at the rows of ``x``: shape (m,) + d.shape[1:]."""
        x = self._points(x)
        columns = [np.zeros(len(x)) if m is None else m(x) for m in self.models]
        out = columns[0] if len(columns) == 1 else np.stack(columns, axis=1)
        return out.reshape((len(x),) + self._value_shape)

    def gradient(self, x: ArrayLike) -> np.ndarray:
        """The gradient at the rows of ``x``: shape (m,) + d.shape[1:] + (dim,)."""
        x = self._points(x)
        dim = x.shape[1]
        columns = [np.zeros(x.shape) if m is None else m.gradient(x) for m in self.models]
        out = columns[0] if len(columns) == 1 else np.stack(columns, axis=1)
        return out.reshape((len(x),) + self._value_shape + (dim,))
