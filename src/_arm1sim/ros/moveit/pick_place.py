"""move_group's ``pickup`` and ``place`` actions (MoveIt's MoveGroupPickPlaceAction), as
moveit_ros_manipulation's pick and place pipelines run them, for grasps and place locations
the client gives (no grasp planner).

Pick, for each grasp by quality: the end effector's parent link at the grasp pose and at the
pre-grasp pose (back along pre_grasp_approach.direction by desired_distance) by IK, the hand
allowed to touch the target; a free motion to the pre-grasp state; the pre-grasp posture;
the approach in a straight line; the grasp posture; the object attached to the parent link
(touch links: the end effector's links and allowed_touch_objects); the retreat along
post_grasp_retreat. Place, for each location: the parent link where the attached object's
pose is the location's place_pose; free motion to the pre-place state, the approach, the
post-place posture, the object detached, the retreat. A direction in the end effector's
parent link frame is taken at the grasp (or place) pose; in any other frame, as that frame
is now. The first grasp (location) whose stages all plan is executed, stage by stage.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Dict, List, Optional, Tuple

import numpy as np
import pybullet as p
import rospy
from moveit_msgs.msg import MoveItErrorCodes, PickupResult, PlaceResult, RobotTrajectory
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

from ...planning.pipeline import Constraints, JointGoal, MotionRequest
from ...planning.scene import SceneObject
from . import convert

if TYPE_CHECKING:
    from .move_group import MoveGroup

PoseT = convert.PoseT
# the stages that move the end effector's joints to a posture (a gripper, which other
# clients may move too): started from the hand's state at their turn
POSTURES = ('pre_grasp', 'grasp', 'release')


class Failed(Exception):
    def __init__(self, code: int, message: str) -> None:
        super().__init__(message)
        self.code = code


def _direction(node: MoveGroup, stamped: Any, link: str, at: PoseT) -> np.ndarray:
    v = np.array([stamped.vector.x, stamped.vector.y, stamped.vector.z], dtype=float)
    n = np.linalg.norm(v)
    if n == 0.0:
        return v
    frame = stamped.header.frame_id.lstrip('/')
    rotation = at[1] if frame == link else node.frame_pose(frame)[1]
    return np.array(p.rotateVector(list(rotation), list(v / n)))


def _shifted(pose: PoseT, direction: np.ndarray, distance: float) -> PoseT:
    return tuple(np.asarray(pose[0]) + direction * distance), pose[1]


class PickPlace:
    def __init__(self, node: MoveGroup) -> None:
        self.node = node

    # --- helpers ----------------------------------------------------------------------------

    def _end_effector(self, group: str, name: str) -> Tuple[str, str]:
        """(end-effector group, its parent link)."""
        for ee in self.node.robot.srdf.end_effectors:
            if (name and ee.name == name) or (not name and ee.parent_group == group):
                return ee.group, ee.parent_link
        raise Failed(MoveItErrorCodes.INVALID_GROUP_NAME, 'no end effector for group %s' % group)

    def _ik(self, group: str, link: str, pose: PoseT, seed: Dict[str, float]) -> Dict[str, float]:
        values = self.node.pipeline.ik(group, link, pose[0], pose[1], seed, timeout=0.5)
        if values is None:
            raise Failed(MoveItErrorCodes.NO_IK_SOLUTION, 'no IK solution')
        return {**seed, **values}

    def _line(self, group: str, link: str, start: Dict[str, float], to: PoseT) -> JointTrajectory:
        result, traj = self.node.pipeline.cartesian(group, link, start, [to], 0.01, 0.0, True)
        if result.fraction < 0.999:
            raise Failed(
                MoveItErrorCodes.PLANNING_FAILED,
                'straight line followed %.0f %% of the way' % (result.fraction * 100),
            )
        return convert.trajectory_msg(traj, self.node.frame).joint_trajectory

    def _free(
        self, group: str, start: Dict[str, float], goal: Dict[str, float], time: float
    ) -> JointTrajectory:
        joints = self.node.robot.group_joints(group)
        req = MotionRequest(
            group,
            start,
            [Constraints(joints=[JointGoal(j, goal[j]) for j in joints])],
            allowed_planning_time=time,
        )
        result = self.node.pipeline.plan(req)
        if result.trajectory is None:
            raise Failed(result.error_code, 'no free motion to the approach: %s' % result.message)
        return convert.trajectory_msg(result.trajectory, self.node.frame).joint_trajectory

    @staticmethod
    def _posture(posture: JointTrajectory, state: Dict[str, float]) -> Optional[JointTrajectory]:
        """The posture as a trajectory from the state (its last point, at its time or 1 s)."""
        if not posture.joint_names or not posture.points:
            return None
        last = posture.points[-1]
        out = JointTrajectory(joint_names=list(posture.joint_names))
        out.points.append(
            JointTrajectoryPoint(
                positions=[state.get(j, v) for j, v in zip(posture.joint_names, last.positions)],
                time_from_start=rospy.Duration(0),
            )
        )
        end = (
            last.time_from_start
            if last.time_from_start > rospy.Duration(0)
            else rospy.Duration(1.0)
        )
        out.points.append(JointTrajectoryPoint(positions=list(last.positions), time_from_start=end))
        return out

    def _end(self, traj: JointTrajectory, state: Dict[str, float]) -> Dict[str, float]:
        return {**state, **dict(zip(traj.joint_names, traj.points[-1].positions))}

    def _allow(self, names: List[str], target: str, allowed: bool) -> None:
        for n in names:
            self.node.world.allow(n, target, allowed)

    def _run(self, stages: List[Tuple[str, Optional[JointTrajectory], Any]]) -> Tuple[int, str]:
        """Execute each stage's trajectory, then its follow-up (attach, detach): one
        execution of several parts, the first checked against the current state."""
        first = True
        for name, traj, then in stages:
            if traj is not None:
                if name in POSTURES:  # from wherever the hand is now (it moves by itself)
                    now = self.node.current_state()
                    first = traj.points[0]
                    first.positions = [
                        now.get(j, v) for j, v in zip(traj.joint_names, first.positions)
                    ]
                code, message = self.node.execution.execute(traj, validate=first)
                first = False
                if code != MoveItErrorCodes.SUCCESS:
                    return code, '%s: %s' % (name, message)
            if then is not None:
                with self.node.lock:
                    then()
                self.node.publish_scene()
        return MoveItErrorCodes.SUCCESS, ''

    def _first_that_plans(
        self, goal: Any, result: Any, candidates: List[Any], stages_of: Any, field: str, what: str
    ) -> Tuple[Any, str]:
        """The first candidate (grasp, place location) whose stages all plan, executed unless
        plan_only; the result filled as MoveIt fills it."""
        last = Failed(MoveItErrorCodes.PLANNING_FAILED, 'no %s planned' % what)
        for candidate in candidates:
            try:
                stages = stages_of(candidate)
            except Failed as exc:
                last = exc
                rospy.loginfo("%s '%s': %s", what, candidate.id, exc)
                continue
            setattr(result, field, candidate)
            executed = [s for s in stages if s[1] is not None]
            result.trajectory_descriptions = [s[0] for s in executed]
            result.trajectory_stages = [RobotTrajectory(joint_trajectory=s[1]) for s in executed]
            if goal.planning_options.plan_only:
                result.error_code.val = MoveItErrorCodes.SUCCESS
                return result, 'planned'
            code, message = self._run(stages)
            result.error_code.val = code
            return result, message
        result.error_code.val = last.code
        return result, str(last)

    # --- pick -------------------------------------------------------------------------------

    def pick(self, goal: Any) -> Tuple[PickupResult, str]:
        result = PickupResult()
        node = self.node
        if goal.target_name not in node.world.objects:
            result.error_code.val = MoveItErrorCodes.INVALID_OBJECT_NAME
            return result, "no world object '%s'" % goal.target_name
        grasps = sorted(goal.possible_grasps, key=lambda g: -g.grasp_quality)
        if not grasps:
            result.error_code.val = MoveItErrorCodes.INVALID_GOAL_CONSTRAINTS
            return result, 'no grasps given'
        return self._first_that_plans(
            goal, result, grasps, lambda g: self._pick_stages(goal, g), 'grasp', 'grasp'
        )

    def _pick_stages(
        self, goal: Any, grasp: Any
    ) -> List[Tuple[str, Optional[JointTrajectory], Any]]:
        node = self.node
        eef_group, link = self._end_effector(goal.group_name, goal.end_effector)
        eef_links = node.robot.group_links(eef_group)
        target = goal.target_name
        with node.lock:
            state = node.current_state()
            at = convert.compose(
                node.frame_pose(grasp.grasp_pose.header.frame_id),
                convert.pose_tuple(grasp.grasp_pose.pose),
            )
            approach = _direction(node, grasp.pre_grasp_approach.direction, link, at)
            retreat = _direction(node, grasp.post_grasp_retreat.direction, link, at)
            pre = _shifted(at, approach, -grasp.pre_grasp_approach.desired_distance)
            self._allow(eef_links + list(goal.allowed_touch_objects), target, True)
            try:
                grasp_state = self._ik(goal.group_name, link, at, state)
                pre_state = self._ik(goal.group_name, link, pre, grasp_state)
                free = self._free(
                    goal.group_name, state, pre_state, goal.allowed_planning_time or 5.0
                )
                opening = self._posture(grasp.pre_grasp_posture, state)
                approach_traj = self._line(goal.group_name, link, pre_state, at)
                closing = self._posture(grasp.grasp_posture, self._end(approach_traj, pre_state))
            finally:
                self._allow(eef_links + list(goal.allowed_touch_objects), target, False)
            # the retreat with the object in hand: planned with it attached, then put back
            touch = eef_links + list(goal.allowed_touch_objects)
            grasped = self._end(approach_traj, pre_state)
            saved = node.world.objects[target]
            node.robot.set_positions(grasped)
            lp = node.robot.link_pose(link)
            rel = convert.compose(convert.inverse((tuple(lp[0]), tuple(lp[1]))), saved.pose)
            node.world.remove(target)
            node.world.attach(SceneObject(target, rel, saved.shapes, link=link, touch_links=touch))
            try:
                after = _shifted(at, retreat, grasp.post_grasp_retreat.desired_distance)
                retreat_traj = self._line(goal.group_name, link, grasped, after)
            finally:
                node.world.remove(target)
                node.world.add_object(SceneObject(target, saved.pose, saved.shapes))
        return [
            ('plan', free, None),
            ('pre_grasp', opening, None),
            ('approach', approach_traj, None),
            ('grasp', closing, _attach(node, target, link, touch)),
            ('retreat', retreat_traj, None),
        ]

    # --- place ------------------------------------------------------------------------------

    def place(self, goal: Any) -> Tuple[PlaceResult, str]:
        result = PlaceResult()
        node = self.node
        obj = node.world.attached.get(goal.attached_object_name)
        if obj is None:
            result.error_code.val = MoveItErrorCodes.INVALID_OBJECT_NAME
            return result, "no attached object '%s'" % goal.attached_object_name
        if not goal.place_locations:
            result.error_code.val = MoveItErrorCodes.INVALID_GOAL_CONSTRAINTS
            return result, 'no place locations given'
        locations = sorted(goal.place_locations, key=lambda x: -x.quality)
        return self._first_that_plans(
            goal,
            result,
            locations,
            lambda x: self._place_stages(goal, x, obj),
            'place_location',
            'place location',
        )

    def _place_stages(
        self, goal: Any, loc: Any, obj: Any
    ) -> List[Tuple[str, Optional[JointTrajectory], Any]]:
        node = self.node
        link = obj.link
        name = obj.id
        with node.lock:
            state = node.current_state()
            place = convert.compose(
                node.frame_pose(loc.place_pose.header.frame_id),
                convert.pose_tuple(loc.place_pose.pose),
            )
            at = convert.compose(place, convert.inverse((tuple(obj.pose[0]), tuple(obj.pose[1]))))
            approach = _direction(node, loc.pre_place_approach.direction, link, at)
            retreat = _direction(node, loc.post_place_retreat.direction, link, at)
            pre = _shifted(at, approach, -loc.pre_place_approach.desired_distance)
            place_state = self._ik(goal.group_name, link, at, state)
            pre_state = self._ik(goal.group_name, link, pre, place_state)
            free = self._free(goal.group_name, state, pre_state, goal.allowed_planning_time or 5.0)
            approach_traj = self._line(goal.group_name, link, pre_state, at)
            placed = self._end(approach_traj, pre_state)
            opening = self._posture(loc.post_place_posture, placed)
            # the retreat without the object: planned with it left there, then attached again
            node.robot.set_positions(placed)
            left = node.world.attached_pose(obj)
            node.world.remove(name)
            node.world.add_object(SceneObject(name, (tuple(left[0]), tuple(left[1])), obj.shapes))
            for t in list(obj.touch_links) + [link]:
                node.world.allow(name, t, True)  # the fingers leave it touching
            try:
                after = _shifted(at, retreat, loc.post_place_retreat.desired_distance)
                retreat_traj = self._line(goal.group_name, link, placed, after)
            finally:
                for t in list(obj.touch_links) + [link]:
                    node.world.allow(name, t, False)
                node.world.remove(name)
                node.world.attach(obj)
        return [
            ('plan', free, None),
            ('approach', approach_traj, None),
            ('release', opening, lambda: _detach(node, name)),
            ('retreat', retreat_traj, None),
        ]


def _detach(node: MoveGroup, name: str) -> None:
    """Detach ``name`` where the arm holds it now; it stays in the world there."""
    node.robot.set_positions(node.current_state())
    node.world.detach(name)


def _attach(node: MoveGroup, name: str, link: str, touch: List[str]) -> Any:
    """A callable attaching world object ``name`` to ``link`` where it is now."""

    def attach() -> None:
        from moveit_msgs.msg import AttachedCollisionObject, CollisionObject

        aco = AttachedCollisionObject(link_name=link, touch_links=touch)
        aco.object = CollisionObject(id=name, operation=CollisionObject.ADD)
        node.apply_attached(aco)

    return attach
