"""Camera renderer backends (physics/renderers.py): the default draws arm1 as TinyRenderer does."""

import math

import numpy as np
import pybullet as p
import pytest
from conftest import REPO_ROOT, WORLD_FILE

from _arm1sim.description.sdf_world import read_world
from _arm1sim.physics import renderers
from _arm1sim.physics.render_process import render
from _arm1sim.sim.simulation import Simulation

# two views of arm1 with joints bent: from the side and above, and close from behind
VIEWS = [
    ((0.3, 0.3, 0.2), (0, math.atan2(0.15, 0.3 * math.sqrt(2)), math.atan2(-0.3, -0.3))),
    ((0.15, -0.1, 0.25), (0, 0.9, 2.5)),
]
POSE = {'joint2': 0.6, 'joint3': -0.8}


@pytest.fixture(scope='module')
def arm1_frames(arm1_urdf):
    """{backend: [(rgba, depth) per view]} of arm1 in the willow_garage world."""
    sim = Simulation(read_world(WORLD_FILE))
    try:
        prepared = sim.prepare_urdf('arm1', arm1_urdf, find_package=lambda pkg: REPO_ROOT)
        model = sim.spawn_urdf('arm1', arm1_urdf, find_package=lambda pkg: REPO_ROOT)
        sensor = model.cameras[0].sensor
        frames = {}
        for name in renderers.BACKENDS:
            backend = renderers.open_backend(name)
            world = backend.open_world(read_world(WORLD_FILE))
            try:
                world.load_robot(*prepared.load_args).set_joint_positions(POSE)
                frames[name] = [
                    renderers.render(
                        backend, world.client, sensor, pos, p.getQuaternionFromEuler(rpy)
                    )
                    for pos, rpy in VIEWS
                ]
            finally:
                backend.close()
                world.close()
        yield sensor, frames
    finally:
        sim.close()


def orange(rgba):
    """The arm's orange links (material in urdf/arm1.urdf.xacro), however lit; the ground and
    white links are grey."""
    return rgba[:, :, 0].astype(int) - rgba[:, :, 2] > 100


def iou(a, b):
    return (a & b).sum() / max(1, (a | b).sum())


def test_every_backend_gives_rgba_and_depth_of_the_sensors_size(arm1_frames):
    sensor, frames = arm1_frames
    for name, views in frames.items():
        for rgba, depth in views:
            assert rgba.shape == (sensor.height, sensor.width, 4), name
            assert rgba.dtype == np.uint8 and depth.dtype == np.float32, name
            assert 0.0 <= depth.min() and depth.max() <= 1.0, name


def test_the_default_backend_matches_tinyrenderers_picture(arm1_frames):
    _, frames = arm1_frames
    assert renderers.DEFAULT != 'tiny'
    for k, ((tiny, tiny_depth), (ours, our_depth)) in enumerate(
        zip(frames['tiny'], frames[renderers.DEFAULT])
    ):
        mad = np.abs(tiny[:, :, :3].astype(int) - ours[:, :, :3]).mean()
        assert mad < 4.0, 'view %d: mean absolute pixel difference %.2f' % (k, mad)
        a, b = orange(tiny), orange(ours)
        assert a.sum() > 400, 'view %d: the arm is not in the picture' % k
        assert iou(a, b) > 0.8, 'view %d: the arm is elsewhere (IoU %.2f)' % (k, iou(a, b))
        ca, cb = np.argwhere(a).mean(axis=0), np.argwhere(b).mean(axis=0)
        assert np.abs(ca - cb).max() < 3.0, 'view %d: centroid %s vs %s' % (k, ca, cb)
        assert np.abs(tiny_depth - our_depth).mean() < 1e-3, 'view %d: depth' % k


def test_pybullets_egl_plugin_puts_the_arm_in_the_same_place(arm1_frames):
    """Its lighting and shadows differ (BENCHMARKS.md), its geometry must not."""
    _, frames = arm1_frames
    for k, ((_, tiny_depth), (egl, egl_depth)) in enumerate(zip(frames['tiny'], frames['egl'])):
        near = tiny_depth < 0.999  # something closer than the far sky
        assert iou(near, egl_depth < 0.999) > 0.95, 'view %d' % k
        assert np.abs(tiny_depth - egl_depth).mean() < 1e-3, 'view %d: depth' % k
        assert (egl[~(egl_depth < 1.0), :3] == renderers.SKY).all(), 'view %d: sky' % k


def test_render_of_a_render_process_goes_through_the_backend(arm1_frames, arm1_urdf):
    sensor, frames = arm1_frames
    sim = Simulation(read_world(WORLD_FILE))
    try:
        sim.spawn_urdf('arm1', arm1_urdf, find_package=lambda pkg: REPO_ROOT)
        sim.models['arm1'].robot.set_joint_positions(POSE)
        pos, rpy = VIEWS[0]
        data = render(sim.world.client, sensor, pos, p.getQuaternionFromEuler(rpy))
        tiny = frames['tiny'][0][0]
        assert data == np.ascontiguousarray(tiny[:, :, :3]).tobytes()  # no backend: TinyRenderer
    finally:
        sim.close()


def test_an_unknown_renderer_is_refused_naming_the_variable_and_choices(monkeypatch):
    monkeypatch.setenv(renderers.ENV, 'vulkan')
    with pytest.raises(renderers.BackendError, match=r"ARM1_RENDERER='vulkan'.*tiny, egl, gl"):
        renderers.open_backend()
    monkeypatch.setenv(renderers.ENV, ' TINY ')
    assert renderers.backend_name() == 'tiny'
    monkeypatch.delenv(renderers.ENV)
    assert renderers.backend_name() == renderers.DEFAULT


def test_a_mesh_the_gl_backend_cannot_read_is_drawn_by_tinyrenderer_and_named_once(
    tmp_path, capsys
):
    obj = tmp_path / 'tri.obj'
    obj.write_text('v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n')
    backend = renderers.open_backend('gl')
    world = backend.open_world(read_world(WORLD_FILE))
    try:
        c = world.client
        vis = p.createVisualShape(p.GEOM_MESH, fileName=str(obj), physicsClientId=c)
        p.createMultiBody(0, -1, vis, (0, 0, 0.2), physicsClientId=c)
        args = (c, 64, 48, p.computeViewMatrix((0.5, 0.5, 1), (0.3, 0.3, 0.2), (0, 0, 1)))
        args += (p.computeProjectionMatrixFOV(60, 64 / 48, 0.02, 10),)
        frames = [backend.render(*args) for _ in range(2)]
        tiny = renderers.Backend().render(*args)
    finally:
        backend.close()
        world.close()
    assert all((f[0] == tiny[0]).all() for f in frames)
    err = capsys.readouterr().err
    assert err.count('tri.obj') == 1 and 'STL meshes only' in err and 'TinyRenderer' in err


def test_boxes_spheres_cylinders_and_capsules_land_where_tinyrenderer_puts_them():
    from _arm1sim.description.sdf_world import WorldConfig

    colours = {'box': (1, 0, 0), 'sphere': (0, 1, 0), 'cylinder': (0, 0, 1), 'capsule': (1, 1, 0)}
    pictures = {}
    for name in ('tiny', 'gl'):
        backend = renderers.open_backend(name)
        world = backend.open_world(WorldConfig())
        c = world.client
        try:
            shapes = {
                'box': (dict(shapeType=p.GEOM_BOX, halfExtents=(0.1, 0.05, 0.02)), (0, -0.3, 0)),
                'sphere': (dict(shapeType=p.GEOM_SPHERE, radius=0.08), (0, 0, 0)),
                'cylinder': (
                    dict(shapeType=p.GEOM_CYLINDER, radius=0.05, length=0.3),
                    (0, 0.3, 0),
                ),
                'capsule': (
                    dict(shapeType=p.GEOM_CAPSULE, radius=0.04, length=0.2),
                    (0.2, 0.15, 0),
                ),
            }
            for key, (kwargs, pos) in shapes.items():
                vis = p.createVisualShape(
                    rgbaColor=colours[key] + (1,), physicsClientId=c, **kwargs
                )
                tilt = p.getQuaternionFromEuler((0.5, 0, 0))
                p.createMultiBody(0, -1, vis, pos, tilt, physicsClientId=c)
            view = p.computeViewMatrix((1.2, 0.2, 0.8), (0, 0, 0), (0, 0, 1))
            projection = p.computeProjectionMatrixFOV(50, 4 / 3, 0.05, 10)
            pictures[name] = backend.render(c, 320, 240, view, projection)[0][:, :, :3]
        finally:
            backend.close()
            world.close()
    for key, colour in colours.items():
        masks = [
            np.all((pictures[n] > 60) == np.array(colour, bool), axis=2)
            & (pictures[n].max(axis=2) > 60)
            for n in ('tiny', 'gl')
        ]
        assert masks[0].sum() > 150, key
        assert iou(*masks) > 0.8, '%s: IoU %.2f' % (key, iou(*masks))
        ca, cb = (np.argwhere(m).mean(axis=0) for m in masks)
        assert np.abs(ca - cb).max() < 2.0, '%s: centroid %s vs %s' % (key, ca, cb)


def test_a_world_with_an_unknown_renderer_names_it_and_steps_on(monkeypatch, caplog):
    from _arm1sim.description.camera_sensor import CameraSensor
    from _arm1sim.description.sdf_world import WorldConfig
    from _arm1sim.physics.sensor_manager import SensorManager

    monkeypatch.setenv(renderers.ENV, 'vulkan')
    manager = SensorManager(WorldConfig(), 1, restart_delay=0.0, max_restarts=2)
    [cam] = manager.add_robot('m', ('m.urdf',), [CameraSensor('eye', 'l', update_rate=30)])
    cam.wants_image = lambda: True
    for t in range(1, 100):
        manager.update(t * 1000000, lambda: {})  # returns: the world goes on
    assert manager.failed and not manager.renderers  # no child was started
    assert any("ARM1_RENDERER='vulkan'" in r.message for r in caplog.records)


def test_the_default_falls_back_to_tinyrenderer_saying_why_but_an_asked_for_one_does_not(
    monkeypatch, capsys
):
    def no_egl(self):
        raise renderers.BackendError('no EGL display')

    monkeypatch.setattr(renderers.GlBackend, '__init__', no_egl)
    monkeypatch.delenv(renderers.ENV, raising=False)
    backend = renderers.open_backend()
    assert type(backend) is renderers.Backend and backend.name == 'tiny'
    assert "'gl' unavailable (no EGL display); using 'tiny'" in capsys.readouterr().err
    monkeypatch.setenv(renderers.ENV, 'gl')
    with pytest.raises(renderers.BackendError, match='no EGL display'):
        renderers.open_backend()
