"""Edit the singularities of quad, triangle and quad-dominant meshes.

A :class:`Mesh` holds positions and faces (numpy arrays in, numpy arrays out). Its reports
are the ``zipmesh`` command's ``--json`` output, parsed: each method writes the mesh to a
temporary binary PLY file (exact), runs the command in this process and reads the result
back. The keys ``file`` and ``output``, which would name those temporary files, are left
out; everything else is as the command prints it (docs/cli.md). Edits return a new mesh
and the report; the mesh they are called on is never changed.

Vertex and face numbers count from 0 in the order of :attr:`Mesh.vertices` and
:attr:`Mesh.faces`, as the command's do for a file.
"""

from __future__ import annotations

import json
import os
import tempfile
from typing import Any, Iterable, Optional, Sequence, Tuple

import numpy as np

from . import _zipmesh

__all__ = ["Mesh", "load", "run"]

__version__ = "0.1.0"

_PATH_KEYS = ("file", "output")


def run(args: Sequence[str]) -> str:
    """Run one ``zipmesh`` command (without the program's name) and return its output.

    The command reads and writes files as the binary does. The interpreter lock is released
    while it runs. A usage error or a refused edit raises ``ValueError`` with the command's
    message.
    """
    return _zipmesh.run([str(a) for a in args])


def load(path: "os.PathLike[str] | str") -> "Mesh":
    """Read a mesh from an .obj, .off or .ply file.

    Unreferenced vertices are dropped and the rest keep their order. Raises ``OSError``
    when the file cannot be read and ``ValueError`` when its content is not a mesh.
    """
    return Mesh._wrap(_zipmesh.load(os.fspath(path)))


def _strip(report: Any) -> Any:
    """The report without the keys that name the temporary files."""
    if isinstance(report, dict):
        for key in _PATH_KEYS:
            report.pop(key, None)
    return report


def _message(text: str) -> str:
    """A command's error as one sentence: clap's ``error:`` and its help hint dropped."""
    first = text.strip().splitlines()[0] if text.strip() else text
    return first[len("error: "):] if first.startswith("error: ") else first


def _opt(flag: str, value: Any) -> list:
    """``[flag, value]`` when a value is given, else nothing; lists are comma-joined."""
    if value is None:
        return []
    if isinstance(value, (list, tuple)):
        value = ",".join(str(int(v)) for v in value)
    return [flag, str(value)]


class Mesh:
    """A polygon mesh: triangles, quads or both (faces of any degree can be read).

    ``Mesh(vertices, faces)`` takes an (N, 3) float array of positions and an (F, k)
    integer array of faces, or a list of lists for faces of mixed degrees, with vertices
    numbered from 0 and each face counter-clockwise. Vertices no face uses are dropped (the
    others keep their order). Raises ``ValueError`` on a bad array or a non-manifold mesh.
    """

    __slots__ = ("_m",)

    def __init__(self, vertices: Any, faces: Any) -> None:
        self._m = _zipmesh.Mesh(vertices, faces)

    @classmethod
    def _wrap(cls, inner: "_zipmesh.Mesh") -> "Mesh":
        mesh = cls.__new__(cls)
        mesh._m = inner
        return mesh

    def __repr__(self) -> str:
        return f"<zipmesh.Mesh: {self._m.num_vertices} vertices, {self._m.num_faces} faces>"

    @property
    def vertices(self) -> np.ndarray:
        """The positions, an (N, 3) float64 array (a new copy at each access)."""
        return self._m.vertices

    @property
    def faces(self) -> "np.ndarray | list[list[int]]":
        """The faces: an (F, k) int64 array when all have k corners, else a list of lists."""
        polys = self._m.polygons()
        degrees = {len(p) for p in polys}
        if len(degrees) <= 1:
            k = degrees.pop() if degrees else 3
            return np.array(polys, dtype=np.int64).reshape(len(polys), k)
        return polys

    def save(self, path: "os.PathLike[str] | str", ascii: bool = False) -> None:
        """Write the mesh; the extension (.obj, .off, .ply) picks the format.

        ``ascii=True`` writes PLY as text (binary PLY is the default). The file appears
        whole or not at all. Raises ``OSError`` when it cannot be written.
        """
        self._m.save(os.fspath(path), ascii)

    # -- running the command -------------------------------------------------------------

    def _run(self, command: str, args: Iterable[str], output: Optional[str] = None) -> Tuple[Any, Optional["Mesh"]]:
        """Run ``zipmesh COMMAND <this mesh> ARGS --json``; the report and the written mesh."""
        with tempfile.TemporaryDirectory(prefix="zipmesh-") as tmp:
            src = os.path.join(tmp, "mesh.ply")
            self._m.save(src, False)
            argv = [command, src, *args]
            out = os.path.join(tmp, "out." + (output or "ply"))
            if output is not None:
                argv += ["-o", out]
            try:
                text = _zipmesh.run(argv)
            except ValueError as e:
                raise ValueError(_message(str(e)).replace(src, "mesh").replace(out, "output")) from None
            if output is None:
                return text, None
            if output != "ply":
                with open(out, "rb") as f:
                    return text, f.read()
            return text, Mesh._wrap(_zipmesh.load(out))

    def _report(self, command: str, *args: str) -> Any:
        text, _ = self._run(command, [*args, "--json"])
        return _strip(json.loads(text))

    def _edit(self, command: str, *args: str) -> Tuple["Mesh", dict]:
        text, mesh = self._run(command, [*args, "--json"], output="ply")
        return mesh, _strip(json.loads(text))

    # -- reports -------------------------------------------------------------------------

    def stats(self, reference: Optional["Mesh"] = None) -> dict:
        """``zipmesh stats --json``: counts, genus, histograms, Gauss-Bonnet, the canonical
        hash and the quality; the distances to ``reference``'s surface when given."""
        if reference is None:
            return self._report("stats")
        with tempfile.TemporaryDirectory(prefix="zipmesh-") as tmp:
            ref = os.path.join(tmp, "reference.ply")
            reference.save(ref)
            return self._report("stats", "--reference", ref)

    def quality(self, reference: Optional["Mesh"] = None) -> dict:
        """The ``quality`` object of :meth:`stats`: folded quads, scaled Jacobians, angles,
        edge ratios, and the distances to ``reference`` when given."""
        return self.stats(reference)["quality"]

    def singularities(self) -> dict:
        """``zipmesh singularities --json``: the mesh kind and every irregular vertex with
        its valence, place, defect and position."""
        return self._report("singularities")

    def moves(self, a: int, b: int, path: Optional[Sequence[int]] = None, preprocess: bool = False) -> list:
        """``zipmesh moves --json``: the four Q-zip movements (LS, RS, LC, RC) of the
        singularities ``a`` and ``b`` along ``path`` (default: a shortest path), each with
        whether it is realizable and what it would do."""
        args = ["--from", str(int(a)), "--to", str(int(b)), *_opt("--path", path)]
        return self._report("moves", *args, *(["--preprocess"] if preprocess else []))

    def partners(self, a: int, n: int = 5) -> list:
        """``zipmesh moves --partners N --json``: the ``n`` interior singularities nearest
        to ``a``, each with its distance and the movements realizable towards it."""
        return self._report("moves", "--from", str(int(a)), "--partners", str(int(n)))

    # -- edits ---------------------------------------------------------------------------

    def zip(
        self,
        a: int,
        b: int,
        move: str,
        path: Optional[Sequence[int]] = None,
        preprocess: bool = False,
        relax: bool = True,
    ) -> Tuple["Mesh", dict]:
        """``zipmesh zip --json``: move the pair ``a``, ``b`` of a quad mesh by one Q-zip.

        ``move`` is LS, RS, LC or RC (see :meth:`moves`). Returns the edited mesh
        (compacted) and the report, whose ``undo`` names the Q-zip that restores the input.
        ``relax=False`` keeps the raw placement. Raises ``ValueError`` when the movement is
        not realizable.
        """
        args = ["--from", str(int(a)), "--to", str(int(b)), "--move", str(move), *_opt("--path", path)]
        args += (["--preprocess"] if preprocess else []) + ([] if relax else ["--no-relax"])
        return self._edit("zip", *args)

    @staticmethod
    def _tri_relax(relax: Optional[str], rings: int) -> list:
        if relax is None:
            return ["--no-relax"]
        return ["--relax", relax, "--rings", str(int(rings))]

    def tri_move(
        self, pair: Sequence[int], direction: int, steps: int = 1, relax: Optional[str] = "surface", rings: int = 2
    ) -> Tuple["Mesh", dict]:
        """``zipmesh tri-move --json``: move a 5-7 pair (or a 5-5, 7-7 pair) of a triangle
        mesh ``steps`` steps in ``direction`` (0 to 5). ``relax`` is "surface", "local",
        "global" or None (keep the operators' placement)."""
        args = [*_opt("--pair", pair), "--direction", str(int(direction)), "--steps", str(int(steps))]
        return self._edit("tri-move", *args, *self._tri_relax(relax, rings))

    def tri_generate(
        self,
        at: int,
        toward: Optional[int] = None,
        config: str = "flip",
        apart: Optional[int] = None,
        direction: Optional[int] = None,
        relax: Optional[str] = "surface",
        rings: int = 2,
    ) -> Tuple["Mesh", dict]:
        """``zipmesh tri-generate --json``: a 5-5-7-7 quadruple at a regular vertex ``at`` of
        a triangle mesh (a triple at a v5 or v7); ``apart`` and ``direction`` walk one pair
        away."""
        args = ["--at", str(int(at)), "--config", config, *_opt("--toward", toward)]
        args += _opt("--apart", apart) + _opt("--direction", direction)
        return self._edit("tri-generate", *args, *self._tri_relax(relax, rings))

    def tri_type(
        self,
        split: Optional[int] = None,
        aggregate: Optional[Sequence[int]] = None,
        relax: Optional[str] = "surface",
        rings: int = 2,
    ) -> Tuple["Mesh", dict]:
        """``zipmesh tri-type --json``: split an irregular vertex's type (``split``) or
        aggregate v5s or v7s into one vertex (``aggregate``); give exactly one."""
        args = _opt("--split", split) + _opt("--aggregate", aggregate)
        return self._edit("tri-type", *args, *self._tri_relax(relax, rings))

    def tri_cancel(
        self,
        quadruple: Optional[Sequence[int]] = None,
        triple: Optional[Sequence[int]] = None,
        relax: Optional[str] = "surface",
        rings: int = 2,
    ) -> Tuple["Mesh", dict]:
        """``zipmesh tri-cancel --json``: cancel a 5-5-7-7 ``quadruple`` or reduce a 5-5-7 /
        5-7-7 ``triple`` to one singularity; give exactly one."""
        args = _opt("--quadruple", quadruple) + _opt("--triple", triple)
        return self._edit("tri-cancel", *args, *self._tri_relax(relax, rings))

    def qd_walk(
        self,
        triangle: int,
        moves: Optional[Sequence[str]] = None,
        tip: Optional[int] = None,
        steps: int = 1,
        to: Optional[int] = None,
    ) -> Tuple["Mesh", dict]:
        """``zipmesh qd-walk --json``: move a triangle of a quad-dominant mesh by ``moves``
        (VE, EV, LE, RE), ``steps`` times, or walk its tip to vertex ``to``."""
        args = ["--triangle", str(int(triangle)), *_opt("--tip", tip), *_opt("--to", to)]
        if moves is not None:
            args += ["--move", ",".join(moves)]
        if to is None:
            args += ["--steps", str(int(steps))]
        return self._edit("qd-walk", *args)

    def optimize(
        self,
        batches: Optional[int] = None,
        time_limit: Optional[float] = None,
        seed: int = 0,
        smooth: bool = True,
        fold_guard: bool = True,
        paths: bool = False,
    ) -> Tuple["Mesh", dict]:
        """``zipmesh optimize --json``: reduce the singularities by batches of Q-zips (quad and
        quad-dominant meshes) or the triangle paper's moves (triangle meshes).

        ``batches`` caps the batches, ``time_limit`` (seconds, quad meshes) stops between
        candidates, ``seed`` fixes the sampling (the same seed gives the same mesh).
        ``smooth=False`` skips the smoothing, ``fold_guard=False`` lets edits fold quads,
        ``paths=True`` adds each batch's surgery paths. The interpreter lock is released
        while it runs. The report's ``seconds`` are this run's timings.
        """
        args = _opt("--batches", batches) + _opt("--time-limit", time_limit) + ["--seed", str(int(seed))]
        args += ([] if smooth else ["--no-smooth"]) + ([] if fold_guard else ["--no-fold-guard"])
        args += ["--paths"] if paths else []
        return self._edit("optimize", *args)

    # -- pictures ------------------------------------------------------------------------

    def _render(self, ext: str, view: Optional[Tuple[float, float]], size: Tuple[int, int], paths: Any) -> bytes:
        args = ["--size", f"{int(size[0])},{int(size[1])}"]
        if view is not None:
            args += ["--view", f"{float(view[0])},{float(view[1])}"]
        with tempfile.TemporaryDirectory(prefix="zipmesh-") as tmp:
            if paths is not None:
                report = os.path.join(tmp, "paths.json")
                with open(report, "w") as f:
                    json.dump(paths, f)
                args += ["--paths", report]
            _, picture = self._run("render", args, output=ext)
        return picture

    def render_svg(
        self, view: Optional[Tuple[float, float]] = None, size: Tuple[int, int] = (800, 600), paths: Any = None
    ) -> str:
        """``zipmesh render``: an SVG picture (shaded faces, edges, the seen interior
        singularities as balls). ``view`` is (azimuth, elevation) in degrees, ``size``
        (width, height) in pixels; ``paths`` a report of :meth:`zip` or :meth:`optimize`
        (``paths=True``) whose surgery paths are drawn."""
        return self._render("svg", view, size, paths).decode("utf-8")

    def render_png(
        self, view: Optional[Tuple[float, float]] = None, size: Tuple[int, int] = (800, 600), paths: Any = None
    ) -> bytes:
        """``zipmesh render``: the picture of :meth:`render_svg` as PNG bytes."""
        return self._render("png", view, size, paths)

    # -- other libraries -----------------------------------------------------------------

    def to_trimesh(self) -> Any:
        """A ``trimesh.Trimesh`` of the same vertices and faces (quads are split into two
        triangles by trimesh); needs trimesh installed."""
        trimesh = _need("trimesh")
        return trimesh.Trimesh(vertices=self.vertices, faces=self._m.polygons(), process=False)

    def to_pyvista(self) -> Any:
        """A ``pyvista.PolyData`` of the same vertices and faces; needs pyvista installed."""
        pyvista = _need("pyvista")
        cells = [x for p in self._m.polygons() for x in (len(p), *p)]
        return pyvista.PolyData(self.vertices, np.array(cells, dtype=np.int64))

    def to_meshio(self) -> Any:
        """A ``meshio.Mesh`` with one cell block per face degree ("triangle", "quad",
        "polygon"); needs meshio installed."""
        meshio = _need("meshio")
        blocks: dict = {}
        for p in self._m.polygons():
            blocks.setdefault(len(p), []).append(p)
        names = {3: "triangle", 4: "quad"}
        cells = [(names.get(k, "polygon"), np.array(v, dtype=np.int64)) for k, v in sorted(blocks.items())]
        return meshio.Mesh(self.vertices, cells)


def _need(name: str) -> Any:
    """Import ``name`` or raise ``ImportError`` saying how to install it."""
    import importlib

    try:
        return importlib.import_module(name)
    except ImportError as e:
        raise ImportError(f"this needs the package {name!r}: pip install {name}") from e
