"""``/clock`` and ``~real_time_factor`` from the physics thread."""

from __future__ import annotations

import time

import rospy
import rospy.impl.simtime
from rosgraph_msgs.msg import Clock
from std_msgs.msg import Float64

from ...sim.pacer import RealTimeFactorMeter
from ..common.publishers import synchronous_publisher
from ..common.stamps import to_time

MIN_CLOCK_WALL_PERIOD = 0.001  # s: the most /clock messages a wall second gets is 1000


class SimClock:
    """Publishes sim time every ``pub_clock_frequency`` of sim time, at most once per
    MIN_CLOCK_WALL_PERIOD of wall time (faster than real time, every 50 ms of sim time at
    50x is still fine for a rospy.Rate(10)), and the measured real-time factor."""

    def __init__(self, pub_clock_frequency: float) -> None:
        self.period_ns = int(1e9 / max(1e-3, float(pub_clock_frequency)))
        self._pub = synchronous_publisher('/clock', Clock)
        self._own_clock = self._stop_listening_to_own_clock()
        self._rtf_pub = rospy.Publisher('~real_time_factor', Float64, queue_size=1, latch=True)
        self.rtf = RealTimeFactorMeter()
        self._last_ns: int | None = None
        self._last_wall = 0.0

    def publish(self, now_ns: int) -> None:
        now = to_time(now_ns)
        self._pub.publish(Clock(now))
        if self._own_clock:
            rospy.rostime._set_rostime(now)  # this node's own sim time, without the round trip

    def after_step(self, now_ns: int) -> None:
        """Publish if due; a time that went back (reset_simulation) is always due."""
        last = self._last_ns
        if (
            last is None
            or now_ns < last
            or (
                now_ns - last >= self.period_ns
                and time.perf_counter() - self._last_wall >= MIN_CLOCK_WALL_PERIOD
            )
        ):
            self.publish(now_ns)
            self._last_ns, self._last_wall = now_ns, time.perf_counter()
            if self.rtf.update(now_ns * 1e-9):
                self._rtf_pub.publish(self.rtf.value)

    def pause(self) -> None:
        """Physics is paused: the next step publishes at once and the RTF meter restarts."""
        self.rtf.pause()
        self._last_ns = None

    @staticmethod
    def _stop_listening_to_own_clock() -> bool:
        """With use_sim_time, rospy subscribes this node to /clock: to its own messages.

        Receiving each one back costs a thread wake-up and the GIL on the physics
        thread; the world sets its own time instead. Returns True when it did.
        """
        sub = getattr(rospy.impl.simtime, '_clock_sub', None)  # only set with use_sim_time
        if sub is None:
            return False
        sub.unregister()
        rospy.impl.simtime._clock_sub = None
        return True
