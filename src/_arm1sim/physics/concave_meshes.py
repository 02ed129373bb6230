"""The URDF pass: each concave ``<collision>`` mesh replaced by its convex pieces
(physics/convex_pieces.py, through the cache of physics/mesh_cache.py), as ODE's trimeshes
collide in Gazebo; visuals are left alone."""

from __future__ import annotations

import logging
import re
import xml.etree.ElementTree as ET
from typing import List, Optional, Tuple

from ..description import safe_xml
from ..description.limits import Limits
from .mesh_cache import collision_mesh, default_cache_dir
from .mesh_jobs import fill_later
from .mesh_reading import MeshReadError

log = logging.getLogger('_arm1sim.physics')

_SCALE = re.compile(r'\s+')
# A mesh of more triangles whose pieces are not cached collides as its hull at once; a
# process of its own makes them for the next spawn (physics/mesh_jobs.py). arm1's links
# (396-592 triangles) take 0.1 s each; 2000 take about 0.5 s.
INLINE_TRIANGLES = 2000


def concave_collisions(
    urdf_text: str,
    cache_dir: Optional[str] = None,
    limits: Optional[Limits] = None,
    inline_triangles: Optional[int] = INLINE_TRIANGLES,
) -> str:
    """The URDF with each concave ``<collision>`` mesh (absolute paths: resolve_mesh_uris
    ran) replaced by its convex pieces, each repaired one by its checked triangles, and
    each without a triangle to collide with (or unreadable) left out with a warning (the
    link keeps its inertia); visuals are left alone. Meshes over ``inline_triangles``
    whose pieces are not cached keep their hull and get them made off this process
    (None: made here, however long it takes)."""
    root = safe_xml.parse_trusted(urdf_text)
    folder = cache_dir or default_cache_dir()
    changed = False
    later: List[Tuple[str, Tuple[float, float, float]]] = []
    for link in root.findall('link'):
        name = link.get('name')
        for collision in link.findall('collision'):
            mesh = collision.find('geometry/mesh')
            if mesh is None:
                continue
            filename = mesh.get('filename', '')
            text = (mesh.get('scale') or '1 1 1').strip()
            try:
                scale = [float(v) for v in _SCALE.split(text)]
                if len(scale) != 3:
                    raise ValueError(text)
                result = collision_mesh(filename, scale, folder, limits, inline_triangles)
            except (MeshReadError, ValueError, OSError) as exc:
                log.warning(
                    "link '%s': collision mesh %s left out (the link keeps its inertia and "
                    'collides with nothing): %s',
                    name,
                    filename,
                    exc,
                )
                link.remove(collision)
                changed = True
                continue
            for note in result.notes:
                log.warning("link '%s': collision mesh %s: %s", name, filename, note)
            if result.empty:
                log.warning(
                    "link '%s': collision mesh %s has no triangle to collide with: left out "
                    '(the link keeps its inertia and collides with nothing)',
                    name,
                    filename,
                )
                link.remove(collision)
                changed = True
                continue
            if result.deferred:
                later.append((filename, (scale[0], scale[1], scale[2])))
            if result.path is not None:
                mesh.set('filename', result.path)
                mesh.set('scale', '1 1 1')  # written at the mesh's scale
                changed = True
    if later:
        fill_later(later, folder, limits or Limits())
    return ET.tostring(root, encoding='unicode') if changed else urdf_text
