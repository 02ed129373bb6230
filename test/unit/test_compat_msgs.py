"""gazebo_msgs, control_msgs and controller_manager_msgs as the workspace builds them
(tools/compat_msgs via tools/make_compat_packages.py): every type has upstream's md5sum,
so a client built against upstream's definitions talks to arm1 and arm1 to it.

Needs the built workspace (tools/ws-run python -m pytest test/unit/test_compat_msgs.py).
"""

from __future__ import annotations

import os
import sys
from typing import Dict

import pytest
from helpers import COMPAT_PACKAGES as PACKAGES
from helpers import DEFINITIONS, generated_class, types_defined_here

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# md5s listed in shared/reference (ros-controllers-semantics.md §4, gazebo-ros-api.md §2).
REFERENCE = {
    'control_msgs/FollowJointTrajectoryAction': 'bc4f9b743838566551c0390c65f1a248',
    'control_msgs/FollowJointTrajectoryActionFeedback': 'd8920dc4eae9fc107e00999cce4be641',
    'control_msgs/FollowJointTrajectoryActionGoal': 'cff5c1d533bf2f82dd0138d57f4304bb',
    'control_msgs/FollowJointTrajectoryActionResult': 'c4fb3b000dc9da4fd99699380efcc5d9',
    'control_msgs/FollowJointTrajectoryFeedback': '10817c60c2486ef6b33e97dcd87f4474',
    'control_msgs/FollowJointTrajectoryGoal': '69636787b6ecbde4d61d711979bc7ecb',
    'control_msgs/FollowJointTrajectoryResult': '493383b18409bfb604b4e26c676401d2',
    'control_msgs/GripperCommand': '680acaff79486f017132a7f198d40f08',
    'control_msgs/GripperCommandAction': '950b2a6ebe831f5d4f4ceaba3d8be01e',
    'control_msgs/GripperCommandActionFeedback': '653dff30c045f5e6ff3feb3409f4558d',
    'control_msgs/GripperCommandActionGoal': 'aa581f648a35ed681db2ec0bf7a82bea',
    'control_msgs/GripperCommandActionResult': '143702cb2df0f163c5283cedc5efc6b6',
    'control_msgs/GripperCommandFeedback': 'e4cbff56d3562bcf113da5a5adeef91f',
    'control_msgs/GripperCommandGoal': '86fd82f4ddc48a4cb6856cfa69217e43',
    'control_msgs/GripperCommandResult': 'e4cbff56d3562bcf113da5a5adeef91f',
    'control_msgs/JointControllerState': '987ad85e4756f3aef7f1e5e7fe0595d1',
    'control_msgs/JointTolerance': 'f544fe9c16cf04547e135dd6063ff5be',
    'control_msgs/JointTrajectoryControllerState': '10817c60c2486ef6b33e97dcd87f4474',
    'control_msgs/PidState': 'b138ec00e886c10e73f27e8712252ea6',
    'control_msgs/QueryTrajectoryState': 'ec93cdecbd8062d761aa52b7c90cd44b',
    'controller_manager_msgs/ControllerState': 'aeb6b261d97793ab74099a3740245272',
    'controller_manager_msgs/ControllerStatistics': '697780c372c8d8597a1436d0e2ad3ba8',
    'controller_manager_msgs/ControllersStatistics': 'a154c347736773e3700d1719105df29d',
    'controller_manager_msgs/HardwareInterfaceResources': 'f25b55cbf1d1f76e82e5ec9e83f76258',
    'controller_manager_msgs/ListControllerTypes': 'c1d4cd11aefa9f97ba4aeb5b33987f4e',
    'controller_manager_msgs/ListControllers': '1341feb2e63fa791f855565d0da950d8',
    'controller_manager_msgs/LoadController': '647e5c54b8d6468952d8d31f1efe96c0',
    'controller_manager_msgs/ReloadControllerLibraries': '40e8c411fd1797d2e2c486018f846040',
    'controller_manager_msgs/SwitchController': 'b29a7abc673b2c54c14b54e50f8d06a5',
    'controller_manager_msgs/UnloadController': '647e5c54b8d6468952d8d31f1efe96c0',
    'gazebo_msgs/ApplyBodyWrench': '585b9f9618aa0581b207e2f2d90866bc',
    'gazebo_msgs/ApplyJointEffort': 'c0039811b8cc919490b3cff748cdf46b',
    'gazebo_msgs/BodyRequest': '5eade9afe7f232d78005bd0cafeab755',
    'gazebo_msgs/ContactState': '48c0ffb054b8c444f870cecea1ee50d9',
    'gazebo_msgs/ContactsState': 'acbcb1601a8e525bf72509f18e6f668d',
    'gazebo_msgs/DeleteLight': 'ae11ea8100d536d5b92c2b5917abf912',
    'gazebo_msgs/DeleteModel': '9ce56b4e9e54616de25d796dc972a262',
    'gazebo_msgs/GetJointProperties': '7b30be900f50aa21efec4a0ec92d91c9',
    'gazebo_msgs/GetLightProperties': 'df2cef87e13e2e6990e81e8aaa454c19',
    'gazebo_msgs/GetLinkProperties': '0e06a70386d0ee3fb880c02f23fcd821',
    'gazebo_msgs/GetLinkState': '09d6c98cce97b35f7ab9bd70300657ab',
    'gazebo_msgs/GetModelProperties': '5717f7bd34ed990fa80e28b3015027a3',
    'gazebo_msgs/GetModelState': '4c515e936d3319c9610c559c60bfc3d4',
    'gazebo_msgs/GetPhysicsProperties': '575a5e74786981b7df2e3afc567693a6',
    'gazebo_msgs/GetWorldProperties': '36bb0f2eccf4d8be971410c22818ba3f',
    'gazebo_msgs/JointRequest': '0be1351618e1dc030eb7959d9a4902de',
    'gazebo_msgs/LinkState': '0818ebbf28ce3a08d48ab1eaa7309ebe',
    'gazebo_msgs/LinkStates': '48c080191eb15c41858319b4d8a609c2',
    'gazebo_msgs/ModelState': '9330fd35f2fcd82d457e54bd54e10593',
    'gazebo_msgs/ModelStates': '48c080191eb15c41858319b4d8a609c2',
    'gazebo_msgs/ODEJointProperties': '1b744c32a920af979f53afe2f9c3511f',
    'gazebo_msgs/ODEPhysics': '667d56ddbd547918c32d1934503dc335',
    'gazebo_msgs/PerformanceMetrics': '884f71fd5037b886ec5e126b83c4425a',
    'gazebo_msgs/SensorPerformanceMetric': '01762ded18cfe9ebc7c8222667c99547',
    'gazebo_msgs/SetJointProperties': '15a76e921b1410c698d82782ea5fa370',
    'gazebo_msgs/SetLightProperties': 'e6f13430c57278bb364aca53a1bf5ebf',
    'gazebo_msgs/SetLinkProperties': 'd534ce1b36ee99de0ffa806c3a6348f0',
    'gazebo_msgs/SetLinkState': '8a5146eb66ae4d26b0860b08f3f271be',
    'gazebo_msgs/SetModelConfiguration': '10e3139d3b669c40afc057d38956fff7',
    'gazebo_msgs/SetModelState': '5b3ab0281d4f5445def017e3a2e4a07b',
    'gazebo_msgs/SetPhysicsProperties': '97e2057080558ce4730434b5fae75c91',
    'gazebo_msgs/SpawnModel': '9ed9c82c96abe1a00c3e8cdaeee24413',
    'gazebo_msgs/WorldState': 'de1a9de3ab7ba97ac0e9ec01a4eb481e',
    'trajectory_msgs/JointTrajectory': '65b4f94a94d1ed67169da35a02f33d3f',
    'trajectory_msgs/JointTrajectoryPoint': 'f3cd1e1c4d320c79d6985c904ae5dcd3',
}
# Not listed there: computed with genmsg from upstream's own files (control_msgs
# kinetic-devel, gazebo_msgs noetic-devel) and matching the md5s in generated code
# that public projects publish for these types.
UPSTREAM = {
    'control_msgs/JointJog': '1685da700c8c2e1254afc92a5fb89c96',
    'control_msgs/JointTrajectoryAction': 'a04ba3ee8f6a2d0985a6aeaf23d9d7ad',
    'control_msgs/JointTrajectoryActionFeedback': 'aae20e09065c3809e8a8e87c4c8953fd',
    'control_msgs/JointTrajectoryActionGoal': 'a99e83ef6185f9fdd7693efe99623a86',
    'control_msgs/JointTrajectoryActionResult': '1eb06eeff08fa7ea874431638cb52332',
    'control_msgs/JointTrajectoryFeedback': 'd41d8cd98f00b204e9800998ecf8427e',
    'control_msgs/JointTrajectoryGoal': '2a0eff76c870e8595636c2a562ca298e',
    'control_msgs/JointTrajectoryResult': 'd41d8cd98f00b204e9800998ecf8427e',
    'control_msgs/PointHeadAction': '7252920f1243de1b741f14f214125371',
    'control_msgs/PointHeadActionFeedback': '33c9244957176bbba97dd641119e8460',
    'control_msgs/PointHeadActionGoal': 'b53a8323d0ba7b310ba17a2d3a82a6b8',
    'control_msgs/PointHeadActionResult': '1eb06eeff08fa7ea874431638cb52332',
    'control_msgs/PointHeadFeedback': 'cce80d27fd763682da8805a73316cab4',
    'control_msgs/PointHeadGoal': '8b92b1cd5e06c8a94c917dc3209a4c1d',
    'control_msgs/PointHeadResult': 'd41d8cd98f00b204e9800998ecf8427e',
    'control_msgs/QueryCalibrationState': '28af3beedcb84986b8e470dc5470507d',
    'control_msgs/SingleJointPositionAction': 'c4a786b7d53e5d0983decf967a5a779e',
    'control_msgs/SingleJointPositionActionFeedback': '3503b7cf8972f90d245850a5d8796cfa',
    'control_msgs/SingleJointPositionActionGoal': '4b0d3d091471663e17749c1d0db90f61',
    'control_msgs/SingleJointPositionActionResult': '1eb06eeff08fa7ea874431638cb52332',
    'control_msgs/SingleJointPositionFeedback': '8cee65610a3d08e0a1bded82f146f1fd',
    'control_msgs/SingleJointPositionGoal': 'fbaaa562a23a013fd5053e5f72cbb35c',
    'control_msgs/SingleJointPositionResult': 'd41d8cd98f00b204e9800998ecf8427e',
    'gazebo_msgs/SetJointTrajectory': '88f5c10979e3f9649d5ae87a3b12aa65',
}

ALL: Dict[str, str] = {**REFERENCE, **UPSTREAM}


@pytest.mark.parametrize('type_name', sorted(ALL))
def test_generated_type_has_upstream_md5sum(type_name: str) -> None:
    cls = generated_class(type_name)
    assert cls._type == type_name
    assert cls._md5sum == ALL[type_name]


def test_every_definition_file_is_checked_and_none_is_missing() -> None:
    upstream_types = sorted(t for t in ALL if not t.startswith('trajectory_msgs/'))
    assert types_defined_here() == upstream_types


def test_classes_clients_use_import_with_upstream_constants() -> None:
    from control_msgs.msg import (
        FollowJointTrajectoryAction,
        FollowJointTrajectoryGoal,
        FollowJointTrajectoryResult,
        JointControllerState,
    )
    from controller_manager_msgs.srv import SwitchController, SwitchControllerRequest
    from gazebo_msgs.srv import GetJointPropertiesResponse, SpawnModel, SpawnModelResponse

    assert SpawnModel._request_class._type == 'gazebo_msgs/SpawnModelRequest'
    assert SpawnModelResponse().__slots__ == ['success', 'status_message']
    assert SwitchController._response_class().__slots__ == ['ok']
    assert (SwitchControllerRequest.BEST_EFFORT, SwitchControllerRequest.STRICT) == (1, 2)
    assert FollowJointTrajectoryResult.GOAL_TOLERANCE_VIOLATED == -5
    assert FollowJointTrajectoryAction().action_goal.goal.__class__ is FollowJointTrajectoryGoal
    assert GetJointPropertiesResponse.UNIVERSAL == 5
    assert JointControllerState().__slots__[-1] == 'antiwindup'


def test_arm1_keeps_no_copies_of_upstream_types() -> None:
    # Only arm1's own arm_mover service is left in arm1's msg/ and srv/.
    own = [
        os.path.join(d, f)
        for d in ('msg', 'srv')
        if os.path.isdir(os.path.join(REPO_ROOT, d))
        for f in os.listdir(os.path.join(REPO_ROOT, d))
    ]
    assert own == ['srv/GoToPosition.srv']


def test_generator_writes_each_definition_and_leaves_unchanged_files_alone(tmp_path) -> None:
    sys.path.insert(0, os.path.join(REPO_ROOT, 'tools'))
    try:
        import make_compat_packages
    finally:
        sys.path.pop(0)
    make_compat_packages.make(str(tmp_path))
    for pkg in PACKAGES:
        cmake = (tmp_path / pkg / 'CMakeLists.txt').read_text()
        for kind in ('msg', 'srv', 'action'):
            folder = os.path.join(DEFINITIONS, pkg, kind)
            for fname in os.listdir(folder) if os.path.isdir(folder) else []:
                with open(os.path.join(folder, fname)) as f:
                    assert (tmp_path / pkg / kind / fname).read_text() == f.read()
                assert '\n  %s' % fname in cmake, (pkg, fname)
    stale = tmp_path / 'gazebo_msgs' / 'srv' / 'Gone.srv'
    stale.write_text('---\n')
    mtimes = {p: p.stat().st_mtime_ns for p in tmp_path.rglob('*') if p.is_file() and p != stale}
    make_compat_packages.make(str(tmp_path))
    assert not stale.exists()
    assert {p: p.stat().st_mtime_ns for p in mtimes} == mtimes
