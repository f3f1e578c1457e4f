"""The Python steps of docs/guide.md run as written, from a folder whose `tests/data` is the
repository's, and do what the guide says."""

import os
import re

import zipmesh

from conftest import ROOT


def guide_blocks():
    text = (ROOT / "docs" / "guide.md").read_text()
    return re.findall(r"```python\n(.*?)```", text, flags=re.S)


def test_the_guide_python_session_runs(tmp_path, monkeypatch):
    blocks = guide_blocks()
    assert blocks, "docs/guide.md has no python block"
    (tmp_path / "tests").symlink_to(ROOT / "tests")
    monkeypatch.chdir(tmp_path)
    names = {}
    for block in blocks:
        exec(compile(block, "docs/guide.md", "exec"), names)
    # The steps did what the guide says: a listing, partners, a zip, fewer singularities.
    assert names["found"] and all("vertex" in s and "valence" in s for s in names["found"])
    assert len(names["zipped"].faces) > 0
    before = names["mesh"].singularities()["singularities"]
    after = names["fewer"].singularities()["singularities"]
    assert len(after) < len(before)
    assert len(zipmesh.load(tmp_path / "fewer.ply").faces) == len(names["fewer"].faces)
    assert names["svg"].startswith("<?xml")
    assert os.path.getsize(tmp_path / "fewer.ply") > 0
