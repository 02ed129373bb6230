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
