"""Cross-checks zipmesh's PLY against an independent reader and writer (plyfile).

Run: python3 -m venv /tmp/venv && /tmp/venv/bin/pip install plyfile numpy &&
cargo build --release -p zipmesh-cli && /tmp/venv/bin/python scripts/ply_crosscheck.py

plyfile reads what zipmesh writes; zipmesh reads what plyfile writes (binary big- and
little-endian and ASCII, float64 coordinates among extra properties, ushort corner indices
under the name vertex_index) and must give the canonical hash of the OBJ it came from.
"""
import subprocess, sys, numpy as np
from plyfile import PlyData, PlyElement
import os
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
Z = os.path.join(ROOT, "target/release/zipmesh")
src = os.path.join(ROOT, "tests/data/quad/spot_quadrangulated.obj")
V, F = [], []
for line in open(src):
    t = line.split()
    if not t: continue
    if t[0] == "v": V.append([float(x) for x in t[1:4]])
    if t[0] == "f": F.append([int(x.split("/")[0]) - 1 for x in t[1:]])
V = np.array(V); F = np.array(F)
# 1. zipmesh writes binary little-endian PLY (one optimizer batch, so it writes its own file).
out = "/tmp/spot_zm.ply"
subprocess.run([Z, "optimize", src, "-o", out, "--batches", "1"], check=True, capture_output=True)
d = PlyData.read(out)
print("zipmesh-written read by plyfile:", d.elements[0].count, "vertices,", d.elements[1].count, "faces, format", "binary" if not d.text else "ascii", d.byte_order)
# 2. plyfile writes big-endian float32 with normals and a colour, faces as vertex_index with ushort
vert = np.zeros(len(V), dtype=[("x","f8"),("nx","f4"),("y","f8"),("z","f8"),("red","u1")])
vert["x"], vert["y"], vert["z"] = V[:,0], V[:,1], V[:,2]
face = np.empty(len(F), dtype=[("vertex_index","O"),("flag","i4")])
face["vertex_index"] = [np.array(f, dtype="u2") for f in F]; face["flag"] = 1
for text, order in [(False, ">"), (False, "<"), (True, "=")]:
    p = f"/tmp/spot_pf_{'ascii' if text else order.replace('>','be').replace('<','le')}.ply"
    PlyData([PlyElement.describe(vert, "vertex", len_types={"vertex_index":"u1"}),
             PlyElement.describe(face, "face", val_types={"vertex_index":"u2"}, len_types={"vertex_index":"u1"})],
            text=text, byte_order=order).write(p)
    a = subprocess.run([Z, "hash", p], capture_output=True, text=True)
    b = subprocess.run([Z, "hash", src], capture_output=True, text=True)
    same = a.returncode == 0 and a.stdout.split()[0] == b.stdout.split()[0]
    print(p, "hash equals the OBJ's:", same, a.stderr.strip()[:200])
    if not same:
        sys.exit(1)
