"""The hardware sims by gazebo_ros_control's ``<robotSimType>``, as its pluginlib lookup.

gazebo_ros_control builds the RobotHWSim class its plugin's ``<robotSimType>`` names
(``gazebo_ros_control/DefaultRobotHWSim`` unless told). Here each is a class of the
RobotHWSim Protocol (control/interfaces.py) built as ``cls(description, robot, period)``:
the default is registered below like any other, vendors' come from their rooms' manifests
(vendors/__init__.py), imported when a robot first asks for them.

A type nobody offers gets the default, as before, and description.gazebo_plugins says so
in the spawn's warning (Gazebo would fail to load the class).
"""

from __future__ import annotations

from typing import Callable, Dict

from ..control.interfaces import RobotHWSim
from ..description.gazebo_plugins import DEFAULT_ROBOT_SIM_TYPE
from ..description.urdf_model import RobotModel
from ..physics.robot import Robot
from ..vendors import load, robot_sim_types
from .robot_hw_sim import DefaultRobotHWSim

# (description, simulated robot, physics step in s) -> the hardware sim
RobotHWSimClass = Callable[[RobotModel, Robot, float], RobotHWSim]

BUILT_IN: Dict[str, RobotHWSimClass] = {DEFAULT_ROBOT_SIM_TYPE: DefaultRobotHWSim}


def robot_hw_sim_class(sim_type: str) -> RobotHWSimClass:
    """The class ``<robotSimType>`` names; the default for a type nobody offers."""
    built_in = BUILT_IN.get(sim_type)
    if built_in is not None:
        return built_in
    offered = robot_sim_types().get(sim_type)
    if offered is None:
        return DefaultRobotHWSim
    room, ref = offered
    cls: RobotHWSimClass = load(room, ref)
    return cls


def make_robot_hw_sim(
    sim_type: str, description: RobotModel, robot: Robot, period: float
) -> RobotHWSim:
    """The hardware sim of a spawned model; RobotHWSimError says why it cannot be one."""
    return robot_hw_sim_class(sim_type)(description, robot, period)
