"""arm_mover: simple_arm's ``safe_move`` service for arm1's four joints.

``/arm_mover/safe_move`` (arm1/GoToPosition) clamps each requested angle into
``[~min_<joint>_angle, ~max_<joint>_angle]`` (default: the URDF limits of
``robot_description``), warning when it had to, publishes the angles to the
joints' position controllers and answers once every joint is within
``~tolerance`` (0.05 rad) of its target, with the time that took (joint-state
stamp minus request time). Unlike simple_arm it never waits forever: after
``~timeout`` seconds (ROS time, 10 s) -- or when no joint state has arrived for
that long in wall time (physics paused, controller stopped) -- it answers with a
service error naming the joints that did not arrive and where they are.
One move at a time: a second request waits for the first to finish.
"""

import math
import threading
import time

import rospy
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64

from arm1.srv import GoToPosition, GoToPositionResponse

from ...description.urdf_model import UrdfError
from ...goal.arm_mover import clamp_request, describe, joint_limits, off_target

JOINTS = ('joint1', 'joint2', 'joint3', 'joint4')  # the fields of GoToPosition


class ArmMover:
    def __init__(self):
        ns = rospy.get_param('~robot_namespace', '/arm1').rstrip('/')
        self.joint_states_topic = ns + '/joint_states'
        limits = self._urdf_limits()
        self.ranges = {}
        for j in JOINTS:
            lower, upper = limits.get(j, (-math.pi, math.pi))
            self.ranges[j] = (
                float(rospy.get_param('~min_%s_angle' % j, lower)),
                float(rospy.get_param('~max_%s_angle' % j, upper)),
            )
            if not self.ranges[j][0] <= self.ranges[j][1]:
                raise ValueError(
                    '~min_%s_angle %g is above ~max_%s_angle %g'
                    % (j, self.ranges[j][0], j, self.ranges[j][1])
                )
        self.tolerance = float(rospy.get_param('~tolerance', 0.05))
        self.timeout = float(rospy.get_param('~timeout', 10.0))
        self._commands = {
            j: rospy.Publisher(
                '%s/%s_position_controller/command' % (ns, j), Float64, queue_size=10
            )
            for j in JOINTS
        }
        self._state = None  # last JointState
        self._state_wall = time.monotonic()
        self._new_state = threading.Condition()
        self._one_move = threading.Lock()
        self._sub = rospy.Subscriber(
            self.joint_states_topic, JointState, self._on_state, queue_size=1
        )
        self._service = rospy.Service('~safe_move', GoToPosition, self.safe_move)
        rospy.loginfo(
            'arm_mover: ranges %s, tolerance %g rad, timeout %g s',
            ', '.join('%s [%.2f, %.2f]' % (j, *self.ranges[j]) for j in JOINTS),
            self.tolerance,
            self.timeout,
        )

    @staticmethod
    def _urdf_limits():
        try:
            return joint_limits(rospy.get_param('robot_description'))
        except KeyError:
            rospy.logwarn('arm_mover: no robot_description: joint ranges default to [-pi, pi]')
        except UrdfError as exc:
            rospy.logwarn(
                'arm_mover: robot_description unusable (%s): joint ranges default to [-pi, pi]', exc
            )
        return {}

    def _on_state(self, msg):
        with self._new_state:
            self._state, self._state_wall = msg, time.monotonic()
            self._new_state.notify_all()

    def safe_move(self, req):
        try:
            targets, warnings = clamp_request({j: getattr(req, j) for j in JOINTS}, self.ranges)
        except ValueError as exc:
            self._fail(str(exc))
        for w in warnings:
            rospy.logwarn('safe_move: %s', w)
        with self._one_move:
            start = rospy.Time.now()
            for j in JOINTS:
                self._commands[j].publish(targets[j])
            msg = self._wait_until_there(start, targets)
        elapsed = msg.header.stamp - start
        rospy.loginfo(
            'safe_move: at (%s) after %.2f s',
            ', '.join('%.2f' % targets[j] for j in JOINTS),
            elapsed.to_sec(),
        )
        return GoToPositionResponse(elapsed)

    def _wait_until_there(self, start, targets):
        """The first joint state since ``start`` with every joint on target; raises on timeout."""
        deadline = start + rospy.Duration.from_sec(self.timeout)
        asked = time.monotonic()
        with self._new_state:
            while not rospy.is_shutdown():
                msg = self._state
                if msg is not None and msg.header.stamp >= start:
                    positions = dict(zip(msg.name, msg.position))
                    off = off_target(positions, targets, self.tolerance)
                    if not off:
                        return msg
                    if msg.header.stamp > deadline:
                        self._fail(
                            'not there after %g s: %s (tolerance %g rad)'
                            % (self.timeout, describe(off, positions, targets), self.tolerance)
                        )
                if time.monotonic() - max(self._state_wall, asked) > self.timeout:
                    self._fail(
                        'no message on %s for %g s (physics paused? joint_state_controller '
                        'not running?)' % (self.joint_states_topic, self.timeout)
                    )
                self._new_state.wait(0.2)
        self._fail('shutting down')

    @staticmethod
    def _fail(text):
        rospy.logerr('safe_move: %s', text)
        raise rospy.ServiceException('safe_move: %s' % text)


def main(argv=None):
    rospy.init_node('arm_mover')
    try:
        ArmMover()
    except ValueError as exc:
        rospy.logfatal('arm_mover: %s', exc)
        return 1
    rospy.spin()
