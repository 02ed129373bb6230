"""The node handle controllers receive (control/interfaces.py's NodeHandle and
ConfigServer), implemented with rospy.

It translates between the plain dicts and floats of the ROS-free core and ROS
messages; nothing else happens here.
"""

from __future__ import annotations

import logging
import warnings
from typing import Any, Callable, Dict, List, Optional, Tuple

import rospy
from control_msgs.msg import JointControllerState, JointTrajectoryControllerState
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64, Float64MultiArray
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

from ..control.interfaces import Fields, Params

Fill = Callable[[Any, Any], None]  # (message, the core's value) -> None


def synchronous_publisher(topic: str, msg_class: type, **kwargs: Any) -> rospy.Publisher:
    """A publisher that writes in the caller's thread, for the physics thread's topics.

    rospy's queued publisher (queue_size set) ends every publish with ``time.sleep(0)``
    to hand the message to a writer thread: about 0.1 ms each here, a third of the
    top speed at 50 Hz joint_states and 100 Hz /clock of sim time. Written
    synchronously, a small message on loopback costs a few tens of microseconds.
    """
    with warnings.catch_warnings():
        warnings.simplefilter('ignore')  # rospy warns when queue_size is None
        return rospy.Publisher(topic, msg_class, queue_size=None, **kwargs)


def to_time(ns: int) -> rospy.Time:
    return rospy.Time(ns // 1000000000, ns % 1000000000)


def _fill_stamped(msg: Any, fields: Fields) -> None:
    """Copy the core's fields into a message; ``stamp`` (ns of sim time) goes to the header."""
    for key, value in fields.items():
        if key == 'stamp':
            msg.header.stamp = to_time(value)
        else:
            setattr(msg, key, value)


def _fill_data(msg: Any, value: Any) -> None:
    msg.data = value


def _fill_point(point: Any, fields: Fields) -> None:
    """A trajectory_msgs/JointTrajectoryPoint from plain fields (time_from_start: ns)."""
    for key, value in fields.items():
        if key == 'time_from_start':
            point.time_from_start = (
                rospy.Duration.from_sec(value)
                if isinstance(value, float)
                else rospy.Duration(0, int(value))
            )
        else:
            setattr(point, key, value)


def _fill_trajectory_state(msg: Any, fields: Fields) -> None:
    """control_msgs/JointTrajectoryControllerState (also the action's feedback)."""
    for key, value in fields.items():
        if key == 'stamp':
            msg.header.stamp = to_time(value)
        elif key in ('desired', 'actual', 'error'):
            point = JointTrajectoryPoint()
            _fill_point(point, value)
            setattr(msg, key, point)
        else:
            setattr(msg, key, value)


def _read_data(msg: Any) -> Any:
    return msg.data


def duration_ns(d: Any) -> int:
    return int(d.secs) * 1000000000 + int(d.nsecs)


def read_trajectory(msg: Any) -> Dict[str, Any]:
    """trajectory_msgs/JointTrajectory as the core's plain fields (times in ns)."""
    return dict(
        stamp=duration_ns(msg.header.stamp),
        joint_names=list(msg.joint_names),
        points=[
            dict(
                positions=list(p.positions),
                velocities=list(p.velocities),
                accelerations=list(p.accelerations),
                effort=list(p.effort),
                time_from_start=duration_ns(p.time_from_start),
            )
            for p in msg.points
        ],
    )


def read_follow_joint_trajectory_goal(goal: Any) -> Dict[str, Any]:
    def tolerances(entries: Any) -> List[Dict[str, Any]]:
        return [
            dict(name=t.name, position=t.position, velocity=t.velocity, acceleration=t.acceleration)
            for t in entries
        ]

    return dict(
        trajectory=read_trajectory(goal.trajectory),
        path_tolerance=tolerances(goal.path_tolerance),
        goal_tolerance=tolerances(goal.goal_tolerance),
        goal_time_tolerance=duration_ns(goal.goal_time_tolerance),
    )


# type name -> (message class, fill(message, core's fields))
MESSAGES: Dict[str, Tuple[type, Fill]] = {
    'sensor_msgs/JointState': (JointState, _fill_stamped),
    'control_msgs/JointControllerState': (JointControllerState, _fill_stamped),
    'std_msgs/Float64': (Float64, _fill_data),
    'std_msgs/Float64MultiArray': (Float64MultiArray, _fill_data),
    'control_msgs/JointTrajectoryControllerState': (
        JointTrajectoryControllerState,
        _fill_trajectory_state,
    ),
    'trajectory_msgs/JointTrajectory': (JointTrajectory, _fill_stamped),
}
# type name -> what a subscriber's callback gets from a message (default: its ``data``)
READERS: Dict[str, Callable[[Any], Any]] = {
    'trajectory_msgs/JointTrajectory': read_trajectory,
}


class RosGoalHandle:
    """control/interfaces.py's GoalHandle over actionlib's ServerGoalHandle."""

    def __init__(
        self,
        gh: Any,
        goal: Dict[str, Any],
        result_class: type,
        feedback_class: type,
        fill_feedback: Fill,
    ) -> None:
        self._gh, self.goal = gh, goal
        self.id = gh.get_goal_id().id
        self._result_class, self._feedback_class = result_class, feedback_class
        self._fill_feedback = fill_feedback

    def _result(self, fields: Fields) -> Any:
        result = self._result_class()
        for key, value in fields.items():
            setattr(result, key, value)
        return result

    def accept(self) -> None:
        self._gh.set_accepted()

    def reject(self, result: Fields) -> None:
        self._gh.set_rejected(self._result(result), result.get('error_string', ''))

    def succeed(self, result: Fields) -> None:
        self._gh.set_succeeded(self._result(result), result.get('error_string', ''))

    def abort(self, result: Fields) -> None:
        self._gh.set_aborted(self._result(result), result.get('error_string', ''))

    def cancel(self, result: Fields) -> None:
        self._gh.set_canceled(self._result(result), result.get('error_string', ''))

    def publish_feedback(self, fields: Fields) -> None:
        feedback = self._feedback_class()
        self._fill_feedback(feedback, fields)
        self._gh.publish_feedback(feedback)


class _ActionServer:
    """actionlib's ActionServer, withdrawn by unregister(). Its status timer is made anew
    with reset=True: rospy's Timer otherwise dies when sim time jumps back (reset_simulation)."""

    def __init__(
        self,
        name: str,
        type_name: str,
        on_goal: Callable[[Any], None],
        on_cancel: Callable[[Any], None],
    ) -> None:
        import actionlib

        spec, goal_reader, result_class, feedback_class, fill_feedback = ACTIONS[type_name]

        def wrap(gh: Any) -> RosGoalHandle:
            return RosGoalHandle(
                gh, goal_reader(gh.get_goal()), result_class, feedback_class, fill_feedback
            )

        self.server = actionlib.ActionServer(
            name,
            spec,
            lambda gh: on_goal(wrap(gh)),
            lambda gh: on_cancel(wrap(gh)),
            auto_start=False,
        )
        self.server.start()
        timer = getattr(self.server, 'status_timer', None)
        if timer is not None:
            period = timer._period
            timer.shutdown()
            self._last_now = rospy.Time.now()
            self.server.status_timer = rospy.Timer(period, self._publish_status, reset=True)

    def _publish_status(self, event: Any) -> None:
        # After reset_simulation a cancel stamped before it would silently cancel every new
        # goal (actionlib cancels goals stamped at or before the newest cancel): forget it.
        now = rospy.Time.now()
        if now < self._last_now:
            with self.server.lock:
                self.server.last_cancel = rospy.Time()
        self._last_now = now
        self.server.publish_status_async(event)

    def unregister(self) -> None:
        s = self.server
        timer = getattr(s, 'status_timer', None)
        if timer is not None:
            timer.shutdown()
        for name in ('status_pub', 'result_pub', 'feedback_pub', 'goal_sub', 'cancel_sub'):
            handle = getattr(s, name, None)
            if handle is not None:
                handle.unregister()


def _actions() -> Dict[str, Tuple[Any, Callable[[Any], Any], type, type, Fill]]:
    from control_msgs.msg import (
        FollowJointTrajectoryAction,
        FollowJointTrajectoryFeedback,
        FollowJointTrajectoryResult,
        GripperCommandAction,
        GripperCommandFeedback,
        GripperCommandResult,
    )

    return {
        'control_msgs/FollowJointTrajectory': (
            FollowJointTrajectoryAction,
            read_follow_joint_trajectory_goal,
            FollowJointTrajectoryResult,
            FollowJointTrajectoryFeedback,
            _fill_trajectory_state,
        ),
        'control_msgs/GripperCommand': (
            GripperCommandAction,
            read_gripper_command_goal,
            GripperCommandResult,
            GripperCommandFeedback,
            _fill_fields,
        ),
    }


def read_gripper_command_goal(goal: Any) -> Dict[str, Any]:
    return dict(command=dict(position=goal.command.position, max_effort=goal.command.max_effort))


def _fill_fields(msg: Any, fields: Fields) -> None:
    for key, value in fields.items():
        setattr(msg, key, value)


ACTIONS = _actions()


class _Service:
    def __init__(self, name: str, type_name: str, handler: Callable[[Fields], Fields]) -> None:
        srv_class, read_request = SERVICES[type_name]

        def call(req: Any) -> Any:
            try:
                fields = handler(read_request(req))
            except ValueError as exc:
                raise rospy.ServiceException(str(exc))
            response = srv_class._response_class()
            for key, value in fields.items():
                setattr(response, key, value)
            return response

        self.service = rospy.Service(name, srv_class, call)

    def unregister(self) -> None:
        self.service.shutdown()


def _services() -> Dict[str, Tuple[Any, Callable[[Any], Fields]]]:
    from control_msgs.srv import QueryTrajectoryState

    return {
        'control_msgs/QueryTrajectoryState': (
            QueryTrajectoryState,
            lambda req: dict(time=duration_ns(req.time)),
        )
    }


SERVICES = _services()


class _Publisher:
    """Fills one message again for each publish: publishing is synchronous (serialised
    before publish returns), so reuse is safe and spares building a message each time."""

    __slots__ = ('pub', 'fill', 'msg')

    def __init__(self, pub: rospy.Publisher, msg_class: type, fill: Fill) -> None:
        self.pub, self.fill, self.msg = pub, fill, msg_class()

    def publish(self, fields: Fields) -> None:
        if self.pub.get_num_connections():  # build no message nobody reads
            self.fill(self.msg, fields)
            self.pub.publish(self.msg)


class RosNodeHandle:
    # Called after each message a subscription of a node handle delivers (rospy's thread):
    # the world loop's Pacer.wake, so that a command does not wait out a batched sleep.
    on_message: Optional[Callable[[], None]] = None

    def __init__(self, namespace: str) -> None:
        self.namespace = namespace.rstrip('/') or '/'
        params = rospy.get_param(self.namespace, {})
        self.params: Params = params if isinstance(params, dict) else {}
        self._handles: List[Any] = []  # whatever has unregister(): publishers, subscribers, servers

    def _name(self, topic: str) -> str:
        return topic if topic.startswith('/') else '%s/%s' % (self.namespace.rstrip('/'), topic)

    def advertise(self, topic: str, type_name: str, queue_size: int) -> _Publisher:
        # queue_size is part of the node handle's interface; publishing here is synchronous.
        cls, fill = MESSAGES[type_name]
        pub = synchronous_publisher(self._name(topic), cls)
        self._handles.append(pub)
        return _Publisher(pub, cls, fill)

    def subscribe(
        self, topic: str, type_name: str, callback: Callable[[Any], object]
    ) -> rospy.Subscriber:
        cls, _ = MESSAGES[type_name]
        read = READERS.get(type_name, _read_data)

        def deliver(msg: Any) -> None:
            callback(read(msg))
            wake = RosNodeHandle.on_message
            if wake is not None:
                wake()

        sub = rospy.Subscriber(self._name(topic), cls, deliver, queue_size=1)
        self._handles.append(sub)
        return sub

    def serve_config(
        self,
        namespace: str,
        type_name: str,
        current: Dict[str, Any],
        on_change: Callable[[Dict[str, Any]], Dict[str, Any]],
    ) -> object:
        """A dynamic_reconfigure server at ``namespace`` (e.g. a controller's ``pid``):
        starts at ``current``; ``on_change(values)`` returns the values in force."""
        from .pid_reconfigure import serve_config

        server = serve_config(self._name(namespace), type_name, current, on_change)
        if server is not None:
            self._handles.append(server)
        return server

    def action_server(
        self,
        name: str,
        type_name: str,
        on_goal: Callable[[Any], None],
        on_cancel: Callable[[Any], None],
    ) -> _ActionServer:
        server = _ActionServer(self._name(name), type_name, on_goal, on_cancel)
        self._handles.append(server)
        return server

    def serve(self, name: str, type_name: str, handler: Callable[[Fields], Fields]) -> _Service:
        service = _Service(self._name(name), type_name, handler)
        self._handles.append(service)
        return service

    def shutdown(self) -> None:
        for h in self._handles:
            h.unregister()
        self._handles = []


class RospyLogHandler(logging.Handler):
    """Sends the core's Python log records to rosout."""

    def emit(self, record: logging.LogRecord) -> None:
        level = record.levelno
        log = (
            rospy.logerr
            if level >= logging.ERROR
            else rospy.logwarn
            if level >= logging.WARNING
            else rospy.loginfo
            if level >= logging.INFO
            else rospy.logdebug
        )
        log(self.format(record))


def route_core_logs() -> None:
    logger = logging.getLogger('arm1')
    if not any(isinstance(h, RospyLogHandler) for h in logger.handlers):
        logger.addHandler(RospyLogHandler())
        logger.setLevel(logging.INFO)
        logger.propagate = False
