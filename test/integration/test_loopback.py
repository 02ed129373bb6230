"""RosSession (make demo, bench, soak) keeps its master and nodes on loopback, whatever the shell
says.

ROS 1 has no authentication: a port reachable from the network lets anyone move the arm.
"""

import os
import time

import psutil
import pytest
import rosgraph

from _arm1sim.session.launcher import RosSession, listening_addresses, loopback_env, node_pid

LOOPBACK = '127.0.0.1'


def outside(pid):
    return [a for a in listening_addresses(pid) if a[0] != LOOPBACK]


def test_loopback_env_drops_ros_ip_and_keeps_the_master_port():
    env = loopback_env(
        {'ROS_IP': '192.0.2.7', 'ROS_MASTER_URI': 'http://192.0.2.7:12345/', 'PATH': '/bin'}
    )
    assert env == {
        'ROS_HOSTNAME': 'localhost',
        'ROS_MASTER_URI': 'http://localhost:12345',
        'PATH': '/bin',
    }
    assert loopback_env({})['ROS_MASTER_URI'] == 'http://localhost:11311'
    assert (
        loopback_env({'ROS_MASTER_URI': 'http://host:11311'}, 2000)['ROS_MASTER_URI']
        == 'http://localhost:2000'
    )


# Shells that would put every node on all interfaces: ROS's default (neither variable set),
# and an outside ROS_IP (which would also be advertised to peers).
@pytest.mark.parametrize('ros_ip', [None, '192.0.2.7'], ids=['plain_shell', 'outside_ros_ip'])
def test_session_master_world_and_roslaunch_listen_on_loopback_only(monkeypatch, ros_ip):
    monkeypatch.delenv('ROS_HOSTNAME', raising=False)
    if ros_ip:
        monkeypatch.setenv('ROS_IP', ros_ip)
    else:
        monkeypatch.delenv('ROS_IP', raising=False)
    with RosSession() as session:
        launch = session.roslaunch('arm1', 'gazebo.launch', 'gui:=false')
        assert session.wait_for_master(), 'the master did not start'
        master = rosgraph.Master('/test_loopback', master_uri=session.env['ROS_MASTER_URI'])
        deadline = time.monotonic() + 60
        while True:
            try:
                world = node_pid('/gazebo', session.env['ROS_MASTER_URI'], '/test_loopback')
                break
            except Exception:  # not registered yet (rosgraph.MasterError / socket errors)
                assert time.monotonic() < deadline, 'the world /gazebo never registered'
                time.sleep(0.2)
        for who, pid in (
            ('master', master.getPid()),
            ('world /gazebo', world),
            ('roslaunch', launch.pid),
        ):
            assert listening_addresses(pid), '%s listens on no TCP port' % who
            assert outside(pid) == [], '%s listens beyond loopback' % who
        # Every Python process roslaunch started (master, spawner, joint_state_publisher,
        # world); the roscpp ones (rosout, robot_state_publisher) bind XML-RPC on every
        # interface whatever ROS_HOSTNAME says: xmlrpcpp has no bind address.
        children = [
            p
            for p in psutil.Process(launch.pid).children(recursive=True)
            if 'python' in os.path.basename(p.exe())
        ]
        assert len(children) >= 4, [p.cmdline() for p in children]
        for p in children:
            assert outside(p.pid) == [], ' '.join(p.cmdline())
