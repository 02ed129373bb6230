"""The ``<sensor>`` and ``<plugin>`` elements of a URDF's ``<gazebo>`` blocks, as plain records.

ROS-free and pybullet-free. Each plugin implementation (sim/plugins/) reads
its own parameters from a ``SensorSpec`` or ``PluginSpec`` with the helpers here,
so that every plugin spells defaults, numbers and poses the same way.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, field
from typing import Any, Iterable, List, Optional, Set

from ..vendors import robot_sim_types
from .names import legal_ros_name, shown
from .sdf_values import ZERO_POSE, Pose, flag, number, pose
from .urdf_model import CONTROL_PLUGIN, RobotModel, UrdfError

log = logging.getLogger('_arm1sim.physics')


DEFAULT_ROBOT_SIM_TYPE = 'gazebo_ros_control/DefaultRobotHWSim'
# The plugin implemented outside sim/plugins' registry (whose file names count as handled
# too): the rest are named in a warning at spawn.
HANDLED_PLUGINS: Set[str] = {CONTROL_PLUGIN}


@dataclass
class PluginSpec:
    """One ``<plugin name filename>``: its parameters are its child elements."""

    name: str
    filename: str
    element: Any  # the <plugin> Element
    where: str  # for messages: "plugin 'x' (libx.so) of sensor 'y' on link 'z'"

    def text(self, tag: str, default: str = '') -> str:
        value = self.element.findtext(tag)
        return value.strip() if value is not None and value.strip() else default

    def number(self, tag: str, default: float) -> float:
        return number(self.element, tag, default, self.where)

    def flag(self, tag: str, default: bool) -> bool:
        return flag(self.element, tag, default, self.where)

    def namespace(self, request: str, model: str) -> str:
        """The plugin's ``<robotNamespace>``, else the spawn request's, which Gazebo's spawn
        writes into plugins without one; an empty element means the model's name
        (gazebo_plugins' GetRobotNamespace)."""
        own = self.element.findtext('robotNamespace')
        if own is None:
            return request
        return own.strip() or model


@dataclass
class SensorSpec:
    """One ``<sensor type name>`` in ``<gazebo reference="link">``, with its plugins."""

    name: str
    type: str
    link: str
    element: Any  # the <sensor> Element
    pose: Pose = ZERO_POSE  # of the sensor in its link's frame
    update_rate: float = 0.0  # Hz in sim time; 0: every physics step
    always_on: bool = False
    plugins: List[PluginSpec] = field(default_factory=list)

    @property
    def where(self) -> str:
        return "sensor '%s' on link '%s'" % (self.name, self.link)

    def plugin(self, *filenames: str) -> Optional[PluginSpec]:
        return next((p for p in self.plugins if p.filename in filenames), None)

    def number(self, path: str, default: float) -> float:
        return number(self.element, path, default, self.where)


def topic(namespace: str, name: str) -> str:
    """``/<namespace>/<name>`` as gazebo_plugins advertise it (a name starting with '/' is
    absolute)."""
    if name.startswith('/'):
        out = name
    else:
        parts = [s.strip('/') for s in (namespace, name)]
        out = '/' + '/'.join(s for s in parts if s)
    # rospy would take it, log FATAL and publish nothing while the spawn said success
    if not legal_ros_name(out):
        raise UrdfError('topic %s is not a legal ROS name' % shown(out))
    return out


def _plugins(elements: Iterable[Any], where: str) -> List[PluginSpec]:
    out = []
    for p in elements:
        name, filename = p.get('name', ''), p.get('filename', '')
        out.append(
            PluginSpec(name, filename, p, "plugin '%s' (%s) of %s" % (name, filename, where))
        )
    return out


def sensor_specs(description: RobotModel) -> List[SensorSpec]:
    """Every ``<sensor>`` of the description, in document order."""
    out = []
    for link, element in description.sensors:
        name = element.get('name', '')
        spec = SensorSpec(name, element.get('type', ''), link, element)
        where = spec.where
        if link not in description.links:
            raise UrdfError('%s: the link is not in the URDF' % where)
        spec.pose = pose(element, 'pose', where)
        spec.update_rate = number(element, 'update_rate', 0.0, where)
        if spec.update_rate < 0:
            raise UrdfError('%s <update_rate>: %g Hz is negative' % (where, spec.update_rate))
        spec.always_on = flag(element, 'always_on', False, where)
        spec.plugins = _plugins(element.findall('plugin'), where)
        out.append(spec)
    return out


def model_plugins(description: RobotModel) -> List[PluginSpec]:
    """The ``<plugin>``s of ``<gazebo>`` blocks without a reference (model plugins)."""
    return _plugins(description.model_plugins, 'the model')


def unimplemented(description: RobotModel, model: str, handled: Iterable[str] = ()) -> List[str]:
    """One line per plugin the stand-in does not implement, for the warning at spawn."""
    known = HANDLED_PLUGINS.union(handled)
    lines = []
    for spec in model_plugins(description):
        if spec.filename not in known:
            lines.append("model '%s': %s is not implemented by the stand-in" % (model, spec.where))
    for sensor in sensor_specs(description):
        for plugin in sensor.plugins:
            if plugin.filename not in known:
                lines.append(
                    "model '%s': %s is not implemented by the stand-in" % (model, plugin.where)
                )
        if not sensor.plugins:
            lines.append(
                "model '%s': %s (type %s) has no plugin: nothing publishes it, as in Gazebo"
                % (model, sensor.where, sensor.type)
            )
    for link, element in description.unplaced_sensors:
        lines.append(
            "model '%s': sensor '%s' names link '%s', which is not in the URDF: left out, as "
            'Gazebo leaves it out' % (model, element.get('name', ''), link)
        )
    control = description.control_plugin
    sim_types = (DEFAULT_ROBOT_SIM_TYPE, *robot_sim_types())
    if control is not None and control.robot_sim_type not in sim_types:
        # Gazebo loads the named RobotHWSim class; the stand-in has the default and those of
        # the vendor rooms' manifests (sim/robot_hw_sims.py), and says so rather than swap
        # the default in silently.
        lines.append(
            "model '%s': robotSimType %s of gazebo_ros_control is not implemented by the "
            "stand-in: %s's joint interfaces are offered instead"
            % (model, control.robot_sim_type, DEFAULT_ROBOT_SIM_TYPE)
        )
    return lines
