"""A user's own arm package named arm1, as the seed's tutorial makes one (issue 29): a
SolidWorks export with dense STL meshes, six joints, six effort position controllers, a
camera and its own six-field ``srv/GoToPosition.srv`` (tools/make_own_arm.py). It builds with
plain catkin_make in a workspace of its own over ours, and its own ``roslaunch arm1
gazebo.launch`` comes up on the stand-in, cold (an empty mesh cache), with every controller
loaded and started by upstream's spawner within its 30 s; its own node serves its own
GoToPosition and moves the arm.
"""

import json
import os
import subprocess
import sys
import tempfile

import pytest

from _arm1sim.session import launcher
from _arm1sim.tryout import workspace

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO_ROOT, 'tools'))
import make_own_arm  # noqa: E402

sys.path.pop(0)

# Bounds on a hang only (wall time): what is judged is upstream's own spawner timeout.
WAIT = 240.0

# Run with the user's workspace sourced: their arm1.srv, their controllers, their node.
CLIENT = r'''
import json, sys, time
import rospy
from controller_manager_msgs.srv import ListControllers
from sensor_msgs.msg import JointState
from arm1.srv import GoToPosition

WAIT, NAMES = float(sys.argv[1]), sys.argv[2].split(',')
rospy.init_node('own_arm_check')
out = {'fields': list(GoToPosition._request_class.__slots__)}
rospy.wait_for_service('/arm1/controller_manager/list_controllers', timeout=WAIT)
listing = rospy.ServiceProxy('/arm1/controller_manager/list_controllers', ListControllers)
deadline = time.monotonic() + WAIT
while time.monotonic() < deadline:
    states = {c.name: c.state for c in listing().controller}
    if all(states.get(n) == 'running' for n in NAMES):
        break
    time.sleep(0.5)
out['controllers'] = states
rospy.wait_for_service('/arm1/go_to', timeout=WAIT)
go_to = rospy.ServiceProxy('/arm1/go_to', GoToPosition)
go_to(joint1=0.5, joint2=0.0, joint3=0.0, joint4=-0.5, joint5=0.01, joint6=0.01)
rospy.sleep(4.0)  # sim time: the PID settles in well under that
msg = rospy.wait_for_message('/arm1/joint_states', JointState, timeout=WAIT)
out['positions'] = dict(zip(msg.name, msg.position))
print('RESULT ' + json.dumps(out))
'''


@pytest.fixture(scope='module')
def own_arm(tmp_path_factory):
    src = str(tmp_path_factory.mktemp('checkout'))
    root = make_own_arm.make(src, 'arm1', triangles=15000)
    ws = str(tmp_path_factory.mktemp('ws'))
    pkg = workspace.read_package(root)
    return ws, pkg, workspace.build(ws, [pkg], timeout=900)


def test_own_arm1_package_builds_over_ours(own_arm):
    ws, pkg, built = own_arm
    assert built.ok, built.log_tail  # no "Circular dependency in subset of packages: arm1"
    env = workspace.workspace_env(ws, [pkg])
    found = subprocess.run(
        ['rospack', 'find', 'arm1'], env=env, stdout=subprocess.PIPE, text=True, check=True
    )
    assert os.path.realpath(found.stdout.strip()) == os.path.realpath(pkg.path)


def test_own_arm1_comes_up_cold_with_every_controller_running(own_arm):
    ws, pkg, built = own_arm
    assert built.ok, built.log_tail
    env = workspace.workspace_env(ws, [pkg])
    names = make_own_arm.controller_names()
    with tempfile.TemporaryDirectory() as cache:
        env['XDG_CACHE_HOME'] = cache  # a first launch: no collision pieces cached
        session = launcher.RosSession()
        session.env = launcher.loopback_env(env, launcher.free_port())
        log = os.path.join(ws, 'launch.log')
        with session, open(log, 'w') as out:
            launch = subprocess.Popen(
                ['roslaunch', 'arm1', 'gazebo.launch', 'gui:=false'],
                env=session.env,
                stdout=out,
                stderr=subprocess.STDOUT,
                start_new_session=True,
            )
            session.procs.append(launch)
            assert session.wait_for_master(60.0)
            session.start('rosrun', 'arm1', 'go_to')
            check = subprocess.run(
                [sys.executable, '-c', CLIENT, str(WAIT), ','.join(names)],
                env=session.env,
                stdout=subprocess.PIPE,
                stderr=subprocess.STDOUT,
                text=True,
                timeout=4 * WAIT,
            )
        with open(log) as f:
            launch_log = f.read()
    lines = [ln for ln in check.stdout.splitlines() if ln.startswith('RESULT ')]
    assert lines, check.stdout[-3000:] + launch_log[-3000:]
    result = json.loads(lines[-1][len('RESULT ') :])
    # their GoToPosition (six joints), not ours (four)
    assert result['fields'] == ['joint%d' % i for i in range(1, 7)]
    assert result['controllers'] == {n: 'running' for n in names}, launch_log[-3000:]
    assert "couldn't find the expected controller_manager" not in launch_log
    assert 'No module named' not in launch_log and 'Traceback' not in launch_log
    assert result['positions']['joint1'] == pytest.approx(0.5, abs=0.05), result
    assert result['positions']['joint4'] == pytest.approx(-0.5, abs=0.05), result
