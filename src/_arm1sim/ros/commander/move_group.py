"""moveit_commander.MoveGroupCommander: one planning group's targets, planned and executed by
move_group through its actions and services, as move_group.py and the C++
MoveGroupInterface it wraps do (noetic): the same requests on the wire (goal constraints,
tolerances, scaling, planner id, planning time), the same return values.
"""

from __future__ import annotations

import copy
import random
from typing import Dict, List, Optional, Sequence

import actionlib
import rospy
from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import Pose, PoseStamped
from moveit_msgs.msg import (
    AttachedCollisionObject,
    CollisionObject,
    Constraints,
    ExecuteTrajectoryAction,
    ExecuteTrajectoryGoal,
    Grasp,
    JointConstraint,
    MotionPlanRequest,
    MoveGroupAction,
    MoveGroupGoal,
    MoveItErrorCodes,
    OrientationConstraint,
    PickupAction,
    PickupGoal,
    PlaceAction,
    PlaceGoal,
    PlaceLocation,
    PlannerInterfaceDescription,
    PositionConstraint,
    RobotState,
    RobotTrajectory,
    TrajectoryConstraints,
    WorkspaceParameters,
)
from moveit_msgs.srv import (
    GetCartesianPath,
    GetCartesianPathRequest,
    GetPositionIK,
    GetPositionIKRequest,
    QueryPlannerInterfaces,
)
from rosgraph.names import ns_join
from sensor_msgs.msg import JointState
from shape_msgs.msg import SolidPrimitive
from std_msgs.msg import String

from _arm1sim.description import semantic_model
from _arm1sim.description.pose_math import quat_from_rpy, rpy_from_quat

from . import client, conversions
from .exception import MoveItCommanderException

# move_group_interface.h
DEFAULT_GOAL_JOINT_TOLERANCE = 1e-4
DEFAULT_GOAL_POSITION_TOLERANCE = 1e-4
DEFAULT_GOAL_ORIENTATION_TOLERANCE = 1e-3
DEFAULT_ALLOWED_PLANNING_TIME = 5.0
DEFAULT_NUM_PLANNING_ATTEMPTS = 1

JOINT, POSE, POSITION, ORIENTATION = 'joint', 'pose', 'position', 'orientation'


class MoveGroupCommander:
    """Execution of simple commands for a particular group."""

    def __init__(
        self,
        name: str,
        robot_description: str = 'robot_description',
        ns: str = '',
        wait_for_servers: float = 5.0,
    ) -> None:
        self._model = client.semantic_model(robot_description)
        self._group = client.group(self._model, name)
        self._ns = ns
        desc = robot_description or 'robot_description'
        kin = '%s_kinematics/%s/' % (desc, name)
        self._goal_joint_tolerance = rospy.get_param(
            kin + 'goal_joint_tolerance', DEFAULT_GOAL_JOINT_TOLERANCE
        )
        self._goal_position_tolerance = rospy.get_param(
            kin + 'goal_position_tolerance', DEFAULT_GOAL_POSITION_TOLERANCE
        )
        self._goal_orientation_tolerance = rospy.get_param(
            kin + 'goal_orientation_tolerance', DEFAULT_GOAL_ORIENTATION_TOLERANCE
        )
        planning = desc + '_planning/'
        self._velocity_scaling = rospy.get_param(planning + 'default_velocity_scaling_factor', 0.1)
        self._acceleration_scaling = rospy.get_param(
            planning + 'default_acceleration_scaling_factor', 0.1
        )
        self._planning_time = DEFAULT_ALLOWED_PLANNING_TIME
        self._attempts = DEFAULT_NUM_PLANNING_ATTEMPTS
        self._pipeline_id = ''
        self._planner_id = ''
        self._workspace = WorkspaceParameters()
        self._start_state: RobotState = RobotState(is_diff=True)
        self._target: Dict[str, float] = {
            j: semantic_model.default_value(self._model.limits[j])
            for j in self._model.variable_joints
        }
        self._active_target = JOINT
        self._pose_targets: Dict[str, List[PoseStamped]] = {}
        self._eef_link = self._group.end_effector_link
        self._pose_reference_frame = self._model.model_frame
        self._path_constraints: Optional[Constraints] = None
        self._trajectory_constraints: Optional[TrajectoryConstraints] = None
        self._remembered: Dict[str, List[float]] = {}
        self._support_surface = ''
        self._cartesian_speed_link = ''
        self._max_cartesian_speed = 0.0
        self._can_look = False
        self._can_replan = False
        self._replan_delay = 2.0
        self._replan_attempts = 1
        client.state_monitor()
        self._event_pub = rospy.Publisher(
            ns_join(ns, client.EXECUTION_EVENT_TOPIC), String, queue_size=1
        )
        self._attached_pub = rospy.Publisher(
            ns_join(ns, client.ATTACHED_COLLISION_OBJECT_TOPIC),
            AttachedCollisionObject,
            queue_size=1,
        )
        deadline = rospy.Duration(wait_for_servers) if wait_for_servers > 0 else rospy.Duration()
        self._move = self._action(client.MOVE_ACTION, MoveGroupAction, deadline)
        self._pick = self._action(client.PICKUP_ACTION, PickupAction, rospy.Duration(0.5))
        self._place = self._action(client.PLACE_ACTION, PlaceAction, rospy.Duration(0.5))
        self._execute = self._action(client.EXECUTE_ACTION, ExecuteTrajectoryAction, deadline)
        if self._move is None:
            raise MoveItCommanderException(
                "Unable to connect to move_group action server '%s' within allotted time (%.0fs): "
                'is move_group running?'
                % (rospy.resolve_name(ns_join(ns, client.MOVE_ACTION)), wait_for_servers)
            )
        self._cartesian = rospy.ServiceProxy(
            ns_join(ns, client.CARTESIAN_PATH_SERVICE), GetCartesianPath
        )
        self._ik = rospy.ServiceProxy(ns_join(ns, client.IK_SERVICE), GetPositionIK)
        self._query = rospy.ServiceProxy(
            ns_join(ns, client.QUERY_PLANNERS_SERVICE), QueryPlannerInterfaces
        )
        rospy.loginfo('Ready to take commands for planning group %s.' % name)

    def _action(self, name: str, spec, timeout: rospy.Duration):
        ac = client.ActionClient(ns_join(self._ns, name), spec)
        if ac.wait_for_server(timeout):
            return ac
        return None

    # --- the group
    def get_name(self) -> str:
        return self._group.name

    def get_active_joints(self) -> List[str]:
        return list(self._group.active_joints)

    def get_joints(self) -> List[str]:
        return list(self._group.joints)

    def get_variables(self) -> List[str]:
        return list(self._group.variables)

    def get_variable_count(self) -> int:
        return len(self._group.variables)

    def has_end_effector_link(self) -> bool:
        return bool(self._eef_link)

    def get_end_effector_link(self) -> str:
        return self._eef_link

    def set_end_effector_link(self, link_name: str) -> None:
        if not self._eef_link or not link_name:
            raise MoveItCommanderException('Unable to set end effector link')
        self._eef_link = link_name

    def get_pose_reference_frame(self) -> str:
        return self._pose_reference_frame

    def set_pose_reference_frame(self, reference_frame: str) -> None:
        self._pose_reference_frame = reference_frame

    def get_planning_frame(self) -> str:
        return self._model.model_frame

    def get_interface_description(self) -> PlannerInterfaceDescription:
        try:
            res = self._query()
        except (rospy.ServiceException, rospy.ROSException):
            return PlannerInterfaceDescription()
        return (
            res.planner_interfaces[0] if res.planner_interfaces else PlannerInterfaceDescription()
        )

    # --- the current state
    def get_current_joint_values(self) -> List[float]:
        return client.current_values(self._model, self._group.variables)

    def get_current_state(self) -> RobotState:
        return client.current_robot_state(self._model)

    def get_current_state_bounded(self) -> RobotState:
        state = self.get_current_state()
        state.joint_state.position = [
            self._clamp(j, v) for j, v in zip(state.joint_state.name, state.joint_state.position)
        ]
        return state

    def _clamp(self, joint: str, value: float) -> float:
        lower, upper = self._model.limits.get(joint, (None, None))
        if lower is not None and value < lower:
            return lower
        if upper is not None and value > upper:
            return upper
        return value

    def _eef(self, end_effector_link: str) -> str:
        eef = end_effector_link or self._eef_link
        if not eef:
            raise MoveItCommanderException('There is no end effector to get the pose of')
        return eef

    def get_current_pose(self, end_effector_link: str = '') -> PoseStamped:
        eef = self._eef(end_effector_link)
        pose = client.forward_kinematics(self._model, [eef], self.get_current_state())[0]
        pose.header.stamp = rospy.Time.now()
        return pose

    def get_current_rpy(self, end_effector_link: str = '') -> List[float]:
        o = self.get_current_pose(end_effector_link).pose.orientation
        return list(rpy_from_quat((o.x, o.y, o.z, o.w)))

    def get_random_joint_values(self) -> List[float]:
        out = []
        for j in self._group.variables:
            lower, upper = self._model.limits[j]
            lower = -3.141592653589793 if lower is None else lower
            upper = 3.141592653589793 if upper is None else upper
            out.append(random.uniform(lower, upper))
        return out

    def get_random_pose(self, end_effector_link: str = '') -> PoseStamped:
        eef = self._eef(end_effector_link)
        state = self.get_current_state()
        values = dict(zip(state.joint_state.name, state.joint_state.position))
        values.update(zip(self._group.variables, self.get_random_joint_values()))
        state.joint_state.position = [values[n] for n in state.joint_state.name]
        return client.forward_kinematics(self._model, [eef], state)[0]

    # --- start state
    def set_start_state_to_current_state(self) -> None:
        self._start_state = RobotState(is_diff=True)

    def set_start_state(self, msg: RobotState) -> None:
        self._start_state = copy.deepcopy(msg)

    # --- joint targets
    def get_joint_value_target(self) -> List[float]:
        return [self._target[j] for j in self._group.variables]

    def _within_bounds(self, joints: Sequence[str]) -> bool:
        tol = self._goal_joint_tolerance
        for j in joints:
            lower, upper = self._model.limits[j]
            v = self._target[j]
            if (lower is not None and v < lower - tol) or (upper is not None and v > upper + tol):
                return False
        return True

    def _set_values(self, values: Dict[str, float]) -> bool:
        for j in values:
            if j not in self._target:
                rospy.logerr("joint '%s' is not a variable of the robot model" % j)
                return False
        self._target.update(values)
        self._active_target = JOINT
        return self._within_bounds(list(values))

    def set_joint_value_target(self, arg1, arg2=None, arg3=None) -> None:
        """A list (every variable of the group), a dict or JointState (some joints), a joint
        name and value, or a Pose/PoseStamped solved by IK (optionally eef link and approx)."""
        bounds_msg = 'Error setting joint target. Is the target within bounds?'
        if isinstance(arg1, JointState):
            if arg2 is not None or arg3 is not None:
                raise MoveItCommanderException('Too many arguments specified')
            if len(arg1.name) != len(arg1.position) or not self._set_values(
                dict(zip(arg1.name, arg1.position))
            ):
                raise MoveItCommanderException(bounds_msg)
        elif isinstance(arg1, str):
            if arg2 is None:
                raise MoveItCommanderException('Joint value expected when joint name specified')
            if arg3 is not None:
                raise MoveItCommanderException('Too many arguments specified')
            values = list(arg2) if hasattr(arg2, '__iter__') else [arg2]
            if len(values) != 1 or not self._set_values({arg1: float(values[0])}):
                raise MoveItCommanderException(bounds_msg)
        elif isinstance(arg1, (Pose, PoseStamped)):
            approx, eef = False, ''
            for extra in (arg2, arg3):
                if extra is None:
                    continue
                if type(extra) is str:
                    eef = extra
                elif type(extra) is bool:
                    approx = extra
                else:
                    raise MoveItCommanderException('Unexpected type')
            if not self._joint_target_from_pose(arg1, eef, approx):
                raise MoveItCommanderException(
                    'Error setting joint target. Does your IK solver support approximate IK?'
                    if approx
                    else 'Error setting joint target. Is the IK solver functional?'
                )
        elif isinstance(arg1, dict):
            if arg2 is not None or arg3 is not None:
                raise MoveItCommanderException('Too many arguments specified')
            if not self._set_values({k: float(v) for k, v in arg1.items()}):
                raise MoveItCommanderException(bounds_msg)
        elif hasattr(arg1, '__iter__'):
            if arg2 is not None or arg3 is not None:
                raise MoveItCommanderException('Too many arguments specified')
            values = [float(v) for v in arg1]
            if len(values) != len(self._group.variables):
                rospy.logerr(
                    'The group %s has %d variables, the target has %d values'
                    % (self._group.name, len(self._group.variables), len(values))
                )
                raise MoveItCommanderException(bounds_msg)
            if not self._set_values(dict(zip(self._group.variables, values))):
                raise MoveItCommanderException(bounds_msg)
        else:
            raise MoveItCommanderException('Unsupported argument of type %s' % type(arg1))

    def _joint_target_from_pose(self, pose, eef: str, approx: bool) -> bool:
        """One IK solution from move_group's compute_ik, seeded with the current state (the
        C++ interface calls its local solver, no collision check; so does this request)."""
        if isinstance(pose, Pose):
            stamped = PoseStamped(pose=pose)
            stamped.header.frame_id = self._pose_reference_frame
        else:
            stamped = pose
        req = GetPositionIKRequest()
        req.ik_request.group_name = self._group.name
        req.ik_request.robot_state = self.get_current_state()
        req.ik_request.avoid_collisions = False
        req.ik_request.ik_link_name = eef or self._eef_link
        req.ik_request.pose_stamped = stamped
        try:
            self._ik.wait_for_service(5.0)
            res = self._ik(req)
        except (rospy.ServiceException, rospy.ROSException) as e:
            rospy.logerr('compute_ik: %s' % e)
            return False
        if res.error_code.val != MoveItErrorCodes.SUCCESS:
            return False
        values = dict(zip(res.solution.joint_state.name, res.solution.joint_state.position))
        return self._set_values({j: values[j] for j in self._group.variables if j in values})

    def set_named_target(self, name: str) -> None:
        values = self.get_named_target_values(name)
        if not values or not self._set_values(values):
            raise MoveItCommanderException(
                'Unable to set target %s. Is the target within bounds?' % name
            )

    def get_named_targets(self) -> List[str]:
        names = list(self._model.group_states.get(self._group.name, {}))
        return names + [n for n in self._remembered if n not in names]

    def get_named_target_values(self, target: str) -> Dict[str, float]:
        if target in self._remembered:
            return dict(zip(self._group.variables, self._remembered[target]))
        state = self._model.group_states.get(self._group.name, {}).get(target)
        if state is None:
            rospy.logerr("The requested named target '%s' does not exist" % target)
            return {}
        return dict(state)

    def remember_joint_values(self, name: str, values: Optional[Sequence[float]] = None) -> None:
        self._remembered[name] = (
            list(values) if values is not None else self.get_current_joint_values()
        )

    def get_remembered_joint_values(self) -> Dict[str, List[float]]:
        return dict(self._remembered)

    def forget_joint_values(self, name: str) -> None:
        self._remembered.pop(name, None)

    def set_random_target(self) -> None:
        self._set_values(dict(zip(self._group.variables, self.get_random_joint_values())))

    # --- pose targets
    def _stamped(self, pose) -> PoseStamped:
        if isinstance(pose, PoseStamped):
            return copy.deepcopy(pose)
        out = PoseStamped()
        out.header.frame_id = self._pose_reference_frame
        out.header.stamp = rospy.Time.now()
        out.pose = copy.deepcopy(pose) if isinstance(pose, Pose) else conversions.list_to_pose(pose)
        return out

    def set_pose_target(self, pose, end_effector_link: str = '') -> None:
        """A Pose, PoseStamped, or list [x, y, z, r, p, y] / [x, y, z, qx, qy, qz, qw]."""
        if not (end_effector_link or self._eef_link):
            raise MoveItCommanderException('There is no end effector to set the pose for')
        if not isinstance(pose, (Pose, PoseStamped)) and len(pose) not in (6, 7):
            raise MoveItCommanderException('Unable to set target pose')
        self._pose_targets[end_effector_link or self._eef_link] = [self._stamped(pose)]
        self._active_target = POSE

    def set_pose_targets(self, poses, end_effector_link: str = '') -> None:
        if not (end_effector_link or self._eef_link):
            raise MoveItCommanderException('There is no end effector to set poses for')
        self._pose_targets[end_effector_link or self._eef_link] = [self._stamped(p) for p in poses]
        self._active_target = POSE

    def _partial_target(self, end_effector_link: str) -> PoseStamped:
        eef = end_effector_link or self._eef_link
        if not eef:
            raise MoveItCommanderException('There is no end effector to set the pose for')
        targets = self._pose_targets.get(eef)
        if targets:
            return copy.deepcopy(targets[0])
        out = PoseStamped()
        out.header.frame_id = self._pose_reference_frame
        out.pose.orientation.w = 1.0
        return out

    def set_position_target(self, xyz, end_effector_link: str = '') -> None:
        target = self._partial_target(end_effector_link)
        target.pose.position.x, target.pose.position.y, target.pose.position.z = xyz[0:3]
        self._pose_targets[end_effector_link or self._eef_link] = [target]
        self._active_target = POSITION

    def set_orientation_target(self, q, end_effector_link: str = '') -> None:
        if len(q) != 4:
            raise MoveItCommanderException('Expected [qx, qy, qz, qw]')
        target = self._partial_target(end_effector_link)
        o = target.pose.orientation
        o.x, o.y, o.z, o.w = q
        self._pose_targets[end_effector_link or self._eef_link] = [target]
        self._active_target = ORIENTATION

    def set_rpy_target(self, rpy, end_effector_link: str = '') -> None:
        if len(rpy) != 3:
            raise MoveItCommanderException('Expected [roll, pitch, yaw]')
        self.set_orientation_target(list(quat_from_rpy(*rpy)), end_effector_link)

    def shift_pose_target(self, axis: int, value: float, end_effector_link: str = '') -> None:
        pose = self.get_current_pose(end_effector_link)
        values = conversions.pose_to_list(pose.pose)
        o = pose.pose.orientation
        flat = values[0:3] + list(rpy_from_quat((o.x, o.y, o.z, o.w)))
        flat[axis] += value
        self.set_pose_target(flat, end_effector_link)

    def clear_pose_target(self, end_effector_link: str) -> None:
        self._pose_targets.pop(end_effector_link or self._eef_link, None)

    def clear_pose_targets(self) -> None:
        self._pose_targets.clear()
        self._active_target = JOINT

    # --- tolerances and planner settings
    def get_goal_tolerance(self) -> List[float]:
        return [
            self._goal_joint_tolerance,
            self._goal_position_tolerance,
            self._goal_orientation_tolerance,
        ]

    def get_goal_joint_tolerance(self) -> float:
        return self._goal_joint_tolerance

    def get_goal_position_tolerance(self) -> float:
        return self._goal_position_tolerance

    def get_goal_orientation_tolerance(self) -> float:
        return self._goal_orientation_tolerance

    def set_goal_tolerance(self, value: float) -> None:
        self._goal_joint_tolerance = self._goal_position_tolerance = value
        self._goal_orientation_tolerance = value

    def set_goal_joint_tolerance(self, value: float) -> None:
        self._goal_joint_tolerance = value

    def set_goal_position_tolerance(self, value: float) -> None:
        self._goal_position_tolerance = value

    def set_goal_orientation_tolerance(self, value: float) -> None:
        self._goal_orientation_tolerance = value

    def allow_looking(self, value: bool) -> None:
        self._can_look = value

    def allow_replanning(self, value: bool) -> None:
        self._can_replan = value

    def set_planning_time(self, seconds: float) -> None:
        if seconds > 0:
            self._planning_time = seconds

    def get_planning_time(self) -> float:
        return self._planning_time

    def set_planning_pipeline_id(self, planning_pipeline: str) -> None:
        self._pipeline_id = planning_pipeline

    def get_planning_pipeline_id(self) -> str:
        return self._pipeline_id

    def set_planner_id(self, planner_id: str) -> None:
        self._planner_id = planner_id

    def get_planner_id(self) -> str:
        return self._planner_id

    def set_num_planning_attempts(self, num_planning_attempts: int) -> None:
        self._attempts = num_planning_attempts

    def set_workspace(self, ws) -> None:
        if len(ws) == 0:
            ws = [0.0] * 6
        elif len(ws) == 4:
            ws = [ws[0], ws[1], 0.0, ws[2], ws[3], 0.0]
        elif len(ws) != 6:
            raise MoveItCommanderException('Expected 0, 4 or 6 values in list specifying workspace')
        p = WorkspaceParameters()
        p.header.frame_id = self._model.model_frame
        p.header.stamp = rospy.Time.now()
        p.min_corner.x, p.min_corner.y, p.min_corner.z = ws[0:3]
        p.max_corner.x, p.max_corner.y, p.max_corner.z = ws[3:6]
        self._workspace = p

    def set_max_velocity_scaling_factor(self, value: float) -> None:
        if not 0 < value <= 1:
            raise MoveItCommanderException(
                'Expected value in the range from 0 to 1 for scaling factor'
            )
        self._velocity_scaling = value

    def set_max_acceleration_scaling_factor(self, value: float) -> None:
        if not 0 < value <= 1:
            raise MoveItCommanderException(
                'Expected value in the range from 0 to 1 for scaling factor'
            )
        self._acceleration_scaling = value

    def limit_max_cartesian_link_speed(self, speed: float, link_name: str = '') -> None:
        if speed <= 0.0:
            raise MoveItCommanderException('Expected speed value to be greater than 0')
        self._max_cartesian_speed = speed
        self._cartesian_speed_link = link_name or self._eef_link

    def clear_max_cartesian_link_speed(self) -> None:
        self._max_cartesian_speed = 0.0
        self._cartesian_speed_link = ''

    # --- constraints
    def get_path_constraints(self) -> Constraints:
        return copy.deepcopy(self._path_constraints) if self._path_constraints else Constraints()

    def set_path_constraints(self, value) -> None:
        if value is None:
            self.clear_path_constraints()
        elif isinstance(value, Constraints):
            self._path_constraints = copy.deepcopy(value)
        else:  # a name in the constraints database: there is no warehouse here
            raise MoveItCommanderException('Unable to set path constraints ' + str(value))

    def clear_path_constraints(self) -> None:
        self._path_constraints = None

    def get_known_constraints(self) -> List[str]:
        return []

    def get_trajectory_constraints(self) -> TrajectoryConstraints:
        return (
            copy.deepcopy(self._trajectory_constraints)
            if self._trajectory_constraints
            else TrajectoryConstraints()
        )

    def set_trajectory_constraints(self, value) -> None:
        if value is None:
            self.clear_trajectory_constraints()
        elif isinstance(value, TrajectoryConstraints):
            self._trajectory_constraints = copy.deepcopy(value)
        else:
            raise MoveItCommanderException('Unable to set trajectory constraints ' + str(value))

    def clear_trajectory_constraints(self) -> None:
        self._trajectory_constraints = None

    def set_support_surface_name(self, value: str) -> None:
        self._support_surface = value

    # --- requests
    def _goal_constraints(self) -> List[Constraints]:
        if self._active_target == JOINT:
            tol = self._goal_joint_tolerance
            return [
                Constraints(
                    joint_constraints=[
                        JointConstraint(
                            joint_name=j,
                            position=self._target[j],
                            tolerance_above=tol,
                            tolerance_below=tol,
                            weight=1.0,
                        )
                        for j in self._group.variables
                    ]
                )
            ]
        count = max((len(v) for v in self._pose_targets.values()), default=0)
        goals = [Constraints() for _ in range(count)]
        for link, poses in self._pose_targets.items():
            for i, pose in enumerate(poses):
                if self._active_target != ORIENTATION:
                    region = PositionConstraint(link_name=link, header=pose.header, weight=1.0)
                    region.constraint_region.primitives = [
                        SolidPrimitive(
                            type=SolidPrimitive.SPHERE, dimensions=[self._goal_position_tolerance]
                        )
                    ]
                    centre = Pose()
                    centre.position = copy.deepcopy(pose.pose.position)
                    centre.orientation.w = 1.0
                    region.constraint_region.primitive_poses = [centre]
                    goals[i].position_constraints.append(region)
                if self._active_target != POSITION:
                    tol = self._goal_orientation_tolerance
                    goals[i].orientation_constraints.append(
                        OrientationConstraint(
                            header=pose.header,
                            orientation=pose.pose.orientation,
                            link_name=link,
                            absolute_x_axis_tolerance=tol,
                            absolute_y_axis_tolerance=tol,
                            absolute_z_axis_tolerance=tol,
                            weight=1.0,
                        )
                    )
        return goals

    def construct_motion_plan_request(self) -> MotionPlanRequest:
        """The MotionPlanRequest move_group gets for the current targets."""
        req = MotionPlanRequest()
        req.group_name = self._group.name
        req.num_planning_attempts = self._attempts
        req.max_velocity_scaling_factor = self._velocity_scaling
        req.max_acceleration_scaling_factor = self._acceleration_scaling
        req.cartesian_speed_limited_link = self._cartesian_speed_link
        req.max_cartesian_speed = self._max_cartesian_speed
        req.allowed_planning_time = self._planning_time
        req.pipeline_id = self._pipeline_id
        req.planner_id = self._planner_id
        req.workspace_parameters = copy.deepcopy(self._workspace)
        req.start_state = copy.deepcopy(self._start_state)
        if self._active_target != JOINT and not self._pose_targets:
            rospy.logerr('Unable to construct MotionPlanRequest representation: no pose target')
        req.goal_constraints = self._goal_constraints()
        if self._path_constraints:
            req.path_constraints = copy.deepcopy(self._path_constraints)
        if self._trajectory_constraints:
            req.trajectory_constraints = copy.deepcopy(self._trajectory_constraints)
        return req

    def _goal(self, plan_only: bool) -> MoveGroupGoal:
        goal = MoveGroupGoal(request=self.construct_motion_plan_request())
        goal.planning_options.plan_only = plan_only
        goal.planning_options.look_around = False if plan_only else self._can_look
        goal.planning_options.replan = False if plan_only else self._can_replan
        goal.planning_options.replan_attempts = self._replan_attempts
        goal.planning_options.replan_delay = self._replan_delay
        goal.planning_options.planning_scene_diff.is_diff = True
        goal.planning_options.planning_scene_diff.robot_state.is_diff = True
        return goal

    @staticmethod
    def _outcome(ac, what: str) -> MoveItErrorCodes:
        """The result's error code, as the C++ interface reports it (FAILURE without one)."""
        result = ac.get_result()
        if ac.get_state() != GoalStatus.SUCCEEDED:
            rospy.loginfo(
                '%s: %s: %s'
                % (
                    what,
                    actionlib.get_name_of_constant(GoalStatus, ac.get_state()),
                    ac.get_goal_status_text(),
                )
            )
        if result is None:
            return MoveItErrorCodes(val=MoveItErrorCodes.FAILURE)
        return result.error_code

    # --- planning and moving
    def go(self, joints=None, wait: bool = True) -> bool:
        """Set the target (if given) and move there; True on success."""
        if type(joints) is bool:
            wait, joints = joints, None
        elif type(joints) is JointState:
            self.set_joint_value_target(joints)
        elif type(joints) is Pose:
            self.set_pose_target(joints)
        elif joints is not None:
            try:
                self.set_joint_value_target(self.get_remembered_joint_values()[joints])
            except (KeyError, TypeError):
                self.set_joint_value_target(joints)
        self._move.send_goal(self._goal(plan_only=False))
        if not wait:
            return True
        self._move.wait_for_result()
        return self._outcome(self._move, 'MoveGroup').val == MoveItErrorCodes.SUCCESS

    def plan(self, joints=None):
        """(success, RobotTrajectory, planning time, MoveItErrorCodes), noetic's 4-tuple."""
        if type(joints) is str:
            self.set_joint_value_target(self.get_remembered_joint_values()[joints])
        elif type(joints) is Pose:
            self.set_pose_target(joints)
        elif joints is not None:
            self.set_joint_value_target(joints)
        self._move.send_goal(self._goal(plan_only=True))
        self._move.wait_for_result()
        error = self._outcome(self._move, 'MoveGroup')
        result = self._move.get_result()
        ok = self._move.get_state() == GoalStatus.SUCCEEDED and result is not None
        trajectory = result.planned_trajectory if ok else RobotTrajectory()
        planning_time = result.planning_time if ok else 0.0
        return (error.val == MoveItErrorCodes.SUCCESS, trajectory, planning_time, error)

    def execute(self, trajectory, wait: bool = True) -> bool:
        """Execute a planned RobotTrajectory (or a JointTrajectory); True on success."""
        if not hasattr(trajectory, 'joint_trajectory'):
            trajectory = RobotTrajectory(joint_trajectory=trajectory)
        if self._execute is None:
            rospy.logwarn('execute action server not connected')
            return False
        self._execute.send_goal(ExecuteTrajectoryGoal(trajectory=trajectory))
        if not wait:
            return True
        self._execute.wait_for_result()
        return self._outcome(self._execute, 'ExecuteTrajectory').val == MoveItErrorCodes.SUCCESS

    def stop(self) -> None:
        """Stop the current execution, if any (move_group's trajectory execution event)."""
        self._event_pub.publish(String(data='stop'))

    def compute_cartesian_path(
        self,
        waypoints,
        eef_step: float,
        jump_threshold: float,
        avoid_collisions: bool = True,
        path_constraints=None,
    ):
        """(RobotTrajectory, fraction followed); fraction -1.0 when the service fails."""
        if path_constraints and not isinstance(path_constraints, Constraints):
            raise MoveItCommanderException(
                'Unable to set path constraints, unknown constraint type %s'
                % type(path_constraints)
            )
        req = GetCartesianPathRequest()
        req.start_state = copy.deepcopy(self._start_state)
        req.group_name = self._group.name
        req.header.frame_id = self._pose_reference_frame
        req.header.stamp = rospy.Time.now()
        req.waypoints = list(waypoints)
        req.max_step = eef_step
        req.jump_threshold = jump_threshold
        req.path_constraints = path_constraints or Constraints()
        req.avoid_collisions = avoid_collisions
        req.link_name = self._eef_link
        req.cartesian_speed_limited_link = self._cartesian_speed_link
        req.max_cartesian_speed = self._max_cartesian_speed
        try:
            self._cartesian.wait_for_service(5.0)
            res = self._cartesian(req)
        except (rospy.ServiceException, rospy.ROSException) as e:
            rospy.logerr('compute_cartesian_path: %s' % e)
            return RobotTrajectory(), -1.0
        if res.error_code.val != MoveItErrorCodes.SUCCESS:
            return RobotTrajectory(), -1.0
        return res.solution, res.fraction

    # --- objects
    def attach_object(
        self, object_name: str, link_name: str = '', touch_links: Sequence[str] = ()
    ) -> bool:
        """Attach a world object to a link (the end effector by default) through the
        attached_collision_object topic; True once the request is sent."""
        link = link_name or self._eef_link or (self._group.links[0] if self._group.links else '')
        if not link:
            rospy.logerr('No known link to attach object %s to' % object_name)
            return False
        aco = AttachedCollisionObject(link_name=link, touch_links=list(touch_links) or [link])
        aco.object.id = object_name
        aco.object.operation = CollisionObject.ADD
        self._attached_pub.publish(aco)
        return True

    def detach_object(self, name: str = '') -> bool:
        """Detach the objects on the group's link ``name``, or the object ``name``, or every
        object on a link of the group."""
        if name and name in self._group.links:
            acos = [AttachedCollisionObject(link_name=name)]
        elif name:
            acos = [AttachedCollisionObject(object=CollisionObject(id=name))]
        else:
            acos = [AttachedCollisionObject(link_name=link) for link in self._group.links]
        for aco in acos:
            aco.object.operation = CollisionObject.REMOVE
            self._attached_pub.publish(aco)
        return True

    def pick(self, object_name: str, grasp=(), plan_only: bool = False) -> bool:
        """Pick through move_group's pickup action, when it offers one."""
        grasps = [grasp] if isinstance(grasp, Grasp) else list(grasp)
        if self._pick is None:
            rospy.logerr(
                "move_group offers no '%s' action: pick is not available" % client.PICKUP_ACTION
            )
            return False
        if not grasps:
            rospy.logerr(
                "Grasp planning service 'plan_grasps' is not available. "
                'This has to be implemented and started separately.'
            )
            return False
        goal = PickupGoal(
            target_name=object_name,
            end_effector=self._end_effector_name(),
            possible_grasps=grasps,
        )
        return self._manipulate(self._pick, goal, 'Pickup', plan_only)

    def place(self, object_name: str, location=None, plan_only: bool = False) -> bool:
        """Place through move_group's place action, when it offers one."""
        if self._place is None:
            rospy.logerr(
                "move_group offers no '%s' action: place is not available" % client.PLACE_ACTION
            )
            return False
        if isinstance(location, (Pose, PoseStamped)):
            locations = self._place_locations([location])
        elif isinstance(location, PlaceLocation):
            locations = [location]
        elif isinstance(location, list) and all(isinstance(x, PlaceLocation) for x in location):
            locations = list(location)
        elif isinstance(location, list) and all(isinstance(x, PoseStamped) for x in location):
            locations = self._place_locations(location)
        elif location is None:
            locations = []
        else:
            raise MoveItCommanderException(
                'Parameter location must be a Pose, PoseStamped, PlaceLocation, list of '
                'PoseStamped or list of PlaceLocation object'
            )
        goal = PlaceGoal(attached_object_name=object_name, place_locations=locations)
        return self._manipulate(self._place, goal, 'Place', plan_only)

    def _place_locations(self, poses) -> List[PlaceLocation]:
        """MoveGroupInterface::posesToPlaceLocations: approach 0.1-0.2 m down the model
        frame's z, retreat up to 0.2 m back along the end effector's x; the detach posture is
        the attached object's."""
        out = []
        for pose in poses:
            loc = PlaceLocation(place_pose=self._stamped(pose))
            loc.pre_place_approach.direction.vector.z = -1.0
            loc.pre_place_approach.direction.header.frame_id = self._model.model_frame
            loc.pre_place_approach.min_distance = 0.1
            loc.pre_place_approach.desired_distance = 0.2
            loc.post_place_retreat.direction.vector.x = -1.0
            loc.post_place_retreat.direction.header.frame_id = self._eef_link
            loc.post_place_retreat.min_distance = 0.0
            loc.post_place_retreat.desired_distance = 0.2
            out.append(loc)
        return out

    def _manipulate(self, ac, goal, what: str, plan_only: bool) -> bool:
        """A pickup or place goal with the group's settings (constructPickupGoal,
        constructPlaceGoal), sent and waited for; True on success."""
        goal.group_name = self._group.name
        goal.support_surface_name = self._support_surface
        goal.allow_gripper_support_collision = bool(self._support_surface)
        goal.planner_id = self._planner_id
        goal.allowed_planning_time = self._planning_time
        if self._path_constraints:
            goal.path_constraints = self._path_constraints
        self._fill_options(goal, plan_only)
        ac.send_goal(goal)
        ac.wait_for_result()
        return self._outcome(ac, what).val == MoveItErrorCodes.SUCCESS

    def _fill_options(self, goal, plan_only: bool) -> None:
        o = goal.planning_options
        o.plan_only, o.look_around, o.replan = plan_only, self._can_look, self._can_replan
        o.replan_delay = self._replan_delay
        o.planning_scene_diff.is_diff = True
        o.planning_scene_diff.robot_state.is_diff = True

    def _end_effector_name(self) -> str:
        for eef in self._model.end_effectors:
            if eef.parent_group == self._group.name or eef.parent_link == self._eef_link:
                return eef.name
        return ''

    def retime_trajectory(
        self,
        ref_state_in,
        traj_in,
        velocity_scaling_factor=1.0,
        acceleration_scaling_factor=1.0,
        algorithm='iterative_time_parameterization',
    ):
        raise MoveItCommanderException(
            'retime_trajectory runs MoveIt time parameterization in the client; this stand-in '
            'has none in the client: plan() returns trajectories move_group timed already'
        )

    def get_jacobian_matrix(self, joint_values, reference_point=None):
        raise MoveItCommanderException('get_jacobian_matrix is not available in this stand-in')

    def enforce_bounds(self, robot_state_msg: RobotState) -> RobotState:
        out = copy.deepcopy(robot_state_msg)
        out.joint_state.position = [
            self._clamp(j, v) for j, v in zip(out.joint_state.name, out.joint_state.position)
        ]
        return out
