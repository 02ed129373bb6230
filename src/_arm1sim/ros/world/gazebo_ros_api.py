"""gazebo_ros's ``/gazebo/*`` services around a Simulation (upstream: gazebo_ros_api_plugin).

Handlers run on rospy's threads. A request is checked and parsed there; whatever
changes the world is handed to the physics thread (SimThreadCalls).
"""

from __future__ import annotations

import os
from typing import Any, Callable, List, Optional, Sequence, Tuple

import rosgraph.names
import rospy
from gazebo_msgs.srv import DeleteModel, SetModelConfiguration
from std_srvs.srv import Empty

from ...control.interfaces import RobotHWSimError
from ...description.names import shown
from ...description.resource_paths import ResourcePaths, gazebo_paths
from ...description.sdf_model import SdfModelError, model_dir_finder
from ...description.sdf_to_urdf import ModelSpawn, sdf_spawn
from ...sim.model_state import WORLD_NAMES, State, compose, frame_state
from ...sim.plugins.mimic import attach_mimic_pids
from ...sim.simulation import Model, PreparedUrdf, Simulation, SpawnError
from ..common.packages import find_package, gazebo_exports
from ..control.controller_manager_services import ControllerManagerServices
from ..control.node_handle import RosNodeHandle
from ..plugins.sensor_plugins import attach_sensor_plugins
from .sim_thread import SimThreadCalls
from .spawn_request import PiecewiseSpawnModel
from .world_loop import WorldLoop


class GazeboRosApi:
    def __init__(self, sim: Simulation, calls: SimThreadCalls, loop: WorldLoop) -> None:
        self.sim, self.calls, self.loop = sim, calls, loop
        self._paths: Optional[ResourcePaths] = None  # model:// of SDF spawns, found once
        self._services = [
            rospy.Service('~pause_physics', Empty, self._empty(self._set_paused, True)),
            rospy.Service('~unpause_physics', Empty, self._empty(self._set_paused, False)),
            rospy.Service('~reset_simulation', Empty, self._empty(self.sim.reset_simulation)),
            rospy.Service('~reset_world', Empty, self._empty(self.sim.reset_world)),
            # requests of up to description_bytes, decoded without stopping physics
            rospy.Service('~spawn_urdf_model', PiecewiseSpawnModel, self._spawn),
            rospy.Service('~spawn_sdf_model', PiecewiseSpawnModel, self._spawn_sdf),
            rospy.Service('~delete_model', DeleteModel, self._delete),
            rospy.Service('~set_model_configuration', SetModelConfiguration, self._configure),
        ]

    def _empty(self, fn: Callable[..., Any], *args: Any) -> Callable[[Any], List[Any]]:
        def handler(req: Any) -> List[Any]:
            self.calls.call(fn, *args)
            return []

        return handler

    def _set_paused(self, paused: bool) -> None:
        self.loop.paused = paused

    def _spawn_sdf(self, req: Any) -> Tuple[bool, str]:
        return self._spawn(req, sdf=True)

    def _spawn(self, req: Any, sdf: bool = False) -> Tuple[bool, str]:
        pose = req.initial_pose
        xyz: Sequence[float] = (pose.position.x, pose.position.y, pose.position.z)
        q: Sequence[float] = (
            pose.orientation.x,
            pose.orientation.y,
            pose.orientation.z,
            pose.orientation.w,
        )
        if tuple(q) == (0, 0, 0, 0):
            q = (0, 0, 0, 1)
        xml, dropped = req.model_xml, []
        try:
            xyz, q = self._in_reference_frame(req.reference_frame, xyz, q)
            if sdf:  # an SDF <model> takes the URDF path as sdf_model's URDF; a <robot> as is
                spawn = self._sdf_spawn(req.model_name, xml, xyz, q)
                if spawn is not None:
                    xml, xyz, q, dropped = (
                        spawn.urdf,
                        spawn.position,
                        spawn.orientation,
                        spawn.warnings,
                    )
            model = self.spawn(req.model_name, xml, xyz, q, req.robot_namespace)
        except SpawnError as exc:
            rospy.logerr(str(exc))
            return False, str(exc)
        msg = "SpawnModel: Successfully spawned entity '%s'" % model.name
        if dropped:
            msg += '; not built: %s' % '; '.join(dropped)
        if model.controller_manager is not None:
            msg += ' with controller manager in %s' % model.namespace
        for c in model.cameras:
            msg += '; camera %s on %s' % (c.sensor.name, c.sensor.image_topic)
        # The caller logs it (spawn_model: "Spawn status: ..."), as upstream's world does not;
        # what was not built is the world's to warn about.
        (rospy.logwarn if dropped else rospy.logdebug)(msg)
        return True, msg

    def _in_reference_frame(
        self, reference: str, xyz: Sequence[float], quat: Sequence[float]
    ) -> Tuple[Sequence[float], Sequence[float]]:
        """The initial pose in the world: as upstream, given in the entity ``reference_frame``
        names (a model or a link), the world for '', world or map; any other name refused."""
        if reference in WORLD_NAMES:
            return xyz, quat
        try:
            frame = self.calls.call(frame_state, self.sim, reference)
        except KeyError:
            frame = None
        if frame is None:  # upstream's message, with the name it could not find
            raise SpawnError(
                'SpawnModel: reference reference_frame [%s] not found, did you forget to scope '
                'the link by model name?' % shown(reference)[1:-1]
            )
        world = compose(frame, State(tuple(xyz), tuple(quat)))  # type: ignore[arg-type]
        return world.position, world.orientation

    def spawn(
        self, name: str, xml: str, xyz: Sequence[float], quat: Sequence[float], namespace: str = ''
    ) -> Model:
        """Spawn a URDF model with its plugins (controller manager, cameras).

        The request is parsed and checked on the calling thread; only what changes the
        world runs on the physics thread, so a large document does not hold physics back.
        """
        if namespace and not rosgraph.names.is_legal_name(namespace):
            raise SpawnError(
                "cannot spawn '%s': robot_namespace %s is not a legal ROS name"
                % (name, shown(namespace))
            )
        prepared = self.sim.prepare_urdf(name, xml, xyz, quat, find_package)
        return self.calls.call(self._spawn_prepared, prepared, namespace)

    def _sdf_spawn(
        self, name: str, xml: str, xyz: Sequence[float], quat: Sequence[float]
    ) -> Optional[ModelSpawn]:
        """The SDF request as URDF (None for a URDF); SpawnError naming the culprit."""
        if self._paths is None:
            self._paths = gazebo_paths(os.environ, gazebo_exports())
        paths = self._paths
        try:
            return sdf_spawn(
                xml,
                name,
                xyz,
                quat,
                self.sim.limits,
                model_dir_finder(paths.model),
                paths.find_model,
            )
        except SdfModelError as exc:
            raise SpawnError("cannot spawn '%s': %s" % (name, exc)) from None

    def _spawn_prepared(self, prepared: PreparedUrdf, namespace: str) -> Model:
        return self.sim.spawn_prepared(prepared, namespace, attach=self._attach_plugins)

    def _attach_plugins(self, model: Model) -> None:
        """The ROS side of a model's plugins; each goes into the model's record."""
        # roboticsgroup's <hasPID> reads its gains at Load, as gazebo_ros_control does
        attach_mimic_pids(
            model.description, model.robot, lambda ns: RosNodeHandle(ns).params, self.sim.period
        )
        if model.hw is not None:
            if not rosgraph.names.is_legal_name(model.namespace):
                raise SpawnError(
                    'controller manager namespace %s is not a legal ROS name'
                    % shown(model.namespace)
                )
            # initSim: the hardware sim reads what it needs (joint limits, PIDs, a vendor's
            # own) from the robot namespace's parameters, through its node handle.
            nh = RosNodeHandle(model.namespace)
            model.plugins.append(nh)
            try:
                model.hw.init_sim(nh, model.namespace)
            except RobotHWSimError as exc:
                control = model.description.control_plugin
                sim_type = control.robot_sim_type if control is not None else ''
                raise SpawnError('%s: %s' % (sim_type, exc))
            services = ControllerManagerServices(model.hw, model.namespace)
            model.controller_manager = services.manager
            model.plugins.append(services)
        attach_sensor_plugins(model)

    def _delete(self, req: Any) -> Tuple[bool, str]:
        try:
            self.calls.call(self.sim.delete_model, req.model_name)
        except SpawnError as exc:
            return False, str(exc)
        return True, "DeleteModel: successfully deleted model '%s'" % req.model_name

    def _configure(self, req: Any) -> Tuple[bool, str]:
        try:
            self.calls.call(
                self.sim.set_model_configuration,
                req.model_name,
                list(req.joint_names),
                list(req.joint_positions),
            )
        except SpawnError as exc:
            return False, str(exc)
        return True, 'SetModelConfiguration: success'
