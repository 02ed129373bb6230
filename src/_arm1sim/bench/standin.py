"""The world node of gzserver in this process, with N arm1s and their controllers running,
and listeners in another process (as robot_state_publisher would be)."""

from __future__ import annotations

import subprocess
from typing import TYPE_CHECKING, List, Optional, Tuple

import yaml

from ..control.switching import SwitchRequest
from .arm import CONTROLLERS, NAMES, TRAJECTORY_CONTROLLERS, TRAJECTORY_NAMES, WORLD, arm1_urdf

if TYPE_CHECKING:
    from ..ros.world.world_node import WorldNode
    from ..sim.pacer import Pacer


def start_standin(
    arms: int,
    real_time_update_rate: Optional[float],
    lockstep: bool = False,
    trajectory: bool = False,
) -> Tuple[WorldNode, Pacer]:
    """``(world node, pacer)``: the world file with ``arms`` arm1s, each in /armK, all five
    controllers asked to start (they do at the first update of ``node.run``); ``lockstep``:
    physics waits for every camera frame (gzserver --lockstep); ``trajectory``: each arm
    driven by one JointTrajectoryController (config/controllers_trajectory.yaml) instead."""
    import rosparam
    import rospy

    from ..ros.world.world_node import parse_args, start_world

    argv = [WORLD] + (['--lockstep'] if lockstep else [])
    if real_time_update_rate is not None:
        argv += ['--real-time-update-rate', str(real_time_update_rate)]
    rosparam.set_param('/use_sim_time', 'true')  # as gazebo.launch sets it
    node, pacer = start_world(parse_args(argv))
    names = TRAJECTORY_NAMES if trajectory else NAMES
    with open(TRAJECTORY_CONTROLLERS if trajectory else CONTROLLERS) as f:
        params = yaml.safe_load(f)['arm1']
    managers = []
    for k in range(1, arms + 1):
        ns = '/arm%d' % k
        rospy.set_param(ns, params)
        model = node.spawn('arm%d' % k, arm1_urdf(ns), (0.4 * (k - 1), 0, 0), (0, 0, 0, 1))
        manager = model.controller_manager
        if manager is None:
            raise RuntimeError('arm1 came without its controller manager (gazebo_ros_control)')
        for name in names:
            manager.load_controller(name)
        managers.append(manager)
    # A switch waits for the next update: ask from threads, the world loop does it.
    for manager in managers:
        SwitchRequest(manager, names)
    return node, pacer


def listeners(
    arms: int, camera: bool = False, model_states: bool = False
) -> List[subprocess.Popen]:
    """A subscriber to every arm's joint_states in another process; one process for all, so
    that N arms do not bring N Python listeners. With ``camera``, it also watches arm1's
    camera, which makes the world render it; with ``model_states``, /gazebo/model_states
    (published before every step while subscribed, as Gazebo does)."""
    topics = ['/arm%d/joint_states' % k for k in range(1, arms + 1)]
    topics += ['/rgb_camera/image_raw'] if camera else []
    topics += ['/gazebo/model_states'] if model_states else []
    return [
        subprocess.Popen(
            ['rostopic', 'hz'] + topics, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL
        )
    ]
