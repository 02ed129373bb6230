"""The on-disk cache of what each collision mesh becomes (physics/convex_pieces.py).

Results are cached by the mesh file's content and scale, so a second spawn, in this world
or the next, reads one small file. A mesh over ``Limits.concave_mesh_triangles`` keeps
its hull unchecked (the check grows as triangles x hull vertices), with a warning.
"""

from __future__ import annotations

import hashlib
import json
import os
import tempfile
from dataclasses import dataclass, field
from typing import List, Optional, Sequence

import numpy as np

from ..description.limits import Limits
from .convex_pieces import CONCAVE_DEPTH, concavity, patch_hulls
from .mesh_hulls import hull_points, points_obj_text
from .mesh_reading import checked_triangles

VERSION = 7  # of the cached files' format; a change makes new ones (7: pieces cut at convex edges)
# A mesh of more triangles that collides as its hull is handed to pybullet as its hull's
# points (physics/mesh_hulls.py): pybullet's own hull of it would hold up the physics
# thread (45 ms for 20 k triangles, seconds for millions).
HULL_POINTS_ABOVE = 2000
# More pieces than this and pybullet's loader stalls (a 1446-piece file of a 20k-triangle
# bumpy part took minutes; 1300 of its pieces 0.2 s): the mesh collides as its hull.
MAX_PIECES = 1024


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


def obj_text(triangles: np.ndarray) -> str:
    """The triangles as one .obj object (each corner its own vertex)."""
    return ''.join('v %.9g %.9g %.9g\n' % tuple(v) for v in triangles.reshape(-1, 3)) + ''.join(
        'f %d %d %d\n' % (3 * i + 1, 3 * i + 2, 3 * i + 3) for i in range(len(triangles))
    )


@dataclass
class CollisionMesh:
    """What a collision mesh becomes: ``path`` to load (None: the mesh file as it is)."""

    path: Optional[str]
    concavity: float  # metres, at its scale (past CONCAVE_DEPTH: at least this)
    cached: bool  # read from the cache, nothing computed
    notes: List[str] = field(default_factory=list)  # what was wrong and done (no path)
    empty: bool = False  # no triangle left: nothing to collide with
    deferred: bool = False  # its hull for now: the pieces are still to be made


def collision_mesh(
    path: str,
    scale: Sequence[float],
    cache_dir: Optional[str] = None,
    limits: Optional[Limits] = None,
    defer_above: Optional[int] = None,
) -> CollisionMesh:
    """The mesh at ``path`` (scaled by ``scale``) as it should collide: its convex pieces
    when it is concave, else its hull: the file itself, or its checked triangles when the
    file had to be repaired (mesh_reading.checked_triangles), or for more than
    HULL_POINTS_ABOVE triangles its hull's points (physics/mesh_hulls.py). With
    ``defer_above``, a mesh of more triangles whose pieces are not cached yet is answered
    with its hull (``deferred``) and nothing is cached: a later call without it makes them.
    Raises MeshReadError for an unreadable mesh."""
    limits = limits or Limits()
    folder = cache_dir or default_cache_dir()
    with open(path, 'rb') as f:
        digest = hashlib.sha256(f.read()).hexdigest()
    key = hashlib.sha256(
        ('%s %d %r' % (digest, VERSION, tuple(float(s) for s in scale))).encode()
    ).hexdigest()[:32]
    info_path = os.path.join(folder, key + '.json')
    hulls_path = os.path.join(folder, key + '.obj')
    clean_path = os.path.join(folder, key + '.checked.obj')
    points_path = os.path.join(folder, key + '.hull.obj')
    known = _cached(info_path, hulls_path, clean_path, points_path)
    if known is not None:
        return known
    triangles, notes = checked_triangles(path)
    triangles = triangles * np.asarray(scale, dtype=np.float64)
    info = {'mesh': path, 'notes': notes, 'concave': False, 'depth': 0.0}
    if not len(triangles):
        info['empty'] = True
        _atomic_write(info_path, json.dumps(info))
        return CollisionMesh(None, 0.0, False, notes, empty=True)
    if len(triangles) > HULL_POINTS_ABOVE:  # its hull made here, not on the physics thread
        if not os.path.isfile(points_path):  # the spawn that deferred the pieces made it
            _atomic_write(points_path, points_obj_text(hull_points(triangles)))
        info['points'] = True
        hull: Optional[str] = points_path
    elif notes:  # pybullet is handed the repaired triangles, never the file
        _atomic_write(clean_path, obj_text(triangles))
        info['clean'] = True
        hull = clean_path
    else:
        hull = None
    if len(triangles) > limits.concave_mesh_triangles:
        # the check itself grows as triangles x hull vertices: not made past the limit
        notes.append(
            '%d triangles, over the limit concave_mesh_triangles (%d): it collides as '
            'its convex hull, concave or not' % (len(triangles), limits.concave_mesh_triangles)
        )
        _atomic_write(info_path, json.dumps(info))
        return CollisionMesh(hull, 0.0, False, notes)
    if defer_above is not None and len(triangles) > defer_above:
        return CollisionMesh(hull, 0.0, False, notes, deferred=True)
    depth = concavity(triangles, stop_above=CONCAVE_DEPTH)
    info['depth'] = depth
    if depth > CONCAVE_DEPTH:
        text, pieces = patch_hulls(triangles)
        if pieces <= MAX_PIECES:
            _atomic_write(hulls_path, text)
            info['concave'] = True
        else:
            notes.append(
                '%d convex pieces, more than pybullet loads in time (%d): it collides '
                'as its convex hull' % (pieces, MAX_PIECES)
            )
    _atomic_write(info_path, json.dumps(info))
    return CollisionMesh(hulls_path if info['concave'] else hull, depth, False, notes)


def _cached(
    info_path: str, hulls_path: str, clean_path: str, points_path: str
) -> Optional[CollisionMesh]:
    """What the cache holds for this mesh, None when it holds nothing whole."""
    try:
        with open(info_path) as f:
            info = json.load(f)
        notes = [str(n) for n in info['notes']]
        if info.get('empty'):
            return CollisionMesh(None, 0.0, True, notes, empty=True)
        hull = points_path if info.get('points') else clean_path if info.get('clean') else None
        if hull is not None and not os.path.exists(hull):
            return None
        if info['concave'] is False:
            return CollisionMesh(hull, info['depth'], True, notes)
        if os.path.exists(hulls_path):
            return CollisionMesh(hulls_path, info['depth'], True, notes)
    except (OSError, ValueError, KeyError, TypeError):
        pass
    return None
