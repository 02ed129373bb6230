"""What moveit_commander's C++ side does in the client process: the robot model (URDF and
SRDF from the parameter server), the current state from /joint_states, and the names of
move_group's actions, services and topics (move_group/capability_names.h, noetic).
"""

from __future__ import annotations

import threading
import time
from typing import Dict, List, Optional, Sequence

import actionlib
import rospy
from moveit_msgs.msg import RobotState
from moveit_msgs.srv import GetPositionFK, GetPositionFKRequest
from sensor_msgs.msg import JointState

from _arm1sim.description import semantic_model as srdf

from .exception import MoveItCommanderException

MOVE_ACTION = 'move_group'
EXECUTE_ACTION = 'execute_trajectory'
PICKUP_ACTION = 'pickup'
PLACE_ACTION = 'place'
CARTESIAN_PATH_SERVICE = 'compute_cartesian_path'
FK_SERVICE = 'compute_fk'
IK_SERVICE = 'compute_ik'
GET_PLANNING_SCENE_SERVICE = 'get_planning_scene'
APPLY_PLANNING_SCENE_SERVICE = 'apply_planning_scene'
QUERY_PLANNERS_SERVICE = 'query_planner_interface'
EXECUTION_EVENT_TOPIC = 'trajectory_execution_event'
ATTACHED_COLLISION_OBJECT_TOPIC = 'attached_collision_object'
COLLISION_OBJECT_TOPIC = 'collision_object'

# CurrentStateMonitor's default wait for a state newer than the request (seconds, wall)
STATE_WAIT = 1.0


class ActionClient(actionlib.SimpleActionClient):
    """SimpleActionClient without its race: move_group may answer before send_goal has
    stored the new goal's handle, and rospy's client then logs 'Got a transition callback on
    a goal handle that we're not tracking' (an ERROR line the C++ interface never prints).
    The handle is stored under a lock the callbacks take; a stale handle's news is dropped."""

    def __init__(self, ns: str, action_spec) -> None:
        self._tracking = threading.RLock()
        super().__init__(ns, action_spec)

    def send_goal(self, goal, done_cb=None, active_cb=None, feedback_cb=None) -> None:
        with self._tracking:
            super().send_goal(goal, done_cb, active_cb, feedback_cb)

    def _handle_transition(self, gh) -> None:
        with self._tracking:
            if gh == self.gh:
                super()._handle_transition(gh)

    def _handle_feedback(self, gh, feedback) -> None:
        with self._tracking:
            if gh == self.gh:
                super()._handle_feedback(gh, feedback)


_models: Dict[str, srdf.SemanticModel] = {}
_models_lock = threading.Lock()


def semantic_model(robot_description: str = 'robot_description') -> srdf.SemanticModel:
    """The robot model named by ``robot_description`` and its ``_semantic`` twin, read once
    per process (upstream's getSharedRobotModel)."""
    with _models_lock:
        if robot_description not in _models:
            try:
                urdf_text = rospy.get_param(robot_description)
                srdf_text = rospy.get_param(robot_description + '_semantic')
            except KeyError as e:
                raise MoveItCommanderException(
                    "Unable to construct robot model: parameter %s is not set. Please make "
                    "sure all needed information is on the parameter server (a *_moveit_config's "
                    "planning_context.launch loads it)." % e
                ) from None
            try:
                _models[robot_description] = srdf.load(urdf_text, srdf_text)
            except ValueError as e:  # SrdfError, UrdfError
                raise MoveItCommanderException('Unable to construct robot model: %s' % e) from None
        return _models[robot_description]


class StateMonitor:
    """The latest value of every joint on joint_states, with the stamp it came with."""

    def __init__(self) -> None:
        self._lock = threading.Condition()
        self.positions: Dict[str, float] = {}
        self.velocities: Dict[str, float] = {}
        self.stamps: Dict[str, rospy.Time] = {}
        self._sub = rospy.Subscriber('joint_states', JointState, self._on_state, queue_size=25)

    def _on_state(self, msg: JointState) -> None:
        with self._lock:
            for i, name in enumerate(msg.name):
                if i < len(msg.position):
                    self.positions[name] = msg.position[i]
                    self.stamps[name] = msg.header.stamp
                if i < len(msg.velocity):
                    self.velocities[name] = msg.velocity[i]
            self._lock.notify_all()

    def wait_for(
        self, joints: Sequence[str], since: Optional[rospy.Time], timeout: float = STATE_WAIT
    ) -> bool:
        """True once every joint has a value (stamped at or after ``since`` when given)."""
        deadline = time.monotonic() + timeout

        def ready() -> bool:
            for j in joints:
                stamp = self.stamps.get(j)
                if stamp is None or (since is not None and stamp < since):
                    return False
            return True

        with self._lock:
            while not ready():
                left = deadline - time.monotonic()
                if left <= 0 or rospy.is_shutdown():
                    return False
                self._lock.wait(min(left, 0.05))
            return True

    def values(self, joints: Sequence[str]) -> List[float]:
        with self._lock:
            return [self.positions.get(j, 0.0) for j in joints]


_monitor: Optional[StateMonitor] = None


def state_monitor() -> StateMonitor:
    """One monitor per process, shared by every commander (upstream's getSharedStateMonitor)."""
    global _monitor
    if _monitor is None:
        _monitor = StateMonitor()
    return _monitor


def current_values(model: srdf.SemanticModel, joints: Sequence[str]) -> List[float]:
    """The joints' current values, waiting up to a second for a state newer than now, as
    MoveGroupInterface::getCurrentState does; complains once if joints never report."""
    monitor = state_monitor()
    if not monitor.wait_for(joints, rospy.Time.now()):
        if not monitor.wait_for(joints, None, timeout=0.0):
            missing = [j for j in joints if j not in monitor.stamps]
            rospy.logerr_throttle(
                10,
                'moveit_commander: no joint_states for %s: the current state is unknown'
                % ', '.join(missing),
            )
    return monitor.values(joints)


def current_robot_state(model: srdf.SemanticModel) -> RobotState:
    """The current state as robotStateToRobotStateMsg writes it: every variable of the model."""
    state = RobotState()
    names = model.variable_joints
    state.joint_state.header.stamp = rospy.Time.now()
    state.joint_state.header.frame_id = model.model_frame
    state.joint_state.name = list(names)
    state.joint_state.position = current_values(model, names)
    return state


def forward_kinematics(
    model: srdf.SemanticModel, links: Sequence[str], state: RobotState, frame: str = ''
) -> list:
    """Poses (PoseStamped) of ``links`` in ``frame`` (the planning frame by default) for a
    state, from move_group's compute_fk service."""
    try:
        rospy.wait_for_service(FK_SERVICE, timeout=5.0)
    except rospy.ROSException:
        raise MoveItCommanderException(
            "move_group's %s service is not available: is move_group running?"
            % rospy.resolve_name(FK_SERVICE)
        ) from None
    req = GetPositionFKRequest()
    req.header.frame_id = frame or model.model_frame
    req.header.stamp = rospy.Time.now()
    req.fk_link_names = list(links)
    req.robot_state = state
    res = rospy.ServiceProxy(FK_SERVICE, GetPositionFK)(req)
    if res.error_code.val != 1:
        raise MoveItCommanderException(
            'compute_fk failed for %s (error code %d)' % (', '.join(links), res.error_code.val)
        )
    return list(res.pose_stamped)


def group(model: srdf.SemanticModel, name: str) -> srdf.Group:
    try:
        return model.groups[name]
    except KeyError:
        raise MoveItCommanderException(
            "Group '%s' was not found. The SRDF defines: %s"
            % (name, ', '.join(model.groups) or 'no group')
        ) from None
