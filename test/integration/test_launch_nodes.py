"""The everyday nodes robot launch files start besides the simulator, from Debian's packages
that make setup installs (docs/building.md): static transforms from tf2_ros and tf and a
topic_tools relay run under a real master; the GUI ones are found where roslaunch looks.
"""

import subprocess
from urllib.parse import urlparse

import pytest
import roslib.packages

from _arm1sim.session.launcher import RosSession

LAUNCH = """<launch>
  <node pkg="tf2_ros" type="static_transform_publisher" name="tf2_static"
        args="0.1 0.2 0.3 0 0 0 base_link tf2_frame"/>
  <node pkg="tf" type="static_transform_publisher" name="tf1_static"
        args="0 0 1 0 0 0 base_link tf1_frame 100"/>
  <node pkg="topic_tools" type="relay" name="relay" args="/relay_in /relay_out"/>
</launch>
"""

# (package, node) that robot and MoveIt launch files start and a headless test cannot run
FOUND = [
    ('joint_state_publisher_gui', 'joint_state_publisher_gui'),
    ('rviz', 'rviz'),
    ('image_view', 'image_view'),
    ('image_transport', 'republish'),
    ('tf2_ros', 'buffer_server'),
    ('topic_tools', 'throttle'),
    ('topic_tools', 'mux'),
]


def _run(session, *cmd, timeout=60):
    return subprocess.run(
        cmd, env=session.env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=timeout
    ).stdout.decode('utf-8', 'replace')


@pytest.fixture(scope='module')
def session(tmp_path_factory):
    with RosSession(log_dir=str(tmp_path_factory.mktemp('ros_log'))) as s:
        s.start('roscore', '-p', str(urlparse(s.env['ROS_MASTER_URI']).port))
        assert s.wait_for_master(), 'the master did not start'
        launch = tmp_path_factory.mktemp('launch') / 'nodes.launch'
        launch.write_text(LAUNCH)
        s.start('roslaunch', str(launch))
        yield s


def test_tf2_ros_static_transform_publisher_latches_its_frame(session):
    out = _run(session, 'rostopic', 'echo', '-n', '1', '/tf_static')
    assert 'child_frame_id: "tf2_frame"' in out, out
    assert 'x: 0.1' in out and 'y: 0.2' in out and 'z: 0.3' in out, out


def test_tf_static_transform_publisher_repeats_its_frame_on_tf(session):
    out = _run(session, 'rostopic', 'echo', '-n', '2', '/tf')
    assert out.count('child_frame_id: "tf1_frame"') == 2, out


def test_topic_tools_relay_passes_messages_on(session):
    echo = subprocess.Popen(
        ['rostopic', 'echo', '-n', '1', '/relay_out'],
        env=session.env,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
    )
    try:
        # -r: until the relay has subscribed and the echo has its message
        pub = subprocess.Popen(
            ['rostopic', 'pub', '-r', '5', '/relay_in', 'std_msgs/String', 'data: relayed'],
            env=session.env,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        try:
            out = echo.communicate(timeout=60)[0].decode()
        finally:
            pub.terminate()
            pub.wait(10)
    finally:
        if echo.poll() is None:
            echo.kill()
            echo.wait()
    assert 'data: "relayed"' in out, out


@pytest.mark.parametrize('package,node', FOUND)
def test_a_launch_files_node_is_found_where_roslaunch_looks(session, package, node):
    paths = roslib.packages.find_node(package, node)
    assert paths, '%s/%s not found' % (package, node)
