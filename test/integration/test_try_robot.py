"""try_robot on a robot package of our own making (test/robots/mini_arm), shaped like a
vendor's: built unchanged in a throw-away workspace, its Gazebo bringup run headless, the
report checked (make test has no network, so the real robots are tried by hand).
"""

import json
import os
import subprocess
import sys

import pytest

from _arm1sim.tryout import workspace

HERE = os.path.dirname(os.path.abspath(__file__))
MINI_ARM = os.path.join(os.path.dirname(HERE), 'robots', 'mini_arm')


def tree(path):
    return sorted(
        os.path.relpath(os.path.join(root, f), path)
        for root, _, files in os.walk(path)
        for f in files
    )


@pytest.fixture(scope='module')
def run(tmp_path_factory):
    out = tmp_path_factory.mktemp('try_robot')
    ws = out / 'ws'
    before = tree(MINI_ARM)
    proc = subprocess.run(
        [
            sys.executable,
            '-m',
            '_arm1sim.tryout',
            MINI_ARM,
            'mini_arm',
            'mini_arm_gazebo.launch',
            '--out',
            str(out / 'report'),
            '--workspace',
            str(ws),
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        timeout=150,
    )
    with open(out / 'report' / 'report.json') as f:
        rep = json.load(f)
    return proc, rep, out, before


def test_builds_unchanged_in_its_own_workspace(run):
    proc, rep, out, before = run
    assert rep['build']['ok'], rep['build']
    assert rep['build']['packages'] == ['mini_arm']
    assert rep['build']['per_package'] == {'mini_arm': {'built': True}}
    assert os.path.islink(out / 'ws' / 'src' / 'mini_arm')
    assert os.path.exists(out / 'ws' / 'devel' / 'setup.bash')
    assert tree(MINI_ARM) == before, 'the checkout was changed'
    assert rep['launch']['args'] == ['gui:=false'], 'headless by its own gui arg'


def test_reports_models_controllers_and_plugins(run):
    proc, rep, out, before = run
    assert rep['bringup']['up'], rep['bringup']
    # worlds/empty.world found through GAZEBO_RESOURCE_PATH, as Gazebo finds it
    assert rep['models'] == ['ground_plane', 'mini_arm']
    assert list(rep['controller_managers']) == ['/'], 'spawn_model namespace: the caller\'s'
    states = {c['name']: (c['type'], c['state']) for c in rep['controller_managers']['/']}
    assert states == {
        'joint_state_controller': ('joint_state_controller/JointStateController', 'running'),
        'arm_controller': ('position_controllers/JointTrajectoryController', 'running'),
        'group_position_controller': (
            'position_controllers/JointGroupPositionController',
            'initialized',
        ),
    }
    desc = rep['descriptions']['/robot_description']
    assert desc['robot'] == 'mini_arm'
    assert {p['filename'] for p in desc['plugins']} == {
        'libgazebo_ros_control.so',
        'libmini_arm_teleporter.so',
    }
    assert any('libmini_arm_teleporter.so' in line for line in rep['unimplemented'])
    assert '/joint_states' in rep['gazebo_topics']


def test_a_trajectory_goal_succeeds_and_the_joints_move(run):
    proc, rep, out, before = run
    [goal] = rep['motion']
    assert goal['controller'] == '/arm_controller'
    assert goal['error_code'] == 0 and goal['ok'], goal
    assert goal['joints'] == ['shoulder_joint', 'elbow_joint']
    assert goal['moved'] == {'shoulder_joint': True, 'elbow_joint': True}
    # within the package's own goal constraint (0.05 rad)
    assert goal['max_abs_error'] < 0.05
    for j in goal['joints']:
        assert abs(goal['target'][j] - goal['start'][j]) > 0.1


def test_verdict_report_text_and_progress(run):
    proc, rep, out, before = run
    assert rep['verdict'] == {'ok': True, 'problems': []}
    assert proc.returncode == 0, proc.stderr.decode()[-2000:]
    text = proc.stdout.decode()
    assert 'verdict    PASS' in text
    assert 'FollowJointTrajectory over 2 joints: SUCCESSFUL' in text
    with open(out / 'report' / 'report.txt') as f:
        assert f.read() == text
    progress = proc.stderr.decode()
    for step in ('building mini_arm', 'built in', 'world /gazebo is up', 'stopping'):
        assert step in progress, progress


def test_a_package_not_in_the_checkout_is_named(tmp_path):
    with pytest.raises(ValueError, match='no_such_robot.*mini_arm'):
        workspace.needed_packages(workspace.find_packages(MINI_ARM), 'no_such_robot')
