"""gazebo_ros_camera for the stand-in: a camera sensor's frames as sensor_msgs Image and CameraInfo.

The world (physics.camera) renders only while ``image_raw`` has a subscriber;
``camera_info`` alone is published at the sensor's rate without rendering.
Frames arrive on the world's main thread, stamped with the sim time they show.
"""
import rospy
from sensor_msgs.msg import CameraInfo, Image

from ..physics.camera import intrinsics
from .node_handle import to_time


def camera_info(sensor):
    """The CameraInfo of an ideal pinhole with the sensor's size and field of view."""
    k, proj = intrinsics(sensor.width, sensor.height, sensor.horizontal_fov)
    msg = CameraInfo(height=sensor.height, width=sensor.width, distortion_model='plumb_bob',
                     D=[0.0] * 5, K=k, R=[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0], P=proj)
    msg.header.frame_id = sensor.frame_name
    return msg


class GazeboRosCamera:
    def __init__(self, camera):
        """``camera`` is a physics.camera.Camera of a spawned model."""
        self.sensor = sensor = camera.sensor
        self._camera = camera
        # A viewer more than 5 frames behind loses the oldest (ROS's way; Gazebo keeps 2).
        self._image_pub = rospy.Publisher(sensor.image_topic, Image, queue_size=5)
        self._info_pub = rospy.Publisher(sensor.camera_info_topic, CameraInfo, queue_size=5)
        self._info = camera_info(sensor)
        camera.wants_image = lambda: self._image_pub.get_num_connections() > 0
        camera.wants_info = lambda: self._info_pub.get_num_connections() > 0
        camera.on_image = self.publish_image
        camera.on_info = self.publish_info

    def publish_image(self, stamp_ns, data):
        s = self.sensor
        msg = Image(height=s.height, width=s.width, encoding=s.encoding, is_bigendian=0,
                    step=s.step, data=data)
        msg.header.stamp = to_time(stamp_ns)
        msg.header.frame_id = s.frame_name
        self._image_pub.publish(msg)
        self.publish_info(stamp_ns)

    def publish_info(self, stamp_ns):
        self._info.header.stamp = to_time(stamp_ns)
        self._info_pub.publish(self._info)

    def shutdown(self):
        cam = self._camera
        cam.on_image = cam.on_info = None
        self._image_pub.unregister()
        self._info_pub.unregister()
