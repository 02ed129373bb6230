"""Paces simulation steps against the wall clock, and measures the real-time factor."""

import threading
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
    """Sleeps between steps so that step k runs at ``start + k * period`` of wall time.

    With ``steps_per_wake`` N > 1 it sleeps until N steps are due and lets them run back to
    back: N times fewer wake-ups (each costs CPU, and the first step after one runs on cold
    caches). ``wake()`` (any thread: a command or a hand-over call arrived) cuts such a sleep
    short, so the next step runs when due, as with one step per wake-up: input waits no
    longer than it would without batching.
    """

    MAX_LAG = 0.1  # further behind than this, catch up no more: start a new schedule
    # Longer waits are napped, so that wake() ends them: a slow schedule (set_physics_
    # properties' max_update_rate 0.1 is a 10 s period) must not hold a hand-over call
    # (a service answer, the next rate change) for its whole period.
    MAX_SLEEP = 0.05

    def __init__(self, period, clock=time.perf_counter, sleep=time.sleep, nap=None):
        """``nap(seconds)``: an interruptible sleep, True when woken (default: by wake())."""
        self.period, self.clock, self.sleep = period, clock, sleep
        self.steps_per_wake = 1
        self._woken = threading.Lock()
        self._woken.acquire()  # held while nobody has called wake()
        self.nap = nap or self._nap
        self._batched = False
        self.restart()

    def restart(self):
        self._start = self.clock()
        self._count = 0

    def wake(self):
        """Any thread: end a batched or long sleep now (the next step still waits for its
        time)."""
        try:
            self._woken.release()
        except RuntimeError:  # already woken, not yet seen
            pass

    def _nap(self, seconds):
        return self._woken.acquire(timeout=seconds)

    def wait(self):
        """Call once per step, after it: sleeps until the next step is due. True then; False
        when woken before (a call to serve): serve it, then call ``resume`` until True."""
        self._count += 1
        self._batched = self.steps_per_wake > 1
        return self.resume()

    def resume(self):
        """Go on waiting for the step ``wait`` waits for (or the schedule since restart)."""
        if self.period <= 0:
            return True
        due = self._start + self._count * self.period
        ahead = due - self.clock()
        if ahead <= 0:
            if ahead < -self.MAX_LAG:
                self.restart()
            return True
        woken = False
        if self._batched:
            self._batched = False
            if not self.nap(ahead + (self.steps_per_wake - 1) * self.period):
                return True  # slept until the batch's last step was due: run them all now
            woken = True  # the next step at its own time
            ahead = due - self.clock()
            if ahead <= 0:
                return True
        if ahead <= self.MAX_SLEEP:
            self.sleep(ahead)
            return True
        return not woken and not self.nap(ahead)


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
