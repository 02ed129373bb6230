"""franka_msgs and franka_gripper as the workspace builds them (tools/compat_msgs via
tools/make_compat_packages.py): every type has the md5sum upstream's own definitions give
(franka_ros noetic-devel 35e1f654, computed with genmsg and genaction from its files), so
franka_ros's clients and arm1's FrankaHWSim talk to each other.

Needs the built workspace (tools/ws-run python -m pytest test/unit/test_compat_franka_msgs.py).
"""

from __future__ import annotations

import pytest
from helpers import generated_class, types_defined_here

UPSTREAM = {
    'franka_gripper/GraspAction': '6f89449359949eaf1f0fef57b7e0db2a',
    'franka_gripper/GraspActionFeedback': 'aae20e09065c3809e8a8e87c4c8953fd',
    'franka_gripper/GraspActionGoal': '7bd1a6e7f94ef15bb6dd05cb170e7909',
    'franka_gripper/GraspActionResult': '89dbc4e75593b525bbbea3a150532ed6',
    'franka_gripper/GraspEpsilon': '95b2c5464a6f679bd1dacaf86414f095',
    'franka_gripper/GraspFeedback': 'd41d8cd98f00b204e9800998ecf8427e',
    'franka_gripper/GraspGoal': '627a0f0b10ad0c919fbd62b0b3427e63',
    'franka_gripper/GraspResult': '45872d25d65c97743cc71afc6d4e884d',
    'franka_gripper/HomingAction': 'f37964fcdec026d9507d088d32b65b38',
    'franka_gripper/HomingActionFeedback': 'aae20e09065c3809e8a8e87c4c8953fd',
    'franka_gripper/HomingActionGoal': '4b30be6cd12b9e72826df56b481f40e0',
    'franka_gripper/HomingActionResult': '89dbc4e75593b525bbbea3a150532ed6',
    'franka_gripper/HomingFeedback': 'd41d8cd98f00b204e9800998ecf8427e',
    'franka_gripper/HomingGoal': 'd41d8cd98f00b204e9800998ecf8427e',
    'franka_gripper/HomingResult': '45872d25d65c97743cc71afc6d4e884d',
    'franka_gripper/MoveAction': '85e8e11f508e446b706022926779afee',
    'franka_gripper/MoveActionFeedback': 'aae20e09065c3809e8a8e87c4c8953fd',
    'franka_gripper/MoveActionGoal': 'f8907a1e7bb902f2e4c7db8e1cf3d24f',
    'franka_gripper/MoveActionResult': '89dbc4e75593b525bbbea3a150532ed6',
    'franka_gripper/MoveFeedback': 'd41d8cd98f00b204e9800998ecf8427e',
    'franka_gripper/MoveGoal': 'd16050a0fe85f1c2cb8347c99678362e',
    'franka_gripper/MoveResult': '45872d25d65c97743cc71afc6d4e884d',
    'franka_gripper/StopAction': 'f37964fcdec026d9507d088d32b65b38',
    'franka_gripper/StopActionFeedback': 'aae20e09065c3809e8a8e87c4c8953fd',
    'franka_gripper/StopActionGoal': '4b30be6cd12b9e72826df56b481f40e0',
    'franka_gripper/StopActionResult': '89dbc4e75593b525bbbea3a150532ed6',
    'franka_gripper/StopFeedback': 'd41d8cd98f00b204e9800998ecf8427e',
    'franka_gripper/StopGoal': 'd41d8cd98f00b204e9800998ecf8427e',
    'franka_gripper/StopResult': '45872d25d65c97743cc71afc6d4e884d',
    'franka_msgs/ErrorRecoveryAction': 'd5a016b49f278075666fbc901debbd08',
    'franka_msgs/ErrorRecoveryActionFeedback': 'aae20e09065c3809e8a8e87c4c8953fd',
    'franka_msgs/ErrorRecoveryActionGoal': '4b30be6cd12b9e72826df56b481f40e0',
    'franka_msgs/ErrorRecoveryActionResult': '1eb06eeff08fa7ea874431638cb52332',
    'franka_msgs/ErrorRecoveryFeedback': 'd41d8cd98f00b204e9800998ecf8427e',
    'franka_msgs/ErrorRecoveryGoal': 'd41d8cd98f00b204e9800998ecf8427e',
    'franka_msgs/ErrorRecoveryResult': 'd41d8cd98f00b204e9800998ecf8427e',
    'franka_msgs/Errors': '082e9a670c96d8bc64b53e32777458e7',
    'franka_msgs/FrankaState': '431567d5df6caf4e4dd7385f25cb71ee',
    'franka_msgs/SetCartesianImpedance': 'c648a0b1340a53eac0c535568e9b5c60',
    'franka_msgs/SetEEFrame': '459aea8fa6dbdd34ba4bc52d3eddbacf',
    'franka_msgs/SetForceTorqueCollisionBehavior': 'b1e592d1b6960bc05e6e3cba1eb02349',
    'franka_msgs/SetFullCollisionBehavior': 'c6fef9a8ad446db9a39cca3b7bc200d8',
    'franka_msgs/SetJointImpedance': 'f11c4defa2a13040512214f9d77dc982',
    'franka_msgs/SetKFrame': '11b22d30e6a11a7b51828be575a77359',
    'franka_msgs/SetLoad': 'c9a8ec436164dd9cbc1e5e137d358e0b',
}


@pytest.mark.parametrize('type_name', sorted(UPSTREAM))
def test_generated_type_has_upstream_md5sum(type_name: str) -> None:
    cls = generated_class(type_name)
    assert cls._type == type_name
    assert cls._md5sum == UPSTREAM[type_name]


def test_every_franka_definition_file_is_checked() -> None:
    assert types_defined_here(('franka_msgs', 'franka_gripper')) == sorted(UPSTREAM)


def test_franka_state_keeps_upstreams_robot_mode_constants() -> None:
    from franka_msgs.msg import FrankaState

    assert (FrankaState.ROBOT_MODE_IDLE, FrankaState.ROBOT_MODE_MOVE) == (1, 2)
    assert FrankaState.ROBOT_MODE_AUTOMATIC_ERROR_RECOVERY == 6
