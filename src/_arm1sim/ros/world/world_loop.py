"""The physics thread of the world node: hand-over calls, step, clock, pace."""

from __future__ import annotations

import rospy

from ...sim.pacer import Pacer, steps_per_wake
from ...sim.simulation import Simulation
from ..control.node_handle import RosNodeHandle
from .sim_clock import SimClock
from .sim_thread import SimThreadCalls

# The loop runs a /clock period's steps per wake-up (sim/pacer.py's steps_per_wake). Commands
# (node handle subscriptions) and hand-over calls wake it early, so they wait no longer than
# with one step per wake-up.
PAUSED_NAP = 0.05  # s: a paused world wakes for hand-over calls, else this seldom


class WorldLoop:
    def __init__(
        self, sim: Simulation, calls: SimThreadCalls, clock: SimClock, paused: bool = False
    ) -> None:
        self.sim, self.calls, self.clock = sim, calls, clock
        self.paused = paused  # set only on this thread (through calls)

    def pace(self, pacer: Pacer, period: float) -> None:
        """Wall seconds per step (0: flat out), batched to the clock; a new schedule from now."""
        pacer.period = period
        pacer.steps_per_wake = steps_per_wake(self.clock.period_ns, self.sim.step_ns, period)
        pacer.restart()

    def run(self, pacer: Pacer) -> None:
        """Step until ROS shuts down."""
        self.pace(pacer, pacer.period)
        self.calls.on_call = RosNodeHandle.on_message = pacer.wake
        try:
            self._loop(pacer)
        except rospy.ROSException:
            if not rospy.core.is_shutdown_requested():
                raise  # publishing raises once shutdown has begun closing the topics
        finally:
            self.calls.on_call = RosNodeHandle.on_message = None

    def _loop(self, pacer: Pacer) -> None:
        sim, calls, clock = self.sim, self.calls, self.clock
        clock.publish(sim.time_ns)
        while not rospy.core.is_shutdown_requested():
            calls.run_pending()
            if self.paused:
                clock.pause()
                pacer.nap(PAUSED_NAP)  # woken by a hand-over call (e.g. unpause)
                pacer.restart()
                continue
            sim.step()
            clock.after_step(sim.time_ns)
            due = pacer.wait(sim.steps)
            # woken in a long wait (a slow max_update_rate): serve the call, then wait on
            while not (due or self.paused or rospy.core.is_shutdown_requested()):
                calls.run_pending()
                due = pacer.resume()
