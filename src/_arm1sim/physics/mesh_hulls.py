"""A dense mesh's convex hull made in numpy on the spawn caller's thread, so pybullet
builds it from a few points on the physics thread.

pybullet builds a mesh's hull from every vertex, inside ``loadURDF`` on the physics
thread, holding the GIL: 45 ms for 20 k triangles, 6-11 s for 2 M, while ``/clock``
stands still. Here the hull's points are the mesh's extreme points along DIRECTIONS
directions (a Fibonacci sphere plus the 26 of a box's faces, edges and corners), which
numpy finds with the GIL released; pybullet then builds the hull of at most that many
points (about 4 ms). The hull made is the exact hull's inner approximation: every point
is a vertex of the mesh, the bounding box is exact, and a smooth round part of radius r
comes out at most 0.0033 r inside (0.33 mm for a 10 cm part; pybullet adds
1 mm of margin outside).
"""

from __future__ import annotations

import itertools

import numpy as np

DIRECTIONS = 1000  # on the Fibonacci sphere, besides the 26 of the box
CHUNK = 4096  # points per numpy batch: CHUNK x directions floats at a time


def _directions() -> np.ndarray:
    i = np.arange(DIRECTIONS) + 0.5
    z = 1.0 - 2.0 * i / DIRECTIONS
    r = np.sqrt(1.0 - z * z)
    phi = np.pi * (1.0 + 5**0.5) * i
    sphere = np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)
    box = np.array([d for d in itertools.product((-1, 0, 1), repeat=3) if any(d)], dtype=float)
    box /= np.linalg.norm(box, axis=1)[:, None]
    return np.concatenate([box, sphere]).astype(np.float32)


def hull_points(triangles: np.ndarray) -> np.ndarray:
    """(k, 3) points of the triangles whose convex hull stands for theirs: all of their
    distinct corners when they are few, else the extreme ones along each direction."""
    corners = triangles.reshape(-1, 3)
    # distinct corners (an STL repeats each in ~6 triangles), by a 1-d key: numpy sorts
    # floats without the GIL, where rows (np.unique axis=0) would hold it
    key = corners @ np.array([1.0, np.sqrt(2.0) * 1e3, np.sqrt(3.0) * 1e6])
    _, first = np.unique(key, return_index=True)
    points = corners[first]
    directions = _directions()
    if len(points) <= len(directions):
        return points
    best = np.full(len(directions), -np.inf, dtype=np.float32)
    which = np.zeros(len(directions), dtype=np.int64)
    centred = (points - points.mean(axis=0)).astype(np.float32).T.copy()
    rows = np.arange(len(directions))
    for start in range(0, len(points), CHUNK):
        heights = directions @ centred[:, start : start + CHUNK]  # a row per direction
        top = heights.argmax(axis=1)
        value = heights[rows, top]
        better = value > best
        best[better] = value[better]
        which[better] = start + top[better]
    return points[np.unique(which)]


def points_obj_text(points: np.ndarray) -> str:
    """The points as an .obj whose hull is theirs: pybullet's OBJ loader takes the
    vertices its faces name, so one fan names them all."""
    return ''.join('v %.9g %.9g %.9g\n' % tuple(v) for v in points) + ''.join(
        'f 1 %d %d\n' % (i, i + 1) for i in range(2, len(points))
    )
