"""trajectory_demo: one FollowJointTrajectory goal to arm1's arm_controller, result printed.

Run against `roslaunch arm1 gazebo.launch controllers:=trajectory`. The goal is what
MoveIt sends: header stamp 0 (start at the controller's next update), every joint named.
"""

from __future__ import annotations

import argparse
import sys
from typing import List, Optional, Sequence

import actionlib
import rospy
from actionlib_msgs.msg import GoalStatus
from control_msgs.msg import FollowJointTrajectoryAction, FollowJointTrajectoryGoal
from trajectory_msgs.msg import JointTrajectoryPoint

from ...control.joint_trajectory_controller import ERROR_CODE_NAMES

JOINTS = ['joint1', 'joint2', 'joint3', 'joint4']
# (seconds from start, positions): out to one side, to the other, back up.
WAYPOINTS = [
    (2.0, [0.6, 0.8, 0.4, 0.3]),
    (4.0, [-0.6, 0.5, 0.2, -0.2]),
    (6.0, [0.0, 1.0, 0.0, 0.0]),
]
STATES = {v: k for k, v in vars(GoalStatus).items() if k.isupper() and isinstance(v, int)}


def make_goal(
    waypoints: Sequence = WAYPOINTS, joints: Sequence[str] = JOINTS
) -> FollowJointTrajectoryGoal:
    goal = FollowJointTrajectoryGoal()
    goal.trajectory.joint_names = list(joints)
    for t, positions in waypoints:
        point = JointTrajectoryPoint(positions=list(positions))
        point.time_from_start = rospy.Duration.from_sec(t)
        goal.trajectory.points.append(point)
    return goal


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--action', default='/arm1/arm_controller/follow_joint_trajectory')
    parser.add_argument('--timeout', type=float, default=60.0, help='wall seconds to wait')
    args = parser.parse_args(rospy.myargv(argv if argv is not None else sys.argv)[1:])
    rospy.init_node('trajectory_demo', anonymous=True)
    client = actionlib.SimpleActionClient(args.action, FollowJointTrajectoryAction)
    if not client.wait_for_server(rospy.Duration(args.timeout)):
        print(
            'trajectory_demo: no action server at %s (is gazebo.launch running with '
            'controllers:=trajectory?)' % args.action,
            file=sys.stderr,
        )
        return 2
    goal = make_goal()
    for t, positions in WAYPOINTS:
        print('  t=%.1f s  %s' % (t, ', '.join('%s=%.2f' % jp for jp in zip(JOINTS, positions))))
    client.send_goal(goal)
    if not client.wait_for_result(rospy.Duration(WAYPOINTS[-1][0] + args.timeout)):
        client.cancel_goal()
        print('trajectory_demo: no result in time; goal cancelled', file=sys.stderr)
        return 1
    state, result = client.get_state(), client.get_result()
    code = result.error_code if result is not None else None
    print(
        'state: %s  error_code: %s (%s)  error_string: %r'
        % (
            STATES.get(state, state),
            code,
            ERROR_CODE_NAMES.get(code, '?') if code is not None else '-',
            result.error_string if result is not None else '',
        )
    )
    return 0 if state == GoalStatus.SUCCEEDED else 1
