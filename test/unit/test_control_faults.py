"""Bad input to the controller manager and the position controller: refused or clamped, said
once."""

import logging
import math

import pytest
from conftest import pump_switch
from helpers import PositionControllerRig as Rig
from helpers import mixed_rig, states  # noqa: F401 (mixed_rig is the rig fixture)

from _arm1sim.control.controller_manager import BEST_EFFORT, STRICT, ControllerManagerError


@pytest.mark.parametrize(
    'name, why',
    [
        ('', 'the name is empty'),
        ('two words', 'not a valid controller name'),
        ('/absolute', 'not a valid controller name'),
        ('../up', 'not a valid controller name'),
        ('x' * 300, 'not a valid controller name'),
    ],
)
def test_load_refuses_names_that_are_not_relative_ros_names(rig, name, why):  # noqa: F811
    cm, _, _, _ = rig
    with pytest.raises(ControllerManagerError, match=why) as info:
        cm.load_controller(name)
    assert len(str(info.value)) < 300, 'the whole name went into the message'


def test_nested_controller_names_are_still_valid(rig):  # noqa: F811
    cm, _, _, _ = rig
    with pytest.raises(ControllerManagerError, match='type was not specified'):
        cm.load_controller('group/flap_controller')


def test_best_effort_says_once_which_names_it_skips(rig, caplog):  # noqa: F811
    cm, _, _, _ = rig
    cm.load_controller('flap_controller')
    names = ['ghost%d' % i for i in range(1000)]
    with caplog.at_level(logging.WARNING, logger='_arm1sim.control'):
        ok, _ = pump_switch(cm, ['flap_controller'] + names, names, strictness=BEST_EFFORT)
    assert ok is True
    assert states(cm)['flap_controller'] == 'running'
    said = [r.getMessage() for r in caplog.records]
    assert len(said) == 2, said
    assert "Not starting controllers 'ghost0', 'ghost1'" in said[0]
    assert 'and 995 more: they are not loaded' in said[0]
    assert said[1].startswith('Not stopping controllers')


def test_strict_names_the_first_unknown_only(rig, caplog):  # noqa: F811
    cm, _, _, _ = rig
    with caplog.at_level(logging.ERROR, logger='_arm1sim.control'):
        assert cm.switch_controller(['ghost%d' % i for i in range(1000)], [], STRICT) is False
    assert [r.getMessage() for r in caplog.records] == [
        "Could not start controller 'ghost0': it is not loaded"
    ]


@pytest.mark.parametrize('strictness', [0, 3, -1])
def test_invalid_strictness_is_best_effort_with_a_warning(rig, caplog, strictness):  # noqa: F811
    cm, _, _, _ = rig
    cm.load_controller('flap_controller')
    with caplog.at_level(logging.WARNING, logger='_arm1sim.control'):
        ok, _ = pump_switch(cm, ['flap_controller', 'ghost'], strictness=strictness)
    assert ok is True
    assert any('strictness %d' % strictness in r.getMessage() for r in caplog.records)


@pytest.mark.parametrize('timeout', [math.nan, math.inf, 1e300, -1.0])
def test_a_timeout_no_wait_can_take_means_wait_for_the_update(rig, timeout):  # noqa: F811
    cm, _, _, _ = rig
    cm.load_controller('flap_controller')
    ok, updates = pump_switch(cm, ['flap_controller'], timeout=timeout)
    assert ok is True and updates >= 1
    assert states(cm)['flap_controller'] == 'running'


def test_a_command_outside_the_limits_is_clamped_and_said_once_per_start(caplog):
    jrig = Rig('slider_joint', {'p': 1.0})
    caplog.clear()  # the jrig's own passive-joint message
    jrig.start()
    with caplog.at_level(logging.WARNING, logger='_arm1sim.control'):
        jrig.command(1e300)
        jrig.command(-5.0)
        jrig.command(0.1)
    jrig.update()
    assert jrig.states()[-1]['set_point'] == pytest.approx(0.1)
    said = [r.getMessage() for r in caplog.records]
    assert (
        len(said) == 1
        and 'c: command 1e+300 for joint slider_joint is outside its limits' in said[0]
        and 'clamped to 0.2000' in said[0]
    ), said
    jrig.stop()
    jrig.start()
    with caplog.at_level(logging.WARNING, logger='_arm1sim.control'):
        jrig.command(7.0)
    assert len(caplog.records) == 2


def test_negative_gains_apply_with_a_warning_naming_the_controller(caplog):
    jrig = Rig('flap_joint', {'p': 1.0})
    caplog.clear()
    with caplog.at_level(logging.WARNING, logger='_arm1sim.control'):
        applied = jrig.c.set_gains({'p': -2.0, 'd': -0.5})
    assert (applied['p'], applied['d']) == (-2.0, -0.5)
    said = [r.getMessage() for r in caplog.records]
    assert len(said) == 1 and said[0].startswith('c: negative pid gain(s) p=-2, d=-0.5')
