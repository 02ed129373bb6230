"""MoveIt's fake controller manager (moveit_fake_controller_manager, noetic), as demo.launch
names it: trajectories are "executed" by publishing the joint states they pass through on
move_group's ``~fake_controller_joint_states`` (latched), which joint_state_publisher merges
through its ``source_list``. No robot, no simulation: the first page of every MoveIt tutorial.

Per controller ``type`` (fake_controllers.yaml, ``$(arg fake_execution_type)``):
- ``interpolate`` (the default): linear interpolation between the waypoints, published at
  ``~fake_interpolating_controller_rate`` (10 Hz) of wall time, then the last point;
- ``via points``: each waypoint at its time_from_start;
- ``last point``: the last waypoint at once (execution then waits 0.5 s, as upstream).
``~initial`` (a list of {group, pose}) is published once at start-up: the named states of the
SRDF, other joints at their default values.
"""

from __future__ import annotations

import threading
import time
from typing import Any, Dict, List, Optional

import rospy
from sensor_msgs.msg import JointState
from trajectory_msgs.msg import JointTrajectory

from ...description import semantic_model
from ...planning.config import ControllerConfig
from .controller_managers import (
    ABORTED,
    PREEMPTED,
    SUCCEEDED,
    ControllerHandle,
    ControllerManager,
    register,
)

PLUGIN = 'moveit_fake_controller_manager/MoveItFakeControllerManager'
DEFAULT_TYPE = 'interpolate'
TYPES = ('interpolate', 'via points', 'last point')
DEFAULT_RATE = 10.0  # Hz of wall time, InterpolatingController's rate_
LAST_POINT_WAIT = 0.5  # s LastPointController::waitForExecution sleeps


def _state(trajectory: JointTrajectory, positions, velocities=(), effort=()) -> JointState:
    js = JointState()
    js.header.frame_id = trajectory.header.frame_id
    js.header.stamp = rospy.Time.now()
    js.name = list(trajectory.joint_names)
    js.position, js.velocity, js.effort = list(positions), list(velocities), list(effort)
    return js


class FakeHandle(ControllerHandle):
    """One fake controller: publishes the trajectory's states in a thread of its own."""

    def __init__(self, config: ControllerConfig, pub: rospy.Publisher, rate: float) -> None:
        super().__init__(config)
        self.pub, self.rate = pub, rate
        self._cancel = threading.Event()
        self._thread: Optional[threading.Thread] = None

    def send(self, trajectory: JointTrajectory) -> bool:
        self._stop()  # a new trajectory cancels the fake motion still running
        self._cancel.clear()
        self.done.clear()
        self.status = PREEMPTED
        self._thread = threading.Thread(target=self._run, args=(trajectory,), daemon=True)
        self._thread.start()
        return True

    def _run(self, trajectory: JointTrajectory) -> None:
        rospy.loginfo('Fake execution of trajectory')
        try:
            if trajectory.points:
                kind = self.config.type
                if kind == 'last point':
                    last = trajectory.points[-1]
                    self.pub.publish(
                        _state(trajectory, last.positions, last.velocities, last.effort)
                    )
                    self._cancel.wait(LAST_POINT_WAIT)
                elif kind == 'via points':
                    self._via_points(trajectory)
                else:
                    self._interpolate(trajectory)
        finally:
            if self.status == PREEMPTED and not self._cancel.is_set():
                self.status = SUCCEEDED
            self.done.set()

    def _via_points(self, trajectory: JointTrajectory) -> None:
        start = rospy.Time.now()
        for p in trajectory.points:
            if self._cancel.is_set():
                return
            wait = (p.time_from_start - (rospy.Time.now() - start)).to_sec()
            if wait > 1e-7:
                rospy.sleep(wait)
            self.pub.publish(_state(trajectory, p.positions, p.velocities, p.effort))

    def _interpolate(self, trajectory: JointTrajectory) -> None:
        points = trajectory.points
        start = rospy.Time.now()
        i = 0
        while not self._cancel.is_set():
            elapsed = rospy.Time.now() - start
            while i + 1 < len(points) and elapsed > points[i + 1].time_from_start:
                i += 1
            if i + 1 >= len(points):
                break
            prev, nxt = points[i], points[i + 1]
            span = (nxt.time_from_start - prev.time_from_start).to_sec()
            alpha = (elapsed - prev.time_from_start).to_sec() / span if span > 1e-12 else 1.0
            self.pub.publish(
                _state(
                    trajectory, [a + alpha * (b - a) for a, b in zip(prev.positions, nxt.positions)]
                )
            )
            time.sleep(1.0 / self.rate)
        if not self._cancel.is_set():
            self.pub.publish(_state(trajectory, points[-1].positions))

    def _stop(self) -> None:
        self._cancel.set()
        if self._thread is not None:
            self._thread.join()

    def cancel(self) -> None:
        if not self.done.is_set():
            self._stop()
            rospy.loginfo('Fake trajectory execution cancelled')
            self.status = ABORTED


class FakeControllerManager(ControllerManager):
    """``~controller_list`` of fake controllers, all always active."""

    def __init__(self, params: Dict[str, Any]) -> None:
        super().__init__()
        self._list: List[ControllerConfig] = []
        self.pub = rospy.Publisher(
            '~fake_controller_joint_states', JointState, queue_size=100, latch=True
        )
        self.rate = float(params.get('fake_interpolating_controller_rate', DEFAULT_RATE))
        entries = params.get('controller_list')
        if not isinstance(entries, list):
            rospy.logerr(
                'MoveItFakeControllerManager: No controller_list specified.'
                if entries is None
                else 'MoveItFakeControllerManager: controller_list should be an array'
            )
            return
        initial = params.get('initial')
        if initial:
            self.pub.publish(self._initial_state(initial))
        for i, entry in enumerate(entries):
            if not isinstance(entry, dict) or 'name' not in entry or 'joints' not in entry:
                rospy.logerr(
                    'MoveItFakeControllerManager: Name and joints must be specified '
                    'for each controller (controller_list[%d])',
                    i,
                )
                continue
            kind = str(entry.get('type', DEFAULT_TYPE))
            if kind not in TYPES:
                rospy.logerr(
                    "Unknown fake controller type: %s (controller '%s'; types: %s)",
                    kind,
                    entry['name'],
                    ', '.join(TYPES),
                )
                continue
            self._list.append(
                ControllerConfig(
                    name=str(entry['name']),
                    type=kind,
                    joints=[str(j) for j in entry['joints']],
                    default=bool(entry.get('default', False)),
                )
            )

    def controllers(self) -> List[ControllerConfig]:
        return list(self._list)

    def handle(self, config: ControllerConfig) -> Optional[ControllerHandle]:
        h = self._handles.get(config.name)
        if h is None:
            h = self._handles[config.name] = FakeHandle(config, self.pub, self.rate)
        return h

    def _initial_state(self, initial: Any) -> JointState:
        """The SRDF's named states of ``initial``'s groups, other joints at their defaults."""
        js = JointState()
        js.header.stamp = rospy.Time.now()
        if not isinstance(initial, list):
            rospy.logerr("Parameter 'initial' should be an array of (group, pose) structs.")
            return js
        try:
            model = semantic_model.load(
                rospy.get_param('robot_description'), rospy.get_param('robot_description_semantic')
            )
        except (KeyError, ValueError) as e:
            rospy.logerr('fake controller manager: no robot model for initial poses: %s', e)
            return js
        values = {j: semantic_model.default_value(model.limits[j]) for j in model.variable_joints}
        for item in initial:
            group = str(item.get('group', '')) if isinstance(item, dict) else ''
            pose = str(item.get('pose', '')) if isinstance(item, dict) else ''
            if group not in model.groups:
                rospy.logwarn('Unknown joint model group: %s', group)
                continue
            state = model.group_states.get(group, {}).get(pose)
            if state is None:
                rospy.logwarn("Unknown pose '%s' for group '%s'.", pose, group)
                continue
            rospy.loginfo("Set joints of group '%s' to pose '%s'.", group, pose)
            values.update(state)
        js.name = list(values)
        js.position = [values[j] for j in js.name]
        return js


register(PLUGIN, FakeControllerManager)
