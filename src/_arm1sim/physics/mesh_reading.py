"""Mesh files read into triangles: .stl (physics/stl.py), .obj (our reader: polygons as
fans), .dae (pycollada, node transforms and <unit meter> applied, as pybullet's loader
applies them)."""

from __future__ import annotations

from typing import List, Tuple

import numpy as np

from ..description.mesh_limits import mesh_kind
from .stl import read_stl


class MeshReadError(ValueError):
    """The mesh cannot be read into triangles; the message names the file."""


def mesh_triangles(path: str) -> np.ndarray:
    """(n, 3, 3) triangles of an .stl, .obj or .dae file, in the file's units (COLLADA's
    <unit meter> and node transforms applied, as pybullet's loader applies them)."""
    kind = mesh_kind(path)
    try:
        if kind == '.stl':
            return read_stl(path)[0]
        if kind == '.obj':
            return _obj_triangles(path)
        if kind == '.dae':
            return _dae_triangles(path)
    except (OSError, ValueError, IndexError) as exc:
        raise MeshReadError('%s: cannot read its triangles: %s' % (path, exc)) from None
    raise MeshReadError('%s: not an .stl, .obj or .dae mesh' % path)


def _obj_triangles(path: str) -> np.ndarray:
    vertices: List[Tuple[float, float, float]] = []
    faces: List[Tuple[int, int, int]] = []
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
                    refs.append(i - 1 if i > 0 else len(vertices) + i)
                for k in range(1, len(refs) - 1):  # a polygon as a fan
                    faces.append((refs[0], refs[k], refs[k + 1]))
    if not faces:
        return np.zeros((0, 3, 3))
    return np.asarray(vertices, dtype=np.float64)[np.asarray(faces)]


def _dae_triangles(path: str) -> np.ndarray:
    import collada  # pycollada: only COLLADA meshes need it

    try:
        document = collada.Collada(
            path, ignore=[collada.common.DaeUnsupportedError, collada.common.DaeBrokenRefError]
        )
    except collada.common.DaeError as exc:
        raise ValueError(str(exc)) from None
    unit = float(getattr(document.assetInfo, 'unitmeter', None) or 1.0)
    out = []
    if document.scene is not None:
        for geometry in document.scene.objects('geometry'):
            for primitive in geometry.primitives():
                if isinstance(primitive, collada.triangleset.BoundTriangleSet):
                    tris = primitive
                elif hasattr(primitive, 'triangleset'):
                    tris = primitive.triangleset()
                else:
                    continue  # lines and points have no surface
                if len(tris.vertex_index):
                    out.append(np.asarray(tris.vertex, dtype=np.float64)[tris.vertex_index])
    if not out:
        return np.zeros((0, 3, 3))
    return np.concatenate(out) * unit
