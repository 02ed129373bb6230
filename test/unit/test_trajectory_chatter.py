"""arm1's trajectory controller started while the arm still falls after spawn (as the spawner
may start it): with the URDF's 0.5 rad/s, the effort saturation's velocity cut holds joints
2-4 in a step-rate chatter after a goal, as Gazebo's EffortJointSaturationHandle would;
config/controllers_trajectory.yaml lifts the cut with joint_limits parameters and the arm
comes to rest (docs/controllers.md, "Trajectories")."""

import pytest
from helpers import JOINTS, largest_speed_at_the_end, trajectory_params

S = 10**9


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
