"""The controller interface of ros_control (init / starting / update / stopping), ROS-free.

Controllers talk to the outside world through node handles given to ``init``:
``root_nh`` (the robot namespace, e.g. ``/arm1``) and ``controller_nh`` (the
controller's own, e.g. ``/arm1/joint1_position_controller``). A node handle has
``namespace``, ``params`` (the parameter subtree of that namespace, a dict),
``advertise(topic, type_name, queue_size)`` returning an object with
``publish(fields)``, ``subscribe(topic, type_name, callback)`` and ``shutdown()``;
optionally ``serve_config(namespace, type_name, current, on_change)`` for live
parameters (dynamic_reconfigure). The ROS layer implements them with rospy; the
tuner and the tests, in-process (tuning/local_ros.py).
"""


class ControllerError(Exception):
    """A controller could not be initialised; the message names the culprit."""


class Controller:
    """Base class: a controller claims joints of one hardware interface."""

    type_name = None
    interface = None  # hardware interface whose joints it claims; None claims nothing

    def __init__(self):
        self.name = None
        self.joints = []  # JointHandles this controller claims

    def init(self, robot_hw, root_nh, controller_nh):
        raise NotImplementedError

    def starting(self, time_ns):
        pass

    def update(self, time_ns, period):
        raise NotImplementedError

    def stopping(self, time_ns):
        pass

    def claimed_resources(self):
        """``[(interface, [joint names])]``, as list_controllers reports them."""
        if self.interface is None:
            return []
        return [(self.interface, [j.name for j in self.joints])]


def require_param(params, key, controller_ns):
    if key not in params:
        raise ControllerError("Parameter '%s' not set in namespace %s" % (key, controller_ns))
    return params[key]
