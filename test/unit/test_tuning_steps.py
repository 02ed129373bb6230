"""The tuner's step runs on arm1 (tuning/steps.py, local_ros.py), live gains in the
controller, the state topic's fields, and metrics from a recorded run (rosbag)."""

import os

import pytest
from conftest import JPC, MIXED_URDF, WORLD_FILE, FakeRobot

from _arm1sim.control.joint_position_controller import JointPositionController
from _arm1sim.description.urdf_model import parse_urdf
from _arm1sim.sim.robot_hw_sim import DefaultRobotHWSim
from _arm1sim.tuning.local_ros import LocalRos
from _arm1sim.tuning.metrics import worst
from _arm1sim.tuning.save import with_gains
from _arm1sim.tuning.steps import ARM1_START, Protocol, StepRig, yaml_pid

SHORT = Protocol(dict(ARM1_START), step=0.3, settle=0.2, hold=1.0)


@pytest.fixture(scope='module')
def rig(arm1_urdf, controllers_params):
    from conftest import REPO_ROOT

    def find(pkg):
        if pkg == 'arm1':
            return REPO_ROOT
        raise LookupError(pkg)

    r = StepRig(arm1_urdf, controllers_params, WORLD_FILE, find)
    yield r
    r.close()


# ------------------------------------------------------------------ controller gains
def one_controller(pid):
    robot = FakeRobot(list(parse_urdf(MIXED_URDF).joints))
    hw = DefaultRobotHWSim(parse_urdf(MIXED_URDF), robot)
    ros = LocalRos({'ns': {'c': {'type': JPC, 'joint': 'flap_joint', 'pid': pid}}})
    c = JointPositionController()
    c.name = 'c'
    c.init(hw, ros.node_handle('/ns'), ros.node_handle('/ns/c'))
    return c, hw, robot, ros


def test_new_gains_apply_at_the_next_update_and_show_in_the_state():
    c, hw, robot, ros = one_controller({'p': 1.0})
    states = ros.record('/ns/c/state')
    c.start_request(0)
    ros.publish('/ns/c/command', 0.5)
    c.update(0, 1000000)
    assert hw.handles['flap_joint'].command == pytest.approx(0.5)
    accepted = c.set_gains({'p': 3.0, 'd': 0.0})
    assert accepted['p'] == 3.0 and c.pid.p == 1.0  # not before the update
    c.update(1000000, 1000000)
    assert hw.handles['flap_joint'].command == pytest.approx(1.5)
    for _ in range(9):
        c.update(0, 1000000)
    assert states[-1]['p'] == 3.0


def test_invalid_gains_are_refused():
    c, *_ = one_controller({'p': 1.0, 'i': 1.0, 'i_clamp': 0.2})
    kept = c.set_gains({'i_clamp_min': 0.5, 'i_clamp_max': 0.1})
    assert kept['i_clamp_max'] == pytest.approx(0.2) and kept['i_clamp_min'] == pytest.approx(-0.2)
    assert c.set_gains({'p': float('nan')})['p'] == 1.0


def test_serve_config_is_offered_by_node_handles_that_have_it():
    served = []

    class Nh(LocalRos):
        pass

    ros = LocalRos({'ns': {'c': {'type': JPC, 'joint': 'flap_joint', 'pid': {'p': 2.0}}}})
    nh = ros.node_handle('/ns/c')
    nh.serve_config = lambda ns, type_name, current, cb: served.append((ns, type_name, current, cb))
    hw = DefaultRobotHWSim(parse_urdf(MIXED_URDF), FakeRobot(list(parse_urdf(MIXED_URDF).joints)))
    c = JointPositionController()
    c.init(hw, ros.node_handle('/ns'), nh)
    ((ns, type_name, current, cb),) = served
    assert (ns, type_name) == ('pid', 'control_toolbox/Parameters')
    assert current == dict(p=2.0, i=0.0, d=0.0, i_clamp_max=0.0, i_clamp_min=-0.0, antiwindup=False)
    assert cb({'p': 5.0})['p'] == 5.0


# ------------------------------------------------------------------ state topic
def test_state_fields_match_the_controller_internals(rig):
    topic = rig.state_topic('joint2')
    log = rig.ros.record(topic)
    rig.restart(SHORT)
    c = rig.controller('joint2')
    rig.ros.publish(rig.command_topic('joint2'), 1.1)
    n = len(log)
    for k in range(35):
        rig.sim.step()
        if len(log) > n:  # published at this update
            n = len(log)
            s = log[-1]
            assert s['stamp'] == rig.sim.time_ns - rig.sim.step_ns
            assert s['set_point'] == 1.1 and s['error'] == c.pid.p_error
            assert s['process_value'] == pytest.approx(1.1 - c.pid.p_error)
            assert s['command'] == c.pid.cmd and s['time_step'] == pytest.approx(0.001)
            assert (s['p'], s['i'], s['d'], s['i_clamp']) == (
                c.pid.p,
                c.pid.i,
                c.pid.d,
                c.pid.i_max,
            )
    stamps = [s['stamp'] for s in log[-3:]]
    assert [b - a for a, b in zip(stamps, stamps[1:])] == [10 * rig.sim.step_ns] * 2


# ------------------------------------------------------------------ step runs
def test_a_step_run_follows_the_protocol(rig):
    run = rig.run('joint1', SHORT)
    assert [s[0] for s in run.steps] == ['out', 'back']
    assert run.steps[0][1] == pytest.approx(0.2) and run.steps[1][1] == pytest.approx(1.2)
    assert run.steps[0][3] == pytest.approx(0.3) and run.steps[1][3] == pytest.approx(0.0)
    assert len(run.times) == 2200 and len(run.metrics) == 2
    assert rig.targets('joint2', SHORT) == (1.0, 1.3)
    assert rig.targets('joint2', Protocol({'joint2': 1.4}, step=0.3)) == (1.4, pytest.approx(1.1))


def test_runs_are_repeatable_and_gains_restore(rig):
    a = rig.run('joint3', SHORT, {'p': 2.0, 'd': 0.001})
    b = rig.run('joint3', SHORT)
    c = rig.run('joint3', SHORT, {'p': 2.0, 'd': 0.001})
    assert a.positions == c.positions
    assert b.gains['p'] == 1.0 and a.gains['p'] == 2.0


def test_seed_gains_overshoot(rig):
    """The seed's gains overshoot on every joint (docs/tuning.md's table)."""
    for joint in rig.joints:
        w = worst(rig.run(joint, SHORT).metrics)
        assert w.overshoot > 5.0


def test_yaml_snippet_round_trips(controllers_params):
    g = dict(p=2.0, i=0.5, d=0.001, i_clamp_max=0.05, i_clamp_min=-0.05, antiwindup=True)
    assert yaml_pid(g) == {'p': 2.0, 'i': 0.5, 'd': 0.001, 'i_clamp': 0.05, 'antiwindup': True}
    params = with_gains(
        controllers_params, '/arm1', {'joint2': 'joint2_position_controller'}, {'joint2': g}
    )
    from _arm1sim.control.pid import Pid

    assert Pid.from_params(params['arm1']['joint2_position_controller']['pid']).gains() == g
    assert controllers_params['arm1']['joint2_position_controller']['pid']['p'] == 1


# ------------------------------------------------------------------ recorded run
def test_metrics_from_a_rosbag_match_the_simulated_step(rig, tmp_path):
    rosbag = pytest.importorskip('rosbag')
    import rospy
    from sensor_msgs.msg import JointState
    from std_msgs.msg import Float64

    from _arm1sim.ros.tools.bag import read_run
    from _arm1sim.tuning.recorded import recorded_steps

    run = rig.run('joint4', SHORT)
    path = os.path.join(str(tmp_path), 'run.bag')
    with rosbag.Bag(path, 'w') as bag:
        t0 = 100.0
        bag.write('/arm1/joint4_position_controller/command', Float64(0.0), rospy.Time(t0))
        for name, t_step, _, target in run.steps:
            bag.write(
                '/arm1/joint4_position_controller/command',
                Float64(target),
                rospy.Time.from_sec(t0 + t_step),
            )
        for t, x in list(zip(run.times, run.positions))[19::20]:  # 50 Hz
            m = JointState(name=['joint1', 'joint4'], position=[0.0, x])
            m.header.stamp = rospy.Time.from_sec(t0 + t)
            bag.write('/arm1/joint_states', m, m.header.stamp)
    data = read_run(path, '/arm1', {'joint4_position_controller': 'joint4'})
    steps = recorded_steps(*data['joint4'], lower=-0.8, upper=1.57)
    assert len(steps) == 2
    for (t, m), sim in zip(steps, run.metrics):
        # 50 Hz samples can only miss excursions of the dense (1 kHz) response
        assert m.target == pytest.approx(sim.target)
        assert m.start == pytest.approx(sim.start, abs=1e-3)
        assert m.overshoot <= sim.overshoot + 1e-9
        assert m.overshoot == pytest.approx(sim.overshoot, abs=5.0)
        assert m.jitter <= sim.jitter + 1e-9
        assert m.settling_time <= sim.settling_time + 0.02
        assert m.steady_state_error == pytest.approx(sim.steady_state_error, abs=3e-3)
