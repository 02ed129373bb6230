"""gazebo_ros's launch files, written into the gazebo_ros stand-in by make_compat_packages.py.

The same files and arguments as gazebo_ros (noetic-devel) ships, so launch files that
include them (with any of their arguments) run unchanged: empty_world.launch hands its
arguments to world_node.launch, written here from arm1's launch/empty_world.launch with
gazebo_ros's own gzserver (so nothing in gazebo_ros names the package arm1, which a user's
own package of that name would hide); the world node applies or explains each argument.
The world launch files name worlds of arm1's own with the same meaning (gazebo_share/worlds,
found on GAZEBO_RESOURCE_PATH as Gazebo's are).
"""

from __future__ import annotations

import os
from typing import Callable, List, Tuple

ARM1 = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GAZEBO_SHARE_WORLDS = os.path.join(ARM1, 'gazebo_share', 'worlds')
ARM1_WORLD_LAUNCH = os.path.join(ARM1, 'launch', 'empty_world.launch')
ARM1_GZSERVER = 'pkg="arm1" type="gzserver"'

# gazebo_ros/launch/empty_world.launch's 17 arguments and defaults, in its order.
EMPTY_WORLD_ARGS: List[Tuple[str, str]] = [
    ('paused', 'false'),
    ('use_sim_time', 'true'),
    ('extra_gazebo_args', ''),
    ('gui', 'true'),
    ('recording', 'false'),
    ('headless', 'false'),  # inert upstream too (gazebo_ros_pkgs issue 491)
    ('debug', 'false'),
    ('physics', 'ode'),
    ('verbose', 'false'),
    ('output', 'screen'),
    ('world_name', 'worlds/empty.world'),  # on GAZEBO_RESOURCE_PATH: ground plane and sun
    ('respawn_gazebo', 'false'),
    ('use_clock_frequency', 'false'),
    ('pub_clock_frequency', '100'),
    ('enable_ros_network', 'true'),
    ('server_required', 'false'),
    ('gui_required', 'false'),
]
# arm1's own, beyond upstream's (launch/empty_world.launch documents them)
ARM1_ARGS: List[Tuple[str, str]] = [
    ('real_time_factor', ''),
    ('real_time_update_rate', ''),
    ('lockstep', 'false'),
    ('web', 'false'),  # the browser view (docs/web-view.md)
    ('web_host', '127.0.0.1'),
    ('web_port', '8080'),
]

EMPTY_WORLD = '''<launch>
  <!-- gazebo_ros/launch/empty_world.launch: upstream's 17 arguments (then arm1's own),
       all handed to arm1's pybullet world, which applies each or logs once why not. -->
{args}
  <include file="$(find gazebo_ros)/launch/world_node.launch" pass_all_args="true"/>
</launch>
'''

# willowgarage, shapes, mud and rubble_world.launch: empty_world.launch with a world_name
# and these values, as upstream's pass them.
FIXED_WORLD = '''<launch>
  <!-- gazebo_ros/launch/{name}_world.launch: empty_world.launch with {world}. -->
  <include file="$(find gazebo_ros)/launch/empty_world.launch">
    <arg name="world_name" value="{world}"/>
    <arg name="paused" value="false"/>
    <arg name="use_sim_time" value="true"/>
    <arg name="gui" value="true"/>
    <arg name="headless" value="false"/>
    <arg name="recording" value="false"/>
    <arg name="debug" value="false"/>
  </include>
</launch>
'''
FIXED_WORLDS = {
    'willowgarage': 'worlds/willowgarage.world',
    'shapes': 'worlds/shapes.world',
    'mud': 'worlds/mud.world',
    'rubble': 'worlds/rubble.world',
}

# range_world.launch: its own arguments, a world from gazebo_plugins' test worlds by name.
RANGE_ARGS = [
    ('paused', 'false'),
    ('use_sim_time', 'true'),
    ('extra_gazebo_args', ''),
    ('gui', 'true'),
    ('debug', 'false'),
    ('physics', 'ode'),
    ('verbose', 'true'),
    ('output', 'screen'),
    ('world', 'gazebo_ros_range'),
]
RANGE_WORLD = '''<launch>
  <!-- gazebo_ros/launch/range_world.launch: $(find gazebo_plugins)/test/test_worlds/WORLD.world -->
{args}
  <include file="$(find gazebo_ros)/launch/empty_world.launch">
    <arg name="world_name" value="$(find gazebo_plugins)/test/test_worlds/$(arg world).world"/>
{passed}
  </include>
</launch>
'''

# elevator_world.launch upstream starts gzserver itself with these arguments; here it
# hands them to empty_world.launch, which does the same.
ELEVATOR_ARGS = [
    ('paused', 'false'),
    ('use_sim_time', 'true'),
    ('extra_gazebo_args', ''),
    ('gui', 'true'),
    ('recording', 'false'),
    ('headless', 'false'),
    ('debug', 'false'),
    ('physics', 'ode'),
    ('verbose', 'true'),
    ('output', 'screen'),
    ('world_name', 'worlds/elevator_ros.world'),
]
ELEVATOR_WORLD = '''<launch>
  <!-- gazebo_ros/launch/elevator_world.launch: its arguments, through empty_world.launch. -->
{args}
  <include file="$(find gazebo_ros)/launch/empty_world.launch">
{passed}
  </include>
</launch>
'''


def _args(args: List[Tuple[str, str]]) -> str:
    return '\n'.join('  <arg name="%s" default="%s"/>' % a for a in args)


def _passed(args: List[Tuple[str, str]], leave_out: Tuple[str, ...] = ()) -> str:
    return '\n'.join(
        '    <arg name="%s" value="$(arg %s)"/>' % (n, n) for n, _ in args if n not in leave_out
    )


def world_node_launch() -> str:
    """arm1's launch/empty_world.launch, starting gazebo_ros's gzserver instead of arm1's."""
    with open(ARM1_WORLD_LAUNCH) as f:
        text = f.read()
    if text.count(ARM1_GZSERVER) != 1:
        raise ValueError('%s: expected one <node %s>' % (ARM1_WORLD_LAUNCH, ARM1_GZSERVER))
    return text.replace(ARM1_GZSERVER, 'pkg="gazebo_ros" type="gzserver"')


def make_gazebo_ros_launch(dest: str, write: Callable[..., None]) -> None:
    launch = os.path.join(dest, 'gazebo_ros', 'launch')
    write(os.path.join(launch, 'world_node.launch'), world_node_launch())
    write(
        os.path.join(launch, 'empty_world.launch'),
        EMPTY_WORLD.format(args=_args(EMPTY_WORLD_ARGS + ARM1_ARGS)),
    )
    for name, world in FIXED_WORLDS.items():
        write(
            os.path.join(launch, name + '_world.launch'), FIXED_WORLD.format(name=name, world=world)
        )
    write(
        os.path.join(launch, 'range_world.launch'),
        RANGE_WORLD.format(args=_args(RANGE_ARGS), passed=_passed(RANGE_ARGS, ('world',))),
    )
    write(
        os.path.join(launch, 'elevator_world.launch'),
        ELEVATOR_WORLD.format(args=_args(ELEVATOR_ARGS), passed=_passed(ELEVATOR_ARGS)),
    )
    # range_world.launch's default world, where upstream keeps it; ours is in gazebo_share
    with open(os.path.join(GAZEBO_SHARE_WORLDS, 'gazebo_ros_range.world')) as f:
        range_world = f.read()
    write(
        os.path.join(dest, 'gazebo_plugins', 'test', 'test_worlds', 'gazebo_ros_range.world'),
        range_world,
    )
