"""look_away: simple_arm's node for arm1. When the camera sees nothing but a blank
(uniform) view and the arm is still, it calls ``/arm_mover/safe_move`` with
``~pose`` to point the camera elsewhere, and waits for the result before it
reacts again.

Still: every joint moved less than ``~still_threshold`` (0.0005 rad) since the
previous ``<robot_namespace>/joint_states`` message. Uniform: every pixel
equals the first one (see image.is_uniform).
"""

import rospy
from sensor_msgs.msg import Image, JointState

from arm1.srv import GoToPosition

from ...goal.image import is_uniform
from ...goal.look_away import LookAwayPolicy

# Camera along the arm, pitched 0.2 rad down: the horizon in the upper third.
DEFAULT_POSE = [0.0, 0.6, -0.4, -0.4]
RETRY_AFTER = 1.0  # s of ROS time before trying again after safe_move failed


class LookAway:
    def __init__(self):
        ns = rospy.get_param('~robot_namespace', '/arm1').rstrip('/')
        self.pose = [float(v) for v in rospy.get_param('~pose', DEFAULT_POSE)]
        if len(self.pose) != 4:
            raise ValueError('~pose must be 4 angles (joint1..joint4), got %r' % (self.pose,))
        self.policy = LookAwayPolicy(float(rospy.get_param('~still_threshold', 0.0005)))
        self._safe_move = rospy.ServiceProxy('/arm_mover/safe_move', GoToPosition)
        self._not_before = rospy.Time(0)  # images taken before the last move ended are stale
        self._subs = [
            rospy.Subscriber(
                ns + '/joint_states',
                JointState,
                lambda m: self.policy.joint_positions(m.position),
                queue_size=1,
            ),
            rospy.Subscriber(
                'rgb_camera/image_raw', Image, self._on_image, queue_size=1, buff_size=1 << 24
            ),
        ]

    def _on_image(self, img):
        if img.header.stamp < self._not_before:
            return
        if not self.policy.decide(is_uniform(img.data, img.width, img.height, img.step)):
            return
        rospy.loginfo('look_away: uniform image and the arm is still: safe_move to %s', self.pose)
        retry = rospy.Duration(0)
        try:
            resp = self._safe_move(*self.pose)
            rospy.loginfo('look_away: moved in %.2f s', resp.time_elapsed.to_sec())
        except (rospy.ServiceException, rospy.ROSException) as exc:
            rospy.logwarn('look_away: safe_move failed: %s', exc)
            retry = rospy.Duration.from_sec(RETRY_AFTER)
        finally:
            self._not_before = rospy.Time.now() + retry
            self.policy.done()


def main(argv=None):
    rospy.init_node('look_away')
    try:
        LookAway()
    except (TypeError, ValueError) as exc:
        rospy.logfatal('look_away: %s', exc)
        return 1
    rospy.spin()
