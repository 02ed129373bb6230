"""Pacer with several steps per wake-up (sim/pacer.py): fewer sleeps, same schedule, batches
ending on the clock's steps, and wake() lets input reach the next step as soon as without
batching."""

import threading
import time

import pytest
from helpers import FakeClock

from _arm1sim.sim.pacer import Pacer, steps_per_wake


def test_two_steps_per_wake_up_keep_the_schedule_with_half_the_sleeps():
    clock = FakeClock()
    pacer = Pacer(0.001, clock, clock.sleep, clock.nap)
    pacer.steps_per_wake = 2
    start = clock.t
    for _ in range(1000):
        clock.t += 0.0001  # a step's work
        pacer.wait()
    assert 1.0 <= clock.t - start <= 1.0 + 0.0011  # no drift; at most a step's offset
    assert len(clock.sleeps) == 501  # the first step alone, then pairs ending on even steps
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


def _batch_ends(clock, pacer, steps, first_done=0, wake_at=None):
    """Steps done when each sleep began, over ``steps`` steps from ``first_done``."""
    ends = []
    for done in range(first_done + 1, first_done + steps + 1):
        clock.t += 0.00002  # a step's work: a batch of 10 takes a fifth of a period
        before = len(clock.sleeps)
        if done == wake_at:
            clock.wake_after = 0.0002
        if not pacer.wait(done):
            while not pacer.resume():
                pass
        if len(clock.sleeps) > before:
            ends.append(done)
    return ends


def test_batches_end_where_the_steps_done_are_a_multiple_of_the_batch():
    clock = FakeClock()
    pacer = Pacer(0.001, clock, clock.sleep, clock.nap)
    pacer.steps_per_wake = 10
    start = clock.t
    # 3 steps were done before this schedule (a world unpaused at sim time 3 ms)
    ends = _batch_ends(clock, pacer, 57, first_done=3)
    assert ends == [4, 10, 20, 30, 40, 50, 60]
    # the schedule holds: the last sleep ends when step 70 (the 67th of this schedule) is due
    assert clock.t - start == pytest.approx(0.066, abs=1e-9)


def test_a_wake_in_a_batch_runs_the_next_step_then_the_batch_ends_where_it_would_have():
    clock = FakeClock()
    pacer = Pacer(0.001, clock, clock.sleep, clock.nap)
    pacer.steps_per_wake = 10
    ends = _batch_ends(clock, pacer, 30, wake_at=10)
    # woken in the sleep after step 10: step 11 at its own time, then on to 20, not to 21
    assert ends == [1, 10, 11, 20, 30]


@pytest.mark.parametrize(
    'clock_hz, step, period, steps',
    [
        (100, 0.001, 0.001, 10),  # gazebo.launch: 1 kHz, /clock at 100 Hz: one wake-up a message
        (1000, 0.001, 0.001, 2),  # /clock every step: two steps a wake-up, as before
        (100, 0.001, 0.01, 2),  # real-time factor 0.1: 10 ms a step, no longer batches
        (100, 0.002, 0.002, 5),
        (100, 0.001, 0.0, 10),  # flat out: the pacer never sleeps anyway
        (30, 0.001, 0.001, 10),  # a slow clock: at most 10 ms of wall time a batch
    ],
)
def test_steps_per_wake_are_a_clock_period_within_10_ms_of_wall_time(clock_hz, step, period, steps):
    assert steps_per_wake(int(1e9 / clock_hz), int(step * 1e9), period) == steps
