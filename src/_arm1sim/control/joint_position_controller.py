"""effort_controllers/JointPositionController: a PID from position error to effort."""

from __future__ import annotations

import logging
import math
import threading
import time
from typing import Any, Dict, Mapping, Optional, Sequence, cast

from .angles import shortest_angular_distance, shortest_angular_distance_with_large_limits
from .controller import Controller, ControllerError, require_param
from .hardware_interface import EFFORT_JOINT_INTERFACE, JointHandle
from .interfaces import ConfigServer, NodeHandle, Publisher, RobotHW
from .message_types import DATA, STAMPED, register_message
from .pid import Pid, PidConfigError

log = logging.getLogger('_arm1sim.control')

register_message('control_msgs/JointControllerState', STAMPED)
register_message('std_msgs/Float64', DATA)  # the command

STATE_PUBLISH_DIVIDER = 10  # state goes out every 10th update, as in ros_controllers
WARN_PERIOD = 5.0  # seconds between repeated warnings of one kind
GAIN_KEYS = ('p', 'i', 'd', 'i_clamp_max', 'i_clamp_min', 'antiwindup')  # as Pid.gains()
Gains = Dict[str, Any]  # GAIN_KEYS -> float (bool for antiwindup)


class JointPositionController(Controller):
    type_name = 'effort_controllers/JointPositionController'
    interface = EFFORT_JOINT_INTERFACE

    # Set by init; a controller is only started after a successful init.
    joint: JointHandle
    pid: Pid
    _state_pub: Publisher

    def __init__(self) -> None:
        super().__init__()
        self.target = 0.0  # target position: from the command topic, clamped in update
        self._loop_count = 0
        self._last_warn = -math.inf
        self._clamp_said = False  # the first command outside the limits since start is logged
        self._lower, self._upper = -math.inf, math.inf
        self._plain_error = False
        self._gains_lock = threading.Lock()
        # Set by set_gains (any thread), applied by update.
        self._pending_gains: Optional[Gains] = None

    def init(self, robot_hw: RobotHW, root_nh: NodeHandle, controller_nh: NodeHandle) -> None:
        ns = controller_nh.namespace
        joint_name = require_param(controller_nh.params, 'joint', ns)
        self.joint = robot_hw.get_handle(joint_name, self.interface, ns)
        self.joints = [self.joint]
        self._bind_joint_rules()
        try:
            self.pid = Pid.from_params(controller_nh.params.get('pid'), ns + '/pid')
        except PidConfigError as exc:
            raise ControllerError(str(exc))
        self._state_pub = controller_nh.advertise('state', 'control_msgs/JointControllerState', 1)
        controller_nh.subscribe('command', 'std_msgs/Float64', self.set_target)
        # Live gains at <controller>/pid, as control_toolbox's Pid serves them with
        # dynamic_reconfigure; a node handle that is no ConfigServer offers none.
        if isinstance(controller_nh, ConfigServer):
            controller_nh.serve_config(
                'pid', 'control_toolbox/Parameters', self.pid.gains(), self.set_gains
            )

    def set_gains(self, gains: Mapping[str, Any]) -> Gains:
        """New PID gains (keys of Pid.gains(); missing ones keep their value). Thread-safe:
        they take effect at the next update. Returns the gains that will apply; invalid ones
        (non-finite, i_clamp_min > i_clamp_max) are refused and the gains in force returned."""
        with self._gains_lock:
            current = dict(self._pending_gains or self.pid.gains())
            new = dict(current)
            for key in GAIN_KEYS:
                if key in gains:
                    new[key] = bool(gains[key]) if key == 'antiwindup' else float(gains[key])
            bad = [k for k in GAIN_KEYS if not math.isfinite(new[k])]
            if bad or new['i_clamp_min'] > new['i_clamp_max']:
                log.error(
                    '%s: refusing pid gains %s (%s); keeping %s',
                    self.name,
                    new,
                    'non-finite ' + ', '.join(bad) if bad else 'i_clamp_min > i_clamp_max',
                    current,
                )
                return current
            negative = ['%s=%g' % (k, new[k]) for k in ('p', 'i', 'd') if new[k] < 0]
            if negative:
                # Allowed (control_toolbox's ranges are symmetric), but a negative gain drives
                # the joint away from its target: say so.
                log.warning(
                    '%s: negative pid gain(s) %s for joint %s push it away from its target',
                    self.name,
                    ', '.join(negative),
                    self.joint.name,
                )
            self._pending_gains = new
            return dict(new)

    def set_target(self, position: float) -> bool:
        """The command topic's callback (ROS thread): a new target position. A non-finite one
        is refused and the last one held; returns whether it was taken."""
        if not self.running:
            return False  # commands before start are dropped
        if not math.isfinite(position):
            now = time.monotonic()
            if now - self._last_warn > WARN_PERIOD:
                self._last_warn = now
                log.warning(
                    '%s: ignoring non-finite command %r for joint %s; holding %.4f',
                    self.name,
                    position,
                    self.joint.name,
                    self.target,
                )
            return False
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
        self.target = float(position)
        return True

    def starting(self, time_ns: int) -> None:
        self.target = self.joint.position
        self.pid.reset()
        self._loop_count = 0
        self._clamp_said = False

    def stopping(self, time_ns: int) -> None:
        self.joint.command = 0.0  # an effort controller leaves no effort behind

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

    def _apply_pending_gains(self) -> None:
        if self._pending_gains is not None:
            with self._gains_lock:
                gains, self._pending_gains = self._pending_gains, None
            self.pid.set_gains(
                gains['p'],
                gains['i'],
                gains['d'],
                gains['i_clamp_max'],
                gains['i_clamp_min'],
                gains['antiwindup'],
            )

    def update(self, time_ns: int, period_ns: int) -> None:
        self._apply_pending_gains()
        set_point = min(max(self.target, self._lower), self._upper)
        error = set_point - self.joint.position if self._plain_error else self.error(set_point)
        dt = period_ns * 1e-9  # the PID works in seconds, as control_toolbox's does
        effort = self.pid.compute_command(error, dt)
        self.joint.command = effort
        if self._loop_count % STATE_PUBLISH_DIVIDER == 0:
            self._state_pub.publish(self._state(time_ns, set_point, error, dt, effort))
        self._loop_count += 1

    @classmethod
    def update_group(cls, controllers: Sequence[Controller], time_ns: int, period_ns: int) -> None:
        """``update`` of each, in one pass: Pid.compute_command written out inline (same
        arithmetic in the same order, so the same efforts to the bit; test_pid checks), which
        spares the per-joint method calls that made up most of a step's Python time."""
        if cls.update is not JointPositionController.update:
            # A subclass with an update of its own (JointVelocityController) goes one by one.
            super().update_group(controllers, time_ns, period_ns)
            return
        dt = period_ns * 1e-9  # the PID works in seconds, as control_toolbox's does
        isfinite = math.isfinite
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
            pid = c.pid
            if dt == 0.0 or not isfinite(error):
                effort = 0.0
            else:
                error_dot = (error - pid.p_error_last) / dt
                pid.p_error_last = pid.p_error = error
                pid.d_error = error_dot
                if not isfinite(error_dot):
                    effort = 0.0
                else:
                    i_error = pid.i_error + dt * error
                    i = pid.i
                    if pid.antiwindup:
                        if i != 0.0:
                            lo, hi = sorted((pid.i_min / i, pid.i_max / i))
                            i_error = min(max(i_error, lo), hi)
                        i_term = i * i_error
                    else:
                        i_term = i * i_error
                        if pid.i_min > i_term:
                            i_term = pid.i_min
                        if pid.i_max < i_term:
                            i_term = pid.i_max
                    pid.i_error = i_error
                    pid.cmd = effort = pid.p * error + i_term + pid.d * error_dot
            joint.command = effort
            count = c._loop_count
            if count % STATE_PUBLISH_DIVIDER == 0:
                c._state_pub.publish(c._state(time_ns, set_point, error, dt, effort))
            c._loop_count = count + 1

    def _state(
        self, time_ns: int, set_point: float, error: float, dt: float, effort: float
    ) -> Dict[str, Any]:
        pid = self.pid
        return dict(
            stamp=time_ns,
            set_point=set_point,
            process_value=self.joint.position,
            process_value_dot=self.joint.velocity,
            error=error,
            time_step=dt,
            command=effort,
            p=pid.p,
            i=pid.i,
            d=pid.d,
            i_clamp=pid.i_max,
            antiwindup=pid.antiwindup,
        )
