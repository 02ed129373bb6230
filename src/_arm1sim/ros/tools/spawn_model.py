"""``rosrun arm1 spawn_model``: gazebo_ros's spawn_model, against the stand-in world."""

import argparse
import sys
import time

import rospy
from gazebo_msgs.srv import SetModelConfiguration, SpawnModel
from geometry_msgs.msg import Pose
from std_srvs.srv import Empty

from ...description.pose_math import quat_from_rpy


def parse_args(argv):
    parser = argparse.ArgumentParser(
        prog='spawn_model',
        description=(
            'Spawn a URDF or SDF model into the stand-in world (gazebo_ros spawn_model arguments).'
        ),
    )
    source = parser.add_mutually_exclusive_group(required=True)
    source.add_argument('-param', help='parameter holding the model (e.g. robot_description)')
    source.add_argument('-file', help='model file')
    source.add_argument(
        '-database', help='model NAME found on GAZEBO_MODEL_PATH (model://NAME), spawned as SDF'
    )
    kind = parser.add_mutually_exclusive_group()
    kind.add_argument('-urdf', action='store_true', help='the model is URDF (the default)')
    kind.add_argument('-sdf', action='store_true', help='the model is SDF (spawn_sdf_model)')
    parser.add_argument('-model', required=True, help='model name')
    for axis in ('x', 'y', 'z', 'R', 'P', 'Y'):
        parser.add_argument('-' + axis, type=float, default=0.0)
    parser.add_argument(
        '-J',
        nargs=2,
        action='append',
        default=[],
        metavar=('JOINT', 'VALUE'),
        help='initial joint position (repeatable)',
    )
    parser.add_argument(
        '-robot_namespace',
        default=None,
        help="namespace for plugins without <robotNamespace> (default: this node's, e.g. /)",
    )
    parser.add_argument('-reference_frame', default='')
    parser.add_argument('-gazebo_namespace', default='/gazebo')
    parser.add_argument('-unpause', action='store_true')
    parser.add_argument('-wait', help='ignored (waits for a model in Gazebo)')
    parser.add_argument(
        '-timeout',
        type=float,
        default=60.0,
        help='seconds to wait for the parameter and the world (default 60)',
    )
    parser.add_argument('-package_to_model', action='store_true', help='ignored')
    return parser.parse_args(argv)


def wait_for_param(name, timeout):
    deadline = time.monotonic() + timeout
    announced = False
    while not rospy.is_shutdown():
        if rospy.has_param(name):
            return rospy.get_param(name)
        if time.monotonic() >= deadline:
            return None
        if not announced:
            rospy.loginfo(
                'spawn_model: waiting for parameter %s (up to %.0f s)',
                rospy.resolve_name(name),
                timeout,
            )
            announced = True
        time.sleep(0.1)
    return None


def main(argv=None):
    args = parse_args(rospy.myargv(sys.argv if argv is None else argv)[1:])
    rospy.init_node('spawn_model', anonymous=True)
    if args.robot_namespace is None:
        args.robot_namespace = rospy.get_namespace()  # as upstream: the caller's, '/' at top
    if args.database:
        # as upstream: a world that includes the model, for spawn_sdf_model
        args.sdf = True
        xml = (
            '<?xml version="1.0" ?><sdf version="1.5"><world name="default"><include>'
            '<uri>model://%s</uri></include></world></sdf>' % args.database
        )
    elif args.param:
        xml = wait_for_param(args.param, args.timeout)
        if xml is None:
            rospy.logfatal(
                'spawn_model: gave up after %.0f s waiting for parameter %s: is the '
                'robot description loaded?',
                args.timeout,
                rospy.resolve_name(args.param),
            )
            return 1
    else:
        try:
            with open(args.file) as f:
                xml = f.read()
        except OSError as exc:
            rospy.logfatal('spawn_model: cannot read %s: %s', args.file, exc.strerror)
            return 1
    ns = args.gazebo_namespace.rstrip('/')
    spawn_name = ns + ('/spawn_sdf_model' if args.sdf else '/spawn_urdf_model')
    rospy.loginfo('spawn_model: waiting for service %s', spawn_name)
    try:
        rospy.wait_for_service(spawn_name, args.timeout)
    except rospy.ROSException:
        rospy.logfatal(
            'spawn_model: gave up after %.0f s waiting for service %s: is the world running?',
            args.timeout,
            spawn_name,
        )
        return 1
    pose = Pose()
    pose.position.x, pose.position.y, pose.position.z = args.x, args.y, args.z
    q = quat_from_rpy(args.R, args.P, args.Y)
    pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w = q
    resp = rospy.ServiceProxy(spawn_name, SpawnModel)(
        args.model, xml, args.robot_namespace, pose, args.reference_frame
    )
    if not resp.success:
        rospy.logfatal('spawn_model: %s', resp.status_message)
        return 1
    rospy.loginfo('Spawn status: %s', resp.status_message)
    if args.J:
        try:
            values = [float(v) for _, v in args.J]
        except ValueError:
            rospy.logfatal('spawn_model: -J takes a joint name and a number')
            return 1
        resp = rospy.ServiceProxy(ns + '/set_model_configuration', SetModelConfiguration)(
            args.model, args.param or '', [j for j, _ in args.J], values
        )
        if not resp.success:
            rospy.logfatal('spawn_model: %s', resp.status_message)
            return 1
    if args.unpause:
        rospy.ServiceProxy(ns + '/unpause_physics', Empty)()
    return 0
