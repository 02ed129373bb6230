"""What a position joint's jump gives to the objects its links grip.

A position-interface joint without ``pid_gains`` reaches its command in one step, as Gazebo's
``Joint::SetPosition`` does: its links change velocity at once, and an object held between
two of them by friction would need that step's whole impulse (a 1 mm jump in a 1 ms step is
1 m/s: ~30 N for a 30 g box) to follow. No friction grip supplies it, in ODE either: Gazebo
drops the object, a grip at a few tenths of a newton slips a little at every command. Here an
object gripped at that moment (contact forces from two of the robot's links more than
GRIP_ANGLE apart) takes the same change of velocity as the links gripping it, so only the
jump is carried; gravity, inertia and friction act on it as before between commands.
"""

from __future__ import annotations

import math
from typing import Dict, List, Sequence, Tuple

import pybullet as p

Vec3 = Tuple[float, float, float]
# Link twist in world axes: centre of mass, linear velocity there, angular velocity
Twist = Tuple[Vec3, Vec3, Vec3]

# Two contact forces more than this far apart grip an object (the grasp plugin's default
# forces_angle_tolerance)
GRIP_ANGLE = math.radians(120.0)
# CheckGrip's: the weaker of two opposing forces must be at least this part of the stronger
FORCE_LENGTH_RATIO = 0.3
# A joint's velocity change (rad/s or m/s) in one step above which its links' jump is carried
CARRY_MIN_CHANGE = 1e-3


def norm(v: Sequence[float]) -> float:
    return math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])


def opposing(forces: Sequence[Vec3], min_angle: float, ratio: float = FORCE_LENGTH_RATIO) -> bool:
    """The grasp plugin's CheckGrip: two of the forces more than ``min_angle`` apart, the
    weaker at least ``ratio`` of the stronger (forces under 1e-4 N count as none)."""
    if min_angle < math.pi / 2:
        return False  # upstream refuses (and says so each time; here once, at load)
    for i, a in enumerate(forces):
        la = norm(a)
        if la < 1e-4:
            continue
        for b in forces[i + 1 :]:
            lb = norm(b)
            if lb < 1e-4:
                continue
            cos = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (la * lb)
            if (
                math.acos(max(-1.0, min(1.0, cos))) > min_angle
                and min(la, lb) / max(la, lb) >= ratio
            ):
                return True
    return False


def gripped(client: int, body: int) -> Dict[int, List[int]]:
    """Free bodies gripped between links of ``body`` at the last step: {object: [link, ...]}
    (the links touching it). Objects are whole bodies touched on their base; ones pybullet
    keeps static (mass 0) are not carried."""
    forces: Dict[int, Dict[int, List[float]]] = {}
    for c in p.getContactPoints(bodyA=body, physicsClientId=client):
        other, link, other_link, normal, force = c[2], c[3], c[4], c[7], c[9]
        if other == body or other_link != -1 or link < 0 or force <= 0.0:
            continue
        # the force on the object: along the normal on it, pointing from it to the link
        total = forces.setdefault(other, {}).setdefault(link, [0.0, 0.0, 0.0])
        for k in range(3):
            total[k] -= normal[k] * force
    held = {}
    for other, by_link in forces.items():
        if len(by_link) < 2:
            continue
        vectors = [(f[0], f[1], f[2]) for f in by_link.values()]
        if not opposing(vectors, GRIP_ANGLE):
            continue
        if p.getDynamicsInfo(other, -1, physicsClientId=client)[0] <= 0.0:
            continue
        held[other] = sorted(by_link)
    return held


def link_twists(client: int, body: int, links: Sequence[int]) -> List[Twist]:
    """The links' centres of mass and velocities as the joints' velocities now give them."""
    states = p.getLinkStates(
        body, links, computeLinkVelocity=1, computeForwardKinematics=1, physicsClientId=client
    )
    return [(s[0], s[6], s[7]) for s in states]


def velocity_change(
    before: Sequence[Twist], after: Sequence[Twist], point: Vec3
) -> Tuple[Vec3, Vec3]:
    """The mean change of the links' velocity field at ``point``: (linear, angular)."""
    n = len(after)
    dv = [0.0, 0.0, 0.0]
    dw = [0.0, 0.0, 0.0]
    for (_, v0, w0), (com, v1, w1) in zip(before, after):
        w = (w1[0] - w0[0], w1[1] - w0[1], w1[2] - w0[2])
        r = (point[0] - com[0], point[1] - com[1], point[2] - com[2])
        at = (w[1] * r[2] - w[2] * r[1], w[2] * r[0] - w[0] * r[2], w[0] * r[1] - w[1] * r[0])
        for k in range(3):
            dv[k] += (v1[k] - v0[k] + at[k]) / n
            dw[k] += w[k] / n
    return (dv[0], dv[1], dv[2]), (dw[0], dw[1], dw[2])


class JumpCarrier:
    """Around one step's jump of a robot's position joints: what its links grip, and their
    velocities before the jump (``before``), then the change given to what they grip
    (``after``, once the joints' new velocities are set)."""

    def __init__(self, client: int, body: int) -> None:
        self.client = client
        self.body = body
        self.held = gripped(client, body)
        self.links = sorted({link for links in self.held.values() for link in links})
        self._before: Dict[int, Twist] = {}
        if self.links:
            self._before = dict(zip(self.links, link_twists(client, body, self.links)))

    def after(self) -> None:
        if not self.links:
            return
        cid = self.client
        now = dict(zip(self.links, link_twists(cid, self.body, self.links)))
        for obj, links in self.held.items():
            point = p.getBasePositionAndOrientation(obj, physicsClientId=cid)[0]
            dv, dw = velocity_change(
                [self._before[link] for link in links], [now[link] for link in links], point
            )
            v, w = p.getBaseVelocity(obj, physicsClientId=cid)
            p.resetBaseVelocity(
                obj,
                [v[k] + dv[k] for k in range(3)],
                [w[k] + dw[k] for k in range(3)],
                physicsClientId=cid,
            )
