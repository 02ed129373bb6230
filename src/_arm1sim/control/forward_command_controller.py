"""ros_controllers' forward_command_controller family: the command goes to the joint as is.

One class per shape, parametrised by interface as upstream's templates are:
ForwardCommandController (one ``joint``, std_msgs/Float64 ``command``) and
ForwardJointGroupCommandController (``joints``, std_msgs/Float64MultiArray ``command``,
``data[i]`` to ``joints[i]``). No clamping, no state topic: the hardware's joint limits
apply. Position controllers start at the current position(s), the others at zero.
"""

from __future__ import annotations

import logging
import math
import time
from typing import Any, ClassVar, List

from .controller import Controller, ControllerError
from .hardware_interface import (
    EFFORT_JOINT_INTERFACE,
    POSITION_JOINT_INTERFACE,
    VELOCITY_JOINT_INTERFACE,
    JointHandle,
)
from .interfaces import NodeHandle, RobotHW
from .message_types import DATA, register_message

log = logging.getLogger('_arm1sim.control')

register_message('std_msgs/Float64', DATA)  # the commands
register_message('std_msgs/Float64MultiArray', DATA)

WARN_PERIOD = 5.0  # seconds between repeated warnings of one kind


class _Forward(Controller):
    """What both shapes share: the start value and the refusal of non-finite commands."""

    start_at_position: ClassVar[bool] = False

    def __init__(self) -> None:
        super().__init__()
        self.commands: List[float] = []  # one per joint; replaced whole by the ROS thread
        self._last_warn = -math.inf

    def starting(self, time_ns: int) -> None:
        # Commands sent before start are overwritten, as upstream's starting() does.
        self.commands = [j.position if self.start_at_position else 0.0 for j in self.joints]

    def update(self, time_ns: int, period_ns: int) -> None:
        for joint, command in zip(self.joints, self.commands):
            joint.command = command

    def _warn(self, message: str, *args: Any) -> None:
        now = time.monotonic()
        if now - self._last_warn > WARN_PERIOD:
            self._last_warn = now
            log.warning(message, *args)

    def _finite(self, values: List[float]) -> bool:
        bad = [v for v in values if not math.isfinite(v)]
        if bad:
            # Upstream forwards them; a NaN position would wreck the physics, so hold instead.
            self._warn(
                '%s: ignoring a command with non-finite value(s) %s; holding %s',
                self.name,
                bad,
                self.commands,
            )
        return not bad


class ForwardCommandController(_Forward):
    """forward_command_controller::ForwardCommandController<interface>."""

    joint: JointHandle

    def init(self, robot_hw: RobotHW, root_nh: NodeHandle, controller_nh: NodeHandle) -> None:
        ns = controller_nh.namespace
        name = controller_nh.params.get('joint')
        if not isinstance(name, str) or not name:
            raise ControllerError('No joint given (namespace: %s)' % ns)
        self.joint = robot_hw.get_handle(name, self.interface, ns)
        self.joints = [self.joint]
        self.commands = [0.0]
        controller_nh.subscribe('command', 'std_msgs/Float64', self.set_command)

    def set_command(self, value: float) -> bool:
        """The command topic's callback (ROS thread); returns whether it was taken."""
        value = float(value)
        if not self._finite([value]):
            return False
        self.commands = [value]
        return True


class ForwardJointGroupCommandController(_Forward):
    """forward_command_controller::ForwardJointGroupCommandController<interface>."""

    def init(self, robot_hw: RobotHW, root_nh: NodeHandle, controller_nh: NodeHandle) -> None:
        ns = controller_nh.namespace
        names = controller_nh.params.get('joints')
        if not isinstance(names, list) or not all(isinstance(n, str) for n in names):
            raise ControllerError("Failed to getParam 'joints' (namespace: %s)." % ns)
        if not names:
            raise ControllerError('List of joint names is empty.')
        self.joints = [robot_hw.get_handle(n, self.interface, ns) for n in names]
        self.commands = [0.0] * len(self.joints)
        controller_nh.subscribe('command', 'std_msgs/Float64MultiArray', self.set_commands)

    def set_commands(self, data: Any) -> bool:
        """The command topic's callback (ROS thread): ``data[i]`` for ``joints[i]``. A command
        of the wrong size is dropped with upstream's error; returns whether it was taken."""
        values = [float(v) for v in data]
        if len(values) != len(self.joints):
            log.error(
                '%s: Dimension of command (%d) does not match number of joints (%d)! '
                'Not executing!',
                self.name,
                len(values),
                len(self.joints),
            )
            return False
        if not self._finite(values):
            return False
        self.commands = values
        return True


class PositionJointPositionController(ForwardCommandController):
    type_name = 'position_controllers/JointPositionController'
    interface = POSITION_JOINT_INTERFACE
    start_at_position = True


class VelocityJointVelocityController(ForwardCommandController):
    type_name = 'velocity_controllers/JointVelocityController'
    interface = VELOCITY_JOINT_INTERFACE


class EffortJointEffortController(ForwardCommandController):
    type_name = 'effort_controllers/JointEffortController'
    interface = EFFORT_JOINT_INTERFACE

    def stopping(self, time_ns: int) -> None:
        self.joint.command = 0.0  # as the PID effort controllers here: no effort left behind


class JointGroupPositionController(ForwardJointGroupCommandController):
    type_name = 'position_controllers/JointGroupPositionController'
    interface = POSITION_JOINT_INTERFACE
    start_at_position = True


class JointGroupVelocityController(ForwardJointGroupCommandController):
    type_name = 'velocity_controllers/JointGroupVelocityController'
    interface = VELOCITY_JOINT_INTERFACE


class JointGroupEffortController(ForwardJointGroupCommandController):
    type_name = 'effort_controllers/JointGroupEffortController'
    interface = EFFORT_JOINT_INTERFACE

    def stopping(self, time_ns: int) -> None:
        for joint in self.joints:
            joint.command = 0.0


FORWARD_CONTROLLERS = (
    PositionJointPositionController,
    VelocityJointVelocityController,
    EffortJointEffortController,
    JointGroupPositionController,
    JointGroupVelocityController,
    JointGroupEffortController,
)
