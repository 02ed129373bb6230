"""Franka Emika (franka_ros): franka_gazebo's FrankaHWSim and FrankaGripperSim, franka_control's
FrankaStateController, franka_hw's state and model interfaces (docs/franka.md).

- ``hw_sim``: FrankaHWSim, the RobotHWSim of ``<robotSimType>franka_gazebo/FrankaHWSim``;
- ``interfaces``: FrankaStateInterface and FrankaModelInterface, ROS-free;
- ``state_controller``: franka_control/FrankaStateController;
- ``gripper_sim``: franka_gazebo/FrankaGripperSim (franka_gripper's actions).

This file is the room's manifest (see vendors/__init__.py): it imports nothing else.
"""

from .. import Room

ROOM = Room(
    'franka',
    robot_hw_sims={'franka_gazebo/FrankaHWSim': 'hw_sim:FrankaHWSim'},
    controllers=('state_controller:FrankaStateController', 'gripper_sim:FrankaGripperSim'),
    # franka_ros's example controllers are C++ plugins only: no Python manager loads them
    cpp_only_packages={'franka_example_controllers': 'franka_ros'},
)
