"""What a running bringup offers, asked over ROS: models, controller managers and their
controllers, sensors, topics, and whether the joints follow a command and a trajectory goal.

Runs in the try_robot process, whose rospy talks to the session's private master.
"""

import math
import time
from typing import Any, Callable, Dict, List, Optional, Tuple

import rosgraph
import rospy

from _arm1sim.description import urdf_model

Progress = Callable[[str], None]

JTC_SUFFIX = '/JointTrajectoryController'
POSITION_TYPES = (
    'position_controllers/JointPositionController',
    'effort_controllers/JointPositionController',
    'velocity_controllers/JointPositionController',
)
GROUP_POSITION_TYPES = (
    'position_controllers/JointGroupPositionController',
    'effort_controllers/JointGroupPositionController',
)
ACTION_RESULT = 'control_msgs/FollowJointTrajectoryActionResult'
CONTROLLER_STATE = 'control_msgs/JointTrajectoryControllerState'
STEP = 0.15  # rad (or m) each joint is asked to move
MOVED = 0.5  # a joint moved if it covered this share of STEP


def master(caller: str = '/try_robot') -> rosgraph.Master:
    return rosgraph.Master(caller)


def system_state() -> Tuple[list, list, list]:
    pubs, subs, srvs = master().getSystemState()
    return pubs, subs, srvs


def node_registered(name: str) -> bool:
    try:
        master().lookupNode(name)
        return True
    except Exception:  # rosgraph.MasterError: not (yet) registered
        return False


def node_alive(name: str) -> bool:
    """The node answers on its slave API, or is too busy to answer in time (a dead node may
    still be registered; a live world spawning a big model may not answer for seconds)."""
    try:
        uri = master().lookupNode(name)
    except Exception:  # rosgraph.MasterError: not (yet) registered
        return False
    return answers(uri) != 'no'


def answers(uri: str, timeout: float = 2.0) -> str:
    """'yes' when the XML-RPC server at uri answers getPid within timeout, 'busy' when it
    accepted the connection but did not answer in time, 'no' when nothing listens."""
    import socket
    import xmlrpc.client

    old = socket.getdefaulttimeout()
    socket.setdefaulttimeout(timeout)
    try:
        xmlrpc.client.ServerProxy(uri).getPid('/try_robot')
        return 'yes'
    except socket.timeout:
        return 'busy'
    except Exception:  # refused, reset, malformed: no node there
        return 'no'
    finally:
        socket.setdefaulttimeout(old)


def offered(msg_type: str, suffix: str = '') -> List[str]:
    """Topics of that type with a publisher now, without the suffix (an action's '/result')."""
    return sorted(
        t[: len(t) - len(suffix)]
        for t, ty in master().getTopicTypes()
        if ty == msg_type and t.endswith(suffix)
    )


def remapped(default: str, offered: List[str], defaults: List[str]) -> Optional[str]:
    """Where a launch file's <remap> put a controller's topic or action: default when it is
    offered, else the one offered name no controller has by default (ROS-Industrial's
    bringups remap arm_controller/follow_joint_trajectory to /joint_trajectory_action and
    arm_controller/state to /feedback_states); None when there is not exactly one."""
    if default in offered:
        return default
    left = [o for o in offered if o not in defaults]
    return left[0] if len(left) == 1 else None


def controller_managers() -> List[str]:
    """Namespaces of every controller manager (services .../controller_manager/list_controllers)."""
    suffix = '/controller_manager/list_controllers'
    return sorted(s[: -len(suffix)] or '/' for s, _ in system_state()[2] if s.endswith(suffix))


def _service(ns: str, name: str) -> str:
    return rosgraph.names.ns_join(ns, 'controller_manager/' + name)


def list_controllers(ns: str) -> List[Dict[str, Any]]:
    from controller_manager_msgs.srv import ListControllers

    service = _service(ns, 'list_controllers')
    rospy.wait_for_service(service, 5.0)
    reply = rospy.ServiceProxy(service, ListControllers)()
    out = []
    for c in reply.controller:
        joints = sorted({r for cr in c.claimed_resources for r in cr.resources})
        ifaces = sorted({cr.hardware_interface for cr in c.claimed_resources})
        out.append(
            {
                'name': c.name,
                'type': c.type,
                'state': c.state,
                'joints': joints,
                'interfaces': ifaces,
            }
        )
    return out


def settle_controllers(
    timeout: float, quiet_for: float, progress: Progress, world_alive: Callable[[], bool]
) -> Dict[str, List[Dict[str, Any]]]:
    """Controller managers and their controllers once nothing changed for quiet_for seconds
    (the spawners are done), at timeout, or as soon as the world is gone."""
    deadline = time.monotonic() + timeout
    last: Optional[object] = None
    since = time.monotonic()
    found: Dict[str, List[Dict[str, Any]]] = {}
    while time.monotonic() < deadline:
        if not found and not world_alive():
            progress('the world /gazebo is gone')
            break
        found = {}
        for ns in controller_managers():
            try:
                found[ns] = list_controllers(ns)
            except Exception as e:  # a manager going away, a service not ready
                found[ns] = [{'error': str(e)}]
        key = repr(sorted((ns, repr(v)) for ns, v in found.items()))
        if key != last:
            last = key
            since = time.monotonic()
            n = sum(len(v) for v in found.values())
            running = sum(1 for v in found.values() for c in v if c.get('state') == 'running')
            progress(
                'controller managers %s: %d controllers, %d running'
                % (', '.join(found) or '(none yet)', n, running)
            )
        elif found and time.monotonic() - since >= quiet_for:
            break
        time.sleep(0.5)
    return found


def models() -> Optional[List[str]]:
    from gazebo_msgs.srv import GetWorldProperties

    try:
        rospy.wait_for_service('/gazebo/get_world_properties', 5.0)
        reply = rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties)()
        return list(reply.model_names)
    except Exception:  # no world, or not the stand-in's services
        return None


def paused() -> Optional[bool]:
    """Whether the world is paused (None: it does not say)."""
    from gazebo_msgs.srv import GetPhysicsProperties

    try:
        rospy.wait_for_service('/gazebo/get_physics_properties', 5.0)
        return bool(
            rospy.ServiceProxy('/gazebo/get_physics_properties', GetPhysicsProperties)().pause
        )
    except Exception:  # no such service
        return None


def unpause() -> None:
    from std_srvs.srv import Empty

    rospy.ServiceProxy('/gazebo/unpause_physics', Empty)()


def gazebo_topics() -> List[str]:
    """Topics the world node /gazebo publishes (sensors, controllers, clock, states)."""
    return sorted(t for t, nodes in system_state()[0] if '/gazebo' in nodes)


def descriptions() -> Dict[str, str]:
    """Every robot_description-like parameter (a URDF string) by name."""
    out = {}
    for name in master().getParamNames():
        if name.rsplit('/', 1)[-1].endswith('robot_description'):
            value = rospy.get_param(name)
            if isinstance(value, str) and '<robot' in value:
                out[name] = value
    return out


def describe(urdf: str) -> Dict[str, Any]:
    """Joints with limits, sensors and Gazebo plugins named in a URDF."""
    model = urdf_model.parse_urdf(urdf)
    sensors = [
        {'link': link, 'name': s.get('name'), 'type': s.get('type')} for link, s in model.sensors
    ]
    plugins = [{'name': p.get('name'), 'filename': p.get('filename')} for p in model.model_plugins]
    for _, s in model.sensors:
        for p in s.iter('plugin'):
            plugins.append({'name': p.get('name'), 'filename': p.get('filename')})
    joints = {
        j.name: {'type': j.type, 'lower': j.limits.lower, 'upper': j.limits.upper}
        for j in model.joints.values()
    }
    return {'robot': model.name, 'joints': joints, 'sensors': sensors, 'plugins': plugins}


class JointStates:
    """Latest position of every joint, from every sensor_msgs/JointState topic."""

    def __init__(self) -> None:
        from sensor_msgs.msg import JointState

        self.positions: Dict[str, float] = {}
        self.velocities: Dict[str, float] = {}
        self.stamp = 0.0
        topics = [t for t, ty in master().getPublishedTopics('/') if ty == 'sensor_msgs/JointState']
        self.topics = sorted(topics)
        self.subs = [rospy.Subscriber(t, JointState, self._cb, queue_size=5) for t in self.topics]

    def _cb(self, msg) -> None:
        for name, pos in zip(msg.name, msg.position):
            self.positions[name] = pos
        for name, vel in zip(msg.name, msg.velocity):
            self.velocities[name] = vel
        self.stamp = time.monotonic()

    def wait(self, joints: List[str], timeout: float = 10.0) -> Dict[str, float]:
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if all(j in self.positions for j in joints):
                return {j: self.positions[j] for j in joints}
            time.sleep(0.1)
        missing = [j for j in joints if j not in self.positions]
        raise RuntimeError('no joint_states for %s on %s' % (missing, self.topics or 'no topic'))

    def wait_still(self, joints: List[str], timeout: float = 15.0, window: float = 0.5) -> bool:
        """Until no joint moved more than 2 mrad in a window (the arm has settled)."""
        deadline = time.monotonic() + timeout
        before = self.wait(joints)
        while time.monotonic() < deadline:
            time.sleep(window)
            now = {j: self.positions[j] for j in joints}
            if all(abs(now[j] - before[j]) < 0.002 for j in joints):
                return True
            before = now
        return False

    def close(self) -> None:
        for s in self.subs:
            s.unregister()


def _target(start: float, limits: Optional[dict]) -> float:
    """STEP away from start: towards the description's zero pose (usually clear of the
    ground: an effort-controlled arm lies where it fell before its controllers started, as
    in Gazebo), or, from near zero, towards the middle of the joint's range."""
    lo = limits.get('lower') if limits else None
    hi = limits.get('upper') if limits else None
    if abs(start) >= STEP:
        direction = -1.0 if start > 0 else 1.0
    elif lo is not None and hi is not None and hi > lo:
        direction = 1.0 if start <= (lo + hi) / 2 else -1.0
    else:
        direction = 1.0
    target = start + direction * STEP
    if lo is not None and hi is not None and hi > lo:
        target = min(max(target, float(lo)), float(hi))
    return target


def _moved(start: Dict[str, float], now: Dict[str, float], target: Dict[str, float]) -> dict:
    return {
        j: abs(now[j] - start[j]) >= MOVED * abs(target[j] - start[j]) and now[j] != start[j]
        for j in start
    }


def position_command(
    ns: str, controller: Dict[str, Any], states: JointStates, limits: Dict[str, dict]
) -> Dict[str, Any]:
    """Command a (group) position controller STEP away, watch joint_states for 5 s."""
    from std_msgs.msg import Float64, Float64MultiArray

    name = str(controller['name'])
    joints = list(controller['joints'])
    if controller['type'] in GROUP_POSITION_TYPES:
        joints = rospy.get_param(rosgraph.names.ns_join(ns, name + '/joints'), joints)
    settled = states.wait_still(joints)
    start = states.wait(joints)
    target = {j: _target(start[j], limits.get(j)) for j in joints}
    topic = rosgraph.names.ns_join(ns, name + '/command')
    if controller['type'] in GROUP_POSITION_TYPES:
        pub = rospy.Publisher(topic, Float64MultiArray, queue_size=1, latch=True)
        msg: object = Float64MultiArray(data=[target[j] for j in joints])
    else:
        pub = rospy.Publisher(topic, Float64, queue_size=1, latch=True)
        msg = Float64(data=target[joints[0]])
    deadline = time.monotonic() + 5.0
    while pub.get_num_connections() == 0 and time.monotonic() < deadline:
        time.sleep(0.05)
    pub.publish(msg)
    time.sleep(0.2)
    moved: dict = {}
    while time.monotonic() < deadline + 5.0:
        now = {j: states.positions[j] for j in joints}
        moved = _moved(start, now, target)
        if all(moved.values()):
            break
        time.sleep(0.1)
    # back where it was, so the next check starts from rest
    if controller['type'] in GROUP_POSITION_TYPES:
        pub.publish(Float64MultiArray(data=[start[j] for j in joints]))
    else:
        pub.publish(Float64(data=start[joints[0]]))
    time.sleep(1.0)
    pub.unregister()
    return {
        'controller': rosgraph.names.ns_join(ns, name),
        'type': controller['type'],
        'command_topic': topic,
        'settled': settled,
        'start': start,
        'target': target,
        'reached': {j: states.positions[j] for j in joints},
        'moved': moved,
        'ok': bool(moved) and all(moved.values()),
    }


def trajectory_goal(
    ns: str,
    controller: Dict[str, Any],
    states: JointStates,
    limits: Dict[str, dict],
    duration: float = 2.0,
    siblings: Tuple[str, ...] = (),
) -> Dict[str, Any]:
    """A FollowJointTrajectory goal over all the controller's joints, STEP away, with no
    tolerances of its own: the controller's constraints (the package's yaml) judge it.
    siblings: every trajectory controller's full name (their action and state topics'
    default names, to tell which remapped name is this one's)."""
    import actionlib
    from control_msgs.msg import FollowJointTrajectoryAction, FollowJointTrajectoryGoal
    from trajectory_msgs.msg import JointTrajectoryPoint

    name = str(controller['name'])
    joints = rospy.get_param(
        rosgraph.names.ns_join(ns, name + '/joints'),
        list(controller['joints']),
    )
    default = rosgraph.names.ns_join(ns, name + '/follow_joint_trajectory')
    action = (
        remapped(
            default,
            offered(ACTION_RESULT, '/result'),
            [s + '/follow_joint_trajectory' for s in siblings],
        )
        or default
    )
    out: Dict[str, Any] = {
        'controller': rosgraph.names.ns_join(ns, name),
        'type': controller['type'],
        'action': action,
        'remapped_from': default if action != default else None,
        'joints': joints,
        'ok': False,
    }
    client = actionlib.SimpleActionClient(action, FollowJointTrajectoryAction)
    if not client.wait_for_server(rospy.Duration(10.0)):
        out['error'] = 'action server %s did not come up in 10 s' % action
        return out
    out['settled'] = states.wait_still(joints)
    # An effort-controlled arm started while falling holds where its stop trajectory ended,
    # which may be inside the ground it now lies on (as in Gazebo): the path tolerance would
    # abort any goal at once. A restart holds the measured pose, as a user would do.
    state = rosgraph.names.ns_join(ns, name + '/state')
    state = remapped(state, offered(CONTROLLER_STATE), [s + '/state' for s in siblings]) or state
    error = hold_error(state)
    out['hold_error_before'] = error
    path = [
        rospy.get_param(rosgraph.names.ns_join(ns, '%s/constraints/%s/trajectory' % (name, j)), 0.0)
        for j in joints
    ]
    if error is not None and any(
        tol > 0 and abs(error.get(j, 0.0)) > tol / 2 for j, tol in zip(joints, path)
    ):
        restart(ns, name)
        out['restarted_to_hold_the_measured_pose'] = True
        time.sleep(1.0)
        out['hold_error_after_restart'] = hold_error(state)
    start = states.wait(joints)
    target = {j: _target(start[j], limits.get(j)) for j in joints}
    goal = FollowJointTrajectoryGoal()
    goal.trajectory.joint_names = joints
    goal.trajectory.points = [
        JointTrajectoryPoint(
            positions=[target[j] for j in joints],
            velocities=[0.0] * len(joints),
            time_from_start=rospy.Duration(duration),
        )
    ]
    t0 = time.monotonic()
    client.send_goal(goal)
    finished = client.wait_for_result(rospy.Duration(duration + 20.0))
    elapsed = time.monotonic() - t0
    result = client.get_result()
    time.sleep(0.3)
    reached = {j: states.positions[j] for j in joints}
    out['final_velocity'] = {j: states.velocities.get(j) for j in joints}
    errors = {j: reached[j] - target[j] for j in joints}
    out.update(
        {
            'start': start,
            'target': target,
            'reached': reached,
            'final_error': errors,
            'max_abs_error': max((abs(e) for e in errors.values()), default=0.0),
            'moved': _moved(start, reached, target),
            'seconds': round(elapsed, 2),
            'finished': bool(finished),
            'goal_state': client.get_state(),
            'error_code': result.error_code if result else None,
            'error_string': result.error_string if result else '',
            'constraints': rospy.get_param(rosgraph.names.ns_join(ns, name + '/constraints'), None),
        }
    )
    out['ok'] = bool(finished and result is not None and result.error_code == 0)
    if not finished:
        client.cancel_goal()
    return out


def hold_error(topic: str) -> Optional[Dict[str, float]]:
    """A trajectory controller's position error per joint, from its state topic."""
    from control_msgs.msg import JointTrajectoryControllerState

    try:
        msg = rospy.wait_for_message(topic, JointTrajectoryControllerState, 3.0)
    except rospy.ROSException:
        return None
    return dict(zip(msg.joint_names, msg.error.positions))


def restart(ns: str, name: str) -> None:
    """Stop and start a controller (it then holds the measured state)."""
    from controller_manager_msgs.srv import SwitchController

    switch = rospy.ServiceProxy(_service(ns, 'switch_controller'), SwitchController)
    switch([], [name], 2, False, 0.0)
    switch([name], [], 2, False, 0.0)


def finite(d: Dict[str, float]) -> bool:
    return all(math.isfinite(v) for v in d.values())
