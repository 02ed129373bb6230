"""The node handle controllers receive (control/interfaces.py's NodeHandle and
ConfigServer), implemented with rospy; messages.py translates the messages.
"""

from __future__ import annotations

from typing import Any, Callable, Dict, List, Optional

import rosgraph.masterapi
import rospy

from ...control.interfaces import Fields, Params
from ..common.publishers import subscribed, synchronous_publisher
from .action_server import ActionServer
from .messages import Fill, message, service


class _Service:
    def __init__(self, name: str, type_name: str, handler: Callable[[Fields], Fields]) -> None:
        srv_class, read_request = service(type_name)

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


class _Publisher:
    """Fills one message again for each publish: publishing is synchronous (serialised
    before publish returns), so reuse is safe and spares building a message each time."""

    __slots__ = ('pub', 'fill', 'msg')

    def __init__(self, pub: rospy.Publisher, msg_class: type, fill: Fill) -> None:
        self.pub, self.fill, self.msg = pub, fill, msg_class()

    def wanted(self) -> bool:
        return subscribed(self.pub)

    def publish(self, fields: Fields) -> None:
        if subscribed(self.pub):  # build no message nobody reads
            self.fill(self.msg, fields)
            self.pub.publish(self.msg)


def _namespace_params(namespace: str) -> Any:
    """The parameters under ``namespace``, from the master. Not rospy.get_param: its cache
    answers a namespace holding a cached parameter with the cached ones alone (the root '/'
    with rosout's rosout_disable_topics_generation only)."""
    try:
        return rosgraph.masterapi.Master(rospy.get_name()).getParam(namespace)
    except rosgraph.masterapi.Error:  # not set
        return {}


class RosNodeHandle:
    # Called after each message a subscription of a node handle delivers (rospy's thread):
    # the world loop's Pacer.wake, so that a command does not wait out a batched sleep.
    on_message: Optional[Callable[[], None]] = None

    def __init__(self, namespace: str) -> None:
        self.namespace = namespace.rstrip('/') or '/'
        params = _namespace_params(self.namespace)
        self.params: Params = params if isinstance(params, dict) else {}
        self._handles: List[Any] = []  # whatever has unregister(): publishers, subscribers, servers

    def _name(self, topic: str) -> str:
        return topic if topic.startswith('/') else '%s/%s' % (self.namespace.rstrip('/'), topic)

    def advertise(self, topic: str, type_name: str, queue_size: int) -> _Publisher:
        # queue_size is part of the node handle's interface; publishing here is synchronous.
        cls, fill, _ = message(type_name)
        pub = synchronous_publisher(self._name(topic), cls)
        self._handles.append(pub)
        return _Publisher(pub, cls, fill)

    def subscribe(
        self, topic: str, type_name: str, callback: Callable[[Any], object]
    ) -> rospy.Subscriber:
        cls, _, read = message(type_name)

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
    ) -> ActionServer:
        server = ActionServer(self._name(name), type_name, on_goal, on_cancel)
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
