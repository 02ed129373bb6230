"""gazebo_ros's ``/gazebo/*`` services around a Simulation (upstream: gazebo_ros_api_plugin).

Handlers run on rospy's threads. A request is checked and parsed there; whatever
changes the world is handed to the physics thread (SimThreadCalls).
"""

from __future__ import annotations

from typing import Any, Callable, List, Sequence, Tuple

import rosgraph.names
import rospy
from gazebo_msgs.srv import DeleteModel, SetModelConfiguration, SpawnModel
from std_srvs.srv import Empty

from ..description.names import shown
from ..sim.simulation import Model, PreparedUrdf, Simulation, SpawnError
from .camera_plugin import GazeboRosCamera
from .controller_manager_services import ControllerManagerServices
from .packages import find_package
from .sim_thread import SimThreadCalls
from .world_loop import WorldLoop


class GazeboRosApi:
    def __init__(self, sim: Simulation, calls: SimThreadCalls, loop: WorldLoop) -> None:
        self.sim, self.calls, self.loop = sim, calls, loop
        self._services = [
            rospy.Service('~pause_physics', Empty, self._empty(self._set_paused, True)),
            rospy.Service('~unpause_physics', Empty, self._empty(self._set_paused, False)),
            rospy.Service('~reset_simulation', Empty, self._empty(self.sim.reset_simulation)),
            rospy.Service('~reset_world', Empty, self._empty(self.sim.reset_world)),
            rospy.Service('~spawn_urdf_model', SpawnModel, self._spawn),
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

    def _spawn(self, req: Any) -> Tuple[bool, str]:
        pose = req.initial_pose
        xyz = (pose.position.x, pose.position.y, pose.position.z)
        q = (pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w)
        if q == (0, 0, 0, 0):
            q = (0, 0, 0, 1)
        try:
            model = self.spawn(req.model_name, req.model_xml, xyz, q, req.robot_namespace)
        except SpawnError as exc:
            rospy.logerr(str(exc))
            return False, str(exc)
        msg = "SpawnModel: Successfully spawned entity '%s'" % model.name
        if model.controller_manager is not None:
            msg += ' with controller manager in %s' % model.namespace
        for c in model.cameras:
            msg += '; camera %s on %s' % (c.sensor.name, c.sensor.image_topic)
        rospy.loginfo(msg)
        return True, msg

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

    def _spawn_prepared(self, prepared: PreparedUrdf, namespace: str) -> Model:
        return self.sim.spawn_prepared(prepared, namespace, attach=self._attach_plugins)

    @staticmethod
    def _attach_plugins(model: Model) -> None:
        """The ROS side of a model's plugins; each goes into the model's record."""
        if model.hw is not None:
            if not rosgraph.names.is_legal_name(model.namespace):
                raise SpawnError(
                    'controller manager namespace %s is not a legal ROS name'
                    % shown(model.namespace)
                )
            # What DefaultRobotHWSim reads from the parameter server: joint limits over the
            # URDF's, and the hardware's own PIDs for position/velocity joints.
            ns = model.namespace.rstrip('/')
            limits = rospy.get_param(ns + '/joint_limits', {})
            model.hw.set_joint_limits(limits if isinstance(limits, dict) else {})
            gains = rospy.get_param(ns + '/gazebo_ros_control/pid_gains', {})
            model.hw.set_pid_gains(gains if isinstance(gains, dict) else {})
            services = ControllerManagerServices(model.hw, model.namespace)
            model.controller_manager = services.manager
            model.plugins.append(services)
        for camera in model.cameras:
            model.plugins.append(GazeboRosCamera(camera))

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
