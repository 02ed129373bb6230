#!/usr/bin/env python
"""worlds/empty.world by name and spawn_model's default namespace, as with UR's launch files
(test/arm1_resources.test, robot test/config/res_bot.urdf)."""

import os
import sys

import rosnode
import rospy
import rostest
from controller_manager_msgs.srv import ListControllers
from rosservice import get_service_list

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rostest_util import Recorder, WorldTestCase, positions, wait_for  # noqa: E402
from sensor_msgs.msg import JointState  # noqa: E402

REST = -0.9  # slider position with the block's bottom on the ground (base at z=1, half 0.1)


class Resources(WorldTestCase):
    NODE = 'test_resources'
    SERVICES = ('/gazebo/spawn_urdf_model',)

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.states = Recorder('/joint_states', JointState)

    def test_01_world_named_worlds_empty_world_is_found_and_runs(self):
        # Before, the world node died: "cannot read world file worlds/empty.world".
        self.assertIn('/gazebo', rosnode.get_node_names())

    def test_02_controller_manager_is_at_the_root_namespace(self):
        name = '/controller_manager/list_controllers'
        rospy.wait_for_service(name, 60)
        names = []

        def loaded():  # the service is up before the spawner has loaded the controller
            names[:] = [c.name for c in rospy.ServiceProxy(name, ListControllers)().controller]
            return bool(names)

        wait_for(loaded, 30)
        self.assertEqual(names, ['joint_state_controller'])
        self.assertNotIn('/res_bot/controller_manager/list_controllers', get_service_list())

    def test_03_block_falls_onto_the_ground_plane_and_rests_there(self):
        def resting():
            msgs = [m for _, m in self.states.msgs[-20:]]
            if len(msgs) < 20:
                return False
            values = [positions(m)['slider'] for m in msgs]
            return max(values) - min(values) < 1e-3 and abs(values[-1] - REST) < 0.02

        self.assertTrue(
            wait_for(resting, 60),
            'slider not resting at %.2f: last %s' % (REST, self.states.last()),
        )


if __name__ == '__main__':
    rostest.rosrun('arm1', 'resources', Resources)
