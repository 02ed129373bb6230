#!/usr/bin/env python
"""A gazebo_msgs client moves, reads and pushes a box through /gazebo's state services and
topics; bad requests get messages naming the culprit while /clock runs on."""

import math
import os
import sys
import time

import rospy
import rostest
from gazebo_msgs.msg import LinkState, ModelState, ModelStates
from gazebo_msgs.srv import (
    ApplyBodyWrench,
    ApplyJointEffort,
    GetJointProperties,
    GetLinkState,
    GetModelProperties,
    GetModelState,
    GetPhysicsProperties,
    GetWorldProperties,
    SetLinkState,
    SetModelState,
)
from geometry_msgs.msg import Point, Pose, Quaternion, Twist, Vector3, Wrench

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rostest_util import (  # noqa: E402
    Recorder,
    SpawningTestCase,
    sim_wait,
    spawn_urdf,
    wait_for,
)

BOX = """<robot name="box"><link name="body">
  <inertial><mass value="0.5"/><inertia ixx="0.00083" ixy="0" ixz="0" iyy="0.00083" iyz="0"
    izz="0.00083"/></inertial>
  <visual><geometry><box size="0.1 0.1 0.1"/></geometry></visual>
  <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>
</link></robot>"""


def proxy(name, srv):
    rospy.wait_for_service('/gazebo/' + name, 60)
    return rospy.ServiceProxy('/gazebo/' + name, srv)


def xyz(p):
    return (p.x, p.y, p.z)


class GazeboState(SpawningTestCase):
    NODE = 'test_gazebo_state'

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        spawn_urdf('box', BOX, '', (1, 0, 0.05))
        cls.get_state = proxy('get_model_state', GetModelState)
        cls.set_state = proxy('set_model_state', SetModelState)

    def place(self, x, y, z):
        return self.set_state(
            ModelState('box', Pose(Point(x, y, z), Quaternion(0, 0, 0, 1)), Twist(), 'world')
        )

    def test_set_model_state_moves_the_box_and_get_reads_it_back(self):
        res = self.place(1.5, 0.5, 0.05)
        self.assertTrue(res.success, res.status_message)
        self.assertEqual(res.status_message, 'SetModelState: set model state done')
        got = self.get_state('box', 'world')
        self.assertTrue(got.success)
        self.assertEqual(got.status_message, 'GetModelState: got properties')
        for a, b in zip(xyz(got.pose.position), (1.5, 0.5, 0.05)):
            self.assertAlmostEqual(a, b, delta=0.01)

    def test_model_states_topic_shows_the_moved_box(self):
        states = Recorder('/gazebo/model_states', ModelStates)
        try:
            self.place(-1.0, 1.0, 0.05)

            def near():
                m = states.last()
                if m is None or 'box' not in m.name:
                    return False
                p = m.pose[m.name.index('box')].position
                return abs(p.x + 1.0) < 0.01 and abs(p.y - 1.0) < 0.01

            self.assertTrue(wait_for(near, 20), 'model_states never showed the box at (-1, 1)')
            self.assertIn('arm1', states.last().name)
            # As Gazebo: once per step while subscribed (1 kHz at 1 ms; the publisher thread
            # drops readings while it lags, so ask for a tenth of that). Judged per second of
            # sim time, between two /clock messages: the messages carry no stamp, and a busy
            # machine runs the world slower than real time, so a wall window holds fewer steps.
            mark = time.monotonic()

            def ticks():  # (arrival, sim seconds) of each /clock message since mark
                with self.clock.lock:
                    return [(t, m.clock.to_sec()) for t, m in self.clock.msgs if t >= mark]

            span = lambda: ticks()[-1][1] - ticks()[0][1] if ticks() else 0.0  # noqa: E731
            self.assertTrue(wait_for(lambda: span() >= 0.5, 60), '/clock stalled')
            (t0, s0), (t1, s1) = ticks()[0], ticks()[-1]
            with states.lock:
                count = sum(t0 <= t <= t1 for t, _ in states.msgs)
            rate = count / (s1 - s0)
            self.assertGreater(rate, 100, 'model_states %.0f a sim second' % rate)
        finally:
            states.sub.unregister()

    def test_topic_set_model_state_moves_the_box(self):
        pub = rospy.Publisher('/gazebo/set_model_state', ModelState, queue_size=1, latch=True)
        pub.publish(
            ModelState('box', Pose(Point(0.7, -0.7, 0.05), Quaternion(0, 0, 0, 1)), Twist(), '')
        )
        self.assertTrue(
            wait_for(lambda: abs(self.get_state('box', '').pose.position.y + 0.7) < 0.01, 20),
            'the set_model_state topic did not move the box',
        )
        pub.unregister()

    def test_apply_body_wrench_pushes_the_box_along_the_force(self):
        self.place(0.0, 1.5, 0.05)
        sim_wait(0.2)
        before = self.get_state('box', '').pose.position
        wrench = proxy('apply_body_wrench', ApplyBodyWrench)
        # 10 N up on 0.5 kg (weight 4.9 N) and 2 N along +x, for 0.3 s: it lifts and slides.
        res = wrench(
            'box::body',
            '',
            Point(),
            Wrench(Vector3(2, 0, 10), Vector3()),
            rospy.Time(0),
            rospy.Duration(0.3),
        )
        self.assertTrue(res.success, res.status_message)
        sim_wait(0.3)
        after = self.get_state('box', '').pose.position
        self.assertGreater(after.z - before.z, 0.05, 'the box did not rise')
        self.assertGreater(after.x - before.x, 0.005, 'the box did not move along +x')

    def test_set_link_state_moves_the_box_and_get_link_state_reads_it(self):
        res = proxy('set_link_state', SetLinkState)(
            LinkState('box::body', Pose(Point(0.4, 0.4, 0.05), Quaternion(0, 0, 0, 1)), Twist(), '')
        )
        self.assertTrue(res.success, res.status_message)
        got = proxy('get_link_state', GetLinkState)('box::body', 'world')
        self.assertTrue(got.success, got.status_message)
        self.assertEqual(got.link_state.link_name, 'box::body')
        self.assertAlmostEqual(got.link_state.pose.position.x, 0.4, delta=0.01)

    def test_world_model_and_joint_properties(self):
        world = proxy('get_world_properties', GetWorldProperties)()
        self.assertTrue(world.success)
        self.assertIn('arm1', world.model_names)
        self.assertIn('box', world.model_names)
        self.assertEqual(world.model_names[0], 'ground_plane')  # the world file's come first
        self.assertGreater(world.sim_time, 0)
        model = proxy('get_model_properties', GetModelProperties)('arm1')
        self.assertTrue(model.success, model.status_message)
        for j in ('joint1', 'joint2', 'joint3', 'joint4'):
            self.assertIn(j, model.joint_names)
        self.assertIn('base_link', model.body_names)
        joint = proxy('get_joint_properties', GetJointProperties)('joint1')
        self.assertTrue(joint.success, joint.status_message)
        self.assertEqual(len(joint.position), 1)
        self.assertTrue(math.isfinite(joint.position[0]))
        physics = proxy('get_physics_properties', GetPhysicsProperties)()
        self.assertAlmostEqual(physics.time_step, 0.001)
        self.assertAlmostEqual(physics.gravity.z, -9.8)

    def test_bad_requests_name_the_culprit_and_the_world_runs_on(self):
        before = self.clock.last().clock
        res = self.get_state('nobox', 'world')
        self.assertFalse(res.success)
        self.assertIn('nobox', res.status_message)
        res = self.get_state('box', 'nowhere')
        self.assertFalse(res.success)
        self.assertIn('nowhere', res.status_message)
        res = self.set_state(
            ModelState('box', Pose(Point(math.nan, 0, 0), Quaternion(0, 0, 0, 1)), Twist(), '')
        )
        self.assertFalse(res.success)
        self.assertIn('box', res.status_message)
        self.assertIn('finite', res.status_message)
        res = proxy('get_link_state', GetLinkState)('box::nolink', '')
        self.assertFalse(res.success)
        self.assertIn('box::nolink', res.status_message)
        res = proxy('get_joint_properties', GetJointProperties)('nojoint')
        self.assertFalse(res.success)
        self.assertIn('nojoint', res.status_message)
        res = proxy('apply_body_wrench', ApplyBodyWrench)(
            'ghost::body', '', Point(), Wrench(), rospy.Time(0), rospy.Duration(1)
        )
        self.assertFalse(res.success)
        self.assertIn('ghost::body', res.status_message)
        res = proxy('apply_joint_effort', ApplyJointEffort)(
            'nojoint', 1.0, rospy.Time(0), rospy.Duration(1)
        )
        self.assertFalse(res.success)
        self.assertIn('nojoint', res.status_message)
        res = proxy('set_link_state', SetLinkState)(LinkState('arm1::nolink', Pose(), Twist(), ''))
        self.assertFalse(res.success)
        self.assertIn('arm1::nolink', res.status_message)
        self.assertTrue(
            wait_for(lambda: self.clock.last().clock > before, 10),
            '/clock stopped after bad requests',
        )


if __name__ == '__main__':
    rostest.rosrun('arm1', 'gazebo_state', GazeboState)
