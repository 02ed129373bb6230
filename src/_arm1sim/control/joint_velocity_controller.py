"""effort_controllers/JointVelocityController: a PID from velocity error to effort.

It shares the effort JointPositionController's base (control/joint_pid_controller.py:
``joint``, gains in ``pid/``, live gains, ``state`` every 10th update); what differs is the
set point, a velocity starting at 0, and the error, command - velocity.
"""

from __future__ import annotations

from .joint_pid_controller import STATE_PUBLISH_DIVIDER, JointPidController


class JointVelocityController(JointPidController):
    type_name = 'effort_controllers/JointVelocityController'

    def starting(self, time_ns: int) -> None:
        super().starting(time_ns)
        self.target = 0.0

    def update(self, time_ns: int, period_ns: int) -> None:
        self._apply_pending_gains()
        error = self.target - self.joint.velocity
        dt = period_ns * 1e-9
        effort = self.pid.compute_command(error, dt)
        self.joint.command = effort
        if self._loop_count % STATE_PUBLISH_DIVIDER == 0 and self._state_pub.wanted():
            state = self._state(time_ns, self.target, error, dt, effort)
            # The process value is the velocity; upstream leaves process_value_dot unset (0).
            state.update(process_value=self.joint.velocity, process_value_dot=0.0)
            self._state_pub.publish(state)
        self._loop_count += 1
