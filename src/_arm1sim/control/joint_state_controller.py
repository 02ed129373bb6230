"""joint_state_controller/JointStateController: publishes every joint at publish_rate in sim
time."""

from __future__ import annotations

from typing import List, Optional, Tuple

from .controller import Controller, ControllerError, require_param
from .interfaces import NodeHandle, Publisher, RobotHW
from .message_types import STAMPED, register_message

register_message('sensor_msgs/JointState', STAMPED)

ExtraJoint = Tuple[str, float, float, float]  # name, position, velocity, effort


class JointStateController(Controller):
    type_name = 'joint_state_controller/JointStateController'
    interface = None  # reads only: claims nothing

    _pub: Publisher  # set by init

    def __init__(self) -> None:
        super().__init__()
        self.publish_period_ns: Optional[int] = None  # None: publish_rate <= 0, never publish
        self.last_publish_ns: Optional[int] = None
        self._extra: List[ExtraJoint] = []
        self._names: List[str] = []

    def init(self, robot_hw: RobotHW, root_nh: NodeHandle, controller_nh: NodeHandle) -> None:
        ns = controller_nh.namespace
        rate = require_param(controller_nh.params, 'publish_rate', ns)
        try:
            rate = float(rate)
        except (TypeError, ValueError):
            raise ControllerError("Parameter 'publish_rate' in %s is not a number: %r" % (ns, rate))
        self.publish_period_ns = int(round(1e9 / rate)) if rate > 0 else None
        # Sorted by default, as std::map gives them.
        names = controller_nh.params.get('joints') or robot_hw.joint_names()
        self.joints = [robot_hw.get_handle(n, None, ns) for n in names]
        extra = controller_nh.params.get('extra_joints') or []
        self._extra = [
            (
                e['name'],
                float(e.get('position', 0.0)),
                float(e.get('velocity', 0.0)),
                float(e.get('effort', 0.0)),
            )
            for e in extra
        ]
        self._names = [j.name for j in self.joints] + [e[0] for e in self._extra]
        self._pub = root_nh.advertise('joint_states', 'sensor_msgs/JointState', 4)

    def starting(self, time_ns: int) -> None:
        self.last_publish_ns = None

    def update(self, time_ns: int, period_ns: int) -> None:
        if self.publish_period_ns is None:
            return
        if self.last_publish_ns is None or time_ns < self.last_publish_ns:
            # First update, or time went back (reset_simulation): publish now, not once the
            # old time is reached again.
            self.last_publish_ns = time_ns
        elif self.last_publish_ns + self.publish_period_ns < time_ns:
            self.last_publish_ns += self.publish_period_ns  # exactly one period on: no drift
        else:
            return
        pub = self._pub
        if not pub.wanted():
            return  # nobody listens: the schedule above goes on, no message is built
        joints, extra = self.joints, self._extra
        position = [j.position for j in joints]
        velocity = [j.velocity for j in joints]
        effort = [j.effort for j in joints]
        if extra:
            position += [e[1] for e in extra]
            velocity += [e[2] for e in extra]
            effort += [e[3] for e in extra]
        pub.publish(
            dict(
                stamp=time_ns, name=self._names, position=position, velocity=velocity, effort=effort
            )
        )
