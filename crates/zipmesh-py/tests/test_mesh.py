"""The Mesh type: arrays in and out, errors as Python exceptions, edits leave their input
alone, and optimize lets other threads run."""

import threading
import time

import numpy as np
import pytest

import zipmesh

from conftest import SPOT_POLY, SPOT_QUAD

# A unit cube's eight corners and six outward quads.
CUBE_V = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1)], dtype=float)
CUBE_F = np.array([[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]])


def test_arrays_round_trip():
    mesh = zipmesh.Mesh(CUBE_V, CUBE_F)
    np.testing.assert_array_equal(mesh.vertices, CUBE_V)
    np.testing.assert_array_equal(mesh.faces, CUBE_F)
    assert mesh.vertices.dtype == np.float64 and mesh.faces.dtype == np.int64
    assert mesh.stats()["genus"] == 0


def test_lists_and_mixed_degrees():
    # The cube's top quad split into two triangles: faces of two degrees, as lists.
    faces = [list(f) for f in CUBE_F[:1]] + [[4, 5, 7], [4, 7, 6]] + [list(f) for f in CUBE_F[2:]]
    mesh = zipmesh.Mesh(CUBE_V.tolist(), faces)
    assert mesh.faces == faces
    assert mesh.stats()["kind"] == "mixed"


def test_unreferenced_vertices_are_dropped():
    extra = np.vstack([CUBE_V, [[9.0, 9.0, 9.0]]])
    mesh = zipmesh.Mesh(extra, CUBE_F)
    assert mesh.vertices.shape == (8, 3)


@pytest.mark.parametrize(
    "vertices, faces, words",
    [
        (np.zeros((3, 2)), [[0, 1, 2]], "(N, 3)"),
        (CUBE_V, [[0, 1, 99]], "vertex 99"),
        (CUBE_V, [[0, 1, -1]], "vertex -1"),
        (CUBE_V, "not faces", "list of lists"),
        (np.full((3, 3), np.nan), [[0, 1, 2]], "finite"),
        (CUBE_V, [[0, 1, 2], [0, 1, 2], [0, 1, 2]], "faces:"),
    ],
)
def test_bad_input_is_a_value_error(vertices, faces, words):
    with pytest.raises(ValueError, match=words.replace("(", r"\(").replace(")", r"\)")):
        zipmesh.Mesh(vertices, faces)


def test_file_errors(tmp_path):
    with pytest.raises(OSError):
        zipmesh.load(tmp_path / "missing.obj")
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 zero\n")
    with pytest.raises(ValueError, match="bad.obj:1: expected a vertex coordinate"):
        zipmesh.load(bad)
    with pytest.raises(OSError):
        zipmesh.Mesh(CUBE_V, CUBE_F).save(tmp_path / "no" / "such" / "dir.obj")


def test_refused_edit_names_no_temporary_file():
    mesh = zipmesh.load(SPOT_QUAD)
    with pytest.raises(ValueError) as e:
        mesh.zip(15, 0, move="LS")  # vertex 0 of Spot is regular
    assert "zipmesh-" not in str(e.value) and "not irregular" in str(e.value)
    with pytest.raises(ValueError, match="unknown move"):
        mesh.zip(15, 2, move="XX")


@pytest.mark.parametrize("ext", ["obj", "off", "ply"])
def test_save_and_load(tmp_path, ext):
    mesh = zipmesh.load(SPOT_POLY)
    mesh.save(tmp_path / f"spot.{ext}")
    again = zipmesh.load(tmp_path / f"spot.{ext}")
    np.testing.assert_array_equal(again.vertices, mesh.vertices)
    assert again.faces == mesh.faces


def test_edits_return_new_meshes():
    mesh = zipmesh.load(SPOT_QUAD)
    before = mesh.vertices, mesh.faces
    moved, report = mesh.zip(15, 2, move="LC")
    np.testing.assert_array_equal(mesh.vertices, before[0])
    np.testing.assert_array_equal(mesh.faces, before[1])
    assert moved.vertices.shape[0] == before[0].shape[0] + report["splits"] - report["collapses"]


def test_pictures():
    mesh = zipmesh.load(SPOT_QUAD)
    svg = mesh.render_svg(view=(30, 10), size=(200, 150))
    assert svg.startswith("<?xml") and 'width="200"' in svg
    png = mesh.render_png(size=(64, 48))
    assert png.startswith(b"\x89PNG\r\n\x1a\n")
    _, report = mesh.zip(15, 2, move="LC")
    assert mesh.render_svg(paths=report) != svg


def test_optimize_releases_the_interpreter_lock():
    """While optimize runs, this thread keeps running: the longest pause between its
    clock readings stays far below the optimizer's run time."""
    mesh = zipmesh.load(SPOT_QUAD)
    done = []
    worker = threading.Thread(target=lambda: done.append(mesh.optimize(batches=6)))
    start = time.perf_counter()
    last, longest = start, 0.0
    worker.start()
    while worker.is_alive():
        now = time.perf_counter()
        longest = max(longest, now - last)
        last = now
        time.sleep(0.001)
    took = time.perf_counter() - start
    worker.join()
    assert done and took > 0.2, f"optimize took only {took:.3f} s: too short to tell"
    assert longest < took / 2, f"a pause of {longest:.3f} s in {took:.3f} s"
