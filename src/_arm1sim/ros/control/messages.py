"""ROS messages <-> the plain dicts and floats of the ROS-free control core: what a
controller's node handle publishes, reads, serves and answers, by type name.

Which types exist and how each goes is control/message_types.py's registry, which the
controllers fill; here are the fill and read kinds, one function each, and the classes,
imported by the type name's package when a type is first used (``message``, ``action``,
``service``): a package that is not installed fails that use alone, naming the type.
"""

from __future__ import annotations

import importlib
from typing import Any, Callable, Dict, List, Tuple

import rospy
from trajectory_msgs.msg import JointTrajectoryPoint

from ...control import message_types as types
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


def read_fields(msg: Any) -> Dict[str, Any]:
    """A message's fields as a dict (a nested message as a dict too): a flat goal's."""
    out: Dict[str, Any] = {}
    for name in msg.__slots__:
        value = getattr(msg, name)
        out[name] = read_fields(value) if hasattr(value, '__slots__') else value
    return out


def read_gripper_command_goal(goal: Any) -> Dict[str, Any]:
    return dict(command=dict(position=goal.command.position, max_effort=goal.command.max_effort))


FILLS: Dict[str, Fill] = {
    types.FIELDS: _fill_fields,
    types.STAMPED: _fill_stamped,
    types.DATA: _fill_data,
    types.TRAJECTORY_STATE: _fill_trajectory_state,
    types.WRENCH: _fill_wrench,
}
READS: Dict[str, Callable[[Any], Any]] = {
    types.DATA: read_data,
    types.FIELDS: read_fields,
    types.TRAJECTORY: read_trajectory,
    types.FOLLOW_JOINT_TRAJECTORY_GOAL: read_follow_joint_trajectory_goal,
    types.GRIPPER_COMMAND_GOAL: read_gripper_command_goal,
    types.QUERY_TRAJECTORY_STATE: lambda req: dict(time=duration_ns(req.time)),
}


class MessageTypeError(LookupError):
    """A type no controller registered, or whose package is not installed."""


def _class(type_name: str, kind: str, suffix: str = '') -> Any:
    package, name = type_name.split('/', 1)
    try:
        return getattr(importlib.import_module('%s.%s' % (package, kind)), name + suffix)
    except (ImportError, AttributeError) as exc:
        raise MessageTypeError(
            '%s: no %s.%s.%s (%s); is its package built and sourced?'
            % (type_name, package, kind, name + suffix, exc)
        ) from None


def _spec(table: Dict[str, Any], type_name: str, what: str) -> Any:
    spec = table.get(type_name)
    if spec is None:
        raise MessageTypeError(
            '%s type %s is registered by no controller (control/message_types.py)'
            % (what, type_name)
        )
    return spec


def message(type_name: str) -> Tuple[type, Fill, Callable[[Any], Any]]:
    """(class, fill for publishing, read for subscribers) of a registered message type."""
    spec = _spec(types.MESSAGES, type_name, 'message')
    return _class(type_name, 'msg'), FILLS[spec.fill], READS[spec.read]


def action(type_name: str) -> Tuple[Any, Callable[[Any], Any], type, type, Fill]:
    """(the Action class, its goal's read, Result class, Feedback class, the feedback's fill)."""
    spec = _spec(types.ACTIONS, type_name, 'action')
    return (
        _class(type_name, 'msg', 'Action'),
        READS[spec.read_goal],
        _class(type_name, 'msg', 'Result'),
        _class(type_name, 'msg', 'Feedback'),
        FILLS[spec.fill_feedback],
    )


def service(type_name: str) -> Tuple[Any, Callable[[Any], Fields]]:
    """(the service class, its request's read)."""
    spec = _spec(types.SERVICES, type_name, 'service')
    return _class(type_name, 'srv'), READS[spec.read_request]
