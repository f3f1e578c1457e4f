"""The example script runs on Spot and writes what it says."""

import subprocess
import sys
from pathlib import Path

import zipmesh

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "clean.py"


def test_clean_example(tmp_path):
    done = subprocess.run([sys.executable, str(EXAMPLE), str(Path(__file__).resolve().parents[3] / "tests/data/quad/spot_quadrangulated.obj"), str(tmp_path)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "zip " in done.stdout and "optimize: v3" in done.stdout
    cleaned = zipmesh.load(tmp_path / "clean.obj")
    assert cleaned.stats()["kind"] == "quad"
    assert (tmp_path / "clean.svg").read_text().startswith("<?xml")
