"""The velocity-limit chatter diagnosis (sim/limit_chatter.py): the world warns once, naming
the joint, its velocity limit and the fix, when arm1's trajectory controller is caught in the
trap with the URDF's limits; nothing is said once the yaml lifts the cut or when a joint
merely moves fast."""

import logging

import pytest
from helpers import JOINTS, largest_speed_at_the_end, trajectory_params

from _arm1sim.sim.limit_chatter import STEPS, LimitChatterWatch


def test_the_watch_sees_sign_flips_beyond_the_limit_only():
    watch = LimitChatterWatch([('a', 0.5), ('b', 0.5)])
    found = []
    for k in range(3 * STEPS):
        sign = 1 if k % 2 else -1
        # a: flips beyond the limit; b: fast one way, then flips within the limit
        found += watch.observe([2.0 * sign, 3.0 if k < STEPS else 0.3 * sign])
    assert found == [('a', 0.5)]
    for k in range(3 * STEPS):  # once only
        assert watch.observe([2.0 * (1 if k % 2 else -1), 0.0]) == []


def test_a_short_burst_of_flips_is_not_a_chatter():
    watch = LimitChatterWatch([('a', 0.5)])
    for _ in range(5):
        for k in range(STEPS - 1):
            assert watch.observe([2.0 * (1 if k % 2 else -1)]) == []
        watch.observe([0.0])


@pytest.mark.parametrize('lifted', [False, True], ids=['urdf_limits', 'yaml_joint_limits'])
def test_arm1_in_the_trap_is_warned_about_once_per_joint(arm1_urdf, lifted, caplog):
    limits = trajectory_params()['arm1']['joint_limits'] if lifted else {}
    with caplog.at_level(logging.WARNING, logger='arm1'):
        largest_speed_at_the_end(arm1_urdf, limits)
    said = [r.getMessage() for r in caplog.records if 'velocity-limit chatter' in r.getMessage()]
    if lifted:
        assert said == []
        return
    assert said, 'no warning about the chatter'
    named = [next(j for j in JOINTS if "joint '%s'" % j in m) for m in said]
    assert len(named) == len(set(named)), 'a joint warned about twice'
    for m, joint in zip(said, named):
        assert 'velocity limit of 0.5' in m
        assert 'joint_limits/%s/has_velocity_limits: false' % joint in m
        assert 'gains' in m


def test_try_robot_reports_the_chatter_warning_as_a_problem():
    from _arm1sim.sim.limit_chatter import chatter_message
    from _arm1sim.tryout import report

    message = chatter_message('joint2', 0.5)
    rep = {
        'build': {'ok': True},
        'bringup': {'up': True, 'alive': True},
        'controller_managers': {'/arm1': [{'name': 'c', 'type': 't', 'state': 'running'}]},
        'motion': [{'controller': '/arm1/c', 'ok': True}],
        'warnings': [{'level': 'WARN', 'node': '/gazebo', 'message': message, 'count': 1}],
    }
    v = report.verdict(rep)
    assert v == {'ok': False, 'problems': [message]}


def test_a_non_finite_velocity_breaks_a_run():
    """NaN is beyond no limit: it ends a run of flips, as a velocity within the limit does."""
    watch = LimitChatterWatch([('a', 0.5)])
    for k in range(STEPS - 1):
        assert watch.observe([2.0 * (1 if k % 2 else -1)]) == []
    assert watch.observe([float('nan')]) == []
    found = []  # a run starts again: STEPS flips need STEPS + 1 velocities
    for k in range(STEPS + 1):
        found.append(watch.observe([2.0 * (1 if k % 2 else -1)]))
    assert found[:-1] == [[]] * STEPS and found[-1] == [('a', 0.5)]
