"""gazebo_ros_ft_sensor: the wrench a joint exerts on its child link.

Gazebo (ODEJoint::GetForceTorque, body2): force and torque on the child in the child link's
axes, torque about the joint anchor (the child link's origin in a URDF), the joint's own
effort removed. pybullet's joint force-torque sensor reports the whole transmitted wrench in
the child's inertial frame with the moment about its centre of mass: converted here. pybullet
cannot tell the actuator's effort from a stop's, so along a revolute or prismatic joint's axis
the component is dropped (a joint pressed against its limit reads no axial load).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import pybullet as p

from .link_motion import Frame, Vec3, add, cross, gaussian, rotate, scale
from .robot import Robot
from .sim_sensor import SimSensor


@dataclass
class WrenchReading:
    force: Vec3
    torque: Vec3


class ForceTorque(SimSensor):
    kind = 'gazebo_ros_ft_sensor'

    def __init__(
        self,
        model: str,
        name: str,
        robot: Robot,
        joint: int,
        update_rate: float,
        noise: float = 0.0,
        feedback: bool = True,  # the joint's <provideFeedback>: without it Gazebo reads zeros
    ) -> None:
        super().__init__(model, name, update_rate)
        self.robot, self.joint, self.noise, self.feedback = robot, joint, noise, feedback
        cid = robot.client
        info = p.getJointInfo(robot.body, joint, physicsClientId=cid)
        self.axis: Optional[Vec3] = None
        if info[2] in (p.JOINT_REVOLUTE, p.JOINT_PRISMATIC):
            a = info[13]
            norm = (a[0] ** 2 + a[1] ** 2 + a[2] ** 2) ** 0.5
            self.axis = (a[0] / norm, a[1] / norm, a[2] / norm) if norm else None
            self.revolute = info[2] == p.JOINT_REVOLUTE
        com = p.getDynamicsInfo(robot.body, joint, physicsClientId=cid)[3:5]
        self.inertial: Frame = (tuple(com[0]), tuple(com[1]))
        self._enabled = False

    def enable(self) -> None:
        """pybullet computes joint reactions only when asked: only while someone listens."""
        if not self._enabled and self.feedback:
            p.enableJointForceTorqueSensor(
                self.robot.body, self.joint, True, physicsClientId=self.robot.client
            )
            self._enabled = True

    def update(self, now_ns: int) -> None:
        wanted = self.deliver is not None and self.wanted()
        if wanted and self.feedback and not self._enabled:
            self.enable()  # pybullet fills the reaction in the next step: measure from then
        elif wanted:
            super().update(now_ns)
        elif self._enabled:
            self.disable()  # nobody listens: pybullet stops computing it

    def measure(self, now_ns: int) -> WrenchReading:
        force: Vec3 = (0.0, 0.0, 0.0)
        torque: Vec3 = (0.0, 0.0, 0.0)
        if self.feedback:
            r = p.getJointState(self.robot.body, self.joint, physicsClientId=self.robot.client)[2]
            com, inertial_orn = self.inertial
            force = rotate(inertial_orn, r[:3])
            # about the centre of mass -> about the child frame's origin (the anchor)
            torque = add(rotate(inertial_orn, r[3:]), cross(com, force))
            if self.axis is not None:
                if self.revolute:
                    torque = _without(torque, self.axis)
                else:
                    force = _without(force, self.axis)
        n = self.noise
        return WrenchReading(
            (force[0] + gaussian(n), force[1] + gaussian(n), force[2] + gaussian(n)),
            (torque[0] + gaussian(n), torque[1] + gaussian(n), torque[2] + gaussian(n)),
        )

    def disable(self) -> None:
        if self._enabled:
            try:
                p.enableJointForceTorqueSensor(
                    self.robot.body, self.joint, False, physicsClientId=self.robot.client
                )
            except p.error:  # the body is already gone
                pass
            self._enabled = False

    def close(self) -> None:
        self.disable()
        super().close()


def _without(v: Vec3, axis: Vec3) -> Vec3:
    along = v[0] * axis[0] + v[1] * axis[1] + v[2] * axis[2]
    return add(v, scale(axis, -along))
