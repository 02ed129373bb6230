"""Contact sensors (``<sensor type="contact">``) for gazebo_ros_bumper.

One state per colliding pair with, per contact point, the wrench on the sensor's link (body 1)
in that link's frame (force, and torque about its centre of mass, as ODE's feedback gives it),
the position and the normal (pointing into body 1) in world axes, and the depth
(gazebo/physics/ode/ODEPhysics.cc; gazebo_ros_bumper.cpp). pybullet reports contacts per link,
not per collision: the sensor's link stands for its collision.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable, Dict, List, Tuple

import pybullet as p

from .link_motion import Vec3, add, cross, scale, sub, unrotate
from .robot import Robot
from .sim_sensor import SimSensor

# (pybullet body, link index) -> the scoped collision name Gazebo would give
CollisionNamer = Callable[[int, int], str]
_namers: Dict[int, CollisionNamer] = {}  # per physics client


def set_collision_namer(client: int, namer: CollisionNamer) -> None:
    """How the world names what a contact sensor touches (the simulation knows models)."""
    _namers[client] = namer


def collision_name(client: int, body: int, link: int) -> str:
    """Gazebo's scoped collision name of a pybullet body's link, as the world names it."""
    return _namers.get(client, _unnamed)(body, link)


def _unnamed(body: int, link: int) -> str:
    return 'body%d::link%d' % (body, link)


@dataclass
class ContactPair:
    collision1: str
    collision2: str
    wrenches: List[Tuple[Vec3, Vec3]] = field(default_factory=list)  # (force, torque)
    positions: List[Vec3] = field(default_factory=list)
    normals: List[Vec3] = field(default_factory=list)
    depths: List[float] = field(default_factory=list)


class ContactSensor(SimSensor):
    kind = 'contact'

    def __init__(
        self, model: str, name: str, robot: Robot, link: int, collision: str, update_rate: float
    ) -> None:
        super().__init__(model, name, update_rate)
        self.robot, self.link, self.collision = robot, link, collision
        self.enabled = True  # False: no <collision> named, nothing is reported

    def measure(self, now_ns: int) -> List[ContactPair]:
        if not self.enabled:
            return []
        cid, body = self.robot.client, self.robot.body
        points = p.getContactPoints(bodyA=body, linkIndexA=self.link, physicsClientId=cid)
        if not points:
            return []
        if self.link == -1:
            com, orn = p.getBasePositionAndOrientation(body, physicsClientId=cid)
            frame_orn = p.multiplyTransforms(com, orn, *self.robot._base_from_com)[1]
        else:
            s = p.getLinkState(body, self.link, computeForwardKinematics=1, physicsClientId=cid)
            com, frame_orn = s[0], s[5]
        namer = _namers.get(cid, _unnamed)
        pairs: Dict[Tuple[int, int], ContactPair] = {}
        for c in points:
            other = (c[2], c[4])
            pair = pairs.get(other)
            if pair is None:
                pair = pairs[other] = ContactPair(self.collision, namer(*other))
            position: Vec3 = tuple(c[5])  # on A: this link
            normal: Vec3 = tuple(c[7])  # on B, pointing to A
            # normal force along the normal, friction along the lateral directions (on A)
            force = add(add(scale(normal, c[9]), scale(c[11], c[10])), scale(c[13], c[12]))
            torque = cross(sub(position, com), force)
            pair.wrenches.append((unrotate(frame_orn, force), unrotate(frame_orn, torque)))
            pair.positions.append(position)
            pair.normals.append(normal)
            pair.depths.append(max(0.0, -c[8]))
        return list(pairs.values())
