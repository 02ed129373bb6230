"""control/controller_manager.py: load, unload, switch (with a service thread), list, update."""

import threading
import time

import pytest
from conftest import JPC, JSC, FakeRos, pump_switch
from helpers import MIXED_NS as NS
from helpers import MS as PERIOD_NS
from helpers import mixed_rig, states  # noqa: F401 (mixed_rig is the rig fixture)

from _arm1sim.control.controller import Controller
from _arm1sim.control.controller_manager import (
    BEST_EFFORT,
    STRICT,
    ControllerManager,
    ControllerManagerError,
)
from _arm1sim.control.joint_position_controller import JointPositionController
from _arm1sim.control.registry import CONTROLLER_TYPES, by_type_name
from _arm1sim.control.switching import SwitchRequest, SwitchTimeout, switch_while_updating


# ----------------------------------------------------------------------------- load
def test_controller_types():
    cm = ControllerManager(None, FakeRos().node_handle, '/x')
    assert cm.controller_types() == [
        'effort_controllers/GripperActionController',
        'effort_controllers/JointEffortController',
        'effort_controllers/JointGroupEffortController',
        JPC,
        'effort_controllers/JointTrajectoryController',
        'effort_controllers/JointVelocityController',
        'franka_control/FrankaStateController',
        'franka_gazebo/FrankaGripperSim',
        JSC,
        'position_controllers/GripperActionController',
        'position_controllers/JointGroupPositionController',
        'position_controllers/JointPositionController',
        'position_controllers/JointTrajectoryController',
        'velocity_controllers/JointGroupVelocityController',
        'velocity_controllers/JointTrajectoryController',
        'velocity_controllers/JointVelocityController',
    ]


def test_load_lists_name_type_state_and_claimed_resources(rig):
    cm, _, _, _ = rig
    cm.load_controller('flap_controller')
    cm.load_controller('joint_state_controller')
    assert cm.list_controllers() == [
        (
            'flap_controller',
            JPC,
            'initialized',
            [('hardware_interface/EffortJointInterface', ['flap_joint'])],
        ),
        ('joint_state_controller', JSC, 'initialized', []),
    ]


def test_missing_type_message(rig):
    cm, _, _, ros = rig
    with pytest.raises(ControllerManagerError) as exc:
        cm.load_controller('no_type_controller')
    msg = str(exc.value)
    assert "Could not load controller 'no_type_controller'" in msg
    assert 'type was not specified' in msg
    assert all(h.is_shutdown for h in ros.handles)


def test_missing_type_for_unknown_name(rig):
    cm, _, _, _ = rig
    with pytest.raises(ControllerManagerError, match='type was not specified'):
        cm.load_controller('never_configured')


def test_unknown_type_message_names_the_type(rig):
    cm, _, _, _ = rig
    with pytest.raises(ControllerManagerError) as exc:
        cm.load_controller('bad_type_controller')
    assert 'velocity_controllers/JointPositionController' in str(exc.value)
    assert 'bad_type_controller' in str(exc.value)


@pytest.mark.parametrize(
    'name, joint',
    [('bad_joint_controller', 'elbow_joint'), ('passive_controller', 'passive_joint')],
)
def test_unknown_joint_message_names_joint_and_controller(rig, name, joint):
    cm, _, _, ros = rig
    with pytest.raises(ControllerManagerError) as exc:
        cm.load_controller(name)
    assert "'%s'" % joint in str(exc.value)
    assert name in str(exc.value)
    assert all(h.is_shutdown for h in ros.handles)
    assert ros.subscribers.get(NS + '/%s/command' % name, []) == []


def test_missing_p_names_the_controller(rig):
    cm, _, _, _ = rig
    with pytest.raises(ControllerManagerError) as exc:
        cm.load_controller('no_p_controller')
    msg = str(exc.value)
    assert 'No p gain specified for pid.' in msg
    assert 'no_p_controller' in msg
    assert NS + '/no_p_controller/pid' in msg


def test_missing_publish_rate_names_the_parameter(rig):
    cm, _, _, _ = rig
    with pytest.raises(ControllerManagerError, match="'publish_rate' not set"):
        cm.load_controller('no_rate_controller')


def test_failures_do_not_stop_the_others_from_loading(rig):
    cm, _, _, _ = rig
    names = [
        'joint_state_controller',
        'no_type_controller',
        'wheel_controller',
        'bad_joint_controller',
        'no_p_controller',
        'slider_controller',
        'bad_type_controller',
        'flap_controller',
    ]
    failed = []
    for n in names:
        try:
            cm.load_controller(n)
        except ControllerManagerError:
            failed.append(n)
    assert failed == [
        'no_type_controller',
        'bad_joint_controller',
        'no_p_controller',
        'bad_type_controller',
    ]
    assert [n for n, _, _, _ in cm.list_controllers()] == [
        'joint_state_controller',
        'wheel_controller',
        'slider_controller',
        'flap_controller',
    ]
    ok, _ = pump_switch(
        cm, ['joint_state_controller', 'wheel_controller', 'slider_controller', 'flap_controller']
    )
    assert ok
    assert set(states(cm).values()) == {'running'}


def test_loading_twice_is_refused(rig):
    cm, _, _, _ = rig
    cm.load_controller('flap_controller')
    with pytest.raises(ControllerManagerError, match='already loaded'):
        cm.load_controller('flap_controller')


# ----------------------------------------------------------------------------- switch
def test_switch_takes_effect_at_the_next_update_and_the_caller_waits(rig):
    cm, hw, robot, ros = rig
    cm.load_controller('flap_controller')
    robot.set('flap_joint', 0.3)
    hw.read()
    request = SwitchRequest(cm, ['flap_controller'], [], STRICT)
    time.sleep(0.1)
    assert request.waiting, 'switch_controller returned before any update'
    assert states(cm)['flap_controller'] == 'initialized'
    cm.update(5000000, PERIOD_NS)
    assert request.wait(2.0) is True
    assert states(cm)['flap_controller'] == 'running'
    # started at that update: it holds the position it had then
    assert cm.controller('flap_controller').target == pytest.approx(0.3)
    assert ros.messages(NS + '/flap_controller/state')[0]['stamp'] == 5000000


def test_switch_with_timeout_and_no_update_fails_and_is_withdrawn(rig):
    cm, _, _, _ = rig
    cm.load_controller('flap_controller')
    t0 = time.monotonic()
    assert cm.switch_controller(['flap_controller'], [], STRICT, timeout=0.1) is False
    assert time.monotonic() - t0 >= 0.09
    cm.update(0, PERIOD_NS)  # the withdrawn request must not be applied late
    assert states(cm)['flap_controller'] == 'initialized'


def test_empty_switch_returns_at_once(rig):
    cm, _, _, _ = rig
    assert cm.switch_controller([], [], STRICT) is True


def test_strict_refuses_unknown_controller_and_changes_nothing(rig):
    cm, _, _, _ = rig
    cm.load_controller('flap_controller')
    assert cm.switch_controller(['flap_controller', 'ghost'], [], STRICT) is False
    cm.update(0, PERIOD_NS)
    assert states(cm)['flap_controller'] == 'initialized'


def test_best_effort_skips_unknown_controller_and_starts_the_rest(rig):
    cm, _, _, _ = rig
    cm.load_controller('flap_controller')
    ok, _ = pump_switch(cm, ['flap_controller', 'ghost'], strictness=BEST_EFFORT)
    assert ok is True
    assert states(cm)['flap_controller'] == 'running'


def test_strictness_zero_means_best_effort(rig):
    cm, _, _, _ = rig
    cm.load_controller('flap_controller')
    ok, _ = pump_switch(cm, ['flap_controller', 'ghost'], strictness=0)
    assert ok is True
    assert states(cm)['flap_controller'] == 'running'


def test_strict_refuses_starting_a_running_or_stopping_a_stopped_controller(rig):
    cm, _, _, _ = rig
    cm.load_controller('flap_controller')
    cm.load_controller('wheel_controller')
    assert pump_switch(cm, ['flap_controller'])[0]
    assert cm.switch_controller(['flap_controller'], [], STRICT) is False
    assert cm.switch_controller(['wheel_controller'], ['slider_controller'], STRICT) is False
    assert cm.switch_controller([], ['wheel_controller'], STRICT) is False
    cm.update(0, PERIOD_NS)
    assert states(cm) == {'flap_controller': 'running', 'wheel_controller': 'initialized'}
    # best effort ignores what is already so
    assert pump_switch(cm, ['flap_controller', 'wheel_controller'], strictness=BEST_EFFORT)[0]
    assert states(cm) == {'flap_controller': 'running', 'wheel_controller': 'running'}


def test_stop_sets_stopped_and_zeroes_the_effort_command(rig):
    cm, hw, _, _ = rig
    cm.load_controller('flap_controller')
    assert pump_switch(cm, ['flap_controller'])[0]
    cm.controller('flap_controller').set_target(1.0)
    cm.update(0, PERIOD_NS)
    assert hw.handles['flap_joint'].command != 0.0
    assert pump_switch(cm, [], ['flap_controller'])[0]
    assert states(cm)['flap_controller'] == 'stopped'
    assert hw.handles['flap_joint'].command == 0.0
    cm.update(0, PERIOD_NS)
    assert hw.handles['flap_joint'].command == 0.0  # not updated any more


def test_resource_conflict_is_refused(rig):
    cm, _, _, _ = rig
    cm.load_controller('flap_controller')
    cm.load_controller('flap_other_controller')
    cm.load_controller('joint_state_controller')
    # both at once
    assert cm.switch_controller(['flap_controller', 'flap_other_controller'], [], STRICT) is False
    cm.update(0, PERIOD_NS)
    assert states(cm)['flap_controller'] == 'initialized'
    # one running, the other asked for
    assert pump_switch(cm, ['flap_controller', 'joint_state_controller'])[0]
    assert cm.switch_controller(['flap_other_controller'], [], BEST_EFFORT) is False
    cm.update(0, PERIOD_NS)
    assert states(cm)['flap_other_controller'] == 'initialized'
    # handing the joint over in one switch is fine
    assert pump_switch(cm, ['flap_other_controller'], ['flap_controller'])[0]
    assert states(cm) == {
        'flap_controller': 'stopped',
        'flap_other_controller': 'running',
        'joint_state_controller': 'running',
    }


def test_running_controller_cannot_be_unloaded(rig):
    cm, _, _, ros = rig
    cm.load_controller('flap_controller')
    assert pump_switch(cm, ['flap_controller'])[0]
    with pytest.raises(ControllerManagerError) as exc:
        cm.unload_controller('flap_controller')
    assert 'flap_controller' in str(exc.value) and 'running' in str(exc.value)
    assert states(cm)['flap_controller'] == 'running'
    assert pump_switch(cm, [], ['flap_controller'])[0]
    cm.unload_controller('flap_controller')
    assert cm.list_controllers() == []
    assert ros.subscribers[NS + '/flap_controller/command'] == []  # node handles shut down
    cm.load_controller('flap_controller')  # and it can be loaded again


def test_unload_unknown_is_an_error(rig):
    cm, _, _, _ = rig
    with pytest.raises(ControllerManagerError, match='ghost'):
        cm.unload_controller('ghost')


def test_update_runs_only_running_controllers(rig):
    cm, hw, robot, ros = rig
    for n in ('flap_controller', 'wheel_controller', 'joint_state_controller'):
        cm.load_controller(n)
    assert pump_switch(cm, ['flap_controller', 'joint_state_controller'])[0]
    n_js = len(ros.messages(NS + '/joint_states'))
    ros.publish(NS + '/flap_controller/command', 0.5)
    ros.publish(NS + '/wheel_controller/command', 0.5)
    cm.update(10**9, PERIOD_NS)
    assert hw.handles['flap_joint'].command == pytest.approx(0.5)
    assert hw.handles['wheel_joint'].command == 0.0
    assert len(ros.messages(NS + '/joint_states')) == n_js + 1


def switch_concurrently(cm, names, timeout):
    """Each name started by its own STRICT switch_controller call on its own thread (as
    rospy serves service calls), all waiting before physics steps again; then updates
    until the calls return or 3 s pass. Returns {name: result} and whether any still waits."""
    requests = {}
    for name in names:
        requests[name] = SwitchRequest(cm, [name], [], STRICT, timeout)
        time.sleep(0.05)
    end = time.monotonic() + 3.0
    while any(r.waiting for r in requests.values()) and time.monotonic() < end:
        cm.update(0, PERIOD_NS)
        time.sleep(0.002)
    results = {n: r.result for n, r in requests.items() if not r.waiting}
    return results, any(r.waiting for r in requests.values())


def test_concurrent_switch_requests_are_all_served(rig):
    """Two spawners in one namespace call switch_controller at the same time (rospy serves
    each call on its own thread). Both calls must be carried out and return True."""
    cm, _, _, _ = rig
    cm.load_controller('joint_state_controller')
    cm.load_controller('flap_controller')
    results, waiting = switch_concurrently(cm, ('joint_state_controller', 'flap_controller'), 1.0)
    assert not waiting
    assert results == {'joint_state_controller': True, 'flap_controller': True}
    assert states(cm) == {'joint_state_controller': 'running', 'flap_controller': 'running'}


def test_concurrent_conflicting_switches_never_run_both(rig):
    cm, _, _, _ = rig
    cm.load_controller('flap_controller')
    cm.load_controller('flap_other_controller')
    results, _ = switch_concurrently(cm, ('flap_controller', 'flap_other_controller'), 0.5)
    running = [n for n, s in states(cm).items() if s == 'running']
    assert len(running) == 1
    assert results[running[0]] is True


def test_concurrent_loads_of_one_name_load_it_once(rig):
    """Two load_controller calls for the same name on two service threads: one loads it,
    the other is told it is already loaded, and no node handle is leaked."""
    cm, _, _, ros = rig
    first_inside = threading.Event()
    second_done = threading.Event()
    make_handle = ros.node_handle
    calls = []

    def slow_factory(namespace):
        calls.append(namespace)
        if namespace == NS + '/flap_controller' and not first_inside.is_set():
            first_inside.set()
            second_done.wait(0.5)  # the first load is still setting up when the second comes
        return make_handle(namespace)

    cm.node_factory = slow_factory
    outcomes = {}

    def load(tag):
        try:
            cm.load_controller('flap_controller')
            outcomes[tag] = 'loaded'
        except ControllerManagerError as exc:
            outcomes[tag] = str(exc)
        finally:
            if tag == 'second':
                second_done.set()

    t1 = threading.Thread(target=load, args=('first',), daemon=True)
    t1.start()
    assert first_inside.wait(2.0)
    t2 = threading.Thread(target=load, args=('second',), daemon=True)
    t2.start()
    t1.join(3.0)
    t2.join(3.0)
    assert sorted(outcomes) == ['first', 'second']
    assert list(outcomes.values()).count('loaded') == 1, outcomes
    assert any('already loaded' in v for v in outcomes.values()), outcomes
    # exactly one live subscriber to the command topic: the loaded controller's
    assert len(ros.subscribers[NS + '/flap_controller/command']) == 1


# ----------------------------------------------------------------------------- seams
def test_every_registered_type_loads_under_its_type_name():
    assert (
        sorted(CONTROLLER_TYPES)
        == ControllerManager(None, FakeRos().node_handle, '/x').controller_types()
    )
    for type_name, cls in CONTROLLER_TYPES.items():
        assert issubclass(cls, Controller) and cls.type_name == type_name


def test_two_classes_with_one_type_name_are_refused():
    class Other(JointPositionController):
        pass

    with pytest.raises(TypeError, match="Other: type_name '%s'" % JPC):
        by_type_name((JointPositionController, Other))


def test_the_controller_owns_its_run_state_and_the_manager_reports_it(rig):
    cm, _, _, _ = rig
    c = cm.load_controller('flap_controller')
    assert c.state == 'initialized'
    assert pump_switch(cm, ['flap_controller'])[0]
    assert c.state == 'running' and c.running
    assert pump_switch(cm, [], ['flap_controller'])[0]
    assert c.state == 'stopped' and not c.running
    assert states(cm) == {'flap_controller': 'stopped'}


def test_switch_while_updating_gives_up_after_its_deadline_and_says_so(rig):
    cm, _, _, _ = rig
    cm.load_controller('flap_controller')
    with pytest.raises(SwitchTimeout, match=r"start=\['flap_controller'\].*0.2 s"):
        switch_while_updating(cm, ['flap_controller'], [], lambda: None, deadline=0.2)
    cm.update(0, PERIOD_NS)  # the call still waiting is served at the next update
    assert states(cm) == {'flap_controller': 'running'}


def test_switch_while_updating_passes_on_what_the_switch_raised():
    class Broken:
        def switch_controller(self, start, stop, strictness, timeout):
            raise ValueError('broken manager')

    with pytest.raises(ValueError, match='broken manager'):
        switch_while_updating(Broken(), ['c'], [], lambda: None)
