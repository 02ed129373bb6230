"""pacer.py with a fake clock: wall_period, Pacer, RealTimeFactorMeter."""

import pytest

from _arm1sim.sim.pacer import Pacer, RealTimeFactorMeter, wall_period


class FakeClock:
    def __init__(self, t=100.0):
        self.t = t
        self.sleeps = []

    def __call__(self):
        return self.t

    def sleep(self, dt):
        assert dt > 0
        self.sleeps.append(dt)
        self.t += dt

    def work(self, dt):
        self.t += dt


@pytest.mark.parametrize(
    'step, rtf, rate, expected',
    [
        (0.001, 1.0, 1000.0, 0.001),
        (0.001, 0.5, 1000.0, 0.002),  # real-time factor slows it
        (0.001, 1.0, 500.0, 0.002),  # update rate slows it
        (0.001, 2.0, 1000.0, 0.001),  # rtf above what the update rate allows: the rate wins
        (0.001, 1.0, 0.0, 0.0),  # update rate 0: as fast as possible
        (0.002, 1.0, 500.0, 0.002),
    ],
)
def test_wall_period(step, rtf, rate, expected):
    assert wall_period(step, rtf, rate) == pytest.approx(expected)


def test_pacer_keeps_a_fixed_schedule():
    clock = FakeClock()
    pacer = Pacer(0.001, clock, clock.sleep)
    start = clock.t
    for k in range(1000):
        clock.work(0.0004 if k % 2 else 0.0009)  # uneven work, always under the period
        pacer.wait()
    assert clock.t - start == pytest.approx(1.0, abs=1e-9)


def test_pacer_catches_up_a_short_lag_without_drift():
    clock = FakeClock()
    pacer = Pacer(0.001, clock, clock.sleep)
    start = clock.t
    clock.work(0.005)  # one slow step: 4 ms behind
    pacer.wait()
    n_sleeps = len(clock.sleeps)
    for _ in range(9):
        pacer.wait()  # the next steps run without sleeping until back on schedule
    assert clock.t - start == pytest.approx(0.010)
    assert len(clock.sleeps) - n_sleeps <= 5
    for _ in range(990):
        pacer.wait()
    assert clock.t - start == pytest.approx(1.0, abs=1e-9)


def test_pacer_restarts_its_schedule_after_a_long_stall():
    clock = FakeClock()
    pacer = Pacer(0.001, clock, clock.sleep)
    pacer.wait()
    clock.work(0.5)  # far behind (more than MAX_LAG)
    pacer.wait()
    stall_end = clock.t
    for _ in range(100):
        pacer.wait()
    # a fresh schedule from the stall: 100 periods, no burst of catch-up steps
    assert clock.t - stall_end == pytest.approx(0.1, abs=1e-9)


def test_pacer_with_zero_period_never_sleeps():
    clock = FakeClock()
    pacer = Pacer(0.0, clock, clock.sleep)
    for _ in range(100):
        pacer.wait()
    assert clock.sleeps == []


def test_pacer_restart_forgets_the_past():
    clock = FakeClock()
    pacer = Pacer(0.01, clock, clock.sleep)
    for _ in range(5):
        pacer.wait()
    clock.work(0.05)  # e.g. paused; restart on unpause
    pacer.restart()
    t0 = clock.t
    pacer.wait()
    assert clock.t - t0 == pytest.approx(0.01)


def test_rtf_meter_measures_sim_over_wall_per_window():
    clock = FakeClock()
    meter = RealTimeFactorMeter(1.0, clock)
    assert meter.update(0.0) is False
    sim = 0.0
    reported = []
    for _ in range(3000):  # 3 wall seconds at half real time
        clock.work(0.001)
        sim += 0.0005
        if meter.update(sim):
            reported.append(meter.value)
    assert len(reported) in (2, 3)
    assert all(v == pytest.approx(0.5, rel=1e-3) for v in reported)


def test_rtf_meter_pause_and_time_going_back():
    clock = FakeClock()
    meter = RealTimeFactorMeter(1.0, clock)
    meter.update(5.0)
    clock.work(0.5)
    meter.pause()
    clock.work(10.0)  # paused: the long wall time must not count
    assert meter.update(5.0) is False  # restarts the window
    clock.work(1.0)
    assert meter.update(6.0) is True
    assert meter.value == pytest.approx(1.0)
    # reset_simulation: sim time jumps back, the window restarts rather than reporting < 0
    clock.work(0.5)
    assert meter.update(0.0) is False
    clock.work(1.0)
    assert meter.update(2.0) is True
    assert meter.value == pytest.approx(2.0)
