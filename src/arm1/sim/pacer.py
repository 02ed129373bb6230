"""Paces simulation steps against the wall clock, and measures the real-time factor."""

import time


def wall_period(step, real_time_factor, real_time_update_rate):
    """Wall seconds per step: the slower of the update rate and the real-time factor; 0 = flat out.

    Gazebo sleeps to ``real_time_update_rate`` steps per wall second; a
    ``real_time_factor`` below that pace (e.g. 0.5) slows it further.
    """
    if real_time_update_rate <= 0 or real_time_factor <= 0:
        return 0.0
    return max(1.0 / real_time_update_rate, step / real_time_factor)


class Pacer:
    MAX_LAG = 0.1  # further behind than this, catch up no more: start a new schedule

    def __init__(self, period, clock=time.perf_counter, sleep=time.sleep):
        self.period, self.clock, self.sleep = period, clock, sleep
        self.restart()

    def restart(self):
        self._start = self.clock()
        self._count = 0

    def wait(self):
        """Call once per step, after it: sleeps until the next step is due."""
        self._count += 1
        if self.period <= 0:
            return
        due = self._start + self._count * self.period
        ahead = due - self.clock()
        if ahead > 0:
            self.sleep(ahead)
        elif ahead < -self.MAX_LAG:
            self.restart()


class RealTimeFactorMeter:
    """Sim seconds per wall second over a sliding window of ``window`` wall seconds."""

    def __init__(self, window=1.0, clock=time.perf_counter):
        self.window, self.clock = window, clock
        self._mark = None
        self.value = 0.0

    def update(self, sim_time):
        now = self.clock()
        if self._mark is None or sim_time < self._mark[1]:
            self._mark = (now, sim_time)
            return False
        wall = now - self._mark[0]
        if wall < self.window:
            return False
        self.value = (sim_time - self._mark[1]) / wall
        self._mark = (now, sim_time)
        return True

    def pause(self):
        """Forget the window: paused time is not slow time."""
        self._mark = None
