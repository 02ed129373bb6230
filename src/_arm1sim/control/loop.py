"""When controllers update: gazebo_ros_control's Update(), once per physics step.

The controllers update when at least one control period of sim time (the plugin's
``<controlPeriod>``, by default the physics step) has passed since they last did, and
get that elapsed time as their period; the efforts they left are written every step.
"""

from __future__ import annotations

import logging
import math
from typing import Optional

from .controller_manager import ControllerManager
from .interfaces import RobotHWSim

log = logging.getLogger('_arm1sim.control')


def control_period_ns(control_period: Optional[float], step_ns: int, who: str = '') -> int:
    """``<controlPeriod>`` (seconds, None when absent) in ns; the physics step when absent,
    and, said once, when it is not a finite positive number."""
    if control_period is None:
        return step_ns
    if not (math.isfinite(control_period) and control_period > 0):
        log.error(
            '%scontrolPeriod %r is not a positive number of seconds: controllers '
            'update every physics step (%g s)',
            who and who + ': ',
            control_period,
            step_ns * 1e-9,
        )
        return step_ns
    period_ns = int(round(control_period * 1e9))
    if period_ns < step_ns:
        log.error(
            '%scontrolPeriod %g s is shorter than the physics step (%g s): controllers '
            'update every step',
            who and who + ': ',
            control_period,
            step_ns * 1e-9,
        )
    return period_ns


class ControlLoop:
    """One model's hardware and controller manager, updated at its control period."""

    def __init__(self, hw: RobotHWSim, manager: ControllerManager, period_ns: int) -> None:
        self.hw, self.manager, self.period_ns = hw, manager, period_ns
        self.last_update_ns: Optional[int] = None

    def update(self, now_ns: int) -> bool:
        """Called every physics step, before it; True when the controllers updated."""
        last = self.last_update_ns
        if last is None or now_ns < last:
            # First step, or time went back (reset_simulation): update now, a period's worth.
            elapsed = self.period_ns
        else:
            elapsed = now_ns - last
        due = elapsed >= self.period_ns
        if due:
            self.last_update_ns = now_ns
            self.hw.read(now_ns, elapsed)
            self.manager.update(now_ns, elapsed)
        self.hw.write()
        return due
