"""gripper_action_controller, ROS-free: one joint driven to a GripperCommand goal's position,
with upstream's stall detection.

``position_controllers/GripperActionController`` writes the goal position; the effort one
runs a PID (``gains/<joint>``) to an effort clamped to the goal's +-|max_effort|. A goal
succeeds (reached_goal) within ``goal_tolerance`` of its position and is aborted (stalled)
when the joint has not moved faster than ``stall_velocity_threshold`` for ``stall_timeout``
seconds, e.g. because the fingers closed on an object. No feedback is published, as upstream.

update ends goals outside the lock: actionlib calls on_goal/on_cancel holding its own lock,
so the physics thread must not wait for ours while calling into actionlib.
"""

from __future__ import annotations

import logging
import math
import threading
from typing import Any, ClassVar, Dict, Optional, Tuple

from .controller import Controller, ControllerError, require_param
from .hardware_interface import EFFORT_JOINT_INTERFACE, POSITION_JOINT_INTERFACE, JointHandle
from .interfaces import GoalHandle, NodeHandle, RobotHW
from .message_types import FIELDS, GRIPPER_COMMAND_GOAL, register_action
from .pid import Pid, PidConfigError

log = logging.getLogger('_arm1sim.control')

register_action('control_msgs/GripperCommand', GRIPPER_COMMAND_GOAL, FIELDS)

NS = 1e-9


def _param(params: Dict[str, Any], key: str, default: float, ns: str) -> float:
    value = params.get(key, default)
    try:
        f = float(value)
    except (TypeError, ValueError):
        raise ControllerError('%s/%s: %r is not a number' % (ns, key, value))
    if not math.isfinite(f):
        raise ControllerError('%s/%s: %r is not finite' % (ns, key, value))
    return f


class GripperActionController(Controller):
    type_name = 'effort_controllers/GripperActionController'
    interface = EFFORT_JOINT_INTERFACE
    commands_position: ClassVar[bool] = False  # the hardware_interface_adapter: PID to effort

    def __init__(self) -> None:
        super().__init__()
        self.joint: Optional[JointHandle] = None
        self.pid = Pid()
        self.goal_tolerance = 0.01
        self.default_max_effort = 0.0
        self.stall_velocity_threshold = 0.001
        self.stall_timeout = 1.0
        self._lock = threading.Lock()
        self._active: Optional[GoalHandle] = None
        self.position = 0.0  # the command: desired position and the effort allowed
        self.max_effort = 0.0
        self.computed_effort = 0.0  # what the result reports as effort
        self._last_movement_ns = 0
        self._time_ns = 0

    def init(self, robot_hw: RobotHW, root_nh: NodeHandle, controller_nh: NodeHandle) -> None:
        ns, params = controller_nh.namespace, controller_nh.params
        name = require_param(params, 'joint', ns)
        if not isinstance(name, str) or not name:
            raise ControllerError("%s: the 'joint' parameter is not a joint name: %r" % (ns, name))
        self.joint = robot_hw.get_handle(name, self.interface, ns)
        self.joints = [self.joint]
        self.goal_tolerance = abs(_param(params, 'goal_tolerance', 0.01, ns))
        self.default_max_effort = abs(_param(params, 'max_effort', 0.0, ns))
        self.stall_velocity_threshold = _param(params, 'stall_velocity_threshold', 0.001, ns)
        self.stall_timeout = _param(params, 'stall_timeout', 1.0, ns)
        if not self.commands_position:
            gains = params.get('gains', {})
            try:
                self.pid = Pid.from_params(
                    gains.get(name) if isinstance(gains, dict) else None,
                    '%s/gains/%s' % (ns, name),
                )
            except PidConfigError as exc:  # upstream only warns: the joint gets no effort
                log.warning('%s: %s', ns, exc)
                self.pid = Pid()
        controller_nh.action_server(
            'gripper_cmd', 'control_msgs/GripperCommand', self.on_goal, self.on_cancel
        )

    # -- run state -------------------------------------------------------------------------
    def starting(self, time_ns: int) -> None:
        assert self.joint is not None
        with self._lock:
            self.position, self.max_effort = self.joint.position, self.default_max_effort
            self.pid.reset()
            self._time_ns = self._last_movement_ns = time_ns

    def stopping(self, time_ns: int) -> None:
        with self._lock:
            active, self._active = self._active, None
        if active is not None:
            active.cancel({})
        if not self.commands_position and self.joint is not None:
            self.joint.command = 0.0

    # -- goals (any thread) ----------------------------------------------------------------
    def on_goal(self, gh: GoalHandle) -> None:
        """A GripperCommand goal: accepted, preempting the active one, or rejected."""
        command = gh.goal.get('command') or {}
        values = (command.get('position'), command.get('max_effort'))
        with self._lock:  # accepted under the lock: update must not end a pending goal
            if not self.running:
                log.error(
                    "%s: Can't accept new action goals. Controller is not running.", self.name
                )
                gh.reject({})
                return
            if not all(isinstance(v, (int, float)) and math.isfinite(v) for v in values):
                log.error(
                    '%s: rejecting goal: position %r and max_effort %r must be finite',
                    self.name,
                    *values,
                )
                gh.reject({})
                return
            previous, self._active = self._active, gh
            self.position, self.max_effort = float(values[0]), float(values[1])  # type: ignore[arg-type]
            self._last_movement_ns = self._time_ns
            if previous is not None:
                previous.cancel({})
            gh.accept()

    def on_cancel(self, gh: GoalHandle) -> None:
        """Cancelling the active goal holds where the joint is, at the default max_effort."""
        with self._lock:
            if self._active is None or self._active.id != gh.id or self.joint is None:
                return
            self._active = None
            self.position, self.max_effort = self.joint.position, self.default_max_effort
        gh.cancel({})

    # -- the control cycle (physics thread) ------------------------------------------------
    def update(self, time_ns: int, period_ns: int) -> None:
        joint = self.joint
        assert joint is not None
        outcome: Optional[Tuple[GoalHandle, str, Dict[str, Any]]] = None
        with self._lock:
            self._time_ns = time_ns
            error_position = self.position - joint.position
            error_velocity = -joint.velocity
            outcome = self._check_for_success(time_ns, error_position, joint)
            allowed = abs(self.max_effort)
            if self.commands_position:
                joint.command = self.position
                self.computed_effort = allowed
            else:
                effort = self.pid.compute_command_with_rate(
                    error_position, error_velocity, max(period_ns, 0) * NS
                )
                self.computed_effort = max(-allowed, min(effort, allowed))
                joint.command = self.computed_effort
        if outcome is not None:
            gh, what, result = outcome
            getattr(gh, what)(result)

    def _check_for_success(
        self, time_ns: int, error_position: float, joint: JointHandle
    ) -> Optional[Tuple[GoalHandle, str, Dict[str, Any]]]:
        """Upstream's checkForSuccess (lock held); the effort reported is the last command's."""
        active = self._active
        if active is None:
            return None
        if abs(error_position) < self.goal_tolerance:
            self._active = None
            return active, 'succeed', self._result(joint, stalled=False, reached=True)
        if abs(joint.velocity) > self.stall_velocity_threshold:
            self._last_movement_ns = time_ns
        elif (time_ns - self._last_movement_ns) * NS > self.stall_timeout:
            self._active = None
            return active, 'abort', self._result(joint, stalled=True, reached=False)
        return None

    def _result(self, joint: JointHandle, stalled: bool, reached: bool) -> Dict[str, Any]:
        return dict(
            position=joint.position,
            effort=self.computed_effort,
            stalled=stalled,
            reached_goal=reached,
        )


class PositionGripperActionController(GripperActionController):
    type_name = 'position_controllers/GripperActionController'
    interface = POSITION_JOINT_INTERFACE
    commands_position = True  # the goal position goes to the joint; effort reported = max_effort
