#!/usr/bin/env python3
"""The optimizer's robustness meshes (issue 45; the Q-zip paper's Fig. 17 starts from such
meshes): a smooth union of g tori (g = 3 in a row, g = 4 in a square), triangulated by
marching cubes (scikit-image) into a closed triangle mesh of genus g. One Catmull-Clark
step (the `catmull_clark` example) makes it a quad mesh whose every face centre is a v3.

    pip install numpy scikit-image
    python3 scripts/robust_meshes.py OUTDIR        # OUTDIR/g3.obj (7,004 triangles), g4.obj (8,912)
    cargo run --release --example catmull_clark -- OUTDIR/g3.obj OUTDIR/g3cc.obj
"""
import sys

import numpy as np
from skimage import measure


def torus_sdf(p, c, big=1.0, small=0.42):
    q = p - c
    a = np.sqrt(q[..., 0] ** 2 + q[..., 1] ** 2) - big
    return np.sqrt(a ** 2 + q[..., 2] ** 2) - small


def smooth_min(a, b, k=0.25):
    h = np.clip(0.5 + 0.5 * (b - a) / k, 0, 1)
    return b * (1 - h) + a * h - k * h * (1 - h)


def write(path, centres, n):
    lo = centres.min(0) - 1.6
    hi = centres.max(0) + 1.6
    lo[2], hi[2] = -0.8, 0.8
    step = (hi - lo).max() / n
    axes = [np.arange(lo[i], hi[i] + step, step) for i in range(3)]
    p = np.stack(np.meshgrid(*axes, indexing="ij"), -1)
    d = torus_sdf(p, centres[0])
    for c in centres[1:]:
        d = smooth_min(d, torus_sdf(p, c))
    verts, faces, _, _ = measure.marching_cubes(d, 0.0, spacing=(step,) * 3)
    verts += lo
    with open(path, "w") as out:
        out.write("# %d tori, marching cubes at %d cells across (scripts/robust_meshes.py)\n" % (len(centres), n))
        for v in verts:
            out.write("v %.6f %.6f %.6f\n" % tuple(v))
        for f in faces:
            out.write("f %d %d %d\n" % tuple(f + 1))
    print(path, len(verts), "vertices", len(faces), "triangles")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "."
    row = np.array([[1.7 * i, 0.0, 0.0] for i in range(3)])
    square = np.array([[1.7 * (i % 2), 1.7 * (i // 2), 0.0] for i in range(4)])
    write(out + "/g3.obj", row, 54)
    write(out + "/g4.obj", square, 41)


if __name__ == "__main__":
    main()
