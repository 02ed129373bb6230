"""The compat gazebo_ros package's empty_world.launch defaults as upstream's does: robot
bringups that include it without a world_name get Gazebo's worlds/empty.world (a ground
plane and a sun), not a world without ground under their mobile base."""

import os
import sys
import xml.etree.ElementTree as ET

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def test_gazebo_ros_empty_world_launch_defaults_to_worlds_empty_world(tmp_path) -> None:
    sys.path.insert(0, os.path.join(REPO_ROOT, 'tools'))
    try:
        import make_compat_packages
    finally:
        sys.path.pop(0)
    make_compat_packages.make(str(tmp_path))
    launch = ET.parse(str(tmp_path / 'gazebo_ros' / 'launch' / 'empty_world.launch'))
    defaults = {a.get('name'): a.get('default') for a in launch.getroot().iter('arg')}
    # gazebo_ros/launch/empty_world.launch: world_name default="worlds/empty.world"
    assert defaults['world_name'] == 'worlds/empty.world'


UPSTREAM_EMPTY_WORLD_ARGS = (
    'paused use_sim_time extra_gazebo_args gui recording headless debug physics verbose output '
    'world_name respawn_gazebo use_clock_frequency pub_clock_frequency enable_ros_network '
    'server_required gui_required'
).split()


def _make(tmp_path):
    sys.path.insert(0, os.path.join(REPO_ROOT, 'tools'))
    try:
        import make_compat_packages
    finally:
        sys.path.pop(0)
    make_compat_packages.make(str(tmp_path))
    return tmp_path / 'gazebo_ros' / 'launch'


def _args(path):
    return {a.get('name'): a.get('default') for a in ET.parse(str(path)).getroot().iter('arg')}


def test_empty_world_has_upstreams_17_arguments_and_arm1s_launch_takes_them_all(tmp_path):
    launch = _make(tmp_path)
    stand_in = _args(launch / 'empty_world.launch')
    assert set(UPSTREAM_EMPTY_WORLD_ARGS) <= set(stand_in)
    # upstream's defaults (gazebo_ros noetic-devel)
    assert stand_in['use_clock_frequency'] == 'false' and stand_in['gui_required'] == 'false'
    assert stand_in['enable_ros_network'] == 'true' and stand_in['extra_gazebo_args'] == ''
    # pass_all_args: arm1's launch/empty_world.launch must declare every one of them
    arm1 = _args(os.path.join(REPO_ROOT, 'launch', 'empty_world.launch'))
    assert set(stand_in) <= set(arm1), set(stand_in) - set(arm1)


def test_each_world_launch_names_a_world_of_ours(tmp_path):
    launch = _make(tmp_path)
    worlds = os.path.join(REPO_ROOT, 'gazebo_share', 'worlds')
    for name in ('willowgarage', 'shapes', 'mud', 'rubble', 'elevator'):
        root = ET.parse(str(launch / ('%s_world.launch' % name))).getroot()
        values = {}  # the first: elevator's own arg, then the include's value for the others
        for a in root.iter('arg'):
            values.setdefault(a.get('name'), a.get('value') or a.get('default'))
        world = values['world_name']
        assert world.startswith('worlds/'), world
        assert os.path.isfile(os.path.join(worlds, world[len('worlds/') :])), world
    range_world = tmp_path / 'gazebo_plugins' / 'test' / 'test_worlds' / 'gazebo_ros_range.world'
    assert range_world.is_file()
    assert _args(launch / 'range_world.launch')['world'] == 'gazebo_ros_range'
