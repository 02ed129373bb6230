"""An in-process stand-in for the parameter server and topics, so that the real
ControllerManager and controllers run without a ROS master (see control/controller.py
for the node-handle contract they use).

Parameters are a plain dict tree (what ``rosparam load controllers.yaml`` would put
on the server); ``publish(topic, value)`` delivers to subscribers at once; the last
message of each advertised topic is kept (and every message, for topics asked for
with ``record``).
"""


class LocalPublisher:
    __slots__ = ('ros', 'topic', 'type_name')

    def __init__(self, ros, topic, type_name):
        self.ros, self.topic, self.type_name = ros, topic, type_name

    def publish(self, fields):
        self.ros.last[self.topic] = fields
        log = self.ros.recorded.get(self.topic)
        if log is not None:
            log.append(fields)


class LocalNodeHandle:
    def __init__(self, ros, namespace):
        self.ros = ros
        self.namespace = namespace.rstrip('/') or '/'
        self.params = ros.get_param(self.namespace)
        self._subscriptions = []

    def resolve(self, topic):
        return topic if topic.startswith('/') else '%s/%s' % (self.namespace.rstrip('/'), topic)

    def advertise(self, topic, type_name, queue_size):
        return LocalPublisher(self.ros, self.resolve(topic), type_name)

    def subscribe(self, topic, type_name, callback):
        name = self.resolve(topic)
        self.ros.subscribers.setdefault(name, []).append(callback)
        self._subscriptions.append((name, callback))
        return callback

    def shutdown(self):
        for name, callback in self._subscriptions:
            self.ros.subscribers[name].remove(callback)
        self._subscriptions = []


class LocalRos:
    def __init__(self, params=None):
        self.params = params if params is not None else {}
        self.subscribers = {}  # topic -> [callback]
        self.last = {}  # topic -> last published fields
        self.recorded = {}  # topic -> [fields], for the topics passed to record()

    def get_param(self, namespace):
        node = self.params
        for part in [p for p in namespace.split('/') if p]:
            if not isinstance(node, dict) or part not in node:
                return {}
            node = node[part]
        return node if isinstance(node, dict) else {}

    def node_handle(self, namespace):
        """The ``node_factory`` a ControllerManager takes."""
        return LocalNodeHandle(self, namespace)

    def publish(self, topic, value):
        """Deliver to every subscriber of ``topic``; returns how many got it."""
        callbacks = list(self.subscribers.get(topic, ()))
        for callback in callbacks:
            callback(value)
        return len(callbacks)

    def record(self, topic):
        """Keep every message published on ``topic`` from now on; returns the list."""
        return self.recorded.setdefault(topic, [])
