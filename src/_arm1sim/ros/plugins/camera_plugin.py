"""gazebo_ros_camera for the stand-in: a camera sensor's frames as sensor_msgs Image and CameraInfo.

The world (physics.sensor_manager) renders only while ``image_raw`` has a
subscriber; ``camera_info`` alone is published at the sensor's rate without
rendering. Frames arrive on the world's physics thread, stamped with the sim
time they show; they are published from a thread of the camera's own, so that
serializing a large frame (108 MB at 6000x6000) never holds the physics.
"""

from __future__ import annotations

import collections
import struct
import threading
from typing import Any, Callable, Deque, List, Protocol, Tuple

import rospy
from sensor_msgs.msg import CameraInfo, Image

from ...description.camera_sensor import CameraSensor
from ...physics.camera_geometry import intrinsics
from ...physics.sensor_manager import Camera, Pixels
from ..common.stamps import to_time
from .frames import tf_prefix, tf_resolve

MAX_PENDING_IMAGES = 2  # frames waiting for the publishing thread; older ones are dropped
CHUNK = 1 << 20  # bytes of pixels serialized at a time


class FrameViewer(Protocol):
    """An in-process viewer of a camera's frames, shown a few a second."""

    def due(self) -> bool: ...  # asked on the physics thread: render a frame for me?

    def show(self, stamp_ns: int, data: Pixels) -> None: ...


def camera_frame(sensor: CameraSensor) -> str:
    """gazebo_ros_camera_utils' frame id: tf_prefix searched from ``<ns>/<cameraName>``, else the
    robot namespace, in front of frameName."""
    search = '/'.join(s.strip('/') for s in (sensor.robot_namespace, sensor.camera_name))
    return tf_resolve(tf_prefix(search, sensor.robot_namespace), sensor.frame_name)


def camera_info(sensor: CameraSensor, frame_id: str) -> CameraInfo:
    """The CameraInfo of an ideal pinhole with the sensor's size and field of view."""
    k, proj = intrinsics(sensor.width, sensor.height, sensor.horizontal_fov)
    msg = CameraInfo(
        height=sensor.height,
        width=sensor.width,
        distortion_model='plumb_bob',
        D=[0.0] * 5,
        K=k,
        R=[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
        P=proj,
    )
    msg.header.frame_id = frame_id
    return msg


class ChunkedImage(Image):
    """sensor_msgs/Image (same type and wire format) whose pixels are serialized in slices.

    genpy writes ``data`` with one struct.pack and one write, two C calls that keep
    the GIL for tens of milliseconds on a large frame; between slices the physics
    thread gets it back.
    """

    def serialize(self, buff: Any) -> None:
        serialize_chunked(self, super().serialize, buff, b'')  # data is Image's last field


def serialize_chunked(msg: Any, serialize: Callable[[Any], None], buff: Any, tail: bytes) -> None:
    """``serialize`` (the message type's own) run with an empty ``data``, then the real
    length and ``data`` written over its end in CHUNK slices; ``tail``: the fields the type
    writes after ``data``, written again after it."""
    data: Any = getattr(msg, 'data')
    msg.data = b''
    try:
        serialize(buff)  # everything up to a data length of 0, then the tail
    finally:
        msg.data = data
    buff.seek(buff.tell() - 4 - len(tail))
    buff.write(struct.pack('<I', len(data)))
    view = memoryview(data)
    for start in range(0, len(view), CHUNK):
        buff.write(view[start : start + CHUNK])
    buff.write(tail)


class GazeboRosCamera:
    def __init__(self, camera: Camera) -> None:
        """``camera`` is a physics.sensor_manager.Camera of a spawned model."""
        self.sensor = sensor = camera.sensor
        self._camera = camera
        # A viewer more than 5 frames behind loses the oldest (ROS's way; Gazebo keeps 2).
        self._image_pub = rospy.Publisher(sensor.image_topic, Image, queue_size=5)
        self._info_pub = rospy.Publisher(sensor.camera_info_topic, CameraInfo, queue_size=5)
        self.frame_id = camera_frame(sensor)
        self._info = camera_info(sensor, self.frame_id)
        self._pending: Deque[Tuple[str, int, Pixels]] = collections.deque()
        self._cond = threading.Condition()
        self._running = True
        self.dropped = 0  # frames the publishing thread was too slow for
        # In-process viewers (the browser view), shown frames on the publishing thread
        # without a copy through a socket; a frame is rendered for them only when one is due.
        self.viewers: List[FrameViewer] = []
        self._thread = threading.Thread(
            target=self._run, daemon=True, name='camera-%s' % sensor.name
        )
        self._thread.start()
        camera.wants_image = lambda: (
            self._image_pub.get_num_connections() > 0 or any(v.due() for v in list(self.viewers))
        )
        camera.wants_info = lambda: self._info_pub.get_num_connections() > 0
        camera.on_image = self._queue_image
        camera.on_info = self._queue_info

    # -- physics thread: hand over, never wait -------------------------------------------
    def _queue_image(self, stamp_ns: int, data: Pixels) -> None:
        with self._cond:
            images = [item for item in self._pending if item[0] == 'image']
            if len(images) >= MAX_PENDING_IMAGES:
                self._pending.remove(images[0])
                self.dropped += 1
            self._pending.append(('image', stamp_ns, data))
            self._cond.notify()

    def _queue_info(self, stamp_ns: int) -> None:
        with self._cond:
            self._pending.append(('info', stamp_ns, b''))
            self._cond.notify()

    # -- publishing thread ---------------------------------------------------------------
    def _run(self) -> None:
        while True:
            with self._cond:
                self._cond.wait_for(lambda: self._pending or not self._running)
                if not self._running:
                    return
                kind, stamp_ns, data = self._pending.popleft()
            try:
                if kind == 'image':
                    for viewer in list(self.viewers):
                        if viewer.due():
                            viewer.show(stamp_ns, data)
                    # always: a depth camera's override publishes its depth and points here
                    self.publish_image(stamp_ns, data)
                else:
                    self.publish_info(stamp_ns)
            except rospy.ROSException:  # the topic closed: shut down, or the model deleted
                if not self._running or rospy.is_shutdown():
                    return
                raise

    def publish_image(self, stamp_ns: int, data: Pixels) -> None:
        s = self.sensor
        msg = ChunkedImage(
            height=s.height,
            width=s.width,
            encoding=s.encoding,
            is_bigendian=0,
            step=s.step,
            data=data,
        )
        msg.header.stamp = to_time(stamp_ns)
        msg.header.frame_id = self.frame_id
        self._image_pub.publish(msg)
        self.publish_info(stamp_ns)

    def publish_info(self, stamp_ns: int) -> None:
        self._info.header.stamp = to_time(stamp_ns)
        self._info_pub.publish(self._info)

    def shutdown(self) -> None:
        """Stop publishing (without waiting for a frame being published) and unadvertise."""
        cam = self._camera
        cam.on_image = cam.on_info = None
        cam.wants_image = cam.wants_info = lambda: False
        self.viewers = []
        with self._cond:
            self._running = False
            self._pending.clear()
            self._cond.notify()
        self._image_pub.unregister()
        self._info_pub.unregister()
