"""The controller interface of ros_control (init / starting / update / stopping), ROS-free.

Time is integer nanoseconds of sim time everywhere here: ``time_ns`` is now, ``period_ns``
the sim time since the previous update. Controllers reach ROS and the joints through the
Protocols of interfaces.py.
"""

from __future__ import annotations

from typing import Any, ClassVar, List, Literal, Optional, Sequence, Tuple

from .hardware_interface import JointHandle
from .interfaces import NodeHandle, Params, RobotHW

# ros_control's ControllerBase states, as list_controllers names them.
State = Literal['constructed', 'initialized', 'running', 'stopped']


class ControllerError(Exception):
    """A controller could not be initialised; the message names the culprit."""


class Controller:
    """Base class: a controller claims joints of one hardware interface.

    The controller owns its run state (``state``), as ros_control's ControllerBase does:
    the manager calls ``init_request``, ``start_request`` and ``stop_request``, which call
    the hooks a controller type overrides (``init``, ``starting``, ``stopping``) and set
    the state. ``update`` is called only while running.
    """

    type_name: ClassVar[str] = ''  # the ``type`` parameter that loads it
    interface: ClassVar[Optional[str]] = None  # whose joints it claims; None claims nothing

    def __init__(self) -> None:
        self.name = ''
        self.joints: List[JointHandle] = []  # the handles this controller claims
        self.state: State = 'constructed'

    # -- what the manager calls -------------------------------------------------
    def init_request(
        self, robot_hw: RobotHW, root_nh: NodeHandle, controller_nh: NodeHandle
    ) -> None:
        self.init(robot_hw, root_nh, controller_nh)
        self.state = 'initialized'

    def start_request(self, time_ns: int) -> None:
        self.starting(time_ns)
        self.state = 'running'

    def stop_request(self, time_ns: int) -> None:
        self.stopping(time_ns)
        self.state = 'stopped'

    @property
    def running(self) -> bool:
        return self.state == 'running'

    # -- what a controller type implements --------------------------------------
    def init(self, robot_hw: RobotHW, root_nh: NodeHandle, controller_nh: NodeHandle) -> None:
        raise NotImplementedError

    def starting(self, time_ns: int) -> None:
        pass

    def update(self, time_ns: int, period_ns: int) -> None:
        raise NotImplementedError

    def stopping(self, time_ns: int) -> None:
        pass

    @classmethod
    def update_group(cls, controllers: Sequence[Controller], time_ns: int, period_ns: int) -> None:
        """Update running controllers of this very type, in their order. The manager calls
        this once per run of consecutive controllers of one type; a type may override it to
        do them all in one pass, with the same result as ``update`` on each."""
        for c in controllers:
            c.update(time_ns, period_ns)

    def claimed_resources(self) -> List[Tuple[str, List[str]]]:
        """``[(interface, [joint names])]``, as list_controllers reports them."""
        if self.interface is None:
            return []
        return [(self.interface, [j.name for j in self.joints])]


def require_param(params: Params, key: str, controller_ns: str) -> Any:
    if key not in params:
        raise ControllerError("Parameter '%s' not set in namespace %s" % (key, controller_ns))
    return params[key]
