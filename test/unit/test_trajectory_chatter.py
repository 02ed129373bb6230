"""arm1's trajectory controller started while the arm still falls after spawn (as the spawner
may start it): with the URDF's 0.5 rad/s, the effort saturation's velocity cut holds joints
2-4 in a step-rate chatter after a goal, as Gazebo's EffortJointSaturationHandle would;
config/controllers_trajectory.yaml lifts the cut with joint_limits parameters and the arm
comes to rest (docs/controllers.md, "Trajectories")."""

import os

import pytest
import yaml
from conftest import REPO_ROOT, FakeRos

from _arm1sim.control.controller_manager import ControllerManager
from _arm1sim.control.switching import switch_while_updating
from _arm1sim.description.sdf_world import parse_world
from _arm1sim.sim.simulation import Simulation

S = 10**9
JOINTS = ['joint1', 'joint2', 'joint3', 'joint4']
START_STEP = 50  # the controller starts 50 ms after spawn, mid-fall


def trajectory_params():
    with open(os.path.join(REPO_ROOT, 'config', 'controllers_trajectory.yaml')) as f:
        return yaml.safe_load(f)


def largest_speed_at_the_end(arm1_urdf, joint_limits):
    """The test's first goal from a mid-fall start; the joints' largest |velocity| over the
    last half second of 2 s after the trajectory's end."""
    ros = FakeRos(trajectory_params())
    with open(os.path.join(REPO_ROOT, 'worlds', 'willow_garage.world')) as f:
        sim = Simulation(parse_world(f.read()))
    try:
        model = sim.spawn_urdf(
            'arm1',
            arm1_urdf,
            robot_namespace='/arm1',
            find_package=lambda pkg: REPO_ROOT,
            controller_manager_factory=lambda hw, ns: ControllerManager(hw, ros.node_handle, ns),
        )
        model.hw.set_joint_limits(joint_limits)
        cm = model.controller_manager
        for _ in range(START_STEP):
            sim.step()
        cm.load_controller('arm_controller')
        assert switch_while_updating(cm, ['arm_controller'], [], sim.step, 1, poll=0.0005)[0]
        for _ in range(200):
            sim.step()
        points = [
            dict(positions=[0.5, 0.7, 0.3, 0.2], time_from_start=2 * S),
            dict(positions=[-0.4, 1.0, 0.1, -0.1], time_from_start=4 * S),
        ]
        cm.controller('arm_controller').on_command(dict(stamp=0, joint_names=JOINTS, points=points))
        index = model.robot.indices(JOINTS)
        largest = 0.0
        for k in range(6000):
            sim.step()
            if k >= 5500:
                largest = max(largest, max(abs(v) for _, v in model.robot.read(index)))
        return largest
    finally:
        sim.close()


@pytest.mark.parametrize('lifted', [False, True], ids=['urdf_limits', 'yaml_joint_limits'])
def test_the_velocity_cut_can_hold_the_arm_in_chatter_and_the_yaml_lifts_it(arm1_urdf, lifted):
    limits = trajectory_params()['arm1']['joint_limits'] if lifted else {}
    if lifted:
        assert all(limits[j] == {'has_velocity_limits': False} for j in JOINTS)
    speed = largest_speed_at_the_end(arm1_urdf, limits)
    if lifted:
        assert speed < 0.2, speed  # under the yaml's stopped_velocity_tolerance: at rest
    else:
        assert speed > 1.0, speed  # Gazebo's semantics: the chatter (about 2 rad/s)
