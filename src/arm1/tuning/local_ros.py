"""An in-process stand-in for the parameter server and topics, so that the real
ControllerManager and controllers run without a ROS master (a NodeHandle of
control/interfaces.py).

Parameters are a plain dict tree (what ``rosparam load controllers.yaml`` would put
on the server); ``publish(topic, value)`` delivers to subscribers at once; the last
message of each advertised topic is kept (and every message, for topics asked for
with ``record``).
"""
from __future__ import annotations

from typing import Any, Callable, Dict, List, Optional, Tuple

from ..control.interfaces import Fields, Params, Publisher

Callback = Callable[[Any], object]


class LocalPublisher:
    __slots__ = ('ros', 'topic', 'type_name')

    def __init__(self, ros: LocalRos, topic: str, type_name: str) -> None:
        self.ros, self.topic, self.type_name = ros, topic, type_name

    def publish(self, fields: Fields) -> None:
        self.ros.last[self.topic] = fields
        log = self.ros.recorded.get(self.topic)
        if log is not None:
            log.append(fields)


class LocalNodeHandle:
    def __init__(self, ros: LocalRos, namespace: str) -> None:
        self.ros = ros
        self.namespace = namespace.rstrip('/') or '/'
        self.params = ros.get_param(self.namespace)
        self._subscriptions: List[Tuple[str, Callback]] = []

    def resolve(self, topic: str) -> str:
        return topic if topic.startswith('/') else '%s/%s' % (self.namespace.rstrip('/'), topic)

    def advertise(self, topic: str, type_name: str, queue_size: int) -> Publisher:
        return LocalPublisher(self.ros, self.resolve(topic), type_name)

    def subscribe(self, topic: str, type_name: str, callback: Callback) -> object:
        name = self.resolve(topic)
        self.ros.subscribers.setdefault(name, []).append(callback)
        self._subscriptions.append((name, callback))
        return callback

    def shutdown(self) -> None:
        for name, callback in self._subscriptions:
            self.ros.subscribers[name].remove(callback)
        self._subscriptions = []


class LocalRos:
    def __init__(self, params: Optional[Params] = None) -> None:
        self.params: Params = params if params is not None else {}
        self.subscribers: Dict[str, List[Callback]] = {}
        self.last: Dict[str, Fields] = {}  # topic -> last published fields
        self.recorded: Dict[str, List[Fields]] = {}  # for the topics passed to record()

    def get_param(self, namespace: str) -> Params:
        node: Any = self.params
        for part in [p for p in namespace.split('/') if p]:
            if not isinstance(node, dict) or part not in node:
                return {}
            node = node[part]
        return node if isinstance(node, dict) else {}

    def node_handle(self, namespace: str) -> LocalNodeHandle:
        """The ``node_factory`` a ControllerManager takes."""
        return LocalNodeHandle(self, namespace)

    def publish(self, topic: str, value: Any) -> int:
        """Deliver to every subscriber of ``topic``; returns how many got it."""
        callbacks = list(self.subscribers.get(topic, ()))
        for callback in callbacks:
            callback(value)
        return len(callbacks)

    def record(self, topic: str) -> List[Fields]:
        """Keep every message published on ``topic`` from now on; returns the list."""
        return self.recorded.setdefault(topic, [])
