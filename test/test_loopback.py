#!/usr/bin/env python
"""What make test starts listens on loopback only: the rostest master, the world, every rospy node.

ROS 1 has no authentication, so a port reachable from the network lets anyone move the arm.
tools/ws-run (every make target) sets ROS_HOSTNAME=localhost; run by hand, export it too.
"""

import os
import sys
import unittest
from urllib.parse import urlparse

import psutil
import rosgraph
import rospy
import rostest

from _arm1sim.session.launcher import listening_addresses, node_pid

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rostest_util import wait_for  # noqa: E402

LOOPBACK = '127.0.0.1'


def graph_nodes(master):
    """Names of every node that publishes, subscribes or serves something."""
    pubs, subs, srvs = master.getSystemState()
    return sorted({n for _, nodes in pubs + subs + srvs for n in nodes})


class Loopback(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_loopback')
        cls.master = rosgraph.Master('/test_loopback')
        # The spawner's switch_controller has run once joint_states flow: the graph is complete.
        rospy.wait_for_message('/arm1/joint_states', rospy.AnyMsg, timeout=60)

    def assert_loopback_only(self, pid, who):
        addrs = listening_addresses(pid)
        self.assertTrue(addrs, '%s (pid %d) listens on no TCP port at all' % (who, pid))
        outside = [a for a in addrs if a[0] != LOOPBACK]
        self.assertEqual(
            outside,
            [],
            '%s (pid %d) listens beyond loopback: %s'
            % (who, pid, ', '.join('%s:%d' % a for a in outside)),
        )

    def test_master_listens_on_loopback_only(self):
        self.assert_loopback_only(self.master.getPid(), 'the ROS master')

    def test_world_listens_on_loopback_only(self):
        self.assertTrue(
            wait_for(lambda: '/gazebo' in graph_nodes(self.master), 30),
            'the world node /gazebo never registered',
        )
        self.assert_loopback_only(node_pid('/gazebo', caller='/test_loopback'), 'the world /gazebo')

    def test_every_rospy_node_listens_on_loopback_only(self):
        # rosout and robot_state_publisher are Debian's roscpp binaries: their XML-RPC server
        # (xmlrpcpp) binds every interface whatever ROS_HOSTNAME says; their topics do not.
        checked = []
        for name in graph_nodes(self.master):
            pid = node_pid(name, caller='/test_loopback')
            if 'python' in os.path.basename(psutil.Process(pid).exe()):
                self.assert_loopback_only(pid, name)
                checked.append(name)
        for expected in ('/gazebo', rospy.get_name(), '/joint_state_publisher'):
            self.assertIn(expected, checked)

    def test_every_node_advertises_localhost(self):
        for name in graph_nodes(self.master):
            uri = self.master.lookupNode(name)
            self.assertEqual(urlparse(uri).hostname, 'localhost', '%s advertises %s' % (name, uri))
        self.assertEqual(urlparse(self.master.getUri()).hostname, 'localhost')


if __name__ == '__main__':
    rostest.rosrun('arm1', 'loopback', Loopback)
