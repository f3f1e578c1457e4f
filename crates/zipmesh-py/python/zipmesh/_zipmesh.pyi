"""Type stubs of the compiled module `zipmesh._zipmesh` (src/lib.rs); use the package
`zipmesh`, whose `Mesh` wraps this one."""

import os
from typing import Any, Sequence

import numpy as np
import numpy.typing as npt

class Mesh:
    """A polygon mesh held in Rust; unreferenced vertices dropped."""

    def __init__(self, vertices: npt.ArrayLike, faces: Any) -> None:
        """From an (N, 3) float array and an (F, k) integer array or a list of lists."""
    @property
    def vertices(self) -> npt.NDArray[np.float64]:
        """The positions, an (N, 3) float64 array."""
    def polygons(self) -> list[list[int]]:
        """The faces as lists of vertex numbers, counter-clockwise."""
    @property
    def num_vertices(self) -> int:
        """The number of vertices."""
    @property
    def num_faces(self) -> int:
        """The number of faces."""
    def save(self, path: str | os.PathLike[str], ascii: bool = False) -> None:
        """Writes the mesh; the extension picks the format, `ascii` makes PLY text."""

def load(path: str | os.PathLike[str]) -> Mesh:
    """Reads an .obj, .off or .ply file (OSError, ValueError on failure)."""

def run(args: Sequence[str]) -> str:
    """Runs one `zipmesh` command in this process, lock released; its standard output."""
