"""The seams of the control layer: what controllers need from the outside, as Protocols.

Controllers talk to ROS through node handles given to ``init``: ``root_nh`` (the robot
namespace, e.g. ``/arm1``) and ``controller_nh`` (the controller's own, e.g.
``/arm1/joint1_position_controller``). Three implementations exist: ros/node_handle.py
(rospy), tuning/local_ros.py (in-process, for the tuner) and the unit tests' fake; the
controller manager's ``node_factory`` type makes mypy hold each of them to this contract.
Joints come from a RobotHW (robot_hw_sim.py simulates one).
"""

from __future__ import annotations

from typing import (
    Any,
    Callable,
    Dict,
    List,
    Mapping,
    Optional,
    Protocol,
    Sequence,
    Tuple,
    runtime_checkable,
)

from .hardware_interface import JointHandle

# What a controller publishes: message fields by name, plain Python values; a ``stamp``
# is integer nanoseconds of sim time. The ROS node handle turns them into a message.
Fields = Mapping[str, Any]
Params = Dict[str, Any]  # a parameter subtree, as ``rosparam get <namespace>`` gives it


class Publisher(Protocol):
    def publish(self, fields: Fields) -> None: ...

    def wanted(self) -> bool:
        """Whether a publish now would reach anyone: a controller's hot loop builds no fields
        for nobody (roscpp serialises nothing for a topic without subscribers either)."""
        ...


class GoalHandle(Protocol):
    """One goal of an action server (actionlib's ServerGoalHandle). ``goal`` is the goal
    as plain fields; ``id`` is the same for every handle of one goal. The outcome calls
    take the result's fields (e.g. ``error_code``, ``error_string``)."""

    id: str
    goal: Fields

    def accept(self) -> None: ...

    def reject(self, result: Fields) -> None: ...

    def succeed(self, result: Fields) -> None: ...

    def abort(self, result: Fields) -> None: ...

    def cancel(self, result: Fields) -> None:
        """setCanceled: PREEMPTED for an accepted goal."""
        ...

    def publish_feedback(self, fields: Fields) -> None: ...


class NodeHandle(Protocol):
    """ros::NodeHandle as controllers use it."""

    namespace: str  # absolute, without a trailing '/' ('/' for the root)
    params: Params  # the parameters under ``namespace`` ({} when there are none)

    def advertise(self, topic: str, type_name: str, queue_size: int) -> Publisher: ...

    def subscribe(self, topic: str, type_name: str, callback: Callable[[Any], object]) -> object:
        """``callback`` gets the message's ``data`` (e.g. a float for std_msgs/Float64)."""
        ...

    def action_server(
        self,
        name: str,
        type_name: str,
        on_goal: Callable[[GoalHandle], None],
        on_cancel: Callable[[GoalHandle], None],
    ) -> object:
        """An action server at ``name`` (e.g. 'control_msgs/FollowJointTrajectory'); the
        callbacks may run on any thread and decide a goal's fate through its handle."""
        ...

    def serve(self, name: str, type_name: str, handler: Callable[[Fields], Fields]) -> object:
        """A service: ``handler(request fields)`` returns the response's fields or raises
        ValueError (the call fails with its message)."""
        ...

    def shutdown(self) -> None:
        """Withdraw every publisher, subscriber and server made through this handle."""
        ...


@runtime_checkable
class ConfigServer(Protocol):
    """A node handle that also offers live parameters (dynamic_reconfigure); optional."""

    def serve_config(
        self,
        namespace: str,
        type_name: str,
        current: Dict[str, Any],
        on_change: Callable[[Dict[str, Any]], Dict[str, Any]],
    ) -> object:
        """Serve ``current`` at ``namespace``; ``on_change(values)`` returns the values in force."""
        ...


NodeFactory = Callable[[str], NodeHandle]  # namespace -> node handle

# A controller's claimed resources: [(hardware interface, [joint names])]
Resources = List[Tuple[str, List[str]]]


class RobotHW(Protocol):
    """hardware_interface::RobotHW as controllers use it: joint handles by name."""

    def joint_names(self) -> List[str]:
        """Sorted, as hardware_interface's std::map gives them."""
        ...

    def get_handle(self, name: str, interface: Optional[str], controller_ns: str) -> JointHandle:
        """The handle of joint ``name`` offering ``interface`` (None: any); raises
        ControllerError naming the joint and ``controller_ns`` when there is none."""
        ...


class RobotHWSimError(ValueError):
    """A hardware sim cannot simulate the description or its parameters; the message says
    why (the spawn fails with it, naming the robotSimType)."""


class RobotHWSim(RobotHW, Protocol):
    """gazebo_ros_control's RobotHWSim: a RobotHW bound to a simulated robot. Every hardware
    sim, the default and each vendor's, is one of these, found by its ``<robotSimType>``
    (sim/robot_hw_sims.py) and built from the description, the simulated robot and the
    physics step; it raises RobotHWSimError when it cannot simulate them."""

    def init_sim(self, model_nh: NodeHandle, robot_namespace: str) -> None:
        """initSim: the parameters it needs are ``model_nh.params`` (the robot namespace's
        subtree, as the ROS layer or a test hands them in); topics it offers go through
        ``model_nh``. Raises RobotHWSimError on parameters it cannot use."""
        ...

    def read(self, time_ns: int, period_ns: int) -> None:
        """readSim: joint state from the simulation into the handles, at sim time ``time_ns``,
        ``period_ns`` after the last read."""
        ...

    def write(self) -> None:
        """writeSim, every physics step: the handles' commands, saturated, to the simulation."""
        ...

    def do_switch(self, start: Sequence[Resources], stop: Sequence[Resources]) -> None:
        """RobotHW::doSwitch: the claimed resources of the controllers just started and
        stopped (most hardware sims ignore them)."""
        ...
