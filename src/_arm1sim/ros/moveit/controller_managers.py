"""MoveIt's controller managers: who executes which joints' part of a trajectory.

``MANAGERS`` maps the plugin names a *_moveit_config sets as ``moveit_controller_manager``
to a factory; another manager (e.g. the fake one of demo.launch) registers itself there with
``register``. Each manager lists its controllers (name, joints) and makes a handle that
sends a trajectory part and reports MoveIt's execution status.

- moveit_simple_controller_manager/MoveItSimpleControllerManager: ``~controller_list``
  entries, FollowJointTrajectory goals to ``<name>/<action_ns>``, GripperCommand goals
  (the last point's position of the first joint, ``max_effort``) likewise.
- moveit_ros_control_interface/MoveItControllerManager: the running controllers that
  ``<ros_control_namespace>/controller_manager/list_controllers`` reports, joint trajectory
  controllers through ``<name>/follow_joint_trajectory``, gripper action controllers
  through ``<name>/gripper_cmd``.
"""

from __future__ import annotations

import threading
from typing import Any, Callable, Dict, List, Optional

import actionlib
import rospy
from actionlib_msgs.msg import GoalStatus
from control_msgs.msg import (
    FollowJointTrajectoryAction,
    FollowJointTrajectoryGoal,
    GripperCommandAction,
    GripperCommandGoal,
)
from trajectory_msgs.msg import JointTrajectory

from ...planning.config import ControllerConfig, controller_list

SUCCEEDED, ABORTED, PREEMPTED, TIMED_OUT, FAILED = (
    'SUCCEEDED',
    'ABORTED',
    'PREEMPTED',
    'TIMED_OUT',
    'FAILED',
)
SERVER_WAIT = 5.0  # s a handle waits for its action server on first use


class ControllerHandle:
    """One controller's part of an execution (MoveIt's MoveItControllerHandle)."""

    def __init__(self, config: ControllerConfig) -> None:
        self.config = config
        self.status = SUCCEEDED
        self.done = threading.Event()
        self.done.set()

    @property
    def name(self) -> str:
        return self.config.name

    def send(self, trajectory: JointTrajectory) -> bool:
        raise NotImplementedError

    def cancel(self) -> None:
        raise NotImplementedError


class _ActionHandle(ControllerHandle):
    action: Any = None
    default_ns = ''

    def __init__(self, config: ControllerConfig) -> None:
        super().__init__(config)
        ns = config.action_ns or self.default_ns
        self.server = ('%s/%s' % (config.name, ns)).replace('//', '/')
        self.client = actionlib.SimpleActionClient(self.server, self.action)
        self._connected = False

    def _connect(self) -> bool:
        if not self._connected:
            self._connected = self.client.wait_for_server(rospy.Duration(SERVER_WAIT))
            if not self._connected:
                rospy.logerr('Action client not connected: %s', self.server)
        return self._connected

    def _goal(self, trajectory: JointTrajectory) -> Any:
        raise NotImplementedError

    def _succeeded(self, state: int, result: Any) -> bool:
        return state == GoalStatus.SUCCEEDED

    def send(self, trajectory: JointTrajectory) -> bool:
        if not self._connect():
            return False
        self.done.clear()
        self.status = FAILED
        self.client.send_goal(self._goal(trajectory), done_cb=self._finished)
        return True

    def _finished(self, state: int, result: Any) -> None:
        if self._succeeded(state, result):
            self.status = SUCCEEDED
        elif state in (GoalStatus.PREEMPTED, GoalStatus.RECALLED):
            self.status = PREEMPTED
        else:
            self.status = ABORTED
            text = getattr(result, 'error_string', '') if result is not None else ''
            rospy.logwarn(
                "Controller '%s' failed with error %s: %s",
                self.name,
                getattr(result, 'error_code', state),
                text,
            )
        self.done.set()

    def cancel(self) -> None:
        if not self.done.is_set():
            self.client.cancel_goal()


class FollowJointTrajectoryHandle(_ActionHandle):
    action = FollowJointTrajectoryAction
    default_ns = 'follow_joint_trajectory'

    def _goal(self, trajectory: JointTrajectory) -> FollowJointTrajectoryGoal:
        return FollowJointTrajectoryGoal(trajectory=trajectory)


class GripperCommandHandle(_ActionHandle):
    """MoveIt's GripperControllerHandle: the last point's position of the first joint the
    controller has; a stalled gripper (holding something) has done its part."""

    action = GripperCommandAction
    default_ns = 'gripper_cmd'

    def _goal(self, trajectory: JointTrajectory) -> GripperCommandGoal:
        goal = GripperCommandGoal()
        last = trajectory.points[-1]
        index = next(
            (i for i, j in enumerate(trajectory.joint_names) if j in self.config.joints), 0
        )
        goal.command.position = last.positions[index]
        goal.command.max_effort = self.config.max_effort
        return goal

    def _succeeded(self, state: int, result: Any) -> bool:
        return state == GoalStatus.SUCCEEDED or bool(result is not None and result.stalled)


HANDLES: Dict[str, Callable[[ControllerConfig], ControllerHandle]] = {
    'FollowJointTrajectory': FollowJointTrajectoryHandle,
    'GripperCommand': GripperCommandHandle,
}


class ControllerManager:
    """A MoveIt controller manager: its controllers and a handle for each."""

    def __init__(self) -> None:
        self._handles: Dict[str, ControllerHandle] = {}

    def controllers(self) -> List[ControllerConfig]:
        raise NotImplementedError

    def handle(self, config: ControllerConfig) -> Optional[ControllerHandle]:
        h = self._handles.get(config.name)
        if h is None or h.config != config:
            maker = HANDLES.get(config.type)
            if maker is None:
                rospy.logerr(
                    "Unknown controller type '%s' of controller '%s'", config.type, config.name
                )
                return None
            h = self._handles[config.name] = maker(config)
        return h


class SimpleControllerManager(ControllerManager):
    def __init__(self, params: Dict[str, Any]) -> None:
        super().__init__()
        self._list = controller_list(params.get('controller_list'))

    def controllers(self) -> List[ControllerConfig]:
        return list(self._list)


# ros_control controller types and how MoveIt's ros_control manager talks to them
ROS_CONTROL_TYPES = {
    'JointTrajectoryController': 'FollowJointTrajectory',
    'GripperActionController': 'GripperCommand',
}


class RosControlControllerManager(ControllerManager):
    def __init__(self, params: Dict[str, Any]) -> None:
        super().__init__()
        self.ns = str(params.get('ros_control_namespace', '/')).rstrip('/')

    def controllers(self) -> List[ControllerConfig]:
        from controller_manager_msgs.srv import ListControllers

        name = self.ns + '/controller_manager/list_controllers'
        try:
            rospy.wait_for_service(name, 2.0)
            reply = rospy.ServiceProxy(name, ListControllers)()
        except (rospy.ROSException, rospy.ServiceException) as exc:
            rospy.logerr('ros_control controller manager: %s (%s)', name, exc)
            return []
        out = []
        for c in reply.controller:
            kind = ROS_CONTROL_TYPES.get(c.type.split('/')[-1])
            if kind is None or c.state != 'running':
                continue
            joints = [j for r in c.claimed_resources for j in r.resources]
            # absolute, as the controller manager's namespace is (not move_group's)
            name = '%s/%s' % (self.ns if self.ns.startswith('/') else '/' + self.ns, c.name)
            out.append(ControllerConfig(name.replace('//', '/'), kind, joints, default=True))
        return out


MANAGERS: Dict[str, Callable[[Dict[str, Any]], ControllerManager]] = {
    'moveit_simple_controller_manager/MoveItSimpleControllerManager': SimpleControllerManager,
    'moveit_ros_control_interface/MoveItControllerManager': RosControlControllerManager,
    'moveit_ros_control_interface/Ros1ControllerManager': RosControlControllerManager,
}


def register(plugin: str, factory: Callable[[Dict[str, Any]], ControllerManager]) -> None:
    """Make ``plugin`` (a moveit_controller_manager value) available."""
    MANAGERS[plugin] = factory


def make_manager(plugin: str, params: Dict[str, Any]) -> Optional[ControllerManager]:
    """The manager ``plugin`` names; with none named, the simple one if a controller list is
    given (MoveIt takes the only manager it has then)."""
    if not plugin:
        plugin = 'moveit_simple_controller_manager/MoveItSimpleControllerManager'
    # pluginlib takes a plugin's C++ type too: the Setup Assistant's
    # ros_control_moveit_controller_manager.launch.xml names moveit_ros_control_interface::...
    factory = MANAGERS.get(plugin) or MANAGERS.get(plugin.replace('::', '/', 1))
    if factory is None:
        rospy.logerr(
            "moveit_controller_manager '%s' is not available here (available: %s): "
            'trajectories will not be executed',
            plugin,
            ', '.join(sorted(MANAGERS)),
        )
        return None
    return factory(params)
