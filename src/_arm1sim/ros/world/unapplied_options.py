"""What gzserver's command line and gazebo_ros's empty_world.launch ask for that this world
cannot do, one log line each, so a launch file written for Gazebo runs and says what differs.

ROS-free: the world node hands in its parsed options and its private parameters.
"""

from __future__ import annotations

from typing import Any, List, Mapping, Sequence


def _true(value: Any) -> bool:
    return str(value).lower() in ('true', '1', 'yes')


def unapplied_options(
    physics: str, recording: bool, unknown: Sequence[str], params: Mapping[str, Any]
) -> List[str]:
    """One sentence per requested option that is accepted but not applied here. ``params``:
    the node's private parameters empty_world.launch sets (debug, gui_required,
    use_clock_frequency, pub_clock_frequency, enable_ros_network)."""
    notes: List[str] = []
    if physics != 'ode':
        notes.append(
            'physics %s: not applied, pybullet is the engine whatever the world asks for' % physics
        )
    if recording:
        notes.append(
            "recording (-r): Gazebo's state log is not written here; record topics with rosbag"
        )
    if unknown:
        notes.append(
            'gzserver options not applied here (extra_gazebo_args?): %s' % ' '.join(unknown)
        )
    if _true(params.get('debug', False)):
        notes.append(
            'debug: gzserver would run under gdb; this world is a Python process (use pdb)'
        )
    if _true(params.get('gui_required', False)):
        notes.append(
            'gui_required: there is no separate gzclient (gui:=true opens the window inside '
            'this process), so only server_required ends the launch'
        )
    if not _true(params.get('use_clock_frequency', True)):
        notes.append(
            'use_clock_frequency false: Gazebo would publish /clock every physics step; this '
            'world publishes it at pub_clock_frequency (%s Hz of sim time)'
            % params.get('pub_clock_frequency', 100)
        )
    if not _true(params.get('enable_ros_network', True)):
        notes.append(
            'enable_ros_network false: not applied, the /gazebo topics and services are '
            'offered all the same'
        )
    return notes
