"""control/pid.py against control_toolbox::Pid as the spec states it."""

import math

import pytest

from _arm1sim.control.pid import Pid, PidConfigError


# ----------------------------------------------------------------------------- parameters
def test_missing_p_is_an_error_with_the_control_toolbox_message():
    with pytest.raises(PidConfigError) as exc:
        Pid.from_params({'i': 1.0, 'd': 0.1}, '/arm1/joint1_position_controller/pid')
    msg = str(exc.value)
    assert msg.startswith('No p gain specified for pid.')
    assert 'Namespace: /arm1/joint1_position_controller/pid' in msg


@pytest.mark.parametrize('params', [None, {}, 'not a dict', 3.0])
def test_missing_pid_block_is_a_missing_p(params):
    with pytest.raises(PidConfigError, match='No p gain specified for pid'):
        Pid.from_params(params, '/ns/c/pid')


def test_i_d_and_i_clamp_default_to_zero():
    pid = Pid.from_params({'p': 2.5})
    assert (pid.p, pid.i, pid.d) == (2.5, 0.0, 0.0)
    assert (pid.i_max, pid.i_min) == (0.0, 0.0)
    assert pid.antiwindup is False


def test_i_clamp_gives_symmetric_bounds_from_its_absolute_value():
    pid = Pid.from_params({'p': 1, 'i': 1, 'i_clamp': -0.3})
    assert pid.i_max == pytest.approx(0.3)
    assert pid.i_min == pytest.approx(-0.3)


def test_i_clamp_min_and_max_override_i_clamp():
    pid = Pid.from_params({'p': 1, 'i': 1, 'i_clamp': 1.0, 'i_clamp_min': -0.2, 'i_clamp_max': 0.7})
    assert (pid.i_min, pid.i_max) == (pytest.approx(-0.2), pytest.approx(0.7))


def test_non_numeric_gain_is_a_config_error_naming_the_namespace():
    with pytest.raises(PidConfigError, match='/ns/c/pid'):
        Pid.from_params({'p': 'stiff'}, '/ns/c/pid')


# ----------------------------------------------------------------------------- P and I terms
def test_proportional_term():
    pid = Pid(p=3.0)
    assert pid.compute_command(0.5, 0.001) == pytest.approx(1.5)
    assert pid.compute_command(-0.2, 0.001) == pytest.approx(-0.6)


def test_integral_term_is_always_zero_without_i_clamp():
    """The seed's `i: 0.001` without i_clamp does nothing in Gazebo."""
    pid = Pid.from_params({'p': 0.0, 'i': 0.001, 'd': 0.0})
    out = [pid.compute_command(1.0, 0.01) for _ in range(1000)]
    assert max(abs(v) for v in out) == 0.0
    # ... and the same with a huge i gain
    pid = Pid.from_params({'p': 0.0, 'i': 1000.0})
    assert all(pid.compute_command(1.0, 0.01) == 0.0 for _ in range(100))


def test_integral_term_accumulates_inside_i_clamp():
    pid = Pid.from_params({'p': 0.0, 'i': 2.0, 'i_clamp': 10.0})
    for _ in range(10):
        cmd = pid.compute_command(1.0, 0.1)
    assert cmd == pytest.approx(2.0 * 1.0)  # i * sum(error * dt) = 2 * 1.0


def test_without_antiwindup_i_clamp_bounds_the_term_but_the_error_winds_up():
    pid = Pid.from_params({'p': 0.0, 'i': 1.0, 'i_clamp': 0.5})
    for _ in range(100):  # 10 s of error 1: accumulated error 10
        cmd = pid.compute_command(1.0, 0.1)
    assert cmd == pytest.approx(0.5)
    assert pid.i_error == pytest.approx(10.0)
    # error reverses for 1 s: the wound-up accumulator keeps the term at the clamp
    for _ in range(10):
        cmd = pid.compute_command(-1.0, 0.1)
    assert cmd == pytest.approx(0.5)
    # negative side is bounded too
    for _ in range(200):
        cmd = pid.compute_command(-1.0, 0.1)
    assert cmd == pytest.approx(-0.5)


def test_antiwindup_clamps_the_accumulated_error_to_i_clamp_over_i():
    pid = Pid.from_params({'p': 0.0, 'i': 2.0, 'i_clamp': 1.0, 'antiwindup': True})
    for _ in range(100):
        cmd = pid.compute_command(1.0, 0.1)
    assert pid.i_error == pytest.approx(0.5)  # i_max / i
    assert cmd == pytest.approx(1.0)
    # no windup: reversing the error for 0.5 s already brings the term to zero...
    for _ in range(5):
        cmd = pid.compute_command(-1.0, 0.1)
    assert cmd == pytest.approx(0.0, abs=1e-12)
    # ... and further on to the lower bound
    for _ in range(100):
        cmd = pid.compute_command(-1.0, 0.1)
    assert pid.i_error == pytest.approx(-0.5)
    assert cmd == pytest.approx(-1.0)


def test_antiwindup_with_asymmetric_clamp():
    pid = Pid.from_params(
        {'p': 0.0, 'i': 4.0, 'i_clamp_min': -0.4, 'i_clamp_max': 2.0, 'antiwindup': True}
    )
    for _ in range(50):
        pid.compute_command(1.0, 0.1)
    assert pid.i_error == pytest.approx(0.5)
    for _ in range(100):
        pid.compute_command(-1.0, 0.1)
    assert pid.i_error == pytest.approx(-0.1)


def test_antiwindup_without_i_clamp_keeps_the_integral_term_zero():
    pid = Pid.from_params({'p': 0.0, 'i': 1.0, 'antiwindup': True})
    assert all(pid.compute_command(1.0, 0.1) == 0.0 for _ in range(20))


# ----------------------------------------------------------------------------- D term
def test_derivative_is_finite_difference_of_the_error():
    pid = Pid(p=0.0, d=0.5)
    pid.compute_command(0.2, 0.01)
    assert pid.compute_command(0.3, 0.01) == pytest.approx(0.5 * (0.3 - 0.2) / 0.01)
    assert pid.compute_command(0.3, 0.01) == pytest.approx(0.0)
    assert pid.compute_command(0.1, 0.02) == pytest.approx(0.5 * (0.1 - 0.3) / 0.02)


def test_first_derivative_after_reset_uses_previous_error_zero():
    pid = Pid(p=0.0, d=1.0)
    assert pid.compute_command(0.5, 0.1) == pytest.approx(5.0)  # fresh: previous error 0
    pid.compute_command(2.0, 0.1)
    pid.reset()
    assert pid.compute_command(0.5, 0.1) == pytest.approx(5.0)  # not (0.5 - 2.0) / 0.1


def test_reset_clears_the_integral():
    pid = Pid.from_params({'p': 0.0, 'i': 1.0, 'i_clamp': 100.0})
    for _ in range(10):
        pid.compute_command(1.0, 0.1)
    pid.reset()
    assert pid.compute_command(1.0, 0.1) == pytest.approx(0.1)


def test_p_i_d_sum():
    pid = Pid.from_params({'p': 2.0, 'i': 3.0, 'd': 0.5, 'i_clamp': 100.0})
    cmd = pid.compute_command(0.4, 0.1)
    assert cmd == pytest.approx(2.0 * 0.4 + 3.0 * 0.04 + 0.5 * 4.0)


# ----------------------------------------------------------------------------- degenerate input
def test_zero_period_gives_zero_and_leaves_state_alone():
    pid = Pid(p=1.0, d=1.0)
    pid.compute_command(0.1, 0.1)
    assert pid.compute_command(5.0, 0.0) == 0.0
    # the zero-period call did not become the "previous error"
    assert pid.compute_command(0.1, 0.1) == pytest.approx(0.1)


@pytest.mark.parametrize('bad', [math.nan, math.inf, -math.inf])
def test_non_finite_error_gives_zero_and_does_not_poison_later_commands(bad):
    pid = Pid.from_params({'p': 1.0, 'i': 1.0, 'd': 1.0, 'i_clamp': 10.0})
    pid.compute_command(0.1, 0.1)
    assert pid.compute_command(bad, 0.1) == 0.0
    nxt = pid.compute_command(0.1, 0.1)
    assert math.isfinite(nxt)
    assert nxt == pytest.approx(0.1 + 1.0 * 0.02 + 0.0)  # p*e + i*(0.01+0.01) + d*0


def test_gains_report():
    pid = Pid.from_params({'p': 1, 'i': 2, 'd': 3, 'i_clamp': 4, 'antiwindup': True})
    assert pid.gains() == dict(
        p=1.0, i=2.0, d=3.0, i_clamp_max=4.0, i_clamp_min=-4.0, antiwindup=True
    )
