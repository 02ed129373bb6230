"""The node handle controllers receive (control/interfaces.py's NodeHandle and
ConfigServer), implemented with rospy.

It translates between the plain dicts and floats of the ROS-free core and ROS
messages; nothing else happens here.
"""
from __future__ import annotations

import logging
import warnings
from typing import Any, Callable, Dict, List, Tuple

import rospy
from control_msgs.msg import JointControllerState
from sensor_msgs.msg import JointState
from std_msgs.msg import Float64

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


# type name -> (message class, fill(message, core's fields))
MESSAGES: Dict[str, Tuple[type, Fill]] = {
    'sensor_msgs/JointState': (JointState, _fill_stamped),
    'control_msgs/JointControllerState': (JointControllerState, _fill_stamped),
    'std_msgs/Float64': (Float64, _fill_data),
}


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

    def subscribe(self, topic: str, type_name: str,
                  callback: Callable[[Any], object]) -> rospy.Subscriber:
        cls, _ = MESSAGES[type_name]
        sub = rospy.Subscriber(self._name(topic), cls, lambda m: callback(m.data), queue_size=1)
        self._handles.append(sub)
        return sub

    def serve_config(self, namespace: str, type_name: str, current: Dict[str, Any],
                     on_change: Callable[[Dict[str, Any]], Dict[str, Any]]) -> object:
        """A dynamic_reconfigure server at ``namespace`` (e.g. a controller's ``pid``):
        starts at ``current``; ``on_change(values)`` returns the values in force."""
        from .pid_reconfigure import serve_config
        server = serve_config(self._name(namespace), type_name, current, on_change)
        if server is not None:
            self._handles.append(server)
        return server

    def shutdown(self) -> None:
        for h in self._handles:
            h.unregister()
        self._handles = []


class RospyLogHandler(logging.Handler):
    """Sends the core's Python log records to rosout."""

    def emit(self, record: logging.LogRecord) -> None:
        level = record.levelno
        log = (rospy.logerr if level >= logging.ERROR else rospy.logwarn if level >= logging.WARNING
               else rospy.loginfo if level >= logging.INFO else rospy.logdebug)
        log(self.format(record))


def route_core_logs() -> None:
    logger = logging.getLogger('arm1')
    if not any(isinstance(h, RospyLogHandler) for h in logger.handlers):
        logger.addHandler(RospyLogHandler())
        logger.setLevel(logging.INFO)
        logger.propagate = False
