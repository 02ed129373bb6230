"""gazebo_ros_control's DefaultRobotHWSim: joint handles bound to a simulated robot.

The actuated joints are those the URDF's transmissions name. Each is read from the
physics when the controllers update and written every physics step, as its
transmission's hardware interface says (default_robot_hw_sim.cpp's writeSim):

- EffortJointInterface: the saturated effort.
- PositionJointInterface: the command, clamped to the position limits and to a
  max_velocity step from the previous one; without pid gains the joint reaches it in one
  step as with Gazebo's SetPosition, but by moving there (physics.robot.move_positions: a
  velocity motor capped at the effort limit), so that friction carries what it holds; with
  them a PID turns the error into effort.
- VelocityJointInterface: the command, clamped to +-max_velocity; without pid gains a
  velocity motor capped at the effort limit (Gazebo's SetParam("vel")), with them a PID.

A mimic follower (URDF ``<mimic>`` or roboticsgroup's plugin) is read but never written:
physics.mimic drives it, as the plugin's SetPosition overrides any force in Gazebo.

The pid gains are ``<robotNamespace>/gazebo_ros_control/pid_gains/<joint>``: init_sim
finds them in the parameters its node handle carries (set_pid_gains takes them directly).
"""

from __future__ import annotations

import logging
import math
from typing import TYPE_CHECKING, Any, Dict, List, Mapping, Optional, Protocol, Sequence, Tuple

from ..control.angles import shortest_angular_distance, shortest_angular_distance_with_large_limits
from ..control.controller import ControllerError
from ..control.hardware_interface import (
    EFFORT_JOINT_INTERFACE,
    POSITION_JOINT_INTERFACE,
    VELOCITY_JOINT_INTERFACE,
    JointHandle,
    SaturationBounds,
    saturate_handles,
    saturation_bounds,
)
from ..control.interfaces import NodeHandle, Resources
from ..control.pid import Pid, PidConfigError
from .limit_chatter import LimitChatterWatch, chatter_message

if TYPE_CHECKING:
    from ..description.urdf_model import RobotModel

log = logging.getLogger('_arm1sim.control')

SIMULATED_INTERFACES = (EFFORT_JOINT_INTERFACE, POSITION_JOINT_INTERFACE, VELOCITY_JOINT_INTERFACE)
DEFAULT_PERIOD = 0.001  # s between writes: Gazebo's default max_step_size
# A motor force bullet can apply when the joint has no effort limit (Gazebo's DBL_MAX).
UNLIMITED_MOTOR_FORCE = 1e6


class SimulatedJoints(Protocol):
    """What the hardware needs of a simulated robot (physics.robot.Robot)."""

    def indices(self, joint_names: Sequence[str]) -> List[int]: ...

    def read(self, indices: Sequence[int]) -> Sequence[Tuple[float, float]]:
        """``(position, velocity)`` of each joint."""
        ...

    def apply_efforts(self, indices: Sequence[int], efforts: Sequence[float]) -> None: ...

    def set_velocity_motors(
        self, indices: Sequence[int], velocities: Sequence[float], max_forces: Sequence[float]
    ) -> None:
        """Velocity motors that last until changed (max force 0 switches one off)."""
        ...

    def move_positions(
        self,
        indices: Sequence[int],
        positions: Sequence[float],
        max_forces: Sequence[float],
        dt: float,
    ) -> None:
        """Reach the positions at the end of the next step, moving there (contacts see the
        motion) with at most ``max_forces``."""
        ...


class _Drive:
    """How one joint is written: its mode, limits and, for the PID modes, its PID."""

    __slots__ = (
        'handle',
        'index',
        'bounds',
        'max_acceleration',
        'has_range',
        'pid',
        'prev_cmd',
        'prev_vel',
        'wrapped',
    )

    def __init__(self, handle: JointHandle, index: int) -> None:
        self.handle, self.index = handle, index
        self.pid: Optional[Pid] = None
        self.prev_cmd = math.nan  # position saturation: the last command written
        self.prev_vel = 0.0  # velocity saturation: the last command written
        self.set_bounds(saturation_bounds(handle.limits), math.inf)

    def set_bounds(self, bounds: SaturationBounds, max_acceleration: float) -> None:
        self.bounds, self.max_acceleration = bounds, max_acceleration
        lower, upper = bounds[1], bounds[2]
        self.has_range = math.isfinite(lower) and math.isfinite(upper)
        # A revolute position error wraps only when its range spans a turn or more; within a
        # narrower range the plain difference is what the angles package gives.
        self.wrapped = self.handle.type == 'continuous' or (
            self.handle.type == 'revolute' and upper - lower >= 2 * math.pi
        )

    def position_error(self, command: float) -> float:
        h = self.handle
        if h.type == 'continuous':
            return shortest_angular_distance(h.position, command)
        if self.wrapped:
            return shortest_angular_distance_with_large_limits(
                h.position, command, self.bounds[1], self.bounds[2]
            )[0]
        return command - h.position

    def soft_velocity_bounds(self, position: float) -> Tuple[float, float]:
        """The soft limits' velocity bounds at ``position``: -k_position times the distance
        beyond each soft limit, within +-max_velocity (+-max_velocity without a range)."""
        soft, max_velocity = self.handle.limits.soft, self.bounds[3]
        assert soft is not None
        if not self.has_range:
            return -max_velocity, max_velocity
        return (
            _clamp(-soft.k_position * (position - soft.lower), -max_velocity, max_velocity),
            _clamp(-soft.k_position * (position - soft.upper), -max_velocity, max_velocity),
        )

    def soft_effort(self) -> float:
        """EffortJointSoftLimitsHandle: the effort that keeps the velocity within the soft
        velocity bounds, within +-max_effort."""
        h, soft, max_effort = self.handle, self.handle.limits.soft, self.bounds[0]
        assert soft is not None
        low, high = self.soft_velocity_bounds(h.position)
        cmd = h.command if math.isfinite(h.command) else 0.0
        return _clamp(
            cmd,
            _clamp(-soft.k_velocity * (h.velocity - low), -max_effort, max_effort),
            _clamp(-soft.k_velocity * (h.velocity - high), -max_effort, max_effort),
        )

    def saturate_position(self, dt: float) -> float:
        """joint_limits_interface's PositionJointSaturationHandle: within the range and one
        max_velocity step of the previous command (first: of the measured position)."""
        h = self.handle
        _, lower, upper, max_velocity = self.bounds
        if math.isnan(self.prev_cmd):
            self.prev_cmd = h.position
        cmd = h.command if math.isfinite(h.command) else self.prev_cmd
        if h.limits.soft is not None:
            # PositionJointSoftLimitsHandle: steps bounded by the soft velocity bounds
            low, high = self.soft_velocity_bounds(self.prev_cmd)
            low, high = self.prev_cmd + low * dt, self.prev_cmd + high * dt
        else:
            step = max_velocity * dt
            low, high = self.prev_cmd - step, self.prev_cmd + step
        cmd = _clamp(cmd, max(low, lower), min(high, upper))
        self.prev_cmd = cmd
        return cmd

    def saturate_velocity(self, dt: float) -> float:
        """VelocityJointSaturationHandle: +-max_velocity and, with an acceleration limit,
        one max_acceleration step from the previous command (first: from 0)."""
        max_velocity = self.bounds[3]
        low, high = -max_velocity, max_velocity
        if self.handle.limits.soft is not None:
            # VelocityJointSoftLimitsHandle: the soft bounds, and acceleration from the
            # measured velocity rather than the last command
            low, high = self.soft_velocity_bounds(self.handle.position)
            if self.max_acceleration < math.inf:
                step, vel = self.max_acceleration * dt, self.handle.velocity
                low, high = max(vel - step, low), min(vel + step, high)
        elif self.max_acceleration < math.inf:
            step = self.max_acceleration * dt
            low, high = max(self.prev_vel - step, low), min(self.prev_vel + step, high)
        cmd = self.handle.command if math.isfinite(self.handle.command) else 0.0
        self.prev_vel = cmd = min(max(cmd, low), high)
        return cmd


def _clamp(value: float, low: float, high: float) -> float:
    """joint_limits_interface's clamp: min(max(value, low), high)."""
    return min(max(value, low), high)


def _override_limits(
    bounds: SaturationBounds, params: Mapping[str, Any]
) -> Tuple[SaturationBounds, float]:
    """joint_limits_interface's getJointLimits from rosparam over the URDF's: each kind
    (position, velocity, acceleration, effort) changes only when its ``has_*`` is given;
    false removes it, true sets it when its values are given too."""
    max_effort, lower, upper, max_velocity = bounds
    max_acceleration = math.inf

    def given(kind: str, *keys: str) -> Optional[List[float]]:
        """None: unchanged; []: removed; else the values."""
        if 'has_' + kind not in params:
            return None
        if not params['has_' + kind]:
            return []
        if not all(k in params for k in keys):
            return None
        values = [float(params[k]) for k in keys]
        if not all(math.isfinite(v) for v in values):
            raise ValueError('%s is not finite' % ', '.join(keys))
        return values

    pos = given('position_limits', 'min_position', 'max_position')
    if pos is not None:
        lower, upper = pos if pos else (-math.inf, math.inf)
    vel = given('velocity_limits', 'max_velocity')
    if vel is not None:
        max_velocity = vel[0] if vel else math.inf
    acc = given('acceleration_limits', 'max_acceleration')
    if acc is not None:
        max_acceleration = acc[0] if acc else math.inf
    eff = given('effort_limits', 'max_effort')
    if eff is not None:
        max_effort = eff[0] if eff else math.inf
    return (max_effort, lower, upper, max_velocity), max_acceleration


class DefaultRobotHWSim:
    """A RobotHWSim (control/interfaces.py): each actuated joint offers the interface its
    transmission names."""

    def __init__(
        self,
        description: RobotModel,
        robot: SimulatedJoints,
        period: float = DEFAULT_PERIOD,
        pid_gains: Optional[Mapping[str, Any]] = None,
    ) -> None:
        """``period``: seconds between writes (the physics step); ``pid_gains``: joint ->
        gains dict, the parameters under ``gazebo_ros_control/pid_gains``."""
        self.robot = robot
        # Each joint's state starting (position, velocity): physics.robot.Robot's own tuples
        # when it offers them (no copy per read), else SimulatedJoints.read's pairs.
        self._read_states = getattr(robot, 'joint_states', robot.read)
        self.period = period
        self.handles: Dict[str, JointHandle] = {}
        for joint, interface in description.actuated_joints():
            if interface not in SIMULATED_INTERFACES:
                log.error(
                    "No matching hardware interface found for '%s' while loading interfaces "
                    "for %s; the joint is left passive (simulated: %s)",
                    interface,
                    joint.name,
                    ', '.join(SIMULATED_INTERFACES),
                )
                continue
            self.handles[joint.name] = JointHandle(joint.name, joint.type, joint.limits, interface)
        self._ordered = [self.handles[n] for n in sorted(self.handles)]
        self._indices = robot.indices([h.name for h in self._ordered])
        # A mimic follower is read like any joint but never written: the mimic drives it, and
        # an effort or set position from here would fight that (physics.mimic).
        followers = {m.follower for m in description.mimics}
        self._drives = [
            _Drive(h, i) for h, i in zip(self._ordered, self._indices) if h.name not in followers
        ]
        self.set_pid_gains(pid_gains or {})

    def set_joint_limits(self, joint_limits: Mapping[str, Any]) -> None:
        """``<robotNamespace>/joint_limits/<joint>`` parameters (has_position_limits,
        min_position, max_position, has_velocity_limits, max_velocity, has_acceleration_limits,
        max_acceleration, has_effort_limits, max_effort) over the URDF's limits, as
        gazebo_ros_control applies them. Bad values name the joint; its URDF limits stay."""
        for d in self._drives:
            bounds, max_acceleration = saturation_bounds(d.handle.limits), math.inf
            params = joint_limits.get(d.handle.name)
            if isinstance(params, dict):
                try:
                    bounds, max_acceleration = _override_limits(bounds, params)
                except (TypeError, ValueError) as exc:
                    log.error("joint_limits/%s: %s; the URDF's limits apply", d.handle.name, exc)
            d.set_bounds(bounds, max_acceleration)
        self._plan()

    def set_pid_gains(self, pid_gains: Mapping[str, Any]) -> None:
        """Position and velocity joints with gains (a dict with ``p``) get a PID to effort;
        the others are set directly. Bad gains name the joint and leave it set directly."""
        for d in self._drives:
            if d.handle.interface == EFFORT_JOINT_INTERFACE:
                continue
            d.pid = None
            gains = pid_gains.get(d.handle.name)
            if gains is not None:
                try:
                    d.pid = Pid.from_params(gains, 'gazebo_ros_control/pid_gains/' + d.handle.name)
                except PidConfigError as exc:
                    log.error(
                        "joint '%s': %s; the joint is driven without a PID", d.handle.name, exc
                    )
        self._plan()

    def _plan(self) -> None:
        """Group the joints by how they are written, so that each step makes one call per kind."""
        self._torque = [
            d
            for d in self._drives
            if d.handle.interface == EFFORT_JOINT_INTERFACE or d.pid is not None
        ]
        self._torque_indices = [d.index for d in self._torque]
        # Effort joints without soft limits (all of them, usually): saturated in one pass.
        self._plain_efforts = [
            (d.handle,) + d.bounds
            for d in self._torque
            if d.handle.interface == EFFORT_JOINT_INTERFACE and d.handle.limits.soft is None
        ]
        if len(self._plain_efforts) < len(self._torque):
            self._plain_efforts = []
        # Effort joints whose velocity limit the saturation enforces: watched for its trap.
        watched = [
            d
            for d in self._torque
            if d.handle.interface == EFFORT_JOINT_INTERFACE and math.isfinite(d.bounds[3])
        ]
        self._chatter_handles = [d.handle for d in watched]
        self._chatter = (
            LimitChatterWatch([(d.handle.name, d.bounds[3]) for d in watched]) if watched else None
        )
        self._teleported = [
            d
            for d in self._drives
            if d.pid is None and d.handle.interface == POSITION_JOINT_INTERFACE
        ]
        self._motored = [
            d
            for d in self._drives
            if d.pid is None and d.handle.interface == VELOCITY_JOINT_INTERFACE
        ]
        motor_force = {
            d.index: min(d.bounds[0], UNLIMITED_MOTOR_FORCE)
            for d in self._teleported + self._motored
        }
        self._motor_forces = [motor_force[d.index] for d in self._motored]
        self._position_forces = [motor_force[d.index] for d in self._teleported]
        # Gazebo gives a set joint's motor fmax = the effort limit (a brake between teleports);
        # joints driven by effort must have theirs off, or it would fight the effort.
        indices = [d.index for d in self._drives if d.handle.interface != EFFORT_JOINT_INTERFACE]
        if indices:
            self.robot.set_velocity_motors(
                indices, [0.0] * len(indices), [motor_force.get(i, 0.0) for i in indices]
            )

    def joint_names(self) -> List[str]:
        """Sorted, as hardware_interface's std::map gives them."""
        return [h.name for h in self._ordered]

    def get_handle(self, name: str, interface: Optional[str], controller_ns: str) -> JointHandle:
        handle = self.handles.get(name)
        if handle is None:
            raise ControllerError(
                "joint '%s' (from %s/joint) is not an actuated joint of the robot; known joints: %s"
                % (name, controller_ns, ', '.join(self.joint_names()) or 'none')
            )
        if interface is not None and interface != handle.interface:
            raise ControllerError(
                "Could not find resource '%s' in '%s' (%s): its transmission names %s"
                % (name, interface.replace('/', '::'), controller_ns, handle.interface)
            )
        return handle

    def init_sim(self, model_nh: NodeHandle, robot_namespace: str) -> None:
        """initSim's parameters: ``joint_limits`` and ``gazebo_ros_control/pid_gains`` under
        the robot namespace (either absent or not a dict: none)."""
        params = model_nh.params
        limits = params.get('joint_limits', {})
        self.set_joint_limits(limits if isinstance(limits, dict) else {})
        control = params.get('gazebo_ros_control', {})
        gains = control.get('pid_gains', {}) if isinstance(control, dict) else {}
        self.set_pid_gains(gains if isinstance(gains, dict) else {})

    def do_switch(self, start: Sequence[Resources], stop: Sequence[Resources]) -> None:
        """Each joint has one interface: a switch changes nothing here."""

    def read(self, time_ns: int = 0, period_ns: int = 0) -> None:
        for h, state in zip(self._ordered, self._read_states(self._indices)):
            h.position = state[0]
            h.velocity = state[1]

    def write(self) -> None:
        if self._plain_efforts:
            self.robot.apply_efforts(self._torque_indices, saturate_handles(self._plain_efforts))
        else:
            self._write_torques()
        if self._teleported or self._motored:
            self._write_set_joints()
        if self._chatter is not None:
            for name, limit in self._chatter.observe([h.velocity for h in self._chatter_handles]):
                log.warning(chatter_message(name, limit))

    def _write_torques(self) -> None:
        dt = self.period
        efforts = []
        for d in self._torque:
            h = d.handle
            if h.interface == EFFORT_JOINT_INTERFACE:
                if h.limits.soft is not None:
                    effort = d.soft_effort()
                else:
                    effort = saturate_handles(((h,) + d.bounds,))[0]
            else:
                assert d.pid is not None
                if h.interface == POSITION_JOINT_INTERFACE:
                    h.command = cmd = d.saturate_position(dt)
                    error = d.position_error(cmd)
                else:
                    h.command = cmd = d.saturate_velocity(dt)
                    error = cmd - h.velocity
                limit = d.bounds[0]
                effort = min(max(d.pid.compute_command(error, dt), -limit), limit)
            h.effort = effort
            efforts.append(effort)
        self.robot.apply_efforts(self._torque_indices, efforts)

    def _write_set_joints(self) -> None:
        dt = self.period
        if self._teleported:
            positions = []
            for d in self._teleported:
                d.handle.command = cmd = d.saturate_position(dt)
                positions.append(cmd)
            self.robot.move_positions(
                [d.index for d in self._teleported], positions, self._position_forces, dt
            )
        if self._motored:
            velocities = []
            for d in self._motored:
                d.handle.command = cmd = d.saturate_velocity(dt)
                velocities.append(cmd)
            self.robot.set_velocity_motors(
                [d.index for d in self._motored], velocities, self._motor_forces
            )
