"""effort_controllers/JointPositionController: a PID from position error to effort."""
import logging
import math
import time

from .angles import shortest_angular_distance, shortest_angular_distance_with_large_limits
from .controller import Controller, ControllerError, require_param
from .hardware_interface import EFFORT_JOINT_INTERFACE
from .pid import Pid, PidConfigError

log = logging.getLogger('arm1.control')

STATE_PUBLISH_DIVIDER = 10  # state goes out every 10th update, as in ros_controllers
WARN_PERIOD = 5.0  # seconds between repeated warnings of one kind


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
        self._state_pub = None
        self.last_state = None

    def init(self, robot_hw, root_nh, controller_nh):
        ns = controller_nh.namespace
        joint_name = require_param(controller_nh.params, 'joint', ns)
        self.joint = robot_hw.get_handle(joint_name, self.interface, ns)
        self.joints = [self.joint]
        try:
            self.pid = Pid.from_params(controller_nh.params.get('pid'), ns + '/pid')
        except PidConfigError as exc:
            raise ControllerError(str(exc))
        self._state_pub = controller_nh.advertise('state', 'arm1/JointControllerState', 1)
        controller_nh.subscribe('command', 'std_msgs/Float64', self.set_command)

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
        self.command = float(position)
        return True

    def starting(self, time_ns):
        self.command = self.joint.position
        self.pid.reset()
        self._loop_count = 0
        self._started = True

    def stopping(self, time_ns):
        self._started = False

    def enforce_joint_limits(self, position):
        limits = self.joint.limits
        if self.joint.type in ('revolute', 'prismatic') and limits.has_position_limits:
            return min(max(position, limits.lower), limits.upper)
        return position

    def error(self, set_point):
        j = self.joint
        if j.type == 'revolute' and j.limits.has_position_limits:
            return shortest_angular_distance_with_large_limits(
                j.position, set_point, j.limits.lower, j.limits.upper)[0]
        if j.type == 'continuous':
            return shortest_angular_distance(j.position, set_point)
        return set_point - j.position

    def update(self, time_ns, period):
        set_point = self.enforce_joint_limits(self.command)
        error = self.error(set_point)
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
