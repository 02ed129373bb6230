"""gazebo_ros's launch files (the stand-in's, tools/compat_gazebo_ros_launch.py) come up under
a real master: a launch file of ours passing every one of upstream empty_world.launch's 17
arguments, and each world launch file gazebo_ros ships, with its world's models in
/gazebo/get_world_properties.
"""

import glob
import os
import signal
import subprocess
from urllib.parse import urlparse

import pytest

from _arm1sim.session.launcher import RosSession

# all 17 of gazebo_ros/launch/empty_world.launch's arguments, none at its default
ALL_ARGS = {
    'paused': 'false',
    'use_sim_time': 'true',
    'extra_gazebo_args': '--seed 7',
    'gui': 'false',
    'recording': 'true',
    'headless': 'true',
    'debug': 'false',
    'physics': 'bullet',
    'verbose': 'true',
    'output': 'log',
    'world_name': 'worlds/shapes.world',
    'respawn_gazebo': 'false',
    'use_clock_frequency': 'true',
    'pub_clock_frequency': '50',
    'enable_ros_network': 'true',
    'server_required': 'true',
    'gui_required': 'true',
}
INCLUDING = '''<launch>
  <include file="$(find gazebo_ros)/launch/empty_world.launch">
{args}
  </include>
</launch>
'''

WORLDS = {
    'willowgarage_world.launch': ['willowgarage'],
    'shapes_world.launch': ['box', 'sphere', 'cylinder'],
    'mud_world.launch': ['mud_box', 'box_1', 'box_2'],
    'rubble_world.launch': ['rubble_%d' % i for i in range(12)],
    'range_world.launch': ['sensor_post', 'wall', 'box'],
    'elevator_world.launch': ['elevator', 'building'],
}


def _run(session, *cmd, timeout=60):
    return subprocess.run(
        cmd, env=session.env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=timeout
    ).stdout.decode('utf-8', 'replace')


def _stop(proc):
    if proc.poll() is None:
        os.killpg(proc.pid, signal.SIGINT)
    try:
        proc.wait(20)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()


def _up(session, launch_cmd, models):
    """Start a launch, wait for two /clock messages and the world's models, stop it."""
    proc = session.start(*launch_cmd)
    try:
        clock = _run(session, 'rostopic', 'echo', '-n', '2', '/clock', timeout=120)
        assert clock.count('clock:') == 2, clock
        # the world file's models are spawned before physics starts, so before /clock ticks
        props = _run(session, 'rosservice', 'call', '/gazebo/get_world_properties')
        for m in ['ground_plane'] + models:
            assert '- %s\n' % m in props, props
        return proc
    finally:
        _stop(proc)


@pytest.fixture(scope='module')
def session(tmp_path_factory):
    with RosSession(log_dir=str(tmp_path_factory.mktemp('ros_log'))) as s:
        s.start('roscore', '-p', str(urlparse(s.env['ROS_MASTER_URI']).port))
        assert s.wait_for_master(), 'the master did not start'
        yield s


def test_empty_world_with_all_17_arguments_comes_up_and_says_what_it_cannot_apply(
    session, tmp_path
):
    launch = tmp_path / 'all_args.launch'
    launch.write_text(
        INCLUDING.format(
            args='\n'.join('    <arg name="%s" value="%s"/>' % item for item in ALL_ARGS.items())
        )
    )
    _up(session, ['roslaunch', str(launch)], ['box', 'sphere', 'cylinder'])
    logs = ''
    for path in glob.glob(os.path.join(session.env['ROS_LOG_DIR'], '**', '*.log'), recursive=True):
        with open(path, errors='replace') as f:
            logs += f.read()
    for said in (
        'gzserver: physics bullet',
        'gzserver: recording (-r)',
        'gzserver: gzserver options not applied here (extra_gazebo_args?): --seed 7',
        'gzserver: gui_required',
    ):
        assert logs.count(said) >= 1, said
    assert 'use_clock_frequency false' not in logs


@pytest.mark.parametrize('launch_file', sorted(WORLDS))
def test_world_launch_file_comes_up(session, launch_file):
    # gui:=true in upstream's fixed world launch files: no display here, so no window
    _up(session, ['roslaunch', 'gazebo_ros', launch_file], WORLDS[launch_file])
