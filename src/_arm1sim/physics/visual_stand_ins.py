"""Large visual meshes kept out of the physics thread's pybullet load.

gzserver never reads a model's visual meshes: its clients draw them. pybullet parses every
``<visual>`` mesh inside ``loadURDF``, on the physics thread: 22 ms of CPU per MB of STL,
16 per MB of OBJ, 34 per MB of Collada, so a 200 k-triangle Collada export held ``/clock``
for 0.8 s of CPU (seconds of wall time on a busy machine). A visual mesh file over its
format's budget is handed to the physics client as a stand-in (a speck of a tetrahedron, the
``<visual>``'s origin, scale and material kept); the render processes (cameras) load the
URDF as written, off the physics thread, and the browser view is told the real file.
"""

from __future__ import annotations

import os
import tempfile
import xml.etree.ElementTree as ET
from typing import Dict, Tuple

from .stl import write_binary_stl

# bytes of a visual mesh file pybullet parses in about 50 ms of CPU (measured above)
VISUAL_LOAD_BUDGET = {'.stl': 2_500_000, '.obj': 3_000_000, '.dae': 1_500_000}
OTHER_BUDGET = 1_500_000
# The stand-in: a tetrahedron of 1 um (pybullet wants a mesh it can read)
_O, _X, _Y, _Z = (0.0, 0.0, 0.0), (1e-6, 0.0, 0.0), (0.0, 1e-6, 0.0), (0.0, 0.0, 1e-6)
SPECK = [(_O, _Y, _X), (_O, _X, _Z), (_O, _Z, _Y), (_X, _Y, _Z)]


def over_budget(path: str) -> bool:
    """True for a visual mesh file too large to parse on the physics thread."""
    try:
        size = os.path.getsize(path)
    except OSError:  # missing or unreadable: pybullet's own warning, as before
        return False
    return size > VISUAL_LOAD_BUDGET.get(os.path.splitext(path)[1].lower(), OTHER_BUDGET)


def light_visuals(urdf_xml: str, folder: str) -> Tuple[str, Dict[str, str]]:
    """``urdf_xml`` (mesh paths resolved) with each visual mesh over budget replaced by a
    stand-in file written in ``folder``, and {stand-in path: the real file}; the text as it
    was (and {}) when none is over."""
    root = ET.fromstring(urdf_xml)
    stand_ins: Dict[str, str] = {}
    for mesh in root.iterfind('link/visual/geometry/mesh'):
        path = mesh.get('filename', '')  # a plain path: resolve_mesh_uris made it one
        if not over_budget(path):
            continue
        fd, stand_in = tempfile.mkstemp(suffix='.stl', prefix='visual-stand-in-', dir=folder)
        os.close(fd)
        write_binary_stl(stand_in, SPECK)
        mesh.set('filename', stand_in)
        stand_ins[stand_in] = path
    if not stand_ins:
        return urdf_xml, {}
    return ET.tostring(root, encoding='unicode'), stand_ins
