"""effort_controllers/JointVelocityController: a PID from velocity error to effort.

It shares the effort JointPositionController's machinery (``joint``, gains in ``pid/``,
live gains, ``state`` every 10th update); what differs is the set point, a velocity
starting at 0, and the error, command - velocity.
"""

from __future__ import annotations

import math
import time

from .joint_position_controller import (
    STATE_PUBLISH_DIVIDER,
    WARN_PERIOD,
    JointPositionController,
    log,
)


class JointVelocityController(JointPositionController):
    type_name = 'effort_controllers/JointVelocityController'

    def set_target(self, velocity: float) -> bool:
        """The command topic's callback (ROS thread): a new velocity; non-finite ones are
        refused and the last one held. Returns whether it was taken."""
        if not self.running:
            return False  # starting() sets the command to 0 anyway
        if not math.isfinite(velocity):
            now = time.monotonic()
            if now - self._last_warn > WARN_PERIOD:
                self._last_warn = now
                log.warning(
                    '%s: ignoring non-finite command %r for joint %s; holding %.4f',
                    self.name,
                    velocity,
                    self.joint.name,
                    self.target,
                )
            return False
        self.target = float(velocity)
        return True

    def starting(self, time_ns: int) -> None:
        self.target = 0.0
        self.pid.reset()
        self._loop_count = 0

    def update(self, time_ns: int, period_ns: int) -> None:
        self._apply_pending_gains()
        error = self.target - self.joint.velocity
        dt = period_ns * 1e-9
        effort = self.pid.compute_command(error, dt)
        self.joint.command = effort
        if self._loop_count % STATE_PUBLISH_DIVIDER == 0:
            state = self._state(time_ns, self.target, error, dt, effort)
            # The process value is the velocity; upstream leaves process_value_dot unset (0).
            state.update(process_value=self.joint.velocity, process_value_dot=0.0)
            self._state_pub.publish(state)
        self._loop_count += 1
