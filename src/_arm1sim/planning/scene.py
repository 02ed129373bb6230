"""The planning scene's collision world: the robot, world objects and objects attached to
the robot's links, in the planner's own pybullet DIRECT client.

As MoveIt's collision checking (FCL) decides it: a state is in collision when two bodies
interpenetrate, except pairs the allowed-collision matrix allows: the SRDF's disabled
pairs, an attached object and its touch links (the link it is attached to among them), and
entries a planning scene message adds. World objects are not checked against each other.
Meshes collide as their convex hulls (pybullet's convex shapes), a cone as its cylinder.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence, Set, Tuple

import numpy as np
import pybullet as p

from .kinematics import ModelError, Pose, RobotKinematics, Vector

BOX, SPHERE, CYLINDER, CONE = 1, 2, 3, 4  # shape_msgs/SolidPrimitive types
# Penetration depth (m) still taken as touching, not colliding: pybullet's convex shapes
# report contacts a hair inside each other when merely touching.
TOUCH = 1e-5


@dataclass
class Shape:
    """One shape of an object: a SolidPrimitive (kind, dimensions) or a mesh (vertices,
    triangles), at ``pose`` in the object's frame."""

    kind: str  # 'box', 'sphere', 'cylinder', 'cone', 'mesh' or 'plane'
    dimensions: Tuple[float, ...] = ()
    pose: Tuple[Sequence[float], Sequence[float]] = ((0, 0, 0), (0, 0, 0, 1))
    vertices: List[Sequence[float]] = field(default_factory=list)
    triangles: List[Sequence[int]] = field(default_factory=list)


@dataclass
class SceneObject:
    id: str
    pose: Tuple[Sequence[float], Sequence[float]]  # model frame (world) or link frame (attached)
    shapes: List[Shape]
    link: str = ''  # attached: the robot link it is attached to
    touch_links: List[str] = field(default_factory=list)
    bodies: List[int] = field(default_factory=list)
    filtered: List[Tuple[int, int, int, int]] = field(default_factory=list)  # pairs disabled


class SceneError(ValueError):
    """An object cannot be added or attached; the message names it."""


def _collision_shape(client: Optional[int], shape: Shape) -> int:
    d = shape.dimensions
    try:
        if shape.kind == 'box':
            return p.createCollisionShape(
                p.GEOM_BOX, halfExtents=[d[0] / 2, d[1] / 2, d[2] / 2], physicsClientId=client
            )
        if shape.kind == 'sphere':
            return p.createCollisionShape(p.GEOM_SPHERE, radius=d[0], physicsClientId=client)
        if shape.kind in ('cylinder', 'cone'):
            return p.createCollisionShape(
                p.GEOM_CYLINDER, radius=d[1], height=d[0], physicsClientId=client
            )
        if shape.kind == 'mesh':
            return p.createCollisionShape(
                p.GEOM_MESH,
                vertices=[list(v) for v in shape.vertices],
                physicsClientId=client,
            )
        if shape.kind == 'plane':
            return p.createCollisionShape(
                p.GEOM_PLANE, planeNormal=list(d[:3]), physicsClientId=client
            )
    except (IndexError, p.error) as exc:
        raise SceneError('%s with dimensions %s: %s' % (shape.kind, list(d), exc)) from None
    raise SceneError("shape '%s' is not supported" % shape.kind)


class CollisionWorld:
    def __init__(self, robot: RobotKinematics) -> None:
        self.robot = robot
        self.client = robot.client
        self.objects: Dict[str, SceneObject] = {}  # world objects
        self.attached: Dict[str, SceneObject] = {}
        self.allowed: Set[Tuple[str, str]] = set()  # extra ACM entries (names: links, objects)
        c, body = self.client, robot.body
        for a, b in itertools.combinations(robot.link_index, 2):
            if robot.srdf.collision_disabled(a, b):
                ia, ib = robot.link_index[a], robot.link_index[b]
                p.setCollisionFilterPair(body, body, ia, ib, 0, physicsClientId=c)
        self._body_owner: Dict[int, str] = {}

    # --- objects -------------------------------------------------------------------------

    def _make_bodies(self, obj: SceneObject, mass: float = 0.0) -> None:
        for shape in obj.shapes:
            shape_id = _collision_shape(self.client, shape)
            body = p.createMultiBody(mass, shape_id, -1, physicsClientId=self.client)
            obj.bodies.append(body)
            self._body_owner[body] = obj.id

    def _remove_bodies(self, obj: SceneObject) -> None:
        # pybullet keeps a pair filter after its bodies are gone: a new body given the same
        # id would inherit it, so what attach disabled is enabled again first
        for a, b, la, lb in obj.filtered:
            p.setCollisionFilterPair(a, b, la, lb, 1, physicsClientId=self.client)
        obj.filtered = []
        for body in obj.bodies:
            p.removeBody(body, physicsClientId=self.client)
            self._body_owner.pop(body, None)
        obj.bodies = []

    def add_object(self, obj: SceneObject) -> None:
        """Add or replace a world object (by id)."""
        self.remove(obj.id)
        self._make_bodies(obj)
        self.objects[obj.id] = obj
        self._place(obj, (obj.pose[0], obj.pose[1]))

    def attach(self, obj: SceneObject) -> None:
        """Attach ``obj`` to ``obj.link`` (its pose in that link's frame)."""
        if obj.link not in self.robot.link_index:
            raise SceneError("cannot attach '%s': no link '%s' in the robot" % (obj.id, obj.link))
        self.remove(obj.id)
        # with a mass (never stepped): Bullet checks no pair of two static bodies, and the
        # world's objects are static
        self._make_bodies(obj, mass=1.0)
        touch = set(obj.touch_links) | {obj.link}
        for body in obj.bodies:
            for link in touch:
                i = self.robot.link_index.get(link)
                if i is not None:
                    p.setCollisionFilterPair(
                        body, self.robot.body, -1, i, 0, physicsClientId=self.client
                    )
                    obj.filtered.append((body, self.robot.body, -1, i))
            for other in obj.bodies:
                if other != body:
                    p.setCollisionFilterPair(body, other, -1, -1, 0, physicsClientId=self.client)
                    obj.filtered.append((body, other, -1, -1))
        self.attached[obj.id] = obj

    def remove(self, object_id: str) -> Optional[SceneObject]:
        for table in (self.objects, self.attached):
            obj = table.pop(object_id, None)
            if obj is not None:
                self._remove_bodies(obj)
                return obj
        return None

    def detach(self, object_id: str) -> Optional[SceneObject]:
        """Detach an attached object; it stays in the world where it is now (as MoveIt)."""
        obj = self.attached.get(object_id)
        if obj is None:
            return None
        pose = self.attached_pose(obj)
        self.remove(object_id)
        world = SceneObject(obj.id, (tuple(pose[0]), tuple(pose[1])), obj.shapes)
        self.add_object(world)
        return world

    def snapshot(self) -> Tuple[List[SceneObject], List[SceneObject], Set[Tuple[str, str]]]:
        """What restore() puts back: the objects (without their bodies) and the allowed
        entries."""

        def bare(o: SceneObject) -> SceneObject:
            return SceneObject(o.id, o.pose, list(o.shapes), o.link, list(o.touch_links))

        return (
            [bare(o) for o in self.objects.values()],
            [bare(o) for o in self.attached.values()],
            set(self.allowed),
        )

    def restore(
        self, snap: Tuple[List[SceneObject], List[SceneObject], Set[Tuple[str, str]]]
    ) -> None:
        self.clear()
        for o in snap[0]:
            self.add_object(o)
        for o in snap[1]:
            self.attach(o)
        self.allowed = set(snap[2])

    def clear(self) -> None:
        for object_id in list(self.objects) + list(self.attached):
            self.remove(object_id)

    def attached_pose(self, obj: SceneObject) -> Pose:
        link = self.robot.link_pose(obj.link)
        pos, orn = p.multiplyTransforms(link[0], link[1], obj.pose[0], obj.pose[1])
        return np.array(pos), np.array(orn)

    def _place(self, obj: SceneObject, pose: Tuple[Vector, Vector]) -> None:
        for body, shape in zip(obj.bodies, obj.shapes):
            pos, orn = p.multiplyTransforms(pose[0], pose[1], shape.pose[0], shape.pose[1])
            p.resetBasePositionAndOrientation(body, pos, orn, physicsClientId=self.client)

    def allow(self, a: str, b: str, allowed: bool = True) -> None:
        """An allowed-collision entry between two names (links or object ids)."""
        key = (min(a, b), max(a, b))
        if allowed:
            self.allowed.add(key)
        else:
            self.allowed.discard(key)

    # --- checking ------------------------------------------------------------------------

    def _name(self, body: int, link: int) -> Optional[str]:
        if body == self.robot.body:
            for name, i in self.robot.link_index.items():
                if i == link:
                    return name
            return None
        return self._body_owner.get(body)

    def contacts(
        self, positions: Optional[Dict[str, float]] = None
    ) -> List[Tuple[str, str, float]]:
        """The colliding pairs (names, depth) at ``positions`` (default: as set)."""
        if positions is not None:
            self.robot.set_positions(positions)
        for obj in self.attached.values():
            self._place(obj, self.attached_pose(obj))
        c = self.client
        p.performCollisionDetection(physicsClientId=c)
        robot = self.robot.body
        attached = {b for obj in self.attached.values() for b in obj.bodies}
        out = []
        for point in p.getContactPoints(physicsClientId=c):
            a, b, la, lb, depth = point[1], point[2], point[3], point[4], point[8]
            if depth > -TOUCH:
                continue
            if a != robot and b != robot and a not in attached and b not in attached:
                continue  # world objects among themselves
            na, nb = self._name(a, la), self._name(b, lb)
            if na is None or nb is None or na == nb:
                continue
            if (min(na, nb), max(na, nb)) in self.allowed or self.robot.srdf.collision_disabled(
                na, nb
            ):
                continue  # the scene's or the SRDF's (a link colliding with nothing by default)
            out.append((na, nb, -depth))
        return out

    def in_collision(self, positions: Optional[Dict[str, float]] = None) -> bool:
        return bool(self.contacts(positions))

    def world_names(self) -> List[str]:
        return list(self.objects)


def pairs_checked(robot: RobotKinematics) -> int:
    """How many robot link pairs the checker considers (every pair less the SRDF's)."""
    links = list(robot.link_index)
    return sum(
        1 for a, b in itertools.combinations(links, 2) if not robot.srdf.collision_disabled(a, b)
    )


__all__ = ['CollisionWorld', 'ModelError', 'SceneError', 'SceneObject', 'Shape']
