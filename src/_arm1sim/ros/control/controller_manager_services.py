"""The ``<ns>/controller_manager/*`` services (upstream: the ROS side of controller_manager),
translated onto the ROS-free ControllerManager."""

import rospy
from controller_manager_msgs.msg import ControllerState, HardwareInterfaceResources
from controller_manager_msgs.srv import (
    ListControllers,
    ListControllerTypes,
    LoadController,
    ReloadControllerLibraries,
    SwitchController,
    UnloadController,
)

from ...control.controller_manager import BASE_CLASS, ControllerManager, ControllerManagerError
from .node_handle import RosNodeHandle


def cpp_type_name(interface: str) -> str:
    """``hardware_interface::EffortJointInterface``: list_controllers names the C++ type, as
    upstream does (MoveIt's ros_control plugin matches on it); the resources come sorted
    (a std::set upstream)."""
    return interface.replace('/', '::')


class ControllerManagerServices:
    def __init__(self, robot_hw, namespace):
        self.manager = ControllerManager(robot_hw, RosNodeHandle, namespace)
        base = '%s/controller_manager/' % namespace.rstrip('/')
        self._services = [
            rospy.Service(base + name, srv, handler)
            for name, srv, handler in (
                ('list_controllers', ListControllers, self._list),
                ('list_controller_types', ListControllerTypes, self._types),
                ('load_controller', LoadController, self._load),
                ('unload_controller', UnloadController, self._unload),
                ('switch_controller', SwitchController, self._switch),
                ('reload_controller_libraries', ReloadControllerLibraries, self._reload),
            )
        ]

    def _list(self, req):
        return [
            [
                ControllerState(
                    name=n,
                    type=t,
                    state=s,
                    claimed_resources=[
                        HardwareInterfaceResources(cpp_type_name(i), sorted(joints))
                        for i, joints in res
                    ],
                )
                for n, t, s, res in self.manager.list_controllers()
            ]
        ]

    def _types(self, req):
        types = self.manager.controller_types()
        return types, [BASE_CLASS] * len(types)

    def _load(self, req):
        try:
            self.manager.load_controller(req.name)
        except ControllerManagerError as exc:
            rospy.logerr(str(exc))
            return False
        rospy.loginfo("Loaded controller '%s'", req.name)
        return True

    def _unload(self, req):
        try:
            self.manager.unload_controller(req.name)
        except ControllerManagerError as exc:
            rospy.logerr(str(exc))
            return False
        return True

    def _switch(self, req):
        return self.manager.switch_controller(
            req.start_controllers, req.stop_controllers, req.strictness, req.timeout
        )

    def _reload(self, req):
        return self.manager.reload_controller_libraries(bool(req.force_kill))

    def shutdown(self):
        for s in self._services:
            s.shutdown()
