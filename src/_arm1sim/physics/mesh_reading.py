"""Mesh files read into triangles: .stl (physics/stl.py), .obj (our reader: polygons as
fans), .dae (pycollada, node transforms and <unit meter> applied, as pybullet's loader
applies them).

Read checked (``checked_triangles``): pybullet crashes the world on a NaN vertex or an
out-of-range face index and makes a body with an infinite vertex fall through everything,
so what it is handed is repaired first: such triangles are left out, each kind of repair
said once.
"""

from __future__ import annotations

from typing import List, Optional, Tuple

import numpy as np

from ..description.mesh_limits import mesh_kind
from .stl import read_stl


class MeshReadError(ValueError):
    """The mesh cannot be read into triangles; the message names the file."""


def mesh_triangles(path: str) -> np.ndarray:
    """(n, 3, 3) finite triangles of an .stl, .obj or .dae file, in the file's units
    (COLLADA's <unit meter> and node transforms applied, as pybullet's loader applies
    them): what ``checked_triangles`` keeps."""
    return checked_triangles(path)[0]


def checked_triangles(path: str) -> Tuple[np.ndarray, List[str]]:
    """The mesh's triangles with every vertex finite and every face index in range, and
    what was repaired to get them: one message per kind of fault, saying how many were
    left out (the caller names the file: the cache keeps them by content, not by path).
    MeshReadError, naming the file, for a file that cannot be read at all."""
    kind = mesh_kind(path)
    notes: List[str] = []
    try:
        if kind == '.stl':
            triangles = read_stl(path)[0]
        elif kind == '.obj':
            triangles, bad = _obj_triangles(path)
            if bad:
                notes.append('%d faces name a vertex that is not in the file: left out' % bad)
        elif kind == '.dae':
            triangles, bad = _dae_triangles(path)
            if bad:
                notes.append('%d triangles name a vertex that is not in the file: left out' % bad)
        else:
            raise MeshReadError('%s: not an .stl, .obj or .dae mesh' % path)
    except (OSError, ValueError, IndexError) as exc:
        if isinstance(exc, MeshReadError):
            raise
        raise MeshReadError('%s: cannot read its triangles: %s' % (path, exc)) from None
    finite = np.isfinite(triangles).all(axis=(1, 2))
    if not finite.all():
        notes.append(
            '%d of %d triangles have a NaN or infinite vertex: left out'
            % (int((~finite).sum()), len(triangles))
        )
        triangles = triangles[finite]
    return triangles, notes


def _obj_triangles(path: str) -> Tuple[np.ndarray, int]:
    """The triangles and how many faces named a vertex the file does not have (0 is no
    OBJ index; a negative one counts back from the last vertex read)."""
    with open(path, 'rb') as f:
        fast = _plain_obj_triangles(f.read())
    if fast is not None:
        return fast
    vertices: List[Tuple[float, float, float]] = []
    faces: List[Tuple[int, int, int]] = []
    bad = 0
    with open(path, encoding='utf-8', errors='replace') as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == 'v' and len(parts) >= 4:
                vertices.append((float(parts[1]), float(parts[2]), float(parts[3])))
            elif parts[0] == 'f' and len(parts) >= 4:
                refs = []
                for ref in parts[1:]:
                    i = int(ref.split('/')[0])
                    refs.append(i - 1 if i > 0 else len(vertices) + i if i < 0 else -1)
                if min(refs) < 0 or max(refs) >= len(vertices):
                    bad += 1
                    continue
                for k in range(1, len(refs) - 1):  # a polygon as a fan
                    faces.append((refs[0], refs[k], refs[k + 1]))
    if not faces:
        return np.zeros((0, 3, 3)), bad
    return np.asarray(vertices, dtype=np.float64)[np.asarray(faces)], bad


def _plain_obj_triangles(data: bytes) -> Optional[Tuple[np.ndarray, int]]:
    """``_obj_triangles`` of a plain file, parsed by numpy (a fifth of the time line by
    line): every ``v`` line three numbers, every ``f`` line a triangle of positive vertex
    numbers without ``/``, no line indented, no tab. None for any other file."""
    if b'\t' in data or b'\n ' in data or data.startswith(b' '):
        return None
    lines = data.splitlines()
    vs = [line[2:] for line in lines if line[:2] == b'v ']
    fs = [line[2:] for line in lines if line[:2] == b'f ']
    faces = b' '.join(fs)
    if b'/' in faces or b'-' in faces:
        return None
    try:
        vertices = np.array(b' '.join(vs).split(), dtype=np.float64)
        index = np.array(faces.split(), dtype=np.int64) - 1
    except ValueError:
        return None
    if len(vertices) != 3 * len(vs) or len(index) != 3 * len(fs):
        return None
    vertices, index = vertices.reshape(-1, 3), index.reshape(-1, 3)
    ok = ((index >= 0) & (index < len(vertices))).all(axis=1)
    if not len(index):
        return np.zeros((0, 3, 3)), 0
    return vertices[index[ok]], int((~ok).sum())


def _dae_triangles(path: str) -> Tuple[np.ndarray, int]:
    """The triangles and how many named a vertex the file does not have."""
    import collada  # pycollada: only COLLADA meshes need it

    try:
        document = collada.Collada(
            path, ignore=[collada.common.DaeUnsupportedError, collada.common.DaeBrokenRefError]
        )
    except collada.common.DaeError as exc:
        raise ValueError(str(exc)) from None
    unit = float(getattr(document.assetInfo, 'unitmeter', None) or 1.0)
    out = []
    bad = 0
    if document.scene is not None:
        for geometry in document.scene.objects('geometry'):
            for primitive in geometry.primitives():
                if isinstance(primitive, collada.triangleset.BoundTriangleSet):
                    tris = primitive
                elif hasattr(primitive, 'triangleset'):
                    tris = primitive.triangleset()
                else:
                    continue  # lines and points have no surface
                if tris.vertex_index is None or not len(tris.vertex_index):
                    continue
                # pycollada refuses an index past its source (DaeMalformedError): kept as
                # a second guard, since pybullet would read past its arrays
                index = np.asarray(tris.vertex_index, dtype=np.int64).reshape(-1, 3)
                vertex = np.asarray(tris.vertex, dtype=np.float64).reshape(-1, 3)
                ok = ((index >= 0) & (index < len(vertex))).all(axis=1)
                bad += int((~ok).sum())
                if ok.any():
                    out.append(vertex[index[ok]])
    if not out:
        return np.zeros((0, 3, 3)), bad
    return np.concatenate(out) * unit, bad
