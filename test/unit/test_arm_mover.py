"""arm_nodes.py, arm_mover's part: joint ranges from the URDF, clamping, arrival."""

import math

import pytest

from _arm1sim.goal.arm_mover import clamp_request, describe, joint_limits, off_target

ARM1_RANGES = {
    'joint1': (-1.57, 1.57),
    'joint2': (0.01, 1.57),
    'joint3': (-1.0, 1.57),
    'joint4': (-0.8, 1.57),
}


def test_default_ranges_are_the_urdf_limits(arm1_urdf):
    assert joint_limits(arm1_urdf) == ARM1_RANGES  # fixed joints (camera, base) have none


def test_in_range_requests_pass_unchanged():
    req = {'joint1': 0.5, 'joint2': 0.01, 'joint3': 1.57, 'joint4': 0.0}
    assert clamp_request(req, ARM1_RANGES) == (req, [])


def test_out_of_range_values_are_clamped_with_a_warning_naming_joint_and_range():
    targets, warnings = clamp_request({'joint1': 3.0, 'joint2': -1.0, 'joint3': 0.2}, ARM1_RANGES)
    assert targets == {'joint1': 1.57, 'joint2': 0.01, 'joint3': 0.2}
    assert warnings == [
        'joint1 = 3.000 is out of range [-1.570, 1.570]: clamped to 1.570',
        'joint2 = -1.000 is out of range [0.010, 1.570]: clamped to 0.010',
    ]


@pytest.mark.parametrize('bad', [math.nan, math.inf])
def test_non_finite_requests_are_refused(bad):
    with pytest.raises(ValueError, match='joint2'):
        clamp_request({'joint1': 0.0, 'joint2': bad}, ARM1_RANGES)


def test_arrival_within_tolerance():
    targets = {'joint1': 1.0, 'joint2': 0.5}
    assert off_target({'joint1': 0.96, 'joint2': 0.54, 'joint3': 9}, targets, 0.05) == []
    assert off_target({'joint1': 0.9, 'joint2': 0.5}, targets, 0.05) == ['joint1']
    assert off_target({'joint1': math.nan, 'joint2': 0.5}, targets, 0.05) == ['joint1']
    assert off_target({'joint2': 0.5}, targets, 0.05) == ['joint1']  # missing: not arrived


def test_timeout_text_says_where_the_joints_are():
    assert (
        describe(['joint2', 'joint4'], {'joint2': 1.5693}, {'joint2': 3.0, 'joint4': 0.1})
        == 'joint2 at 1.569 (target 3.000), joint4 at unknown (target 0.100)'
    )
