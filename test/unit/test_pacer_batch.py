"""Pacer with several steps per wake-up (sim/pacer.py): half the sleeps, same schedule, and
wake() lets input reach the next step as soon as without batching."""

import threading
import time

import pytest
from helpers import FakeClock

from _arm1sim.sim.pacer import Pacer


def test_two_steps_per_wake_up_keep_the_schedule_with_half_the_sleeps():
    clock = FakeClock()
    pacer = Pacer(0.001, clock, clock.sleep, clock.nap)
    pacer.steps_per_wake = 2
    start = clock.t
    for _ in range(1000):
        clock.t += 0.0001  # a step's work
        pacer.wait()
    assert 1.0 <= clock.t - start <= 1.0 + 0.0011  # no drift; at most a step's offset
    assert len(clock.sleeps) == 500
    assert {kind for kind, _ in clock.sleeps} == {'nap'}


def test_a_wake_during_a_batched_sleep_runs_the_next_step_when_due():
    clock = FakeClock()
    pacer = Pacer(0.001, clock, clock.sleep, clock.nap)
    pacer.steps_per_wake = 4
    start = clock.t
    clock.t += 0.0001
    clock.wake_after = 0.0002  # a command arrives 0.3 ms after the first step began
    pacer.wait()
    # Woken, then slept only until the next step was due: 1 ms after the first, as unbatched.
    assert [k for k, _ in clock.sleeps] == ['woken', 'sleep']
    assert clock.t - start == pytest.approx(0.001)


def test_a_wake_after_the_next_step_is_due_sleeps_no_more():
    clock = FakeClock()
    pacer = Pacer(0.001, clock, clock.sleep, clock.nap)
    pacer.steps_per_wake = 4
    start = clock.t
    clock.wake_after = 0.0015
    pacer.wait()
    assert [k for k, _ in clock.sleeps] == ['woken']
    assert clock.t - start == pytest.approx(0.0015)


def test_wake_from_another_thread_ends_a_real_nap():
    pacer = Pacer(0.001)
    threading.Timer(0.05, pacer.wake).start()
    t = time.perf_counter()
    assert pacer.nap(5.0) is True
    assert time.perf_counter() - t < 2.0
    assert pacer.nap(0.01) is False  # one wake ends one nap
    pacer.wake()
    pacer.wake()  # a second before it is seen is harmless
    assert pacer.nap(0.01) is True
    assert pacer.nap(0.01) is False
