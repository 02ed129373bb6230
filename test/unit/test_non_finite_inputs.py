"""Non-finite inputs (ROS-free parts): non-finite values never reach physics (huge
quaternions, NaN cmd_vel) and a body pybullet cannot report on is refused whole."""

import math
import os

import pybullet as p
import pytest
from conftest import box_link
from helpers import GROUND, run, spawn
from urdf_snippets import joint, link

from _arm1sim.description.pose_math import normalized
from _arm1sim.description.sdf_world import WorldConfig, parse_world
from _arm1sim.physics.world import MAX_BODY_JOINTS
from _arm1sim.sim import model_state as ms
from _arm1sim.sim.model_state import State
from _arm1sim.sim.simulation import Simulation, SpawnError

BOX = '<robot name="box">%s</robot>' % box_link('body')
ARM = (
    '<robot name="two">%s%s<joint name="hinge" type="revolute"><parent link="base"/>'
    '<child link="arm"/><origin xyz="0 0 0.2"/><axis xyz="0 1 0"/>'
    '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>'
    % (box_link('base'), box_link('arm'))
)


def finite(values):
    return all(math.isfinite(v) for v in values)


@pytest.mark.parametrize('scale', [1e200, 1e-200, 1e308, 5e-324])
def test_normalized_survives_huge_and_tiny_components(scale):
    q = normalized((scale, scale, scale, scale))
    assert finite(q) and q == pytest.approx((0.5, 0.5, 0.5, 0.5))
    assert normalized((0.0, 0.0, 0.0, 0.0)) == (0.0, 0.0, 0.0, 1.0)


def test_set_model_state_with_1e200_quaternion_keeps_physics_finite():
    sim = Simulation(WorldConfig())
    try:
        sim.spawn_urdf('box', BOX, (0, 0, 1))
        sim.spawn_urdf('two', ARM, (1, 0, 1))
        for name in ('box', 'two'):
            ms.set_model_state(sim, name, State((0, 0, 1), (1e200, 1e200, 1e200, 1e200)), '')
            s = ms.get_model_state(sim, name, '')
            assert s.orientation == pytest.approx((0.5, 0.5, 0.5, 0.5), abs=1e-6)
        for _ in range(50):
            sim.step()
        for name in ('box', 'two'):
            s = ms.get_model_state(sim, name, '')
            assert finite(s.position + s.orientation), (name, s)
        robot = sim.models['two'].robot
        hinge = p.getJointState(
            robot.body, robot.joint_index['hinge'], physicsClientId=robot.client
        )
        assert finite(hinge[:2]), hinge
    finally:
        sim.close()


def test_spawn_pose_with_1e200_quaternion_is_normalised():
    sim = Simulation(WorldConfig())
    try:
        sim.spawn_urdf('box', BOX, (0, 0, 1), (0.0, 0.0, 1e200, 1e200))
        sim.step()
        s = ms.get_model_state(sim, 'box', '')
        assert finite(s.orientation)
        assert s.orientation == pytest.approx((0, 0, math.sqrt(0.5), math.sqrt(0.5)), abs=1e-6)
    finally:
        sim.close()


@pytest.fixture
def ground():
    s = Simulation(parse_world(GROUND))
    yield s
    s.close()


@pytest.mark.parametrize('bad', [(math.nan, 0.0), (0.0, math.inf), (-math.inf, math.nan)])
def test_a_non_finite_cmd_vel_is_refused_and_the_last_command_kept(ground, bad):
    model, drive, readings = spawn(ground)
    drive.set_command(0.2, 0.1)
    with pytest.raises(ValueError, match='not finite'):
        drive.set_command(*bad)
    run(ground, 0.5)
    r = readings[-1][1]
    assert finite(list(r.pose.position) + list(r.pose.orientation)) if hasattr(r, 'pose') else r
    pos, orn = p.getBasePositionAndOrientation(model.robot.body, physicsClientId=model.robot.client)
    assert finite(pos + orn)
    assert drive.wheel_speeds() != (0.0, 0.0), 'the last good command was dropped'


def chain(n):
    return '<robot name="r">%s</robot>' % ''.join(
        [link('l%d' % i) for i in range(n + 1)]
        + [joint('j%d' % i, 'l%d' % (i - 1), 'l%d' % i, 'revolute') for i in range(1, n + 1)]
    )


def test_a_body_of_200_joints_is_refused_whole_and_leaves_nothing_behind():
    sim = Simulation(WorldConfig())
    try:
        client = sim.world.client
        bodies = p.getNumBodies(physicsClientId=client)
        files = set(os.listdir(sim._tmp.name))
        with pytest.raises(SpawnError) as info:
            sim.spawn_urdf('big', chain(200))
        message = str(info.value)
        assert "'big'" in message and '200 joints' in message and str(MAX_BODY_JOINTS) in message
        assert p.getNumBodies(physicsClientId=client) == bodies, 'a half-built body stayed'
        assert set(os.listdir(sim._tmp.name)) == files, 'its URDF stayed in the temp folder'
        assert 'big' not in sim.models
        assert len(sim.world.robots) == 0
        for _ in range(10):
            sim.step()
        sim.spawn_urdf('big', chain(MAX_BODY_JOINTS))  # the name is free; 127 joints load
        sim.step()
        assert len(sim.models['big'].robot.joint_index) == MAX_BODY_JOINTS
    finally:
        sim.close()
