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


def test_no_stand_in_names_the_arm1_package(tmp_path) -> None:
    """A user's own package named arm1 (the tutorial's name) overlays ours: a stand-in that
    depended on, found or started anything of package arm1 would get theirs (issue 29)."""
    _make(tmp_path)
    offending = []
    for root, _, files in os.walk(str(tmp_path)):
        for name in files:
            path = os.path.join(root, name)
            with open(path, encoding='utf-8', errors='replace') as f:
                text = f.read()
            for needle in ('$(find arm1)', 'pkg="arm1"', '<exec_depend>arm1<', '<depend>arm1<'):
                if needle in text:
                    offending.append('%s: %s' % (os.path.relpath(path, str(tmp_path)), needle))
    assert offending == []
    world = ET.parse(str(tmp_path / 'gazebo_ros' / 'launch' / 'world_node.launch'))
    (node,) = list(world.getroot().iter('node'))
    assert (node.get('pkg'), node.get('type')) == ('gazebo_ros', 'gzserver')


def test_pid_gains_are_control_toolbox_parameters(tmp_path) -> None:
    """The live PID gains' dynamic_reconfigure type is upstream's control_toolbox/Parameters,
    generated in the control_toolbox stand-in (not in package arm1)."""
    _make(tmp_path)
    pkg = tmp_path / 'control_toolbox'
    assert (pkg / 'cfg' / 'Parameters.cfg').is_file()
    cmake = (pkg / 'CMakeLists.txt').read_text()
    assert 'generate_dynamic_reconfigure_options(cfg/Parameters.cfg)' in cmake
    assert cmake.index('generate_dynamic_reconfigure_options') < cmake.index('catkin_package(')
    assert '<depend>dynamic_reconfigure</depend>' in (pkg / 'package.xml').read_text()
