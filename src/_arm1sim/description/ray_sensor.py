"""A ``ray``/``gpu_ray`` sensor's ``<ray>`` element and its gazebo_ros_laser parameters.

ROS-free, pybullet-free. Defaults are SDF's (sdformat ``ray.sdf``, ``noise.sdf``):
640 horizontal samples, resolution 1, angles 0, one vertical sample, range 0..0
(``<range><max>`` is required there: a ray sensor without one is refused here),
noise type gaussian when ``<noise>`` is present. Counts follow Gazebo's
RaySensor: ``ranges = int(samples * resolution)`` per layer, interpolated from
the rays when resolution is not 1.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Optional

from .gazebo_plugins import PluginSpec, SensorSpec, number
from .limits import Limits
from .urdf_model import UrdfError

RAY_TYPES = ('ray', 'gpu_ray')
LASER_PLUGIN = 'libgazebo_ros_laser.so'
GPU_LASER_PLUGIN = 'libgazebo_ros_gpu_laser.so'
# the sensor type each plugin's Load requires (it throws on any other parent sensor)
PLUGIN_SENSOR_TYPE = {LASER_PLUGIN: 'ray', GPU_LASER_PLUGIN: 'gpu_ray'}


@dataclass
class RayNoise:
    """SDF ``<noise type="gaussian">`` as Gazebo's GaussianNoiseModel applies it."""

    mean: float = 0.0
    stddev: float = 0.0
    bias_mean: float = 0.0
    bias_stddev: float = 0.0
    precision: float = 0.0  # > 0: quantised to multiples of it (gaussian_quantized)


@dataclass
class RaySpec:
    samples: int = 640
    resolution: float = 1.0
    min_angle: float = 0.0
    max_angle: float = 0.0
    vertical_samples: int = 1
    vertical_resolution: float = 1.0
    vertical_min_angle: float = 0.0
    vertical_max_angle: float = 0.0
    range_min: float = 0.0
    range_max: float = 0.0
    range_resolution: float = 0.0  # read, not applied (as in Gazebo)
    noise: Optional[RayNoise] = None

    @property
    def rays(self) -> int:
        return self.samples * self.vertical_samples

    @property
    def range_count(self) -> int:
        """Ranges per layer (Gazebo's RangeCount: the product truncated to int)."""
        return int(self.samples * self.resolution)

    @property
    def vertical_range_count(self) -> int:
        return int(self.vertical_samples * self.vertical_resolution)

    @property
    def angle_increment(self) -> float:
        """Gazebo's AngleResolution: (max - min) / (range count - 1); with one range that
        division is by zero: +-inf, or NaN for an empty span, as C++ doubles give."""
        span = self.max_angle - self.min_angle
        steps = self.range_count - 1
        if steps:
            return span / steps
        return math.nan if span == 0 else math.copysign(math.inf, span)


@dataclass
class LaserPlugin:
    """gazebo_ros_laser's (and gazebo_ros_gpu_laser's) own parameters."""

    topic_name: str = '/world'  # '' advertises nothing
    frame_name: str = '/world'  # before tf::resolve
    namespace: str = ''


def _count(element: Any, path: str, default: int, where: str) -> int:
    value = number(element, path, default, where)
    if value < 1 or value != int(value):
        raise UrdfError('%s <%s>: %r is not a positive whole number' % (where, path, value))
    return int(value)


def _noise(element: Any, where: str) -> Optional[RayNoise]:
    noise = element.find('ray/noise')
    if noise is None:
        return None
    kind = (noise.get('type') or noise.findtext('type') or 'gaussian').strip()
    if kind == 'none':
        return None
    if kind not in ('gaussian', 'gaussian_quantized'):
        raise UrdfError("%s <ray><noise>: type %r is not 'gaussian' or 'none'" % (where, kind))
    here = '%s <ray><noise>' % where
    out = RayNoise(
        number(noise, 'mean', 0.0, here),
        number(noise, 'stddev', 0.0, here),
        number(noise, 'bias_mean', 0.0, here),
        number(noise, 'bias_stddev', 0.0, here),
        number(noise, 'precision', 0.0, here) if kind == 'gaussian_quantized' else 0.0,
    )
    if out.stddev < 0 or out.bias_stddev < 0 or out.precision < 0:
        raise UrdfError('%s: stddev, bias_stddev and precision must not be negative' % here)
    return out


def ray_spec(sensor: SensorSpec, limits: Optional[Limits] = None) -> RaySpec:
    """The sensor's ``<ray>``; raises UrdfError or LimitError naming the sensor."""
    e, where = sensor.element, sensor.where
    if e.find('ray') is None:
        raise UrdfError('%s (type %s) has no <ray> element' % (where, sensor.type))
    h, v, r = 'ray/scan/horizontal/', 'ray/scan/vertical/', 'ray/range/'
    if not (e.findtext(r + 'max') or '').strip():
        raise UrdfError('%s: <ray><range><max> is required' % where)
    spec = RaySpec(
        samples=_count(e, h + 'samples', 640, where),
        resolution=number(e, h + 'resolution', 1.0, where),
        min_angle=number(e, h + 'min_angle', 0.0, where),
        max_angle=number(e, h + 'max_angle', 0.0, where),
        vertical_samples=_count(e, v + 'samples', 1, where),
        vertical_resolution=number(e, v + 'resolution', 1.0, where),
        vertical_min_angle=number(e, v + 'min_angle', 0.0, where),
        vertical_max_angle=number(e, v + 'max_angle', 0.0, where),
        range_min=number(e, r + 'min', 0.0, where),
        range_max=number(e, r + 'max', 0.0, where),
        range_resolution=number(e, r + 'resolution', 0.0, where),
        noise=_noise(e, where),
    )
    if not 0 <= spec.range_min < spec.range_max:
        raise UrdfError(
            '%s <ray><range>: min %g and max %g must satisfy 0 <= min < max'
            % (where, spec.range_min, spec.range_max)
        )
    if spec.range_count < 1 or spec.vertical_range_count < 1:
        raise UrdfError(
            '%s <ray><scan>: samples x resolution gives %d x %d ranges; at least one of each'
            % (where, spec.range_count, spec.vertical_range_count)
        )
    if limits is not None:
        limits.check('rays_per_laser', spec.rays, where)
        limits.check(
            'rays_per_laser', spec.range_count * spec.vertical_range_count, where + ' (ranges)'
        )
        limits.check('sensor_update_rate', sensor.update_rate, where)
        # every step (rate 0) is charged as the fastest rate a sensor may have
        rate = sensor.update_rate or limits.sensor_update_rate
        limits.check('ray_casts_per_second', spec.rays * rate, where)
    return spec


def laser_plugin(plugin: PluginSpec, namespace: str) -> LaserPlugin:
    """topicName and frameName ('/world' each when absent, as upstream), robotNamespace."""

    def given(tag: str) -> Optional[str]:
        text = plugin.element.findtext(tag)
        return None if text is None else text.strip()

    topic, frame = given('topicName'), given('frameName')
    return LaserPlugin(
        '/world' if topic is None else topic,
        '/world' if frame is None else frame,
        namespace,  # PluginSpec.namespace's answer
    )
