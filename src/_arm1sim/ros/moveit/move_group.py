"""``rosrun moveit_ros_move_group move_group``: MoveIt's move_group node on the planning
core of arm1 (_arm1sim.planning): the parameters a *_moveit_config loads, MoveIt's
capabilities under their names, execution through the robot's controllers.

Names as MoveIt 1 (noetic) has them, relative to the node's namespace: actions move_group
and execute_trajectory; services plan_kinematic_path, compute_ik, compute_fk,
compute_cartesian_path, check_state_validity, get_planning_scene, apply_planning_scene,
query_planner_interface, get_planner_params, set_planner_params, clear_octomap; topics
collision_object, attached_collision_object, planning_scene, planning_scene_world and
trajectory_execution_event in, ~display_planned_path and ~monitored_planning_scene out.
"""

from __future__ import annotations

import copy
import logging
import sys
import threading
import time
from typing import Any, Callable, Dict, List, Optional, Tuple

import actionlib
import rospy
from geometry_msgs.msg import PoseStamped
from moveit_msgs.msg import (
    AttachedCollisionObject,
    CollisionObject,
    ContactInformation,
    DisplayTrajectory,
    ExecuteTrajectoryAction,
    ExecuteTrajectoryFeedback,
    ExecuteTrajectoryResult,
    MoveGroupAction,
    MoveGroupFeedback,
    MoveGroupResult,
    MoveItErrorCodes,
    PickupAction,
    PlaceAction,
    PlannerInterfaceDescription,
    PlannerParams,
    PlanningScene,
    PlanningSceneComponents,
    PlanningSceneWorld,
    RobotState,
)
from moveit_msgs.srv import (
    ApplyPlanningScene,
    ApplyPlanningSceneResponse,
    GetCartesianPath,
    GetCartesianPathResponse,
    GetMotionPlan,
    GetMotionPlanResponse,
    GetPlannerParams,
    GetPlannerParamsResponse,
    GetPlanningScene,
    GetPlanningSceneResponse,
    GetPositionFK,
    GetPositionFKResponse,
    GetPositionIK,
    GetPositionIKResponse,
    GetStateValidity,
    GetStateValidityResponse,
    QueryPlannerInterfaces,
    QueryPlannerInterfacesResponse,
    SetPlannerParams,
    SetPlannerParamsResponse,
)
from sensor_msgs.msg import JointState
from std_msgs.msg import String
from std_srvs.srv import Empty, EmptyResponse

from ...description.srdf import SrdfError, parse_srdf
from ...planning import config as cfg
from ...planning.kinematics import ModelError, RobotKinematics
from ...planning.ompl_planner import PLANNERS, planner_type
from ...planning.pipeline import MotionRequest, PipelineSettings, PlanningPipeline
from ...planning.scene import CollisionWorld, SceneError, SceneObject
from ..common.logs import route_core_logs
from ..common.packages import find_package
from . import convert, fake_controller_manager  # noqa: F401  (registers the fake manager)
from .controller_managers import make_manager
from .execution import TrajectoryExecution
from .pick_place import PickPlace

log = logging.getLogger(__name__)

PLANNING_PLUGIN = 'ompl_interface/OMPLPlanner'
KNOWN_ADAPTERS = {
    'default_planner_request_adapters/AddTimeParameterization',
    'default_planner_request_adapters/FixWorkspaceBounds',
    'default_planner_request_adapters/FixStartStateBounds',
    'default_planner_request_adapters/FixStartStateCollision',
    'default_planner_request_adapters/FixStartStatePathConstraints',
    'default_planner_request_adapters/ResolveConstraintFrames',
}
TIMING_ADAPTERS = {
    'default_planner_request_adapters/AddTimeOptimalParameterization',
    'default_planner_request_adapters/AddIterativeSplineParameterization',
    'default_planner_request_adapters/AddRuckigTrajectorySmoothing',
}
STATE_WAIT = 1.0  # s, as MoveIt's wait for a complete current state


def _param(name: str, default: Any = None) -> Any:
    try:
        return rospy.get_param(name, default)
    except (KeyError, rospy.ROSException):
        return default


class MoveGroup:
    def __init__(self) -> None:
        self.lock = threading.RLock()
        description = _param('robot_description')
        semantic = _param('robot_description_semantic')
        if not description or not semantic:
            raise ModelError(
                'move_group needs robot_description and robot_description_semantic on the '
                'parameter server (%s, %s)'
                % (
                    rospy.resolve_name('robot_description'),
                    rospy.resolve_name('robot_description_semantic'),
                )
            )
        srdf = parse_srdf(semantic)
        limits = cfg.joint_limits_config(_param('robot_description_planning', {}))
        self.robot = RobotKinematics(description, srdf, limits, find_package)
        self.world = CollisionWorld(self.robot)
        private = _param('~', {}) or {}
        self.private = private
        pipeline = self._pipeline_params(private)
        self._say_unapplied(pipeline)
        self.ompl = cfg.ompl_config(pipeline, list(srdf.groups))
        self.kinematics = cfg.kinematics_config(_param('robot_description_kinematics', {}))
        self.pipeline = PlanningPipeline(
            self.robot,
            self.world,
            self.ompl,
            self.kinematics,
            PipelineSettings(
                start_state_max_bounds_error=float(
                    pipeline.get('start_state_max_bounds_error', 0.05)
                ),
                jiggle_fraction=float(pipeline.get('jiggle_fraction', 0.05)),
                max_sampling_attempts=int(pipeline.get('max_sampling_attempts', 100)),
            ),
        )
        self.frame = self.robot.model_frame
        self.joint_state: Dict[str, float] = {}
        self._waited = False
        self._state_lock = threading.Lock()
        execution = cfg.execution_config(private.get('trajectory_execution', {}))
        self.allow_execution = bool(private.get('allow_trajectory_execution', True))
        manager = make_manager(str(private.get('moveit_controller_manager', '')), private)
        self.execution = TrajectoryExecution(manager, execution, self.current_state)
        self._tf: Any = None
        ns_private = rospy.get_name()
        self.display_pub = rospy.Publisher(
            ns_private + '/display_planned_path', DisplayTrajectory, queue_size=10, latch=True
        )
        self.scene_pub = rospy.Publisher(
            ns_private + '/monitored_planning_scene', PlanningScene, queue_size=100, latch=True
        )
        rospy.Subscriber('joint_states', JointState, self._on_joint_state, queue_size=25)
        rospy.Subscriber(
            'collision_object', CollisionObject, self._on_collision_object, queue_size=100
        )
        rospy.Subscriber(
            'attached_collision_object', AttachedCollisionObject, self._on_attached, queue_size=100
        )
        rospy.Subscriber('planning_scene', PlanningScene, self._on_scene, queue_size=100)
        rospy.Subscriber(
            'planning_scene_world', PlanningSceneWorld, self._on_scene_world, queue_size=100
        )
        rospy.Subscriber(
            'trajectory_execution_event', String, self._on_execution_event, queue_size=10
        )
        services = [
            ('plan_kinematic_path', GetMotionPlan, self.srv_plan),
            ('compute_ik', GetPositionIK, self.srv_ik),
            ('compute_fk', GetPositionFK, self.srv_fk),
            ('compute_cartesian_path', GetCartesianPath, self.srv_cartesian),
            ('check_state_validity', GetStateValidity, self.srv_validity),
            ('get_planning_scene', GetPlanningScene, self.srv_get_scene),
            ('apply_planning_scene', ApplyPlanningScene, self.srv_apply_scene),
            ('query_planner_interface', QueryPlannerInterfaces, self.srv_query),
            ('get_planner_params', GetPlannerParams, self.srv_get_params),
            ('set_planner_params', SetPlannerParams, self.srv_set_params),
            ('clear_octomap', Empty, self.srv_clear_octomap),
        ]
        self.services = [rospy.Service(n, t, cb) for n, t, cb in services]
        self.move_server = actionlib.SimpleActionServer(
            'move_group', MoveGroupAction, self.act_move, auto_start=False
        )
        self.move_server.register_preempt_callback(self.execution.stop)
        self.exec_server = actionlib.SimpleActionServer(
            'execute_trajectory', ExecuteTrajectoryAction, self.act_execute, auto_start=False
        )
        self.exec_server.register_preempt_callback(self.execution.stop)
        self.move_server.start()
        self.exec_server.start()
        self.pick_place = PickPlace(self)
        self.pick_server = actionlib.SimpleActionServer(
            'pickup', PickupAction, self.act_pickup, auto_start=False
        )
        self.place_server = actionlib.SimpleActionServer(
            'place', PlaceAction, self.act_place, auto_start=False
        )
        for server in (self.pick_server, self.place_server):
            server.register_preempt_callback(self.execution.stop)
            server.start()
        self.publish_scene()
        rospy.loginfo(
            'move_group (arm1 stand-in): %s with groups %s, planning frame %s. '
            'You can start planning now!',
            srdf.name,
            ', '.join(srdf.groups),
            self.frame,
        )

    # --- parameters ------------------------------------------------------------------------

    @staticmethod
    def _pipeline_params(private: Dict[str, Any]) -> Dict[str, Any]:
        """The planning pipeline's parameters: MoveIt 1.1's planning_pipelines/<name>/
        (default_planning_pipeline, else ompl), or those of older configurations, straight
        under the node's namespace."""
        pipelines = private.get('planning_pipelines')
        if not isinstance(pipelines, dict) or not pipelines:
            return private
        name = str(private.get('default_planning_pipeline') or 'ompl')
        chosen = pipelines.get(name)
        if (
            not isinstance(chosen, dict)
            or chosen.get('planning_plugin', PLANNING_PLUGIN) != PLANNING_PLUGIN
        ):
            if name != 'ompl':
                rospy.logwarn(
                    "default_planning_pipeline '%s': planning with the 'ompl' pipeline instead",
                    name,
                )
            chosen = pipelines.get('ompl')
        return dict(chosen) if isinstance(chosen, dict) else private

    def _say_unapplied(self, private: Dict[str, Any]) -> None:
        plugin = private.get('planning_plugin', PLANNING_PLUGIN)
        if plugin and plugin != PLANNING_PLUGIN:
            rospy.logwarn(
                "planning_plugin '%s': planning with OMPL (ompl_interface/OMPLPlanner) instead",
                plugin,
            )
        adapters = str(private.get('request_adapters', '')).split()
        for a in adapters:
            if a in TIMING_ADAPTERS:
                rospy.logwarn(
                    "request adapter '%s': paths are timed by the iterative parabolic time "
                    'parameterization (AddTimeParameterization) instead',
                    a,
                )
            elif a not in KNOWN_ADAPTERS:
                rospy.logwarn("request adapter '%s' is not applied (the default adapters are)", a)
        for solver in {
            k.get('kinematics_solver')
            for k in (_param('robot_description_kinematics', {}) or {}).values()
            if isinstance(k, dict)
        }:
            if solver and 'kdl' not in solver.lower():
                rospy.logwarn(
                    "kinematics_solver '%s': solving with numerical IK (as KDL) instead", solver
                )
        for key in ('capabilities', 'disable_capabilities'):
            if private.get(key):
                rospy.loginfo(
                    '%s %r noted: the default capabilities are offered', key, private[key]
                )

    # --- state ------------------------------------------------------------------------------

    def _on_joint_state(self, msg: JointState) -> None:
        values = convert.joint_values(msg)
        with self._state_lock:
            self.joint_state.update(values)

    def current_state(self) -> Dict[str, float]:
        # MoveIt waits for a complete state; a joint nobody publishes is waited for once only
        deadline = time.monotonic() + (0.0 if self._waited else STATE_WAIT)
        while True:
            with self._state_lock:
                known = dict(self.joint_state)
            missing = [j for j in self.robot.variables if j not in known]
            if not missing or time.monotonic() > deadline or rospy.is_shutdown():
                break
            time.sleep(0.01)
        if missing:
            self._waited = True
            rospy.logwarn_throttle(
                10,
                'The complete state of the robot is not yet known. Missing %s',
                ', '.join(missing),
            )
        full = {j: self.robot.default_position(j) for j in self.robot.variables}
        full.update({k: v for k, v in known.items() if k in full})
        return full

    def state_from_msg(self, msg) -> Dict[str, float]:
        """A RobotState message over the current state (MoveIt's robotStateMsgToRobotState:
        the current state, then the message's values)."""
        state = self.current_state()
        for name, value in zip(msg.joint_state.name, msg.joint_state.position):
            if name in state:
                state[name] = float(value)
        return state

    # --- frames -----------------------------------------------------------------------------

    def frame_pose(self, frame_id: str) -> convert.PoseT:
        frame = frame_id.lstrip('/')
        if not frame or frame == self.frame or frame == self.robot.root_link:
            return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0)
        if frame in self.robot.link_index:
            with self.lock:
                self.robot.set_positions(self.current_state())
                pos, orn = self.robot.link_pose(frame)
            return tuple(pos), tuple(orn)
        for obj in list(self.world.objects.values()):
            if obj.id == frame:
                return obj.pose
        return self._tf_pose(frame)

    def _tf_pose(self, frame: str) -> convert.PoseT:
        import tf2_ros

        if self._tf is None:
            self._tf = tf2_ros.Buffer()
            self._tf_listener = tf2_ros.TransformListener(self._tf)
        try:
            t = self._tf.lookup_transform(self.frame, frame, rospy.Time(0), rospy.Duration(1.0))
        except (
            tf2_ros.LookupException,
            tf2_ros.ConnectivityException,
            tf2_ros.ExtrapolationException,
        ) as exc:
            raise LookupError("frame '%s' is unknown (%s)" % (frame, exc)) from None
        tr, rot = t.transform.translation, t.transform.rotation
        return (tr.x, tr.y, tr.z), (rot.x, rot.y, rot.z, rot.w)

    # --- planning scene ---------------------------------------------------------------------

    def _attached_msgs(self) -> List[AttachedCollisionObject]:
        out = []
        for obj in self.world.attached.values():
            a = AttachedCollisionObject(link_name=obj.link, touch_links=list(obj.touch_links))
            a.object = convert.object_msg(obj, obj.link)
            out.append(a)
        return out

    def scene_msg(self, components: int = 0xFFFF) -> PlanningScene:
        msg = PlanningScene()
        msg.name = '(noname)'
        msg.robot_model_name = self.robot.srdf.name
        msg.is_diff = False
        C = PlanningSceneComponents
        with self.lock:
            if components & (C.ROBOT_STATE | C.ROBOT_STATE_ATTACHED_OBJECTS):
                attached = (
                    self._attached_msgs() if components & C.ROBOT_STATE_ATTACHED_OBJECTS else []
                )
                msg.robot_state = convert.robot_state_msg(self.current_state(), attached)
            if components & (C.WORLD_OBJECT_NAMES | C.WORLD_OBJECT_GEOMETRY):
                for obj in self.world.objects.values():
                    co = convert.object_msg(obj, self.frame)
                    if not components & C.WORLD_OBJECT_GEOMETRY:
                        co = CollisionObject(
                            id=obj.id, header=co.header, operation=CollisionObject.ADD
                        )
                    msg.world.collision_objects.append(co)
            if components & C.ALLOWED_COLLISION_MATRIX:
                names = (
                    sorted(self.robot.link_index)
                    + sorted(self.world.objects)
                    + sorted(self.world.attached)
                )
                msg.allowed_collision_matrix.entry_names = names
                for a in names:
                    from moveit_msgs.msg import AllowedCollisionEntry

                    msg.allowed_collision_matrix.entry_values.append(
                        AllowedCollisionEntry(
                            enabled=[
                                self.robot.srdf.collision_disabled(a, b)
                                or (min(a, b), max(a, b)) in self.world.allowed
                                for b in names
                            ]
                        )
                    )
        return msg

    def publish_scene(self) -> None:
        self.scene_pub.publish(self.scene_msg())

    def apply_collision_object(self, co: CollisionObject) -> None:
        op = co.operation
        if op == CollisionObject.REMOVE:
            if co.id:
                self.world.remove(co.id) if co.id in self.world.objects else None
            else:
                for oid in list(self.world.objects):
                    self.world.remove(oid)
            return
        frame = self.frame_pose(co.header.frame_id)
        if op == CollisionObject.MOVE:
            obj = self.world.objects.get(co.id)
            if obj is None:
                raise SceneError("cannot move '%s': no such world object" % co.id)
            obj.pose = convert.compose(frame, convert.pose_tuple(co.pose))
            self.world.add_object(SceneObject(obj.id, obj.pose, obj.shapes))
            return
        shapes = convert.shapes_of(co)
        pose = convert.compose(frame, convert.pose_tuple(co.pose))
        if op == CollisionObject.APPEND and co.id in self.world.objects:
            old = self.world.objects[co.id]
            rel = convert.compose(convert.inverse(old.pose), pose)
            for s in shapes:
                s.pose = convert.compose(rel, s.pose)
            shapes = old.shapes + shapes
            pose = old.pose
        if not shapes:
            raise SceneError("collision object '%s' has no shapes" % co.id)
        self.world.add_object(SceneObject(co.id, pose, shapes))

    def apply_attached(self, aco: AttachedCollisionObject) -> None:
        co = aco.object
        if co.operation == CollisionObject.REMOVE:
            ids = (
                [co.id]
                if co.id
                else [
                    i
                    for i, o in self.world.attached.items()
                    if not aco.link_name or o.link == aco.link_name
                ]
            )
            for oid in ids:
                self.world.detach(oid)
            return
        link = aco.link_name
        if link not in self.robot.link_index:
            raise SceneError("cannot attach '%s' to '%s': not a link of the robot" % (co.id, link))
        if co.primitives or co.meshes or co.planes:
            shapes = convert.shapes_of(co)
            frame = self.frame_pose(co.header.frame_id or link)
            world_pose = convert.compose(frame, convert.pose_tuple(co.pose))
        elif co.id in self.world.objects:  # attach a world object where it is
            old = self.world.objects[co.id]
            shapes, world_pose = old.shapes, old.pose
        else:
            raise SceneError("cannot attach '%s': it has no shapes and is no world object" % co.id)
        self.robot.set_positions(self.current_state())
        lp = self.robot.link_pose(link)
        link_pose: convert.PoseT = (tuple(lp[0]), tuple(lp[1]))
        rel = convert.compose(convert.inverse(link_pose), world_pose)
        self.world.remove(co.id)
        self.world.attach(
            SceneObject(co.id, rel, shapes, link=link, touch_links=list(aco.touch_links))
        )

    def apply_scene(self, scene: PlanningScene) -> None:
        with self.lock:
            self._apply_scene(scene)
        self.publish_scene()

    def _apply_scene(self, scene: PlanningScene) -> None:
        """A planning scene message applied (the caller holds the lock)."""
        if not scene.is_diff:
            self.world.clear()
        # the robot state's attached objects first, then the world, as MoveIt's
        # PlanningScene::setPlanningSceneDiffMsg
        for aco in scene.robot_state.attached_collision_objects:
            self.apply_attached(aco)
        for co in scene.world.collision_objects:
            self.apply_collision_object(co)
        acm = scene.allowed_collision_matrix
        for a, entry in zip(acm.entry_names, acm.entry_values):
            for b, allowed in zip(acm.entry_names, entry.enabled):
                if a != b:
                    self.world.allow(a, b, bool(allowed))

    def _applied(self, topic: str, apply: Callable[[Any], None], msg: Any) -> None:
        """A topic's message applied; a bad one is said in the log and changes nothing."""
        try:
            with self.lock:
                apply(msg)
        except (SceneError, ValueError, LookupError) as exc:
            rospy.logerr('%s: %s', topic, exc)
        self.publish_scene()

    def _on_collision_object(self, msg: CollisionObject) -> None:
        self._applied('collision_object', self.apply_collision_object, msg)

    def _on_attached(self, msg: AttachedCollisionObject) -> None:
        self._applied('attached_collision_object', self.apply_attached, msg)

    def _on_scene(self, msg: PlanningScene) -> None:
        try:
            self.apply_scene(msg)
        except (SceneError, ValueError, LookupError) as exc:
            rospy.logerr('planning_scene: %s', exc)

    def _on_scene_world(self, msg: PlanningSceneWorld) -> None:
        self._on_scene(PlanningScene(world=msg, is_diff=True))

    def _on_execution_event(self, msg: String) -> None:
        if msg.data == 'stop':
            self.execution.stop()

    # --- planning ---------------------------------------------------------------------------

    def motion_request(self, req) -> MotionRequest:
        if req.pipeline_id and req.pipeline_id != 'ompl':
            rospy.logwarn_once(
                "pipeline_id '%s': planning with the 'ompl' pipeline instead" % req.pipeline_id
            )
        start = self.state_from_msg(req.start_state)
        return MotionRequest(
            group=req.group_name,
            start=start,
            goals=[convert.constraints(g, self.frame_pose) for g in req.goal_constraints],
            path_constraints=convert.constraints(req.path_constraints, self.frame_pose),
            planner_id=req.planner_id,
            allowed_planning_time=req.allowed_planning_time
            if req.allowed_planning_time > 0
            else 5.0,
            num_planning_attempts=max(1, req.num_planning_attempts),
            max_velocity_scaling_factor=req.max_velocity_scaling_factor,
            max_acceleration_scaling_factor=req.max_acceleration_scaling_factor,
        )

    def plan(self, req) -> Tuple[int, Any, Dict[str, float], float]:
        """(error code, RobotTrajectory or None, start state, planning time)."""
        try:
            motion = self.motion_request(req)
        except (ValueError, LookupError) as exc:
            rospy.logerr('motion plan request: %s', exc)
            return MoveItErrorCodes.INVALID_GOAL_CONSTRAINTS, None, {}, 0.0
        if not motion.goals:
            rospy.logerr('motion plan request has no goal constraints')
            return MoveItErrorCodes.INVALID_GOAL_CONSTRAINTS, None, motion.start, 0.0
        with self.lock:
            result = self.pipeline.plan(motion)
        if result.error_code != MoveItErrorCodes.SUCCESS or result.trajectory is None:
            rospy.logwarn(
                'planning for group %s failed: error %d %s',
                motion.group,
                result.error_code,
                result.message,
            )
            return result.error_code, None, motion.start, result.planning_time
        traj = convert.trajectory_msg(result.trajectory, self.frame)
        rospy.loginfo(
            'planned %s in %.3f s: %d points, %.2f s long',
            motion.group,
            result.planning_time,
            len(result.trajectory.positions),
            result.trajectory.times[-1] if result.trajectory.times else 0.0,
        )
        return MoveItErrorCodes.SUCCESS, traj, motion.start, result.planning_time

    def plan_in(self, diff: PlanningScene, request) -> Tuple[int, Any, Dict[str, float], float]:
        """plan() in the scene with ``diff`` laid over it for this request only, as MoveIt's
        move action does with a goal's planning_scene_diff that holds anything."""
        start_attached = list(request.start_state.attached_collision_objects)
        if start_attached:  # a start state's attached bodies: part of that state only
            diff = copy.deepcopy(diff)
            diff.is_diff = True
            diff.robot_state.attached_collision_objects += start_attached
        has_content = (
            diff.world.collision_objects
            or diff.robot_state.attached_collision_objects
            or diff.allowed_collision_matrix.entry_names
        )
        if not has_content:
            return self.plan(request)
        with self.lock:
            snapshot = self.world.snapshot()
            try:
                self._apply_scene(diff)
                return self.plan(request)
            except (SceneError, ValueError, LookupError) as exc:
                rospy.logerr('planning_scene_diff: %s', exc)
                return MoveItErrorCodes.FAILURE, None, {}, 0.0
            finally:
                self.world.restore(snapshot)

    def display(self, traj, start: Dict[str, float]) -> None:
        msg = DisplayTrajectory(model_id=self.robot.srdf.name)
        msg.trajectory.append(traj)
        msg.trajectory_start = convert.robot_state_msg(start, self._attached_msgs())
        self.display_pub.publish(msg)

    def srv_plan(self, request) -> GetMotionPlanResponse:
        res = GetMotionPlanResponse()
        code, traj, start, t = self.plan_in(
            PlanningScene(is_diff=True), request.motion_plan_request
        )
        r = res.motion_plan_response
        r.error_code.val = code
        r.planning_time = t
        r.group_name = request.motion_plan_request.group_name
        if start:
            r.trajectory_start = convert.robot_state_msg(start, self._attached_msgs())
        if traj is not None:
            r.trajectory = traj
            self.display(traj, start)
        return res

    def act_move(self, goal) -> None:
        result = MoveGroupResult()
        self.move_server.publish_feedback(MoveGroupFeedback(state='PLANNING'))
        request = goal.request
        if not goal.planning_options.plan_only and (
            request.start_state.joint_state.name or request.start_state.attached_collision_objects
        ):
            rospy.logwarn(
                'Execution of motions should always start at the robot\'s current state. '
                'Ignoring the state supplied as start state in the motion planning request'
            )
            request.start_state = RobotState(is_diff=True)
        code, traj, start, t = self.plan_in(goal.planning_options.planning_scene_diff, request)
        result.error_code.val = code
        result.planning_time = t
        if start:
            result.trajectory_start = convert.robot_state_msg(start, self._attached_msgs())
        if traj is None:
            self.move_server.set_aborted(result, 'No motion plan found. No execution attempted.')
            return
        result.planned_trajectory = traj
        self.display(traj, start)
        if goal.planning_options.plan_only or not self.allow_execution:
            self.move_server.set_succeeded(result, 'Motion plan was computed succesfully.')
            return
        self.move_server.publish_feedback(MoveGroupFeedback(state='MONITOR'))
        code, message = self.execution.execute(traj.joint_trajectory)
        result.error_code.val = code
        if code == MoveItErrorCodes.SUCCESS:
            result.executed_trajectory = traj
        self.move_server.publish_feedback(MoveGroupFeedback(state='IDLE'))
        self._finish(self.move_server, code, result, message)

    def act_execute(self, goal) -> None:
        result = ExecuteTrajectoryResult()
        if not self.allow_execution:
            result.error_code.val = MoveItErrorCodes.CONTROL_FAILED
            self.exec_server.set_aborted(result, 'trajectory execution is not allowed')
            return
        self.exec_server.publish_feedback(ExecuteTrajectoryFeedback(state='MONITOR'))
        code, message = self.execution.execute(goal.trajectory.joint_trajectory)
        result.error_code.val = code
        self.exec_server.publish_feedback(ExecuteTrajectoryFeedback(state='IDLE'))
        self._finish(self.exec_server, code, result, message)

    def act_pickup(self, goal) -> None:
        result, message = self.pick_place.pick(goal)
        self._finish(self.pick_server, result.error_code.val, result, message)

    def act_place(self, goal) -> None:
        result, message = self.pick_place.place(goal)
        self._finish(self.place_server, result.error_code.val, result, message)

    @staticmethod
    def _finish(server, code: int, result, message: str) -> None:
        if code == MoveItErrorCodes.SUCCESS:
            server.set_succeeded(result, message)
        elif code == MoveItErrorCodes.PREEMPTED:
            server.set_preempted(result, message)
        else:
            server.set_aborted(result, message)

    # --- kinematics -------------------------------------------------------------------------

    def srv_ik(self, request) -> GetPositionIKResponse:
        req = request.ik_request
        res = GetPositionIKResponse()
        group = req.group_name
        if group not in self.robot.srdf.groups:
            res.error_code.val = MoveItErrorCodes.INVALID_GROUP_NAME
            return res
        link = req.ik_link_name or self.robot.group_tip(group)
        if link not in self.robot.link_index:
            rospy.logerr("compute_ik: no link '%s' in the robot", link)
            res.error_code.val = MoveItErrorCodes.INVALID_LINK_NAME
            return res
        try:
            frame = self.frame_pose(req.pose_stamped.header.frame_id)
        except LookupError as exc:
            rospy.logerr('compute_ik: %s', exc)
            res.error_code.val = MoveItErrorCodes.FRAME_TRANSFORM_FAILURE
            return res
        target = convert.compose(frame, convert.pose_tuple(req.pose_stamped.pose))
        with self.lock:
            seed = self.state_from_msg(req.robot_state)
            path = convert.constraints(req.constraints, self.frame_pose)
            timeout = req.timeout.to_sec()
            values = self.pipeline.ik(
                group,
                link,
                target[0],
                target[1],
                seed,
                timeout=timeout if timeout > 0 else None,
                avoid_collisions=req.avoid_collisions,
                path=path,
            )
        if values is None:
            res.error_code.val = MoveItErrorCodes.NO_IK_SOLUTION
            res.solution = convert.robot_state_msg(seed, [])
            return res
        seed.update(values)
        res.solution = convert.robot_state_msg(seed, [])
        res.error_code.val = MoveItErrorCodes.SUCCESS
        return res

    def srv_fk(self, request) -> GetPositionFKResponse:
        res = GetPositionFKResponse()
        try:
            frame = self.frame_pose(request.header.frame_id)
        except LookupError as exc:
            rospy.logerr('compute_fk: %s', exc)
            res.error_code.val = MoveItErrorCodes.FRAME_TRANSFORM_FAILURE
            return res
        with self.lock:
            state = self.state_from_msg(request.robot_state)
            self.robot.set_positions(state)
            for link in request.fk_link_names:
                if link not in self.robot.link_index:
                    res.error_code.val = MoveItErrorCodes.INVALID_LINK_NAME
                    return res
                pose = self.robot.link_pose(link)
                rel = convert.compose(convert.inverse(frame), (tuple(pose[0]), tuple(pose[1])))
                ps = PoseStamped()
                ps.header.frame_id = request.header.frame_id or self.frame
                ps.header.stamp = rospy.Time.now()
                ps.pose = convert.pose_msg(*rel)
                res.pose_stamped.append(ps)
                res.fk_link_names.append(link)
        res.error_code.val = MoveItErrorCodes.SUCCESS
        return res

    def srv_cartesian(self, req) -> GetCartesianPathResponse:
        res = GetCartesianPathResponse()
        group = req.group_name
        if group not in self.robot.srdf.groups:
            res.error_code.val = MoveItErrorCodes.INVALID_GROUP_NAME
            return res
        links = self.robot.group_links(group)
        link = req.link_name or (links[-1] if links else '')
        if link not in self.robot.link_index:
            rospy.logerr("compute_cartesian_path: Unknown frame: '%s'", link)
            res.error_code.val = MoveItErrorCodes.FAILURE
            return res
        if req.max_step < sys.float_info.epsilon:
            rospy.logerr(
                'Maximum step to take between consecutive configrations along Cartesian path '
                'was not specified (this value needs to be > 0)'
            )
            res.error_code.val = MoveItErrorCodes.FAILURE
            return res
        try:
            frame = self.frame_pose(req.header.frame_id)
        except LookupError as exc:
            rospy.logerr('compute_cartesian_path: %s', exc)
            res.error_code.val = MoveItErrorCodes.FRAME_TRANSFORM_FAILURE
            return res
        waypoints = [convert.compose(frame, convert.pose_tuple(w)) for w in req.waypoints]
        with self.lock:
            start = self.state_from_msg(req.start_state)
            path = convert.constraints(req.path_constraints, self.frame_pose)
            result, traj = self.pipeline.cartesian(
                group,
                link,
                start,
                waypoints,
                req.max_step,
                req.jump_threshold,
                req.avoid_collisions,
                path,
            )
        rospy.loginfo(
            'Computed Cartesian path with %d points (followed %f%% of requested trajectory)',
            len(result.states),
            result.fraction * 100.0,
        )
        res.start_state = convert.robot_state_msg(start, self._attached_msgs())
        res.solution = convert.trajectory_msg(traj, self.frame)
        res.fraction = result.fraction
        if traj.positions:
            self.display(res.solution, start)
        res.error_code.val = MoveItErrorCodes.SUCCESS
        return res

    def srv_validity(self, req) -> GetStateValidityResponse:
        res = GetStateValidityResponse()
        with self.lock:
            state = self.state_from_msg(req.robot_state)
            contacts = self.world.contacts(state)
            constraints = convert.constraints(req.constraints, self.frame_pose)
            ok_constraints = constraints.empty() or self.pipeline.satisfies(constraints, state)
            bounds_ok = self.robot.within_bounds(state)
        for a, b, depth in contacts:
            c = ContactInformation(contact_body_1=a, contact_body_2=b, depth=depth)
            c.header.frame_id = self.frame
            c.body_type_1 = (
                ContactInformation.ROBOT_LINK
                if a in self.robot.link_index
                else ContactInformation.WORLD_OBJECT
            )
            c.body_type_2 = (
                ContactInformation.ROBOT_LINK
                if b in self.robot.link_index
                else ContactInformation.WORLD_OBJECT
            )
            res.contacts.append(c)
        res.valid = not contacts and ok_constraints and bounds_ok
        return res

    # --- scene services ---------------------------------------------------------------------

    def srv_get_scene(self, req) -> GetPlanningSceneResponse:
        return GetPlanningSceneResponse(scene=self.scene_msg(req.components.components or 0xFFFF))

    def srv_apply_scene(self, req) -> ApplyPlanningSceneResponse:
        try:
            self.apply_scene(req.scene)
        except (SceneError, ValueError, LookupError) as exc:
            rospy.logerr('apply_planning_scene: %s', exc)
            return ApplyPlanningSceneResponse(success=False)
        return ApplyPlanningSceneResponse(success=True)

    def srv_clear_octomap(self, _req) -> EmptyResponse:
        return EmptyResponse()  # no octomap is kept: there is nothing to clear

    # --- planner interface ------------------------------------------------------------------

    def srv_query(self, _req) -> QueryPlannerInterfacesResponse:
        desc = PlannerInterfaceDescription(name='OMPL', pipeline_id='ompl')
        ids = []
        for group, g in self.ompl.groups.items():
            ids += ['%s[%s]' % (group, p) for p in g.planner_configs]
        desc.planner_ids = sorted(set(list(self.ompl.planner_configs) + ids))
        return QueryPlannerInterfacesResponse(planner_interfaces=[desc])

    def _config_key(self, planner_id: str, group: str) -> str:
        if group and planner_id and not planner_id.startswith(group + '['):
            key = '%s[%s]' % (group, planner_id)
            if key in self.ompl.planner_configs:
                return key
        return planner_id or group

    def srv_get_params(self, req) -> GetPlannerParamsResponse:
        res = GetPlannerParamsResponse()
        pc = self.ompl.planner_for(req.group, req.planner_config)
        params = PlannerParams()
        if pc is not None:
            items = {'type': pc.type, **{k: str(v) for k, v in pc.params.items()}}
            params.keys = list(items)
            params.values = [str(v) for v in items.values()]
        res.params = params
        return res

    def srv_set_params(self, req) -> SetPlannerParamsResponse:
        pc = self.ompl.planner_for(req.group, req.planner_config)
        if pc is None:
            rospy.logerr(
                "set_planner_params: no planner config '%s' for group '%s'",
                req.planner_config,
                req.group,
            )
            return SetPlannerParamsResponse()
        new = dict(zip(req.params.keys, req.params.values))
        if req.replace:
            pc.params = {}
        for k, v in new.items():
            if k == 'type':
                pc.type = v
            else:
                pc.params[k] = v
        planner_type(pc)  # says so once when the type cannot be planned with
        return SetPlannerParamsResponse()


def main(argv: Optional[List[str]] = None) -> int:
    rospy.init_node('move_group')
    route_core_logs()
    logging.getLogger('_arm1sim.planning').setLevel(logging.INFO)
    try:
        MoveGroup()
    except (ModelError, SrdfError, cfg.ConfigError) as exc:
        rospy.logfatal('move_group: %s', exc)
        return 1
    rospy.spin()
    return 0


__all__ = ['MoveGroup', 'main', 'PLANNERS']
