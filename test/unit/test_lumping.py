"""Fixed-joint lumping as Gazebo's URDF->SDF conversion does it, on a robot of our own:
mass, centre and inertia combined, frames of lumped links kept for sensors, child joints
re-parented, preserveFixedJoint / disableFixedJointLumping honoured, massless frames."""

import logging
import math
import xml.etree.ElementTree as ET

import pybullet as p
import pytest

from _arm1sim.description.gazebo_tags import prepare_body
from _arm1sim.description.lumping import FRAME_MASS, lump_fixed_joints, mass_of
from _arm1sim.description.sdf_world import WorldConfig
from _arm1sim.description.urdf_model import parse_urdf
from _arm1sim.sim.simulation import Simulation


def inertial(mass, xyz='0 0 0', ixx=0.01, iyy=0.01, izz=0.01):
    return (
        '<inertial><origin xyz="%s"/><mass value="%g"/><inertia ixx="%g" iyy="%g" izz="%g" '
        'ixy="0" ixz="0" iyz="0"/></inertial>' % (xyz, mass, ixx, iyy, izz)
    )


def joint(name, kind, parent, child, xyz='0 0 0', rpy='0 0 0'):
    limit = (
        ''
        if kind == 'fixed'
        else '<axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="10" velocity="1"/>'
    )
    return (
        '<joint name="%s" type="%s"><parent link="%s"/><child link="%s"/>'
        '<origin xyz="%s" rpy="%s"/>%s</joint>' % (name, kind, parent, child, xyz, rpy, limit)
    )


BALL = '<geometry><sphere radius="0.01"/></geometry>'

# world -> base -(j1)-> arm -[fixed, yaw 90 deg, x 0.2]-> tip -[fixed, x 0.05]-> tool0 (frame)
#   tool0 -(j2)-> finger; arm -[fixed, preserved]-> mount; arm -[fixed, no lumping]-> mount2
ROBOT = (
    '<robot name="lumpy"><link name="world"/>'
    '<link name="base">' + inertial(2) + '</link>'
    '<link name="arm">' + inertial(1, '0.1 0 0') + '<collision>' + BALL + '</collision></link>'
    '<link name="tip">'
    + inertial(0.5, '0 0 0', 0.001, 0.002, 0.003)
    + '<collision name="tip_ball"><origin xyz="0.01 0 0"/>'
    + BALL
    + '</collision><visual><origin xyz="0.01 0 0"/>'
    + BALL
    + '</visual></link>'
    '<link name="tool0"/>'
    '<link name="finger">' + inertial(0.1, '0 0 0', 1e-4, 1e-4, 1e-4) + '</link>'
    '<link name="mount">' + inertial(0.1) + '</link>'
    '<link name="mount2">'
    + inertial(0.1)
    + '</link>'
    + joint('world_joint', 'fixed', 'world', 'base')
    + joint('j1', 'revolute', 'base', 'arm', '0 0 0.1')
    + joint('arm_tip', 'fixed', 'arm', 'tip', '0.2 0 0', '0 0 1.5707963267948966')
    + joint('tip_tool0', 'fixed', 'tip', 'tool0', '0.05 0 0')
    + joint('j2', 'revolute', 'tool0', 'finger', '0 0 0.02')
    + joint('arm_mount', 'fixed', 'arm', 'mount', '0 0 0.03')
    + joint('arm_mount2', 'fixed', 'arm', 'mount2', '0 0 -0.03')
    + '<gazebo reference="arm_mount"><preserveFixedJoint>true</preserveFixedJoint></gazebo>'
    '<gazebo reference="arm_mount2"><disableFixedJointLumping>true</disableFixedJointLumping>'
    '</gazebo></robot>'
)


@pytest.fixture
def sim():
    s = Simulation(WorldConfig())
    yield s
    s.close()


def lumped_tree():
    root = ET.fromstring(ROBOT)
    return root, lump_fixed_joints(root, parse_urdf(ROBOT).gazebo_refs)


def test_links_on_fixed_joints_merge_into_their_parent():
    root, report = lumped_tree()
    assert sorted(report.frames) == ['tip', 'tool0']
    assert sorted(report.joints) == ['arm_tip', 'tip_tool0']
    links = [link.get('name') for link in root.findall('link')]
    assert links == ['world', 'base', 'arm', 'finger', 'mount', 'mount2']  # kept: world's
    arm = root.find("link[@name='arm']")
    # the tip's collision and visual now belong to arm, moved by the joint (yaw 90 deg)
    assert len(arm.findall('collision')) == 2 and len(arm.findall('visual')) == 1
    moved = arm.find("collision[@name='tip_ball']/origin")
    assert [float(v) for v in moved.get('xyz').split()] == pytest.approx([0.2, 0.01, 0], abs=1e-9)
    assert float(moved.get('rpy').split()[2]) == pytest.approx(math.pi / 2)


def test_mass_centre_and_inertia_combine_with_the_parallel_axis_theorem():
    root, _ = lumped_tree()
    m = mass_of(root.find("link[@name='arm']"))
    assert m.mass == pytest.approx(1.5)  # tool0 (no <inertial>) adds nothing
    cx = (1 * 0.1 + 0.5 * 0.2) / 1.5
    assert m.com == pytest.approx((cx, 0, 0), abs=1e-12)
    # tip's inertia turned by 90 deg about z: its ixx/iyy swap; plus m d^2 off each axis
    d_arm, d_tip = 0.1 - cx, 0.2 - cx
    parallel = 1 * d_arm**2 + 0.5 * d_tip**2
    assert m.inertia[0][0] == pytest.approx(0.01 + 0.002)
    assert m.inertia[1][1] == pytest.approx(0.01 + 0.001 + parallel)
    assert m.inertia[2][2] == pytest.approx(0.01 + 0.003 + parallel)
    assert m.inertia[0][1] == pytest.approx(0, abs=1e-12)


def test_child_joint_of_a_lumped_link_hangs_from_the_kept_ancestor():
    root, _ = lumped_tree()
    j2 = root.find("joint[@name='j2']")
    assert j2.find('parent').get('link') == 'arm'
    xyz = [float(v) for v in j2.find('origin').get('xyz').split()]
    assert xyz == pytest.approx([0.2, 0.05, 0.02], abs=1e-9)  # tip x 0.2, then tool0's 0.05 on y
    assert float(j2.find('origin').get('rpy').split()[2]) == pytest.approx(math.pi / 2)


def test_pybullet_body_has_gazebos_links_and_mass(sim):
    model = sim.spawn_urdf('lumpy', ROBOT)
    robot = model.robot
    assert sorted(robot.link_index) == ['arm', 'base', 'finger', 'mount', 'mount2', 'world']
    assert 'arm_tip' not in robot.joint_index and 'arm_mount' in robot.joint_index
    info = p.getDynamicsInfo(robot.body, robot.link_index['arm'], physicsClientId=robot.client)
    assert info[0] == pytest.approx(1.5)
    assert info[3] == pytest.approx(((0.1 + 0.1) / 1.5, 0, 0), abs=1e-6)


def quat_yaw(yaw):
    return (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))


def test_frame_and_link_pose_of_a_lumped_link_follow_its_parent(sim):
    model = sim.spawn_urdf('lumpy', ROBOT)
    robot = model.robot
    index, offset = robot.frame('tool0')
    assert index == robot.link_index['arm']
    assert offset[0] == pytest.approx((0.2, 0.05, 0), abs=1e-9)
    assert offset[1] == pytest.approx(quat_yaw(math.pi / 2), abs=1e-9)
    assert robot.frame('arm') == (robot.link_index['arm'], ((0, 0, 0), (0, 0, 0, 1)))
    assert robot.lumped_link('tip')[0] == 'arm' and robot.lumped_link('arm') is None
    with pytest.raises(KeyError):
        robot.frame('no_such_link')
    q = 0.5
    robot.set_joint_positions({'j1': q})
    pos, orn = robot.link_pose('tool0')
    # arm turned by q about z at height 0.1: the tool frame at (0.2, 0.05) in it, yawed 90 deg more
    expect = (0.2 * math.cos(q) - 0.05 * math.sin(q), 0.2 * math.sin(q) + 0.05 * math.cos(q), 0.1)
    assert pos == pytest.approx(expect, abs=1e-6)
    assert abs(sum(a * b for a, b in zip(orn, quat_yaw(q + math.pi / 2)))) == pytest.approx(1)
    # the finger's joint origin was re-parented: the finger sits 2 cm above tool0
    finger = robot.link_pose('finger')[0]
    assert finger == pytest.approx((expect[0], expect[1], 0.12), abs=1e-6)


def test_lumped_links_are_gone_from_the_gazebo_state_api_as_in_gazebo(sim):
    from _arm1sim.sim import model_state as ms

    sim.spawn_urdf('lumpy', ROBOT)
    names, _ = ms.link_states(sim)
    assert 'lumpy::arm' in names and 'lumpy::tool0' not in names and 'lumpy::tip' not in names
    with pytest.raises(ms.StateError, match=r'link \[lumpy::tool0\] not found'):
        ms.get_link_state(sim, 'lumpy::tool0', '')
    props = ms.get_model_properties(sim, 'lumpy')
    assert 'tip' not in props.body_names and 'arm_tip' not in props.joint_names
    assert ms.get_link_properties(sim, 'lumpy::arm')[0] == pytest.approx(1.5)


def test_massless_frames_add_nothing():
    # world -> a (1 kg) -fixed-> frame (none) ; a kept fixed frame gets FRAME_MASS
    urdf = (
        '<robot name="f"><link name="world"/><link name="a">' + inertial(1) + '</link>'
        '<link name="frame"/><link name="held"/>'
        + joint('w', 'fixed', 'world', 'a')
        + joint('f', 'fixed', 'a', 'frame')
        + joint('h', 'fixed', 'a', 'held')
        + '<gazebo reference="h"><preserveFixedJoint>1</preserveFixedJoint></gazebo></robot>'
    )
    root = ET.fromstring(urdf)
    report = lump_fixed_joints(root, parse_urdf(urdf).gazebo_refs)
    assert list(report.frames) == ['frame'] and report.weightless == ['held']
    assert mass_of(root.find("link[@name='a']")).mass == pytest.approx(1)
    assert mass_of(root.find("link[@name='held']")).mass == FRAME_MASS


def test_massless_link_on_a_moving_joint_is_warned_about_once_by_name(caplog):
    urdf = (
        '<robot name="m"><link name="a">'
        + inertial(1)
        + '</link><link name="finger"/>'
        + joint('j', 'revolute', 'a', 'finger')
        + '</robot>'
    )
    with caplog.at_level(logging.WARNING, logger='_arm1sim.description'):
        out, options = prepare_body(urdf, parse_urdf(urdf), 'm')
    warnings = [r.getMessage() for r in caplog.records if r.levelno == logging.WARNING]
    assert len(warnings) == 1 and 'finger' in warnings[0] and '<inertial>' in warnings[0]
    assert out == urdf and options.frames == {}


def test_massless_parent_takes_the_mass_of_what_is_lumped_into_it():
    # a free robot whose root has no inertial: its fixed child's mass becomes the root's
    urdf = (
        '<robot name="r"><link name="base_footprint"/><link name="base_link">'
        + inertial(3, '0 0 0.1')
        + '</link>'
        + joint('fp', 'fixed', 'base_footprint', 'base_link', '0 0 0.05')
        + '</robot>'
    )
    root = ET.fromstring(urdf)
    lump_fixed_joints(root, {})
    m = mass_of(root.find("link[@name='base_footprint']"))
    assert m.mass == pytest.approx(3) and m.com == pytest.approx((0, 0, 0.15))


def test_camera_on_a_lumped_link_keeps_its_pose(sim, arm1_urdf, find_package):
    # arm1's own camera_link sits on a fixed joint: lumped into link4, its frame kept
    model = sim.spawn_urdf('arm1', arm1_urdf, find_package=find_package)
    robot = model.robot
    assert 'camera_link' not in robot.link_index
    assert robot.lumped_link('camera_link')[0] == 'link4'
    # the camera's pose is link4's composed with camera_joint's origin
    link4 = robot.link_pose('link4')
    offset = ((-0.042, -0.035, -0.01), p.getQuaternionFromEuler((-1.57, -3.1415, 0)))
    expect = p.multiplyTransforms(*link4, *offset)
    got = robot.link_pose('camera_link')
    assert got[0] == pytest.approx(expect[0], abs=1e-9)
    assert abs(sum(a * b for a, b in zip(got[1], expect[1]))) == pytest.approx(1, abs=1e-6)


def test_a_long_fixed_chain_lumps_without_recursion():
    n = 1500  # longer than Python's recursion limit
    links = ''.join('<link name="l%d">%s</link>' % (i, inertial(1)) for i in range(n))
    joints = ''.join(
        joint('j%d' % i, 'fixed', 'l%d' % i, 'l%d' % (i + 1), '0 0 0.01') for i in range(n - 1)
    )
    root = ET.fromstring('<robot name="long">%s%s</robot>' % (links, joints))
    report = lump_fixed_joints(root, {})
    assert len(report.frames) == n - 1 and report.frames['l%d' % (n - 1)][0] == 'l0'
    assert report.frames['l%d' % (n - 1)][1][0][2] == pytest.approx(0.01 * (n - 1))
    assert mass_of(root.find('link')).mass == pytest.approx(n)


def test_a_bad_joint_origin_refuses_the_spawn_naming_the_joint(sim):
    from _arm1sim.sim.simulation import SpawnError

    bad = ROBOT.replace(
        '<origin xyz="0.05 0 0" rpy="0 0 0"/>', '<origin xyz="0.05 0" rpy="0 0 0"/>'
    )
    assert bad != ROBOT
    with pytest.raises(SpawnError, match='tip_tool0'):
        sim.spawn_urdf('bad', bad)
    assert sim.models == {}
