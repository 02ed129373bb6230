"""The world node: gazebo_ros's API (``/clock``, ``/gazebo/*`` services) around a Simulation.

Physics runs on the main thread. Service calls arrive on rospy's threads and are
handed to the main thread between two steps, so pybullet is only touched there.
"""
import argparse
import collections
import sys
import threading
import time

import rosgraph.names
import rospkg
import rospy
import rospy.impl.simtime
from rosgraph_msgs.msg import Clock
from std_msgs.msg import Float64
from std_srvs.srv import Empty

from arm1.srv import DeleteModel, SetModelConfiguration, SpawnModel

from ..pacer import Pacer, RealTimeFactorMeter, wall_period
from ..physics.limits import LimitError, Limits
from ..physics.names import shown
from ..physics.sdf_world import SdfError, WorldConfig, read_world
from ..simulation import Simulation, SpawnError
from .camera_plugin import GazeboRosCamera
from .controller_manager_interface import ControllerManagerInterface
from .master_watch import MasterWatch
from .node_handle import route_core_logs, synchronous_publisher, to_time


MIN_CLOCK_WALL_PERIOD = 0.001  # s: the most /clock messages a wall second gets is 1000


class PackageFinder:
    def __init__(self):
        self._rospack = rospkg.RosPack()

    def __call__(self, name):
        try:
            return self._rospack.get_path(name)
        except rospkg.ResourceNotFound:
            raise LookupError(name)


class GazeboRosApi:
    def __init__(self, sim, paused=False):
        self.sim = sim
        self.paused = paused
        self._calls = collections.deque()
        self._find_package = PackageFinder()
        self.clock_period_ns = int(1e9 / max(1e-3, float(rospy.get_param('~pub_clock_frequency', 100))))
        self._clock_pub = synchronous_publisher('/clock', Clock)
        self._own_clock = self._stop_listening_to_own_clock()
        self._rtf_pub = rospy.Publisher('~real_time_factor', Float64, queue_size=1, latch=True)
        self.rtf = RealTimeFactorMeter()
        self._services = [
            rospy.Service('~pause_physics', Empty, self._empty(self._set_paused, True)),
            rospy.Service('~unpause_physics', Empty, self._empty(self._set_paused, False)),
            rospy.Service('~reset_simulation', Empty, self._empty(self.sim.reset_simulation)),
            rospy.Service('~reset_world', Empty, self._empty(self.sim.reset_world)),
            rospy.Service('~spawn_urdf_model', SpawnModel, self._spawn),
            rospy.Service('~delete_model', DeleteModel, self._delete),
            rospy.Service('~set_model_configuration', SetModelConfiguration, self._configure),
        ]

    # -- services: run on rospy threads, work on the main thread -------------------
    def call_in_sim_thread(self, fn, *args):
        done, box = threading.Event(), []

        def run():
            try:
                box.append((True, fn(*args)))
            except Exception as exc:  # handed back to the caller's thread
                box.append((False, exc))
            done.set()
        self._calls.append(run)
        while not done.wait(0.5):
            if rospy.is_shutdown():
                raise rospy.ServiceException('simulation shut down')
        ok, value = box[0]
        if not ok:
            raise value
        return value

    def _empty(self, fn, *args):
        def handler(req):
            self.call_in_sim_thread(fn, *args)
            return []
        return handler

    def _set_paused(self, paused):
        self.paused = paused

    def _spawn(self, req):
        pose = req.initial_pose
        xyz = (pose.position.x, pose.position.y, pose.position.z)
        q = (pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w)
        if q == (0, 0, 0, 0):
            q = (0, 0, 0, 1)
        try:
            model = self.spawn(req.model_name, req.model_xml, xyz, q, req.robot_namespace)
        except SpawnError as exc:
            rospy.logerr(str(exc))
            return False, str(exc)
        msg = "SpawnModel: Successfully spawned entity '%s'" % model.name
        if model.controller_manager is not None:
            msg += ' with controller manager in %s' % model.namespace
        for c in model.cameras:
            msg += '; camera %s on %s' % (c.sensor.name, c.sensor.image_topic)
        rospy.loginfo(msg)
        return True, msg

    def spawn(self, name, xml, xyz, quat, namespace=''):
        """Spawn a URDF model with its plugins (controller manager, cameras).

        The request is parsed and checked on the calling thread; only what changes the
        world runs on the sim thread, so a large document does not hold physics back.
        """
        if namespace and not rosgraph.names.is_legal_name(namespace):
            raise SpawnError("cannot spawn '%s': robot_namespace %s is not a legal ROS name"
                             % (name, shown(namespace)))
        prepared = self.sim.prepare_urdf(name, xml, xyz, quat, self._find_package)
        if threading.current_thread() is threading.main_thread():
            return self._spawn_prepared(prepared, namespace)
        return self.call_in_sim_thread(self._spawn_prepared, prepared, namespace)

    def _spawn_prepared(self, prepared, namespace):
        return self.sim.spawn_prepared(prepared, namespace, attach=self._attach_plugins)

    @staticmethod
    def _attach_plugins(model):
        """The ROS side of a model's plugins; each goes into the model's record."""
        if model.hw is not None:
            if not rosgraph.names.is_legal_name(model.namespace):
                raise SpawnError('controller manager namespace %s is not a legal ROS name'
                                 % shown(model.namespace))
            interface = ControllerManagerInterface(model.hw, model.namespace)
            model.controller_manager = interface.manager
            model.plugins.append(interface)
        for camera in model.cameras:
            model.plugins.append(GazeboRosCamera(camera))

    def _delete(self, req):
        try:
            self.call_in_sim_thread(self.sim.delete_model, req.model_name)
        except SpawnError as exc:
            return False, str(exc)
        return True, "DeleteModel: successfully deleted model '%s'" % req.model_name

    def _configure(self, req):
        try:
            self.call_in_sim_thread(self.sim.set_model_configuration, req.model_name,
                                    list(req.joint_names), list(req.joint_positions))
        except SpawnError as exc:
            return False, str(exc)
        return True, 'SetModelConfiguration: success'

    # -- main thread ------------------------------------------------------------
    def publish_clock(self):
        now = to_time(self.sim.time_ns)
        self._clock_pub.publish(Clock(now))
        if self._own_clock:
            rospy.rostime._set_rostime(now)  # this node's own sim time, without the round trip

    @staticmethod
    def _stop_listening_to_own_clock():
        """With use_sim_time, rospy subscribes this node to /clock: to its own messages.

        Receiving each one back costs a thread wake-up and the GIL on the physics
        thread; the world sets its own time instead. Returns True when it did.
        """
        sub = getattr(rospy.impl.simtime, '_clock_sub', None)  # only set with use_sim_time
        if sub is None:
            return False
        sub.unregister()
        rospy.impl.simtime._clock_sub = None
        return True

    def run(self, pacer):
        """Step until ROS shuts down."""
        try:
            self._loop(pacer)
        except rospy.ROSException:
            if not rospy.core.is_shutdown_requested():
                raise  # publishing raises once shutdown has begun closing the topics

    def _loop(self, pacer):
        sim, calls, clock_period = self.sim, self._calls, self.clock_period_ns
        last_clock, last_clock_wall = None, 0.0
        self.publish_clock()
        while not rospy.core.is_shutdown_requested():
            while calls:
                calls.popleft()()
            if self.paused:
                self.rtf.pause()
                time.sleep(0.001)
                pacer.restart()
                last_clock = None
                continue
            sim.step()
            now = sim.time_ns
            # Faster than real time, one /clock per MIN_CLOCK_WALL_PERIOD is enough: at 50x
            # that is still every 50 ms of sim time, fine for a rospy.Rate(10).
            if last_clock is None or now < last_clock or (
                    now - last_clock >= clock_period
                    and time.perf_counter() - last_clock_wall >= MIN_CLOCK_WALL_PERIOD):
                self.publish_clock()
                last_clock, last_clock_wall = now, time.perf_counter()
                if self.rtf.update(now * 1e-9):
                    self._rtf_pub.publish(self.rtf.value)
            pacer.wait()


def parse_args(argv):
    parser = argparse.ArgumentParser(prog='gzserver', description=(
        'pybullet stand-in for gzserver with gazebo_ros: runs the world file, publishes /clock '
        'and offers the /gazebo services.'))
    parser.add_argument('world', nargs='?', help='SDF world file (default: an empty world)')
    parser.add_argument('-u', '--paused', action='store_true', help='start with physics paused')
    parser.add_argument('--gui', action='store_true', help="open pybullet's window if a display exists")
    parser.add_argument('-e', '--physics', default='ode', help='ignored: pybullet is the engine')
    parser.add_argument('--verbose', action='store_true')
    parser.add_argument('--lockstep', action='store_true', help=(
        'physics waits for every camera frame (deterministic; the real-time factor drops '
        'instead of the image rate)'))
    parser.add_argument('--real-time-factor', type=float, help='overrides the world file')
    parser.add_argument('--real-time-update-rate', type=float, help='overrides the world file')
    return parser.parse_args(argv)


def start_world(args):
    """Init the node and build the world of parsed gzserver ``args``: (api, pacer)."""
    rospy.init_node('gazebo')
    route_core_logs()
    MasterWatch()  # a restarted master learns the world's topics and services again
    try:
        config = read_world(args.world) if args.world else WorldConfig()
    except SdfError as exc:
        rospy.logfatal(str(exc))
        sys.exit(1)
    config.lockstep = args.lockstep
    try:
        config.limits = Limits.from_mapping(rospy.get_param('~limits', {}),
                                            rospy.resolve_name('~limits'), config.limits)
    except LimitError as exc:
        rospy.logfatal(str(exc))
        sys.exit(1)
    for attr in ('real_time_factor', 'real_time_update_rate'):
        if getattr(args, attr) is not None:
            setattr(config, attr, getattr(args, attr))
    if config.skipped:
        rospy.logwarn('world: not built: %s', '; '.join('%s (%s)' % s for s in config.skipped))
    api = GazeboRosApi(Simulation(config, gui=args.gui), paused=args.paused)
    period = wall_period(config.max_step_size, config.real_time_factor,
                         config.real_time_update_rate)
    rospy.loginfo('world ready: step %.4f s, real-time factor %g, update rate %g Hz%s',
                  config.max_step_size, config.real_time_factor, config.real_time_update_rate,
                  ' (paused)' if args.paused else '')
    return api, Pacer(period)


def main(argv=None):
    api, pacer = start_world(parse_args(rospy.myargv(sys.argv if argv is None else argv)[1:]))
    try:
        api.run(pacer)
    finally:
        api.sim.close()
