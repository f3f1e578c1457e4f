"""Shared fixtures: the repository's meshes and the `zipmesh` binary to compare against."""

import os
import shutil
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
DATA = ROOT / "tests" / "data"
SPOT_QUAD = DATA / "quad" / "spot_quadrangulated.obj"
SPOT_TRI = DATA / "tri" / "spot_triangulated.obj"
TORUS = DATA / "tri" / "torus.obj"
SPOT_POLY = DATA / "poly" / "spot_control_mesh.obj"


def _find_cli():
    """ZIPMESH_CLI, else a built binary of this checkout, else one on PATH."""
    given = os.environ.get("ZIPMESH_CLI")
    if given:
        return given
    targets = [os.environ.get("CARGO_TARGET_DIR"), str(ROOT / "target")]
    for target in filter(None, targets):
        for profile in ("release", "debug"):
            path = Path(target) / profile / "zipmesh"
            if path.is_file():
                return str(path)
    return shutil.which("zipmesh")


@pytest.fixture(scope="session")
def cli():
    """The path of the `zipmesh` binary. Set ZIPMESH_CLI to choose it (CI does, so a
    missing binary fails there); without one the comparisons are skipped."""
    path = _find_cli()
    if path is None:
        pytest.skip("no zipmesh binary: build it (cargo build --release -p zipmesh-cli) or set ZIPMESH_CLI")
    if not os.access(path, os.X_OK):
        pytest.fail(f"ZIPMESH_CLI={path} is not an executable")
    return path
