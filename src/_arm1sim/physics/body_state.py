"""Poses, twists and external forces of a Robot's links, as Gazebo states them.

Gazebo speaks of link *frames* and their origins' velocities; pybullet of centres of
mass. These functions convert at the boundary so callers only see Gazebo's view.
"""

from __future__ import annotations

from typing import Dict, List, Optional, Sequence, Tuple

import pybullet as p

from .robot import Robot

Vec = Tuple[float, float, float]
Quat = Tuple[float, float, float, float]
LinkState = Tuple[Vec, Quat, Vec, Vec]  # frame position, orientation, origin velocity, angular


def cross(a: Sequence[float], b: Sequence[float]) -> Vec:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _origin_velocity(
    v_com: Sequence[float], w: Sequence[float], com: Sequence[float], origin: Sequence[float]
) -> Vec:
    """Velocity of a point of a rigid body: v_com + w x (origin - com)."""
    r = [o - c for o, c in zip(origin, com)]
    wr = cross(w, r)
    return (v_com[0] + wr[0], v_com[1] + wr[1], v_com[2] + wr[2])


def link_states(robot: Robot) -> Dict[str, LinkState]:
    """Every link's frame pose and its origin's twist, in world axes, from one batch of reads."""
    cid, body = robot.client, robot.body
    com_pos, com_orn = p.getBasePositionAndOrientation(body, physicsClientId=cid)
    v, w = p.getBaseVelocity(body, physicsClientId=cid)
    pos, orn = p.multiplyTransforms(com_pos, com_orn, *robot._base_from_com)
    out: Dict[str, LinkState] = {}
    indices = [i for i in robot.link_index.values() if i >= 0]
    states = (
        p.getLinkStates(
            body, indices, computeLinkVelocity=1, computeForwardKinematics=1, physicsClientId=cid
        )
        if indices
        else []
    )
    by_index = dict(zip(indices, states))
    for name, i in robot.link_index.items():
        if i == -1:
            out[name] = (tuple(pos), tuple(orn), _origin_velocity(v, w, com_pos, pos), tuple(w))
        else:
            s = by_index[i]
            out[name] = (
                tuple(s[4]),
                tuple(s[5]),
                _origin_velocity(s[6], s[7], s[0], s[4]),
                tuple(s[7]),
            )
    return out


def base_state(robot: Robot) -> LinkState:
    """The base (root) link's frame pose and origin twist only: two pybullet reads."""
    cid, body = robot.client, robot.body
    com_pos, com_orn = p.getBasePositionAndOrientation(body, physicsClientId=cid)
    v, w = p.getBaseVelocity(body, physicsClientId=cid)
    pos, orn = p.multiplyTransforms(com_pos, com_orn, *robot._base_from_com)
    return (tuple(pos), tuple(orn), _origin_velocity(v, w, com_pos, pos), tuple(w))


def set_base_state(
    robot: Robot,
    position: Sequence[float],
    orientation: Sequence[float],
    linear: Sequence[float],
    angular: Sequence[float],
) -> None:
    """Move the root link's frame there, joints kept; every link gets the same twist
    (Gazebo's Model::SetLinearVel/SetAngularVel), so joint rates become zero."""
    cid, body = robot.client, robot.body
    com_from_base = p.invertTransform(*robot._base_from_com)
    com_pos, com_orn = p.multiplyTransforms(position, orientation, *com_from_base)
    p.resetBasePositionAndOrientation(body, com_pos, com_orn, physicsClientId=cid)
    v_com = _origin_velocity(linear, angular, position, com_pos)
    p.resetBaseVelocity(body, v_com, list(angular), physicsClientId=cid)
    movable = robot.movable
    if movable:
        positions = [s[0] for s in p.getJointStates(body, movable, physicsClientId=cid)]
        for i, q in zip(movable, positions):
            p.resetJointState(body, i, q, 0.0, physicsClientId=cid)


def com_position(robot: Robot, link: str) -> Vec:
    i = robot.link_index[link]
    if i == -1:
        return tuple(p.getBasePositionAndOrientation(robot.body, physicsClientId=robot.client)[0])
    return tuple(
        p.getLinkState(
            robot.body,
            i,
            computeForwardKinematics=1,
            physicsClientId=robot.client,
        )[0]
    )


def apply_wrench(robot: Robot, link: str, force: Sequence[float], torque: Sequence[float]) -> None:
    """World-axis force at the link's centre of mass and torque, for the next step only."""
    i = robot.link_index[link]
    cid = robot.client
    p.applyExternalForce(
        robot.body,
        i,
        list(force),
        list(com_position(robot, link)),
        p.WORLD_FRAME,
        physicsClientId=cid,
    )
    p.applyExternalTorque(robot.body, i, list(torque), p.WORLD_FRAME, physicsClientId=cid)


def apply_joint_effort(robot: Robot, joint: str, effort: float) -> None:
    """A joint effort for the next step, on top of any motor or torque command: equal and
    opposite torques (revolute) or forces (prismatic) along the axis on child and parent."""
    cid, body = robot.client, robot.body
    i = robot.joint_index[joint]
    info = p.getJointInfo(body, i, physicsClientId=cid)
    kind, axis, parent = info[2], info[13], info[16]
    if kind not in (p.JOINT_REVOLUTE, p.JOINT_PRISMATIC):
        return
    orn = p.getLinkState(body, i, computeForwardKinematics=1, physicsClientId=cid)[5]
    world_axis = p.rotateVector(orn, axis)
    v = [effort * c for c in world_axis]
    minus = [-c for c in v]
    if kind == p.JOINT_REVOLUTE:
        p.applyExternalTorque(body, i, v, p.WORLD_FRAME, physicsClientId=cid)
        p.applyExternalTorque(body, parent, minus, p.WORLD_FRAME, physicsClientId=cid)
    else:
        p.applyExternalForce(
            body, i, v, list(com_position_index(robot, i)), p.WORLD_FRAME, physicsClientId=cid
        )
        p.applyExternalForce(
            body,
            parent,
            minus,
            list(com_position_index(robot, parent)),
            p.WORLD_FRAME,
            physicsClientId=cid,
        )


def com_position_index(robot: Robot, i: int) -> Vec:
    if i == -1:
        pos = p.getBasePositionAndOrientation(robot.body, physicsClientId=robot.client)[0]
    else:
        pos = p.getLinkState(
            robot.body, i, computeForwardKinematics=1, physicsClientId=robot.client
        )[0]
    return (pos[0], pos[1], pos[2])


def effort_limit(robot: Robot, joint: str) -> float:
    """The URDF's effort limit as pybullet keeps it; 0 when none was given."""
    return p.getJointInfo(robot.body, robot.joint_index[joint], physicsClientId=robot.client)[10]


def set_joint_dynamics(
    robot: Robot,
    joint: str,
    damping: Optional[float] = None,
    lower: Optional[float] = None,
    upper: Optional[float] = None,
) -> None:
    """What of ODE's joint properties pybullet has: viscous damping and the stops."""
    kwargs: Dict[str, float] = {}
    if damping is not None:
        kwargs['jointDamping'] = damping
    if lower is not None or upper is not None:
        info = p.getJointInfo(robot.body, robot.joint_index[joint], physicsClientId=robot.client)
        kwargs['jointLowerLimit'] = info[8] if lower is None else lower
        kwargs['jointUpperLimit'] = info[9] if upper is None else upper
    if kwargs:
        p.changeDynamics(
            robot.body, robot.joint_index[joint], physicsClientId=robot.client, **kwargs
        )


def link_properties(robot: Robot, link: str) -> Tuple[float, Vec, Vec]:
    """Mass, centre of mass in the link frame, principal inertia diagonal."""
    info = p.getDynamicsInfo(robot.body, robot.link_index[link], physicsClientId=robot.client)
    return info[0], tuple(info[3]), tuple(info[2])


def joint_state(robot: Robot, joint: str) -> Tuple[float, float]:
    s = p.getJointState(robot.body, robot.joint_index[joint], physicsClientId=robot.client)
    return s[0], s[1]


def set_gravity(client: int, gravity: Sequence[float]) -> None:
    p.setGravity(*gravity, physicsClientId=client)


def link_names(robot: Robot) -> List[str]:
    return list(robot.link_index)
