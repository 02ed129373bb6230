"""Gazebo's grasp plugin (gazebo_grasp_plugin's GazeboGraspFix, ``libgazebo_grasp_fix.so``).

An object gripped between two links of an ``<arm>`` (their contact forces on it more than
``forces_angle_tolerance`` apart, the weaker at least 0.3 of the stronger; here the normal
forces, see GraspFix.collect) for more than
``grip_count_threshold`` updates is fixed to the arm's palm link; once no longer gripped,
its count falls by one each update, and at or below the threshold it is let go as soon as
the point where a finger first touched it has moved more than ``release_tolerance`` nearer
to or farther from it (the fingers opened). Each attach and detach is a grasp event
``(arm, object's collision name, attached)``.

``GraspLogic`` is upstream's decision, free of pybullet (unit-tested on synthetic contacts);
``GraspFix`` feeds it pybullet's contacts every step and makes and breaks the fixed joints.
Unlike upstream, the updates run at ``update_rate`` in sim time (upstream counts wall time:
the same at a real-time factor of 1).
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass, field
from typing import Callable, Dict, Hashable, List, Optional, Sequence, Set, Tuple

import pybullet as p

from .carry import norm, opposing
from .link_motion import Vec3, add, scale, sub
from .robot import Robot
from .sim_sensor import SimSensor

log = logging.getLogger('_arm1sim.physics')

# Upstream's defaults (GazeboGraspFix.cpp)
DEFAULT_FORCES_ANGLE_TOLERANCE = 120.0  # degrees
DEFAULT_UPDATE_RATE = 5.0  # Hz
DEFAULT_MAX_GRIP_COUNT = 10
DEFAULT_RELEASE_TOLERANCE = 0.005  # m
# What the fixed joint may pull with, N (Gazebo's joint is rigid)
ATTACH_MAX_FORCE = 1e5
# pybullet's collision filter of a dynamic link (btBroadphaseProxy DefaultFilter, AllFilter):
# what disable_collisions_on_attach gives back on detach
DYNAMIC_FILTER = (1, -1)

GraspEvent = Tuple[str, Hashable, bool]  # (arm, object, attached)


@dataclass
class GraspParams:
    forces_angle_tolerance: float = math.radians(DEFAULT_FORCES_ANGLE_TOLERANCE)  # rad
    update_rate: float = DEFAULT_UPDATE_RATE
    max_grip_count: int = DEFAULT_MAX_GRIP_COUNT
    grip_count_threshold: int = DEFAULT_MAX_GRIP_COUNT // 2
    release_tolerance: float = DEFAULT_RELEASE_TOLERANCE
    disable_collisions_on_attach: bool = False


@dataclass
class Touch:
    """One gripper link's contacts on one object, summed over the steps since the last update:
    the force on the object, the contact point and the object's origin in the link's frame."""

    arm: str
    force: Vec3 = (0.0, 0.0, 0.0)
    position: Vec3 = (0.0, 0.0, 0.0)
    object_position: Vec3 = (0.0, 0.0, 0.0)
    count: int = 0

    def add(self, force: Vec3, position: Vec3, object_position: Vec3) -> None:
        self.force = add(self.force, force)
        self.position = add(self.position, position)
        self.object_position = add(self.object_position, object_position)
        self.count += 1

    def mean(self, total: Vec3) -> Vec3:
        return scale(total, 1.0 / self.count)


# (object, link, the link's first contact point in its frame) -> that point's distance from
# the object's origin now
DistanceNow = Callable[[Hashable, Hashable, Vec3], float]


@dataclass
class GraspLogic:
    """GazeboGraspFix::OnUpdate without the physics: objects and links are any keys."""

    params: GraspParams
    arms: Sequence[str]
    contacts: Dict[Hashable, Dict[Hashable, Touch]] = field(default_factory=dict)
    grip_counts: Dict[Hashable, int] = field(default_factory=dict)
    attached: Dict[str, Hashable] = field(default_factory=dict)  # arm -> object
    # object -> {link: Touch} of the attaching arm's links, as they were at the attach
    attach_contacts: Dict[Hashable, Dict[Hashable, Touch]] = field(default_factory=dict)

    def add_contact(
        self,
        obj: Hashable,
        link: Hashable,
        arm: str,
        force: Vec3,
        position: Vec3,
        object_position: Vec3,
    ) -> None:
        """One step's contact of a gripper link on an object: the mean force on the object,
        the mean contact point and the object's origin, both in the link's frame."""
        links = self.contacts.setdefault(obj, {})
        touch = links.get(link)
        if touch is None:
            touch = links[link] = Touch(arm)
        touch.add(force, position, object_position)

    def update(self, distance_now: DistanceNow) -> List[GraspEvent]:
        """One update: the attaches and detaches it decides, in order."""
        params, events = self.params, []
        contacts, self.contacts = self.contacts, {}
        gripped: Set[Hashable] = set()
        for obj, links in contacts.items():
            forces = [t.mean(t.force) for t in links.values()]
            if not opposing(forces, params.forces_angle_tolerance):
                continue
            gripped.add(obj)
            count = self.grip_counts.get(obj, 0)
            if count < params.max_grip_count:
                count += 1
            self.grip_counts[obj] = count
            if count <= params.grip_count_threshold:
                continue
            involved: Dict[str, int] = {}
            for t in links.values():
                involved[t.arm] = involved.get(t.arm, 0) + 1
            if any(self.attached.get(arm) == obj for arm in involved):
                continue
            # the arm with the most links on it (the first to get there, as upstream)
            arm, most = '', 0
            for t in links.values():
                if involved[t.arm] > most:
                    arm, most = t.arm, involved[t.arm]
            if arm in self.attached:
                log.error(
                    'grasp plugin: arm %s already holds %s, so cannot grasp %s',
                    arm,
                    self.attached[arm],
                    obj,
                )
                continue
            self.attach_contacts[obj] = {k: t for k, t in links.items() if t.arm == arm}
            self.attached[arm] = obj
            events.append((arm, obj, True))
        holders = {obj: arm for arm, obj in self.attached.items()}
        for obj in list(self.grip_counts):
            if obj in gripped:
                continue
            if self.grip_counts[obj] > 0:
                self.grip_counts[obj] -= 1
            holder = holders.get(obj)
            if holder is None or self.grip_counts[obj] > params.grip_count_threshold:
                continue
            if self._released(obj, distance_now):
                del self.attached[holder]
                self.grip_counts[obj] = 0
                del self.attach_contacts[obj]
                events.append((holder, obj, False))
        return events

    def _released(self, obj: Hashable, distance_now: DistanceNow) -> bool:
        """Has the point where any finger first touched the object moved more than
        release_tolerance nearer to or farther from it?"""
        for link, t in self.attach_contacts.get(obj, {}).items():
            contact, origin = t.mean(t.position), t.mean(t.object_position)
            before = norm(sub(contact, origin))
            if abs(before - distance_now(obj, link, contact)) > self.params.release_tolerance:
                return True
        return False

    def forget(self, obj: Hashable) -> Optional[str]:
        """An object gone from the world: the arm that held it, if any."""
        self.grip_counts.pop(obj, None)
        self.attach_contacts.pop(obj, None)
        self.contacts.pop(obj, None)
        for arm, held in list(self.attached.items()):
            if held == obj:
                del self.attached[arm]
                return arm
        return None


@dataclass
class GraspArm:
    """An ``<arm>``: its palm and gripper links as pybullet link indices."""

    name: str
    palm: int
    links: List[int]


Pose = Tuple[Sequence[float], Sequence[float]]
ObjectKey = Tuple[int, int]  # (pybullet body, link index)


class GraspFix(SimSensor):
    """The plugin on one robot: contacts gathered every step, decided at ``update_rate``.

    ``deliver(stamp_ns, events)`` (set by whoever reports them) gets each update's events
    as ``(arm, object's collision name, attached)``; the attaching happens regardless."""

    kind = 'grasp plugin'

    def __init__(
        self,
        model: str,
        name: str,
        robot: Robot,
        arms: Sequence[GraspArm],
        params: GraspParams,
        namer: Callable[[int, int], str],
    ) -> None:
        super().__init__(model, name, params.update_rate)
        self.robot, self.arms, self.params, self.namer = robot, list(arms), params, namer
        self.logic = GraspLogic(params, [a.name for a in arms])
        self.arm_of = {i: a.name for a in arms for i in a.links}
        self.palms = {a.name: a.palm for a in arms}
        self.joints: Dict[str, int] = {}  # arm -> pybullet constraint holding its object

    # ------------------------------------------------------------------ every step
    def update(self, now_ns: int) -> None:
        self.collect()
        if self.due(now_ns):
            events = self.decide()
            if events and self.deliver is not None:
                self.deliver(now_ns, self._named(events))

    def _named(self, events: List[GraspEvent]) -> List[Tuple[str, str, bool]]:
        """Events with the object's collision name, as upstream reports them."""
        named = []
        for arm, obj, attached in events:
            assert isinstance(obj, tuple)
            named.append((arm, self.namer(*obj), attached))
        return named

    def collect(self) -> None:
        """This step's contacts of every gripper link with every dynamic body but its own."""
        cid, body = self.robot.client, self.robot.body
        static: Dict[ObjectKey, bool] = {}  # per step: pybullet reuses a removed body's id
        for link, arm in self.arm_of.items():
            points = p.getContactPoints(bodyA=body, linkIndexA=link, physicsClientId=cid)
            if not points:
                continue
            by_object: Dict[ObjectKey, List[Tuple[Vec3, Vec3]]] = {}
            for c in points:
                obj = (c[2], c[4])
                if obj[0] == body:
                    continue
                if obj not in static:
                    static[obj] = self._is_static(obj)
                if static[obj]:
                    continue
                # The normal force on the object (the normal points from it to the link).
                # Upstream adds the friction: ODE's is what holding needs, but pybullet's
                # friction anchors report friction as large as the normal force on a box
                # squeezed at rest, which can turn two opposing forces under 120 degrees.
                by_object.setdefault(obj, []).append((scale(c[7], -c[9]), tuple(c[5])))
            if not by_object:
                continue
            frame = p.invertTransform(*self._pose(body, link), physicsClientId=cid)
            for obj, hits in by_object.items():
                n = float(len(hits))
                force = scale(_sum(h[0] for h in hits), 1.0 / n)
                point = scale(_sum(h[1] for h in hits), 1.0 / n)
                origin = self._pose(*obj)[0]
                self.logic.add_contact(
                    obj,
                    link,
                    arm,
                    force,
                    _moved(frame, point, cid),
                    _moved(frame, origin, cid),
                )

    def decide(self) -> List[GraspEvent]:
        """One update of the logic, its attaches and detaches made in the physics."""
        for obj in [o for o in self.logic.grip_counts if not self._exists(o)]:
            arm = self.logic.forget(obj)
            assert isinstance(obj, tuple)
            if arm is not None:
                self._break(arm, obj)
        events = self.logic.update(self._distance_now)
        for arm, obj, attached in events:
            assert isinstance(obj, tuple)
            if attached:
                self._attach(arm, obj)
            else:
                self._break(arm, obj)
        return events

    # ------------------------------------------------------------------ physics
    def _pose(self, body: int, link: int) -> Pose:
        cid = self.robot.client
        if link == -1:
            return p.getBasePositionAndOrientation(body, physicsClientId=cid)
        s = p.getLinkState(body, link, computeForwardKinematics=True, physicsClientId=cid)
        return s[0], s[1]

    def _is_static(self, obj: ObjectKey) -> bool:
        """Massless in pybullet: the world's static models and a fixed base."""
        return p.getDynamicsInfo(obj[0], obj[1], physicsClientId=self.robot.client)[0] <= 0.0

    def _exists(self, obj: Hashable) -> bool:
        assert isinstance(obj, tuple)
        try:
            p.getBodyInfo(obj[0], physicsClientId=self.robot.client)
        except p.error:
            return False
        return True

    def _distance_now(self, obj: Hashable, link: Hashable, contact: Vec3) -> float:
        assert isinstance(obj, tuple) and isinstance(link, int)
        cid = self.robot.client
        pos, orn = self._pose(self.robot.body, link)
        point = p.multiplyTransforms(pos, orn, contact, (0, 0, 0, 1), physicsClientId=cid)[0]
        return norm(sub(tuple(point), tuple(self._pose(*obj)[0])))

    def _attach(self, arm: str, obj: ObjectKey) -> None:
        """A fixed joint from the palm to the object where it is now (GazeboGraspGripper's
        HandleAttach)."""
        cid, body, palm = self.robot.client, self.robot.body, self.palms[arm]
        inverse = p.invertTransform(*self._pose(body, palm), physicsClientId=cid)
        rel_pos, rel_orn = p.multiplyTransforms(*inverse, *self._pose(*obj), physicsClientId=cid)
        joint = p.createConstraint(
            body,
            palm,
            obj[0],
            obj[1],
            p.JOINT_FIXED,
            (0, 0, 0),
            rel_pos,
            (0, 0, 0),
            rel_orn,
            (0, 0, 0, 1),
            physicsClientId=cid,
        )
        p.changeConstraint(joint, maxForce=ATTACH_MAX_FORCE, physicsClientId=cid)
        self.joints[arm] = joint
        if self.params.disable_collisions_on_attach:
            p.setCollisionFilterGroupMask(obj[0], obj[1], 0, 0, physicsClientId=cid)
        log.info(
            "model '%s': %s attaches %s to arm %s", self.model, self.name, self.namer(*obj), arm
        )

    def _break(self, arm: str, obj: ObjectKey) -> None:
        cid = self.robot.client
        joint = self.joints.pop(arm, None)
        if joint is not None:
            try:
                p.removeConstraint(joint, physicsClientId=cid)
            except p.error:
                pass  # gone with its object
        if self.params.disable_collisions_on_attach and self._exists(obj):
            p.setCollisionFilterGroupMask(obj[0], obj[1], *DYNAMIC_FILTER, physicsClientId=cid)

    def release_all(self) -> List[GraspEvent]:
        """Let go of everything held (reset, delete): the detach events."""
        events: List[GraspEvent] = []
        for arm, obj in list(self.logic.attached.items()):
            assert isinstance(obj, tuple)
            self._break(arm, obj)
            events.append((arm, obj, False))
        self.logic = GraspLogic(self.params, [a.name for a in self.arms])
        return events

    def reset(self) -> None:
        """Gazebo's reset moves the models back; the held object is let go with it."""
        events = self.release_all()
        if events and self.deliver is not None:
            self.deliver(0, self._named(events))

    def close(self) -> None:
        self.release_all()
        super().close()


def _sum(vectors) -> Vec3:
    total: Vec3 = (0.0, 0.0, 0.0)
    for v in vectors:
        total = add(total, v)
    return total


def _moved(frame: Pose, point: Sequence[float], cid: int) -> Vec3:
    """``point`` (world) in the frame whose inverse is ``frame``."""
    pos = p.multiplyTransforms(frame[0], frame[1], point, (0, 0, 0, 1), physicsClientId=cid)[0]
    return (pos[0], pos[1], pos[2])
