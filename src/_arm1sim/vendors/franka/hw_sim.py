"""franka_gazebo's FrankaHWSim: the Panda's simulated hardware, as a RobotHWSim.

What franka_hw_sim.cpp does, over pybullet instead of Gazebo:

- Each joint of a SimpleTransmission offers every interface its transmissions list
  (franka_description gives each arm joint three: effort, position, velocity). The
  interface a joint is driven by is that of the controller claiming it, set when a switch
  starts or stops one (``do_switch``); finger joints are always effort-driven.
- Every joint is torque-driven. Position and velocity commands go through the hardware's
  own PIDs (``motion_generators/{position,velocity}/gains/<joint>``), clamped to the effort
  limit; an effort command is feed-forward. Every arm joint gets its gravity torque added
  (the real robot compensates gravity itself), from the simulated body's dynamics.
- While no controller drives the arm (robot_mode IDLE), the arm holds the position where
  it was stopped with the position PIDs.
- franka_hw's FrankaStateInterface (``<arm_id>_robot``) and FrankaModelInterface
  (``<arm_id>_model``) come from the simulated body: q, dq, the applied torques, external
  torques (what the dynamics need beyond the applied torques), mass matrix, Coriolis,
  gravity, the end effector's pose and Jacobian (physics/body_dynamics.py).
- ``initialized`` (std_msgs/Bool) in the robot namespace says True once the state has been
  read, which the Panda's controller spawner waits for (``--wait-for initialized``).

Not simulated: franka_control's services (set_EE_frame, set_load, set_user_stop, ...),
error recovery, reflexes and errors (none ever occur), flexible joints (theta = q).
"""

from __future__ import annotations

import logging
import math
from typing import Any, Dict, List, Mapping, Optional, Sequence

import numpy as np

from ...control.controller import ControllerError
from ...control.hardware_interface import (
    EFFORT_JOINT_INTERFACE,
    POSITION_JOINT_INTERFACE,
    VELOCITY_JOINT_INTERFACE,
    JointHandle,
)
from ...control.interfaces import NodeHandle, Publisher, Resources, RobotHWSimError
from ...control.message_types import FIELDS, register_message
from ...control.pid import Pid, PidConfigError
from ...description.urdf_model import RobotModel
from ...physics.body_dynamics import BodyDynamics, Pose, homogeneous, pose_of
from ...physics.robot import Robot
from ...sim.simulation import mimic_links
from .interfaces import (
    FRANKA_MODEL_INTERFACE,
    FRANKA_STATE_INTERFACE,
    ROBOT_MODE_IDLE,
    ROBOT_MODE_MOVE,
    FrankaRobotState,
)

log = logging.getLogger('_arm1sim.control')

register_message('std_msgs/Bool', FIELDS)  # initialized

ROBOT_SIM_TYPE = 'franka_gazebo/FrankaHWSim'
SIMPLE_TRANSMISSION = 'transmission_interface/SimpleTransmission'
COMMAND_INTERFACES = (EFFORT_JOINT_INTERFACE, POSITION_JOINT_INTERFACE, VELOCITY_JOINT_INTERFACE)
INITIALIZED_PERIOD_NS = 100_000_000  # 'initialized' at 10 Hz of sim time (upstream: every read)
# franka_hw_sim's defaults: the hand's flange-to-NE transform when the URDF has a hand
HAND_F_T_NE = [0.7071, -0.7071, 0, 0, 0.7071, 0.7071, 0, 0, 0, 0, 1, 0, 0, 0, 0.1034, 1]


class FrankaHWSimError(RobotHWSimError):
    """The description cannot be simulated as a Franka robot; the message says why."""


class _Joint:
    """One joint: its handles (one per interface), how it is driven, its PIDs and state."""

    def __init__(self, name: str, handles: Dict[str, JointHandle], index: int) -> None:
        self.name, self.handles, self.index = name, handles, index
        first = next(iter(handles.values()))
        self.type, self.limits = first.type, first.limits
        self.method: Optional[str] = None  # the interface of the controller driving it
        self.position = self.velocity = self.effort = 0.0
        self.acceleration = self.jerk = 0.0
        self.stop_position = 0.0  # held while no controller drives the arm
        self.gravity = 0.0
        self.position_pid = Pid()
        self.velocity_pid = Pid()

    @property
    def max_effort(self) -> float:
        e = self.limits.effort
        return e if e is not None and e > 0 else math.inf

    def command(self, interface: str) -> float:
        h = self.handles.get(interface)
        return h.command if h is not None else 0.0

    def set_command(self, interface: str, value: float) -> None:
        h = self.handles.get(interface)
        if h is not None:
            h.command = value


class _Model:
    """franka_hw's FrankaModelHandle over the simulated body (interfaces.py)."""

    def __init__(self, hw: FrankaHWSim) -> None:
        self.hw = hw

    def mass(self) -> List[List[float]]:
        return self.hw.dynamics.mass_matrix(self.hw.q_all)

    def coriolis(self) -> List[float]:
        return self.hw.dynamics.coriolis(self.hw.q_all, self.hw.dq_all)

    def gravity(self) -> List[float]:
        return self.hw.dynamics.gravity(self.hw.q_all)

    def zero_jacobian(self) -> List[List[float]]:
        return self.hw.dynamics.jacobian(self.hw.tip_link, self.hw.ee_offset(), self.hw.q_all)

    def pose(self) -> List[float]:
        return homogeneous(self.hw.dynamics.pose(self.hw.tip_link, self.hw.ee_offset()))


def _vector(params: Mapping[str, Any], key: str, default: Sequence[float], n: int) -> List[float]:
    """A parameter given as franka_hw_sim reads them: a string of n numbers (or a list)."""
    value = params.get(key)
    if value is None:
        return list(default)
    items = value.split() if isinstance(value, str) else value
    try:
        numbers = [float(v) for v in items]
    except (TypeError, ValueError):
        raise FrankaHWSimError('parameter %s: %r is not %d numbers' % (key, value, n))
    if len(numbers) != n or not all(math.isfinite(v) for v in numbers):
        raise FrankaHWSimError('parameter %s: %r is not %d finite numbers' % (key, value, n))
    return numbers


class FrankaHWSim:
    """A RobotHWSim (control/interfaces.py) and FrankaHW (interfaces.py)."""

    def __init__(self, description: RobotModel, robot: Robot, period: float) -> None:
        self.robot, self.period = robot, period
        self.arm_id = ''
        self.state = FrankaRobotState()
        self.tau_ext_lowpass_filter = 1.0
        self._initialized = False
        self._initialized_pub: Optional[Publisher] = None
        self._last_initialized_ns: Optional[int] = None
        self._time_ns = 0
        self._period_ns = int(round(period * 1e9))

        joints: Dict[str, Dict[str, JointHandle]] = {}
        state_joints: List[str] = []
        model_ends: Dict[str, str] = {}
        for t in description.transmissions:
            if t.type == FRANKA_STATE_INTERFACE:
                state_joints = [name for name, _ in t.joints]
                continue
            if t.type == FRANKA_MODEL_INTERFACE:
                model_ends = {role: name for name, role in t.joints}
                continue
            if t.type != SIMPLE_TRANSMISSION:
                continue
            joint = description.joints.get(t.joint)
            if joint is None:
                raise FrankaHWSimError(
                    "transmission '%s' names joint '%s', which is not in the URDF"
                    % (t.name, t.joint)
                )
            for interface in t.interfaces:
                if interface not in COMMAND_INTERFACES:
                    log.warning(
                        "Unsupported transmission interface of joint '%s': %s", t.joint, interface
                    )
                    continue
                handles = joints.setdefault(t.joint, {})
                handles[interface] = JointHandle(joint.name, joint.type, joint.limits, interface)
        if len(state_joints) != 7:
            raise FrankaHWSimError(
                'Cannot create franka_hw/FrankaStateInterface: %d joints were found beneath its '
                '<transmission> tag, but 7 are required' % len(state_joints)
            )
        missing = [j for j in state_joints if j not in joints]
        if missing:
            raise FrankaHWSimError(
                'joint(s) %s of the FrankaStateInterface have no SimpleTransmission'
                % ', '.join(missing)
            )
        if 'root' not in model_ends or 'tip' not in model_ends:
            raise FrankaHWSimError(
                'Cannot create franka_hw/FrankaModelInterface: its <transmission> needs a '
                '<joint> with <role>root</role> and one with <role>tip</role>'
            )
        for end in model_ends.values():
            if end not in description.joints:
                raise FrankaHWSimError(
                    "the FrankaModelInterface's joint '%s' is not in the URDF" % end
                )
        self.arm_joint_names = state_joints
        self.root_link = description.joints[model_ends['root']].parent
        self.tip_link = description.joints[model_ends['tip']].child
        names = sorted(joints)
        self._joints = [_Joint(n, joints[n], i) for n, i in zip(names, robot.indices(names))]
        self._by_name = {j.name: j for j in self._joints}
        self.arm = [self._by_name[n] for n in state_joints]
        self._indices = [j.index for j in self._joints]
        # franka_description's finger_joint2 has a URDF <mimic> of finger_joint1. Gazebo 11
        # reads none (sdformat 9's URDF parser has no such element), so there both fingers
        # are FrankaGripperSim's; the stand-in simulates a URDF <mimic> for other robots, and
        # drops those on this hardware's joints, as Gazebo does. A mimic plugin's follower
        # stays a mimic (the plugin acts in Gazebo too) and is read but never written.
        dropped = {m.follower for m in description.mimics if not m.plugin and m.follower in joints}
        if dropped:
            robot.set_mimics([link for link in mimic_links(description) if link[0] not in dropped])
        followers = {m.follower for m in description.mimics} - dropped
        self._written = [j for j in self._joints if j.name not in followers]
        self._written_indices = [j.index for j in self._written]
        try:
            self.dynamics = BodyDynamics(robot, state_joints, self.root_link)
        except (KeyError, ValueError) as exc:
            raise FrankaHWSimError('the FrankaStateInterface joints: %s' % exc)
        fixed = [j.name for j in self._joints if j.index not in self.dynamics.dofs]
        if fixed:
            raise FrankaHWSimError('transmissions name fixed joint(s) %s' % ', '.join(fixed))
        self._dofs = [self.dynamics.dofs.index(i) for i in self._indices]  # in q_all
        self.q_all, self.dq_all = self.dynamics.state()
        self._model = _Model(self)
        self._links = set(description.links)
        # Every joint torque-driven: no velocity motor may hold it (the loader left friction).
        robot.set_velocity_motors(
            self._indices, [0.0] * len(self._indices), [0.0] * len(self._indices)
        )

    # -- configuration from the parameter server (franka_hw_sim's initSim) ------------------
    def init_sim(self, model_nh: NodeHandle, robot_namespace: str) -> None:
        """The parameters under the robot namespace, and the ``initialized`` topic."""
        params = model_nh.params
        default_id = robot_namespace.strip('/')
        self.arm_id = str(
            params.get('arm_id') or default_id or self.arm_joint_names[0].rsplit('_joint', 1)[0]
        )
        if default_id and self.arm_id != default_id:
            log.warning(
                "Caution: Robot names differ! Read 'arm_id: %s' from parameter server but URDF "
                "defines '<robotNamespace>%s</robotNamespace>'. Will use '%s'!",
                self.arm_id,
                robot_namespace,
                self.arm_id,
            )
        finger = self.arm_id + '_finger_joint'
        for j in self._joints:
            if j.name.startswith(finger):
                j.method = EFFORT_JOINT_INTERFACE
        self.tau_ext_lowpass_filter = float(params.get('tau_ext_lowpass_filter', 1.0))
        gains = params.get('motion_generators', {})
        for kind in ('position', 'velocity'):
            table = gains.get(kind, {}).get('gains', {}) if isinstance(gains, dict) else {}
            for j in self.arm:
                g = table.get(j.name) if isinstance(table, dict) else None
                if g is None:
                    continue
                try:
                    pid = Pid.from_params(g, 'motion_generators/%s/gains/%s' % (kind, j.name))
                except PidConfigError as exc:
                    log.error('%s; joint %s has no %s PID', exc, j.name, kind)
                    continue
                setattr(j, kind + '_pid', pid)
        s = self.state
        hand = self.arm_id + '_hand' in self._links  # franka_hw_sim's guessEndEffector
        s.F_T_NE = _vector(params, 'F_T_NE', HAND_F_T_NE if hand else s.F_T_NE, 16)
        s.NE_T_EE = _vector(params, 'NE_T_EE', s.NE_T_EE, 16)
        s.EE_T_K = _vector(params, 'EE_T_K', s.EE_T_K, 16)
        s.m_ee = float(params.get('m_ee', 0.0))
        s.I_ee = _vector(params, 'I_ee', s.I_ee, 9)
        s.F_x_Cee = _vector(params, 'F_x_Cee', s.F_x_Cee, 3)
        s.m_load = float(params.get('m_load', 0.0))
        s.I_load = _vector(params, 'I_load', s.I_load, 9)
        s.F_x_Cload = _vector(params, 'F_x_Cload', s.F_x_Cload, 3)
        s.m_total = s.m_ee + s.m_load
        f_t_ee = np.array(s.F_T_NE).reshape(4, 4).T @ np.array(s.NE_T_EE).reshape(4, 4).T
        s.F_T_EE = [float(v) for v in f_t_ee.T.reshape(16)]
        log.info(
            "FrankaHWSim: arm_id '%s', end effector %g kg, load %g kg%s",
            self.arm_id,
            s.m_ee,
            s.m_load,
            ' (a Franka Hand found)' if hand else '',
        )
        self._initialized_pub = model_nh.advertise('initialized', 'std_msgs/Bool', 1)
        self._initialized_pub.publish({'data': False})

    def ee_offset(self) -> Pose:
        """The end effector (F_T_EE) on the flange link."""
        return pose_of(self.state.F_T_EE)

    # -- RobotHW ------------------------------------------------------------------------------
    def joint_names(self) -> List[str]:
        return [j.name for j in self._joints]

    def get_handle(self, name: str, interface: Optional[str], controller_ns: str) -> JointHandle:
        joint = self._by_name.get(name)
        if joint is None:
            raise ControllerError(
                "joint '%s' (from %s) is not an actuated joint of the robot; known joints: %s"
                % (name, controller_ns, ', '.join(self.joint_names()))
            )
        if interface is None:
            return next(iter(joint.handles.values()))
        handle = joint.handles.get(interface)
        if handle is None:
            raise ControllerError(
                "Could not find resource '%s' in '%s' (%s): its transmissions name %s"
                % (name, interface.replace('/', '::'), controller_ns, ', '.join(joint.handles))
            )
        return handle

    def franka_state(self, name: str, controller_ns: str) -> FrankaRobotState:
        if name != self.arm_id + '_robot':
            raise ControllerError(
                "%s: no FrankaStateHandle '%s' (this hardware has '%s_robot')"
                % (controller_ns, name, self.arm_id)
            )
        self._update_cartesian()
        return self.state

    def franka_model(self, name: str, controller_ns: str) -> _Model:
        if name != self.arm_id + '_model':
            raise ControllerError(
                "%s: no FrankaModelHandle '%s' (this hardware has '%s_model')"
                % (controller_ns, name, self.arm_id)
            )
        return self._model

    def do_switch(self, start: Sequence[Resources], stop: Sequence[Resources]) -> None:
        """franka_hw_sim's doSwitch: joints of stopped controllers hold where they are; those
        of started ones are driven by the started controller's interface."""
        arm = {j.name for j in self.arm}
        for resources in stop:
            for interface, names in resources:
                for n in names:
                    j = self._by_name.get(n)
                    if j is not None and n in arm and interface in COMMAND_INTERFACES:
                        j.method = None
                        j.stop_position = j.position
                        j.set_command(POSITION_JOINT_INTERFACE, j.position)
                        j.set_command(VELOCITY_JOINT_INTERFACE, 0.0)
        for resources in start:
            for interface, names in resources:
                for n in names:
                    j = self._by_name.get(n)
                    if j is not None and n in arm and interface in COMMAND_INTERFACES:
                        j.method = interface
                        j.set_command(POSITION_JOINT_INTERFACE, j.position)
                        j.set_command(VELOCITY_JOINT_INTERFACE, 0.0)
                        j.position_pid.reset()
                        j.velocity_pid.reset()
        moving = any(j.method is not None for j in self.arm)
        self.state.robot_mode = ROBOT_MODE_MOVE if moving else ROBOT_MODE_IDLE

    # -- RobotHWSim -----------------------------------------------------------------------
    def read(self, time_ns: Optional[int] = None, period_ns: Optional[int] = None) -> None:
        """readSim: joint states, then the robot state (updateRobotState); without a time,
        one physics step after the last read."""
        if period_ns is None:
            period_ns = self._period_ns
        if time_ns is None:
            time_ns = self._time_ns + period_ns
        dt = max(period_ns, 1) * 1e-9
        self._time_ns = time_ns
        # One read of every degree of freedom serves the handles and the dynamics.
        self.q_all, self.dq_all = self.dynamics.state()
        q, dq = self.q_all, self.dq_all
        for j, k in zip(self._joints, self._dofs):
            pos, vel = q[k], dq[k]
            acceleration = (vel - j.velocity) / dt if self._initialized else 0.0
            j.jerk = (acceleration - j.acceleration) / dt if self._initialized else 0.0
            j.position, j.velocity, j.acceleration = pos, vel, acceleration
            for h in j.handles.values():
                h.position, h.velocity, h.effort = pos, vel, j.effort
        self._update_joint_state(time_ns)
        if self._initialized_pub is not None and (
            self._last_initialized_ns is None
            or time_ns < self._last_initialized_ns
            or time_ns - self._last_initialized_ns >= INITIALIZED_PERIOD_NS
        ):
            self._last_initialized_ns = time_ns
            self._initialized_pub.publish({'data': True})

    def _update_joint_state(self, time_ns: int) -> None:
        s = self.state
        moving = s.robot_mode == ROBOT_MODE_MOVE
        if self._initialized:
            # What the body needs beyond the torques applied: the world's push (external torque)
            ddq = [0.0] * len(self.q_all)
            for j, k in zip(self.arm, self.dynamics.columns):
                ddq[k] = j.acceleration
            needed = self.dynamics.inverse_dynamics(self.q_all, self.dq_all, ddq)
            a = self.tau_ext_lowpass_filter
            s.tau_ext_hat_filtered = [
                a * (tau - j.effort) + (1 - a) * old
                for tau, j, old in zip(needed, self.arm, s.tau_ext_hat_filtered)
            ]
        for i, j in enumerate(self.arm):
            if not self._initialized:
                j.stop_position = j.position
                j.set_command(POSITION_JOINT_INTERFACE, j.position)
            s.q[i] = s.theta[i] = j.position
            s.dq[i] = s.dtheta[i] = j.velocity
            s.tau_J[i] = j.effort
            s.dtau_J[i] = j.jerk
            driven_by = j.method if moving else None
            s.q_d[i] = (
                j.command(POSITION_JOINT_INTERFACE)
                if driven_by == POSITION_JOINT_INTERFACE
                else j.position
            )
            s.dq_d[i] = (
                j.command(VELOCITY_JOINT_INTERFACE)
                if driven_by == VELOCITY_JOINT_INTERFACE
                else j.velocity
            )
            s.ddq_d[i] = j.acceleration
            s.tau_J_d[i] = (
                j.command(EFFORT_JOINT_INTERFACE) if driven_by == EFFORT_JOINT_INTERFACE else 0.0
            )
        s.time = time_ns * 1e-9
        s.control_command_success_rate = 1.0
        self._initialized = True

    def _update_cartesian(self) -> None:
        """The end effector's pose and the external wrench: computed when the state is asked
        for (a state controller at 30 Hz), not at every read."""
        s = self.state
        if not self._initialized:
            return
        s.O_T_EE = s.O_T_EE_d = s.O_T_EE_c = self._model.pose()
        jacobian = np.array(self._model.zero_jacobian())
        wrench = np.linalg.pinv(jacobian.T) @ np.array(s.tau_ext_hat_filtered)
        s.O_F_ext_hat_K = [float(v) for v in wrench]
        # K frame = EE_T_K on the end effector: the wrench in its axes
        rotation = (
            np.array(s.O_T_EE).reshape(4, 4).T[:3, :3] @ np.array(s.EE_T_K).reshape(4, 4).T[:3, :3]
        )
        s.K_F_ext_hat_K = [float(v) for v in rotation.T @ wrench[:3]] + [
            float(v) for v in rotation.T @ wrench[3:]
        ]

    def write(self) -> None:
        """writeSim: each joint's effort by how it is driven, gravity added on the arm."""
        dt = self.period
        gravity = self.dynamics.gravity(self.q_all)
        moving = self.state.robot_mode == ROBOT_MODE_MOVE
        for j, g in zip(self.arm, gravity):
            j.gravity = g
        efforts = []
        for j in self._written:
            arm_joint = j in self.arm
            if arm_joint and not moving:
                effort = self._position_control(j, j.stop_position, dt)
            elif j.method == POSITION_JOINT_INTERFACE:
                effort = self._position_control(j, j.command(POSITION_JOINT_INTERFACE), dt)
            elif j.method == VELOCITY_JOINT_INTERFACE:
                error = j.command(VELOCITY_JOINT_INTERFACE) - j.velocity
                effort = _clamp(j.velocity_pid.compute_command(error, dt), j.max_effort)
            elif j.method == EFFORT_JOINT_INTERFACE:
                effort = j.command(EFFORT_JOINT_INTERFACE)  # feed-forward
            else:
                effort = 0.0
            if arm_joint:
                effort += j.gravity
            if not math.isfinite(effort):
                log.warning('Command for %s is not finite, won\'t send to robot', j.name)
                effort = 0.0
            j.effort = effort
            efforts.append(effort)
        self.robot.apply_efforts(self._written_indices, efforts)

    def _position_control(self, j: _Joint, setpoint: float, dt: float) -> float:
        if not math.isfinite(setpoint):
            setpoint = j.position
        lower, upper = j.limits.lower, j.limits.upper
        if lower is not None and upper is not None:
            setpoint = min(max(setpoint, lower), upper)
        return _clamp(j.position_pid.compute_command(setpoint - j.position, dt), j.max_effort)


def _clamp(value: float, limit: float) -> float:
    return min(max(value, -limit), limit)
