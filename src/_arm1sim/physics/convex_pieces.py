"""Concave meshes cut into thin convex pieces that collide as their triangles do, as ODE's
trimeshes in Gazebo.

pybullet gives a mesh on a link its convex hull (a U-shaped finger collides as a block; a
pad slanted by the hull squeezes a box out). Its exact triangle mesh (``concave="yes"``)
collides with no other concave shape, the ground plane included. So a concave mesh becomes
a compound of thin convex prisms, written as one .obj object each, which pybullet's URDF
loader turns into a compound of hulls: exact on every face, and colliding with anything.

Each prism covers one convex patch of the surface: edge-adjacent triangles whose vertices
all stand behind every patch triangle's plane (within TOLERANCE), no deeper than THICKNESS
below any of them, with a convex outline. A flat CAD face of many triangles is one patch,
a curved one a few; each piece costs the physics step a little (compound children), so
fewer pieces make a cheaper step (arm1's links: 396-592 triangles, 64-87 pieces).

pybullet inflates each hull by its collision margin (1 mm). Each patch is moved inward by
half of it, so contacts and rays both see the surface within 0.5 mm (contacts 0.5 mm out,
rays 0.5 mm in), plus up to TOLERANCE on a curved patch. At a convex edge a prism's side
would stand in the next face's plane and its margin a full millimetre out of it, so each
prism is also cut SHRINK behind the plane of every neighbouring face the patch lies behind
(turning by more than 25 degrees):
a piece plus its margin stays within SHRINK of the surface everywhere (Niryo One's hand and
forearm, 1.75 mm apart, touched at such edges; Gazebo's trimeshes don't). Each prism is
thin (about 2 mm with its margin): a body pushed deeper than that into a face passes
through it, where ODE's trimesh would push it back out.

A mesh is concave when some point of its hull stands more than CONCAVE_DEPTH out of a
face's plane; a convex one (or one within that depth of convex) keeps pybullet's hull and
costs nothing but its check (physics/mesh_cache.py keeps both answers).
"""

from __future__ import annotations

import os
import tempfile
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np
import pybullet as p

MARGIN = 0.001  # pybullet's collision margin of a URDF mesh's hulls (gUrdfDefaultCollisionMargin)
SHRINK = MARGIN / 2  # each triangle moved inward by this: rays and contacts both off by half
CONCAVE_DEPTH = 0.0005  # m: a hull standing out less than this from the faces counts as convex
THICKNESS = 0.002  # m: how deep each triangle's prism reaches into the body
TOLERANCE = 0.0002  # m: how far a patch's vertex may stand in front of its own planes
PATCH_CONE = 0.5  # cos 60 degrees: the most a patch's triangle may turn from its seed's
FLAT_COS = 0.9999  # normals this close (under ~0.8 degrees) may be one flat face
PATCH_TRIANGLES = 256  # a patch grows no bigger (a flat face of more stays whole)
WELD = 1e-7  # m: corners closer than this are one vertex (and a cut shallower is none)
TOUCH = 1e-6  # m: a corner this close to a triangle lies on it
# cos 25 degrees: a smoother turn is not cut (its uncut side stands at most
# SHRINK * (1 - cos) = 0.05 mm further out than the faces), so a curved surface's many
# gentle edges cost nothing
SMOOTH_TURN = 0.906
CHUNK = 1 << 22  # face x hull-vertex products per numpy batch of the concavity check


def _normals(triangles: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """Unit normals and a mask of the triangles that have one (not degenerate)."""
    n = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    length = np.linalg.norm(n, axis=1)
    ok = length > 1e-12 * max(1.0, float(np.abs(triangles).max(initial=0.0))) ** 2
    n[ok] /= length[ok, None]
    return n, ok


def _outward(triangles: np.ndarray) -> float:
    """+1 when the triangles wind outward (positive enclosed volume), -1 otherwise."""
    volume = np.einsum(
        'ij,ij->i', triangles[:, 0], np.cross(triangles[:, 1], triangles[:, 2])
    ).sum()
    return 1.0 if volume >= 0 else -1.0


def hull_points(triangles: np.ndarray) -> np.ndarray:
    """The convex hull's vertices, by pybullet's hull computer, in a client of its own."""
    points = np.unique(triangles.reshape(-1, 3), axis=0)
    with tempfile.TemporaryDirectory(prefix='arm1-hull-') as folder:
        path = os.path.join(folder, 'points.obj')
        with open(path, 'w') as f:
            f.writelines('v %r %r %r\n' % tuple(v) for v in points)
            # pybullet's OBJ loader takes the vertices its faces name: one fan over them all
            f.writelines('f 1 %d %d\n' % (i, i + 1) for i in range(2, len(points)))
        client = p.connect(p.DIRECT)
        try:
            shape = p.createCollisionShape(p.GEOM_MESH, fileName=path, physicsClientId=client)
            body = p.createMultiBody(0, shape, physicsClientId=client)
            _, hull = p.getMeshData(body, -1, physicsClientId=client)
        finally:
            p.disconnect(client)
    return np.asarray(hull, dtype=np.float64).reshape(-1, 3)


def concavity(
    triangles: np.ndarray, hull: Optional[np.ndarray] = None, stop_above: float = np.inf
) -> float:
    """How far (in the triangles' units) the convex hull stands out of the mesh: the largest
    distance of a hull vertex in front of a face's plane. 0 for a convex mesh. With
    ``stop_above`` the search may end once that is passed (the answer is then a value above
    it, not necessarily the largest): a concave mesh is told quickly."""
    if len(triangles) < 4:
        return 0.0
    n, ok = _normals(triangles)
    n, a = n[ok] * _outward(triangles), triangles[ok, 0]
    hull = hull_points(triangles) if hull is None else hull
    offsets = np.einsum('ij,ij->i', n, a)
    depth = 0.0
    step = max(1, CHUNK // max(1, len(hull)))
    for i in range(0, len(n), step):
        heights = n[i : i + step] @ hull.T - offsets[i : i + step, None]
        depth = max(depth, float(heights.max()))
        if depth > stop_above:
            break
    return depth


Edge = Tuple[int, int]


def _weld(triangles: np.ndarray) -> Tuple[np.ndarray, np.ndarray]:
    """(n, 3) vertex ids and their points: corners closer than WELD are one vertex (an STL
    repeats each corner in every triangle)."""
    keys = np.round(triangles.reshape(-1, 3) / WELD).astype(np.int64)
    _, first, inverse = np.unique(keys, axis=0, return_index=True, return_inverse=True)
    return inverse.reshape(-1, 3), triangles.reshape(-1, 3)[first]


def _edges(corners: np.ndarray) -> List[Edge]:
    a, b, c = (int(v) for v in corners)
    return [(a, b), (b, c), (c, a)]


Sides = Dict[Edge, Tuple[np.ndarray, float]]


class _Surface:
    """The welded triangles with their planes, edges and convex flat faces."""

    def __init__(self, triangles: np.ndarray, normals: np.ndarray) -> None:
        self.ids, self.points = _weld(triangles)
        self.normals = normals
        self.offsets = np.einsum('ij,ij->i', normals, self.points[self.ids[:, 0]])
        self.by_edge: Dict[Edge, List[int]] = {}
        for t in range(len(triangles)):
            for a, b in _edges(self.ids[t]):
                self.by_edge.setdefault((min(a, b), max(a, b)), []).append(t)

    def neighbours(self, members: Sequence[int]) -> List[int]:
        return [
            u
            for t in members
            for a, b in _edges(self.ids[t])
            for u in self.by_edge[(min(a, b), max(a, b))]
        ]

    def outline(self, members: Sequence[int]) -> Sides:
        """Each boundary edge (wound as its triangle) of these triangles, with its side
        plane: through the edge, along its triangle's normal, facing out of the patch."""
        directed = {e: t for t in members for e in _edges(self.ids[t])}
        out = {}
        for (a, b), t in directed.items():
            if (b, a) not in directed:
                side = np.cross(self.points[b] - self.points[a], self.normals[t])
                side /= np.linalg.norm(side)
                out[(a, b)] = (side, float(side @ self.points[a]))
        return out

    def vertices(self, members: Sequence[int]) -> np.ndarray:
        return np.unique(self.ids[list(members)])

    def units(self, order: Sequence[int]) -> List[List[int]]:
        """Flat faces (coplanar within TOLERANCE, edge-adjacent) with a convex outline as
        one unit each, every other triangle a unit of its own: a rectangle of many
        triangles joins a patch whole, where triangle by triangle it would pass through
        shapes that are not convex."""
        placed = np.zeros(len(self.ids), dtype=bool)
        units: List[List[int]] = []
        for seed in order:
            if placed[seed]:
                continue
            placed[seed] = True
            face, stack = [int(seed)], [int(seed)]
            while stack:
                for u in self.neighbours([stack.pop()]):
                    if placed[u] or self.normals[u] @ self.normals[seed] < FLAT_COS:
                        continue
                    heights = self.points[self.ids[u]] @ self.normals[seed] - self.offsets[seed]
                    if np.abs(heights).max() <= TOLERANCE:
                        placed[u] = True
                        face.append(u)
                        stack.append(u)
            if _in_front(self.points[self.vertices(face)], self.outline(face)) <= TOLERANCE:
                units.append(face)
            else:
                units.extend([t] for t in face)
        return units


def _in_front(points: np.ndarray, sides: Sides) -> float:
    """How far the points stand in front of the side planes at most (-inf for none)."""
    if not sides or not len(points):
        return -np.inf
    planes = np.array([s for s, _ in sides.values()])
    offsets = np.array([d for _, d in sides.values()])
    step = max(1, CHUNK // len(planes))  # a big flat face: many points, many edges
    return max(
        float((points[i : i + step] @ planes.T - offsets).max())
        for i in range(0, len(points), step)
    )


class _Patch:
    """Edge-adjacent units (flat faces, triangles) growing into one convex piece of
    surface. A unit joins while, within TOLERANCE, every vertex stays behind every
    triangle's plane (convex), no deeper than THICKNESS below any of them (a thin piece, as
    each prism), and behind every boundary edge's side plane (its outline convex, no hole):
    the hull of its vertices then is its surface and nothing beside it."""

    def __init__(self, surface: _Surface, unit: List[int]) -> None:
        self.surface = surface
        self.seed_normal = surface.normals[unit[0]]
        self.members = list(unit)
        self.vertices = set(int(v) for v in surface.vertices(unit))
        self.boundary = surface.outline(unit)

    def _behind(self, points: np.ndarray, members: Sequence[int]) -> bool:
        s = self.surface
        heights = points @ s.normals[list(members)].T - s.offsets[list(members)]
        return bool(heights.max() <= TOLERANCE and heights.min() >= -THICKNESS)

    def join(self, unit: List[int], sides: Sides) -> bool:
        """Adds the unit (its outline ``sides``) when the patch stays convex with it; False
        leaves the patch unchanged."""
        s = self.surface
        if len(self.members) + len(unit) > PATCH_TRIANGLES:
            return False  # each join costs as the patch's size: big patches grow no more
        if (s.normals[unit] @ self.seed_normal).min() < PATCH_CONE:
            return False  # a triangle wound the other way, or a turn too sharp for one piece
        corners = set(int(v) for v in s.vertices(unit))
        new = s.points[sorted(corners - self.vertices)]
        every = s.points[sorted(self.vertices | corners)]
        if not self._behind(every, unit) or (len(new) and not self._behind(new, self.members)):
            return False
        kept = dict(self.boundary)
        added = {}
        for (a, b), side in sides.items():
            if (b, a) in kept:
                del kept[(b, a)]  # a shared edge is inside the patch now
            else:
                added[(a, b)] = side
        if len(added) == len(sides):
            return False  # shares no edge with the patch
        if _in_front(every, added) > TOLERANCE or _in_front(new, kept) > TOLERANCE:
            return False
        self.boundary = {**kept, **added}
        self.vertices |= corners
        self.members.extend(unit)
        return True


def convex_patches(
    triangles: np.ndarray, normals: np.ndarray, surface: Optional[_Surface] = None
) -> List[List[int]]:
    """The triangles (wound outward, with their unit ``normals``) grouped into convex
    patches of edge-adjacent triangles, largest first: each list one patch's triangle
    indices. A flat CAD face of many triangles becomes one patch."""
    surface = surface or _Surface(triangles, normals)
    area = np.linalg.norm(
        np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0]), axis=1
    )
    units = surface.units(np.argsort(-area, kind="stable").tolist())
    unit_of = np.empty(len(triangles), dtype=np.int64)
    for i, unit in enumerate(units):
        unit_of[unit] = i
    sides = [surface.outline(unit) for unit in units]
    placed = np.zeros(len(units), dtype=bool)
    patches = []
    for seed in np.argsort([-area[unit].sum() for unit in units], kind='stable'):
        if placed[seed]:
            continue
        placed[seed] = True
        patch = _Patch(surface, units[seed])
        frontier = [int(seed)]
        while frontier:
            for t in surface.neighbours(units[frontier.pop()]):
                u = int(unit_of[t])
                if not placed[u] and patch.join(units[u], sides[u]):
                    placed[u] = True
                    frontier.append(u)
        patches.append(patch.members)
    return patches


_DIRECTIONS = np.array([(np.cos(a), np.sin(a)) for a in np.arange(32) * np.pi / 16])


def _hull_2d(points: np.ndarray) -> np.ndarray:
    """Indices of the 2-D points on their convex hull (Andrew's monotone chain, after
    dropping, in numpy, the points inside the polygon of the extreme points in 32
    directions: a cut's crossings are thousands, its hull a few dozen)."""
    _, unique = np.unique(points, axis=0, return_index=True)
    return unique[_hull_2d_unique(points[unique])]


def _hull_2d_unique(points: np.ndarray) -> np.ndarray:
    corners = np.argmax(points @ _DIRECTIONS.T, axis=0)  # counter-clockwise
    corners = corners[np.r_[True, corners[1:] != corners[:-1]]]
    if len(corners) > 2 and corners[0] == corners[-1]:
        corners = corners[:-1]
    if len(corners) >= 3:
        a = points[corners]
        edge = np.roll(a, -1, axis=0) - a
        rel = points[:, None, :] - a[None]
        # on an edge counts as inside (not a vertex: a cut's crossings line up by thousands)
        tolerance = -1e-12 * float(np.ptp(points, axis=0).max()) ** 2
        cross = edge[None, :, 0] * rel[..., 1] - edge[None, :, 1] * rel[..., 0]
        inside = (cross >= tolerance).all(axis=1)
        inside[corners] = False
        kept = np.flatnonzero(~inside)
    else:
        kept = np.arange(len(points))
    return kept[_monotone_chain(points[kept])]


def _monotone_chain(points: np.ndarray) -> np.ndarray:
    """Indices of the 2-D points on their convex hull (Andrew's monotone chain)."""
    order = np.lexsort((points[:, 1], points[:, 0]))
    if len(order) < 3:
        return order

    def chain(indices: np.ndarray) -> List[int]:
        kept: List[int] = []
        for i in indices:
            while len(kept) >= 2:
                o, a = points[kept[-2]], points[kept[-1]]
                b = points[i]
                if (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]) > 0:
                    break
                kept.pop()
            kept.append(int(i))
        return kept[:-1]

    return np.array(chain(order) + chain(order[::-1]), dtype=np.int64)


def _cut(points: np.ndarray, normal: np.ndarray, offset: float) -> np.ndarray:
    """The convex hull of ``points`` cut to ``normal . x <= offset``, as points whose hull it
    is: those behind the plane and, on it, the hull of where every front-to-back segment
    crosses it (the hull's edges among them). Nothing cut off less than WELD: unchanged."""
    heights = points @ normal - offset
    if heights.max() <= WELD:
        return points
    front, back = heights > 0, heights <= 0
    if not back.any():
        return points[:0]
    hf, hb = heights[front][:, None], heights[back][None, :]
    t = (hf / (hf - hb))[..., None]
    crossings = points[front][:, None] + t * (points[back][None, :] - points[front][:, None])
    crossings = crossings.reshape(-1, 3)
    u = np.cross(normal, (1.0, 0.0, 0.0) if abs(normal[0]) < 0.9 else (0.0, 1.0, 0.0))
    u /= np.linalg.norm(u)
    flat = np.stack([crossings @ u, crossings @ np.cross(normal, u)], axis=1)
    return np.concatenate([points[back], crossings[_hull_2d(flat)]])


def _convex_neighbours(
    surface: _Surface,
    members: Sequence[int],
    boxes: Tuple[np.ndarray, np.ndarray],
    normal: np.ndarray,
) -> List[int]:
    """Triangles that a corner of the patch lies on (so a T-junction counts), whose planes
    the whole patch stands behind: a convex edge or corner between them, turning by more
    than SMOOTH_TURN from the patch's mean ``normal``. ``boxes``: each triangle's bounding
    box (low, high corners)."""
    points = surface.points[surface.vertices(members)]
    low, high = boxes
    near = np.flatnonzero(
        (low <= points.max(axis=0) + TOUCH).all(axis=1)
        & (high >= points.min(axis=0) - TOUCH).all(axis=1)
    )
    near = np.setdiff1d(near, members)
    near = near[surface.normals[near] @ normal < SMOOTH_TURN]
    if not len(near):
        return []
    heights = points @ surface.normals[near].T - surface.offsets[near]
    inside = (
        (points[:, None, :] >= low[near][None] - TOUCH)
        & (points[:, None, :] <= high[near][None] + TOUCH)
    ).all(axis=2)
    touching = ((np.abs(heights) <= TOUCH) & inside).any(axis=0)
    return near[touching & (heights.max(axis=0) <= TOLERANCE)].tolist()


def patch_hulls(triangles: np.ndarray) -> Tuple[str, int]:
    """One .obj object per convex patch: a prism from the patch moved inward by SHRINK to
    THICKNESS deeper, along the patch's mean normal (metres: already scaled), cut SHRINK
    behind its convex neighbours' planes (a piece plus pybullet's margin then stands at
    most MARGIN - SHRINK out of the surface, plus TOLERANCE on a curved patch and 0.05 mm
    at a turn under SMOOTH_TURN). A piece cut thinner than WELD is left out. Returns the
    .obj text and the number of objects (pieces)."""
    if _outward(triangles) < 0:
        triangles = triangles[:, ::-1]  # wound outward from here on
    n, ok = _normals(triangles)
    triangles, n = triangles[ok], n[ok]
    surface = _Surface(triangles, n)
    ids, points = surface.ids, surface.points
    boxes = (triangles.min(axis=1), triangles.max(axis=1))
    lines = []
    base, count = 1, 0
    for members in convex_patches(triangles, n, surface):
        used = np.unique(ids[members])
        area = np.linalg.norm(
            np.cross(
                triangles[members, 1] - triangles[members, 0],
                triangles[members, 2] - triangles[members, 0],
            ),
            axis=1,
        )
        mean = (n[members] * area[:, None]).sum(axis=0)
        inward = -mean / np.linalg.norm(mean)
        top = points[used] + SHRINK * inward
        piece = np.concatenate([top, top + THICKNESS * inward])
        for t in _convex_neighbours(surface, members, boxes, -inward):
            piece = _cut(piece, surface.normals[t], surface.offsets[t] - SHRINK)
            if len(piece) < 4:
                break
        if len(piece) < 4:
            continue  # cut away: a sliver whose neighbours' margins cover it
        centred = piece - piece.mean(axis=0)
        if np.ptp(centred @ np.linalg.svd(centred, full_matrices=False)[2][2]) < WELD:
            continue  # cut flat, as above
        lines.append('o p%d\n' % count)
        lines.extend('v %.9g %.9g %.9g\n' % tuple(v) for v in piece)
        # pybullet takes the hull of the vertices its faces name: one fan over them all
        lines.extend(
            'f %d %d %d\n' % (base, base + i, base + i + 1) for i in range(1, len(piece) - 1)
        )
        base += len(piece)
        count += 1
    return ''.join(lines), count
