"""IMUs: Gazebo's ``imu`` sensor read through gazebo_ros_imu_sensor, and the older
gazebo_ros_imu model plugin, each as upstream computes its numbers.

The sensor (gazebo/sensors/ImuSensor.cc with gazebo_ros_imu_sensor.cpp): orientation of the
sensor frame in the world (or relative to its pose at spawn), angular velocity in the sensor
frame, and linear acceleration as a real accelerometer reads it, Rᵀ(dv/dt − g): +9.8 on z at
rest. The model plugin (gazebo_ros_imu.cpp): link orientation, and world angular velocity and
finite-difference acceleration (no gravity) turned by R, not Rᵀ, as upstream does.
"""

from __future__ import annotations

import random
from dataclasses import dataclass
from typing import Dict, Optional, Sequence, Tuple

from ..description.pose_math import conjugate, multiply, normalized
from .link_motion import (
    Frame,
    Quat,
    Vec3,
    gaussian,
    gravity,
    point_state,
    quaternion_from_rpy,
    rotate,
    scale,
    sub,
    unrotate,
)
from .robot import Robot
from .sim_sensor import SimSensor


@dataclass
class ImuReading:
    orientation: Quat  # xyzw
    angular_velocity: Vec3
    linear_acceleration: Vec3
    noise: float  # the plugin's gaussianNoise: covariance diagonals are its square


@dataclass
class NoiseModel:
    """SDF ``<noise type="gaussian">``: mean, stddev, and a bias drawn once at load with a
    random sign (gazebo/sensors/GaussianNoiseModel.cc)."""

    mean: float = 0.0
    stddev: float = 0.0
    bias: float = 0.0
    precision: float = 0.0  # > 0: the output is rounded to a multiple of it

    @classmethod
    def gaussian(
        cls,
        mean: float,
        stddev: float,
        bias_mean: float = 0.0,
        bias_stddev: float = 0.0,
        precision: float = 0.0,
    ) -> 'NoiseModel':
        bias = bias_mean + gaussian(bias_stddev)
        if random.random() < 0.5:
            bias = -bias
        return cls(mean, stddev, bias, precision)

    def apply(self, value: float) -> float:
        out = value + self.mean + gaussian(self.stddev) + self.bias
        if self.precision > 0:
            out = round(out / self.precision) * self.precision
        return out


# keys: 'angular_velocity/x', ..., 'linear_acceleration/z'
SdfNoise = Dict[str, NoiseModel]


class ImuSensor(SimSensor):
    """``<sensor type="imu">`` with gazebo_ros_imu_sensor.

    The sensor measures at ``<update_rate>`` (0: every step); the plugin publishes a
    measurement when ``updateRateHZ`` allows (upstream: not before 1/rate since the last).
    The acceleration is the change of the sensor point's velocity since the sensor's previous
    update, so the velocity is also sampled at the update just before each publication.
    """

    kind = 'imu'

    def __init__(
        self,
        model: str,
        name: str,
        robot: Robot,
        link_index: int,
        pose: Frame,  # the sensor in the link's frame
        sensor_rate: float,
        publish_rate: float,  # updateRateHZ
        noise: float = 0.0,  # gaussianNoise
        rpy_offset: Sequence[float] = (0.0, 0.0, 0.0),
        initial_reference: bool = False,  # initialOrientationAsReference
        sdf_noise: Optional[SdfNoise] = None,
    ) -> None:
        super().__init__(model, name, sensor_rate)
        self.robot, self.index, self.pose = robot, link_index, pose
        self.publish_period_ns = int(round(1e9 / publish_rate)) if publish_rate > 0 else 0
        self.noise = noise
        self.offset_rotation = quaternion_from_rpy(rpy_offset)
        self.sdf_noise = sdf_noise or {}
        # REP 145: the world is the reference; the deprecated option takes the pose at spawn.
        self.reference: Quat = (0.0, 0.0, 0.0, 1.0)
        if initial_reference:
            self.reference = point_state(robot, link_index, pose)[1]
        self._sample: Optional[Tuple[int, Vec3]] = None  # (time, sensor point velocity)
        self._last_publish = 0  # upstream starts from the sensor's last update: 0 at load
        self._previous_call = -1
        self._step_ns = 0

    def update(self, now_ns: int) -> None:
        # The sensor's and the plugin's clocks run whether or not anyone listens (integers
        # only, as upstream's do); pybullet is read only for a listener.
        if 0 <= self._previous_call < now_ns:
            self._step_ns = now_ns - self._previous_call
        self._previous_call = now_ns
        if now_ns < self._last_publish:  # time went back (reset_simulation)
            self._last_publish = now_ns
            self._sample = None
        if not self.due(now_ns):
            return
        listening = self.deliver is not None and self.wanted()
        if now_ns - self._last_publish >= self.publish_period_ns:
            self._last_publish = now_ns
            if listening and self.deliver is not None:
                reading = self.measure(now_ns)
                self.readings += 1
                self.deliver(now_ns, reading)
        elif listening and (
            now_ns + (self.period_ns or self._step_ns) - self._last_publish
            >= self.publish_period_ns
        ):
            # the next sensor update publishes: keep this one's velocity for its acceleration
            self._sample = (now_ns, point_state(self.robot, self.index, self.pose)[2])

    def measure(self, now_ns: int) -> ImuReading:
        _, orn, v, w = point_state(self.robot, self.index, self.pose)
        acc_world: Vec3 = (0.0, 0.0, 0.0)
        sample = self._sample
        period = self.period_ns or self._step_ns
        if sample is not None and 0 < now_ns - sample[0] <= 2 * period:
            acc_world = scale(sub(v, sample[1]), 1e9 / (now_ns - sample[0]))
        self._sample = (now_ns, v)
        angular = unrotate(orn, w)
        linear = unrotate(orn, sub(acc_world, gravity(self.robot.client)))
        angular, linear = self._sdf_noise(angular, linear)
        orientation = multiply(self.offset_rotation, multiply(conjugate(self.reference), orn))
        n = self.noise
        return ImuReading(
            tuple(c + gaussian(n) for c in orientation),  # type: ignore[arg-type]
            tuple(c + gaussian(n) for c in angular),  # type: ignore[arg-type]
            tuple(c + gaussian(n) for c in linear),  # type: ignore[arg-type]
            n,
        )

    def _sdf_noise(self, angular: Vec3, linear: Vec3) -> Tuple[Vec3, Vec3]:
        if not self.sdf_noise:
            return angular, linear
        out = []
        for kind, values in (('angular_velocity', angular), ('linear_acceleration', linear)):
            noisy = []
            for axis, value in zip('xyz', values):
                model = self.sdf_noise.get('%s/%s' % (kind, axis))
                noisy.append(model.apply(value) if model is not None else value)
            out.append((noisy[0], noisy[1], noisy[2]))
        return out[0], out[1]


class ImuModelPlugin(SimSensor):
    """gazebo_ros_imu (a model plugin): measured at ``updateRate`` (0: every step)."""

    kind = 'gazebo_ros_imu'
    service = ''  # serviceName: an Empty service that does nothing, as upstream

    def __init__(
        self,
        model: str,
        name: str,
        robot: Robot,
        link_index: int,
        offset: Frame,  # the link's offset when lumped (identity otherwise)
        update_rate: float,
        noise: float = 0.0,
        rpy_offset: Sequence[float] = (0.0, 0.0, 0.0),
    ) -> None:
        super().__init__(model, name, update_rate)
        self.robot, self.index, self.offset = robot, link_index, offset
        self.noise = noise
        self.offset_rotation = quaternion_from_rpy(rpy_offset)
        # upstream takes the link's velocity at load as the first "last" one
        self._last: Tuple[int, Vec3] = (0, point_state(robot, link_index, offset)[2])

    def measure(self, now_ns: int) -> ImuReading:
        _, orn, v, w = point_state(self.robot, self.index, self.offset)
        rot = normalized(multiply(self.offset_rotation, orn))
        t0, v0 = self._last
        acc: Vec3 = (0.0, 0.0, 0.0)
        if now_ns != t0:
            acc = scale(sub(v, v0), 1e9 / (now_ns - t0))
            self._last = (now_ns, v)
        n = self.noise
        angular = rotate(rot, tuple(c + gaussian(n) for c in w))
        linear = rotate(rot, tuple(c + gaussian(n) for c in acc))
        return ImuReading(rot, angular, linear, n)
