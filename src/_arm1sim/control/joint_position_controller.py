"""effort_controllers/JointPositionController: a PID from position error to effort."""

from __future__ import annotations

import math
from typing import Sequence, cast

from .angles import shortest_angular_distance, shortest_angular_distance_with_large_limits
from .controller import Controller
from .joint_pid_controller import STATE_PUBLISH_DIVIDER, JointPidController, log


class JointPositionController(JointPidController):
    type_name = 'effort_controllers/JointPositionController'

    def __init__(self) -> None:
        super().__init__()
        self._clamp_said = False  # the first command outside the limits since start is logged
        self._lower, self._upper = -math.inf, math.inf
        self._plain_error = False

    def _check_target(self, position: float) -> None:
        if not self._lower <= position <= self._upper and not self._clamp_said:
            # Clamped in update, as ros_control does silently; said once per start so that a
            # runaway value is visible without a warning per message of a sine into the limits.
            self._clamp_said = True
            log.warning(
                '%s: command %g for joint %s is outside its limits [%.4f, %.4f]: '
                'clamped to %.4f (said once; later ones are clamped silently)',
                self.name,
                position,
                self.joint.name,
                self._lower,
                self._upper,
                min(max(position, self._lower), self._upper),
            )

    def starting(self, time_ns: int) -> None:
        super().starting(time_ns)
        self.target = self.joint.position
        self._clamp_said = False

    def _bind_joint_rules(self) -> None:
        """Decide once, not every update, how this joint's target is clamped and its error taken."""
        j, lim = self.joint, self.joint.limits
        clamped = j.type in ('revolute', 'prismatic') and lim.has_position_limits
        if clamped and lim.lower is not None and lim.upper is not None:
            self._lower, self._upper = lim.lower, lim.upper
        # For a target clamped inside limits narrower than a full turn, the angles package's
        # shortest distance within the limits is the plain difference: skip the general rule.
        self._plain_error = j.type == 'prismatic' or (
            j.type == 'revolute' and clamped and self._upper - self._lower < 2 * math.pi
        )

    def error(self, set_point: float) -> float:
        j, lim = self.joint, self.joint.limits
        if j.type == 'revolute' and lim.lower is not None and lim.upper is not None:
            return shortest_angular_distance_with_large_limits(
                j.position, set_point, lim.lower, lim.upper
            )[0]
        if j.type == 'continuous':
            return shortest_angular_distance(j.position, set_point)
        return set_point - j.position

    def update(self, time_ns: int, period_ns: int) -> None:
        self.update_group((self,), time_ns, period_ns)

    @classmethod
    def update_group(cls, controllers: Sequence[Controller], time_ns: int, period_ns: int) -> None:
        """``update`` of each, in one pass (``update`` is this pass over one): the clamp and
        the state written out inline, the PID's one call per joint, which spares the
        per-joint method calls that made up most of a step's Python time."""
        dt = period_ns * 1e-9  # the PID works in seconds, as control_toolbox's does
        for c in cast(Sequence[JointPositionController], controllers):
            if c._pending_gains is not None:
                c._apply_pending_gains()
            joint = c.joint
            # min(max(target, lower), upper), as builtins' min and max decide it
            set_point, lower, upper = c.target, c._lower, c._upper
            if lower > set_point:
                set_point = lower
            if upper < set_point:
                set_point = upper
            error = set_point - joint.position if c._plain_error else c.error(set_point)
            effort = c.pid.compute_command(error, dt)
            joint.command = effort
            count = c._loop_count
            if count % STATE_PUBLISH_DIVIDER == 0 and c._state_pub.wanted():
                c._state_pub.publish(c._state(time_ns, set_point, error, dt, effort))
            c._loop_count = count + 1
