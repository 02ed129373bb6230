"""gazebo_ros_control's DefaultRobotHWSim: joint handles bound to a simulated robot.

The actuated joints are those the URDF's transmissions name; each is read from
the physics every update and driven by the saturated effort its controller wrote.
"""
from __future__ import annotations

import logging
from typing import TYPE_CHECKING, Dict, List, Optional, Protocol, Sequence, Tuple

from ..control.controller import ControllerError
from ..control.hardware_interface import (
    EFFORT_JOINT_INTERFACE,
    JointHandle,
    SaturationBounds,
    saturate_effort,
    saturation_bounds,
)

if TYPE_CHECKING:
    from ..description.urdf_model import RobotModel

log = logging.getLogger('arm1.control')


class SimulatedJoints(Protocol):
    """What the hardware needs of a simulated robot (physics.robot.Robot)."""

    def indices(self, joint_names: Sequence[str]) -> List[int]: ...

    def read(self, indices: Sequence[int]) -> Sequence[Tuple[float, float]]:
        """``(position, velocity)`` of each joint."""
        ...

    def apply_efforts(self, indices: Sequence[int], efforts: Sequence[float]) -> None: ...


class DefaultRobotHWSim:
    """A RobotHWSim (control/interfaces.py) with an effort interface for each actuated joint."""

    def __init__(self, description: RobotModel, robot: SimulatedJoints) -> None:
        self.robot = robot
        self.handles: Dict[str, JointHandle] = {}
        for joint, interface in description.actuated_joints():
            if interface != EFFORT_JOINT_INTERFACE:
                log.error("joint '%s': hardware interface '%s' is not simulated (only %s); "
                          'the joint is left passive', joint.name, interface,
                          EFFORT_JOINT_INTERFACE)
                continue
            self.handles[joint.name] = JointHandle(joint.name, joint.type, joint.limits, interface)
        self._ordered = [self.handles[n] for n in sorted(self.handles)]
        self._indices = robot.indices([h.name for h in self._ordered])
        self._bounds: List[Tuple[JointHandle, SaturationBounds]] = [
            (h, saturation_bounds(h.limits)) for h in self._ordered]

    def joint_names(self) -> List[str]:
        """Sorted, as hardware_interface's std::map gives them."""
        return [h.name for h in self._ordered]

    def get_handle(self, name: str, interface: Optional[str], controller_ns: str) -> JointHandle:
        handle = self.handles.get(name)
        if handle is None:
            raise ControllerError(
                "joint '%s' (from %s/joint) is not an actuated joint of the robot; known joints: %s"
                % (name, controller_ns, ', '.join(self.joint_names()) or 'none'))
        if interface is not None and interface != handle.interface:
            raise ControllerError("joint '%s' offers %s, not %s"
                                  % (name, handle.interface, interface))
        return handle

    def read(self) -> None:
        for h, (pos, vel) in zip(self._ordered, self.robot.read(self._indices)):
            h.position, h.velocity = pos, vel

    def write(self) -> None:
        efforts = []
        for h, bounds in self._bounds:
            h.effort = effort = saturate_effort(h.command, h.position, h.velocity, *bounds)
            efforts.append(effort)
        self.robot.apply_efforts(self._indices, efforts)
