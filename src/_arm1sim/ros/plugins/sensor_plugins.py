"""The ROS side of a model's plugins: the publisher each registered plugin names.

sim/plugins' registry keys each plugin by its file name and names its publisher
(``module:factory`` in this room); what it built (a camera of physics.sensor_manager, a
physics.sim_sensor.SimSensor) carries the file name, and gets that factory's plugin here.
"""

from __future__ import annotations

import importlib
import logging
from typing import Any, Callable, Optional

from ...sim.plugins import PLUGINS
from ...sim.simulation import Model, Plugin

log = logging.getLogger('rosout')

PluginFactory = Callable[[Any], Plugin]


def publisher(filename: str) -> Optional[PluginFactory]:
    """The factory of the ROS publisher registered for a plugin file; None for none."""
    entry = PLUGINS.get(filename)
    if entry is None or not entry.publisher:
        return None
    module, _, factory = entry.publisher.partition(':')
    found: PluginFactory = getattr(importlib.import_module('.' + module, __package__), factory)
    return found


def attach_sensor_plugins(model: Model) -> None:
    """Give each of the model's cameras and physics sensors its ROS publisher (in
    ``model.plugins``, so that delete_model releases it)."""
    for camera in model.cameras:
        model.plugins.append(_factory(camera.sensor.plugin_filename)(camera))
    for sensor in model.sensors:
        factory = publisher(sensor.plugin_filename)
        if factory is None:
            log.warning(
                "model '%s': %s '%s' has no ROS publisher in the stand-in",
                model.name,
                sensor.kind,
                sensor.name,
            )
            continue
        model.plugins.append(factory(sensor))


def _factory(filename: str) -> PluginFactory:
    factory = publisher(filename)
    if factory is None:  # every camera plugin is registered with its publisher
        raise LookupError('no ROS publisher registered for %s' % filename)
    return factory
