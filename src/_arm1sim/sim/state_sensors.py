"""Builders for the sensors that read the physics state, not the scene: gazebo_ros_imu_sensor,
gazebo_ros_imu, gazebo_ros_p3d, gazebo_ros_bumper and gazebo_ros_ft_sensor, with upstream's
parameters and defaults (gazebo_plugins/src/*.cpp).

A plugin missing a parameter upstream requires, or naming a link or joint the model lacks,
does not load in Gazebo (ROS_FATAL, the model spawns without it): here too, with a warning
naming it. Unlike Gazebo, an ft sensor's joint needs no ``<provideFeedback>``.
"""

from __future__ import annotations

import logging
from typing import Optional, Tuple

from ..description.gazebo_plugins import PluginSpec, SensorSpec, number, topic
from ..description.limits import Limits
from ..description.sdf_values import vector3
from ..description.urdf_model import UrdfError
from ..physics.contact import ContactSensor
from ..physics.force_torque import ForceTorque
from ..physics.imu import ImuModelPlugin, ImuSensor, NoiseModel, SdfNoise
from ..physics.link_motion import Frame, compose, quaternion_from_rpy
from ..physics.p3d import WORLD_FRAMES, P3d
from ..physics.robot import Robot

log = logging.getLogger('_arm1sim.physics')


def _not_loaded(model: str, plugin: PluginSpec, why: str) -> None:
    log.warning("model '%s': %s is not loaded, as in Gazebo: %s", model, plugin.where, why)


def _vector(plugin: PluginSpec, tag: str) -> Tuple[float, float, float]:
    text = plugin.text(tag)
    values = vector3(text)
    if values is None:
        raise UrdfError('%s <%s>: %r is not 3 numbers' % (plugin.where, tag, text))
    return values


def _rate(limits: Limits, value: float, where: str) -> float:
    """A rate in Hz, within the world's limit for one sensor (0 or less: every step)."""
    limits.check('sensor_update_rate', value, where)
    return value


def _plugin_rate(limits: Limits, plugin: PluginSpec) -> float:
    """The plugin's ``<updateRate>`` (absent: 0, every step), within the limit."""
    return _rate(limits, plugin.number('updateRate', 0.0), plugin.where)


def _has(plugin: PluginSpec, tag: str) -> bool:
    return plugin.element.find(tag) is not None


def _link(robot: Robot, name: str) -> Optional[Tuple[int, Frame]]:
    """The pybullet link carrying ``name``'s frame and the frame's offset in it (a link merged
    into its parent by fixed-joint lumping lives on in the parent at an offset); None for a
    name the model does not have."""
    try:
        index, offset = robot.frame(name)
    except KeyError:
        return None
    return index, (tuple(offset[0]), tuple(offset[1]))


def _sensor_frame(robot: Robot, sensor: SensorSpec) -> Tuple[int, Frame]:
    found = _link(robot, sensor.link)
    if found is None:
        raise UrdfError('%s: the link is not in the model' % sensor.where)
    index, offset = found
    x, y, z, roll, pitch, yaw = sensor.pose
    return index, compose(offset, ((x, y, z), quaternion_from_rpy((roll, pitch, yaw))))


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
        _not_loaded(model, plugin, "its sensor is of type '%s', not imu" % sensor.type)
        return None
    frame = plugin.text('frameName')
    if not _has(plugin, 'frameName'):
        _not_loaded(model, plugin, 'missing <frameName>')
        return None
    index, pose = _sensor_frame(robot, sensor)
    imu = ImuSensor(
        model,
        sensor.name,
        robot,
        index,
        pose,
        _rate(limits, sensor.update_rate, sensor.where),
        _rate(limits, plugin.number('updateRateHZ', 1.0), plugin.where),
        plugin.number('gaussianNoise', 0.0),
        _vector(plugin, 'rpyOffset'),
        plugin.flag('initialOrientationAsReference', False),
        _sdf_imu_noise(sensor),
    )
    imu.topic = topic(ns, plugin.text('topicName', 'imu_data'))
    imu.frame_id = frame
    return imu


def _body(model: str, plugin: PluginSpec, robot: Robot) -> Optional[Tuple[int, Frame]]:
    """The link ``<bodyName>`` names, or None after a warning (Gazebo does not load it)."""
    if not _has(plugin, 'bodyName'):
        _not_loaded(model, plugin, 'missing <bodyName>')
        return None
    body = plugin.text('bodyName')
    found = _link(robot, body)
    if found is None:
        _not_loaded(model, plugin, "bodyName '%s' is not a link of the model" % body)
    return found


def build_imu_plugin(
    model: str, plugin: PluginSpec, robot: Robot, ns: str, limits: Limits
) -> Optional[ImuModelPlugin]:
    """gazebo_ros_imu, the model plugin."""
    body = plugin.text('bodyName')
    found = _body(model, plugin, robot)
    if found is None:
        return None
    imu = ImuModelPlugin(
        model,
        plugin.name,
        robot,
        *found,
        _plugin_rate(limits, plugin),
        plugin.number('gaussianNoise', 0.0),
        _vector(plugin, 'rpyOffset'),
    )
    # upstream: an empty topicName advertises neither the topic nor the service
    name = plugin.text('topicName') if _has(plugin, 'topicName') else '/default_imu'
    imu.topic = topic(ns, name) if name else ''
    imu.service = topic(ns, plugin.text('serviceName', '/default_imu'))
    imu.frame_id = plugin.text('frameName', body)
    return imu


def build_p3d(
    model: str, plugin: PluginSpec, robot: Robot, ns: str, limits: Limits
) -> Optional[P3d]:
    """gazebo_ros_p3d. ``<xyzOffsets>``/``<rpyOffsets>`` (plural, a tutorial typo) are not its
    parameters: ignored, as upstream."""
    body = plugin.text('bodyName')
    found = _body(model, plugin, robot)
    if found is None:
        return None
    if not _has(plugin, 'topicName'):
        _not_loaded(model, plugin, 'missing <topicName>')
        return None
    frame_name = plugin.text('frameName', 'world')
    frame: Optional[Tuple[int, Frame]] = None
    if frame_name not in WORLD_FRAMES:
        frame = _link(robot, frame_name)
        if frame is None:
            _not_loaded(model, plugin, "frameName '%s' is not a link of the model" % frame_name)
            return None
    sensor = P3d(
        model,
        plugin.name,
        robot,
        *found,
        _plugin_rate(limits, plugin),
        None if frame is None else frame[0],
        None if frame is None else frame[1],
        _vector(plugin, 'xyzOffset'),
        _vector(plugin, 'rpyOffset'),
        plugin.number('gaussianNoise', 0.0),
    )
    sensor.topic = topic(ns, plugin.text('topicName'))
    sensor.frame_id = frame_name
    sensor.namespace = ns
    sensor.child_frame_id = body
    return sensor


def build_bumper(
    model: str, sensor: SensorSpec, plugin: PluginSpec, robot: Robot, ns: str, limits: Limits
) -> Optional[ContactSensor]:
    """gazebo_ros_bumper in a ``contact`` sensor."""
    if sensor.type != 'contact':
        _not_loaded(model, plugin, "its sensor is of type '%s', not contact" % sensor.type)
        return None
    index, _ = _sensor_frame(robot, sensor)
    collision = (sensor.element.findtext('contact/collision') or '').strip()
    if not collision:
        log.warning(
            "model '%s': %s has no <contact><collision>: it reports no contacts, as in Gazebo",
            model,
            sensor.where,
        )
    contact = ContactSensor(
        model,
        sensor.name,
        robot,
        index,
        '%s::%s::%s' % (model, _owner(robot, sensor.link), collision),
        _rate(limits, sensor.update_rate, sensor.where),
    )
    contact.enabled = bool(collision)
    contact.topic = topic(ns, plugin.text('bumperTopicName', 'bumper_states'))
    contact.frame_id = plugin.text('frameName', 'world')
    contact.namespace = ns
    return contact


def _owner(robot: Robot, link: str) -> str:
    """The link a (possibly lumped) link's sensors belong to in Gazebo's model."""
    lumped = robot.lumped_link(link)
    return link if lumped is None else str(lumped[0])


def build_ft_sensor(
    model: str, plugin: PluginSpec, robot: Robot, ns: str, limits: Limits
) -> Optional[ForceTorque]:
    """gazebo_ros_ft_sensor: the wrench in the joint's child link frame."""
    joint = plugin.text('jointName')
    if not _has(plugin, 'jointName'):
        _not_loaded(model, plugin, 'missing <jointName>')
        return None
    if joint not in robot.joint_index:
        _not_loaded(model, plugin, "jointName '%s' is not a joint of the model" % joint)
        return None
    if not _has(plugin, 'topicName'):
        _not_loaded(model, plugin, 'missing <topicName>')
        return None
    # upstream reads gaussianNoise from the plugin element itself
    sensor = ForceTorque(
        model,
        plugin.name,
        robot,
        robot.joint_index[joint],
        _plugin_rate(limits, plugin),
        plugin.number('gaussianNoise', 0.0),
    )
    sensor.topic = topic(ns, plugin.text('topicName'))
    sensor.frame_id = _child_link(robot, sensor.joint)
    sensor.namespace = ns
    return sensor


def _child_link(robot: Robot, joint: int) -> str:
    for name, index in robot.link_index.items():
        if index == joint:
            return name
    return ''
