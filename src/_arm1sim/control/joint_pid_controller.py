"""What the effort JointPositionController and JointVelocityController share: one joint, a
PID from an error to its effort (control/pid.py) with gains in ``pid/`` and live gains at
``<controller>/pid``, a Float64 command whose non-finite values are refused, and
control_msgs/JointControllerState every 10th update. Each says its set point and error."""

from __future__ import annotations

import logging
import math
import threading
import time
from typing import Any, Dict, Mapping, Optional

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


class JointPidController(Controller):
    """The shared base; subclasses give ``starting`` (the first target) and ``update``."""

    interface = EFFORT_JOINT_INTERFACE

    # Set by init; a controller is only started after a successful init.
    joint: JointHandle
    pid: Pid
    _state_pub: Publisher

    def __init__(self) -> None:
        super().__init__()
        self.target = 0.0  # the set point from the command topic
        self._loop_count = 0
        self._last_warn = -math.inf
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

    def set_target(self, value: float) -> bool:
        """The command topic's callback (ROS thread): a new set point. A non-finite one is
        refused and the last one held; returns whether it was taken."""
        if not self.running:
            return False  # commands before start are dropped
        if not math.isfinite(value):
            now = time.monotonic()
            if now - self._last_warn > WARN_PERIOD:
                self._last_warn = now
                log.warning(
                    '%s: ignoring non-finite command %r for joint %s; holding %.4f',
                    self.name,
                    value,
                    self.joint.name,
                    self.target,
                )
            return False
        self._check_target(value)
        self.target = float(value)
        return True

    def _check_target(self, value: float) -> None:
        """A finite command about to be taken (ROS thread): a subclass may say something."""

    def _bind_joint_rules(self) -> None:
        """Called by init once the joint is known."""

    def starting(self, time_ns: int) -> None:
        self.pid.reset()
        self._loop_count = 0

    def stopping(self, time_ns: int) -> None:
        self.joint.command = 0.0  # an effort controller leaves no effort behind

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
