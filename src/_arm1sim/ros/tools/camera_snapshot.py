"""camera_snapshot: saves a camera's next frame as a PNG file (to look at on a headless machine).

rosrun arm1 camera_snapshot [FILE.png] [--topic /rgb_camera/image_raw]
"""

import argparse
import sys

import rospy
from sensor_msgs.msg import Image

from ...goal.image import PNG_TYPES, png


def main(argv=None):
    argv = rospy.myargv(sys.argv if argv is None else argv)[1:]
    parser = argparse.ArgumentParser(prog='camera_snapshot', description=__doc__.split('\n')[0])
    parser.add_argument('file', nargs='?', default='camera.png')
    parser.add_argument('--topic', default='/rgb_camera/image_raw')
    parser.add_argument('--timeout', type=float, default=30.0, help='wall seconds to wait')
    args = parser.parse_args(argv)
    rospy.init_node('camera_snapshot', anonymous=True)
    try:
        msg = rospy.wait_for_message(args.topic, Image, args.timeout)
    except rospy.ROSException:
        sys.stderr.write('camera_snapshot: no image on %s in %g s\n' % (args.topic, args.timeout))
        return 1
    if msg.encoding not in PNG_TYPES:
        sys.stderr.write('camera_snapshot: cannot save %s images\n' % msg.encoding)
        return 1
    with open(args.file, 'wb') as f:
        f.write(png(msg.data, msg.width, msg.height, msg.step, msg.encoding))
    print(
        '%s: %dx%d %s from %s at t = %.3f s'
        % (args.file, msg.width, msg.height, msg.encoding, args.topic, msg.header.stamp.to_sec())
    )
    return 0
