"""Depth cameras: parsing (gazebo_ros_openni_kinect / gazebo_ros_depth_camera defaults), the
depth buffer in metres, depth image and point cloud conversion, and a rendered wall."""

from __future__ import annotations

import math
import os

import numpy as np
import pybullet as p
import pytest
from conftest import REPO_ROOT, box_link

from _arm1sim.description.camera_sensor import (
    DEPTH_CAMERA_PLUGIN,
    OPENNI_KINECT_PLUGIN,
    CameraSensor,
    camera_sensors,
)
from _arm1sim.description.gazebo_plugins import unimplemented
from _arm1sim.description.sdf_world import WorldConfig
from _arm1sim.description.urdf_model import UrdfError, parse_urdf
from _arm1sim.physics import renderers
from _arm1sim.physics.camera_geometry import depth_metres
from _arm1sim.physics.depth_camera import (
    POINT_STEP,
    PointCloudBuilder,
    depth_image,
    focal_length,
    point_cloud,
    split_frame,
)
from _arm1sim.physics.render_process import render
from _arm1sim.sim.plugins import PLUGINS
from _arm1sim.sim.simulation import Simulation

DEPTH_BOT = os.path.join(REPO_ROOT, 'test', 'config', 'depth_bot.urdf')


def robot_with(sensor_xml: str) -> str:
    return '<robot name="r">%s<gazebo reference="body">%s</gazebo></robot>' % (
        box_link('body'),
        sensor_xml,
    )


def sensor_xml(kind: str = 'depth', plugin: str = OPENNI_KINECT_PLUGIN, params: str = '') -> str:
    return (
        '<sensor type="%s" name="kin"><camera><image><width>8</width><height>6</height>'
        '</image></camera><plugin name="k" filename="%s">%s</plugin></sensor>'
        % (kind, plugin, params)
    )


def parse(xml: str) -> CameraSensor:
    (s,) = camera_sensors(parse_urdf(robot_with(xml)))
    return s


# ------------------------------------------------------------------------------ parsing
def test_openni_kinect_defaults_are_upstreams():
    s = parse(sensor_xml(params='<cameraName>cam</cameraName>'))
    assert s.depth_plugin == OPENNI_KINECT_PLUGIN
    assert s.image_topic == '/cam/ir/image_raw'
    assert s.camera_info_topic == '/cam/ir/camera_info'
    assert s.depth_image_topic == '/cam/depth/image_raw'
    assert s.depth_image_camera_info_topic == '/cam/depth/camera_info'
    assert s.point_cloud_topic == '/cam/points'
    assert (s.point_cloud_cutoff, s.point_cloud_cutoff_max) == (0.4, 5.0)
    assert not s.use_depth_16uc1
    assert (s.near, s.far, s.horizontal_fov) == (0.1, 100.0, 1.047)
    assert s.frame_bytes == 8 * 6 * 3 + 8 * 6 * 4  # rgb8 image, then float32 metres


def test_depth_plugin_parameters_are_read():
    s = parse(
        sensor_xml(
            params='<robotNamespace>bot</robotNamespace><cameraName>cam</cameraName>'
            '<imageTopicName>rgb/image_raw</imageTopicName>'
            '<cameraInfoTopicName>rgb/camera_info</cameraInfoTopicName>'
            '<depthImageTopicName>d/img</depthImageTopicName>'
            '<depthImageCameraInfoTopicName>d/info</depthImageCameraInfoTopicName>'
            '<pointCloudTopicName>/cloud</pointCloudTopicName>'
            '<frameName>cam_optical</frameName><pointCloudCutoff>0.2</pointCloudCutoff>'
            '<pointCloudCutoffMax>3.5</pointCloudCutoffMax>'
            '<useDepth16UC1Format>true</useDepth16UC1Format><updateRate>15</updateRate>'
        )
    )
    assert s.image_topic == '/bot/cam/rgb/image_raw'
    assert s.camera_info_topic == '/bot/cam/rgb/camera_info'
    assert s.depth_image_topic == '/bot/cam/d/img'
    assert s.depth_image_camera_info_topic == '/bot/cam/d/info'
    assert s.point_cloud_topic == '/cloud'
    assert s.frame_name == 'cam_optical'
    assert (s.point_cloud_cutoff, s.point_cloud_cutoff_max) == (0.2, 3.5)
    assert s.use_depth_16uc1 and s.update_rate == 15


def test_tutorials_camera_type_with_openni_and_the_depth_camera_plugin():
    s = parse(sensor_xml(kind='camera', params='<pointCloudCutoffMax>3</pointCloudCutoffMax>'))
    assert s.depth_plugin == OPENNI_KINECT_PLUGIN and s.point_cloud_cutoff_max == 3.0
    d = parse(
        sensor_xml(
            plugin=DEPTH_CAMERA_PLUGIN, params='<pointCloudCutoffMax>3</pointCloudCutoffMax>'
        )
    )
    assert d.depth_plugin == DEPTH_CAMERA_PLUGIN
    assert d.point_cloud_cutoff == 0.4 and d.point_cloud_cutoff_max == math.inf  # none upstream
    assert d.image_topic == '/ir/image_raw'


def test_a_plain_camera_stays_a_camera_and_depth_plugins_count_as_implemented():
    s = parse(sensor_xml(kind='camera', plugin='libgazebo_ros_camera.so'))
    assert not s.depth_plugin and s.image_topic == '/image_raw'
    assert s.frame_bytes == 8 * 6 * 3
    for plugin in (OPENNI_KINECT_PLUGIN, DEPTH_CAMERA_PLUGIN):
        assert unimplemented(parse_urdf(robot_with(sensor_xml(plugin=plugin))), 'r', PLUGINS) == []


def test_bad_depth_parameters_are_named():
    with pytest.raises(UrdfError, match='pointCloudCutoff'):
        parse(sensor_xml(params='<pointCloudCutoff>near</pointCloudCutoff>'))
    with pytest.raises(UrdfError, match='useDepth16UC1Format'):
        parse(sensor_xml(params='<useDepth16UC1Format>maybe</useDepth16UC1Format>'))


# ------------------------------------------------------------------------------ conversions
def test_depth_buffer_to_metres():
    near, far = 0.1, 10.0
    z = np.array([[0.1, 0.5, 2.0, 9.99]])
    d = (far / (far - near)) * (1.0 - near / z)  # the projection's window z
    got = depth_metres(d.astype(np.float32), near, far)
    assert got.dtype == np.float32
    assert np.allclose(got, z, rtol=1e-4)
    assert depth_metres(np.ones((1, 2), np.float32), near, far).tolist() == [[math.inf] * 2]


def sensor_3x2(plugin=OPENNI_KINECT_PLUGIN, fmt='R8G8B8', **kw) -> CameraSensor:
    return CameraSensor(
        'k', 'body', width=3, height=2, format=fmt, depth_plugin=plugin, horizontal_fov=1.2, **kw
    )


DEPTH_3X2 = np.array([[1.0, 2.0, 0.3], [6.0, math.inf, 4.0]], np.float32)


def test_depth_image_is_32fc1_metres_with_nan_outside_the_cutoffs():
    s = sensor_3x2()
    encoding, step, data = depth_image(s, DEPTH_3X2)
    assert (encoding, step) == ('32FC1', 12)
    got = np.frombuffer(data, '<f4').reshape(2, 3)
    assert got[0, :2].tolist() == [1.0, 2.0] and got[1, 2] == 4.0
    assert np.isnan([got[0, 2], got[1, 0], got[1, 1]]).all()  # under 0.4, over 5, nothing hit
    # gazebo_ros_depth_camera: no maximum; +inf and 6 m are kept
    _, _, data = depth_image(
        sensor_3x2(DEPTH_CAMERA_PLUGIN, point_cloud_cutoff_max=math.inf), DEPTH_3X2
    )
    got = np.frombuffer(data, '<f4').reshape(2, 3)
    assert got[1, 0] == 6.0 and got[1, 1] == math.inf and np.isnan(got[0, 2])


def test_depth_image_16uc1_is_millimetres_with_zero_outside():
    encoding, step, data = depth_image(sensor_3x2(use_depth_16uc1=True), DEPTH_3X2)
    assert (encoding, step) == ('16UC1', 6)
    assert np.frombuffer(data, '<u2').tolist() == [1000, 2000, 0, 0, 0, 4000]


def test_point_cloud_of_a_known_depth_image():
    s = sensor_3x2()
    f = focal_length(s)
    assert f == pytest.approx(3 / (2 * math.tan(0.6)))
    rgb = bytes(range(18))  # pixel k: bytes 3k, 3k+1, 3k+2
    data, dense = point_cloud(s, DEPTH_3X2, rgb)
    assert len(data) == 6 * POINT_STEP and dense is False
    pts = np.frombuffer(data, np.uint8).reshape(2, 3, POINT_STEP)
    xyz = pts[:, :, :12].copy().view('<f4').reshape(2, 3, 3)
    # pixel (row 0, col 0): d = 1, i - (W-1)/2 = -1, j - (H-1)/2 = -0.5
    assert xyz[0, 0].tolist() == pytest.approx([-1 / f, -0.5 / f, 1.0])
    assert xyz[0, 1].tolist() == pytest.approx([0.0, -1.0 / f, 2.0])
    assert xyz[1, 2].tolist() == pytest.approx([4 / f, 2.0 / f, 4.0])
    assert np.isnan(xyz[0, 2]).all() and np.isnan(xyz[1, 0]).all() and np.isnan(xyz[1, 1]).all()
    # openni_kinect: the image's bytes in order at 16, 17, 18 (red and blue swap for rgb8)
    assert pts[1, 2, 16:20].tolist() == [15, 16, 17, 0]
    assert pts[0, 0, 12:16].tolist() == [0] * 4 and pts[0, 0, 20:].tolist() == [0] * 12
    # gazebo_ros_depth_camera packs as PCL: blue, green, red, alpha
    data, _ = point_cloud(sensor_3x2(DEPTH_CAMERA_PLUGIN), DEPTH_3X2, rgb)
    assert np.frombuffer(data, np.uint8).reshape(6, POINT_STEP)[5, 16:20].tolist() == [
        17,
        16,
        15,
        255,
    ]
    # mono: the grey byte three times; all in range: dense
    near = np.full((2, 3), 1.0, np.float32)
    data, dense = point_cloud(sensor_3x2(fmt='L8'), near, bytes(range(6)))
    assert dense is True
    assert np.frombuffer(data, np.uint8).reshape(6, POINT_STEP)[4, 16:19].tolist() == [4, 4, 4]


def test_a_point_cloud_builder_reused_gives_each_frame_its_own_points():
    s = sensor_3x2()
    builder = PointCloudBuilder(s)
    first, _ = builder.build(DEPTH_3X2, bytes(range(18)))
    first = bytes(first)
    second, dense = builder.build(np.full((2, 3), 2.0, np.float32), bytes(18))
    assert dense and bytes(second) == bytes(
        point_cloud(s, np.full((2, 3), 2.0, np.float32), bytes(18))[0]
    )
    assert first == bytes(point_cloud(s, DEPTH_3X2, bytes(range(18)))[0]) != bytes(second)


def test_a_frame_splits_into_image_and_depth():
    s = sensor_3x2()
    frame = bytes(range(18)) + DEPTH_3X2.tobytes()
    image, depth = split_frame(s, memoryview(frame))
    assert bytes(image) == bytes(range(18))
    assert np.array_equal(depth, DEPTH_3X2)
    with pytest.raises(ValueError, match='not 42'):
        split_frame(s, frame[:-1])


# ------------------------------------------------------------------------------ rendering
@pytest.fixture
def wall_client():
    """A DIRECT client with a wall whose near face is 1.7 m in front of the origin (+x)."""
    client = p.connect(p.DIRECT)
    shape = p.createVisualShape(
        p.GEOM_BOX, halfExtents=[0.1, 3, 3], rgbaColor=[0.8, 0.2, 0.2, 1], physicsClientId=client
    )
    p.createMultiBody(0, -1, shape, [1.8, 0, 0], physicsClientId=client)
    yield client
    p.disconnect(client)


@pytest.mark.parametrize('backend', ['tiny', 'default'])
def test_a_rendered_plane_is_at_its_distance(wall_client, backend):
    s = CameraSensor(
        'k', 'body', width=64, height=48, near=0.05, far=10.0, depth_plugin=OPENNI_KINECT_PLUGIN
    )
    b = renderers.Backend() if backend == 'tiny' else renderers.open_backend()
    try:
        frame = render(wall_client, s, (0, 0, 0), (0, 0, 0, 1), b)
    finally:
        b.close()
    image, depth = split_frame(s, frame)
    # a plane facing the camera: the same z-depth at every pixel, the centre's included
    assert depth[24, 32] == pytest.approx(1.7, abs=2e-3)
    assert np.allclose(depth, 1.7, atol=5e-3)
    _, _, data = depth_image(s, depth)
    assert np.allclose(np.frombuffer(data, '<f4'), 1.7, atol=5e-3)
    cloud, dense = point_cloud(s, depth, image)
    xyz = np.frombuffer(cloud, np.uint8).reshape(48, 64, POINT_STEP)[:, :, :12].copy()
    xyz = xyz.view('<f4').reshape(48, 64, 3)
    f = focal_length(s)
    assert dense and xyz[0, 63].tolist() == pytest.approx(
        [1.7 * 31.5 / f, -1.7 * 23.5 / f, 1.7], abs=5e-3
    )
    assert image[0] > image[1] + 50 and image[0] > image[2] + 50  # the red wall, top left


def test_nothing_in_view_is_inf_then_nan_in_the_image(wall_client):
    s = CameraSensor('k', 'body', width=16, height=12, depth_plugin=OPENNI_KINECT_PLUGIN)
    frame = render(wall_client, s, (0, 0, 0), p.getQuaternionFromEuler((0, 0, math.pi)))
    _, depth = split_frame(s, frame)
    assert np.isinf(depth).all()
    _, _, data = depth_image(s, depth)
    assert np.isnan(np.frombuffer(data, '<f4')).all()


def test_a_spawned_depth_camera_delivers_image_and_depth_through_the_render_processes():
    sim = Simulation(WorldConfig())
    try:
        with open(DEPTH_BOT) as f:
            model = sim.spawn_urdf('depth_bot', f.read())
        (cam,) = model.cameras
        s = cam.sensor
        assert s.depth_plugin == OPENNI_KINECT_PLUGIN and s.update_rate == 10
        frames = []
        cam.wants_image, cam.on_image = (lambda: True), (lambda t, d: frames.append((t, d)))
        for _ in range(3):
            sim.step()
        sim.sensors.drain()
        assert frames and len(frames[0][1]) == s.frame_bytes
        _, depth = split_frame(s, frames[0][1])
        assert depth[60, 80] == pytest.approx(1.3, abs=5e-3)  # camera 0.1, wall face 1.4
        assert np.isinf(depth[0, 0])  # sky beside the 1 m wide wall
    finally:
        sim.close()


def test_the_chunked_point_cloud_serializes_as_sensor_msgs_does(monkeypatch):
    import io

    from sensor_msgs.msg import PointCloud2

    from _arm1sim.ros.plugins import camera_plugin
    from _arm1sim.ros.plugins.depth_camera_plugin import ChunkedPointCloud2, point_fields

    monkeypatch.setattr(camera_plugin, 'CHUNK', 40)  # several slices of a 6-point cloud
    s = sensor_3x2()
    data, dense = point_cloud(s, DEPTH_3X2, bytes(range(18)))
    fields = dict(height=2, width=3, fields=point_fields(), point_step=32, row_step=96)
    ours, plain = io.BytesIO(), io.BytesIO()
    ChunkedPointCloud2(data=data, is_dense=dense, **fields).serialize(ours)
    PointCloud2(data=bytes(data), is_dense=dense, **fields).serialize(plain)
    assert ours.getvalue() == plain.getvalue()
    back = PointCloud2().deserialize(ours.getvalue())
    assert (back.width, back.point_step, back.is_dense, back.data) == (3, 32, False, bytes(data))
    assert [(f.name, f.offset) for f in back.fields] == [('x', 0), ('y', 4), ('z', 8), ('rgb', 16)]
