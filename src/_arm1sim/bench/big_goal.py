"""A 100 000-point FollowJointTrajectory goal against the real launch at real time (issue 22,
case 1): the longest /clock gap and the real-time factor while the world receives it, next to
the same window before it. The goal is sent by another process (``big_goal_client``), so its
Python work does not delay this probe's /clock recorder."""

from __future__ import annotations

import subprocess
import sys
import time
from typing import Any, Dict

from .launched import WINDOW, clock_pace, launch_and_wait, record_clock

ACTION = '/arm1/arm_controller/follow_joint_trajectory'
JOINTS = ('joint1', 'joint2', 'joint3', 'joint4')
START = (0.0, 0.5, 0.3, 0.2)  # rad: the pose every point holds


def big_goal(count: int) -> Dict[str, Any]:
    import rospy

    from ..session.launcher import RosSession

    session = RosSession()
    session.activate()
    with session:
        launch_and_wait(session, 'controllers:=trajectory')
        clock = record_clock()
        rospy.wait_for_message(ACTION + '/status', rospy.AnyMsg, timeout=60)
        time.sleep(2.0)
        before = time.perf_counter()
        time.sleep(WINDOW)
        during = time.perf_counter()
        client = subprocess.Popen(
            [
                sys.executable,
                '-m',
                '_arm1sim.bench.workers',
                'big_goal_client',
                '--count',
                str(count),
            ]
        )
        time.sleep(WINDOW)
        client.wait(120)
        gap_during, rtf_during = clock_pace([m for m in clock if m[0] < during + WINDOW], during)
        gap_before, rtf_before = clock_pace([m for m in clock if m[0] < during], before)
        rospy.signal_shutdown('measured')
    return {
        'points': count,
        'gap_before_ms': gap_before * 1e3,
        'rtf_before': rtf_before,
        'gap_ms': gap_during * 1e3,
        'rtf': rtf_during,
    }


def big_goal_client(count: int) -> None:
    """Sends one goal of ``count`` points, a millisecond apart, each holding START."""
    import actionlib
    import rospy
    from control_msgs.msg import FollowJointTrajectoryAction, FollowJointTrajectoryGoal
    from trajectory_msgs.msg import JointTrajectoryPoint

    rospy.init_node('bench_big_goal', anonymous=True)
    client = actionlib.SimpleActionClient(ACTION, FollowJointTrajectoryAction)
    if not client.wait_for_server(rospy.Duration(60)):
        raise RuntimeError('no action server ' + ACTION)
    goal = FollowJointTrajectoryGoal()
    goal.trajectory.joint_names = list(JOINTS)
    goal.trajectory.points = [
        JointTrajectoryPoint(positions=list(START), time_from_start=rospy.Duration(0, k * 1000000))
        for k in range(1, count + 1)
    ]
    client.send_goal(goal)
    time.sleep(0.5)
