"""to_trimesh / to_pyvista / to_meshio: the installed one converts, a missing one says how
to install it."""

import sys

import numpy as np
import pytest

import zipmesh

from conftest import SPOT_POLY, TORUS


def test_to_trimesh():
    pytest.importorskip("trimesh")
    mesh = zipmesh.load(TORUS)
    other = mesh.to_trimesh()
    np.testing.assert_array_equal(np.asarray(other.vertices), mesh.vertices)
    np.testing.assert_array_equal(np.asarray(other.faces), mesh.faces)


@pytest.mark.parametrize("method, module", [("to_trimesh", "trimesh"), ("to_pyvista", "pyvista"), ("to_meshio", "meshio")])
def test_missing_package_is_an_import_error(monkeypatch, method, module):
    monkeypatch.setitem(sys.modules, module, None)  # `import module` now fails
    with pytest.raises(ImportError, match=f"pip install {module}"):
        getattr(zipmesh.load(SPOT_POLY), method)()


def test_to_meshio_blocks_by_degree():
    pytest.importorskip("meshio")
    mesh = zipmesh.load(SPOT_POLY)
    cells = mesh.to_meshio().cells
    assert sum(len(c.data) for c in cells) == len(mesh.faces)
