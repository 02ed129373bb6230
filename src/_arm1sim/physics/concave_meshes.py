"""The URDF pass: each concave ``<collision>`` mesh replaced by its convex pieces
(physics/convex_pieces.py, through the cache of physics/mesh_cache.py), as ODE's trimeshes
collide in Gazebo; visuals are left alone."""

from __future__ import annotations

import logging
import re
import xml.etree.ElementTree as ET
from typing import Optional

from ..description import safe_xml
from ..description.limits import Limits
from .mesh_cache import collision_mesh
from .mesh_reading import MeshReadError

log = logging.getLogger('_arm1sim.physics')

_SCALE = re.compile(r'\s+')


def concave_collisions(
    urdf_text: str, cache_dir: Optional[str] = None, limits: Optional[Limits] = None
) -> str:
    """The URDF with each concave ``<collision>`` mesh (absolute paths: resolve_mesh_uris
    ran) replaced by its convex pieces; visuals are left alone."""
    root = safe_xml.parse_trusted(urdf_text)
    changed = False
    for link in root.findall('link'):
        for mesh in link.findall('collision/geometry/mesh'):
            filename = mesh.get('filename', '')
            text = (mesh.get('scale') or '1 1 1').strip()
            try:
                scale = [float(v) for v in _SCALE.split(text)]
                if len(scale) != 3:
                    raise ValueError(text)
                result = collision_mesh(filename, scale, cache_dir, limits)
            except (MeshReadError, ValueError, OSError) as exc:
                log.warning(
                    "link '%s': mesh %s collides as its convex hull: %s",
                    link.get('name'),
                    filename,
                    exc,
                )
                continue
            if result.path is not None:
                mesh.set('filename', result.path)
                mesh.set('scale', '1 1 1')  # the hulls are written at the mesh's scale
                changed = True
    return ET.tostring(root, encoding='unicode') if changed else urdf_text
