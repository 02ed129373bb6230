"""effort_controllers/JointPositionController: a PID from position error to effort."""
import logging
import math
import threading
import time

from .angles import shortest_angular_distance, shortest_angular_distance_with_large_limits
from .controller import Controller, ControllerError, require_param
from .hardware_interface import EFFORT_JOINT_INTERFACE
from .pid import Pid, PidConfigError

log = logging.getLogger('arm1.control')

STATE_PUBLISH_DIVIDER = 10  # state goes out every 10th update, as in ros_controllers
WARN_PERIOD = 5.0  # seconds between repeated warnings of one kind
GAIN_KEYS = ('p', 'i', 'd', 'i_clamp_max', 'i_clamp_min', 'antiwindup')  # as Pid.gains()


class JointPositionController(Controller):
    type_name = 'effort_controllers/JointPositionController'
    interface = EFFORT_JOINT_INTERFACE

    def __init__(self):
        super().__init__()
        self.joint = None
        self.pid = None
        self.command = 0.0  # target position; written by the command subscriber
        self._started = False
        self._loop_count = 0
        self._last_warn = -math.inf
        self._clamp_said = False  # the first command outside the limits since start is logged
        self._state_pub = None
        self.last_state = None
        self._gains_lock = threading.Lock()
        self._pending_gains = None  # set by set_gains (any thread), applied by update

    def init(self, robot_hw, root_nh, controller_nh):
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
        controller_nh.subscribe('command', 'std_msgs/Float64', self.set_command)
        # Live gains at <controller>/pid, as control_toolbox's Pid serves them with
        # dynamic_reconfigure; a node handle without ``serve_config`` offers none.
        serve_config = getattr(controller_nh, 'serve_config', None)
        if serve_config is not None:
            serve_config('pid', 'arm1/Pid', self.pid.gains(), self.set_gains)

    def set_gains(self, gains):
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
                log.error('%s: refusing pid gains %s (%s); keeping %s', self.name, new,
                          'non-finite ' + ', '.join(bad) if bad else 'i_clamp_min > i_clamp_max',
                          current)
                return current
            negative = ['%s=%g' % (k, new[k]) for k in ('p', 'i', 'd') if new[k] < 0]
            if negative:
                # Allowed (control_toolbox's ranges are symmetric), but a negative gain drives
                # the joint away from its target: say so.
                log.warning('%s: negative pid gain(s) %s for joint %s push it away from its '
                            'target', self.name, ', '.join(negative), self.joint.name)
            self._pending_gains = new
            return dict(new)

    def set_command(self, position):
        """Called from the ROS thread; a non-finite target is refused and the last one held."""
        if not self._started:
            return False  # commands before start are dropped
        if not math.isfinite(position):
            now = time.monotonic()
            if now - self._last_warn > WARN_PERIOD:
                self._last_warn = now
                log.warning('%s: ignoring non-finite command %r for joint %s; holding %.4f',
                            self.name, position, self.joint.name, self.command)
            return False
        if not self._lower <= position <= self._upper and not self._clamp_said:
            # Clamped in update, as ros_control does silently; said once per start so that a
            # runaway value is visible without a warning per message of a sine into the limits.
            self._clamp_said = True
            log.warning('%s: command %g for joint %s is outside its limits [%.4f, %.4f]: '
                        'clamped to %.4f (said once; later ones are clamped silently)',
                        self.name, position, self.joint.name, self._lower, self._upper,
                        min(max(position, self._lower), self._upper))
        self.command = float(position)
        return True

    def starting(self, time_ns):
        self.command = self.joint.position
        self.pid.reset()
        self._loop_count = 0
        self._clamp_said = False
        self._started = True

    def stopping(self, time_ns):
        self._started = False

    def _bind_joint_rules(self):
        """Decide once, not every update, how this joint's target is clamped and its error taken."""
        j, lim = self.joint, self.joint.limits
        clamped = j.type in ('revolute', 'prismatic') and lim.has_position_limits
        self._lower, self._upper = (lim.lower, lim.upper) if clamped else (-math.inf, math.inf)
        # For a target clamped inside limits narrower than a full turn, the angles package's
        # shortest distance within the limits is the plain difference: skip the general rule.
        self._plain_error = j.type == 'prismatic' or (
            j.type == 'revolute' and clamped and lim.upper - lim.lower < 2 * math.pi)

    def error(self, set_point):
        j = self.joint
        if j.type == 'revolute' and j.limits.has_position_limits:
            return shortest_angular_distance_with_large_limits(
                j.position, set_point, j.limits.lower, j.limits.upper)[0]
        if j.type == 'continuous':
            return shortest_angular_distance(j.position, set_point)
        return set_point - j.position

    def update(self, time_ns, period):
        if self._pending_gains is not None:
            with self._gains_lock:
                gains, self._pending_gains = self._pending_gains, None
            self.pid.set_gains(gains['p'], gains['i'], gains['d'], gains['i_clamp_max'],
                               gains['i_clamp_min'], gains['antiwindup'])
        set_point = min(max(self.command, self._lower), self._upper)
        error = set_point - self.joint.position if self._plain_error else self.error(set_point)
        effort = self.pid.compute_command(error, period)
        self.joint.command = effort
        if self._loop_count % STATE_PUBLISH_DIVIDER == 0:
            self.last_state = self._state(time_ns, set_point, error, period, effort)
            self._state_pub.publish(self.last_state)
        self._loop_count += 1

    def _state(self, time_ns, set_point, error, period, effort):
        pid = self.pid
        return dict(stamp=time_ns, set_point=set_point, process_value=self.joint.position,
                    process_value_dot=self.joint.velocity, error=error, time_step=period,
                    command=effort, p=pid.p, i=pid.i, d=pid.d, i_clamp=pid.i_max,
                    antiwindup=pid.antiwindup)
