"""Each report equals the `zipmesh` binary's `--json` output on the same file, and each edit's
mesh equals the file the binary writes.

Left out of the comparison, and only these: `file` and `output` (the binary's are the
paths given to it, the package's would be its temporary files, so it drops them) and
`seconds` (timings of the run).
"""

import json
import subprocess

import numpy as np
import pytest

import zipmesh

from conftest import SPOT_QUAD, SPOT_TRI, TORUS

TIMINGS = ("seconds",)


def without_timings(value):
    """`value` with every `seconds` key removed, at any depth."""
    if isinstance(value, dict):
        return {k: without_timings(v) for k, v in value.items() if k not in TIMINGS}
    if isinstance(value, list):
        return [without_timings(v) for v in value]
    return value


def run_cli(cli, *args):
    done = subprocess.run([cli, *map(str, args), "--json"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    report = json.loads(done.stdout)
    if isinstance(report, dict):
        for key in ("file", "output"):
            report.pop(key, None)
    return report


def assert_same_mesh(mesh, path):
    written = zipmesh.load(path)
    np.testing.assert_array_equal(mesh.vertices, written.vertices)
    np.testing.assert_array_equal(np.asarray(mesh.faces), np.asarray(written.faces))


def test_stats_and_quality(cli):
    mesh = zipmesh.load(SPOT_QUAD)
    expected = run_cli(cli, "stats", SPOT_QUAD)
    assert mesh.stats() == expected
    assert mesh.quality() == expected["quality"]


def test_stats_against_a_reference(cli, tmp_path):
    mesh = zipmesh.load(SPOT_TRI)
    moved, _ = mesh.tri_type(split=_first_irregular(mesh, 4) or _first_irregular(mesh, 5))
    moved.save(tmp_path / "moved.ply")
    expected = run_cli(cli, "stats", tmp_path / "moved.ply", "--reference", SPOT_TRI)
    assert moved.stats(reference=mesh) == expected
    assert expected["quality"]["distance"] is not None


def _first_irregular(mesh, valence):
    rows = mesh.singularities()["singularities"]
    return next((r["vertex"] for r in rows if r["valence"] == valence and not r["boundary"]), None)


@pytest.mark.parametrize("path", [SPOT_QUAD, SPOT_TRI])
def test_singularities(cli, path):
    assert zipmesh.load(path).singularities() == run_cli(cli, "singularities", path)


def test_moves_and_partners(cli):
    mesh = zipmesh.load(SPOT_QUAD)
    assert mesh.moves(15, 2) == run_cli(cli, "moves", SPOT_QUAD, "--from", 15, "--to", 2)
    assert mesh.partners(15, 3) == run_cli(cli, "moves", SPOT_QUAD, "--from", 15, "--partners", 3)


def test_zip(cli, tmp_path):
    out = tmp_path / "moved.ply"
    expected = run_cli(cli, "zip", SPOT_QUAD, "--from", 15, "--to", 2, "--move", "LC", "-o", out)
    moved, report = zipmesh.load(SPOT_QUAD).zip(15, 2, move="LC")
    assert report == expected
    assert_same_mesh(moved, out)


def test_tri_generate_then_move(cli, tmp_path):
    four_path = tmp_path / "four.ply"
    expected = run_cli(cli, "tri-generate", TORUS, "--at", 0, "-o", four_path)
    four, report = zipmesh.load(TORUS).tri_generate(at=0)
    assert report == expected
    assert_same_mesh(four, four_path)
    v5, v7 = report["v5"][0], report["v7"][0]
    apart_path = tmp_path / "apart.ply"
    expected = run_cli(cli, "tri-move", four_path, "--pair", f"{v5},{v7}", "--direction", 0, "--steps", 2, "-o", apart_path)
    apart, report = four.tri_move((v5, v7), direction=0, steps=2)
    assert report == expected
    assert_same_mesh(apart, apart_path)


def test_optimize_quad(cli, tmp_path):
    out = tmp_path / "fewer.ply"
    expected = run_cli(cli, "optimize", SPOT_QUAD, "--batches", 3, "--seed", 7, "-o", out)
    fewer, report = zipmesh.load(SPOT_QUAD).optimize(batches=3, seed=7)
    assert without_timings(report) == without_timings(expected)
    assert_same_mesh(fewer, out)


def test_optimize_triangles(cli, tmp_path):
    out = tmp_path / "fewer.ply"
    expected = run_cli(cli, "optimize", SPOT_TRI, "--batches", 1, "-o", out)
    fewer, report = zipmesh.load(SPOT_TRI).optimize(batches=1)
    assert without_timings(report) == without_timings(expected)
    assert_same_mesh(fewer, out)
