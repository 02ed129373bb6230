"""The plugin registry: which Gazebo plugin file the stand-in builds, and how.

As gazebo_plugins loads one class by its file name (``libgazebo_ros_laser.so``), each
plugin here is one ``PluginType`` registered under its file name by the module that builds
it (``register``, at import; ``sim/plugins/__init__.py`` imports every module). A type says
how its plugin is built on spawn (a builder for a plugin inside a ``<sensor>``, or for a model
plugin of a ``<gazebo>`` block without reference, or ``built_by``: who builds it instead) and
which ROS publisher the ROS layer gives what it builds (``publisher``: ``module:factory`` in
``ros/plugins/``, named, not imported: this layer knows no ROS). A file name that is empty or
taken twice is refused when the module loads. Plugins in no type (nor gazebo_ros_control's)
are named in a warning at spawn.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass
from typing import Callable, Dict, List, Optional

from ...description.gazebo_plugins import (
    PluginSpec,
    SensorSpec,
    model_plugins,
    sensor_specs,
    unimplemented,
)
from ...description.limits import Limits
from ...description.urdf_model import RobotModel
from ...physics.robot import Robot
from ...physics.sim_sensor import SimSensor

log = logging.getLogger('_arm1sim.physics')

# (model, sensor, its plugin, robot, namespace for topics, limits) -> the sensor, or None when
# the plugin would not load in Gazebo either (it has said why, naming it)
SensorBuilder = Callable[[str, SensorSpec, PluginSpec, Robot, str, Limits], Optional[SimSensor]]
# (model, plugin, robot, namespace for topics, limits) -> the sensor, or None as above
ModelPluginBuilder = Callable[[str, PluginSpec, Robot, str, Limits], Optional[SimSensor]]


@dataclass(frozen=True)
class PluginType:
    """One plugin file the stand-in implements; exactly one of the three ways to build it."""

    filename: str
    build_sensor: Optional[SensorBuilder] = None  # a plugin inside a <sensor>
    build_model: Optional[ModelPluginBuilder] = None  # a model plugin
    built_by: str = ''  # neither: who builds it (for the docs and messages)
    publisher: str = ''  # 'module:factory' in ros/plugins/; '' when nothing is published


PLUGINS: Dict[str, PluginType] = {}


def register(*types: PluginType) -> None:
    """Add plugin types; a file name that is empty or already taken is refused."""
    for t in types:
        if not t.filename.strip():
            raise ValueError('a plugin type needs a file name: %r' % (t,))
        if t.filename in PLUGINS:
            raise ValueError('plugin %s is registered twice' % t.filename)
        ways = [t.build_sensor is not None, t.build_model is not None, bool(t.built_by)]
        if sum(ways) != 1:
            raise ValueError(
                'plugin %s: give one of build_sensor, build_model or built_by' % t.filename
            )
        PLUGINS[t.filename] = t


def build_sensors(
    model: str, description: RobotModel, robot: Robot, namespace: str, limits: Limits
) -> List[SimSensor]:
    """The physics sensors of a spawned model; warns once about each plugin not implemented.

    ``namespace`` is the spawn request's, used by plugins without ``<robotNamespace>``.
    Each sensor keeps its plugin's file name (``plugin_filename``), by which the ROS layer
    finds its publisher. Raises description.urdf_model.UrdfError (or LimitError) naming a
    sensor that cannot be built.
    """
    for line in unimplemented(description, model, PLUGINS):
        log.warning(line)
    out: List[SimSensor] = []
    for sensor in sensor_specs(description):
        for plugin in sensor.plugins:
            entry = PLUGINS.get(plugin.filename)
            if entry is not None and entry.build_sensor is not None:
                ns = plugin.namespace(namespace, model)
                _add(out, entry, entry.build_sensor(model, sensor, plugin, robot, ns, limits))
    for plugin in model_plugins(description):
        entry = PLUGINS.get(plugin.filename)
        if entry is not None and entry.build_model is not None:
            ns = plugin.namespace(namespace, model)
            _add(out, entry, entry.build_model(model, plugin, robot, ns, limits))
    return out


def _add(out: List[SimSensor], entry: PluginType, built: Optional[SimSensor]) -> None:
    if built is not None:
        built.plugin_filename = entry.filename
        out.append(built)
