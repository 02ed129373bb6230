"""try_grasp's tries over ROS, in the try_robot process once the bringup's controllers run:
place a box between the open fingers (from /gazebo/get_link_state), close the gripper and lift
the arm through the package's own controllers, hold, judge (grasp.judge_lift)."""

import argparse
import math
from typing import Any, Callable, Dict, List, Optional, Tuple

import rospy

from _arm1sim.tryout import grasp

Progress = Callable[[str], None]
BOX = 'try_grasp_box'
PEDESTAL = 'try_grasp_pedestal'


class Arm:
    """The arm and gripper through the package's own interface."""

    def __init__(self, g: grasp.Gripper, timeout: float) -> None:
        self.g = g
        self.last_grip_error = ''  # a franka_gripper goal's error, reported with the try
        self.last_move = ''  # how the last arm goal ended (trajectory actions)
        if g.kind == 'topics':
            from std_msgs.msg import Float64

            self.msg = Float64
            self.gripper = rospy.Publisher(g.gripper_topic, Float64, queue_size=1, latch=True)
            self.joints = [
                rospy.Publisher(t, Float64, queue_size=1, latch=True) for t in g.arm_topics
            ]
        else:
            import actionlib
            from control_msgs.msg import FollowJointTrajectoryAction

            actions: List[Tuple[str, Any]] = [(g.arm_action, FollowJointTrajectoryAction)]
            if g.kind == 'franka':
                from franka_gripper.msg import GraspAction, MoveAction

                actions += [(g.gripper_action + '/move', MoveAction)]
                actions += [(g.gripper_action + '/grasp', GraspAction)]
            else:
                actions += [(g.gripper_action, FollowJointTrajectoryAction)]
            self.clients = {}
            for ns, action in actions:
                c = actionlib.SimpleActionClient(ns, action)
                if not c.wait_for_server(rospy.Duration(timeout)):
                    raise RuntimeError('no %s server at %s' % (action.__name__, ns))
                self.clients[ns] = c
        rospy.sleep(0.5)  # subscribers connect

    def _goal(self, ns: str, joints: tuple, positions: tuple, seconds: float) -> None:
        from control_msgs.msg import FollowJointTrajectoryGoal
        from trajectory_msgs.msg import JointTrajectoryPoint

        goal = FollowJointTrajectoryGoal()
        goal.trajectory.joint_names = list(joints)
        goal.trajectory.points = [
            JointTrajectoryPoint(
                positions=list(positions),
                velocities=[0.0] * len(joints),
                time_from_start=rospy.Duration(seconds),
            )
        ]
        self.clients[ns].send_goal(goal)

    def _franka(self, width: float, seconds: float) -> None:
        """franka_gripper's move to the open width, or a grasp at width (the object's)."""
        from franka_gripper.msg import GraspEpsilon, GraspGoal, MoveGoal

        g = self.g
        self.last_grip_error = ''
        if width >= g.open_position[0]:
            ns, goal = g.gripper_action + '/move', MoveGoal(width=width, speed=g.grasp_speed)
        else:
            eps = GraspEpsilon(inner=g.grasp_epsilon, outer=g.grasp_epsilon)
            ns = g.gripper_action + '/grasp'
            goal = GraspGoal(width=width, epsilon=eps, speed=g.grasp_speed, force=g.grasp_force)
        c = self.clients[ns]
        c.send_goal(goal)
        # the hand answers once its fingers stop (success: within epsilon of the width)
        if not c.wait_for_result(rospy.Duration(seconds + 5.0)):
            raise RuntimeError('%s: no result within %.1f s' % (ns, seconds + 5.0))
        r = c.get_result()
        if r is not None and not r.success:
            self.last_grip_error = '%s: %s' % (ns, r.error or 'not successful')

    def grip(self, positions: tuple, seconds: float) -> None:
        if self.g.kind == 'topics':
            self.gripper.publish(self.msg(positions[0]))
        elif self.g.kind == 'franka':
            self._franka(positions[0], seconds)
            rospy.sleep(0.5)
            return
        else:
            self._goal(self.g.gripper_action, self.g.finger_joints, positions, seconds)
        rospy.sleep(seconds + 0.5)

    def move(self, frm: tuple, to: tuple, seconds: float) -> None:
        if self.g.kind == 'topics':
            # a ramp of position commands (the controllers jump to each; small steps carry)
            n = max(1, int(seconds / 0.02))
            for k in range(1, n + 1):
                for pub, a, b in zip(self.joints, frm, to):
                    pub.publish(self.msg(a + (b - a) * k / n))
                rospy.sleep(seconds / n)
        else:
            self._goal(self.g.arm_action, self.g.arm_joints, to, seconds)
            c = self.clients[self.g.arm_action]
            c.wait_for_result(rospy.Duration(seconds + 5.0))
            self.last_move = goal_outcome(c.get_state(), c.get_result())
        rospy.sleep(0.5)


def goal_outcome(state: int, result: Any) -> str:
    """A FollowJointTrajectory goal's end: its actionlib state and the result's error code."""
    from actionlib_msgs.msg import GoalStatus
    from control_msgs.msg import FollowJointTrajectoryResult as R

    names = {v: k for k, v in vars(GoalStatus).items() if k.isupper() and isinstance(v, int)}
    codes = {v: k for k, v in vars(R).items() if k.isupper() and isinstance(v, int)}
    text = names.get(state, str(state))
    if result is not None and result.error_code:
        text += ' %s' % codes.get(result.error_code, result.error_code)
    return text


class Gazebo:
    def __init__(self, timeout: float) -> None:
        from gazebo_msgs.srv import DeleteModel, GetLinkState, SpawnModel

        for s in ('get_link_state', 'spawn_urdf_model', 'spawn_sdf_model', 'delete_model'):
            rospy.wait_for_service('/gazebo/' + s, timeout)
        self.link_state = rospy.ServiceProxy('/gazebo/get_link_state', GetLinkState)
        self.spawn_urdf = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
        self.spawn_sdf = rospy.ServiceProxy('/gazebo/spawn_sdf_model', SpawnModel)
        self.delete = rospy.ServiceProxy('/gazebo/delete_model', DeleteModel)

    def pose(self, link: str) -> tuple:
        r = self.link_state(link, 'world')
        if not r.success:
            raise RuntimeError('get_link_state %s: %s' % (link, r.status_message))
        p, q = r.link_state.pose.position, r.link_state.pose.orientation
        return (p.x, p.y, p.z), (q.x, q.y, q.z, q.w)

    def remove(self, name: str) -> None:
        try:
            self.delete(name)
        except rospy.ServiceException:
            pass


class LinkStates:
    """/gazebo/link_states while it lives: every pose from one message is from one step. Two
    get_link_state calls are not (the world steps between them): an arm shaking by a fraction
    of a millimetre at its own undamped gains (JACO2's) read as a box slipping 2 mm."""

    def __init__(self, timeout: float) -> None:
        from gazebo_msgs.msg import LinkStates as Msg

        self._msg: Any = None
        self._sub = rospy.Subscriber('/gazebo/link_states', Msg, self._cb, queue_size=1)
        end = rospy.get_time() + timeout
        while self._msg is None:
            if rospy.get_time() > end or rospy.is_shutdown():
                self.close()
                raise RuntimeError('no /gazebo/link_states in %.0f s' % timeout)
            rospy.sleep(0.05)

    def _cb(self, msg: Any) -> None:
        self._msg = msg

    def poses(self, *links: str) -> List[tuple]:
        """((x, y, z), (qx, qy, qz, qw)) of each link, all from the latest message."""
        msg = self._msg
        out = []
        for link in links:
            if link not in msg.name:
                raise RuntimeError('%s not in /gazebo/link_states' % link)
            p = msg.pose[msg.name.index(link)]
            out.append(
                (
                    (p.position.x, p.position.y, p.position.z),
                    (p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w),
                )
            )
        return out

    def close(self) -> None:
        self._sub.unregister()


def one_try(
    g: grasp.Gripper,
    arm: Arm,
    gz: Gazebo,
    states: Any,
    a: argparse.Namespace,
    log: Progress,
) -> Dict[str, Any]:
    from geometry_msgs.msg import Point, Pose, Quaternion

    gz.remove(BOX)
    gz.remove(PEDESTAL)
    arm.grip(g.open_position, 1.5)
    arm.move(g.start, g.start, g.reach_s)  # reset: the start pose, fingers open
    fingers = [gz.pose('%s::%s' % (g.model, link))[0] for link in g.finger_links]
    _, palm_q = gz.pose('%s::%s' % (g.model, g.palm_link))
    centre, q = grasp.box_pose(fingers, palm_q, tuple(a.offset) if a.offset else g.offset)
    size = a.size or g.box_size
    bottom = centre[2] - size / 2
    if bottom > 0.002:
        pose = Pose(Point(centre[0], centre[1], bottom - 0.001), Quaternion(0, 0, 0, 1))
        r = gz.spawn_sdf(
            PEDESTAL, grasp.pedestal_sdf(PEDESTAL, size / 3, bottom - 0.001), '', pose, 'world'
        )
        if not r.success:
            raise RuntimeError('pedestal not spawned: %s' % r.status_message)
    pose = Pose(Point(*centre), Quaternion(*q))
    r = gz.spawn_urdf(BOX, grasp.box_urdf(BOX, size, a.mass, a.mu), '', pose, 'world')
    if not r.success:
        raise RuntimeError('box not spawned: %s' % r.status_message)
    log('  box %.0f mm at (%.3f, %.3f, %.3f)' % (size * 1e3, *centre))
    rospy.sleep(0.3)
    arm.grip(g.closed_position, 1.5)
    grasp_error = arm.last_grip_error
    # the column goes once the fingers hold the box: nothing but the gripper carries it, and
    # no finger or arm can jam against a static body through the lift
    gz.remove(PEDESTAL)
    rospy.sleep(0.5)
    palm = '%s::%s' % (g.model, g.palm_link)
    box = BOX + '::link'
    # palm and box from the same step, each time
    links = LinkStates(10.0)
    try:
        (palm_p, palm_q), (box_before, box_q0) = links.poses(palm, box)
        in_palm_closed = grasp.to_frame(palm_p, palm_q, box_before)
        arm.move(g.start, g.lifted(), 2.0)
        lift_goal = arm.last_move
        samples: List[tuple] = []
        fingers_seen: Dict[str, List[tuple]] = {}
        end = rospy.get_time() + grasp.HOLD_S
        while rospy.get_time() < end:
            (pp, pq), (bp, _) = links.poses(palm, box)
            samples.append(grasp.to_frame(pp, pq, bp))
            for j in g.finger_joints + g.follower_joints:
                fingers_seen.setdefault(j, []).append(
                    (states.positions.get(j, math.nan), states.velocities.get(j, math.nan))
                )
            rospy.sleep(0.1)
        (pp, pq), (box_after, box_q1) = links.poses(palm, box)
    finally:
        links.close()
    # the gripper's rise is the rise of the point where it gripped the box (the palm may
    # turn as the arm lifts: its origin's rise is not the fingers')
    w = grasp.rotate(pq, in_palm_closed)
    grip_after = (pp[0] + w[0], pp[1] + w[1], pp[2] + w[2])
    v = grasp.judge_lift(box_before, box_before, grip_after, box_after, samples)
    # where the box sat in the palm frame (closed, hold start, hold end) and how far it
    # turned: tells a slide along the pads from a swing about the grip axis
    seen: Dict[str, Any] = dict(
        box_in_palm_mm=[
            [round(c * 1e3, 1) for c in p]
            for p in (in_palm_closed, *samples[:: len(samples) - 1 or 1])
        ],
        fingers={
            j: 'q %.4f..%.4f, |v| up to %.3f'
            % (min(q for q, _ in qv), max(q for q, _ in qv), max(abs(w) for _, w in qv))
            for j, qv in fingers_seen.items()
        },
        box_turned_deg=round(grasp.angle_between(box_q0, box_q1) * 57.29578, 1),
    )
    if grasp_error:
        seen['grasp_error'] = grasp_error
    if lift_goal:
        seen['lift_goal'] = lift_goal
    arm.grip(g.open_position, 1.0)
    arm.move(g.lifted(), g.start, 2.0)
    gz.remove(BOX)
    gz.remove(PEDESTAL)
    return dict(
        v.as_dict(),
        text='%s; turned %.1f deg; box in palm (mm) %s%s%s'
        % (
            v,
            seen['box_turned_deg'],
            seen['box_in_palm_mm'],
            '; ' + grasp_error if grasp_error else '',
            '; lift goal ' + lift_goal if lift_goal else '',
        ),
        **seen,
    )


def wait_for_other_commands(g: grasp.Gripper, timeout: float, log: Progress) -> List[str]:
    """Wait, as the robot's user would, while another node still commands the arm or gripper
    (kinova-ros's launch homes the arm and closes the fingers with its move_robot.py for 5 s
    of sim time once the world runs; those commands replace a try's goals). Returns the nodes
    still publishing after ``timeout`` wall seconds."""
    import time

    from _arm1sim.tryout import probe

    topics = set(g.command_topics())
    me = rospy.get_name()
    end = time.monotonic() + timeout
    said: List[str] = []
    while True:
        pubs, _, _ = probe.system_state()
        others = sorted({n for t, nodes in pubs if t in topics for n in nodes if n != me})
        if not others or time.monotonic() > end:
            return others
        if others != said:
            log('waiting for %s to stop commanding the robot' % ', '.join(others))
            said = others
        time.sleep(0.5)


def tries(g: grasp.Gripper, a: argparse.Namespace, log: Progress) -> Dict[str, Any]:
    res: Dict[str, Any] = {'robot': g.name, 'tries': [], 'problems': []}
    try:
        gz = Gazebo(30.0)
        arm = Arm(g, 30.0)
        from _arm1sim.tryout.probe import JointStates

        states = JointStates()
        busy = wait_for_other_commands(g, 60.0, log)
        if busy:  # a node that keeps publishing (and may send nothing): noted, not failed
            res['still_commanding'] = busy
            log('%s still publish on its command topics after 60 s: going ahead' % busy)
    except Exception as e:
        res['problems'].append(str(e))
        res['ok'] = False
        return res
    for k in range(a.tries):
        log('try %d of %d' % (k + 1, a.tries))
        t: Optional[Dict[str, Any]]
        try:
            t = one_try(g, arm, gz, states, a, log)
        except Exception as e:
            t = {'ok': False, 'text': 'ERROR: %s' % e}
        log('  ' + t['text'])
        if t.get('fingers'):
            log('  fingers through the hold: %s' % t['fingers'])
        res['tries'].append(t)
    ok = sum(1 for t in res['tries'] if t.get('ok'))
    res['summary'] = '%s: %d of %d lifted' % (g.name, ok, a.tries)
    res['ok'] = ok == a.tries
    res['lines'] = ['try %d: %s' % (i + 1, t['text']) for i, t in enumerate(res['tries'])]
    res['lines'].append(res['summary'])
    return res
