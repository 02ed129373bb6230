"""Per-link <gazebo reference> physics tags as Gazebo applies them, on robots of our own:
mu1/mu2, kp/kd, turnGravityOff/gravity, selfCollide, and a warning naming each tag pybullet
cannot honour, once per spawn."""

import logging

import pybullet as p
import pytest

from _arm1sim.description.gazebo_tags import prepare_body
from _arm1sim.description.sdf_world import WorldConfig
from _arm1sim.description.surface import KD_DEFAULT
from _arm1sim.description.urdf_model import parse_urdf
from _arm1sim.sim.simulation import Simulation

INERTIAL = (
    '<inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" '
    'iyz="0"/></inertial>'
)
BOX = '<geometry><box size="0.1 0.1 0.1"/></geometry>'


def box_robot(name, tags='', extra_link=''):
    return '<robot name="%s"><link name="body">%s<collision>%s</collision></link>%s%s</robot>' % (
        name,
        INERTIAL,
        BOX,
        extra_link,
        tags,
    )


@pytest.fixture
def sim():
    s = Simulation(WorldConfig())
    yield s
    s.close()


def dynamics(robot, link):
    return p.getDynamicsInfo(robot.body, robot.link_index[link], physicsClientId=robot.client)


def test_mu1_and_kp_kd_become_the_surface_and_contact_stiffness(sim):
    tags = '<gazebo reference="body"><mu1>0.7</mu1><mu2>0.7</mu2><kp>5e4</kp></gazebo>'
    robot = sim.spawn_urdf('b', box_robot('b', tags)).robot
    info = dynamics(robot, 'body')
    # touching nothing, a link has sqrt(mu): two such surfaces make mu (physics/surface_combiner)
    assert info[1] == pytest.approx(0.7**0.5)  # lateral friction
    assert info[9] == pytest.approx(5e4) and info[8] == pytest.approx(KD_DEFAULT)


def test_a_tags_value_attribute_counts_as_its_text(sim):
    # sdformat's URDF reader takes <mu1 value="..."/> first (Hello Robot Stretch's form)
    tags = (
        '<gazebo reference="body"><mu1 value=" 0.7 "/><mu2 value="0.7">0.2</mu2>'
        '<kp value="5e4"/></gazebo>'
    )
    assert parse_urdf(box_robot('b', tags)).gazebo_refs['body'] == {
        'mu1': '0.7',
        'mu2': '0.7',
        'kp': '5e4',
    }
    info = dynamics(sim.spawn_urdf('b', box_robot('b', tags)).robot, 'body')
    assert info[1] == pytest.approx(0.7**0.5) and info[9] == pytest.approx(5e4)


def test_untagged_link_has_gazebos_default_mu_of_1(sim):
    robot = sim.spawn_urdf('b', box_robot('b')).robot
    assert dynamics(robot, 'body')[1] == pytest.approx(1.0)  # not pybullet's default 0.5


def test_lumped_links_tags_move_to_the_parent_but_the_parents_own_win(sim):
    extra = (
        '<link name="pad">%s<collision>%s</collision></link>'
        '<joint name="pad_joint" type="fixed"><parent link="body"/><child link="pad"/>'
        '<origin xyz="0 0 0.1"/></joint>' % (INERTIAL, BOX)
    )
    tags = (
        '<gazebo reference="pad"><mu1>0.9</mu1><kp>1e5</kp><kd>10</kd></gazebo>'
        '<gazebo reference="body"><mu1>0.3</mu1></gazebo>'
    )
    robot = sim.spawn_urdf('b', box_robot('b', tags, extra)).robot
    info = dynamics(robot, 'body')
    assert info[1] == pytest.approx(0.3**0.5) and info[9] == pytest.approx(1e5)
    assert info[8] == pytest.approx(10)


def test_unsupported_tags_are_named_once_at_spawn(caplog):
    tags = (
        '<gazebo reference="body"><mu1>0.2</mu1><mu2>0.8</mu2><maxVel>0.1</maxVel>'
        '<minDepth>0.001</minDepth><material>Gazebo/Red</material></gazebo>'
    )
    urdf = box_robot('b', tags)
    with caplog.at_level(logging.WARNING, logger='_arm1sim.description'):
        _, options = prepare_body(urdf, parse_urdf(urdf), 'b')
    text = [r.getMessage() for r in caplog.records if r.levelno == logging.WARNING]
    assert len(text) == 3  # mu2, maxVel, minDepth: one each; material is not physics
    assert any('mu2' in t and 'body' in t for t in text)
    assert any('maxVel' in t for t in text) and any('minDepth' in t for t in text)
    assert options.surfaces['body'].friction == pytest.approx(0.2)


def test_turn_gravity_off_lets_a_link_float_while_another_falls(sim):
    floating = sim.spawn_urdf(
        'f',
        box_robot('f', '<gazebo reference="body"><turnGravityOff>true</turnGravityOff></gazebo>'),
        position=(0, 0, 1),
    ).robot
    also = sim.spawn_urdf(
        'g',
        box_robot('g', '<gazebo reference="body"><gravity>false</gravity></gazebo>'),
        position=(1, 0, 1),
    ).robot
    falling = sim.spawn_urdf('h', box_robot('h'), position=(2, 0, 1)).robot
    for _ in range(240):
        sim.step()
    assert floating.link_pose('body')[0][2] == pytest.approx(1.0, abs=1e-6)
    assert also.link_pose('body')[0][2] == pytest.approx(1.0, abs=1e-6)
    assert falling.link_pose('body')[0][2] < 0.9


# base -(j1, z 0.15)-> upper -(j2, x 0.3)-> lower: folding j2 by 180 deg at j1 = 0 puts
# lower's box inside base's box. base and lower are not joined, so they collide only if
# either says selfCollide; upper and lower are joined and never collide.
def chain(self_collide_on):
    def link(name, xyz):
        tag = (
            '<gazebo reference="%s"><selfCollide>true</selfCollide></gazebo>' % name
            if name in self_collide_on
            else ''
        )
        return (
            '<link name="%s">%s<collision><origin xyz="%s"/>'
            '<geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>%s'
            % (name, INERTIAL, xyz, tag)
        )

    def joint(name, parent, child, xyz, axis):
        return (
            '<joint name="%s" type="revolute"><parent link="%s"/><child link="%s"/>'
            '<origin xyz="%s"/><axis xyz="%s"/><limit lower="-4" upper="4" effort="1" '
            'velocity="1"/></joint>' % (name, parent, child, xyz, axis)
        )

    return (
        '<robot name="c"><link name="world"/>'
        + link('base', '0 0 0')
        + link('upper', '0.15 0 0')
        + link('lower', '0.3 0 0')
        + '<joint name="w" type="fixed"><parent link="world"/><child link="base"/></joint>'
        + joint('j1', 'base', 'upper', '0 0 0.15', '0 0 1')
        + joint('j2', 'upper', 'lower', '0.3 0 0', '0 1 0')
        + '</robot>'
    )


def self_contacts(sim, urdf):
    robot = sim.spawn_urdf('c%d' % len(sim.models), urdf).robot
    robot.set_joint_positions({'j2': 3.1416})  # lower folds back over base
    p.performCollisionDetection(physicsClientId=robot.client)
    pts = p.getContactPoints(robot.body, robot.body, physicsClientId=robot.client)
    names = {i: n for n, i in robot.link_index.items()}
    return {tuple(sorted((names[c[3]], names[c[4]]))) for c in pts}


def test_self_collide_on_one_link_makes_it_collide_with_the_rest_but_not_across_a_joint(sim):
    assert self_contacts(sim, chain(['lower'])) == {('base', 'lower')}


def test_without_self_collide_links_of_a_model_never_collide(sim):
    assert self_contacts(sim, chain([])) == set()


def test_links_without_self_collide_stay_apart_when_another_link_has_it(sim):
    # upper has the flag, but its only neighbours share a joint with it; base and lower
    # (neither flagged) overlap and still do not collide
    assert self_contacts(sim, chain(['upper'])) == set()
    # both flagged: the pair collides, the joined ones never
    assert self_contacts(sim, chain(['base', 'upper', 'lower'])) == {('base', 'lower')}
