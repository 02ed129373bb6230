"""The physics thread of the world node: hand-over calls, step, clock, pace."""

from __future__ import annotations

import time

import rospy

from ..sim.pacer import Pacer
from ..sim.simulation import Simulation
from .sim_clock import SimClock
from .sim_thread import SimThreadCalls


class WorldLoop:
    def __init__(
        self, sim: Simulation, calls: SimThreadCalls, clock: SimClock, paused: bool = False
    ) -> None:
        self.sim, self.calls, self.clock = sim, calls, clock
        self.paused = paused  # set only on this thread (through calls)

    def run(self, pacer: Pacer) -> None:
        """Step until ROS shuts down."""
        try:
            self._loop(pacer)
        except rospy.ROSException:
            if not rospy.core.is_shutdown_requested():
                raise  # publishing raises once shutdown has begun closing the topics

    def _loop(self, pacer: Pacer) -> None:
        sim, calls, clock = self.sim, self.calls, self.clock
        clock.publish(sim.time_ns)
        while not rospy.core.is_shutdown_requested():
            calls.run_pending()
            if self.paused:
                clock.pause()
                time.sleep(0.001)
                pacer.restart()
                continue
            sim.step()
            clock.after_step(sim.time_ns)
            pacer.wait()
