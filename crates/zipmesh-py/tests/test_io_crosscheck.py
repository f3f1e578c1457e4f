"""zipmesh's PLY and OBJ against independent readers and writers (plyfile, trimesh):
what zipmesh writes they read to the same numbers, and what they write zipmesh reads."""

import numpy as np
import pytest

import zipmesh

from conftest import SPOT_QUAD, TORUS

plyfile = pytest.importorskip("plyfile")
trimesh = pytest.importorskip("trimesh")


def ply_arrays(path):
    data = plyfile.PlyData.read(str(path))
    v = data["vertex"]
    vertices = np.column_stack([v["x"], v["y"], v["z"]]).astype(np.float64)
    face = data["face"].data
    name = "vertex_indices" if "vertex_indices" in face.dtype.names else "vertex_index"
    return vertices, np.array([list(f) for f in face[name]], dtype=np.int64), data


@pytest.mark.parametrize("ascii", [False, True])
def test_plyfile_reads_zipmesh_ply(tmp_path, ascii):
    mesh = zipmesh.load(SPOT_QUAD)
    path = tmp_path / "spot.ply"
    mesh.save(path, ascii=ascii)
    vertices, faces, data = ply_arrays(path)
    assert data.text == ascii
    np.testing.assert_array_equal(vertices, mesh.vertices)
    np.testing.assert_array_equal(faces, mesh.faces)


def test_trimesh_reads_zipmesh_obj(tmp_path):
    mesh = zipmesh.load(TORUS)
    path = tmp_path / "torus.obj"
    mesh.save(path)
    other = trimesh.load(str(path), process=False, maintain_order=True)
    np.testing.assert_array_equal(np.asarray(other.vertices), mesh.vertices)
    np.testing.assert_array_equal(np.asarray(other.faces), mesh.faces)


@pytest.mark.parametrize("text, order", [(False, ">"), (False, "<"), (True, "=")])
def test_zipmesh_reads_plyfile_ply(tmp_path, text, order):
    """Big- and little-endian binary and ASCII, float64 coordinates among other properties,
    ushort corners under the name vertex_index."""
    mesh = zipmesh.load(SPOT_QUAD)
    V, F = mesh.vertices, mesh.faces
    vert = np.zeros(len(V), dtype=[("x", "f8"), ("nx", "f4"), ("y", "f8"), ("z", "f8"), ("red", "u1")])
    vert["x"], vert["y"], vert["z"] = V[:, 0], V[:, 1], V[:, 2]
    face = np.empty(len(F), dtype=[("vertex_index", "O"), ("flag", "i4")])
    face["vertex_index"] = [np.array(f, dtype="u2") for f in F]
    face["flag"] = 1
    path = tmp_path / "spot.ply"
    plyfile.PlyData(
        [
            plyfile.PlyElement.describe(vert, "vertex"),
            plyfile.PlyElement.describe(face, "face", val_types={"vertex_index": "u2"}, len_types={"vertex_index": "u1"}),
        ],
        text=text,
        byte_order=order,
    ).write(str(path))
    again = zipmesh.load(path)
    np.testing.assert_array_equal(again.vertices, V)
    np.testing.assert_array_equal(again.faces, F)
    assert again.stats()["canonical_hash"] == mesh.stats()["canonical_hash"]


def test_zipmesh_reads_trimesh_obj(tmp_path):
    mesh = zipmesh.load(TORUS)
    other = trimesh.Trimesh(vertices=mesh.vertices, faces=mesh.faces, process=False)
    path = tmp_path / "torus.obj"
    other.export(str(path))
    again = zipmesh.load(path)
    # trimesh writes coordinates with fewer digits than a float64 holds.
    np.testing.assert_allclose(again.vertices, mesh.vertices, rtol=0, atol=1e-7)
    np.testing.assert_array_equal(again.faces, mesh.faces)
