"""Mimic joints in pybullet: a follower driven toward leader * multiplier + offset.

roboticsgroup's mimic plugin (and Gazebo's URDF <mimic> handling through it) sets the
follower's position every iteration: nothing of it reaches the leader's joint, but a set
finger also passes through what it grips. Here the follower is a position motor capped at
its max force, so it pushes on what it touches, and the motor's reaction, which pybullet
applies to the follower's parent link, is kept off the leader's joint: when that parent
hangs below the leader (the leader's child link or deeper), the reaction is handed on to
the leader's parent link instead, so the robot as a whole still feels it (no net force
appears from nowhere) while the leader's joint does not. Without that, the reaction feeds
the leader's controller, which can run away.

With ``<hasPID>`` the plugin instead applies a PID's effort (clamped at maxEffort) to the
follower, a joint force like any other: its reaction reaches the parent link, and through
it the leader, in Gazebo as here (``set_pid``: no reroute).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, List, Optional, Sequence, Tuple

import pybullet as p

# positionGain 0.2 settles a light finger in a few steps; 1.0 oscillates.
POSITION_GAIN = 0.2
VELOCITY_GAIN = 1.0


@dataclass
class MimicJoint:
    """One follower, by pybullet joint index."""

    follower: int
    leader: int
    multiplier: float
    offset: float
    max_force: float
    sensitiveness: float
    # Where the reaction goes, when the follower's parent link hangs below the leader:
    # (follower's parent link, leader's parent link, True for a prismatic follower, its axis
    # in its child link's frame over its squared length); None when the reaction does not
    # pass through the leader's joint.
    reroute: Optional[Tuple[int, int, bool, Tuple[float, float, float]]] = None
    last_effort: float = 0.0  # the motor's force or torque in the last step
    # hasPID: effort for (target - position), called once per step; None: a position motor
    pid: Optional[Callable[[float], float]] = None


def mimic_joints(
    body: int, client: int, mimics: Sequence[Tuple[int, int, float, float, float, float]]
) -> List[MimicJoint]:
    """``[(follower, leader, multiplier, offset, max force, sensitiveness)]`` by joint index."""
    out = []
    for follower, leader, multiplier, offset, force, sensitiveness in mimics:
        info = p.getJointInfo(body, follower, physicsClientId=client)
        parent = info[16]
        reroute = None
        if _below(body, client, parent, leader):
            leader_parent = p.getJointInfo(body, leader, physicsClientId=client)[16]
            # pybullet keeps the URDF's axis as written, unnormalised, and a joint force f acts
            # as f * axis / |axis|^2 (S^T applied = f): that is what is handed on.
            axis = info[13]
            norm2 = sum(a * a for a in axis) or 1.0
            scaled = (axis[0] / norm2, axis[1] / norm2, axis[2] / norm2)
            reroute = (parent, leader_parent, info[2] == p.JOINT_PRISMATIC, scaled)
        out.append(MimicJoint(follower, leader, multiplier, offset, force, sensitiveness, reroute))
    return out


def _below(body: int, client: int, link: int, joint: int) -> bool:
    """Whether ``link`` is the child link of ``joint`` or hangs below it (in pybullet a
    joint and its child link share an index; the base is -1)."""
    while link >= 0:
        if link == joint:
            return True
        link = p.getJointInfo(body, link, physicsClientId=client)[16]
    return False


def set_pid(body: int, client: int, m: MimicJoint, law: Callable[[float], float]) -> None:
    """Drives the follower by ``law(error)``, an effort, from now on (hasPID)."""
    m.pid, m.reroute, m.last_effort = law, None, 0.0
    # pybullet's default velocity motor would hold the joint against the effort
    p.setJointMotorControl2(body, m.follower, p.VELOCITY_CONTROL, force=0.0, physicsClientId=client)


def pid_effort(target: float, position: float, m: MimicJoint) -> float:
    """The plugin's hasPID update: no effort within ``sensitiveness`` of the target or at a
    NaN position (and the PID not stepped), else the PID's command clamped at +-maxEffort."""
    assert m.pid is not None
    if not abs(target - position) >= m.sensitiveness:  # NaN too, as the plugin's test
        return 0.0
    return min(max(m.pid(target - position), -m.max_force), m.max_force)


def follow(body: int, client: int, mimics: Sequence[MimicJoint]) -> None:
    """Before a step: each follower's motor toward its target, set last so that it overrides
    anything written to the follower, and last step's reaction kept off its leader."""
    for m in mimics:
        lead = p.getJointState(body, m.leader, physicsClientId=client)[0]
        target = lead * m.multiplier + m.offset
        if m.pid is not None:
            pos = p.getJointState(body, m.follower, physicsClientId=client)[0]
            p.setJointMotorControl2(
                body,
                m.follower,
                p.TORQUE_CONTROL,
                force=pid_effort(target, pos, m),
                physicsClientId=client,
            )
            continue
        if m.sensitiveness > 0:
            pos = p.getJointState(body, m.follower, physicsClientId=client)[0]
            if abs(target - pos) < m.sensitiveness:
                target = pos
        # Target velocity 0, not the leader's: with the leader's (one step old) velocity fed
        # forward, two fingers squeezing an object chattered sideways with it at half the
        # step rate (+-0.02-0.04 m/s every other step, the positions still: a gripper
        # controller never saw a stall). The position term alone follows a moving leader
        # (lagging v * dt / POSITION_GAIN: 0.8 mm at 0.17 m/s and 1 kHz).
        p.setJointMotorControl2(
            body,
            m.follower,
            p.POSITION_CONTROL,
            targetPosition=target,
            targetVelocity=0.0,
            force=m.max_force,
            positionGain=POSITION_GAIN,
            velocityGain=VELOCITY_GAIN,
            physicsClientId=client,
        )
        if m.reroute is not None and m.last_effort:
            _reroute(body, client, m)


def measure(body: int, client: int, mimics: Sequence[MimicJoint]) -> None:
    """After a step: the force each follower's motor applied, for the next step's reroute."""
    for m in mimics:
        if m.reroute is not None:
            m.last_effort = p.getJointState(body, m.follower, physicsClientId=client)[3]


def _reroute(body: int, client: int, m: MimicJoint) -> None:
    """The motor pushed the follower's child with ``last_effort`` along its axis and its
    parent with the opposite: give the parent that back and the leader's parent the
    reaction instead (one step late: pybullet reports a motor's force after the step)."""
    assert m.reroute is not None
    parent, leader_parent, prismatic, axis_local = m.reroute
    # pybullet keeps a joint's axis in its child link's (centre of mass) frame.
    state = p.getLinkState(body, m.follower, computeForwardKinematics=True, physicsClientId=client)
    com, orn = state[0], state[1]
    matrix = p.getMatrixFromQuaternion(orn)
    axis = [sum(matrix[3 * r + c] * axis_local[c] for c in range(3)) for r in range(3)]
    effort = m.last_effort
    push = [effort * a for a in axis]
    pull = [-v for v in push]
    if prismatic:
        # The motor's force acts along the axis through the child's centre of mass: the
        # same line for both links keeps the moment balanced too.
        p.applyExternalForce(body, parent, push, com, p.WORLD_FRAME, physicsClientId=client)
        p.applyExternalForce(body, leader_parent, pull, com, p.WORLD_FRAME, physicsClientId=client)
    else:
        p.applyExternalTorque(body, parent, push, p.WORLD_FRAME, physicsClientId=client)
        p.applyExternalTorque(body, leader_parent, pull, p.WORLD_FRAME, physicsClientId=client)
