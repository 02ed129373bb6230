#!/usr/bin/env python
"""A robot with position- and velocity-interface joints (test/config/iface_bot.urdf) under a
real master: the forward controllers command them, the hardware sets or drives them."""

import os
import sys

import rospy
import rostest
from controller_manager_msgs.srv import SwitchController
from std_msgs.msg import Float64, Float64MultiArray

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rostest_util import Recorder, WorldTestCase, wait_for, wait_for_controllers  # noqa: E402
from sensor_msgs.msg import JointState  # noqa: E402

NS = '/iface_bot'
TOL = 0.02  # rad


def by_name(msg, field):
    return dict(zip(msg.name, getattr(msg, field)))


class Interfaces(WorldTestCase):
    NODE = 'test_interfaces'
    RECORD = ('rosout',)

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.states = Recorder(NS + '/joint_states', JointState)
        cls.list_controllers = wait_for_controllers(4, NS)
        assert wait_for(
            lambda: any(c.name == 'group_controller' for c in cls.list_controllers().controller),
            60,
        ), 'group_controller not loaded'
        cls.pub = {
            c: rospy.Publisher('%s/%s/command' % (NS, c), Float64, queue_size=1, latch=True)
            for c in ('pos_controller', 'vel_controller', 'pid_controller')
        }
        cls.group = rospy.Publisher(
            NS + '/group_controller/command', Float64MultiArray, queue_size=1, latch=True
        )
        assert wait_for(lambda: cls.states.last() is not None, 60), 'no joint_states'

    def settled(self, field, joint, target, tol=TOL, timeout=30, span=0.5):
        """True once ``field`` of ``joint`` has stayed within tol of target for ``span`` s
        of sim time (joint_states at 50 Hz)."""

        def ok():
            recent = self.states.last_sim_seconds(span)
            return len(recent) >= 10 and all(
                abs(by_name(m, field)[joint] - target) <= tol for m in recent
            )

        return wait_for(ok, timeout)

    def last(self, field):
        return by_name(self.states.last(), field)

    def test_1_controllers_claim_their_interfaces(self):
        claimed = {
            c.name: (
                c.state,
                [(r.hardware_interface, list(r.resources)) for r in c.claimed_resources],
            )
            for c in self.list_controllers().controller
        }
        self.assertEqual(claimed['pos_controller'][0], 'running')
        # As upstream: the C++ type name, and the joints sorted (a std::set).
        self.assertEqual(
            claimed['pos_controller'][1][0][0], 'hardware_interface::PositionJointInterface'
        )
        self.assertIn('VelocityJointInterface', claimed['vel_controller'][1][0][0])
        self.assertEqual(claimed['group_controller'][0], 'initialized')  # loaded --stopped
        [(interface, resources)] = claimed['group_controller'][1]
        self.assertIn('PositionJointInterface', interface)
        self.assertEqual(resources, ['pid_joint', 'pos_joint'])
        self.assertEqual(sorted(self.states.last().name), ['pid_joint', 'pos_joint', 'vel_joint'])

    def test_2_position_joints_reach_their_commands(self):
        self.pub['pos_controller'].publish(1.2)
        self.pub['pid_controller'].publish(0.6)
        self.assertTrue(self.settled('position', 'pos_joint', 1.2), self.last('position'))
        self.assertTrue(self.settled('position', 'pid_joint', 0.6), self.last('position'))
        # set directly: no effort; through the hardware's PID: effort holds the arm up
        self.assertEqual(self.last('effort')['pos_joint'], 0.0)
        self.assertGreater(abs(self.last('effort')['pid_joint']), 0.05)
        self.pub['pos_controller'].publish(-0.5)
        self.assertTrue(self.settled('position', 'pos_joint', -0.5), self.last('position'))

    def test_3_velocity_joint_holds_its_velocity(self):
        self.pub['vel_controller'].publish(3.0)
        self.assertTrue(self.settled('velocity', 'vel_joint', 3.0, 0.1), self.last('velocity'))
        self.pub['vel_controller'].publish(-1.5)
        self.assertTrue(self.settled('velocity', 'vel_joint', -1.5, 0.1), self.last('velocity'))
        # beyond the velocity limit (the URDF's 5, overridden by joint_limits/vel_joint to 4):
        # turns at the limit
        self.pub['vel_controller'].publish(40.0)
        self.assertTrue(self.settled('velocity', 'vel_joint', 4.0, 0.1), self.last('velocity'))
        self.pub['vel_controller'].publish(0.0)
        self.assertTrue(self.settled('velocity', 'vel_joint', 0.0, 0.05), self.last('velocity'))

    def test_4_group_controller_takes_over_and_checks_the_command_size(self):
        switch = rospy.ServiceProxy(NS + '/controller_manager/switch_controller', SwitchController)
        ok = switch(
            start_controllers=['group_controller'],
            stop_controllers=['pos_controller', 'pid_controller'],
            strictness=2,
            start_asap=False,
            timeout=0.0,
        ).ok
        self.assertTrue(ok)
        self.group.publish(Float64MultiArray(data=[0.3, -0.4]))
        self.assertTrue(self.settled('position', 'pos_joint', 0.3), self.last('position'))
        self.assertTrue(self.settled('position', 'pid_joint', -0.4), self.last('position'))
        self.rosout.clear()
        self.group.publish(Float64MultiArray(data=[1.0, 1.0, 1.0]))
        said = 'Dimension of command (3) does not match number of joints (2)! Not executing!'
        self.assertTrue(
            wait_for(lambda: any(said in m.msg for m in self.rosout.since(0)), 10),
            'no error for a command of the wrong size',
        )
        self.assertTrue(self.settled('position', 'pos_joint', 0.3), self.last('position'))


if __name__ == '__main__':
    rostest.rosrun('arm1', 'interfaces', Interfaces)
