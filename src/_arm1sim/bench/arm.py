"""arm1 as every measurement runs it: its world, URDF and controllers, in a namespace."""

from __future__ import annotations

from ..paths import repo_path

WORLD = repo_path('worlds', 'willow_garage.world')
XACRO = repo_path('urdf', 'arm1.urdf.xacro')
CONTROLLERS = repo_path('config', 'controllers.yaml')
NAMES = ['joint_state_controller'] + ['joint%d_position_controller' % i for i in range(1, 5)]
# The same arm driven as MoveIt drives it: one effort JointTrajectoryController.
TRAJECTORY_CONTROLLERS = repo_path('config', 'controllers_trajectory.yaml')
TRAJECTORY_NAMES = ['joint_state_controller', 'arm_controller']
JOINTS = ['joint1', 'joint2', 'joint3', 'joint4']
STEP = 0.001  # s, the world file's max_step_size


def arm1_urdf(namespace: str = '/arm1') -> str:
    """arm1's URDF (xacro expanded) with its control plugin in ``namespace``."""
    from ..ros.tools.xacro_bridge import expand

    xml = expand(XACRO)
    return xml.replace(
        '<robotNamespace>/arm1</robotNamespace>', '<robotNamespace>%s</robotNamespace>' % namespace
    )
