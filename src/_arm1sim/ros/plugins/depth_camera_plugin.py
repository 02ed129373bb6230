"""gazebo_ros_openni_kinect and gazebo_ros_depth_camera for the stand-in: a depth camera's
frames as the RGB Image and CameraInfo (``ir/...`` by default), a depth Image (32FC1 metres,
or 16UC1 millimetres) with its CameraInfo, and an organised PointCloud2.

Same design as ros.camera_plugin's GazeboRosCamera: the world renders only while the image,
the depth image or the point cloud has a subscriber; the camera infos alone are published at
the sensor's rate without rendering; frames are converted and published on the camera's own
thread, never on the physics thread. Each output is built only while it has a subscriber.
"""

from __future__ import annotations

import struct
from typing import Any

import rospy
from sensor_msgs.msg import CameraInfo, Image, PointCloud2, PointField

from ...physics import depth_camera
from ...physics.sensor_manager import Camera, Pixels
from ..common.stamps import to_time
from .camera_plugin import (
    ChunkedImage,
    GazeboRosCamera,
    camera_frame,
    camera_info,
    serialize_chunked,
)


class ChunkedPointCloud2(PointCloud2):
    """sensor_msgs/PointCloud2 (same type and wire format) whose points are serialized in
    slices, so that the physics thread gets the GIL between them (see ChunkedImage)."""

    def serialize(self, buff: Any) -> None:
        is_dense = struct.pack('<B', 1 if self.is_dense else 0)  # the field after data
        serialize_chunked(self, super().serialize, buff, is_dense)


def point_fields() -> list:
    return [
        PointField(name=name, offset=offset, datatype=PointField.FLOAT32, count=1)
        for name, offset in depth_camera.POINT_FIELDS
    ]


def depth_image_message(s: Any, depth: Any) -> ChunkedImage:
    """The depth Image of one frame (header left to the caller)."""
    encoding, step, pixels = depth_camera.depth_image(s, depth)
    return ChunkedImage(
        height=s.height, width=s.width, encoding=encoding, is_bigendian=0, step=step, data=pixels
    )


def point_cloud_message(
    s: Any, fields: list, cloud: depth_camera.PointCloudBuilder, depth: Any, image: Any
) -> ChunkedPointCloud2:
    """The organised PointCloud2 of one frame (header left to the caller)."""
    points, dense = cloud.build(depth, image)
    return ChunkedPointCloud2(
        height=s.height,
        width=s.width,
        fields=fields,
        is_bigendian=False,
        point_step=depth_camera.POINT_STEP,
        row_step=depth_camera.POINT_STEP * s.width,
        data=points,
        is_dense=dense,
    )


class GazeboRosDepthCamera(GazeboRosCamera):
    def __init__(self, camera: Camera) -> None:
        """``camera`` is a depth camera (``sensor.depth_plugin`` set) of a spawned model."""
        s = camera.sensor
        assert s.depth_plugin, 'not a depth camera: %s' % s.name
        # before the base class hands the camera its callbacks, which use these
        self._depth_pub = rospy.Publisher(s.depth_image_topic, Image, queue_size=5)
        self._depth_info_pub = rospy.Publisher(
            s.depth_image_camera_info_topic, CameraInfo, queue_size=5
        )
        self._points_pub = rospy.Publisher(s.point_cloud_topic, PointCloud2, queue_size=5)
        self._depth_info = camera_info(s, camera_frame(s))
        self._fields = point_fields()
        self._cloud = depth_camera.PointCloudBuilder(s)  # its buffer: rospy serializes at publish
        super().__init__(camera)
        renders = (self._image_pub, self._depth_pub, self._points_pub)
        infos = (self._info_pub, self._depth_info_pub)
        camera.wants_image = lambda: any(pub.get_num_connections() > 0 for pub in renders)
        camera.wants_info = lambda: any(pub.get_num_connections() > 0 for pub in infos)

    # -- publishing thread ---------------------------------------------------------------
    def publish_image(self, stamp_ns: int, data: Pixels) -> None:
        s = self.sensor
        image, depth = depth_camera.split_frame(s, data)
        if self._image_pub.get_num_connections() > 0:
            super().publish_image(stamp_ns, image)  # with both camera infos
        else:
            self.publish_info(stamp_ns)
        stamp = to_time(stamp_ns)
        if self._depth_pub.get_num_connections() > 0:
            msg = depth_image_message(s, depth)
            msg.header.stamp = stamp
            msg.header.frame_id = self.frame_id
            self._depth_pub.publish(msg)
        if self._points_pub.get_num_connections() > 0:
            cloud = point_cloud_message(s, self._fields, self._cloud, depth, image)
            cloud.header.stamp = stamp
            cloud.header.frame_id = self.frame_id
            self._points_pub.publish(cloud)

    def publish_info(self, stamp_ns: int) -> None:
        super().publish_info(stamp_ns)
        if self._depth_info_pub.get_num_connections() > 0:
            self._depth_info.header.stamp = to_time(stamp_ns)
            self._depth_info_pub.publish(self._depth_info)

    def shutdown(self) -> None:
        super().shutdown()
        for pub in (self._depth_pub, self._depth_info_pub, self._points_pub):
            pub.unregister()
