"""The on-disk cache of what each collision mesh becomes (physics/convex_pieces.py).

Results are cached by the mesh file's content and scale, so a second spawn, in this world
or the next, reads one small file. A mesh over ``Limits.concave_mesh_triangles`` keeps
its hull unchecked (the check grows as triangles x hull vertices), with a warning.
"""

from __future__ import annotations

import hashlib
import json
import logging
import os
import tempfile
from dataclasses import dataclass
from typing import Optional, Sequence

import numpy as np

from ..description.limits import Limits
from .convex_pieces import CONCAVE_DEPTH, concavity, patch_hulls
from .mesh_reading import mesh_triangles

log = logging.getLogger('_arm1sim.physics')

VERSION = 2  # of the cached files' format; a change makes new ones (2: convex patches)


def default_cache_dir() -> str:
    base = os.environ.get('XDG_CACHE_HOME') or os.path.join(os.path.expanduser('~'), '.cache')
    return os.path.join(base, 'arm1', 'collision_meshes')


def _atomic_write(path: str, text: str) -> None:
    """Whole or not at all, whoever else writes the same cache file at once."""
    folder = os.path.dirname(path)
    os.makedirs(folder, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=folder, prefix='.tmp-')
    with os.fdopen(fd, 'w') as f:
        f.write(text)
    os.replace(tmp, path)


@dataclass
class CollisionMesh:
    """What a collision mesh becomes: ``path`` to load (None: the mesh as it is)."""

    path: Optional[str]
    concavity: float  # metres, at its scale (past CONCAVE_DEPTH: at least this)
    cached: bool  # read from the cache, nothing computed


def collision_mesh(
    path: str,
    scale: Sequence[float],
    cache_dir: Optional[str] = None,
    limits: Optional[Limits] = None,
) -> CollisionMesh:
    """The mesh at ``path`` (scaled by ``scale``) as it should collide: its convex pieces
    when it is concave, else itself. Raises MeshReadError for an unreadable mesh."""
    limits = limits or Limits()
    folder = cache_dir or default_cache_dir()
    with open(path, 'rb') as f:
        digest = hashlib.sha256(f.read()).hexdigest()
    key = hashlib.sha256(
        ('%s %d %r' % (digest, VERSION, tuple(float(s) for s in scale))).encode()
    ).hexdigest()[:32]
    info_path = os.path.join(folder, key + '.json')
    hulls_path = os.path.join(folder, key + '.obj')
    try:
        with open(info_path) as f:
            info = json.load(f)
        if info['concave'] is False or os.path.exists(hulls_path):
            return CollisionMesh(hulls_path if info['concave'] else None, info['depth'], True)
    except (OSError, ValueError, KeyError):
        pass
    triangles = mesh_triangles(path) * np.asarray(scale, dtype=np.float64)
    if len(triangles) > limits.concave_mesh_triangles:
        # the check itself grows as triangles x hull vertices: not made past the limit
        log.warning(
            '%s: %d triangles, over the limit concave_mesh_triangles (%d): it collides as '
            'its convex hull, concave or not',
            path,
            len(triangles),
            limits.concave_mesh_triangles,
        )
        return CollisionMesh(None, 0.0, False)
    depth = concavity(triangles, stop_above=CONCAVE_DEPTH)
    concave = depth > CONCAVE_DEPTH
    if concave:
        _atomic_write(hulls_path, patch_hulls(triangles)[0])
    _atomic_write(info_path, json.dumps({'concave': bool(concave), 'depth': depth, 'mesh': path}))
    return CollisionMesh(hulls_path if concave else None, depth, False)
