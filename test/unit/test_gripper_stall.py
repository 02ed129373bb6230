"""An effort GripperActionController closing pick_arm's mimic fingers on a box, in pybullet: the
fingers holding still report still velocities, so the goal ends as stalled within upstream's
stall_timeout (sim time). Before physics/mimic.py dropped the leader's velocity from the
follower's motor, the pair chattered sideways with the box at half the step rate
(+-0.02 m/s every other step): the goal stayed ACTIVE forever."""

import os

import pytest
import xacro
import yaml
from conftest import REPO_ROOT, FakeRos

from _arm1sim.control.controller_manager import ControllerManager
from _arm1sim.control.switching import switch_while_updating
from _arm1sim.description.resource_paths import gazebo_paths
from _arm1sim.description.sdf_world import read_world
from _arm1sim.goal.pick_place import OBJECTS, TABLE_TOP, pick_lift
from _arm1sim.sim.simulation import Simulation

PICK_ARM = os.path.join(REPO_ROOT, 'test', 'robots', 'pick_arm')
CONTROLLERS = ['joint_state_controller', 'lift_controller', 'gripper_controller']
STALL_VELOCITY, STALL_TIMEOUT = 0.001, 1.0  # upstream's defaults
GOAL = '/pa/gripper_controller/gripper_cmd'


@pytest.fixture
def sim():
    world = os.path.join(PICK_ARM, 'worlds', 'pick_rows.world')
    s = Simulation(read_world(world, gazebo_paths({}).find_model))
    for spawn in s.config.spawns:  # the table
        s.spawn_urdf(spawn.name, spawn.urdf, spawn.position, spawn.orientation)
    yield s
    s.close()


def run(sim, seconds, each=None):
    for _ in range(int(round(seconds / sim.period))):
        sim.step()
        if each is not None:
            each()


def test_fingers_holding_a_box_report_no_motion_and_the_goal_stalls(sim):
    urdf = xacro.process_file(
        os.path.join(PICK_ARM, 'urdf', 'pick_arm.urdf.xacro'),
        mappings={'arm': 'false', 'fingers': 'effort', 'ns': '/pa'},
    ).toprettyxml()
    with open(os.path.join(PICK_ARM, 'config', 'controllers.yaml')) as f:
        params = yaml.safe_load(f)
    gripper = params['gripper_controller']
    gripper['stall_velocity_threshold'], gripper['stall_timeout'] = STALL_VELOCITY, STALL_TIMEOUT
    ros = FakeRos({'pa': params})
    model = sim.spawn_urdf(
        'pa',
        urdf,
        controller_manager_factory=lambda hw, ns: ControllerManager(hw, ros.node_handle, ns),
    )
    for name in CONTROLLERS:
        model.controller_manager.load_controller(name)
    ok, _ = switch_while_updating(
        model.controller_manager, CONTROLLERS, [], sim.step, 2, poll=0.0005
    )
    assert ok
    box = OBJECTS[1]  # 4 cm: the fingers stop at 0.025 of their 0.045
    sim.spawn_urdf(box.name, box.urdf(), (0.3, 0.0, TABLE_TOP + box.height / 2 + 0.0005))
    ros.publish(
        '/pa/lift_controller/command',
        dict(
            joint_names=['lift_joint'],
            points=[dict(positions=[pick_lift(box)], velocities=[0.0], time_from_start=800000000)],
        ),
    )
    run(sim, 1.3)
    robot = model.robot
    fingers = robot.indices(['left_finger_joint', 'right_finger_joint'])
    server = ros.action_servers[GOAL]
    goal = server.send_goal(dict(command=dict(position=0.045, max_effort=5.0)))
    sent = sim.time_ns
    ended = []

    def watch():
        if not ended and goal.status != 'ACTIVE':
            ended.append(sim.time_ns)

    run(sim, 0.3, watch)  # closed on the box (0.02 m at 0.17 m/s: 0.15 s)
    samples = []
    run(sim, 0.5, lambda: (watch(), samples.append(robot.read(fingers))))
    positions = [[pos for pos, _ in s] for s in samples]
    speeds = [max(abs(v) for _, v in s) for s in samples]
    # Still (a slow creep of a few micrometres over 0.5 s at most), and so every step's
    # velocity.
    for k in range(2):
        assert max(q[k] for q in positions) - min(q[k] for q in positions) < 1e-5
        assert positions[-1][k] == pytest.approx(0.025, abs=1e-3)  # on the box's faces
    assert max(speeds) < STALL_VELOCITY
    run(sim, STALL_TIMEOUT, watch)
    assert goal.status == 'ABORTED', goal.status
    assert goal.result['stalled'] is True and goal.result['reached_goal'] is False
    # Fingers stopped ~0.15 s after the goal: aborted one stall_timeout later, give or take.
    assert (ended[0] - sent) * 1e-9 < 0.3 + STALL_TIMEOUT
