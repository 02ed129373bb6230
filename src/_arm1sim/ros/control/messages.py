"""ROS messages <-> the plain dicts and floats of the ROS-free control core: what a
controller's node handle publishes, reads, serves and answers, by type name."""

from __future__ import annotations

from typing import Any, Callable, Dict, List, Tuple

import rospy
from control_msgs.msg import JointControllerState, JointTrajectoryControllerState
from franka_msgs.msg import FrankaState
from geometry_msgs.msg import WrenchStamped
from sensor_msgs.msg import JointState
from std_msgs.msg import Bool, Float64, Float64MultiArray
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

from ...control.interfaces import Fields
from ..common.stamps import duration_ns, to_time

Fill = Callable[[Any, Any], None]  # (message, the core's value) -> None


def _fill_stamped(msg: Any, fields: Fields) -> None:
    """Copy the core's fields into a message; ``stamp`` (ns of sim time) goes to the header."""
    for key, value in fields.items():
        if key == 'stamp':
            msg.header.stamp = to_time(value)
        else:
            setattr(msg, key, value)


def _fill_fields(msg: Any, fields: Fields) -> None:
    for key, value in fields.items():
        setattr(msg, key, value)


def _fill_data(msg: Any, value: Any) -> None:
    msg.data = value


def _fill_point(point: Any, fields: Fields) -> None:
    """A trajectory_msgs/JointTrajectoryPoint from plain fields (time_from_start: ns)."""
    for key, value in fields.items():
        if key == 'time_from_start':
            point.time_from_start = (
                rospy.Duration.from_sec(value)
                if isinstance(value, float)
                else rospy.Duration(0, int(value))
            )
        else:
            setattr(point, key, value)


def _fill_trajectory_state(msg: Any, fields: Fields) -> None:
    """control_msgs/JointTrajectoryControllerState (also the action's feedback)."""
    for key, value in fields.items():
        if key == 'stamp':
            msg.header.stamp = to_time(value)
        elif key in ('desired', 'actual', 'error'):
            point = JointTrajectoryPoint()
            _fill_point(point, value)
            setattr(msg, key, point)
        else:
            setattr(msg, key, value)


def _fill_wrench(msg: Any, fields: Fields) -> None:
    """geometry_msgs/WrenchStamped from ``stamp``, ``frame_id`` and ``wrench`` (6 numbers:
    force, then torque)."""
    msg.header.stamp = to_time(fields['stamp'])
    msg.header.frame_id = fields.get('frame_id', '')
    f, t = msg.wrench.force, msg.wrench.torque
    f.x, f.y, f.z, t.x, t.y, t.z = fields['wrench']


def read_data(msg: Any) -> Any:
    return msg.data


def read_trajectory(msg: Any) -> Dict[str, Any]:
    """trajectory_msgs/JointTrajectory as the core's plain fields (times in ns)."""
    return dict(
        stamp=duration_ns(msg.header.stamp),
        joint_names=list(msg.joint_names),
        points=[
            dict(
                positions=list(p.positions),
                velocities=list(p.velocities),
                accelerations=list(p.accelerations),
                effort=list(p.effort),
                time_from_start=duration_ns(p.time_from_start),
            )
            for p in msg.points
        ],
    )


def read_follow_joint_trajectory_goal(goal: Any) -> Dict[str, Any]:
    def tolerances(entries: Any) -> List[Dict[str, Any]]:
        return [
            dict(name=t.name, position=t.position, velocity=t.velocity, acceleration=t.acceleration)
            for t in entries
        ]

    return dict(
        trajectory=read_trajectory(goal.trajectory),
        path_tolerance=tolerances(goal.path_tolerance),
        goal_tolerance=tolerances(goal.goal_tolerance),
        goal_time_tolerance=duration_ns(goal.goal_time_tolerance),
    )


# type name -> (message class, fill(message, core's fields))
MESSAGES: Dict[str, Tuple[type, Fill]] = {
    'sensor_msgs/JointState': (JointState, _fill_stamped),
    'control_msgs/JointControllerState': (JointControllerState, _fill_stamped),
    'std_msgs/Float64': (Float64, _fill_data),
    'std_msgs/Float64MultiArray': (Float64MultiArray, _fill_data),
    'control_msgs/JointTrajectoryControllerState': (
        JointTrajectoryControllerState,
        _fill_trajectory_state,
    ),
    'trajectory_msgs/JointTrajectory': (JointTrajectory, _fill_stamped),
    'std_msgs/Bool': (Bool, _fill_fields),
    'franka_msgs/FrankaState': (FrankaState, _fill_stamped),
    'geometry_msgs/WrenchStamped': (WrenchStamped, _fill_wrench),
}
# type name -> what a subscriber's callback gets from a message (default: its ``data``)
READERS: Dict[str, Callable[[Any], Any]] = {
    'trajectory_msgs/JointTrajectory': read_trajectory,
}


def _actions() -> Dict[str, Tuple[Any, Callable[[Any], Any], type, type, Fill]]:
    from control_msgs.msg import (
        FollowJointTrajectoryAction,
        FollowJointTrajectoryFeedback,
        FollowJointTrajectoryResult,
        GripperCommandAction,
        GripperCommandFeedback,
        GripperCommandResult,
    )
    from franka_gripper.msg import (
        GraspAction,
        GraspFeedback,
        GraspResult,
        HomingAction,
        HomingFeedback,
        HomingResult,
        MoveAction,
        MoveFeedback,
        MoveResult,
        StopAction,
        StopFeedback,
        StopResult,
    )

    def read_fields(goal: Any) -> Dict[str, Any]:
        """A flat goal (franka_gripper's) as its fields; a nested message as a dict too."""
        out: Dict[str, Any] = {}
        for name in goal.__slots__:
            value = getattr(goal, name)
            out[name] = read_fields(value) if hasattr(value, '__slots__') else value
        return out

    franka = {
        'franka_gripper/' + name: (action, read_fields, result, feedback, _fill_fields)
        for name, action, result, feedback in (
            ('Move', MoveAction, MoveResult, MoveFeedback),
            ('Grasp', GraspAction, GraspResult, GraspFeedback),
            ('Homing', HomingAction, HomingResult, HomingFeedback),
            ('Stop', StopAction, StopResult, StopFeedback),
        )
    }
    return {
        **franka,
        'control_msgs/FollowJointTrajectory': (
            FollowJointTrajectoryAction,
            read_follow_joint_trajectory_goal,
            FollowJointTrajectoryResult,
            FollowJointTrajectoryFeedback,
            _fill_trajectory_state,
        ),
        'control_msgs/GripperCommand': (
            GripperCommandAction,
            read_gripper_command_goal,
            GripperCommandResult,
            GripperCommandFeedback,
            _fill_fields,
        ),
    }


def read_gripper_command_goal(goal: Any) -> Dict[str, Any]:
    return dict(command=dict(position=goal.command.position, max_effort=goal.command.max_effort))


def _services() -> Dict[str, Tuple[Any, Callable[[Any], Fields]]]:
    from control_msgs.srv import QueryTrajectoryState

    return {
        'control_msgs/QueryTrajectoryState': (
            QueryTrajectoryState,
            lambda req: dict(time=duration_ns(req.time)),
        )
    }


ACTIONS = _actions()
SERVICES = _services()
