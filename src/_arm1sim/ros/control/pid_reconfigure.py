"""Live PID gains: a dynamic_reconfigure server at ``<controller>/pid``, as control_toolbox's
Pid::initDynamicReconfig offers it in Gazebo.

``rosrun dynamic_reconfigure dynparam set /arm1/joint1_position_controller/pid p 2.0`` (or
rqt_reconfigure) calls the controller's ``set_gains``; the gains apply at its next
update, show in ``<controller>/state`` and are written back to the parameter server
under ``<controller>/pid/``. The server starts from the controller's own gains (its
``pid/*`` parameters), not from the cfg's defaults, as control_toolbox does.
"""

import importlib
import logging

from dynamic_reconfigure.server import Server

log = logging.getLogger('_arm1sim.ros')

# node-handle type name -> module generated from cfg/*.cfg
CONFIG_MODULES = {'control_toolbox/Parameters': 'control_toolbox.cfg.ParametersConfig'}


def config_type(type_name):
    return importlib.import_module(CONFIG_MODULES[type_name])


class ConfigServer:
    """A dynamic_reconfigure server whose values are ``current`` at start and then whatever
    ``on_change(values)`` accepts (it returns the values in force)."""

    def __init__(self, namespace, type_name, current, on_change):
        self.namespace = namespace
        self._keys = list(current)
        self._current = dict(current)
        self._on_change = on_change
        self._started = False
        self.server = Server(config_type(type_name), self._callback, namespace=namespace)

    def _callback(self, config, level):
        if not self._started:
            # First call, from the Server's constructor: show the controller's gains.
            self._started = True
            values = self._current
        else:
            values = self._on_change({k: config[k] for k in self._keys})
        for key in self._keys:
            config[key] = values[key]
        return config

    def unregister(self):
        """Withdraw the service and topics (the controller was unloaded)."""
        s = self.server
        for handle in (s.set_service, s.descr_topic, s.update_topic):
            try:
                handle.shutdown() if hasattr(handle, 'shutdown') else handle.unregister()
            except Exception as exc:  # a handle already gone with the node
                log.debug('%s: %s', self.namespace, exc)


def serve_config(namespace, type_name, current, on_change):
    """A ConfigServer, or None (with an error logged) if the config type is not built."""
    try:
        return ConfigServer(namespace, type_name, current, on_change)
    except ImportError as exc:
        log.error(
            '%s: no dynamic_reconfigure for %s (%s); run `make setup` to generate it',
            namespace,
            type_name,
            exc,
        )
        return None
