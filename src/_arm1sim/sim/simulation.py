"""The simulation, free of ROS: a world, its robots and their controller managers, and time.

One ``step`` is what Gazebo does per physics iteration with gazebo_ros_control
loaded: read the joints, update the controllers, write saturated efforts, step.
"""

from __future__ import annotations

import itertools
import math
import os
import tempfile
from dataclasses import dataclass, field, replace
from typing import Any, Callable, Dict, List, Optional, Protocol, Sequence, Tuple

from ..control.controller_manager import ControllerManager
from ..control.interfaces import RobotHWSim, RobotHWSimError
from ..control.loop import ControlLoop, control_period_ns
from ..description.camera_sensor import CameraSensor, camera_sensors
from ..description.compact_urdf import compact_urdf
from ..description.gazebo_tags import BodyOptions, prepare_body
from ..description.limits import LimitError
from ..description.names import IllegalName, check_name, shown
from ..description.pose_math import normalized
from ..description.sdf_world import WorldConfig
from ..description.urdf_model import (
    RobotModel,
    UrdfError,
    parse_description,
    parse_urdf,
    resolve_mesh_uris,
)
from ..physics.concave_meshes import concave_collisions
from ..physics.contact import set_collision_namer
from ..physics.laser import ray_casts_per_second
from ..physics.robot import Robot, RobotLoadError
from ..physics.sensor_manager import Camera, SensorManager
from ..physics.sim_sensor import SimSensor
from ..physics.visual_stand_ins import light_visuals
from ..physics.world import World
from .plugins import build_sensors
from .plugins.mimic import mimic_links
from .robot_hw_sims import make_robot_hw_sim


class SpawnError(ValueError):
    pass


class Plugin(Protocol):
    """What a model's plugin leaves in the ROS layer (services, topics, servers): gone on delete."""

    def shutdown(self) -> None: ...


@dataclass
class Model:
    """Everything one spawned model brought, so that deleting it is one call."""

    name: str
    description: RobotModel
    robot: Robot
    hw: Optional[RobotHWSim] = None  # when the URDF has the gazebo_ros_control plugin
    controller_manager: Optional[ControllerManager] = None
    control: Optional[ControlLoop] = None  # when its controllers update; with the manager
    namespace: str = ''
    cameras: List[Camera] = field(default_factory=list)  # one per camera sensor
    sensors: List[SimSensor] = field(default_factory=list)  # measured on the physics thread
    plugins: List[Plugin] = field(default_factory=list)  # the ROS layer's part, shut down on delete
    file: str = ''  # the URDF file the render processes load (and pybullet), in the world's folder
    physics_file: str = ''  # the one pybullet loads when it differs (visual stand-ins)
    # stand-in visual mesh file -> the file the URDF names (physics.visual_stand_ins)
    visual_stand_ins: Dict[str, str] = field(default_factory=dict)


@dataclass
class PreparedUrdf:
    """A spawn request checked and parsed, not yet in the world."""

    name: str
    description: RobotModel
    sensors: List[CameraSensor]
    # World.load_robot's: file, position, orientation, fixed base, BodyOptions (the render
    # processes load this file)
    load_args: Tuple[str, Tuple[float, ...], Tuple[float, ...], bool, BodyOptions]
    physics_file: str = ''  # what pybullet loads instead, when visuals were stood in for
    visual_stand_ins: Dict[str, str] = field(default_factory=dict)


ControllerManagerFactory = Callable[[RobotHWSim, str], ControllerManager]


class Simulation:
    def __init__(self, world_config: WorldConfig, gui: bool = False) -> None:
        self.config = world_config
        self.limits = world_config.limits
        self.world = World(world_config, gui)
        self.step_ns = int(round(world_config.max_step_size * 1e9))
        self.period = self.step_ns * 1e-9
        self.steps = 0
        self.models: Dict[str, Model] = {}
        self._controlled: List[Model] = []  # models with a controller manager, in spawn order
        self._sensors: List[SimSensor] = []  # every model's physics sensors, in spawn order
        self._tmp = tempfile.TemporaryDirectory(prefix='arm1-sim-')
        self._files = itertools.count(1)  # the world names its files itself, never from requests
        self.sensors = SensorManager(world_config)
        # Called with the sim time before each physics step (wrenches, model_states).
        self.before_step: List[Callable[[int], None]] = []
        set_collision_namer(self.world.client, self.collision_name)

    def collision_name(self, body: int, link: int) -> str:
        """Gazebo's scoped name of a pybullet body's link collision, for contact sensors."""
        for model in self.models.values():
            if model.robot.body == body:
                for name, index in model.robot.link_index.items():
                    if index == link:
                        return '%s::%s::%s_collision' % (model.name, name, name)
        for static, bodies in zip(self.config.models, getattr(self.world, 'scenery', [])):
            if body in bodies:
                return '%s::link::collision' % static.name
        return 'body%d::link%d' % (body, link)

    @property
    def time_ns(self) -> int:
        return self.steps * self.step_ns

    @property
    def folder(self) -> str:
        """The only folder the world writes to."""
        return self._tmp.name

    def spawn_urdf(
        self,
        name: str,
        urdf_xml: str,
        position: Sequence[float] = (0, 0, 0),
        orientation: Sequence[float] = (0, 0, 0, 1),
        robot_namespace: str = '',
        find_package: Optional[Callable[[str], str]] = None,
        controller_manager_factory: Optional[ControllerManagerFactory] = None,
        attach: Optional[Callable[[Model], None]] = None,
    ) -> Model:
        """Build a robot from URDF text; with the control plugin, give it a controller manager.

        ``find_package(name)`` resolves ``package://`` URIs; ``controller_manager_factory(hw,
        namespace)`` makes the manager; ``attach(model)`` lets the ROS layer add its plugins
        (it may set ``controller_manager`` itself). Raises SpawnError with a message naming
        the culprit; a failed spawn leaves nothing behind.
        """
        prepared = self.prepare_urdf(name, urdf_xml, position, orientation, find_package)
        return self.spawn_prepared(prepared, robot_namespace, controller_manager_factory, attach)

    def prepare_urdf(
        self,
        name: str,
        urdf_xml: str,
        position: Sequence[float] = (0, 0, 0),
        orientation: Sequence[float] = (0, 0, 0, 1),
        find_package: Optional[Callable[[str], str]] = None,
    ) -> PreparedUrdf:
        """Everything of a spawn that reads only the request: parsing, limits, meshes.

        Touches no simulation state, so the ROS layer runs it on the caller's thread and a
        large or hostile document costs that caller, not the physics loop.
        """
        limits = self.limits
        try:
            check_name(name, 'model', limits.name_length)
        except IllegalName as exc:
            raise SpawnError('cannot spawn: %s' % exc)
        if not _finite_pose(position, orientation):
            raise SpawnError("cannot spawn '%s': the initial pose is not 7 finite numbers" % name)
        try:
            root = parse_description(urdf_xml, limits)  # the request's one parse
            description = parse_urdf(root, limits)
            # pybullet parses what it is handed in one call on the physics thread: only the
            # links, joints and materials it reads (comments, <gazebo> and the rest stay here)
            compact = compact_urdf(root)
            resolved = resolve_mesh_uris(compact, find_package or _no_packages, limits)
            # concave collision meshes as their triangles, as ODE's trimeshes (not their hull)
            resolved = concave_collisions(resolved, limits=limits)
            # As Gazebo's URDF->SDF: fixed joints lumped, frames weightless, <gazebo> tags
            resolved, options = prepare_body(resolved, description, name)
            sensors = camera_sensors(description, limits)
        except (UrdfError, LimitError) as exc:
            raise SpawnError("cannot spawn '%s': %s" % (name, exc))
        path = os.path.join(self._tmp.name, 'model-%d.urdf' % next(self._files))
        with open(path, 'w') as f:
            f.write(resolved)
        # A window shows what pybullet loads: with one, every visual is its own.
        light, stand_ins = (
            (resolved, {}) if self.world.gui else light_visuals(resolved, self._tmp.name)
        )
        physics_file = ''
        if stand_ins:
            physics_file = path[: -len('.urdf')] + '-physics.urdf'
            with open(physics_file, 'w') as f:
                f.write(light)
        return PreparedUrdf(
            name,
            description,
            sensors,
            # normalised here: pybullet's own normalisation overflows on 1e200 components
            (
                path,
                tuple(position),
                normalized(orientation),
                description.root_link == 'world',
                options,
            ),
            physics_file,
            stand_ins,
        )

    def spawn_prepared(
        self,
        prepared: PreparedUrdf,
        robot_namespace: str = '',
        controller_manager_factory: Optional[ControllerManagerFactory] = None,
        attach: Optional[Callable[[Model], None]] = None,
    ) -> Model:
        """The part of a spawn that changes the world (see ``spawn_urdf``). Sim thread only."""
        name = prepared.name
        try:
            if name in self.models:
                raise SpawnError("model name '%s' already exists" % name)
            try:
                self.limits.check('models', len(self.models) + 1, 'the world')
            except LimitError as exc:
                raise SpawnError("cannot spawn '%s': %s" % (name, exc))
            try:
                robot = self.world.load_robot(
                    prepared.physics_file or prepared.load_args[0], *prepared.load_args[1:]
                )
            except RobotLoadError as exc:
                raise SpawnError("cannot spawn '%s': %s" % (name, exc))
        except SpawnError:
            _remove_files(prepared.load_args[0], prepared.physics_file, *prepared.visual_stand_ins)
            raise
        model = Model(
            name,
            prepared.description,
            robot,
            file=prepared.load_args[0],
            physics_file=prepared.physics_file,
            visual_stand_ins=prepared.visual_stand_ins,
        )
        robot.set_mimics(mimic_links(prepared.description))
        try:
            self._attach_plugins(model, robot_namespace, controller_manager_factory)
            # As Gazebo's spawn: a sensor plugin without <robotNamespace> gets the request's.
            sensors = [
                replace(c, robot_namespace=c.robot_namespace or robot_namespace)
                for c in prepared.sensors
            ]
            model.cameras = self.sensors.add_robot(name, prepared.load_args, sensors)
            model.sensors = build_sensors(
                name, model.description, robot, robot_namespace, self.limits
            )
            # All lasers together, as cameras are: each is cast on this (the physics) thread.
            rays = ray_casts_per_second(model.sensors, self.limits.sensor_update_rate)
            if rays:
                others = ray_casts_per_second(self._sensors, self.limits.sensor_update_rate)
                self.limits.check(
                    'ray_casts_per_second',
                    rays + others,
                    "model '%s''s ray sensors with the world's others" % name,
                )
            self._sensors.extend(model.sensors)
            if attach is not None:
                attach(model)
            plugin, manager = model.description.control_plugin, model.controller_manager
            if plugin and model.hw and manager and model not in self._controlled:
                model.control = ControlLoop(
                    model.hw, manager, control_period_ns(plugin.control_period, self.step_ns, name)
                )
                self._controlled.append(model)
        except (UrdfError, LimitError, SpawnError) as exc:
            self._release(model)
            raise SpawnError("cannot spawn '%s': %s" % (name, exc))
        except BaseException:
            self._release(model)
            raise
        self.models[name] = model
        return model

    def _attach_plugins(
        self, model: Model, robot_namespace: str, factory: Optional[ControllerManagerFactory]
    ) -> None:
        plugin = model.description.control_plugin
        if plugin is None:
            return
        # As gazebo_ros_control after Gazebo's spawn: the plugin's own <robotNamespace> (even
        # empty), else the request's (written into plugins without one), else the model name.
        ns = plugin.robot_namespace
        if ns is None:
            ns = robot_namespace or model.name
        model.namespace = '/' + ns.strip('/')
        # As gazebo_ros_control's pluginlib lookup of <robotSimType> (sim/robot_hw_sims.py)
        try:
            model.hw = make_robot_hw_sim(
                plugin.robot_sim_type, model.description, model.robot, self.period
            )
        except RobotHWSimError as exc:
            raise SpawnError('%s: %s' % (plugin.robot_sim_type, exc))
        if factory is not None:
            model.controller_manager = factory(model.hw, model.namespace)

    def _release(self, model: Model) -> None:
        """Undo what a (partly) spawned model set up, in the physics and the ROS layer."""
        if model in self._controlled:
            self._controlled.remove(model)
        if model.controller_manager is not None:
            model.controller_manager.shutdown()
        for plugin in reversed(model.plugins):
            plugin.shutdown()
        model.plugins = []
        for sensor in model.sensors:
            sensor.close()
            if sensor in self._sensors:
                self._sensors.remove(sensor)
        model.sensors = []
        self.sensors.remove_robot(model.name)
        if model.robot in self.world.robots:
            self.world.remove_robot(model.robot)
        _remove_files(model.file, model.physics_file, *model.visual_stand_ins)

    def delete_model(self, name: str) -> Model:
        model = self.models.pop(name, None)
        if model is None:
            raise SpawnError("model '%s' does not exist" % name)
        self._release(model)
        return model

    def set_model_configuration(
        self, name: str, joint_names: Sequence[str], positions: Sequence[float]
    ) -> None:
        model = self.models.get(name)
        if model is None:
            raise SpawnError("model '%s' does not exist" % name)
        if len(joint_names) != len(positions):
            raise SpawnError(
                'joint_names lists %d joint(s) but joint_positions has %d value(s)'
                % (len(joint_names), len(positions))
            )
        unknown = [j for j in joint_names if j not in model.robot.joint_index]
        if unknown:
            raise SpawnError(
                "model '%s' has no joint(s) %s" % (name, ', '.join(shown(j) for j in unknown[:10]))
            )
        bad = [j for j, v in zip(joint_names, positions) if not math.isfinite(v)]
        if bad:
            raise SpawnError('non-finite position for joint(s) %s' % ', '.join(bad))
        model.robot.set_joint_positions(dict(zip(joint_names, positions)))

    def step(self) -> None:
        """One physics iteration: read and update controllers (each model at its control
        period), write, step."""
        now = self.steps * self.step_ns  # time_ns, without the property's call
        for model in self._controlled:
            if model.control is not None:
                model.control.update(now)
        for hook in self.before_step:
            hook(now)
        self.world.step()
        self.steps += 1
        now += self.step_ns
        for sensor in self._sensors:
            sensor.update(now)
        if self.sensors.cameras:
            self.sensors.update(now, self._robot_states)

    def _robot_states(self) -> Dict[str, Any]:
        return {name: model.robot.state() for name, model in self.models.items()}

    def reset_world(self) -> None:
        """Robots back to their spawn poses, joints to zero; time goes on."""
        self.world.reset()
        self._reset_plugins()

    def reset_simulation(self) -> None:
        """As reset_world, and time back to zero."""
        self.world.reset()
        self.steps = 0
        self._reset_plugins()

    def _reset_plugins(self) -> None:
        """As Gazebo's World::Reset: every model plugin's Reset()."""
        for sensor in self._sensors:
            sensor.reset()

    def close(self) -> None:
        self.sensors.close()
        self.world.close()
        self._tmp.cleanup()


def _remove_files(*paths: str) -> None:
    for path in paths:
        if path and os.path.exists(path):
            os.unlink(path)


def _no_packages(name: str) -> str:
    raise LookupError(name)


def _finite_pose(position: Sequence[float], orientation: Sequence[float]) -> bool:
    values = list(position) + list(orientation)
    return len(values) == 7 and all(math.isfinite(v) for v in values)
