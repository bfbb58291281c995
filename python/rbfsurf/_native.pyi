"""Type stubs of the native module rbfsurf._native (Rust, PyO3)."""

from os import PathLike
from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, PathLike[str]]

class RbfError(ValueError): ...

class Model:
    def __call__(self, x: npt.ArrayLike) -> npt.NDArray[np.float64]: ...
    def gradient(self, x: npt.ArrayLike) -> npt.NDArray[np.float64]: ...
    @property
    def dim(self) -> int: ...
    @property
    def kernel(self) -> str: ...
    @property
    def centres(self) -> npt.NDArray[np.float64]: ...
    @property
    def weights(self) -> npt.NDArray[np.float64]: ...
    @property
    def report(self) -> Optional[Dict[str, Any]]: ...
    def to_json(self) -> str: ...
    @staticmethod
    def from_json(text: str) -> Model: ...
    def save(self, path: _Path) -> None: ...
    def polygonize(
        self, resolution: int = 128, *, method: str = "continuation"
    ) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]: ...
    def render(
        self,
        width: int = 640,
        height: int = 480,
        *,
        azimuth: float = 30.0,
        elevation: float = 20.0,
        samples: int = 2,
        shadows: bool = False,
        ground: bool = True,
    ) -> npt.NDArray[np.uint8]: ...

class Session:
    COMMANDS: str
    def __init__(self, model: Optional[Model] = None) -> None: ...
    def run(self, line: str) -> str: ...
    def run_script(self, text: str) -> List[str]: ...
    def model(self) -> Model: ...
    def __len__(self) -> int: ...

def _fit(
    points: npt.ArrayLike,
    kinds: npt.ArrayLike,
    values: npt.ArrayLike,
    normals: Optional[npt.ArrayLike],
    smoothing: npt.ArrayLike,
    *,
    kernel: Optional[str] = None,
    lam: float = 0.0,
    offset: Optional[float] = None,
    method: str = "auto",
    max_residual: float = 1e-6,
    allow_unconverged: bool = False,
) -> Model: ...
def convert(
    vertices: npt.ArrayLike,
    faces: npt.ArrayLike,
    *,
    method: str = "iterative",
    resolution: int = 128,
    max_constraints: Optional[int] = None,
    max_iterations: int = 30,
    smoothing: float = 0.0,
    offset: float = 0.01,
) -> Tuple[Model, Dict[str, Any]]: ...
def _voxelize(
    vertices: npt.ArrayLike,
    faces: npt.ArrayLike,
    *,
    resolution: int = 64,
    supersampling: int = 4,
    method: str = "auto",
    distance: bool = False,
) -> Tuple[npt.NDArray[np.float32], List[float], float]: ...
def read_mesh(path: _Path) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]: ...
def write_mesh(path: _Path, vertices: npt.ArrayLike, faces: npt.ArrayLike) -> None: ...
