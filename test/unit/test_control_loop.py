"""control/loop.py: controllers update once per <controlPeriod> of sim time, as
gazebo_ros_control's Update() has it; efforts are written every physics step."""

import logging
import math

import pytest
from conftest import JPC, MIXED_URDF, FakeRobot, FakeRos, mixed_params

from _arm1sim.control.controller_manager import ControllerManager
from _arm1sim.control.loop import ControlLoop, control_period_ns
from _arm1sim.control.switching import switch_while_updating
from _arm1sim.description.sdf_world import WorldConfig
from _arm1sim.description.urdf_model import parse_urdf
from _arm1sim.sim.robot_hw_sim import DefaultRobotHWSim
from _arm1sim.sim.simulation import Simulation

NS = '/mixed_ns'
STEP_NS = 1000000  # a 1 ms physics step


class RecordingManager(ControllerManager):
    """The real manager, keeping the (time, period) of each update."""

    def __init__(self, *args):
        super().__init__(*args)
        self.updates = []

    def update(self, time_ns, period_ns, reset_controllers=False):
        self.updates.append((time_ns, period_ns))
        super().update(time_ns, period_ns, reset_controllers)


def loop_rig(control_period):
    model = parse_urdf(MIXED_URDF)
    robot = FakeRobot(list(model.joints))
    hw = DefaultRobotHWSim(model, robot)
    ros = FakeRos({'mixed_ns': {'c': {'type': JPC, 'joint': 'flap_joint', 'pid': {'p': 1.0}}}})
    cm = RecordingManager(hw, ros.node_handle, NS)
    cm.load_controller('c')
    loop = ControlLoop(hw, cm, control_period_ns(control_period, STEP_NS))
    assert switch_while_updating(cm, ['c'], [], lambda: loop.update(0))[0]
    cm.updates.clear()
    robot.applied.clear()
    return loop, cm, robot, ros


def run(loop, first_step, steps):
    return [loop.update((first_step + k) * STEP_NS) for k in range(steps)]


def test_a_10_ms_control_period_updates_controllers_every_10th_1_ms_step():
    loop, cm, robot, _ = loop_rig(0.01)
    loop.last_update_ns = None  # as spawned: the first step updates
    updated = run(loop, 0, 100)
    assert [k for k, u in enumerate(updated) if u] == list(range(0, 100, 10))
    assert cm.updates == [(k * STEP_NS, 10 * STEP_NS) for k in range(0, 100, 10)]
    assert len(robot.applied) == 100  # the efforts go to the robot at every step


def test_the_period_controllers_get_is_the_state_message_time_step():
    loop, _, _, ros = loop_rig(0.01)
    ros.publish(NS + '/c/command', 0.5)
    run(loop, 1, 200)
    steps = [m['time_step'] for m in ros.messages(NS + '/c/state')]
    assert steps and all(s == pytest.approx(0.01) for s in steps)


def test_without_a_control_period_controllers_update_every_step():
    loop, cm, _, _ = loop_rig(None)
    assert all(run(loop, 1, 20))
    assert cm.updates == [(k * STEP_NS, STEP_NS) for k in range(1, 21)]


def test_a_period_that_is_no_multiple_of_the_step_gets_the_elapsed_time():
    loop, cm, _, _ = loop_rig(0.0025)
    run(loop, 1, 12)  # last update at 0: due at 3, 6, 9, 12 ms
    assert cm.updates == [(k * STEP_NS, 3 * STEP_NS) for k in (3, 6, 9, 12)]


def test_time_going_back_updates_at_once():
    loop, cm, _, _ = loop_rig(0.01)
    run(loop, 1, 30)
    cm.updates.clear()
    assert loop.update(0)  # reset_simulation: time is 0 again
    assert cm.updates == [(0, 10 * STEP_NS)]


@pytest.mark.parametrize('period', [math.nan, math.inf, 0.0, -0.01])
def test_a_control_period_that_is_no_positive_number_means_every_step(period, caplog):
    with caplog.at_level(logging.ERROR, logger='_arm1sim.control'):
        assert control_period_ns(period, STEP_NS, 'robot') == STEP_NS
    assert [r.getMessage().split(':')[0] for r in caplog.records] == ['robot']
    assert 'controlPeriod' in caplog.records[0].getMessage()


def test_a_control_period_shorter_than_the_step_is_said_and_updates_every_step(caplog):
    with caplog.at_level(logging.ERROR, logger='_arm1sim.control'):
        period = control_period_ns(0.0005, STEP_NS, 'robot')
    assert 'shorter than the physics step' in caplog.records[0].getMessage()
    loop, cm, _, _ = loop_rig(0.0005)
    assert loop.period_ns == period
    assert all(run(loop, 1, 5))
    assert [p for _, p in cm.updates] == [STEP_NS] * 5


def test_the_simulation_honours_the_urdf_control_period():
    xml = MIXED_URDF.replace('<robotSimType>', '<controlPeriod>0.01</controlPeriod><robotSimType>')
    assert parse_urdf(xml).control_plugin.control_period == pytest.approx(0.01)
    sim = Simulation(WorldConfig())
    try:
        ros = FakeRos(mixed_params())
        model = sim.spawn_urdf(
            'mixed',
            xml,
            controller_manager_factory=lambda hw, ns: ControllerManager(hw, ros.node_handle, ns),
        )
        assert model.control is not None and model.control.period_ns == 10 * STEP_NS
        model.controller_manager.load_controller('flap_controller')
        assert switch_while_updating(model.controller_manager, ['flap_controller'], [], sim.step)[0]
        for _ in range(1000):
            sim.step()
        states = ros.messages(NS + '/flap_controller/state')
        # one state each 10th update: every 100 ms of sim time, each after 10 ms
        stamps = [s['stamp'] for s in states]
        assert len(states) >= 10
        assert all(b - a == 100 * STEP_NS for a, b in zip(stamps, stamps[1:]))
        assert all(s['time_step'] == pytest.approx(0.01) for s in states[1:])
    finally:
        sim.close()
