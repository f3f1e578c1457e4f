#!/usr/bin/env python3
"""The tables of docs/results.md: `zipmesh optimize --json` on every mesh of tests/data
(quad, poly and tri), with the default command line and with each option given as an
argument, read back from the reports (counts, quality against the input surface, time).

    cargo build --release -p zipmesh-cli
    python3 scripts/results.py                        # the default command line
    python3 scripts/results.py --no-fold-guard        # any optimize options after the script
    python3 scripts/results.py --bin PATH -- FILE...  # another binary, other meshes

A mesh `optimize` refuses (a face of five or more corners) gets a row saying why; a mesh
of the kind an option does not apply to (`--no-fold-guard` on triangles) is left out. The last
column lists the bounds that fail (docs/results.md, "The bounds"): the geometry bounds as the
report's `bounds.failed` gives them (the library's `quality::Bounds`: for quads no more
folded quads or negative scaled Jacobians than the input, the scaled Jacobian's 1st
percentile at least min(input's, 0.3), every vertex within 1 % of the input's bounding-box
diagonal and the mean within 0.1 %, faces within 5 %; for triangles no new flipped
triangle, at most 0.1 % of the faces more triangles under 10 degrees, every vertex within
0.5 % of the diagonal), and the share cut, counted here: on a closed quad mesh at least
75 % of the removable singularities gone (those above the Gauss-Bonnet minimum 4|chi|), on
a triangle mesh at least 70 % of the irregular vertices.
"""

import json
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def singularities(c):
    """Interior irregular vertices of a quad report's counts, and the boundary defect."""
    if "irregular" in c:
        return f"{c['irregular']}"
    total = c["v2"] + c["v3"] + c["v5"] + c["v6plus"]
    bd = c["boundary_defects"]
    return f"{total}" + (f" (bd {bd})" if bd else "")


def pct(x):
    return "-" if x is None else f"{100 * x:.3f} %"


def number(x, digits):
    return "-" if x is None else f"{x:.{digits}f}"


def count(c):
    return c["v2"] + c["v3"] + c["v5"] + c["v6plus"]


# The library's bounds (`quality::Bounds`, reported as `bounds.failed`) by their table labels.
LABELS = {
    "folded_quads": "folds",
    "negative_scaled_jacobian": "SJ < 0",
    "scaled_jacobian_p1": "SJ 1st pct",
    "faces": "faces",
    "flipped_triangles": "flips",
    "thin_triangles": "thin",
    "distance": "distance",
}


def geometry_bounds(r):
    """The geometry bounds the report says fail, by their table labels."""
    return [LABELS.get(name, name) for name in r["bounds"]["failed"]]


def quad_bounds(r, topology):
    """The quad bounds that fail (their names), or "hold"."""
    failed = geometry_bounds(r)
    chi, loops = topology
    removable = count(r["input"]) - 4 * abs(chi)
    if loops == 0 and removable > 0:
        gone = (count(r["input"]) - count(r["final"])) / removable
        if gone < 0.75:
            failed.append(f"removable {100 * gone:.0f} %")
    return ", ".join(failed) or "hold"


def removable_cell(r, topology):
    chi, loops = topology
    removable = count(r["input"]) - 4 * abs(chi)
    if loops or removable <= 0:
        return "-"
    return f"{100 * (count(r['input']) - count(r['final'])) / removable:.0f} %"


def quad_row(name, r, topology):
    qi, qo = r["quality"]["input"], r["quality"]["output"]
    sj = lambda q: (q["scaled_jacobian"] or {}).get("p1")
    d = qo["distance"] or {}
    faces = f"{r['input']['faces']} -> {r['final']['faces']}"
    return (
        f"| {name} | {singularities(r['input'])} -> {singularities(r['final'])} | {faces} "
        f"| {qi['folded_quads']} -> {qo['folded_quads']} "
        f"| {qi['negative_scaled_jacobian']} -> {qo['negative_scaled_jacobian']} "
        f"| {number(sj(qi), 2)} -> {number(sj(qo), 2)} "
        f"| {pct(d.get('mean'))} / {pct(d.get('max'))} | {removable_cell(r, topology)} "
        f"| {r['seconds']:.1f} | {quad_bounds(r, topology)} |"
    )


def tri_bounds(r):
    failed = geometry_bounds(r)
    irregular = r["input"]["irregular"]
    if irregular and (irregular - r["final"]["irregular"]) / irregular < 0.7:
        failed.append("irregular cut")
    return ", ".join(failed) or "hold"


def tri_row(name, r):
    qi, qo = r["quality"]["input"], r["quality"]["output"]
    d = qo["distance"] or {}
    n = r["input"]["irregular"]
    cut = f" ({100 * (n - r['final']['irregular']) / n:.0f} % cut)" if n else ""
    faces = f"{r['input']['faces']} -> {r['final']['faces']}"
    return (
        f"| {name} | {n} -> {r['final']['irregular']}{cut} "
        f"| {faces} | {qi['thin_triangles']} -> {qo['thin_triangles']} "
        f"| {qi['flipped_triangles']} -> {qo['flipped_triangles']} "
        f"| {number(qi['min_angle_degrees'], 1)} -> {number(qo['min_angle_degrees'], 1)} "
        f"| {pct(d.get('mean'))} / {pct(d.get('max'))} | {r['seconds']:.1f} | {tri_bounds(r)} |"
    )


def topology(binary, f):
    """(Euler characteristic, boundary loops) from `zipmesh stats --json`."""
    run = subprocess.run(
        [str(binary), "stats", str(f), "--json"], capture_output=True, text=True, cwd=ROOT
    )
    s = json.loads(run.stdout) if run.returncode == 0 else {}
    return s.get("euler_characteristic", 0), s.get("boundary_loops", 1)


def main():
    args = sys.argv[1:]
    binary = ROOT / "target/release/zipmesh"
    if args[:1] == ["--bin"]:
        binary, args = Path(args[1]), args[2:]
    files = []
    if "--" in args:
        i = args.index("--")
        args, files = args[:i], [Path(f).resolve() for f in args[i + 1 :]]
    if not files:
        files = sorted(Path("tests/data").glob("[pqt]*/*.obj"), key=str)
    quads, tris = [], []
    with tempfile.TemporaryDirectory() as tmp:
        for f in files:
            name = f"{f.parent.name}/{f.name}"
            run = subprocess.run(
                [str(binary), "optimize", str(f), "-o", f"{tmp}/out.obj", "--json", *args],
                capture_output=True,
                text=True,
                cwd=ROOT,
            )
            if run.returncode != 0:
                why = run.stderr.strip().splitlines()[-1] if run.stderr.strip() else "?"
                if "applies to" in why:
                    continue  # an option for the other kind of mesh
                why = why.split(": ", 2)[-1]  # without "zipmesh: FILE: "
                quads.append(f"| {name} | refused: {why} |||||||||")
                continue
            r = json.loads(run.stdout)
            (tris if r.get("kind") == "triangle" else quads).append(
                tri_row(name, r)
                if r.get("kind") == "triangle"
                else quad_row(name, r, topology(binary, f))
            )
    given = " ".join(args) or "(defaults)"
    print(f"`zipmesh optimize IN -o OUT {given}`\n")
    print(
        "| mesh | singularities | faces | folded quads | scaled Jacobian < 0 "
        "| scaled Jacobian 1st pct | distance mean / max | removable gone | s | bounds |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|")
    print("\n".join(quads))
    if tris:
        print()
        print(
            "| triangle mesh | irregular vertices | faces | triangles under 10 deg | flipped "
            "| smallest angle (deg) | distance mean / max | s | bounds |"
        )
        print("|---|---|---|---|---|---|---|---|---|")
        print("\n".join(tris))


if __name__ == "__main__":
    main()
