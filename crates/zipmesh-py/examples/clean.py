"""Clean up a quad mesh's singularities with zipmesh, step by step.

    python crates/zipmesh-py/examples/clean.py [MESH] [OUT_DIR]

MESH defaults to the repository's Spot (tests/data/quad/spot_quadrangulated.obj), OUT_DIR to
a new temporary folder. The script lists the singularities, moves one pair by a Q-zip, runs
a few batches of the optimizer, and writes the result with a picture of it.
"""

import sys
import tempfile
from collections import Counter
from pathlib import Path

import zipmesh

ROOT = Path(__file__).resolve().parents[3]


def main() -> None:
    source = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "tests/data/quad/spot_quadrangulated.obj"
    out_dir = Path(sys.argv[2]) if len(sys.argv) > 2 else Path(tempfile.mkdtemp(prefix="zipmesh-clean-"))
    mesh = zipmesh.load(source)
    print(f"{source.name}: {len(mesh.vertices)} vertices, {len(mesh.faces)} faces")

    found = mesh.singularities()["singularities"]
    print("singularities by valence:", dict(sorted(Counter(s["valence"] for s in found).items())))

    # The first interior singularity with a realizable movement towards a partner.
    for s in (s for s in found if not s["boundary"]):
        partner = next((p for p in mesh.partners(s["vertex"], 3) if p["realizable"]), None)
        if partner is not None:
            a, b, move = s["vertex"], partner["to"], partner["realizable"][0]
            mesh, report = mesh.zip(a, b, move=move)
            print(f"zip {a} -> {b} ({move}): the pair moved to {report['moved']['from']} and {report['moved']['to']}")
            break

    mesh, report = mesh.optimize(batches=5, seed=0)
    before, after = report["input"], report["final"]
    print(f"optimize: v3 {before['v3']} -> {after['v3']}, v5 {before['v5']} -> {after['v5']}")
    print("folded quads:", report["quality"]["output"]["folded_quads"])

    mesh.save(out_dir / "clean.obj")
    (out_dir / "clean.svg").write_text(mesh.render_svg())
    print(f"wrote {out_dir / 'clean.obj'} and {out_dir / 'clean.svg'}")


if __name__ == "__main__":
    main()
