"""gazebo_ros_diff_drive: two wheel joints driven from a (linear.x, angular.z) command, and
odometry of the model, as gazebo_plugins/src/gazebo_ros_diff_drive.cpp does it.

Unlike a sensor it acts every physics update whether anyone listens or not: with
``odometrySource`` encoder it integrates the wheel speeds at every update; at its update
rate it reports odometry (and the wheels' states) and sets each wheel's velocity motor,
capped at ``wheelTorque`` (Gazebo's SetParam("vel") with "fmax"). ``legacyMode`` (true by
default upstream) swaps the sign of the turn, as upstream's old left/right mix-up did.
"""

from __future__ import annotations

import logging
import math
import threading
from dataclasses import dataclass
from typing import List, Optional, Tuple

import pybullet as p

from .link_motion import Frame, Quat, Vec3, point_state
from .robot import Robot
from .sim_sensor import SimSensor

log = logging.getLogger('_arm1sim.physics')

LEFT, RIGHT = 0, 1
ENCODER, WORLD = 'encoder', 'world'


@dataclass
class DiffDriveReading:
    position: Vec3  # of the robot base frame in the odometry frame
    orientation: Quat
    linear: Vec3  # world source: in the base frame; encoder: as upstream, dx/dt, dy/dt
    angular: Vec3
    # (parent link, child link, position, quaternion) of each wheel, for publishWheelTF
    wheel_frames: List[Tuple[str, str, Vec3, Quat]]
    # (joint name, position) of each wheel, for publishWheelJointState
    wheel_positions: List[Tuple[str, float]]


class DiffDrive(SimSensor):
    kind = 'gazebo_ros_diff_drive'
    # set by the builder for the ROS layer: topics under the plugin's namespace, frames
    command_topic = ''
    odometry_topic = ''
    odometry_frame = 'odom'
    robot_base_frame = 'base_footprint'
    publish_tf = True  # <publishTf>: whether odometry is published at all
    publish_odom_tf = True
    publish_wheel_tf = False
    publish_wheel_joint_state = False

    def __init__(
        self,
        model: str,
        name: str,
        robot: Robot,
        base: Tuple[int, Frame],  # the model frame: its root link and offset
        wheels: Tuple[str, str],  # leftJoint, rightJoint
        wheel_separation: float = 0.34,
        wheel_diameter: float = 0.15,
        wheel_torque: float = 5.0,
        wheel_acceleration: float = 0.0,
        update_rate: float = 100.0,
        odometry_source: str = WORLD,
        legacy_mode: bool = True,
    ) -> None:
        super().__init__(model, name, update_rate)
        self.robot, self.base = robot, base
        self.wheel_names = wheels
        self.wheels = robot.indices(list(wheels))
        self.wheel_separation, self.wheel_diameter = wheel_separation, wheel_diameter
        self.wheel_torque, self.wheel_acceleration = wheel_torque, wheel_acceleration
        self.odometry_source, self.legacy_mode = odometry_source, legacy_mode
        self._lock = threading.Lock()
        self._command = (0.0, 0.0)  # x_, rot_ (cmd_vel linear.x, angular.z)
        self.wheel_speed_instr = [0.0, 0.0]
        self._encoder = [0.0, 0.0, 0.0]  # x, y, theta
        self._encoder_twist = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
        self._last_odom_ns: Optional[int] = None
        self._seen_ns = 0
        self._wheel_links = [self._joint_links(i) for i in self.wheels]

    def _joint_links(self, index: int) -> Tuple[str, str, int]:
        """(parent link, child link, child index) of a wheel joint."""
        info = p.getJointInfo(self.robot.body, index, physicsClientId=self.robot.client)
        names = {i: n for n, i in self.robot.link_index.items()}
        return names.get(info[16], ''), info[12].decode(), index

    # ------------------------------------------------------------------ the ROS side's calls
    def set_command(self, linear_x: float, angular_z: float) -> None:
        """cmdVelCallback: kept until the next command (upstream has no timeout). A
        non-finite one raises ValueError and the last command stays: one NaN would make
        the wheel speeds, and through them pose and odometry, NaN for good."""
        command = (float(linear_x), float(angular_z))
        if not all(math.isfinite(v) for v in command):
            raise ValueError(
                'linear.x %r, angular.z %r: not finite; keeping the last command' % command
            )
        with self._lock:
            self._command = command

    def reset(self) -> None:
        """Reset(): odometry back to zero, no command."""
        with self._lock:
            self._command = (0.0, 0.0)
        self._encoder = [0.0, 0.0, 0.0]
        self.wheel_speed_instr = [0.0, 0.0]
        self._last_odom_ns = None

    # ------------------------------------------------------------------ physics thread
    def wheel_speeds(self) -> Tuple[float, float]:
        """getWheelVelocities: the rim speed each wheel is asked for (m/s)."""
        with self._lock:
            vr, va = self._command
        half = va * self.wheel_separation / 2.0
        if self.legacy_mode:
            return vr + half, vr - half
        return vr - half, vr + half

    def update(self, now_ns: int) -> None:
        """UpdateChild: acts every update, whether anyone listens or not."""
        if now_ns < self._seen_ns:
            self.reset()  # time went back (reset_simulation): as upstream's Reset
        self._seen_ns = now_ns
        if self.odometry_source == ENCODER:
            self._update_encoder(now_ns)
        if not self.due(now_ns):
            return
        if self.deliver is not None:
            reading = self.measure(now_ns)
            self.readings += 1
            self.deliver(now_ns, reading)
        self._drive()

    def _drive(self) -> None:
        radius = self.wheel_diameter / 2.0
        target = self.wheel_speeds()
        states = self.robot.read(self.wheels)
        current = [v * radius for _, v in states]
        accel = self.wheel_acceleration
        if (
            accel == 0.0
            or abs(target[LEFT] - current[LEFT]) < 0.01
            or abs(target[RIGHT] - current[RIGHT]) < 0.01
        ):
            speeds = list(target)
        else:
            step = accel * (self.period_ns * 1e-9 if self.period_ns else 0.0)
            for i in (LEFT, RIGHT):
                gap = target[i] - current[i]
                self.wheel_speed_instr[i] += min(gap, step) if gap >= 0 else max(gap, -step)
            speeds = list(self.wheel_speed_instr)
        self.robot.set_velocity_motors(
            self.wheels, [s / radius for s in speeds], [self.wheel_torque] * 2
        )

    def _update_encoder(self, now_ns: int) -> None:
        """UpdateOdometryEncoder: the wheel speeds integrated since the last update."""
        last, self._last_odom_ns = self._last_odom_ns, now_ns
        if last is None or now_ns <= last:
            return
        dt = (now_ns - last) * 1e-9
        radius = self.wheel_diameter / 2.0
        (_, vl), (_, vr) = self.robot.read(self.wheels)
        sl, sr = vl * radius * dt, vr * radius * dt
        ssum = sl + sr
        sdiff = sl - sr if self.legacy_mode else sr - sl
        b = self.wheel_separation
        x, y, theta = self._encoder
        dx = ssum / 2.0 * math.cos(theta + sdiff / (2.0 * b))
        dy = ssum / 2.0 * math.sin(theta + sdiff / (2.0 * b))
        dtheta = sdiff / b
        self._encoder = [x + dx, y + dy, theta + dtheta]
        self._encoder_twist = ((dx / dt, dy / dt, 0.0), (0.0, 0.0, dtheta / dt))

    def measure(self, now_ns: int) -> DiffDriveReading:
        if self.odometry_source == ENCODER:
            x, y, theta = self._encoder
            position: Vec3 = (x, y, 0.0)
            orientation: Quat = (0.0, 0.0, math.sin(theta / 2.0), math.cos(theta / 2.0))
            linear, angular = self._encoder_twist
        else:
            position, orientation, v, w = point_state(self.robot, *self.base)
            qx, qy, qz, qw = orientation
            yaw = math.atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz))
            c, s = math.cos(yaw), math.sin(yaw)
            # upstream: world velocity turned into the base frame by yaw only
            linear = (c * v[0] + s * v[1], c * v[1] - s * v[0], 0.0)
            angular = (0.0, 0.0, w[2])
        frames: List[Tuple[str, str, Vec3, Quat]] = []
        if self.publish_wheel_tf:
            for parent_name, child_name, index in self._wheel_links:
                frames.append((parent_name, child_name, *self._relative(index)))
        positions: List[Tuple[str, float]] = []
        if self.publish_wheel_joint_state:
            states = self.robot.read(self.wheels)
            positions = [(n, s[0]) for n, s in zip(self.wheel_names, states)]
        return DiffDriveReading(position, orientation, linear, angular, frames, positions)

    def _relative(self, child: int) -> Tuple[Vec3, Quat]:
        """The wheel link's frame in the model frame: upstream's RelativePose, though it
        names the joint's parent link as the frame."""
        mp, mo, _, _ = point_state(self.robot, *self.base)
        cp, co, _, _ = point_state(self.robot, child)
        inv = p.invertTransform(mp, mo)
        pos, orn = p.multiplyTransforms(inv[0], inv[1], cp, co)
        return tuple(pos), tuple(orn)
