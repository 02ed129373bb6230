"""moveit_msgs to the planning core's values and back."""

from __future__ import annotations

import copy
import math
from typing import Callable, Dict, List, Optional, Sequence, Tuple

import rospy
from geometry_msgs.msg import Pose, Quaternion
from moveit_msgs.msg import (
    AttachedCollisionObject,
    CollisionObject,
    RobotState,
    RobotTrajectory,
)
from sensor_msgs.msg import JointState
from shape_msgs.msg import Mesh, MeshTriangle, Plane, SolidPrimitive
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

from ...planning.pipeline import (
    Constraints,
    JointGoal,
    OrientationConstraint,
    PositionConstraint,
    Trajectory,
)
from ...planning.scene import SceneObject, Shape

PoseT = Tuple[Sequence[float], Sequence[float]]
# frame_id -> pose of that frame in the model frame; raises LookupError for an unknown frame
FrameLookup = Callable[[str], PoseT]

PRIMITIVES = {
    SolidPrimitive.BOX: 'box',
    SolidPrimitive.SPHERE: 'sphere',
    SolidPrimitive.CYLINDER: 'cylinder',
    SolidPrimitive.CONE: 'cone',
}
KINDS = {v: k for k, v in PRIMITIVES.items()}


def pose_tuple(p: Pose) -> PoseT:
    q = (p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w)
    norm = math.sqrt(sum(v * v for v in q))
    if norm == 0.0:  # unset: the identity, as MoveIt reads it (NaN stays NaN: refused later)
        q = (0.0, 0.0, 0.0, 1.0)
    else:
        q = tuple(v / norm for v in q)
    return (p.position.x, p.position.y, p.position.z), q


def pose_msg(pos: Sequence[float], orn: Sequence[float]) -> Pose:
    out = Pose()
    out.position.x, out.position.y, out.position.z = (float(v) for v in pos)
    (out.orientation.x, out.orientation.y, out.orientation.z, out.orientation.w) = (
        float(v) for v in orn
    )
    return out


def compose(a: PoseT, b: PoseT) -> PoseT:
    import pybullet as p

    pos, orn = p.multiplyTransforms(a[0], a[1], b[0], b[1])
    return tuple(pos), tuple(orn)


def inverse(a: PoseT) -> PoseT:
    import pybullet as p

    pos, orn = p.invertTransform(a[0], a[1])
    return tuple(pos), tuple(orn)


def joint_values(state: JointState) -> Dict[str, float]:
    return {n: float(v) for n, v in zip(state.name, state.position)}


def robot_state_msg(
    values: Dict[str, float], attached: List[AttachedCollisionObject]
) -> RobotState:
    msg = RobotState()
    msg.joint_state.header.stamp = rospy.Time.now()
    msg.joint_state.name = list(values)
    msg.joint_state.position = [values[n] for n in values]
    msg.attached_collision_objects = attached
    msg.is_diff = False
    return msg


def trajectory_msg(traj: Trajectory, frame: str) -> RobotTrajectory:
    out = RobotTrajectory()
    jt = JointTrajectory()
    jt.header.frame_id = frame
    jt.joint_names = list(traj.joint_names)
    for i, q in enumerate(traj.positions):
        pt = JointTrajectoryPoint()
        pt.positions = list(q)
        pt.velocities = list(traj.velocities[i]) if traj.velocities else []
        pt.accelerations = list(traj.accelerations[i]) if traj.accelerations else []
        pt.time_from_start = rospy.Duration.from_sec(traj.times[i])
        jt.points.append(pt)
    out.joint_trajectory = jt
    return out


def shapes_of(obj: CollisionObject) -> List[Shape]:
    """The object's shapes, posed in the object's frame (its ``pose``). A shape without a
    pose of its own sits at the object's origin (planning_scene.cpp; moveit_commander's
    add_box sends none)."""
    shapes = []
    obj = _shape_poses_filled(obj)
    for prim, pose in zip(obj.primitives, obj.primitive_poses):
        kind = PRIMITIVES.get(prim.type)
        if kind is None:
            raise ValueError(
                "collision object '%s': primitive type %d unknown" % (obj.id, prim.type)
            )
        shapes.append(Shape(kind, tuple(prim.dimensions), pose_tuple(pose)))
    for mesh, pose in zip(obj.meshes, obj.mesh_poses):
        shapes.append(
            Shape(
                'mesh',
                pose=pose_tuple(pose),
                vertices=[(v.x, v.y, v.z) for v in mesh.vertices],
                triangles=[tuple(t.vertex_indices) for t in mesh.triangles],
            )
        )
    for plane, pose in zip(obj.planes, obj.plane_poses):
        shapes.append(Shape('plane', tuple(plane.coef), pose_tuple(pose)))
    if len(obj.primitives) != len(obj.primitive_poses) or len(obj.meshes) != len(obj.mesh_poses):
        raise ValueError("collision object '%s': shapes and poses differ in number" % obj.id)
    return shapes


def _shape_poses_filled(obj: CollisionObject) -> CollisionObject:
    def vectors(o: CollisionObject) -> list:
        return [
            (o.primitives, o.primitive_poses),
            (o.meshes, o.mesh_poses),
            (o.planes, o.plane_poses),
        ]

    if all(len(poses) >= len(shapes) for shapes, poses in vectors(obj)):
        return obj
    obj = copy.deepcopy(obj)
    for shapes, poses in vectors(obj):
        poses.extend(Pose(orientation=Quaternion(w=1.0)) for _ in range(len(shapes) - len(poses)))
    return obj


def object_msg(obj: SceneObject, frame: str) -> CollisionObject:
    msg = CollisionObject()
    msg.header.frame_id = frame
    msg.id = obj.id
    msg.pose = pose_msg(*obj.pose)
    for shape in obj.shapes:
        if shape.kind in KINDS:
            msg.primitives.append(
                SolidPrimitive(type=KINDS[shape.kind], dimensions=list(shape.dimensions))
            )
            msg.primitive_poses.append(pose_msg(*shape.pose))
        elif shape.kind == 'mesh':
            m = Mesh()
            from geometry_msgs.msg import Point

            m.vertices = [Point(*v) for v in shape.vertices]
            m.triangles = [MeshTriangle(vertex_indices=list(t)) for t in shape.triangles]
            msg.meshes.append(m)
            msg.mesh_poses.append(pose_msg(*shape.pose))
        elif shape.kind == 'plane':
            msg.planes.append(Plane(coef=list(shape.dimensions)))
            msg.plane_poses.append(pose_msg(*shape.pose))
    msg.operation = CollisionObject.ADD
    return msg


def constraints(msg, frame_pose: FrameLookup) -> Constraints:
    """moveit_msgs/Constraints in the model frame."""
    out = Constraints()
    for jc in msg.joint_constraints:
        out.joints.append(
            JointGoal(jc.joint_name, jc.position, jc.tolerance_above, jc.tolerance_below)
        )
    for pc in msg.position_constraints:
        frame = frame_pose(pc.header.frame_id)
        region = pc.constraint_region
        if region.primitive_poses:
            center_pose = compose(frame, pose_tuple(region.primitive_poses[0]))
        elif region.mesh_poses:
            center_pose = compose(frame, pose_tuple(region.mesh_poses[0]))
        else:
            raise ValueError("position constraint of '%s' has no region" % pc.link_name)
        offset = (pc.target_point_offset.x, pc.target_point_offset.y, pc.target_point_offset.z)
        if any(offset):
            rospy.logwarn_once('position constraints: target_point_offset is not applied')
        prim = region.primitives[0] if region.primitives else None
        if prim is not None and prim.type == SolidPrimitive.BOX:
            out.positions.append(
                PositionConstraint(
                    pc.link_name,
                    center_pose[0],
                    tuple(prim.dimensions[:3]),
                    orientation=center_pose[1],
                )
            )
        else:
            radius = prim.dimensions[0] if prim is not None and prim.dimensions else 1e-4
            out.positions.append(PositionConstraint(pc.link_name, center_pose[0], None, radius))
    for oc in msg.orientation_constraints:
        frame = frame_pose(oc.header.frame_id)
        target = compose(frame, ((0, 0, 0), pose_tuple(Pose(orientation=oc.orientation))[1]))
        out.orientations.append(
            OrientationConstraint(
                oc.link_name,
                target[1],
                (
                    oc.absolute_x_axis_tolerance,
                    oc.absolute_y_axis_tolerance,
                    oc.absolute_z_axis_tolerance,
                ),
            )
        )
    if msg.visibility_constraints:
        rospy.logwarn_once('visibility constraints are not applied')
    return out


def optional(value: Optional[float], default: float) -> float:
    return default if value is None else value
