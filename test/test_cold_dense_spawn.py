#!/usr/bin/env python
"""No upstream wall-clock timeout is hit on a first launch (issue 29 item 6,
arm1_cold_dense_spawn.test): with the mesh cache empty and one core kept busy by a
busy-loop process, `rosrun gazebo_ros spawn_model` spawns a six-link robot of ours whose
links are 20 k-triangle OBJ and COLLADA meshes (bench/dense_meshes.py), and
`rosrun controller_manager spawner` (30 s of wall time for its services) gets every
controller running. The spawn answers well inside that: dense meshes collide as their
hulls at once, their pieces are made off the world (physics/mesh_jobs.py)."""

import os
import shutil
import subprocess
import sys
import tempfile
import time
import unittest

import rospy
import rostest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rostest_util import wait_for_controllers  # noqa: E402

from _arm1sim.bench.dense_meshes import u_bracket, write_mesh  # noqa: E402

LINKS = 6
TRIANGLES = 20000
NS = '/dense'
# Upstream's spawner gives up after 30 s of wall time waiting for load_controller, and
# is started with spawn_model in a launch file: the whole of `rosrun spawn_model` (Python
# and rospy start-up included: 17 s under a load of 13 on 2 cores) stays inside that.
SPAWN_WALL_LIMIT = 30.0
INERTIA = '<inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/>'


def dense_robot(folder):
    """A chain of LINKS links, each with its own dense mesh (OBJ, COLLADA in turn) as
    visual and collision, on revolute joints driven through gazebo_ros_control."""
    tris = u_bracket(TRIANGLES)
    parts = ['<link name="world"/>']
    for i in range(LINKS):
        # each mesh its own file (its own cache entry): nudged so no two are alike
        mesh = os.path.join(folder, 'link%d.%s' % (i, ('obj', 'dae')[i % 2]))
        write_mesh(mesh, tris * (1.0 + 0.01 * i))
        geometry = '<geometry><mesh filename="file://%s"/></geometry>' % mesh
        parts.append(
            '<link name="l%d"><inertial><mass value="0.2"/>%s</inertial><visual>%s</visual>'
            '<collision>%s</collision></link>' % (i, INERTIA, geometry, geometry)
        )
        parts.append(
            '<joint name="j%d" type="%s"><parent link="%s"/><child link="l%d"/>'
            '<origin xyz="0 0 %r"/><axis xyz="0 1 0"/>'
            '<limit lower="-1" upper="1" effort="10" velocity="2"/></joint>'
            % (
                i,
                'fixed' if i == 0 else 'revolute',
                'world' if i == 0 else 'l%d' % (i - 1),
                i,
                0.05,
            )
        )
        if i:
            parts.append(
                '<transmission name="t%d"><type>transmission_interface/SimpleTransmission</type>'
                '<joint name="j%d"><hardwareInterface>hardware_interface/EffortJointInterface'
                '</hardwareInterface></joint><actuator name="m%d"><mechanicalReduction>1'
                '</mechanicalReduction></actuator></transmission>' % (i, i, i)
            )
    parts.append(
        '<gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so">'
        '<robotNamespace>%s</robotNamespace></plugin></gazebo>' % NS
    )
    return '<robot name="dense">%s</robot>' % ''.join(parts)


def controller_params():
    params = {
        'joint_state_controller': {
            'type': 'joint_state_controller/JointStateController',
            'publish_rate': 50,
        }
    }
    for i in range(1, LINKS):
        params['j%d_controller' % i] = {
            'type': 'effort_controllers/JointPositionController',
            'joint': 'j%d' % i,
            'pid': {'p': 20.0, 'i': 0.0, 'd': 1.0},
        }
    return params


class ColdDenseSpawn(unittest.TestCase):
    def test_a_cold_dense_robot_comes_up_with_every_controller_running_on_a_busy_core(self):
        rospy.init_node('test_cold_dense_spawn')
        cache = rospy.get_param('/cold_cache')
        self.assertFalse(os.listdir(cache) if os.path.isdir(cache) else [], 'cache not empty')
        self.addCleanup(shutil.rmtree, cache, True)
        folder = tempfile.mkdtemp(prefix='arm1-dense-meshes-')
        self.addCleanup(shutil.rmtree, folder, True)
        rospy.set_param('/dense_description', dense_robot(folder))
        rospy.set_param(NS, controller_params())
        busy = subprocess.Popen([sys.executable, '-c', 'while True: pass'])
        self.addCleanup(busy.wait)
        self.addCleanup(busy.kill)
        rospy.wait_for_service('/gazebo/spawn_urdf_model', 60)
        start = time.monotonic()
        spawned = subprocess.run(
            [
                'rosrun',
                'gazebo_ros',
                'spawn_model',
                '-urdf',
                '-param',
                'dense_description',
                '-model',
                'dense',
            ],
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            timeout=120,
        )
        took = time.monotonic() - start
        self.assertEqual(spawned.returncode, 0, spawned.stdout)
        self.assertLess(took, SPAWN_WALL_LIMIT, 'spawn_model took %.1f s' % took)
        names = ['joint_state_controller'] + ['j%d_controller' % i for i in range(1, LINKS)]
        spawner = subprocess.Popen(
            ['rosrun', 'controller_manager', 'spawner', '--namespace', NS] + names,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
        )
        self.addCleanup(spawner.wait)
        self.addCleanup(spawner.terminate)
        list_controllers = wait_for_controllers(len(names), NS, timeout=90)
        running = {c.name for c in list_controllers().controller if c.state == 'running'}
        self.assertEqual(running, set(names))
        self.assertIsNone(spawner.poll(), 'the spawner gave up')
        rospy.loginfo('cold dense spawn: spawn_model %.1f s wall (one core busy)', took)


if __name__ == '__main__':
    rostest.rosrun('arm1', 'cold_dense_spawn', ColdDenseSpawn)
