"""franka_gazebo/FrankaGripperSim: the Franka Hand's two fingers as a controller, ROS-free.

As franka_gripper_sim.cpp: an effort controller of ``<arm_id>_finger_joint1/2`` with the
actions franka_gripper serves on the real hand (``move``, ``grasp``, ``homing``, ``stop``)
and ``gripper_action`` (control_msgs/GripperCommand, each finger's position: half the
width). A state machine moves the fingers at the goal's speed with a PID per finger
(``finger1/gains``, ``finger2/gains``); a grasp ends when the fingers stop (the summed
speed under ``grasp/resting_threshold`` for ``grasp/consecutive_samples`` updates) and
then holds, pressing with the goal's force. ``joint_states`` of the fingers at 30 Hz.

Goals end from update (the physics thread), outside the lock: actionlib calls on_goal
holding its own lock (see control/gripper_action_controller.py).
"""

from __future__ import annotations

import math
import threading
from collections import deque
from dataclasses import dataclass
from typing import Any, Callable, Deque, Dict, List, Optional, Tuple

from ...control.controller import Controller, ControllerError
from ...control.hardware_interface import EFFORT_JOINT_INTERFACE, JointHandle
from ...control.interfaces import GoalHandle, NodeHandle, Publisher, RobotHW
from ...control.message_types import (
    FIELDS,
    GRIPPER_COMMAND_GOAL,
    STAMPED,
    register_action,
    register_message,
)
from ...control.pid import Pid, PidConfigError

register_message('sensor_msgs/JointState', STAMPED)
for _name in ('Move', 'Grasp', 'Homing', 'Stop'):
    register_action('franka_gripper/' + _name, FIELDS, FIELDS)
register_action('control_msgs/GripperCommand', GRIPPER_COMMAND_GOAL, FIELDS)

MAX_FINGER_WIDTH = 0.08  # m, both fingers
MOVE_WIDTH_TOLERANCE = 0.001
GRIPPER_ACTION_WIDTH_TOLERANCE = 0.005
GRIPPER_ACTION_SPEED = 0.1
GRASP_RESTING_THRESHOLD = 0.003
GRASP_CONSECUTIVE_SAMPLES = 10
HOMING_SPEED = 0.02
MINIMUM_GRASP_FORCE = 1e-4
PUBLISH_PERIOD_NS = int(1e9 / 30)

IDLE, MOVING, GRASPING, HOLDING = 'idle', 'moving', 'grasping', 'holding'

Outcome = Tuple[GoalHandle, str, Dict[str, Any]]  # goal handle, 'succeed'/'abort', result


@dataclass
class Config:
    width: float = 0.0
    speed: float = 0.0
    force: float = 0.0
    inner: float = MOVE_WIDTH_TOLERANCE
    outer: float = MOVE_WIDTH_TOLERANCE


@dataclass
class _Goal:
    """The goal waiting for the state machine: its kind and what decides its result."""

    kind: str  # 'move', 'grasp', 'homing', 'gripper_move', 'gripper_grasp'
    handle: GoalHandle
    width: float = 0.0
    inner: float = 0.0
    outer: float = 0.0
    phase: int = 0  # homing: 0 closing, 1 opening


def _number(params: Dict[str, Any], path: str, default: float, ns: str) -> float:
    value: Any = params
    for key in path.split('/'):
        value = value.get(key) if isinstance(value, dict) else None
    if value is None:
        return default
    try:
        f = float(value)
    except (TypeError, ValueError):
        raise ControllerError('%s/%s: %r is not a number' % (ns, path, value))
    if not math.isfinite(f):
        raise ControllerError('%s/%s: %r is not finite' % (ns, path, value))
    return f


def _failure(error: str) -> Dict[str, Any]:
    return dict(success=False, error=error)


class FrankaGripperSim(Controller):
    type_name = 'franka_gazebo/FrankaGripperSim'
    interface = EFFORT_JOINT_INTERFACE

    _pub: Publisher

    def __init__(self) -> None:
        super().__init__()
        self.finger1: Optional[JointHandle] = None
        self.finger2: Optional[JointHandle] = None
        self.pid1, self.pid2 = Pid(), Pid()
        self.tolerance_move = MOVE_WIDTH_TOLERANCE
        self.tolerance_gripper_action = GRIPPER_ACTION_WIDTH_TOLERANCE
        self.speed_default = GRIPPER_ACTION_SPEED
        self.speed_threshold = GRASP_RESTING_THRESHOLD
        self.speed_samples = GRASP_CONSECUTIVE_SAMPLES
        self.mode = IDLE
        self.config = Config()
        self._lock = threading.Lock()
        self._goal: Optional[_Goal] = None
        # the fingers' summed speed over the last grasp/consecutive_samples updates
        self._speeds: Deque[float] = deque(maxlen=GRASP_CONSECUTIVE_SAMPLES)
        self._last_publish_ns: Optional[int] = None

    def init(self, robot_hw: RobotHW, root_nh: NodeHandle, controller_nh: NodeHandle) -> None:
        ns, params = controller_nh.namespace, controller_nh.params
        arm_id = params.get('arm_id')
        if not isinstance(arm_id, str) or not arm_id:
            raise ControllerError("Could not find required parameter '%s/arm_id'" % ns)
        self.finger1 = robot_hw.get_handle(arm_id + '_finger_joint1', self.interface, ns)
        self.finger2 = robot_hw.get_handle(arm_id + '_finger_joint2', self.interface, ns)
        self.joints = [self.finger1, self.finger2]
        self.tolerance_move = _number(params, 'move/width_tolerance', MOVE_WIDTH_TOLERANCE, ns)
        self.tolerance_gripper_action = _number(
            params, 'gripper_action/width_tolerance', GRIPPER_ACTION_WIDTH_TOLERANCE, ns
        )
        self.speed_default = _number(params, 'gripper_action/speed', GRIPPER_ACTION_SPEED, ns)
        self.speed_threshold = _number(
            params, 'grasp/resting_threshold', GRASP_RESTING_THRESHOLD, ns
        )
        self.speed_samples = int(
            _number(params, 'grasp/consecutive_samples', GRASP_CONSECUTIVE_SAMPLES, ns)
        )
        if self.speed_samples < 1:
            raise ControllerError('%s/grasp/consecutive_samples must be at least 1' % ns)
        self._speeds = deque(maxlen=self.speed_samples)
        for i in (1, 2):
            gains = params.get('finger%d' % i, {})
            try:
                pid = Pid.from_params(
                    gains.get('gains') if isinstance(gains, dict) else None,
                    '%s/finger%d/gains' % (ns, i),
                )
            except PidConfigError as exc:
                raise ControllerError(str(exc))
            setattr(self, 'pid%d' % i, pid)
        self._pub = controller_nh.advertise('joint_states', 'sensor_msgs/JointState', 1)
        servers: List[Tuple[str, str, Callable[[GoalHandle], None]]] = [
            ('stop', 'franka_gripper/Stop', self.on_stop),
            ('homing', 'franka_gripper/Homing', self.on_homing),
            ('move', 'franka_gripper/Move', self.on_move),
            ('grasp', 'franka_gripper/Grasp', self.on_grasp),
            ('gripper_action', 'control_msgs/GripperCommand', self.on_gripper_action),
        ]
        for name, type_name, on_goal in servers:
            controller_nh.action_server(name, type_name, on_goal, self.on_cancel)

    @property
    def width(self) -> float:
        assert self.finger1 is not None and self.finger2 is not None
        return self.finger1.position + self.finger2.position

    # -- run state -------------------------------------------------------------------------
    def starting(self, time_ns: int) -> None:
        with self._lock:
            self.mode, self.config = IDLE, Config()
        self.pid1.reset()
        self.pid2.reset()
        self._last_publish_ns = None

    def stopping(self, time_ns: int) -> None:
        with self._lock:
            goal, self._goal = self._goal, None
            self.mode = IDLE
        if goal is not None:
            goal.handle.cancel(_failure('the gripper controller was stopped'))

    # -- goals (any thread) ----------------------------------------------------------------
    def _start(self, gh: GoalHandle, goal: Optional[_Goal], state: str, config: Config) -> None:
        """Accept ``gh`` and make it the goal (None: answered at once); the goal it replaces
        is aborted, as upstream's interrupt."""
        gh.accept()
        with self._lock:
            if not self.running:
                previous: Optional[_Goal] = None
                refused = True
            else:
                refused = False
                previous, self._goal = self._goal, goal
                self.mode, self.config = state, config
                self._speeds.clear()
        if refused:
            gh.abort(_failure("Can't accept new action goals. Controller is not running."))
            return
        if previous is not None:
            previous.handle.abort(
                self._result(previous, False, 'Command interrupted, because a new goal came')
            )

    def on_stop(self, gh: GoalHandle) -> None:
        self._start(gh, None, IDLE, Config(width=self.config.width))
        gh.succeed(dict(success=True, error=''))

    def on_homing(self, gh: GoalHandle) -> None:
        eps = self.tolerance_move
        self._start(gh, _Goal('homing', gh), MOVING, Config(0.0, HOMING_SPEED, 0.0, eps, eps))

    def on_move(self, gh: GoalHandle) -> None:
        width, speed = gh.goal.get('width'), gh.goal.get('speed')
        error = self._check_move(width, speed)
        if error:
            gh.accept()
            gh.abort(_failure(error))
            return
        eps = self.tolerance_move
        goal = _Goal('move', gh, float(width), eps, eps)  # type: ignore[arg-type]
        self._start(gh, goal, MOVING, Config(float(width), float(speed), 0.0, eps, eps))  # type: ignore[arg-type]

    def on_grasp(self, gh: GoalHandle) -> None:
        g = gh.goal
        eps = g.get('epsilon') or {}
        values = (
            g.get('width'),
            g.get('speed'),
            g.get('force'),
            eps.get('inner'),
            eps.get('outer'),
        )
        if not all(isinstance(v, (int, float)) and math.isfinite(v) for v in values):
            gh.accept()
            gh.abort(_failure('width, speed, force and epsilon must be finite numbers'))
            return
        width, speed, force, inner, outer = (float(v) for v in values)  # type: ignore[arg-type]
        if width >= MAX_FINGER_WIDTH or width < 0:
            gh.accept()
            gh.abort(
                _failure('Can only grasp inside finger width from [0 .. %f[' % MAX_FINGER_WIDTH)
            )
            return
        if speed < 0:
            gh.accept()
            gh.abort(_failure('Only positive speeds allowed'))
            return
        self._grasp(gh, 'grasp', width, speed, force, inner, outer)

    def on_gripper_action(self, gh: GoalHandle) -> None:
        command = gh.goal.get('command') or {}
        position, max_effort = command.get('position'), command.get('max_effort')
        if not all(
            isinstance(v, (int, float)) and math.isfinite(v) for v in (position, max_effort)
        ):
            gh.accept()
            gh.abort(dict(reached_goal=False))
            return
        # As upstream: MoveIt sends one finger's position (the other mimics it): width = 2x.
        width = 2.0 * float(position)  # type: ignore[arg-type]
        if not 0.0 <= width <= MAX_FINGER_WIDTH:
            gh.accept()
            gh.abort(dict(reached_goal=False, position=self.width))
            return
        effort = float(max_effort)  # type: ignore[arg-type]
        if abs(effort) < MINIMUM_GRASP_FORCE or width > self.width:
            eps = self.tolerance_move
            goal = _Goal('gripper_move', gh, width, eps, eps)
            self._start(gh, goal, MOVING, Config(width, self.speed_default, 0.0, eps, eps))
        else:
            eps = self.tolerance_gripper_action
            self._grasp(
                gh,
                'gripper_grasp',
                width,
                self.speed_default,
                float(max_effort),  # type: ignore[arg-type]
                eps,
                eps,
            )

    def _grasp(
        self,
        gh: GoalHandle,
        kind: str,
        width: float,
        speed: float,
        force: float,
        inner: float,
        outer: float,
    ) -> None:
        current = self.width
        direction = math.copysign(1.0, width - current)
        target = 0.0 if width < current else MAX_FINGER_WIDTH
        config = Config(target, speed, direction * force, inner, outer)
        self._start(gh, _Goal(kind, gh, width, inner, outer), GRASPING, config)

    @staticmethod
    def _check_move(width: Any, speed: Any) -> str:
        if not isinstance(speed, (int, float)) or not math.isfinite(speed) or speed < 0:
            return 'Only positive speeds allowed'
        if not isinstance(width, (int, float)) or not math.isfinite(width):
            return 'Target width has to lie between 0 .. %f' % MAX_FINGER_WIDTH
        if width < 0 or width > MAX_FINGER_WIDTH:
            return 'Target width has to lie between 0 .. %f' % MAX_FINGER_WIDTH
        return ''

    def on_cancel(self, gh: GoalHandle) -> None:
        with self._lock:
            goal = self._goal
            if goal is None or goal.handle.id != gh.id:
                return
            self._goal, self.mode = None, IDLE
        gh.cancel(self._result(goal, False, 'cancelled'))

    def _result(self, goal: _Goal, ok: bool, error: str = '') -> Dict[str, Any]:
        if goal.kind.startswith('gripper_'):
            return dict(position=self.width, effort=0.0, stalled=False, reached_goal=ok)
        return dict(success=ok, error=error)

    # -- the control cycle (physics thread) ------------------------------------------------
    def update(self, time_ns: int, period_ns: int) -> None:
        f1, f2 = self.finger1, self.finger2
        assert f1 is not None and f2 is not None
        last = self._last_publish_ns
        if last is None or not last <= time_ns < last + PUBLISH_PERIOD_NS:
            self._last_publish_ns = time_ns
            self._pub.publish(
                dict(
                    stamp=time_ns,
                    name=[f1.name, f2.name],
                    position=[f1.position, f2.position],
                    velocity=[f1.velocity, f2.velocity],
                    effort=[f1.effort, f2.effort],
                )
            )
        dt = max(period_ns, 1) * 1e-9
        with self._lock:
            outcome = self._step(f1, f2, dt)
        if outcome is not None:
            gh, what, result = outcome
            getattr(gh, what)(result)

    def _step(self, f1: JointHandle, f2: JointHandle, dt: float) -> Optional[Outcome]:
        """One update of franka_gripper_sim's state machine (lock held)."""
        width, state, c = f1.position + f2.position, self.mode, self.config
        if state == IDLE:
            # each finger tracks the other (a mimic joint), with high damping
            self._control(f1, self.pid1, f2.position, 0.0, 0.0, dt)
            self._control(f2, self.pid2, f1.position, 0.0, 0.0, dt)
            return None
        dw = c.speed * math.copysign(1.0, c.width - width)
        w1, w2, force = f1.position + 0.5 * dw * dt, f2.position + 0.5 * dw * dt, 0.0
        if state == HOLDING:
            w1, w2, force = f2.position, f1.position, c.force / 2.0
        self._control(f1, self.pid1, w1, 0.5 * dw, force, dt)
        self._control(f2, self.pid2, w2, 0.5 * dw, force, dt)
        if state == MOVING and c.width - c.inner < width < c.width + c.outer:
            self.mode, self.config = IDLE, Config(c.width, 0.0, 0.0, c.inner, c.outer)
            return self._settle(width)
        if state in (GRASPING, MOVING):
            # Upstream wants every one of the samples under the threshold; pybullet's joint
            # limit leaves a finger pressed on it jittering at +-0.008 m/s from one step to
            # the next, so the samples' mean is held to it instead.
            self._speeds.append(f1.velocity + f2.velocity)
            resting = abs(sum(self._speeds)) <= self.speed_threshold * len(self._speeds)
            if len(self._speeds) >= self.speed_samples and resting:
                self._speeds.clear()
                if state == GRASPING:
                    self.mode = HOLDING
                    self.config = Config(width, 0.0, c.force, c.inner, c.outer)
                else:  # a move blocked by an object: it ends where the fingers are
                    self.mode, self.config = IDLE, Config(width, 0.0, 0.0, c.inner, c.outer)
                return self._settle(width)
        return None

    def _settle(self, width: float) -> Optional[Outcome]:
        """The state just changed: the waiting goal's result, if this ends it."""
        goal = self._goal
        if goal is None:
            return None
        if goal.kind == 'homing' and goal.phase == 0:
            goal.phase = 1  # closed: now open all the way
            eps = self.tolerance_move
            self.mode = MOVING
            self.config = Config(MAX_FINGER_WIDTH, HOMING_SPEED, 0.0, eps, eps)
            return None
        self._goal = None
        within = goal.width - goal.inner < width < goal.width + goal.outer
        if goal.kind == 'homing':
            return goal.handle, 'succeed', dict(success=True, error='')
        if goal.kind == 'move':
            return goal.handle, 'succeed', dict(success=within, error='')
        if goal.kind == 'gripper_move':  # upstream: reached once the move ended
            return goal.handle, 'succeed', self._result(goal, True)
        # grasps: holding now
        if not within:
            self.mode = IDLE
        if goal.kind == 'gripper_grasp':
            return goal.handle, 'succeed', self._result(goal, within)
        error = (
            ''
            if within
            else 'When the gripper stopped (below speed of %f m/s the width between the fingers '
            'was not at %fm (-%fm/+%fm) but at %fm'
            % (self.speed_threshold, goal.width, goal.inner, goal.outer, width)
        )
        return goal.handle, 'succeed', dict(success=within, error=error)

    @staticmethod
    def _control(
        joint: JointHandle, pid: Pid, target: float, target_velocity: float, force: float, dt: float
    ) -> None:
        error, error_dot = target - joint.position, target_velocity - joint.velocity
        joint.command = pid.compute_command_with_rate(error, error_dot, dt) + force
