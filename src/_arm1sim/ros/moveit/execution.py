"""Executing a trajectory as MoveIt's TrajectoryExecutionManager does.

The trajectory's start must be within allowed_start_tolerance of the current state (else
it is refused: CONTROL_FAILED); it is split among the controllers that cover its joints
(default ones first), sent to each at once, and watched: with execution duration
monitoring, a part still running after its duration x allowed_execution_duration_scaling
+ allowed_goal_duration_margin is cancelled (TIMED_OUT). A stop (``stop()``, or "stop" on
trajectory_execution_event) cancels every part (PREEMPTED).
"""

from __future__ import annotations

import threading
from typing import Callable, Dict, List, Optional, Tuple

import rospy
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

from ...planning.config import ControllerConfig, ExecutionConfig
from ...planning.error_codes import CONTROL_FAILED, SUCCESS
from ...planning.error_codes import PREEMPTED as PREEMPTED_CODE
from ...planning.error_codes import TIMED_OUT as TIMED_OUT_CODE
from .controller_managers import (
    PREEMPTED,
    SUCCEEDED,
    TIMED_OUT,
    ControllerHandle,
    ControllerManager,
)


def select_controllers(
    joints: List[str], controllers: List[ControllerConfig]
) -> Optional[List[ControllerConfig]]:
    """Controllers whose joints together cover ``joints``, default ones first, then those
    covering the most; None if no combination does."""
    remaining = set(joints)
    chosen: List[ControllerConfig] = []
    ordered = sorted(controllers, key=lambda c: (not c.default, -len(set(c.joints) & remaining)))
    while remaining:
        best = max(
            ordered,
            key=lambda c: (len(set(c.joints) & remaining), c.default),
            default=None,
        )
        if best is None or not set(best.joints) & remaining:
            return None
        chosen.append(best)
        remaining -= set(best.joints)
        ordered = [c for c in ordered if c is not best]
    return chosen


def split(trajectory: JointTrajectory, joints: List[str]) -> JointTrajectory:
    """The part of ``trajectory`` for ``joints`` (those of them it has)."""
    index = [i for i, j in enumerate(trajectory.joint_names) if j in joints]
    part = JointTrajectory(header=trajectory.header)
    part.joint_names = [trajectory.joint_names[i] for i in index]
    for pt in trajectory.points:
        q = JointTrajectoryPoint(time_from_start=pt.time_from_start)
        q.positions = [pt.positions[i] for i in index]
        if len(pt.velocities) == len(trajectory.joint_names):
            q.velocities = [pt.velocities[i] for i in index]
        if len(pt.accelerations) == len(trajectory.joint_names):
            q.accelerations = [pt.accelerations[i] for i in index]
        part.points.append(q)
    return part


class TrajectoryExecution:
    def __init__(
        self,
        manager: Optional[ControllerManager],
        config: ExecutionConfig,
        current_state: Callable[[], Dict[str, float]],
    ) -> None:
        self.manager = manager
        self.config = config
        self.current_state = current_state
        self._active: List[ControllerHandle] = []
        self._stopped = threading.Event()
        self._lock = threading.Lock()

    def stop(self) -> None:
        self._stopped.set()
        with self._lock:
            for h in self._active:
                h.cancel()

    def check_start(self, trajectory: JointTrajectory) -> Tuple[bool, str]:
        tolerance = self.config.allowed_start_tolerance
        if tolerance == 0 or not trajectory.points:  # 0: MoveIt's "skip this check"
            return True, ''
        current = self.current_state()
        for name, q in zip(trajectory.joint_names, trajectory.points[0].positions):
            if name in current and abs(current[name] - q) > tolerance:
                return False, (
                    'Invalid Trajectory: start point deviates from current robot state more '
                    'than %g at joint \'%s\' (%.4f vs %.4f)' % (tolerance, name, q, current[name])
                )
        return True, ''

    def execute(self, trajectory: JointTrajectory, validate: bool = True) -> Tuple[int, str]:
        """MoveIt's error code and a message. ``validate=False``: a later part of one
        execution (MoveIt checks only the first part's start against the current state)."""
        if not trajectory.points:
            return SUCCESS, 'empty trajectory'
        if self.manager is None:
            return CONTROL_FAILED, 'no controller manager'
        ok, message = self.check_start(trajectory) if validate else (True, '')
        if not ok:
            rospy.logerr(message)
            return CONTROL_FAILED, message
        configs = select_controllers(list(trajectory.joint_names), self.manager.controllers())
        if configs is None:
            message = (
                'Unable to identify any set of controllers that can actuate the specified '
                'joints: [ %s ]' % ' '.join(trajectory.joint_names)
            )
            rospy.logerr(message)
            return CONTROL_FAILED, message
        handles = []
        for c in configs:
            h = self.manager.handle(c)
            if h is None:
                return CONTROL_FAILED, "no handle for controller '%s'" % c.name
            handles.append((h, c))
        self._stopped.clear()
        start = rospy.get_rostime()
        with self._lock:
            self._active = [h for h, _ in handles]
        sent = []
        for h, c in handles:
            part = split(trajectory, c.joints)
            part.header.stamp = rospy.Time(0)
            if not h.send(part):
                self.stop()
                return CONTROL_FAILED, "controller '%s' did not accept the trajectory" % c.name
            sent.append((h, c, part))
        expected = 0.0
        for _, c, part in sent:
            scaling = (
                c.allowed_execution_duration_scaling
                or self.config.allowed_execution_duration_scaling
            )
            margin = c.allowed_goal_duration_margin
            if margin is None:
                margin = self.config.allowed_goal_duration_margin
            duration = part.points[-1].time_from_start.to_sec()
            expected = max(expected, duration * scaling + margin)
        status = SUCCEEDED
        for h, _, _ in sent:
            while not h.done.wait(0.02):
                if rospy.is_shutdown():
                    self.stop()
                    return PREEMPTED_CODE, 'shutdown'
                elapsed = (rospy.get_rostime() - start).to_sec()
                if self.config.execution_duration_monitoring and elapsed > expected:
                    rospy.logerr(
                        'Controller is taking too long to execute trajectory (the expected upper '
                        'bound for the trajectory execution was %f seconds). Stopping trajectory.',
                        expected,
                    )
                    self.stop()
                    h.done.wait(1.0)
                    status = TIMED_OUT
                    break
            if status == TIMED_OUT:
                break
            if self._stopped.is_set():
                status = PREEMPTED
                break
            if h.status != SUCCEEDED:
                status = h.status
                break
        with self._lock:
            self._active = []
        if status == SUCCEEDED:
            return SUCCESS, 'Solution was found and executed.'
        if status == PREEMPTED or self._stopped.is_set():
            return PREEMPTED_CODE, 'Solution was found but the execution was preempted'
        if status == TIMED_OUT:
            return TIMED_OUT_CODE, 'Solution was found but the controller timed out'
        return CONTROL_FAILED, 'Solution found but controller failed during execution'
