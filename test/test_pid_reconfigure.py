#!/usr/bin/env python
"""Live gains and the controller state topic, under gazebo.launch and in-process.

- ``<controller>/state`` (control_msgs/JointControllerState) comes every 10th
  update (100 Hz of sim time) and its fields are the controller's: error = set_point -
  process_value, process_value = the joint_states position, command = the PID's effort,
  p/i/d/i_clamp/antiwindup = the gains in force.
- a dynamic_reconfigure change at ``<controller>/pid`` (client and ``dynparam set``)
  reaches the controller at its next update, shows in the state topic and on the
  parameter server, and the arm keeps moving.
"""

import os
import subprocess
import sys
import time

import rospy
import rostest
from control_msgs.msg import JointControllerState
from dynamic_reconfigure.client import Client
from std_msgs.msg import Float64

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rostest_util import Recorder, WorldTestCase, joint_recorder, positions, sim_wait, wait_for  # noqa: E402

from _arm1sim.control.hardware_interface import JointHandle, JointLimits  # noqa: E402
from _arm1sim.control.joint_position_controller import JointPositionController  # noqa: E402
from _arm1sim.ros.control.node_handle import RosNodeHandle  # noqa: E402

NS = '/arm1/joint1_position_controller'


class OneJointHw:
    """The smallest robot_hw: one effort joint, positions set by the test."""

    def __init__(self):
        self.handle = JointHandle('j', 'revolute', JointLimits(-2.0, 2.0, 10.0, 10.0))

    def get_handle(self, name, interface, ns):
        return self.handle


class Reconfigure(WorldTestCase):
    NODE = 'test_pid_reconfigure'
    CONTROLLERS = 5

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.states = Recorder(NS + '/state', JointControllerState)
        cls.joints = joint_recorder()
        cls.cmd = rospy.Publisher(NS + '/command', Float64, queue_size=1, latch=True)
        rospy.wait_for_service(NS + '/pid/set_parameters', 30)

    def recent_states(self, since, n):
        assert wait_for(lambda: len(self.states.since(since)) >= n, 30), 'no state messages'
        return self.states.since(since)

    def test_01_state_topic_matches_the_controller(self):
        start = time.monotonic()
        msgs = self.recent_states(start, 50)
        stamps = [m.header.stamp.to_sec() for m in msgs]
        gaps = [b - a for a, b in zip(stamps, stamps[1:])]
        self.assertAlmostEqual(
            sorted(gaps)[len(gaps) // 2], 0.01, delta=1e-6, msg='state every 10th update of 1 ms'
        )
        pid = rospy.get_param(NS + '/pid')
        joint_states = self.joints.since(start - 1.0)
        for m in msgs:
            self.assertAlmostEqual(m.time_step, 0.001, places=9)
            self.assertAlmostEqual(m.error, m.set_point - m.process_value, places=9)
            self.assertEqual((m.p, m.i, m.d), (pid['p'], pid['i'], pid['d']))
            self.assertEqual(m.i_clamp, pid['i_clamp_max'])
            self.assertEqual(m.antiwindup, pid['antiwindup'])
            self.assertLessEqual(abs(m.command), 1e6)
        # process_value is the joint's position: joint_states (50 Hz) interpolated at the stamp
        js = [(m.header.stamp.to_sec(), positions(m)['joint1']) for m in joint_states]
        checked = 0
        for m in msgs:
            t = m.header.stamp.to_sec()
            around = [(a, b) for a, b in zip(js, js[1:]) if a[0] <= t <= b[0]]
            if not around:
                continue
            (t0, x0), (t1, x1) = around[0]
            x = x0 if t1 == t0 else x0 + (x1 - x0) * (t - t0) / (t1 - t0)
            self.assertAlmostEqual(m.process_value, x, delta=2e-3)
            checked += 1
        self.assertGreater(checked, 10, 'no state between two joint_states')

    def test_02_dynamic_reconfigure_changes_the_running_controller(self):
        client = Client(NS + '/pid', timeout=30)
        self.cmd.publish(0.4)
        sim_wait(0.5)
        client.update_configuration({'p': 2.0, 'i': 0.0, 'd': 0.0})
        start = time.monotonic()
        assert wait_for(lambda: any(m.p == 2.0 for m in self.states.since(start)), 30)
        first = next(m for m in self.states.since(start) if m.p == 2.0)
        # with i = d = 0 the effort is exactly p * error
        self.assertAlmostEqual(first.command, 2.0 * first.error, places=9)
        self.assertEqual((first.i, first.d), (0.0, 0.0))
        self.assertEqual(rospy.get_param(NS + '/pid/p'), 2.0)
        self.assertEqual(rospy.get_param(NS + '/pid/d'), 0.0)
        # the arm keeps moving under the new gains, no restart
        self.cmd.publish(-0.3)
        self.assertTrue(
            wait_for(lambda: abs(positions(self.joints.last())['joint1'] + 0.3) < 0.05, 30),
            'joint1 did not follow after the gain change',
        )

    def test_03_dynparam_set_from_the_command_line(self):
        out = subprocess.run(
            ['rosrun', 'dynamic_reconfigure', 'dynparam', 'set', NS + '/pid', 'p', '3.0'],
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            timeout=60,
        )
        self.assertEqual(out.returncode, 0, out.stdout)
        start = time.monotonic()
        self.assertTrue(wait_for(lambda: any(m.p == 3.0 for m in self.states.since(start)), 30))
        self.assertEqual(rospy.get_param(NS + '/pid/p'), 3.0)
        # out-of-range values are clamped to control_toolbox's ranges
        Client(NS + '/pid', timeout=30).update_configuration({'d': 5000.0, 'i_clamp_min': 1.0})
        self.assertEqual(rospy.get_param(NS + '/pid/d'), 1000.0)
        self.assertEqual(rospy.get_param(NS + '/pid/i_clamp_min'), 0.0)
        Client(NS + '/pid', timeout=30).update_configuration({'d': 0.002})

    def test_04_a_change_applies_at_the_next_update_exactly(self):
        """In-process: a controller with the ROS node handle and a real server."""
        rospy.set_param(
            '/reconf_test/c',
            {'type': JointPositionController.type_name, 'joint': 'j', 'pid': {'p': 1.0, 'd': 0.0}},
        )
        hw = OneJointHw()
        c = JointPositionController()
        c.name = 'c'
        nh = RosNodeHandle('/reconf_test/c')
        c.init(hw, RosNodeHandle('/reconf_test'), nh)
        try:
            c.start_request(0)
            c.target = 0.5
            c.update(0, 1000000)
            self.assertAlmostEqual(hw.handle.command, 0.5)
            self.assertEqual(rospy.get_param('/reconf_test/c/pid/i_clamp_max'), 0.0)
            Client('/reconf_test/c/pid', timeout=10).update_configuration({'p': 4.0})
            self.assertAlmostEqual(hw.handle.command, 0.5)  # not before the update
            c.update(1000000, 1000000)
            self.assertAlmostEqual(hw.handle.command, 2.0)  # 4.0 * 0.5, at the next update
            self.assertEqual(c.pid.p, 4.0)
        finally:
            nh.shutdown()


if __name__ == '__main__':
    rostest.rosrun('arm1', 'pid_reconfigure', Reconfigure)
