"""Position-interface joints without pid_gains reach their command in one step, as Gazebo's
SetPosition does, but by moving there (physics.robot.Robot.move_positions): a box held
between two position-driven fingers by friction alone rises with a position-driven lift.
Real pybullet, the gripper driven through DefaultRobotHWSim by position controllers."""

import pytest
from conftest import WORLD_FILE, FakeRos
from helpers import BOX, CONTROLLERS, GRIPPER, LIFT_TOP

from _arm1sim.control.controller_manager import ControllerManager
from _arm1sim.control.switching import switch_while_updating
from _arm1sim.description.sdf_world import read_world
from _arm1sim.sim.simulation import Simulation


@pytest.fixture
def sim():
    s = Simulation(read_world(WORLD_FILE))
    yield s
    s.close()


def run(sim, seconds):
    for _ in range(int(round(seconds / sim.period))):
        sim.step()


def _closed_on_the_box(sim, ros, urdf=GRIPPER):
    """The carrier (``urdf``) and the box between its fingers, its controllers running and its
    fingers commanded past the box's faces: (model, box)."""
    model = sim.spawn_urdf(
        'carrier',
        urdf,
        controller_manager_factory=lambda hw, ns: ControllerManager(hw, ros.node_handle, ns),
    )
    box = sim.spawn_urdf('box', BOX, position=(0.5, 0, 0.0205))
    names = sorted(CONTROLLERS)
    for n in names:
        model.controller_manager.load_controller(n)
    ok, _ = switch_while_updating(model.controller_manager, names, [], sim.step, 2, poll=0.0005)
    assert ok
    run(sim, 0.3)
    for side in ('left', 'right'):
        ros.publish('/carrier/%s_controller/command' % side, 0.03)
    run(sim, 0.5)
    return model, box


def test_a_box_held_by_position_driven_fingers_rises_with_a_position_driven_lift(sim):
    ros = FakeRos({'carrier': CONTROLLERS})
    model, box = _closed_on_the_box(sim, ros)
    left = model.robot.read(model.robot.indices(['left']))[0][0]
    assert left == pytest.approx(0.02, abs=2e-3)  # stopped by the box, not put through it
    start = box.robot.link_pose('box')[0][2]
    lift0 = model.robot.link_pose('lift_link')[0][2]
    ros.publish('/carrier/lift_controller/command', LIFT_TOP)
    handle, lift = model.hw.handles['lift'], model.robot.indices(['lift'])
    worst = 0.0
    for _ in range(500):
        sim.step()  # each step reaches the command written before it, box and all
        worst = max(worst, abs(model.robot.read(lift)[0][0] - handle.command))
    assert worst < 1e-6
    lift1 = model.robot.link_pose('lift_link')[0][2]
    risen = box.robot.link_pose('box')[0][2] - start
    assert lift1 - lift0 == pytest.approx(LIFT_TOP, abs=1e-3)  # 0.5 m/s: there in 0.24 s
    assert risen == pytest.approx(LIFT_TOP, abs=2e-3)  # carried, not left on the ground
    held = box.robot.link_pose('box')[0][2]
    run(sim, 1.0)
    assert box.robot.link_pose('box')[0][2] == pytest.approx(held, abs=1e-3)  # no slip


def test_a_position_joint_pushes_with_at_most_its_effort_limit():
    """The force the motor may use is the URDF effort limit (none: a stiff 1e6)."""
    from conftest import FakeRobot

    from _arm1sim.description.urdf_model import parse_urdf
    from _arm1sim.sim.robot_hw_sim import UNLIMITED_MOTOR_FORCE, DefaultRobotHWSim

    urdf = GRIPPER.replace('effort="10"', 'effort="0"', 1)  # the left finger: no limit
    model = parse_urdf(urdf)
    robot = FakeRobot(list(model.joints))
    hw = DefaultRobotHWSim(model, robot, 0.001)
    hw.read()
    hw.write()
    (indices, _), forces = robot.placed[-1], robot.position_forces[-1]
    names = {i: n for n, i in robot.joint_index.items()}
    assert {names[i]: f for i, f in zip(indices, forces)} == {
        'left': UNLIMITED_MOTOR_FORCE,
        'lift': 50.0,
        'right': 10.0,
    }


def _weak_grip(sim, ros):
    """The carrier with fingers that squeeze at 0.5 N each (friction 1 N against the box's
    0.49 N weight), closed on the box; returns the model and the box."""
    return _closed_on_the_box(sim, ros, GRIPPER.replace('effort="10"', 'effort="0.5"'))


def _lift_in_jumps(sim, ros, top, jumps=60, every=0.02):
    """The lift commanded as a coarse stream: each command a one-step jump, then a stop."""
    for k in range(1, jumps + 1):
        ros.publish('/carrier/lift_controller/command', top * k / jumps)
        run(sim, every)


@pytest.mark.parametrize('carried', [True, False])
def test_a_jump_of_a_position_joint_is_carried_by_what_its_fingers_grip(sim, monkeypatch, carried):
    """A 2 mm jump every 20 ms (2 m/s for one step) needs ~100x the box's weight to follow:
    friction at 0.5 N a finger cannot give it, so in Gazebo the box is left behind a little at
    every jump. Here what the fingers grip takes the jump with them (physics.carry)."""
    if not carried:
        monkeypatch.setattr('_arm1sim.physics.robot.CARRY_MIN_CHANGE', float('inf'))
    ros = FakeRos({'carrier': CONTROLLERS})
    model, box = _weak_grip(sim, ros)
    start = box.robot.link_pose('box')[0][2]
    lift0 = model.robot.link_pose('lift_link')[0][2]
    _lift_in_jumps(sim, ros, LIFT_TOP)
    rise = model.robot.link_pose('lift_link')[0][2] - lift0
    risen = box.robot.link_pose('box')[0][2] - start
    assert rise == pytest.approx(LIFT_TOP, abs=1e-3)
    if carried:
        assert risen == pytest.approx(rise, abs=2e-3)
        held = box.robot.link_pose('box')[0][2]
        run(sim, 2.0)
        assert box.robot.link_pose('box')[0][2] == pytest.approx(held, abs=1e-3)  # no slip
    else:
        assert risen < rise - 0.02  # slid down the fingers at the jumps


def test_what_the_fingers_let_go_is_not_carried(sim):
    ros = FakeRos({'carrier': CONTROLLERS})
    model, box = _weak_grip(sim, ros)
    _lift_in_jumps(sim, ros, LIFT_TOP / 2, jumps=30)
    for side in ('left', 'right'):
        ros.publish('/carrier/%s_controller/command' % side, 0.0)
    run(sim, 0.5)
    assert box.robot.link_pose('box')[0][2] == pytest.approx(0.02, abs=2e-3)  # fell
    _lift_in_jumps(sim, ros, LIFT_TOP, jumps=30)  # the open fingers jump up past it
    assert box.robot.link_pose('box')[0][2] == pytest.approx(0.02, abs=2e-3)
