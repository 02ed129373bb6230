#!/usr/bin/env python
"""Bad input ends in a clear message naming the culprit, and the simulation keeps running."""

import os
import re
import subprocess
import sys
import time

import rospy
import rostest
from controller_manager_msgs.srv import ListControllers, LoadController
from gazebo_msgs.srv import DeleteModel, SpawnModel

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rostest_util import WorldTestCase, wait_for  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
CM = '/arm1/controller_manager/'


def run(*cmd, timeout=60):
    proc = subprocess.run(
        cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=timeout
    )
    return proc.returncode, proc.stdout


class BadInput(WorldTestCase):
    NODE = 'test_bad_input'
    RECORD = ('rosout', 'clock')
    SERVICES = (CM + 'list_controllers',)

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.list = rospy.ServiceProxy(CM + 'list_controllers', ListControllers)

    def running(self):
        return {c.name for c in self.list().controller if c.state == 'running'}

    def logged(self, since, *words):
        return wait_for(
            lambda: any(all(w in m.msg for w in words) for m in self.rosout.since(since)), 10
        )

    def test_01_bad_controllers_fail_by_name_and_the_others_run(self):
        good = {
            'joint_state_controller',
            'joint1_position_controller',
            'joint2_position_controller',
        }
        self.assertTrue(wait_for(lambda: self.running() == good, 60), self.running())
        load = rospy.ServiceProxy(CM + 'load_controller', LoadController)
        for name, words in (
            ('unknown_joint_controller', ['joint9']),
            ('no_p_controller', ['No p gain specified']),
            ('unknown_type_controller', ['DiffDriveController', 'does not exist']),
            ('no_type_controller', ['type was not specified']),
        ):
            mark = time.monotonic()
            self.assertFalse(load(name).ok, name)
            self.assertTrue(self.logged(mark, name, *words), 'no message naming %s' % name)
        self.assertEqual(self.running(), good)

    def test_02_a_missing_mesh_is_left_out_naming_its_path_and_the_model_spawns(self):
        # as Gazebo's server: "Unable to load mesh", and the model comes up without it
        xml = rospy.get_param('/robot_description').replace(
            'meshes/link3.STL', 'meshes/no_such_link.STL'
        )
        # without its plugins: a second /arm1/controller_manager cannot be offered
        xml = re.sub(r'<gazebo>.*?</gazebo>', '', xml, flags=re.S)
        spawn = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
        mark = time.monotonic()
        resp = spawn('arm1_broken', xml, '/broken', None, '')
        self.assertTrue(resp.success, resp.status_message)
        self.assertTrue(self.logged(mark, 'link3', 'meshes/no_such_link.STL', 'not found'))
        delete = rospy.ServiceProxy('/gazebo/delete_model', DeleteModel)
        self.assertTrue(delete('arm1_broken').success)

    def test_03_spawn_model_without_description_gives_up(self):
        start = time.monotonic()
        rc, out = run(
            'rosrun',
            'arm1',
            'spawn_model',
            '-urdf',
            '-param',
            'no_such_description',
            '-model',
            'ghost',
            '-timeout',
            '2',
        )
        self.assertNotEqual(rc, 0)
        self.assertIn('waiting for parameter /no_such_description', out)
        self.assertIn('gave up after 2 s waiting for parameter /no_such_description', out)
        self.assertLess(time.monotonic() - start, 30)
        self.assertNotIn('Traceback', out)

    def test_04_malformed_xacro_gives_the_parser_message(self):
        rc, out = run('xacro', os.path.join(HERE, 'config', 'malformed.urdf.xacro'))
        self.assertNotEqual(rc, 0)
        self.assertIn('mismatched tag', out)
        self.assertIn('malformed.urdf.xacro', out)
        self.assertNotIn('Traceback', out)

    def test_05_malformed_yaml_gives_the_parser_message(self):
        path = os.path.join(HERE, 'config', 'malformed.yaml')
        rc, out = run('roslaunch', 'arm1', 'robot_control.xml', 'controllers_file:=' + path)
        self.assertNotEqual(rc, 0)
        self.assertIn('malformed.yaml contains invalid YAML', out)
        self.assertIn('line 4', out)
        self.assertNotIn('Traceback', out)

    def test_06_simulation_still_running(self):
        before = self.clock.last().clock
        self.assertTrue(wait_for(lambda: (self.clock.last().clock - before).to_sec() > 0.2, 10))
        self.assertIn('joint1_position_controller', self.running())


if __name__ == '__main__':
    rostest.rosrun('arm1', 'test_bad_input', BadInput)
