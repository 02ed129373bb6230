"""Dense concave meshes of our own making, as a CAD export of a curved part: a U-shaped
bracket (40 x 30 x 20 mm, a 20 mm slot) whose every face is a grid of triangles bulged by
a fraction of a millimetre, so no two neighbours are coplanar (many convex pieces, as a
SolidWorks export of fillets and curved faces). Written as .stl, .obj or .dae; used by
``make bench`` (the cache's first fill) and the cold-spawn tests.
"""

from __future__ import annotations

import math
from typing import List

import numpy as np

W, H, T, D = 0.04, 0.03, 0.01, 0.02  # width, height, prong thickness, depth (m)
BULGE = 0.0003  # m: how far a face's middle stands out of its plane


def _face(origin, u, v, normal, k: int) -> List[np.ndarray]:
    """A k x k grid of quads over the parallelogram origin + s u + t v, bulged along
    ``normal`` (its outward side), as triangles wound outward."""
    o, u, v, n = (np.asarray(x, dtype=float) for x in (origin, u, v, normal))
    s = np.linspace(0.0, 1.0, k + 1)
    grid = o + s[:, None, None] * u + s[None, :, None] * v
    bump = np.sin(math.pi * s)[:, None] * np.sin(math.pi * s)[None, :]
    grid = grid + BULGE * bump[:, :, None] * n
    a, b = grid[:-1, :-1], grid[1:, :-1]
    c, d = grid[1:, 1:], grid[:-1, 1:]
    tris = np.concatenate(
        [
            np.stack([a, b, c], axis=2).reshape(-1, 3, 3),
            np.stack([a, c, d], axis=2).reshape(-1, 3, 3),
        ]
    )
    if np.dot(np.cross(u, v), n) < 0:
        tris = tris[:, ::-1]
    return [tris]


def u_bracket(triangles: int = 20000) -> np.ndarray:
    """(n, 3, 3) triangles (metres) of the bracket, about ``triangles`` of them (at least
    the number asked for, within a few percent)."""
    outline = [(0, 0), (W, 0), (W, H), (W - T, H), (W - T, T), (T, T), (T, H), (0, H)]
    ends = ((0, 0, T, H), (T, 0, W - T, T), (W - T, 0, W, H))  # the end faces as 3 rectangles
    faces = len(outline) + 2 * len(ends)
    k = max(1, math.ceil(math.sqrt(triangles / (2.0 * faces))))
    out: List[np.ndarray] = []
    for i, (x0, z0) in enumerate(outline):
        x1, z1 = outline[(i + 1) % len(outline)]
        edge = np.array([x1 - x0, 0.0, z1 - z0])
        normal = np.array([edge[2], 0.0, -edge[0]])  # the outline runs counter-clockwise
        out += _face((x0, 0, z0), edge, (0, D, 0), normal / np.linalg.norm(normal), k)
    for x0, z0, x1, z1 in ends:
        out += _face((x0, 0, z0), (x1 - x0, 0, 0), (0, 0, z1 - z0), (0, -1, 0), k)
        out += _face((x0, D, z0), (x1 - x0, 0, 0), (0, 0, z1 - z0), (0, 1, 0), k)
    return np.concatenate(out)


def write_mesh(path: str, triangles: np.ndarray) -> None:
    """The triangles (metres) as .stl, .obj or .dae (in millimetres, <unit meter="0.001">),
    by the path's extension."""
    if path.lower().endswith('.stl'):
        from ..physics.stl import write_binary_stl  # numpy-stl: STL only (rostests lack it)

        write_binary_stl(path, triangles, 'dense mesh by _arm1sim.bench.dense_meshes')
    elif path.lower().endswith('.obj'):
        with open(path, 'w') as f:
            f.writelines('v %.9g %.9g %.9g\n' % tuple(v) for v in triangles.reshape(-1, 3))
            f.writelines(
                'f %d %d %d\n' % (3 * i + 1, 3 * i + 2, 3 * i + 3) for i in range(len(triangles))
            )
    elif path.lower().endswith('.dae'):
        flat = ' '.join('%.9g' % v for v in (triangles * 1000.0).reshape(-1))
        index = ' '.join(str(i) for i in range(3 * len(triangles)))
        with open(path, 'w') as f:
            f.write(
                '<?xml version="1.0"?><COLLADA xmlns="http://www.collada.org/2005/11/'
                'COLLADASchema" version="1.4.1"><asset><unit meter="0.001"/><up_axis>Z_UP'
                '</up_axis></asset><library_geometries><geometry id="g"><mesh><source id="p">'
                '<float_array id="pa" count="%d">%s</float_array><technique_common>'
                '<accessor source="#pa" count="%d" stride="3"><param name="X" type="float"/>'
                '<param name="Y" type="float"/><param name="Z" type="float"/></accessor>'
                '</technique_common></source><vertices id="v"><input semantic="POSITION" '
                'source="#p"/></vertices><triangles count="%d"><input semantic="VERTEX" '
                'source="#v" offset="0"/><p>%s</p></triangles></mesh></geometry>'
                '</library_geometries><library_visual_scenes><visual_scene id="s"><node id="n">'
                '<instance_geometry url="#g"/></node></visual_scene></library_visual_scenes>'
                '<scene><instance_visual_scene url="#s"/></scene></COLLADA>'
                % (triangles.size, flat, 3 * len(triangles), len(triangles), index)
            )
    else:
        raise ValueError('%s: not .stl, .obj or .dae' % path)


def cube_grid_stl(path: str, count: int, size: float = 0.002) -> np.ndarray:
    """``count`` cubes of 12 triangles on a 3-d grid (2 mm apart), written as a binary STL
    by numpy alone (a 2 M-triangle file in well under a second; rostests lack numpy-stl).
    Returns the grid's extent (m) along x, y, z."""
    corner = np.array([(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    cube = np.array([corner[list(t)] for a, b, d, e in quads for t in ((a, b, d), (a, d, e))])
    side = int(np.ceil(count ** (1 / 3)))
    at = np.stack(np.unravel_index(np.arange(count), (side,) * 3), axis=1) * 2 * size
    tris = (cube[None] * size + at[:, None, None, :]).reshape(-1, 3, 3).astype(np.float32)
    record = np.dtype([('n', '<f4', 3), ('v', '<f4', (3, 3)), ('a', '<u2')])
    data = np.zeros(len(tris), dtype=record)
    data['v'] = tris
    with open(path, 'wb') as f:
        f.write(b'cube grid by _arm1sim.bench.dense_meshes'.ljust(80))
        f.write(np.uint32(len(tris)).tobytes())
        data.tofile(f)
    return np.ptp(tris.reshape(-1, 3), axis=0)
