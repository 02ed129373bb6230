"""franka_control/FrankaStateController: the Franka state at publish_rate, in sim time.

As franka_state_controller.cpp: ``franka_states`` (franka_msgs/FrankaState), ``joint_states``
(q, dq, tau_J), ``joint_states_desired`` (q_d, dq_d, tau_J_d) and ``F_ext`` (the external
wrench in the K frame) under the controller's namespace. The /tf it also sends (link8 ->
NE -> EE -> K) is left to robot_state_publisher here.
"""

from __future__ import annotations

from typing import List, Optional

from ...control.controller import Controller, ControllerError, require_param
from ...control.interfaces import NodeHandle, Publisher, RobotHW
from ...control.message_types import STAMPED, WRENCH, register_message
from .interfaces import FrankaHW, FrankaRobotState

register_message('franka_msgs/FrankaState', STAMPED)
register_message('sensor_msgs/JointState', STAMPED)
register_message('geometry_msgs/WrenchStamped', WRENCH)


class FrankaStateController(Controller):
    type_name = 'franka_control/FrankaStateController'
    interface = None  # reads only

    _states: Publisher
    _joints: Publisher
    _desired: Publisher
    _wrench: Publisher

    def __init__(self) -> None:
        super().__init__()
        self.robot_state: Optional[FrankaRobotState] = None
        self._hw: Optional[FrankaHW] = None
        self._handle = ''
        self._ns = ''
        self.arm_id = ''
        self.joint_names: List[str] = []
        self.publish_period_ns = int(1e9 / 30)
        self.last_publish_ns: Optional[int] = None

    def init(self, robot_hw: RobotHW, root_nh: NodeHandle, controller_nh: NodeHandle) -> None:
        ns, params = controller_nh.namespace, controller_nh.params
        if not isinstance(robot_hw, FrankaHW):
            raise ControllerError(
                'FrankaStateController: Error getting franka state interface from hardware '
                "(the robot's robotSimType is not franka_gazebo/FrankaHWSim)"
            )
        arm_id = params.get('arm_id')
        if not isinstance(arm_id, str) or not arm_id:
            raise ControllerError('FrankaStateController: Could not get parameter arm_id (%s)' % ns)
        rate = params.get('publish_rate', 30.0)
        try:
            rate = float(rate)
        except (TypeError, ValueError):
            raise ControllerError('%s/publish_rate: %r is not a number' % (ns, rate))
        if not rate > 0:
            raise ControllerError('%s/publish_rate: %r is not positive' % (ns, rate))
        names = require_param(params, 'joint_names', ns)
        if not isinstance(names, list) or len(names) != 7:
            raise ControllerError(
                'FrankaStateController: Invalid or no joint_names parameters provided, aborting '
                'controller init! (%s/joint_names must list 7 joints)' % ns
            )
        for n in names:
            robot_hw.get_handle(n, None, ns)  # each must be a joint of the robot
        self.arm_id, self.joint_names = arm_id, [str(n) for n in names]
        self.publish_period_ns = int(round(1e9 / rate))
        self._hw, self._handle, self._ns = robot_hw, arm_id + '_robot', ns
        self.robot_state = robot_hw.franka_state(self._handle, ns)
        self._states = controller_nh.advertise('franka_states', 'franka_msgs/FrankaState', 1)
        self._joints = controller_nh.advertise('joint_states', 'sensor_msgs/JointState', 1)
        self._desired = controller_nh.advertise('joint_states_desired', 'sensor_msgs/JointState', 1)
        self._wrench = controller_nh.advertise('F_ext', 'geometry_msgs/WrenchStamped', 1)

    def starting(self, time_ns: int) -> None:
        self.last_publish_ns = None

    def update(self, time_ns: int, period_ns: int) -> None:
        # franka_hw's TriggerRate: at most publish_rate, the first update publishes.
        last = self.last_publish_ns
        if last is not None and last <= time_ns < last + self.publish_period_ns:
            return
        self.last_publish_ns = time_ns
        assert self._hw is not None
        s = self._hw.franka_state(self._handle, self._ns)  # the Cartesian part brought up to date
        fields = s.as_fields()
        fields['stamp'] = time_ns
        fields['O_ddP_O'] = [0.0, 0.0, -9.81]  # as upstream, whatever the base does
        self._states.publish(fields)
        self._joints.publish(
            dict(
                stamp=time_ns,
                name=self.joint_names,
                position=list(s.q),
                velocity=list(s.dq),
                effort=list(s.tau_J),
            )
        )
        self._desired.publish(
            dict(
                stamp=time_ns,
                name=self.joint_names,
                position=list(s.q_d),
                velocity=list(s.dq_d),
                effort=list(s.tau_J_d),
            )
        )
        self._wrench.publish(
            dict(stamp=time_ns, frame_id=self.arm_id + '_K', wrench=list(s.K_F_ext_hat_K))
        )
