"""A ``ray``/``gpu_ray`` sensor measured with pybullet ray casts, as Gazebo's RaySensor and
GpuRaySensor report it (gazebo/sensors/RaySensor.cc, physics/MultiRayShape.cc).

ROS-free. One ``rayTestBatch`` call per scan (chunked past pybullet's batch size).
Rays run from ``<range><min>`` to ``<range><max>`` along Gazebo's directions (yaw
across ``<horizontal>``, pitch up across ``<vertical>``); a ray that first meets the
sensor's own link takes its nearest other hit, so the link carrying the sensor never
shadows it. Ranges: a ray that meets nothing reads max; with resolution != 1 the
ranges are Gazebo's bilinear interpolation of the rays; then, as Gazebo >= 7 (REP 117),
>= max is +inf, <= min is -inf, and only values in between get the gaussian noise,
clamped to [min, max]. Intensities are 0: the laser_retro Gazebo would report is not
modelled (0 is its default).
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from typing import Any, Iterable, List, Optional, Tuple

import numpy as np
import pybullet as p

from ..description.ray_sensor import LaserPlugin, RaySpec
from .robot import Robot
from .sim_sensor import Quat, SimSensor, Vec3, compose

log = logging.getLogger('_arm1sim.physics')

BATCH = 16384  # pybullet's MAX_RAY_INTERSECTION_BATCH_SIZE
MAX_HITS = 16  # hits looked through for a ray that first meets the sensor's own link
Frame = Tuple[Vec3, Quat]


@dataclass
class LaserReading:
    ranges: np.ndarray  # float64, vertical layers concatenated
    intensities: np.ndarray


def ray_directions(spec: RaySpec) -> np.ndarray:
    """Unit vectors (rays x 3) in the sensor frame, vertical layer outer, as MultiRayShape
    builds them: yaw then a pitch about -y (positive vertical angles point up)."""
    hs, vs = spec.samples, spec.vertical_samples
    yaw = (
        np.zeros(1)
        if hs == 1
        else spec.min_angle + np.arange(hs) * ((spec.max_angle - spec.min_angle) / (hs - 1))
    )
    pitch = (
        np.zeros(1)
        if vs == 1
        else spec.vertical_min_angle
        + np.arange(vs) * ((spec.vertical_max_angle - spec.vertical_min_angle) / (vs - 1))
    )
    pv, yv = np.meshgrid(pitch, yaw, indexing='ij')
    out = np.stack([np.cos(pv) * np.cos(yv), np.cos(pv) * np.sin(yv), np.sin(pv)], axis=-1)
    return out.reshape(-1, 3)


def _weights(rays: int, ranges: int) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Gazebo's interpolation indices a, b and fraction for ``ranges`` points over ``rays``."""
    if ranges == 1:
        t = np.zeros(1)
    else:
        t = np.arange(ranges) * ((rays - 1) / (ranges - 1))
    a = np.floor(t).astype(int)
    b = np.minimum(a + 1, rays - 1)
    return a, b, t - a


def interpolate(raw: np.ndarray, spec: RaySpec) -> np.ndarray:
    """Ranges (vertical range count x range count, flattened) from the rays, as RaySensor."""
    hs, vs = spec.samples, spec.vertical_samples
    hr, vr = spec.range_count, spec.vertical_range_count
    if hs == hr and vs == vr:
        return raw
    grid = raw.reshape(vs, hs)
    ha, hb, hf = _weights(hs, hr)
    va, vb, vf = _weights(vs, vr)
    top = grid[va][:, ha] * (1 - hf) + grid[va][:, hb] * hf
    bottom = grid[vb][:, ha] * (1 - hf) + grid[vb][:, hb] * hf
    out: np.ndarray = top * (1 - vf)[:, None] + bottom * vf[:, None]
    return out.reshape(-1)


class Laser(SimSensor):
    """One ray sensor on a link of a spawned robot."""

    kind = 'ray'

    def __init__(
        self,
        model: str,
        name: str,
        robot: Robot,
        link: str,
        pose: Frame,
        spec: RaySpec,
        update_rate: float,
        seed: Optional[int] = None,
        num_threads: int = 1,
    ) -> None:
        super().__init__(model, name, update_rate)
        self.robot, self.link, self.pose, self.spec = robot, link, pose, spec
        self.num_threads = num_threads
        self.sensor_type = 'ray'
        self.plugin = LaserPlugin()
        self.topic = ''  # the ROS topic, '' for none
        self._dirs = ray_directions(spec)
        self._own = (robot.body, robot.link_index[link])
        self._rng = np.random.default_rng(seed)
        self._bias = 0.0
        if spec.noise is not None:
            n = spec.noise
            # GaussianNoiseModel::Load draws the bias once, with a random sign
            self._bias = float(self._rng.normal(n.bias_mean, n.bias_stddev))
            if self._rng.uniform() < 0.5:
                self._bias = -self._bias

    def world_pose(self) -> Frame:
        """The sensor frame in the world: its link's pose times its offset."""
        return compose(self.robot.link_pose(self.link), self.pose)

    def cast(self) -> np.ndarray:
        """Raw ray lengths from the sensor origin: where each ray first meets something
        other than the sensor's own link, ``range_max`` where it meets nothing."""
        spec = self.spec
        position, orientation = self.world_pose()
        rotation = np.array(p.getMatrixFromQuaternion(orientation)).reshape(3, 3)
        dirs = self._dirs @ rotation.T
        origin = np.asarray(position, dtype=float)
        froms = origin + dirs * spec.range_min
        tos = origin + dirs * spec.range_max
        fraction = np.ones(len(dirs))
        own = []
        for k, hit in enumerate(self._ray_test(froms, tos)):
            if (hit[0], hit[1]) == self._own:
                own.append(k)
            elif hit[0] >= 0:
                fraction[k] = hit[2]
        if own:  # the nearest of all their hits that is not on the own link
            index = np.array(own)
            pending = np.ones(len(index), dtype=bool)
            for n in range(MAX_HITS):
                hits = self._ray_test(froms[index], tos[index], n)
                for j, hit in enumerate(hits):
                    if hit[0] < 0:
                        pending[j] = False
                    elif (hit[0], hit[1]) != self._own:
                        k = index[j]
                        fraction[k] = min(fraction[k], hit[2])
                if not pending.any():
                    break
        out: np.ndarray = spec.range_min + fraction * (spec.range_max - spec.range_min)
        return out

    def _ray_test(self, froms: np.ndarray, tos: np.ndarray, hit_number: int = -1) -> List[Any]:
        """pybullet's nearest hit of each ray, or (hit_number >= 0) its hit number n in
        Bullet's (unsorted) order, (-1, ...) past the last."""
        f, t = froms.tolist(), tos.tolist()
        extra = {} if hit_number < 0 else {'reportHitNumber': hit_number}
        hits: List[Any] = []
        for i in range(0, len(f), BATCH):
            hits.extend(
                p.rayTestBatch(
                    f[i : i + BATCH],
                    t[i : i + BATCH],
                    numThreads=self.num_threads,
                    physicsClientId=self.robot.client,
                    **extra,
                )
            )
        return hits

    def measure(self, now_ns: int) -> LaserReading:
        return self.reading(self.cast())

    def reading(self, raw: np.ndarray) -> LaserReading:
        """Ranges and intensities from the raw ray lengths (interpolation, REP 117, noise)."""
        spec = self.spec
        ranges = interpolate(raw, spec).astype(float)
        high = ranges >= spec.range_max
        low = ranges <= spec.range_min
        inside = ~(high | low)
        n = spec.noise
        if n is not None and inside.any():
            noisy = ranges[inside] + self._bias + self._rng.normal(n.mean, n.stddev, inside.sum())
            if n.precision > 0:
                noisy = np.round(noisy / n.precision) * n.precision
            ranges[inside] = np.clip(noisy, spec.range_min, spec.range_max)
        ranges[high] = math.inf
        ranges[low] = -math.inf
        return LaserReading(ranges, np.zeros(len(ranges)))


def ray_casts_per_second(sensors: Iterable[Any], every_step_hz: float) -> float:
    """Rays a second of sim time the lasers among ``sensors`` cast while wanted (a rate of 0,
    every step, counted as ``every_step_hz``)."""
    return sum(
        s.spec.rays * (s.update_rate or every_step_hz) for s in sensors if isinstance(s, Laser)
    )
