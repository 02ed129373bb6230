"""A slow schedule (set_physics_properties' max_update_rate 0.1: one step per 10 s) can be
woken: a hand-over call is served within a short sleep, not after the period, and a new
rate takes effect at once (sim/pacer.py)."""

import threading
import time

import pytest
from helpers import FakeClock

from _arm1sim.sim.pacer import Pacer


@pytest.mark.parametrize('steps_per_wake', [1, 2])
def test_a_wake_in_a_10_s_wait_returns_to_serve_the_call(steps_per_wake):
    clock = FakeClock()
    pacer = Pacer(10.0, clock, clock.sleep, clock.nap)
    pacer.steps_per_wake = steps_per_wake
    start = clock.t
    clock.wake_after = 0.2
    assert pacer.wait() is False  # woken: serve the call
    assert clock.t - start == pytest.approx(0.2)
    assert pacer.resume() is True  # nobody else: the step's own time
    assert clock.t - start == pytest.approx(10.0)


def test_no_plain_sleep_is_longer_than_max_sleep():
    clock = FakeClock()
    pacer = Pacer(10.0, clock, clock.sleep, clock.nap)
    for _ in range(3):
        clock.t += 0.001
        assert pacer.wait() is True
    assert all(dt <= Pacer.MAX_SLEEP for kind, dt in clock.sleeps if kind == 'sleep')


def test_a_rate_change_while_waiting_takes_effect_at_once():
    clock = FakeClock()
    pacer = Pacer(10.0, clock, clock.sleep, clock.nap)
    clock.wake_after = 0.01
    assert pacer.wait() is False
    pacer.period = 0.001  # what the served call (set_physics_properties) does
    pacer.restart()
    assert pacer.resume() is True
    assert clock.t - 100.0 == pytest.approx(0.01)


def test_a_real_10_s_wait_is_woken_from_another_thread():
    pacer = Pacer(10.0)
    threading.Timer(0.05, pacer.wake).start()
    t = time.perf_counter()
    assert pacer.wait() is False
    assert time.perf_counter() - t < 5.0  # not the 10 s period
