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

from ..control.interfaces import Fields, GoalHandle, Params, Publisher

Callback = Callable[[Any], object]
GoalCallback = Callable[[GoalHandle], None]


class LocalGoalHandle:
    """One goal of a LocalActionServer: its status (actionlib's names) and result."""

    def __init__(self, server: LocalActionServer, goal_id: str, goal: Fields) -> None:
        self.server, self.id, self.goal = server, goal_id, goal
        self.status = 'PENDING'
        self.result: Optional[Fields] = None
        self.feedback: List[Fields] = []

    def _end(self, allowed: Tuple[str, ...], status: str, result: Fields) -> None:
        if self.status not in allowed:
            raise RuntimeError('goal %s: %s from %s' % (self.id, status, self.status))
        self.status, self.result = status, result

    def accept(self) -> None:
        self._end(
            ('PENDING', 'RECALLING'), 'ACTIVE' if self.status == 'PENDING' else 'PREEMPTING', {}
        )
        self.result = None

    def reject(self, result: Fields) -> None:
        self._end(('PENDING', 'RECALLING'), 'REJECTED', result)

    def succeed(self, result: Fields) -> None:
        self._end(('ACTIVE', 'PREEMPTING'), 'SUCCEEDED', result)

    def abort(self, result: Fields) -> None:
        self._end(('ACTIVE', 'PREEMPTING'), 'ABORTED', result)

    def cancel(self, result: Fields) -> None:
        self._end(
            ('PENDING', 'RECALLING', 'ACTIVE', 'PREEMPTING'),
            'RECALLED' if self.status in ('PENDING', 'RECALLING') else 'PREEMPTED',
            result,
        )

    def publish_feedback(self, fields: Fields) -> None:
        self.feedback.append(fields)


class LocalActionServer:
    """actionlib's ActionServer in-process: ``send_goal`` and ``cancel`` play the client."""

    def __init__(
        self, name: str, type_name: str, on_goal: GoalCallback, on_cancel: GoalCallback
    ) -> None:
        self.name, self.type_name = name, type_name
        self.on_goal, self.on_cancel = on_goal, on_cancel
        self.goals: List[LocalGoalHandle] = []

    def send_goal(self, goal: Fields) -> LocalGoalHandle:
        gh = LocalGoalHandle(self, 'goal-%d' % (len(self.goals) + 1), goal)
        self.goals.append(gh)
        self.on_goal(gh)
        return gh

    def cancel(self, gh: LocalGoalHandle) -> None:
        if gh.status in ('PENDING', 'ACTIVE'):
            gh.status = 'RECALLING' if gh.status == 'PENDING' else 'PREEMPTING'
            self.on_cancel(gh)


class LocalPublisher:
    __slots__ = ('ros', 'topic', 'type_name')

    def __init__(self, ros: LocalRos, topic: str, type_name: str) -> None:
        self.ros, self.topic, self.type_name = ros, topic, type_name

    def wanted(self) -> bool:
        return True  # the tuner reads every topic (last, recorded)

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
        self._servers: List[str] = []  # names of its action servers and services

    def resolve(self, topic: str) -> str:
        return topic if topic.startswith('/') else '%s/%s' % (self.namespace.rstrip('/'), topic)

    def advertise(self, topic: str, type_name: str, queue_size: int) -> Publisher:
        return LocalPublisher(self.ros, self.resolve(topic), type_name)

    def subscribe(self, topic: str, type_name: str, callback: Callback) -> object:
        name = self.resolve(topic)
        self.ros.subscribers.setdefault(name, []).append(callback)
        self._subscriptions.append((name, callback))
        return callback

    def action_server(
        self, name: str, type_name: str, on_goal: GoalCallback, on_cancel: GoalCallback
    ) -> LocalActionServer:
        server = LocalActionServer(self.resolve(name), type_name, on_goal, on_cancel)
        self.ros.action_servers[server.name] = server
        self._servers.append(server.name)
        return server

    def serve(
        self, name: str, type_name: str, handler: Callable[[Fields], Fields]
    ) -> Callable[[Fields], Fields]:
        self.ros.services[self.resolve(name)] = handler
        self._servers.append(self.resolve(name))
        return handler

    def shutdown(self) -> None:
        for name, callback in self._subscriptions:
            self.ros.subscribers[name].remove(callback)
        self._subscriptions = []
        for name in self._servers:
            self.ros.action_servers.pop(name, None)
            self.ros.services.pop(name, None)
        self._servers = []


class LocalRos:
    def __init__(self, params: Optional[Params] = None) -> None:
        self.params: Params = params if params is not None else {}
        self.subscribers: Dict[str, List[Callback]] = {}
        self.last: Dict[str, Fields] = {}  # topic -> last published fields
        self.recorded: Dict[str, List[Fields]] = {}  # for the topics passed to record()
        self.action_servers: Dict[str, LocalActionServer] = {}
        self.services: Dict[str, Callable[[Fields], Fields]] = {}

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
