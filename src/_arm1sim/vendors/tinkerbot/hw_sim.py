"""TinkerHWSim: a toy RobotHWSim (control/interfaces.py), the pattern a vendor's follows.

Each joint of an EffortJointInterface transmission is read from the simulated robot and
written an effort: the controller's command times ``tinkerbot/gear_ratio`` (a parameter
under the robot namespace, default 1), clamped to the joint's URDF effort limit. Anything
else in the description or the parameters is refused with RobotHWSimError, which the
spawn reports under the robotSimType.
"""

from __future__ import annotations

import math
from typing import Dict, List, Optional, Sequence

from ...control.controller import ControllerError
from ...control.hardware_interface import EFFORT_JOINT_INTERFACE, JointHandle
from ...control.interfaces import NodeHandle, Resources, RobotHWSimError
from ...description.urdf_model import RobotModel
from ...physics.robot import Robot


class TinkerHWSim:
    def __init__(self, description: RobotModel, robot: Robot, period: float) -> None:
        self.robot = robot
        self.gear_ratio = 1.0
        self.handles: Dict[str, JointHandle] = {}
        for joint, interface in description.actuated_joints():
            if interface != EFFORT_JOINT_INTERFACE:
                raise RobotHWSimError(
                    "joint '%s': its transmission says %s; a Tinkerbot drives %s only"
                    % (joint.name, interface, EFFORT_JOINT_INTERFACE)
                )
            self.handles[joint.name] = JointHandle(joint.name, joint.type, joint.limits, interface)
        self._ordered = [self.handles[n] for n in sorted(self.handles)]
        self._indices = robot.indices([h.name for h in self._ordered])
        self.applied: List[float] = [0.0] * len(self._ordered)  # the last efforts written

    def init_sim(self, model_nh: NodeHandle, robot_namespace: str) -> None:
        own = model_nh.params.get('tinkerbot', {})
        ratio = own.get('gear_ratio', 1.0) if isinstance(own, dict) else 1.0
        if not isinstance(ratio, (int, float)) or not math.isfinite(ratio) or ratio <= 0:
            raise RobotHWSimError(
                '%s/tinkerbot/gear_ratio: %r is not a positive number'
                % (robot_namespace.rstrip('/'), ratio)
            )
        self.gear_ratio = float(ratio)

    def joint_names(self) -> List[str]:
        return sorted(self.handles)

    def get_handle(self, name: str, interface: Optional[str], controller_ns: str) -> JointHandle:
        handle = self.handles.get(name)
        if handle is None or interface not in (None, handle.interface):
            raise ControllerError(
                "%s: the Tinkerbot has no joint '%s' with %s" % (controller_ns, name, interface)
            )
        return handle

    def do_switch(self, start: Sequence[Resources], stop: Sequence[Resources]) -> None:
        """One interface per joint: nothing to switch."""

    def read(self, time_ns: int, period_ns: int) -> None:
        for h, (position, velocity) in zip(self._ordered, self.robot.read(self._indices)):
            h.position, h.velocity = position, velocity

    def write(self) -> None:
        efforts = []
        for h in self._ordered:
            limit = h.limits.effort if h.limits.effort else math.inf
            command = h.command if math.isfinite(h.command) else 0.0
            h.effort = min(max(command * self.gear_ratio, -limit), limit)
            efforts.append(h.effort)
        self.applied = efforts
        self.robot.apply_efforts(self._indices, efforts)
