#!/usr/bin/env python
"""SDF models: a world file's static table keeps a dynamic can on it; spawn_sdf_model and
spawn_model -sdf build SDF boxes; a bad SDF gets success false naming the culprit while
/clock runs on."""

import os
import sys

import rospy
import rostest
from gazebo_msgs.srv import DeleteModel, GetModelState, GetWorldProperties, SpawnModel
from geometry_msgs.msg import Point, Pose, Quaternion

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rostest_util import WorldTestCase, sim_wait, wait_for  # noqa: E402

BOX = """<?xml version="1.0"?>
<sdf version="1.6"><model name="ignored"><pose>0 0 0.05 0 0 0</pose>
  <link name="body">
    <inertial><mass>0.5</mass>
      <inertia><ixx>0.00083</ixx><iyy>0.00083</iyy><izz>0.00083</izz></inertia></inertial>
    <collision name="c"><geometry><box><size>0.1 0.1 0.1</size></box></geometry></collision>
    <visual name="v"><geometry><box><size>0.1 0.1 0.1</size></box></geometry></visual>
  </link></model></sdf>"""

TABLE_TOP = 0.72  # the world file's table top (box at 0.7, 0.04 thick)
CAN_HALF = 0.06


def proxy(name, srv):
    rospy.wait_for_service('/gazebo/' + name, 60)
    return rospy.ServiceProxy('/gazebo/' + name, srv)


def pose(x, y, z):
    return Pose(Point(x, y, z), Quaternion(0, 0, 0, 1))


class SdfModels(WorldTestCase):
    NODE = 'test_sdf_models'
    RECORD = ('clock',)
    FIRST = ('clock',)
    SERVICES = ('/gazebo/spawn_sdf_model', '/gazebo/get_model_state')

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.spawn = proxy('spawn_sdf_model', SpawnModel)
        cls.get_state = proxy('get_model_state', GetModelState)

    def z(self, name):
        res = self.get_state(name, 'world')
        self.assertTrue(res.success, res.status_message)
        return res.pose.position.z

    def test_01_world_models_have_their_sdf_names(self):
        names = proxy('get_world_properties', GetWorldProperties)().model_names
        for name in ('ground_plane', 'table', 'can', 'crate'):  # crate: an <include>
            self.assertIn(name, names)
        self.assertNotIn('no_such_model', names)
        table = self.get_state('table', 'world')
        self.assertTrue(table.success, table.status_message)
        self.assertAlmostEqual(table.pose.position.x, 1.0, places=3)

    def test_02_the_can_stays_on_the_static_table(self):
        sim_wait(2.0)
        self.assertGreaterEqual(rospy.Time.now().to_sec(), 2.0, 'less than 2 s of sim time ran')
        can = self.get_state('can', 'world')
        self.assertTrue(can.success, can.status_message)
        # on the table top, not through it or on the floor
        self.assertAlmostEqual(can.pose.position.z, TABLE_TOP + CAN_HALF, delta=0.01)
        self.assertAlmostEqual(can.pose.position.x, 1.0, delta=0.02)
        self.assertAlmostEqual(self.z('table'), 0.0, places=4)  # static: it did not fall
        # the included crate (an OBJ mesh, 0.1 m) fell from 0.2 m onto the ground
        crate = self.get_state('crate', 'world')
        self.assertAlmostEqual(crate.pose.position.z, 0.05, delta=0.01)
        self.assertAlmostEqual(crate.pose.position.x, -1.0, delta=0.02)

    def test_03_spawn_sdf_model_builds_a_box_that_falls_to_the_ground(self):
        res = self.spawn('sdf_box', BOX, '', pose(0, 2, 0.5), 'world')
        self.assertTrue(res.success, res.status_message)
        self.assertIn('sdf_box', res.status_message)
        # the model's own <pose> (z 0.05) is taken in the initial pose (z 0.5)
        self.assertGreater(self.z('sdf_box'), 0.3)
        sim_wait(1.5)
        self.assertAlmostEqual(self.z('sdf_box'), 0.05, delta=0.01)
        again = self.spawn('sdf_box', BOX, '', pose(0, 3, 0.5), 'world')
        self.assertFalse(again.success)
        self.assertIn('sdf_box', again.status_message)
        deleted = proxy('delete_model', DeleteModel)('sdf_box')
        self.assertTrue(deleted.success, deleted.status_message)
        self.assertFalse(self.get_state('sdf_box', 'world').success)

    def test_04_spawn_model_minus_sdf_from_a_file_and_from_the_database(self):
        for name, x, y in (('file_box', -1.0, 1.0), ('db_crate', 2.0, 0.0)):
            found = wait_for(lambda: self.get_state(name, 'world').success, 60)
            self.assertTrue(found, 'spawn_model did not spawn ' + name)
            sim_wait(1.0)
            res = self.get_state(name, 'world')
            self.assertAlmostEqual(res.pose.position.x, x, delta=0.02)
            self.assertAlmostEqual(res.pose.position.y, y, delta=0.02)
            self.assertAlmostEqual(res.pose.position.z, 0.05, delta=0.01)  # on the ground

    def test_05_bad_sdf_names_the_culprit_and_the_world_runs_on(self):
        cases = [
            (
                '<sdf version="1.6"><model name="m"><link name="l"><collision name="rock">'
                '<geometry><box><size>1 1</size></box></geometry></collision></link></model></sdf>',
                'rock',
            ),
            (
                '<sdf version="1.6"><model name="m"><link name="a"/><joint name="hinge" '
                'type="revolute"><parent>a</parent><child>nowhere</child></joint></model></sdf>',
                'nowhere',
            ),
            ('<sdf version="1.6"><model name="m"><link name="l"/>', 'not well-formed'),
            ('<sdf version="1.6"><light name="lamp" type="point"/></sdf>', 'light'),
            (
                '<sdf version="1.6"><model name="m"><link name="l"><visual name="v"><geometry>'
                '<mesh><uri>model://no_such_model/m.stl</uri></mesh></geometry></visual></link>'
                '</model></sdf>',
                'no_such_model',
            ),
        ]
        for i, (xml, culprit) in enumerate(cases):
            res = self.spawn('bad_%d' % i, xml, '', pose(0, 0, 1), 'world')
            self.assertFalse(res.success, xml)
            self.assertIn(culprit, res.status_message)
            self.assertFalse(self.get_state('bad_%d' % i, 'world').success)
        before = self.clock.last().clock
        self.assertTrue(wait_for(lambda: self.clock.last().clock > before, 10), 'clock stopped')


if __name__ == '__main__':
    rostest.rosrun('arm1', 'sdf_models', SdfModels)
