"""moveit_commander.conversions: poses and transforms to and from flat lists, messages to and
from their serialized bytes (upstream's names and behaviour)."""

from __future__ import annotations

from io import BytesIO
from typing import Any, List, Sequence

import rospy
from geometry_msgs.msg import Pose, PoseStamped, Transform

from _arm1sim.description.pose_math import quat_from_rpy

from .exception import MoveItCommanderException


def msg_to_string(msg: Any) -> bytes:
    buf = BytesIO()
    msg.serialize(buf)
    return buf.getvalue()


def msg_from_string(msg: Any, data: bytes) -> None:
    msg.deserialize(data)


def pose_to_list(pose_msg: Pose) -> List[float]:
    p, q = pose_msg.position, pose_msg.orientation
    return [p.x, p.y, p.z, q.x, q.y, q.z, q.w]


def list_to_pose(pose_list: Sequence[float]) -> Pose:
    """[x, y, z, qx, qy, qz, qw] or [x, y, z, roll, pitch, yaw] -> Pose."""
    if len(pose_list) == 7:
        quat = list(pose_list[3:7])
    elif len(pose_list) == 6:
        quat = list(quat_from_rpy(pose_list[3], pose_list[4], pose_list[5]))
    else:
        raise MoveItCommanderException(
            'Expected either 6 or 7 elements in list: (x,y,z,r,p,y) or (x,y,z,qx,qy,qz,qw)'
        )
    pose = Pose()
    pose.position.x, pose.position.y, pose.position.z = pose_list[0:3]
    o = pose.orientation
    o.x, o.y, o.z, o.w = quat
    return pose


def list_to_pose_stamped(pose_list: Sequence[float], target_frame: str) -> PoseStamped:
    msg = PoseStamped()
    msg.pose = list_to_pose(pose_list)
    msg.header.frame_id = target_frame
    msg.header.stamp = rospy.Time.now()
    return msg


def transform_to_list(trf_msg: Transform) -> List[float]:
    t, r = trf_msg.translation, trf_msg.rotation
    return [t.x, t.y, t.z, r.x, r.y, r.z, r.w]


def list_to_transform(trf_list: Sequence[float]) -> Transform:
    msg = Transform()
    t, r = msg.translation, msg.rotation
    t.x, t.y, t.z = trf_list[0:3]
    r.x, r.y, r.z, r.w = trf_list[3:7]
    return msg
