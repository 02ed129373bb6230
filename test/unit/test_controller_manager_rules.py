"""switch_controller and reload_controller_libraries rule by rule, as ros_control noetic's
controller_manager.cpp decides them (one test per rule)."""

import logging
import threading

import pytest
from conftest import pump_switch
from helpers import MS as PERIOD_NS
from helpers import mixed_rig, states  # noqa: F401 (mixed_rig is the rig fixture)

from _arm1sim.control.controller_manager import BEST_EFFORT, STRICT


def count_calls(controller, hook):
    """Count calls of a controller's ``starting`` or ``stopping`` hook."""
    calls = []
    original = getattr(controller, hook)

    def counted(time_ns):
        calls.append(time_ns)
        original(time_ns)

    setattr(controller, hook, counted)
    return calls


def loaded(cm, *names):
    for name in names:
        cm.load_controller(name)
    return cm


# ------------------------------------------------------------------ unknown names
def test_strict_refuses_an_unknown_name_in_the_stop_list_and_stops_nothing(rig):  # noqa: F811
    cm = loaded(rig[0], 'flap_controller')
    assert pump_switch(cm, ['flap_controller'])[0]
    assert cm.switch_controller([], ['flap_controller', 'ghost'], STRICT) is False
    cm.update(0, PERIOD_NS)
    assert states(cm)['flap_controller'] == 'running'


def test_best_effort_skips_unknown_names_in_both_lists(rig):  # noqa: F811
    cm = loaded(rig[0], 'flap_controller')
    assert pump_switch(cm, ['ghost', 'flap_controller'], ['phantom'], BEST_EFFORT)[0]
    assert states(cm)['flap_controller'] == 'running'


# ------------------------------------------------------------------ already so
def test_strict_refuses_stopping_a_controller_that_is_not_running(rig):  # noqa: F811
    cm = loaded(rig[0], 'flap_controller', 'wheel_controller')
    assert cm.switch_controller(['wheel_controller'], ['flap_controller'], STRICT) is False
    cm.update(0, PERIOD_NS)
    assert states(cm)['wheel_controller'] == 'initialized'


def test_best_effort_skips_stopping_a_controller_that_is_not_running(rig):  # noqa: F811
    cm = loaded(rig[0], 'flap_controller', 'wheel_controller')
    stopping = count_calls(cm.controller('flap_controller'), 'stopping')
    assert pump_switch(cm, ['wheel_controller'], ['flap_controller'], BEST_EFFORT)[0]
    assert states(cm) == {'flap_controller': 'initialized', 'wheel_controller': 'running'}
    assert stopping == []


def test_strict_refuses_starting_a_running_controller(rig):  # noqa: F811
    cm = loaded(rig[0], 'flap_controller')
    assert pump_switch(cm, ['flap_controller'])[0]
    starting = count_calls(cm.controller('flap_controller'), 'starting')
    assert cm.switch_controller(['flap_controller'], [], STRICT) is False
    cm.update(0, PERIOD_NS)
    assert starting == []


def test_best_effort_starts_a_running_controller_again_without_stopping_it(rig):  # noqa: F811
    # ControllerBase::startRequest works from RUNNING: its starting() runs once more.
    cm = loaded(rig[0], 'flap_controller')
    assert pump_switch(cm, ['flap_controller'])[0]
    flap = cm.controller('flap_controller')
    starting, stopping = count_calls(flap, 'starting'), count_calls(flap, 'stopping')
    assert pump_switch(cm, ['flap_controller'], [], BEST_EFFORT, time_ns=7)[0]
    assert (starting, stopping) == ([7], [])
    assert states(cm)['flap_controller'] == 'running'


# ------------------------------------------------------------------ named in both lists
@pytest.mark.parametrize('strictness', [STRICT, BEST_EFFORT])
def test_a_running_controller_in_both_lists_is_refused(rig, strictness, caplog):  # noqa: F811
    cm = loaded(rig[0], 'flap_controller')
    assert pump_switch(cm, ['flap_controller'])[0]
    flap = cm.controller('flap_controller')
    starting, stopping = count_calls(flap, 'starting'), count_calls(flap, 'stopping')
    with caplog.at_level(logging.ERROR, logger='_arm1sim.control'):
        ok = cm.switch_controller(['flap_controller'], ['flap_controller'], strictness)
    assert ok is False
    assert 'conflicting switching command' in caplog.text and 'flap_controller' in caplog.text
    cm.update(0, PERIOD_NS)
    assert states(cm)['flap_controller'] == 'running'
    assert (starting, stopping) == ([], [])


def test_strict_refuses_a_stopped_controller_in_both_lists(rig):  # noqa: F811
    cm = loaded(rig[0], 'flap_controller')
    assert cm.switch_controller(['flap_controller'], ['flap_controller'], STRICT) is False
    cm.update(0, PERIOD_NS)
    assert states(cm)['flap_controller'] == 'initialized'


def test_best_effort_starts_a_stopped_controller_in_both_lists(rig):  # noqa: F811
    cm = loaded(rig[0], 'flap_controller')
    assert pump_switch(cm, ['flap_controller'], ['flap_controller'], BEST_EFFORT)[0]
    assert states(cm)['flap_controller'] == 'running'


# ------------------------------------------------------------------ resources, timeout
def test_a_restart_counts_as_a_claim_in_the_conflict_check(rig):  # noqa: F811
    cm = loaded(rig[0], 'flap_controller', 'flap_other_controller')
    assert pump_switch(cm, ['flap_controller'])[0]
    ok = cm.switch_controller(['flap_controller', 'flap_other_controller'], [], BEST_EFFORT)
    assert ok is False
    cm.update(0, PERIOD_NS)
    assert states(cm)['flap_other_controller'] == 'initialized'


def test_a_timeout_gives_up_without_an_update_and_a_zero_timeout_waits(rig):  # noqa: F811
    cm = loaded(rig[0], 'flap_controller')
    assert cm.switch_controller(['flap_controller'], [], STRICT, timeout=0.05) is False
    result = []
    waiter = threading.Thread(
        target=lambda: result.append(cm.switch_controller(['flap_controller'], [], STRICT, 0.0))
    )
    waiter.start()
    waiter.join(0.3)
    assert waiter.is_alive(), 'timeout 0 returned without an update'
    cm.update(0, PERIOD_NS)
    waiter.join(2.0)
    assert result == [True]


# ------------------------------------------------------------------ reload_controller_libraries
def test_reload_without_force_kill_refuses_while_controllers_are_loaded(rig, caplog):  # noqa: F811
    cm = loaded(rig[0], 'flap_controller')  # loaded, not even running
    with caplog.at_level(logging.ERROR, logger='_arm1sim.control'):
        assert cm.reload_controller_libraries(False) is False
    assert 'flap_controller' in caplog.text
    assert states(cm) == {'flap_controller': 'initialized'}


def test_reload_with_nothing_loaded_succeeds(rig):  # noqa: F811
    assert rig[0].reload_controller_libraries(False) is True


def test_reload_with_force_kill_stops_and_unloads_every_controller(rig):  # noqa: F811
    cm = loaded(rig[0], 'flap_controller', 'wheel_controller', 'joint_state_controller')
    assert pump_switch(cm, ['flap_controller', 'joint_state_controller'])[0]
    stopping = count_calls(cm.controller('flap_controller'), 'stopping')
    result = []
    reload = threading.Thread(target=lambda: result.append(cm.reload_controller_libraries(True)))
    reload.start()
    while reload.is_alive():  # the stop waits for an update, as a switch does
        cm.update(0, PERIOD_NS)
        reload.join(0.001)
    assert result == [True]
    assert len(stopping) == 1
    assert states(cm) == {}
    cm.load_controller('flap_controller')  # the names are free again
