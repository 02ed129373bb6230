"""The message registry: the ROS types controllers use, by type name, and how their fields go.

A controller module registers each message, action and service type it publishes,
subscribes to, serves or answers, at import, next to the controller that uses it (a
vendor's controllers in their room). Each names how the controller's plain fields go into
the message (a *fill*) or come out of it (a *read*), from the kinds below; the ROS layer
(ros/control/messages.py) has one function per kind, and imports a type's class by its
package (``sensor_msgs/JointState``: ``sensor_msgs.msg``) when a node handle first uses it,
so a controller manager needs no vendor message package unless a vendor controller is
loaded. A new kind is one function there (docs/controllers.md).

ROS-free: names and kinds only.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Dict, Tuple, TypeVar

# fills: the controller's fields -> a message
FIELDS = 'fields'  # each field by name
STAMPED = 'stamped'  # each field by name; ``stamp`` (ns of sim time) into header.stamp
DATA = 'data'  # the value into ``data``
TRAJECTORY_STATE = 'trajectory_state'  # control_msgs/JointTrajectoryControllerState's points
WRENCH = 'wrench'  # ``stamp``, ``frame_id`` and ``wrench`` (force, torque: 6 numbers)
# reads: a message -> what the controller gets (DATA: its ``data``; FIELDS: a dict of fields)
TRAJECTORY = 'trajectory'  # trajectory_msgs/JointTrajectory, times in ns
FOLLOW_JOINT_TRAJECTORY_GOAL = 'follow_joint_trajectory_goal'
GRIPPER_COMMAND_GOAL = 'gripper_command_goal'
QUERY_TRAJECTORY_STATE = 'query_trajectory_state'  # its request's time, in ns

FILLS = (FIELDS, STAMPED, DATA, TRAJECTORY_STATE, WRENCH)
READS = (DATA, FIELDS, TRAJECTORY, FOLLOW_JOINT_TRAJECTORY_GOAL, GRIPPER_COMMAND_GOAL)
REQUEST_READS = (QUERY_TRAJECTORY_STATE, FIELDS)

_TYPE_NAME = re.compile(r'^[A-Za-z][A-Za-z0-9_]*/[A-Za-z][A-Za-z0-9_]*$')


@dataclass(frozen=True)
class MessageType:
    fill: str = FIELDS  # when published
    read: str = DATA  # when subscribed to


@dataclass(frozen=True)
class ActionType:
    read_goal: str
    fill_feedback: str  # a result is filled field by field (FIELDS)


@dataclass(frozen=True)
class ServiceType:
    read_request: str  # a response is filled field by field (FIELDS)


MESSAGES: Dict[str, MessageType] = {}
ACTIONS: Dict[str, ActionType] = {}
SERVICES: Dict[str, ServiceType] = {}

T = TypeVar('T', MessageType, ActionType, ServiceType)


def _register(table: Dict[str, T], type_name: str, spec: T, *kinds: Tuple[str, ...]) -> None:
    """Refused when the module loads: a malformed name, an unknown kind, or a type already
    registered another way (registering it again the same way is how two controllers share
    one)."""
    if not isinstance(type_name, str) or not _TYPE_NAME.match(type_name):
        raise TypeError('message type %r is not <package>/<Name>' % (type_name,))
    for value, allowed in zip(vars(spec).values(), kinds):
        if value not in allowed:
            raise TypeError('%s: %r is none of %s' % (type_name, value, ', '.join(allowed)))
    old = table.get(type_name)
    if old is not None and old != spec:
        raise TypeError('%s: registered as %s, now as %s' % (type_name, old, spec))
    table[type_name] = spec


def register_message(type_name: str, fill: str = FIELDS, read: str = DATA) -> None:
    _register(MESSAGES, type_name, MessageType(fill, read), FILLS, READS)


def register_action(type_name: str, read_goal: str, fill_feedback: str) -> None:
    """``type_name`` as actionlib names it: ``control_msgs/FollowJointTrajectory`` for
    FollowJointTrajectoryAction, its Goal, Result and Feedback."""
    _register(ACTIONS, type_name, ActionType(read_goal, fill_feedback), READS, FILLS)


def register_service(type_name: str, read_request: str) -> None:
    _register(SERVICES, type_name, ServiceType(read_request), REQUEST_READS)
