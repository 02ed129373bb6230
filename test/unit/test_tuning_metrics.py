"""tuning/metrics.py and tuning/recorded.py on synthetic responses with known figures."""

import math

import pytest

from _arm1sim.tuning.metrics import Criteria, step_metrics, worst
from _arm1sim.tuning.recorded import find_steps, recorded_steps

DT = 1e-4


def first_order(tau, size=0.5, start=0.1, duration=3.0, dt=DT):
    ts = [k * dt for k in range(int(duration / dt) + 1)]
    return ts, [start + size * (1 - math.exp(-t / tau)) for t in ts]


def second_order(zeta, wn, size=1.0, duration=6.0, dt=DT):
    wd = wn * math.sqrt(1 - zeta**2)
    phi = math.acos(zeta)
    ts = [k * dt for k in range(int(duration / dt) + 1)]
    return ts, [
        size * (1 - math.exp(-zeta * wn * t) / math.sqrt(1 - zeta**2) * math.sin(wd * t + phi))
        for t in ts
    ]


def test_first_order_rise_and_settling_time_are_the_textbook_ones():
    tau = 0.2
    ts, xs = first_order(tau)
    m = step_metrics(ts, xs, target=0.6)
    assert m.rise_time == pytest.approx(tau * math.log(9), rel=1e-3)
    assert m.settling_time == pytest.approx(tau * math.log(50), rel=1e-3)
    assert m.overshoot == 0.0
    assert m.steady_state_error == pytest.approx(0.5 * math.exp(-2.75 / tau), abs=1e-5)
    assert m.jitter == pytest.approx(0.5 * (math.exp(-2.5 / tau) - math.exp(-3.0 / tau)), rel=1e-3)
    assert Criteria().ok(m)


def test_downward_steps_measure_the_same():
    tau = 0.1
    ts, xs = first_order(tau, size=-0.3, start=1.0)
    m = step_metrics(ts, xs, target=0.7)
    assert m.rise_time == pytest.approx(tau * math.log(9), rel=1e-3)
    assert m.settling_time == pytest.approx(tau * math.log(50), rel=1e-3)
    assert m.overshoot == 0.0


@pytest.mark.parametrize('zeta', [0.2, 0.5, 0.7])
def test_second_order_overshoot_and_settling(zeta):
    wn = 10.0
    ts, xs = second_order(zeta, wn)
    m = step_metrics(ts, xs, target=1.0)
    expected = 100 * math.exp(-math.pi * zeta / math.sqrt(1 - zeta**2))
    assert m.overshoot == pytest.approx(expected, rel=1e-3)
    # independent settling time: the last sample outside the band, found by brute force
    last_out = max(t for t, x in zip(ts, xs) if abs(x - 1.0) > 0.02)
    assert m.settling_time == pytest.approx(last_out, abs=2 * DT)
    assert m.settled
    assert Criteria().ok(m) == (expected <= 5.0)


def test_never_settling_and_steady_state_error():
    ts = [k * 0.001 for k in range(3001)]
    xs = [0.9 * min(1.0, t / 0.5) for t in ts]  # stops 10 % short of the target
    m = step_metrics(ts, xs, target=1.0)
    assert m.settling_time == math.inf and not m.settled
    assert m.steady_state_error == pytest.approx(0.1)
    assert math.isnan(m.rise_time) is False  # 10 % -> 90 % is reached
    assert m.rise_time == pytest.approx(0.8 * 0.5 / 0.9, rel=1e-3)
    assert 'not settled' in Criteria().failures(m)[0]


def test_jitter_is_the_peak_to_peak_wobble_once_settled():
    ts, xs = first_order(0.05, size=1.0, start=0.0)
    amp = 0.002
    xs = [x + (amp * math.sin(2 * math.pi * 50 * t) if t > 2.0 else 0.0) for t, x in zip(ts, xs)]
    m = step_metrics(ts, xs, target=1.0)
    assert m.jitter == pytest.approx(2 * amp, rel=1e-2)
    assert m.settled  # 2 mrad is inside the 2 % band of a 1 rad step
    assert Criteria(max_jitter=0.001).failures(m) == ['jitter 0.004 rad > 0.001 rad']


def test_step_time_and_start_may_be_given():
    ts, xs = first_order(0.1, size=0.5, start=0.0)
    shifted = [t + 1.0 for t in ts]
    a = step_metrics(ts, xs, 0.5)
    b = step_metrics(shifted, xs, 0.5, start=0.0, t_step=1.0)
    assert b.settling_time == pytest.approx(a.settling_time)
    assert b.rise_time == pytest.approx(a.rise_time)


def test_bad_input_is_refused():
    with pytest.raises(ValueError):
        step_metrics([0.0], [0.0], 1.0)
    with pytest.raises(ValueError):
        step_metrics([0.0, 1.0], [0.5, 0.5], 0.5)


def test_worst_takes_each_figure_from_the_worse_step():
    ts, fast = first_order(0.05)
    _, slow = first_order(0.2)
    a, b = step_metrics(ts, fast, 0.6), step_metrics(ts, slow, 0.6)
    w = worst([a, b])
    assert w.settling_time == b.settling_time and w.rise_time == b.rise_time


# ----------------------------------------------------------------- recorded runs
def test_find_steps_keeps_held_changes_only():
    cmds = [(0.0, 0.0), (1.0, 0.5), (1.1, 0.5), (3.0, 0.52), (3.1, 0.0), (3.2, 0.3)]
    steps = find_steps(cmds, min_step=0.05, min_hold=0.5, end_time=5.0)
    # 0 -> 0.5 held 2 s; 0.5 -> 0.52 too small; 0.52 -> 0 held 0.1 s only; 0 -> 0.3 held
    assert [(t, a, b) for t, a, b, _ in steps] == [(1.0, 0.0, 0.5), (3.2, 0.0, 0.3)]
    assert steps[0][3] == 3.0 and steps[1][3] == 5.0


def test_recorded_steps_match_the_dense_metrics_at_50_hz():
    tau = 0.15
    ts, xs = first_order(tau, size=0.4, start=0.2, duration=2.5, dt=0.001)
    samples = [(1.0 + t, x) for t, x in zip(ts, xs)][::20]  # joint_states at 50 Hz
    samples = [(0.0, 0.2), (0.5, 0.2)] + samples
    commands = [(0.0, 0.2), (0.99, 0.2), (1.0, 0.6)]
    ((t_step, m),) = recorded_steps(commands, samples, lower=-1, upper=1)
    assert t_step == 1.0
    assert m.rise_time == pytest.approx(tau * math.log(9), abs=0.01)
    assert m.settling_time == pytest.approx(tau * math.log(50), abs=0.01)
    assert m.overshoot == 0.0


def test_recorded_targets_are_clamped_to_the_joint_limits():
    samples = [(k * 0.02, min(1.0, k * 0.02)) for k in range(200)]
    ((t, m),) = recorded_steps([(0.0, 0.0), (0.001, 5.0)], samples, lower=-1.0, upper=1.0)
    assert m.target == 1.0
