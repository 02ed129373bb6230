#!/usr/bin/env python
"""Faults, third round, against gazebo.launch controllers:=trajectory: a 100 000-point
FollowJointTrajectory goal, a goal storm and a cancel storm leave /clock at real time (no
gap, real-time factor held), the action's status list stays bounded and the cancel path
logs no actionlib errors; set_physics_properties' max_update_rate 0.1 does not hold the next
service answer for its 10 s period.

The machine may be busy (2 cores shared with other tests): each case is judged against the
pace the world kept just before it, in a window of the same test: the real-time factor
during the case at least MIN_RTF_RATIO of that baseline's, the longest /clock gap at most
GAP_MARGIN longer than the baseline's. The figures are printed; docs/faults.md ("Third
round") states the bounds on an idle machine (real-time factor 0.97, gaps under 0.1 s).
"""

import os
import subprocess
import sys
import time
import uuid

import actionlib
import rospy
import rostest
from actionlib_msgs.msg import GoalID, GoalStatus, GoalStatusArray
from control_msgs.msg import (
    FollowJointTrajectoryAction,
    FollowJointTrajectoryActionGoal,
    FollowJointTrajectoryGoal,
)
from gazebo_msgs.srv import GetPhysicsProperties, SetPhysicsProperties
from trajectory_msgs.msg import JointTrajectoryPoint

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from faults_util import ClockWindow  # noqa: E402
from rostest_util import JOINTS, Recorder, WorldTestCase, positions, sim_wait, wait_for  # noqa: E402

from _arm1sim.ros.common.publishers import synchronous_publisher  # noqa: E402

ACTION = '/arm1/arm_controller/follow_joint_trajectory'
GAP_MARGIN = 0.5  # wall s a /clock gap (100 Hz of sim time) may exceed the baseline's longest
BIG_GOAL_GAP_MARGIN = 1.0  # the same while the world decodes a 100 000-point goal
MIN_RTF_RATIO = 0.5  # of the baseline's real-time factor, over a case's window (old: ~0.05)
HELD_ANSWER_S = 2.0  # wall s: answered in ms even with both cores busy; held, 9.5 s
BASELINE = 2.0  # sim s of the baseline window
CLIENT = '--hostile-client'
MAX_STATUS = 110  # entries of one status message: MAX_FINISHED (100) + the live ones


def goal_msg(points, start, seconds_per_point):
    goal = FollowJointTrajectoryGoal()
    goal.trajectory.joint_names = list(JOINTS)
    for k in range(points):
        point = JointTrajectoryPoint(positions=list(start))
        point.time_from_start = rospy.Duration.from_sec((k + 1) * seconds_per_point)
        goal.trajectory.points.append(point)
    return goal


def client_main(kind, count, seconds):
    """A hostile client in a process of its own (so that its Python work does not delay this
    test's /clock recorder): ``big`` sends one goal of ``count`` points, ``goals`` and
    ``cancels`` send ``count`` goals or cancels spread over ``seconds``."""
    rospy.init_node('faults_trajectory_client', anonymous=True)
    start = [0.0, 0.5, 0.3, 0.2]
    if kind == 'big':
        client = actionlib.SimpleActionClient(ACTION, FollowJointTrajectoryAction)
        client.wait_for_server(rospy.Duration(60))
        client.send_goal(goal_msg(count, start, 0.001))
        print('sent', flush=True)
        rospy.sleep(0.5)
        return
    topic, cls = (
        (ACTION + '/goal', FollowJointTrajectoryActionGoal)
        if kind == 'goals'
        else (ACTION + '/cancel', GoalID)
    )
    pub = synchronous_publisher(topic, cls)
    wait_for(lambda: pub.get_num_connections() > 0, 10)
    time.sleep(0.5)
    mark = time.monotonic()
    for k in range(count):
        if kind == 'goals':
            msg = FollowJointTrajectoryActionGoal()
            msg.goal_id.id = 'storm-%d-%s' % (k, uuid.uuid4().hex)
            msg.goal = goal_msg(2, start, 0.5)
        else:  # unknown ids (each twice), and every tenth a cancel of everything
            msg = GoalID(id='ghost-%d' % (k // 2)) if k % 10 else GoalID()
        pub.publish(msg)
        time.sleep(max(0.0, mark + (k + 1) * seconds / count - time.monotonic()))
    print('sent', flush=True)


def run_client(kind, count, seconds=5.0):
    out = subprocess.run(
        [sys.executable, os.path.abspath(__file__), CLIENT, kind, str(count), str(seconds)],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        timeout=120,
    ).stdout.decode(errors='replace')
    assert 'sent' in out, out[-2000:]


class FaultsTrajectory(WorldTestCase):
    NODE = 'test_faults_trajectory'
    RECORD = ('states', 'clock', 'rosout')
    FIRST = ('states', 'clock')
    CONTROLLERS = 2

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.client = actionlib.SimpleActionClient(ACTION, FollowJointTrajectoryAction)
        assert cls.client.wait_for_server(rospy.Duration(60)), 'no action server ' + ACTION
        cls.status = Recorder(ACTION + '/status', GoalStatusArray)
        cls.window = ClockWindow(cls.clock)

    def here(self):
        p = positions(self.states.last())
        return [p[j] for j in JOINTS]

    def baseline(self):
        """The pace just before a case: (longest /clock gap, real-time factor)."""
        self.window.start()
        sim_wait(BASELINE)
        self.base = self.window.stop()
        self.window.start()

    def assert_pace(self, what, gap, rtf, gap_margin=GAP_MARGIN):
        base_gap, base_rtf = self.base
        print(
            '%s: max /clock gap %.3f s, real-time factor %.3f (just before: %.3f s, %.3f)'
            % (what, gap, rtf, base_gap, base_rtf)
        )
        self.assertLess(
            gap,
            base_gap + gap_margin,
            '%s: /clock stopped for %.3f s (%.3f s before)' % (what, gap, base_gap),
        )
        self.assertGreater(
            rtf,
            MIN_RTF_RATIO * base_rtf,
            '%s: real-time factor %.3f (%.3f before)' % (what, rtf, base_rtf),
        )

    def cancel_if_running(self):
        if self.client.get_state() in (GoalStatus.PENDING, GoalStatus.ACTIVE):
            self.client.cancel_goal()

    def assert_arm_still_obeys(self):
        self.client.send_goal(goal_msg(1, self.here(), 0.5))
        self.assertTrue(self.client.wait_for_result(rospy.Duration(60)), 'no result')
        self.assertEqual(self.client.get_state(), GoalStatus.SUCCEEDED)

    def test_a_100000_point_goal_keeps_the_clock_at_real_time(self):
        # a failed case leaves no 100 s goal. Its own goal by id, not cancel-everything: that
        # travels on /cancel, the next case's goal on /goal, and arriving after it (seen under
        # load) it cancelled the next case's goal before it ever went ACTIVE
        self.addCleanup(self.cancel_if_running)
        self.baseline()
        mark = time.monotonic()
        run_client('big', 100000)
        big = [m for m in self.status.since(mark) if any(s.status for s in m.status_list)]
        active = wait_for(
            lambda: any(
                s.status == GoalStatus.ACTIVE
                for m in self.status.since(mark)
                for s in m.status_list
            ),
            60,
        )
        sim_wait(2.0)
        gap, rtf = self.window.stop()
        self.assertTrue(active or big, 'the goal was not accepted')
        # Receiving 100 000 points is ~1 s of Python in the world's process: the world's short
        # switch interval and rare full collections keep /clock going (docs/faults.md); 40 ms
        # on an idle machine, up to 0.56 s with one core busy, 2.4 s before.
        self.assert_pace('100 000-point goal', gap, rtf, BIG_GOAL_GAP_MARGIN)
        self.assert_arm_still_obeys()  # preempts it

    def test_a_storm_of_1000_goals_in_5_s_keeps_the_clock_and_bounds_the_status_list(self):
        self.baseline()
        mark = time.monotonic()
        run_client('goals', 1000)
        sim_wait(1.0)
        gap, rtf = self.window.stop()
        self.assert_pace('1 000 goals in 5 s', gap, rtf)
        longest = max(len(m.status_list) for m in self.status.since(mark))
        print('longest status message in the storm: %d entries' % longest)
        self.assertLessEqual(longest, MAX_STATUS)
        self.assert_arm_still_obeys()

    def test_a_cancel_storm_logs_no_actionlib_error_and_keeps_the_clock(self):
        self.client.send_goal(goal_msg(1, self.here(), 30.0))
        self.assertTrue(wait_for(lambda: self.client.get_state() == GoalStatus.ACTIVE, 120))
        self.baseline()
        mark = time.monotonic()
        run_client('cancels', 1000)
        sim_wait(1.0)
        gap, rtf = self.window.stop()
        self.assert_pace('1 000 cancels in 5 s', gap, rtf)
        said = [m.msg for m in self.rosout.since(mark) if 'uninitialized' in m.msg]
        self.assertEqual(said, [], 'actionlib errors in the world log')
        longest = max(len(m.status_list) for m in self.status.since(mark))
        print('longest status message in the cancel storm: %d entries' % longest)
        self.assertLessEqual(longest, MAX_STATUS)
        self.assertTrue(wait_for(lambda: self.client.get_state() == GoalStatus.PREEMPTED, 30))
        # a goal sent now is not taken for one stamped before the last cancel-everything
        self.assert_arm_still_obeys()

    def test_a_goal_past_joint2s_limit_leaves_no_chatter_and_the_next_goal_succeeds(self):
        mark = time.monotonic()
        here = self.here()
        past = list(here)
        past[1] = 2.5  # joint2's upper limit is 1.57
        self.client.send_goal(goal_msg(1, past, 1.0))
        self.assertTrue(self.client.wait_for_result(rospy.Duration(60)), 'no result')
        print('goal past the limit: state %d' % self.client.get_state())
        self.assertIn(self.client.get_state(), (GoalStatus.ABORTED, GoalStatus.SUCCEEDED))
        self.client.send_goal(goal_msg(1, here, 1.0))
        self.assertTrue(self.client.wait_for_result(rospy.Duration(60)), 'no result')
        self.assertEqual(
            self.client.get_state(), GoalStatus.SUCCEEDED, self.client.get_result().error_string
        )
        said = [m.msg for m in self.rosout.since(mark) if 'velocity-limit chatter' in m.msg]
        self.assertEqual(said, [], 'the default launch fell into the limit chatter')

    def test_a_slow_max_update_rate_does_not_hold_the_next_service_answer(self):
        get = rospy.ServiceProxy('/gazebo/get_physics_properties', GetPhysicsProperties)
        set_ = rospy.ServiceProxy('/gazebo/set_physics_properties', SetPhysicsProperties)
        before = get()

        def set_rate(rate):
            t = time.monotonic()
            ok = set_(before.time_step, rate, before.gravity, before.ode_config).success
            return ok, time.monotonic() - t

        ok, _ = set_rate(0.1)  # one step per 10 s
        self.assertTrue(ok)
        try:
            time.sleep(0.5)  # the world is in its 10 s wait now
            t = time.monotonic()
            props = get()
            first = time.monotonic() - t
            self.assertAlmostEqual(props.max_update_rate, 0.1)
        finally:
            ok, back = set_rate(before.max_update_rate)
        print('answers in a 10 s step: get %.3f s, set back %.3f s' % (first, back))
        self.assertTrue(ok)
        # Only an answer held by the step fails (3-73 ms on a quiet machine, docs/faults.md).
        self.assertLess(first, HELD_ANSWER_S)
        self.assertLess(back, HELD_ANSWER_S)
        stamp = self.clock.last().clock.to_sec()
        self.assertTrue(wait_for(lambda: self.clock.last().clock.to_sec() > stamp + 0.2, 60))


if __name__ == '__main__':
    if len(sys.argv) > 4 and sys.argv[1] == CLIENT:
        client_main(sys.argv[2], int(sys.argv[3]), float(sys.argv[4]))
    else:
        rostest.rosrun('arm1', 'faults_trajectory', FaultsTrajectory)
