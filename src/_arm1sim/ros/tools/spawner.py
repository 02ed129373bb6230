"""``rosrun arm1 spawner``: controller_manager's spawner, with its arguments and behaviour."""

import argparse
import sys
import threading

import rospy
from controller_manager_msgs.srv import LoadController, SwitchController, UnloadController
from std_msgs.msg import Bool

STRICT = 2


def parse_args(argv):
    parser = argparse.ArgumentParser(
        prog='spawner',
        description=('Loads and starts controllers; on shutdown stops and unloads them.'),
    )
    parser.add_argument('controllers', nargs='+')
    parser.add_argument('--stopped', action='store_true', help='load but do not start')
    parser.add_argument('--wait-for', metavar='TOPIC', help='wait for this topic first')
    parser.add_argument('--namespace', default='', help='namespace of the controller manager')
    parser.add_argument(
        '--timeout',
        type=float,
        default=30.0,
        help='seconds to wait for the controller manager (default 30)',
    )
    parser.add_argument('--no-timeout', action='store_true', help='wait for it forever')
    parser.add_argument('--shutdown-timeout', type=float, default=2.0)
    return parser.parse_args(argv)


class Spawner:
    def __init__(self, args):
        ns = args.namespace.rstrip('/')
        base = (ns + '/' if ns else '') + 'controller_manager/'
        self.names = {
            s: base + s for s in ('load_controller', 'unload_controller', 'switch_controller')
        }
        self.args = args
        self.loaded = []

    def wait_for_manager(self):
        timeout = None if self.args.no_timeout else self.args.timeout
        for name in self.names.values():
            rospy.loginfo('Controller Spawner: Waiting for service %s', rospy.resolve_name(name))
            try:
                rospy.wait_for_service(name, timeout)
            except rospy.ROSException:
                rospy.logerr(
                    "Controller Spawner couldn't find the expected controller_manager ROS "
                    'interface (%s not offered within %.0f s).',
                    rospy.resolve_name(name),
                    timeout,
                )
                return False
        self.load = rospy.ServiceProxy(self.names['load_controller'], LoadController)
        self.unload = rospy.ServiceProxy(self.names['unload_controller'], UnloadController)
        self.switch = rospy.ServiceProxy(self.names['switch_controller'], SwitchController)
        return True

    def spawn(self):
        try:
            self._spawn()
        except (rospy.ServiceException, rospy.ROSException) as exc:
            # e.g. the model was deleted while its controllers were being loaded
            rospy.logerr('Controller Spawner: the controller manager went away: %s', exc)

    def _spawn(self):
        for name in self.args.controllers:
            rospy.loginfo('Loading controller: %s', name)
            if self.load(name).ok:
                self.loaded.append(name)
            else:
                rospy.logerr('Failed to load %s', name)
        rospy.loginfo('Controller Spawner: Loaded controllers: %s', ', '.join(self.loaded))
        if self.loaded and not self.args.stopped:
            if self.switch(self.loaded, [], STRICT, False, 0.0).ok:
                rospy.loginfo('Started controllers: %s', ', '.join(self.loaded))
            else:
                rospy.logerr('Failed to start controllers: %s', ', '.join(self.loaded))

    def shutdown(self):
        if not self.loaded:
            return
        rospy.loginfo('Shutting down spawner. Stopping and unloading controllers...')
        try:
            if not self.args.stopped:
                self.switch([], self.loaded, STRICT, False, self.args.shutdown_timeout)
            for name in reversed(self.loaded):
                self.unload(name)
        except (rospy.ServiceException, rospy.ROSException) as exc:
            rospy.logwarn('Controller Spawner: controller manager gone: %s', exc)


def wait_for_true(topic):
    """As upstream's --wait-for: until a std_msgs/Bool on ``topic`` says True (franka_gazebo's
    ``initialized`` says False first); warns once if nothing is heard in 30 s of sim time."""
    heard = threading.Event()
    ready = threading.Event()

    def on_message(msg):
        heard.set()
        if msg.data:
            ready.set()

    sub = rospy.Subscriber(topic, Bool, on_message)
    started = rospy.get_time()
    warned = False
    try:
        while not ready.wait(0.01):
            if rospy.is_shutdown():
                return False
            if not warned and not heard.is_set() and rospy.get_time() - started > 30:
                warned = True
                rospy.logwarn(
                    'Controller Spawner hasn\'t heard anything from its "wait for" topic (%s)',
                    topic,
                )
    finally:
        sub.unregister()
    return True


def main(argv=None):
    args = parse_args(rospy.myargv(sys.argv if argv is None else argv)[1:])
    rospy.init_node('spawner', anonymous=True)
    spawner = Spawner(args)
    if args.wait_for:
        rospy.loginfo('Controller Spawner: Waiting for topic %s', args.wait_for)
        if not wait_for_true(args.wait_for):
            return 1
    if not spawner.wait_for_manager():
        return 1
    rospy.on_shutdown(spawner.shutdown)
    spawner.spawn()
    rospy.spin()
    return 0
