"""The simulation, free of ROS: a world, its robots and their controller managers, and time.

One ``step`` is what Gazebo does per physics iteration with gazebo_ros_control
loaded: read the joints, update the controllers, write saturated efforts, step.
"""
import math
import os
import tempfile
from dataclasses import dataclass, field

from .physics.camera import SensorManager, camera_sensors
from .physics.urdf_model import UrdfError, parse_urdf, resolve_mesh_uris
from .physics.world import World
from .robot_hw_sim import DefaultRobotHWSim


class SpawnError(ValueError):
    pass


@dataclass
class Model:
    name: str
    description: object  # urdf_model.RobotModel
    robot: object  # physics Robot
    hw: object = None  # DefaultRobotHWSim, when the URDF has the gazebo_ros_control plugin
    controller_manager: object = None
    namespace: str = ''
    cameras: list = field(default_factory=list)  # physics.camera.Camera, one per camera sensor


class Simulation:
    def __init__(self, world_config, gui=False):
        self.config = world_config
        self.world = World(world_config, gui)
        self.step_ns = int(round(world_config.max_step_size * 1e9))
        self.period = self.step_ns * 1e-9
        self.steps = 0
        self.models = {}
        self._controlled = []  # models with a controller manager, in spawn order
        self._tmp = tempfile.TemporaryDirectory(prefix='arm1-sim-')
        self.sensors = SensorManager(world_config)

    @property
    def time_ns(self):
        return self.steps * self.step_ns

    def spawn_urdf(self, name, urdf_xml, position=(0, 0, 0), orientation=(0, 0, 0, 1),
                   robot_namespace='', find_package=None, controller_manager_factory=None):
        """Build a robot from URDF text; with the control plugin, give it a controller manager.

        ``find_package(name)`` resolves ``package://`` URIs; ``controller_manager_factory(hw,
        namespace)`` makes the manager. Raises SpawnError with a message naming the culprit.
        """
        if name in self.models:
            raise SpawnError("model name '%s' already exists" % name)
        try:
            description = parse_urdf(urdf_xml)
            resolved = resolve_mesh_uris(urdf_xml, find_package or _no_packages)
            sensors = camera_sensors(description)
        except UrdfError as exc:
            raise SpawnError("cannot spawn '%s': %s" % (name, exc))
        path = os.path.join(self._tmp.name, '%s.urdf' % name)
        with open(path, 'w') as f:
            f.write(resolved)
        load_args = (path, tuple(position), tuple(orientation), description.root_link == 'world')
        robot = self.world.load_robot(*load_args)
        model = Model(name, description, robot)
        plugin = description.control_plugin
        if plugin is not None:
            model.namespace = '/' + (plugin.robot_namespace or robot_namespace or name).strip('/')
            try:
                model.hw = DefaultRobotHWSim(description, robot)
            except UrdfError as exc:
                self.world.remove_robot(robot)
                raise SpawnError("cannot spawn '%s': %s" % (name, exc))
            if controller_manager_factory is not None:
                model.controller_manager = controller_manager_factory(model.hw, model.namespace)
                self._controlled.append(model)
        model.cameras = self.sensors.add_robot(name, load_args, sensors)
        self.models[name] = model
        return model

    def delete_model(self, name):
        model = self.models.pop(name, None)
        if model is None:
            raise SpawnError("model '%s' does not exist" % name)
        if model in self._controlled:
            self._controlled.remove(model)
        self.world.remove_robot(model.robot)
        self.sensors.remove_robot(name)
        return model

    def set_model_configuration(self, name, joint_names, positions):
        model = self.models.get(name)
        if model is None:
            raise SpawnError("model '%s' does not exist" % name)
        unknown = [j for j in joint_names if j not in model.robot.joint_index]
        if unknown:
            raise SpawnError("model '%s' has no joint(s) %s" % (name, ', '.join(unknown)))
        bad = [j for j, v in zip(joint_names, positions) if not math.isfinite(v)]
        if bad:
            raise SpawnError('non-finite position for joint(s) %s' % ', '.join(bad))
        model.robot.set_joint_positions(dict(zip(joint_names, positions)))

    def step(self):
        """One physics iteration: read, update controllers, write, step."""
        now, period = self.time_ns, self.period
        for model in self._controlled:
            model.hw.read()
            model.controller_manager.update(now, period)
            model.hw.write()
        self.world.step()
        self.steps += 1
        if self.sensors.cameras:
            self.sensors.update(self.time_ns, self._robot_states)

    def _robot_states(self):
        return {name: model.robot.state() for name, model in self.models.items()}

    def reset_world(self):
        """Robots back to their spawn poses, joints to zero; time goes on."""
        self.world.reset()

    def reset_simulation(self):
        """As reset_world, and time back to zero."""
        self.world.reset()
        self.steps = 0

    def close(self):
        self.sensors.close()
        self.world.close()
        self._tmp.cleanup()


def _no_packages(name):
    raise LookupError(name)
