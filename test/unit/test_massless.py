"""Links without <inertial> weigh nothing, as in Gazebo (fixed-joint frames lumped into
their parent), on a robot of our own with ROS-Industrial's frame links."""

import logging
import xml.etree.ElementTree as ET

import pybullet as p
import pytest

from arm1.description.massless import FRAME_MASS, lighten, weightless_frames
from arm1.description.sdf_world import WorldConfig
from arm1.sim.simulation import Simulation


def inertial(mass):
    return (
        '<inertial><mass value="%g"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" '
        'ixz="0" iyz="0"/></inertial>' % mass
    )


def joint(name, kind, parent, child, z=0.1):
    limit = (
        ''
        if kind == 'fixed'
        else '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/>'
    )
    return (
        '<joint name="%s" type="%s"><parent link="%s"/><child link="%s"/>'
        '<origin xyz="0 0 %g"/>%s</joint>' % (name, kind, parent, child, z, limit)
    )


# ROS-Industrial layout: world -> base_link -> base (frame), base_link -> link_1 (moves)
# -> flange (frame) -> tool0 (frame). Declared mass: 2 + 1 = 3 kg.
INDUSTRIAL = (
    '<robot name="ri"><link name="world"/>'
    '<link name="base_link">' + inertial(2) + '</link><link name="base"/>'
    '<link name="link_1">'
    + inertial(1)
    + '</link><link name="flange"/><link name="tool0"/>'
    + joint('world_joint', 'fixed', 'world', 'base_link', 0)
    + joint('base_link-base', 'fixed', 'base_link', 'base')
    + joint('joint_1', 'revolute', 'base_link', 'link_1')
    + joint('joint_1-flange', 'fixed', 'link_1', 'flange')
    + joint('flange-tool0', 'fixed', 'flange', 'tool0')
    + '</robot>'
)


def masses(model):
    robot = model.robot
    n = p.getNumJoints(robot.body, physicsClientId=robot.client)
    return {
        p.getJointInfo(robot.body, i, physicsClientId=robot.client)[12].decode(): p.getDynamicsInfo(
            robot.body, i, physicsClientId=robot.client
        )[0]
        for i in range(n)
    }


def test_frame_links_on_fixed_joints_are_made_weightless():
    root = ET.fromstring(INDUSTRIAL)
    report = weightless_frames(root)
    assert sorted(report.weightless) == ['base', 'flange', 'tool0']
    assert report.moving == []
    for link in root.findall('link'):
        if link.get('name') in ('base', 'flange', 'tool0'):
            assert float(link.find('inertial/mass').get('value')) == FRAME_MASS


def test_pybullet_sees_only_the_declared_mass():
    sim = Simulation(WorldConfig())
    try:
        model = sim.spawn_urdf('ri', INDUSTRIAL)
        seen = masses(model)
        assert sum(seen.values()) == pytest.approx(3.0, abs=1e-4)  # not 3 + 3 phantom kg
        assert seen['tool0'] < 1e-5 and seen['flange'] < 1e-5 and seen['base'] < 1e-5
        assert seen['link_1'] == pytest.approx(1.0)
    finally:
        sim.close()


def test_arm_with_weightless_frames_holds_still_without_drift():
    # A tiny mass on a fixed joint must not destabilise the step: joint_1 stays finite.
    sim = Simulation(WorldConfig())
    try:
        model = sim.spawn_urdf('ri', INDUSTRIAL)
        for _ in range(500):
            sim.step()
        robot = model.robot
        index = robot.link_index['link_1']
        pos = p.getLinkState(robot.body, index, physicsClientId=robot.client)[0]
        assert all(abs(v) < 1.0 for v in pos)
    finally:
        sim.close()


def test_massless_link_on_a_moving_joint_is_warned_about_once_by_name(caplog):
    urdf = (
        '<robot name="m"><link name="a">'
        + inertial(1)
        + '</link><link name="finger"/>'
        + joint('j', 'revolute', 'a', 'finger')
        + '</robot>'
    )
    with caplog.at_level(logging.WARNING, logger='arm1.description'):
        out = lighten(urdf, 'm')
    warnings = [r.getMessage() for r in caplog.records if r.levelno == logging.WARNING]
    assert len(warnings) == 1 and 'finger' in warnings[0] and '<inertial>' in warnings[0]
    assert out == urdf  # nothing to change: pybullet keeps its default there


def test_declared_zero_mass_counts_as_massless():
    urdf = (
        '<robot name="z"><link name="a">'
        + inertial(1)
        + '</link><link name="f">'
        + inertial(0)
        + '</link>'
        + joint('j', 'fixed', 'a', 'f')
        + '</robot>'
    )
    assert weightless_frames(ET.fromstring(urdf)).weightless == ['f']
