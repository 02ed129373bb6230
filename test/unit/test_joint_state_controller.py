"""joint_state_controller/JointStateController (control/joint_state_controller.py)."""

import pytest
from conftest import JSC, MIXED_URDF, FakeRobot, FakeRos

from _arm1sim.control.controller import ControllerError
from _arm1sim.control.joint_state_controller import JointStateController
from _arm1sim.description.urdf_model import parse_urdf
from _arm1sim.sim.robot_hw_sim import DefaultRobotHWSim

STEP_NS = 1000000  # 1 ms


def make(params, ns='/mixed_ns'):
    model = parse_urdf(MIXED_URDF)
    robot = FakeRobot(list(model.joints))
    hw = DefaultRobotHWSim(model, robot)
    ros = FakeRos({'mixed_ns': {'jsc': dict(params, type=JSC)}})
    c = JointStateController()
    c.name = 'jsc'
    c.init(hw, ros.node_handle(ns), ros.node_handle(ns + '/jsc'))
    return c, hw, robot, ros


def run(c, steps, start_ns=0):
    c.starting(start_ns)
    for k in range(steps):
        c.update(start_ns + k * STEP_NS, STEP_NS)


def test_publish_rate_is_required_and_named_in_the_error():
    with pytest.raises(ControllerError) as exc:
        make({})
    assert "Parameter 'publish_rate' not set" in str(exc.value)
    assert '/mixed_ns/jsc' in str(exc.value)


def test_non_numeric_publish_rate_is_refused():
    with pytest.raises(ControllerError, match='publish_rate'):
        make({'publish_rate': 'fast'})


@pytest.mark.parametrize('rate', [0, 0.0, -1, -50.0])
def test_rate_of_zero_or_less_never_publishes(rate):
    c, _, _, ros = make({'publish_rate': rate})
    run(c, 2000)
    assert ros.messages('/mixed_ns/joint_states') == []


def test_publishes_on_first_update_on_the_robot_namespace():
    c, hw, robot, ros = make({'publish_rate': 50})
    robot.set('slider_joint', 0.1, 0.2)
    hw.read()
    c.starting(7 * STEP_NS)
    c.update(7 * STEP_NS, STEP_NS)
    msgs = ros.messages('/mixed_ns/joint_states')
    assert len(msgs) == 1
    assert msgs[0]['stamp'] == 7 * STEP_NS
    assert msgs[0]['position'][msgs[0]['name'].index('slider_joint')] == pytest.approx(0.1)
    assert msgs[0]['velocity'][msgs[0]['name'].index('slider_joint')] == pytest.approx(0.2)


def test_names_are_alphabetical_with_position_velocity_effort_for_each():
    c, hw, robot, ros = make({'publish_rate': 50})
    robot.set('wheel_joint', 1.0, 2.0)
    hw.read()
    hw.handles['wheel_joint'].command = 0.5
    hw.write()
    run(c, 1)
    m = ros.messages('/mixed_ns/joint_states')[0]
    assert m['name'] == ['flap_joint', 'passive_joint', 'slider_joint', 'wheel_joint']
    assert m['position'] == [0.0, 0.0, 0.0, 1.0]
    assert m['velocity'] == [0.0, 0.0, 0.0, 2.0]
    assert m['effort'] == [0.0, 0.0, 0.0, 0.5]
    assert c.claimed_resources() == []  # reads only


def test_joints_parameter_selects_subset_and_order():
    c, _, _, ros = make({'publish_rate': 10, 'joints': ['wheel_joint', 'flap_joint']})
    run(c, 1)
    assert ros.messages('/mixed_ns/joint_states')[0]['name'] == ['wheel_joint', 'flap_joint']


def test_extra_joints_are_appended():
    c, _, _, ros = make(
        {'publish_rate': 10, 'extra_joints': [{'name': 'gripper', 'position': 0.25}]}
    )
    run(c, 1)
    m = ros.messages('/mixed_ns/joint_states')[0]
    assert m['name'][-1] == 'gripper'
    assert (m['position'][-1], m['velocity'][-1], m['effort'][-1]) == (0.25, 0.0, 0.0)
    assert len(m['name']) == len(m['position']) == len(m['velocity']) == len(m['effort']) == 5


def test_fifty_hz_over_ten_thousand_one_ms_steps_without_drift():
    c, _, _, ros = make({'publish_rate': 50})
    run(c, 10000)
    stamps = [m['stamp'] for m in ros.messages('/mixed_ns/joint_states')]
    assert stamps[0] == 0  # first update
    rate = len(stamps) / 10.0
    assert abs(rate - 50.0) / 50.0 <= 0.001
    # after the first one, messages come exactly every 20 ms of sim time
    gaps = {b - a for a, b in zip(stamps[1:], stamps[2:])}
    assert gaps == {20 * STEP_NS}
    # each is the first update strictly after last + 1/rate
    assert stamps[1] == 21 * STEP_NS
    assert stamps[-1] == (21 + 20 * (len(stamps) - 2)) * STEP_NS


@pytest.mark.parametrize('rate', [30.0, 300.0, 333.0])
def test_rate_that_does_not_divide_the_step_does_not_drift(rate):
    """A 'last = now' implementation would publish every ceil(period) ms and fall behind."""
    c, _, _, ros = make({'publish_rate': rate})
    run(c, 10000)
    n = len(ros.messages('/mixed_ns/joint_states'))
    assert abs(n / 10.0 - rate) / rate <= 0.001 + 1 / (10.0 * rate)


def test_restart_publishes_again_at_once():
    c, _, _, ros = make({'publish_rate': 1})
    run(c, 10)
    assert len(ros.messages('/mixed_ns/joint_states')) == 1
    c.stopping(10 * STEP_NS)
    run(c, 1, start_ns=20 * STEP_NS)
    assert len(ros.messages('/mixed_ns/joint_states')) == 2


def test_nobody_subscribed_builds_nothing_and_keeps_the_schedule():
    """joint_states nobody listens to is not built; the publish times stay those of a
    listened topic, so a subscriber that comes hears the same stamps."""
    heard, _, _, heard_ros = make({'publish_rate': 50})
    deaf, _, _, ros = make({'publish_rate': 50})
    (pub,) = ros.publishers['/mixed_ns/joint_states']
    pub.subscribed = False
    run(heard, 70)
    run(deaf, 45)
    assert pub.messages == []
    pub.subscribed = True
    for k in range(45, 70):
        deaf.update(k * STEP_NS, STEP_NS)
    stamps = [m['stamp'] for m in heard_ros.messages('/mixed_ns/joint_states')]
    assert [m['stamp'] for m in pub.messages] == [t for t in stamps if t >= 45 * STEP_NS]
    assert len(pub.messages) == 1
