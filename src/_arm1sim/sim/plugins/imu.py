"""gazebo_ros_imu_sensor (in an ``imu`` sensor) and gazebo_ros_imu (a model plugin), with
upstream's parameters and defaults (gazebo_plugins/src/gazebo_ros_imu_sensor.cpp,
gazebo_ros_imu.cpp)."""

from __future__ import annotations

from typing import Optional

from ...description.gazebo_plugins import PluginSpec, SensorSpec, number, topic
from ...description.limits import Limits
from ...description.urdf_model import UrdfError
from ...physics.imu import ImuModelPlugin, ImuSensor, NoiseModel, SdfNoise
from ...physics.robot import Robot
from .common import body_frame, has, not_loaded, plugin_rate, rate, sensor_frame, vector
from .registry import PluginType, register


def _sdf_imu_noise(sensor: SensorSpec) -> SdfNoise:
    """``<imu><angular_velocity|linear_acceleration><x|y|z><noise type="gaussian">``."""
    out: SdfNoise = {}
    for kind in ('angular_velocity', 'linear_acceleration'):
        for axis in 'xyz':
            path = 'imu/%s/%s/noise' % (kind, axis)
            element = sensor.element.find(path)
            if element is None:
                continue
            kind_attr = (element.get('type') or element.findtext('type') or '').strip()
            if kind_attr in ('', 'none'):
                continue
            if kind_attr not in ('gaussian', 'gaussian_quantized'):
                raise UrdfError(
                    "%s <%s>: noise type %r is not 'gaussian'" % (sensor.where, path, kind_attr)
                )
            where = '%s <%s>' % (sensor.where, path)
            out['%s/%s' % (kind, axis)] = NoiseModel.gaussian(
                number(element, 'mean', 0.0, where),
                number(element, 'stddev', 0.0, where),
                number(element, 'bias_mean', 0.0, where),
                number(element, 'bias_stddev', 0.0, where),
                max(0.0, number(element, 'precision', 0.0, where)),
            )
    return out


def build_imu_sensor(
    model: str, sensor: SensorSpec, plugin: PluginSpec, robot: Robot, ns: str, limits: Limits
) -> Optional[ImuSensor]:
    """gazebo_ros_imu_sensor in an ``imu`` sensor. ``<bodyName>`` is not one of its
    parameters (upstream ignores it)."""
    if sensor.type != 'imu':
        not_loaded(model, plugin, "its sensor is of type '%s', not imu" % sensor.type)
        return None
    frame = plugin.text('frameName')
    if not has(plugin, 'frameName'):
        not_loaded(model, plugin, 'missing <frameName>')
        return None
    index, pose = sensor_frame(robot, sensor)
    imu = ImuSensor(
        model,
        sensor.name,
        robot,
        index,
        pose,
        rate(limits, sensor.update_rate, sensor.where),
        rate(limits, plugin.number('updateRateHZ', 1.0), plugin.where),
        plugin.number('gaussianNoise', 0.0),
        vector(plugin, 'rpyOffset'),
        plugin.flag('initialOrientationAsReference', False),
        _sdf_imu_noise(sensor),
    )
    imu.topic = topic(ns, plugin.text('topicName', 'imu_data'))
    imu.frame_id = frame
    return imu


def build_imu_plugin(
    model: str, plugin: PluginSpec, robot: Robot, ns: str, limits: Limits
) -> Optional[ImuModelPlugin]:
    """gazebo_ros_imu, the model plugin."""
    body = plugin.text('bodyName')
    found = body_frame(model, plugin, robot)
    if found is None:
        return None
    imu = ImuModelPlugin(
        model,
        plugin.name,
        robot,
        *found,
        plugin_rate(limits, plugin),
        plugin.number('gaussianNoise', 0.0),
        vector(plugin, 'rpyOffset'),
    )
    # upstream: an empty topicName advertises neither the topic nor the service
    name = plugin.text('topicName') if has(plugin, 'topicName') else '/default_imu'
    imu.topic = topic(ns, name) if name else ''
    imu.service = topic(ns, plugin.text('serviceName', '/default_imu'))
    imu.frame_id = plugin.text('frameName', body)
    return imu


register(
    PluginType(
        'libgazebo_ros_imu_sensor.so',
        build_sensor=build_imu_sensor,
        publisher='state_sensor_plugins:imu_sensor_publisher',
    ),
    PluginType(
        'libgazebo_ros_imu.so',
        build_model=build_imu_plugin,
        publisher='state_sensor_plugins:imu_plugin_publisher',
    ),
)
