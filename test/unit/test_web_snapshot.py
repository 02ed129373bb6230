"""What the browser view reads of the world (ros/web/web_snapshot.py), in a pybullet world."""

from types import SimpleNamespace

import pytest
from conftest import WORLD_FILE

from _arm1sim.control.controller_manager import ControllerManager
from _arm1sim.description.sdf_world import read_world
from _arm1sim.ros.web.web_snapshot import WorldSnapshots
from _arm1sim.sim.simulation import Simulation


class Calls:
    """SimThreadCalls on one thread: the call runs at once."""

    def call(self, fn, *args):
        return fn(*args)


@pytest.fixture
def world(arm1_urdf, find_package, fake_ros):
    sim = Simulation(read_world(WORLD_FILE))
    loop = SimpleNamespace(paused=True, clock=SimpleNamespace(rtf=SimpleNamespace(value=1.0)))
    snaps = WorldSnapshots(sim, Calls(), loop)

    def spawn():
        return sim.spawn_urdf(
            'arm1',
            arm1_urdf,
            find_package=find_package,
            controller_manager_factory=lambda hw, ns: ControllerManager(
                hw, fake_ros.node_handle, ns
            ),
        )

    spawn()
    yield sim, loop, snaps, spawn
    snaps.close()
    sim.close()


def test_a_new_model_comes_with_its_visuals_once_the_view_has_them_they_stop(world):
    sim, _, snaps, _ = world
    snap = snaps.take()
    arm = snap.models['arm1']
    index = sim.models['arm1'].robot.link_index
    assert [index[n] for n in arm.links] == list(range(-1, len(arm.links) - 1))  # base first
    assert len(arm.poses) == len(arm.links) == len(sim.models['arm1'].robot.link_index)
    assert arm.namespace == '/arm1' and not arm.static
    visuals = snap.visuals[arm.token]
    meshes = [v for v in visuals if v.kind == 'mesh']
    assert meshes and all(v.mesh.lower().endswith('.stl') for v in meshes)
    assert any(v.rgba[:3] != (1.0, 1.0, 1.0) for v in visuals)  # the URDF's materials
    static = [m for m in snap.models.values() if m.static]
    assert [m.name for m in static] == [m.name for m in sim.config.models]
    snaps.known = frozenset(m.token for m in snap.models.values())
    assert snaps.take().visuals == {}


def test_poses_follow_the_joints_and_a_respawn_is_a_new_model(world):
    sim, _, snaps, spawn = world
    first = snaps.take().models['arm1']
    sim.set_model_configuration('arm1', ['joint1'], [1.0])
    moved = snaps.take().models['arm1']
    assert moved.poses[0] == first.poses[0]  # the fixed base stays
    assert moved.poses[-1] != first.poses[-1]
    sim.delete_model('arm1')
    assert 'arm1' not in snaps.take().models
    spawn()
    again = snaps.take()
    assert again.models['arm1'].token != first.token
    assert again.models['arm1'].token in again.visuals


def test_running_the_physics_a_snapshot_is_taken_before_a_step_only_when_asked(world):
    sim, loop, snaps, _ = world
    loop.paused = False
    sim.step()
    assert snaps._latest is None  # nobody asked: nothing read
    snaps._wanted = True
    sim.step()
    assert snaps._latest is not None and snaps._latest.time_ns == sim.time_ns - sim.step_ns
    assert not snaps._wanted
