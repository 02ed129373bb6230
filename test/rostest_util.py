"""Helpers the rostest nodes share: collecting messages and waiting in sim or wall time."""

import threading
import time
import unittest

import rospy
from controller_manager_msgs.srv import ListControllers
from gazebo_msgs.srv import SpawnModel
from geometry_msgs.msg import Point, Pose, Quaternion
from rosgraph_msgs.msg import Clock, Log
from sensor_msgs.msg import JointState

JOINTS = ['joint1', 'joint2', 'joint3', 'joint4']


class Recorder:
    """Keeps every message of a topic (with its wall arrival time)."""

    def __init__(self, topic, msg_type):
        self.lock = threading.Lock()
        self.msgs = []
        self.sub = rospy.Subscriber(topic, msg_type, self._cb, queue_size=1000)

    def _cb(self, msg):
        with self.lock:
            self.msgs.append((time.monotonic(), msg))

    def since(self, wall_time):
        with self.lock:
            return [m for t, m in self.msgs if t >= wall_time]

    def last(self):
        with self.lock:
            return self.msgs[-1][1] if self.msgs else None

    def clear(self):
        with self.lock:
            self.msgs = []

    def last_sim_seconds(self, span):
        """The stamped messages of the newest ``span`` s of sim time, oldest first: back from
        the newest while the stamps stay within ``span`` of it (and do not jump forward, as
        they do across a reset). Judged by stamps, so a busy machine's slower world gives the
        same messages."""
        with self.lock:
            msgs = [m for _, m in self.msgs]
        recent = []
        for m in reversed(msgs):
            age = (msgs[-1].header.stamp - m.header.stamp).to_sec()
            if not 0.0 <= age <= span:
                break
            recent.append(m)
        return recent[::-1]


def wait_for(predicate, timeout, poll=0.05):
    """Wall-clock wait until predicate() is true; returns its last value."""
    deadline = time.monotonic() + timeout
    value = predicate()
    while not value and time.monotonic() < deadline:
        time.sleep(poll)
        value = predicate()
    return value


def clock_recorder():
    return Recorder('/clock', Clock)


def joint_recorder(ns='/arm1'):
    return Recorder(ns + '/joint_states', JointState)


def rosout_recorder():
    return Recorder('/rosout', Log)


def positions(msg):
    return dict(zip(msg.name, msg.position))


def sim_wait(seconds):
    """Sleep in sim time, but never longer than 20x that in wall time."""
    start = rospy.Time.now()
    wait_for(lambda: (rospy.Time.now() - start).to_sec() >= seconds, 20 * seconds + 5)


def wait_for_controllers(count=5, ns='/arm1', timeout=60):
    """Wait until ``count`` controllers run in ``ns``; returns the list_controllers proxy."""
    name = ns + '/controller_manager/list_controllers'
    rospy.wait_for_service(name, timeout)
    list_controllers = rospy.ServiceProxy(name, ListControllers)

    def running():
        return sum(c.state == 'running' for c in list_controllers().controller)

    assert wait_for(lambda: running() >= count, timeout), (
        'only %d of %d controllers running in %s' % (running(), count, ns)
    )
    return list_controllers


RECORDERS = {'states': joint_recorder, 'clock': clock_recorder, 'rosout': rosout_recorder}
FIRST_MESSAGE = {'states': ('joint_states', 60), 'clock': ('/clock', 30)}  # (what, timeout s)


class WorldTestCase(unittest.TestCase):
    """A rostest against a running world. setUpClass starts the test node NODE, keeps a
    recorder for each name in RECORD ('states', 'clock', 'rosout') as a class attribute of
    that name, waits for each service in SERVICES, for the first message of each recorder
    in FIRST, and for CONTROLLERS controllers running in /arm1 (then ``list_controllers``
    is their proxy). A test class extends it with ``super().setUpClass()``."""

    NODE = ''
    RECORD = ()
    SERVICES = ()
    FIRST = ()
    CONTROLLERS = 0

    @classmethod
    def setUpClass(cls):
        rospy.init_node(cls.NODE)
        for name in cls.RECORD:
            setattr(cls, name, RECORDERS[name]())
        for service in cls.SERVICES:
            rospy.wait_for_service(service, 60)
        for name in cls.FIRST:
            what, timeout = FIRST_MESSAGE[name]
            recorder = getattr(cls, name)
            assert wait_for(lambda: recorder.last() is not None, timeout), 'no ' + what
        if cls.CONTROLLERS:
            cls.list_controllers = wait_for_controllers(cls.CONTROLLERS)


class SpawningTestCase(WorldTestCase):
    """A WorldTestCase in sim time that spawns its models (``spawn_urdf``) in setUpClass."""

    RECORD = ('clock',)
    FIRST = ('clock',)
    SERVICES = ('/gazebo/spawn_urdf_model',)


def spawn_urdf(name, xml, namespace, position):
    """Spawns a URDF model unrotated at ``position`` (x, y, z) in the world frame; asserts
    the world took it."""
    spawn = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
    pose = Pose(Point(*position), Quaternion(0, 0, 0, 1))
    res = spawn(name, xml, namespace, pose, 'world')
    assert res.success, res.status_message
