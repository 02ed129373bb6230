"""Contact surfaces as Gazebo/ODE: SDF <surface> and URDF <gazebo> tags read with SDFormat's
defaults (description/surface.py), two surfaces combined as ODE combines them, and
pybullet's product of per-link frictions made ODE's minimum (physics/surface_combiner.py):
a box on a ramp starts to slide where tan(slope) = min(mu_box, mu_ramp)."""

import math
import xml.etree.ElementTree as ET

import pybullet as p
import pytest

from _arm1sim.description.gazebo_tags import prepare_body
from _arm1sim.description.sdf_model import SdfModelError, parse_model
from _arm1sim.description.sdf_to_urdf import to_urdf
from _arm1sim.description.sdf_world import WorldConfig, parse_world
from _arm1sim.description.surface import (
    KD_DEFAULT,
    KP_DEFAULT,
    Surface,
    SurfaceError,
    combine,
    sdf_surface_tags,
    surface_from_tags,
)
from _arm1sim.description.urdf_model import UrdfError, parse_urdf
from _arm1sim.physics.surface_combiner import solve
from _arm1sim.sim.simulation import Simulation

SURFACE = (
    '<surface><friction><ode><mu>0.3</mu><mu2>0.3</mu2><fdir1>1 0 0</fdir1></ode></friction>'
    '<contact><ode><kp>1e5</kp><kd>20</kd><min_depth>0.001</min_depth><max_vel>0.5</max_vel>'
    '</ode></contact><bounce><restitution_coefficient>0.4</restitution_coefficient>'
    '</bounce></surface>'
)


def test_sdf_surface_becomes_gazebo_reference_tags():
    tags = sdf_surface_tags(ET.fromstring(SURFACE), 'c')
    assert tags == {
        'mu1': '0.3',
        'mu2': '0.3',
        'fdir1': '1 0 0',
        'kp': '1e5',
        'kd': '20',
        'minDepth': '0.001',
        'maxVel': '0.5',
        'restitution_coefficient': '0.4',
    }
    surface, skipped = surface_from_tags(tags, 'c')
    assert surface == Surface(mu=0.3, mu2=0.3, restitution=0.4, kp=1e5, kd=20)
    assert sorted(s.split()[0] for s in skipped) == ['fdir1', 'maxVel', 'minDepth']


def test_nothing_said_is_sdformats_defaults():
    surface, skipped = surface_from_tags({}, 'c')
    assert (surface.mu, surface.mu2, surface.restitution) == (1.0, 1.0, 0.0)
    assert surface.kp is None and not skipped  # pybullet's own contact unless one is said
    only_kp, _ = surface_from_tags({'kp': '1e6'}, 'c')
    assert (only_kp.kp, only_kp.kd) == (1e6, KD_DEFAULT)
    only_kd, _ = surface_from_tags({'kd': '5'}, 'c')
    assert (only_kd.kp, only_kd.kd) == (KP_DEFAULT, 5.0)


@pytest.mark.parametrize(
    'tags', [{'mu1': 'nan'}, {'mu2': 'x'}, {'mu1': '-1'}, {'kp': '0'}, {'kd': '-2'}]
)
def test_a_bad_value_is_refused_by_name(tags):
    with pytest.raises(SurfaceError, match="where <%s>" % next(iter(tags))):
        surface_from_tags(tags, 'where')


def test_two_surfaces_combine_as_odes_contact():
    a = Surface(mu=0.3, mu2=2.0, restitution=0.5, kp=1e4, kd=2.0)
    b = Surface(mu=1.5, mu2=0.7, restitution=0.1)
    c = combine(a, b)
    assert (c.mu, c.mu2, c.restitution) == (0.3, 0.7, 0.1)
    assert c.kp == pytest.approx(1.0 / (1e-4 + 1.0 / KP_DEFAULT))  # springs in series
    assert c.kd == pytest.approx(2.0 + KD_DEFAULT)  # dampers side by side
    assert combine(Surface(), Surface()).kp is None


def test_sdf_model_surface_reaches_the_urdf_and_the_body_options():
    model = ET.fromstring(
        '<model name="m"><link name="l"><collision name="c"><geometry><box><size>.1 .1 .1'
        '</size></box></geometry>%s</collision></link></model>' % SURFACE
    )
    urdf = to_urdf(parse_model(model))
    _, options = prepare_body(urdf, parse_urdf(urdf), 'm')
    assert options.surfaces['l'] == Surface(mu=0.3, mu2=0.3, restitution=0.4, kp=1e5, kd=20)
    assert options.dynamics['l'] == {'contactStiffness': 1e5, 'contactDamping': 20.0}


def test_sdf_model_with_a_bad_surface_is_refused_by_name():
    model = ET.fromstring(
        '<model name="m"><link name="l"><collision name="c"><geometry><box><size>.1 .1 .1'
        '</size></box></geometry><surface><friction><ode><mu>lots</mu></ode></friction>'
        '</surface></collision></link></model>'
    )
    with pytest.raises(SdfModelError, match="link 'l' collision 'c' <surface> <friction/ode/mu>"):
        parse_model(model)


def test_urdf_with_a_bad_mu_is_refused_by_name():
    urdf = '<robot name="r"><link name="l"/><gazebo reference="l"><mu1>inf</mu1></gazebo></robot>'
    with pytest.raises(UrdfError, match="reference='l'.*mu1"):
        prepare_body(urdf, parse_urdf(urdf), 'r')


def test_ground_plane_keeps_its_surface():
    world = parse_world(
        '<sdf version="1.6"><world name="w"><model name="ground_plane"><static>true</static>'
        '<link name="link"><collision name="c"><geometry><plane><normal>0 0 1</normal>'
        '</plane></geometry><surface><friction><ode><mu>100</mu><mu2>50</mu2></ode>'
        '</friction></surface></collision></link></model></world></sdf>'
    )
    assert world.models[0].surface.mu == 100 and world.models[0].surface.mu2 == 50


def test_solve_makes_products_the_minimum_on_a_tree_and_an_odd_cycle():
    box, table, left, right = (1, -1), (2, -1), (3, 0), (3, 1)
    mu = {box: 0.5, table: 0.8, left: 2.0, right: 1.0}
    star = frozenset({(box, table), (box, left), (box, right)})
    f = solve(star, mu)
    for a, b in star:
        assert f[a] * f[b] == pytest.approx(min(mu[a], mu[b]), rel=1e-6)
    triangle = star | {(left, right)}  # the fingers touch each other too: an odd cycle
    triangle = frozenset(triangle - {(box, table)})
    f = solve(triangle, mu)
    for a, b in triangle:
        assert f[a] * f[b] == pytest.approx(min(mu[a], mu[b]), rel=1e-6)


def test_solve_a_frictionless_surface_makes_every_pair_frictionless():
    a, b, c = (1, -1), (2, -1), (3, -1)
    f = solve(frozenset({(a, b), (b, c)}), {a: 0.0, b: 0.7, c: 0.4})
    assert f[a] == 0.0 and f[b] * f[c] == pytest.approx(0.4)


# ------------------------------------------------------------------ the rule, for real
INERTIA = '<inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/>'


def ramp(mu, slope):
    """A fixed 1 m x 1 m board tilted by ``slope`` rad about x, its top face through the origin."""
    return (
        '<robot name="ramp"><link name="world"/><link name="board"><inertial><mass value="1"/>'
        '%s</inertial><collision><origin xyz="0 0 -0.05"/><geometry><box size="1 1 0.1"/>'
        '</geometry></collision></link><joint name="fix" type="fixed"><parent link="world"/>'
        '<child link="board"/><origin rpy="%r 0 0"/></joint><gazebo reference="board">'
        '<mu1>%r</mu1><mu2>%r</mu2></gazebo></robot>' % (INERTIA, slope, mu, mu)
    )


def box(mu):
    return (
        '<robot name="box"><link name="box"><inertial><mass value="0.1"/>%s</inertial>'
        '<collision><geometry><box size="0.05 0.05 0.05"/></geometry></collision></link>'
        '<gazebo reference="box"><mu1>%r</mu1><mu2>%r</mu2></gazebo></robot>' % (INERTIA, mu, mu)
    )


def slide(mu_box, mu_ramp, tan_slope, seconds=1.0):
    """How far (m) the box slides down the ramp in ``seconds`` of sim time."""
    sim = Simulation(WorldConfig(models=[]))
    try:
        slope = math.atan(tan_slope)
        sim.spawn_urdf('ramp', ramp(mu_ramp, slope))
        # resting on the board: its centre 25 mm along the board's normal
        normal = (0.0, -math.sin(slope), math.cos(slope))
        start = tuple(0.0255 * n for n in normal)
        orientation = (math.sin(slope / 2), 0.0, 0.0, math.cos(slope / 2))
        robot = sim.spawn_urdf('box', box(mu_box), start, orientation).robot
        for _ in range(100):  # settle onto the board
            sim.step()
        settled = robot.link_pose('box')[0]
        for _ in range(int(seconds / sim.period)):
            sim.step()
        end = robot.link_pose('box')[0]
        return math.dist(settled, end)
    finally:
        sim.close()


@pytest.mark.parametrize('mu_box, mu_ramp', [(0.5, 0.8), (0.8, 0.5)])
def test_a_box_slides_where_the_slope_passes_the_smaller_mu(mu_box, mu_ramp):
    # ODE: min 0.5. pybullet's product of raw mu would be 0.4 (slides at 0.45), the
    # geometric mean 0.63 (holds at 0.55): both are told apart.
    rule = min(mu_box, mu_ramp)
    assert slide(mu_box, mu_ramp, 0.9 * rule) < 0.001
    assert slide(mu_box, mu_ramp, 1.1 * rule) > 0.02


def test_equal_default_surfaces_hold_at_mu_1():
    # Gazebo's default mu 1 on both (pybullet's own default would be 0.5 x 0.5 = 0.25)
    assert slide(1.0, 1.0, 0.9) < 0.001
    assert slide(1.0, 1.0, 1.1) > 0.02


def test_a_child_links_friction_is_applied_too():
    # pybullet drops a link's lateralFriction given in the same changeDynamics call as
    # linearDamping: the surfaces are set in calls of their own
    urdf = (
        '<robot name="arm"><link name="base"><inertial><mass value="1"/>%s</inertial>'
        '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>'
        '<link name="finger"><inertial><mass value="0.1"/>%s</inertial><collision>'
        '<geometry><box size="0.02 0.02 0.05"/></geometry></collision></link>'
        '<joint name="j" type="revolute"><parent link="base"/><child link="finger"/>'
        '<origin xyz="0 0 0.1"/><axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" '
        'velocity="1"/></joint><gazebo reference="finger"><mu1>0.3</mu1><mu2>0.3</mu2>'
        '</gazebo></robot>' % (INERTIA, INERTIA)
    )
    sim = Simulation(WorldConfig())
    try:
        robot = sim.spawn_urdf('arm', urdf).robot
        finger = p.getDynamicsInfo(
            robot.body, robot.link_index['finger'], physicsClientId=sim.world.client
        )
        base = p.getDynamicsInfo(robot.body, -1, physicsClientId=sim.world.client)
        assert finger[1] == pytest.approx(0.3**0.5) and base[1] == pytest.approx(1.0)
    finally:
        sim.close()


# franka_description's fingers say their surface as a <collision> block inside the reference
FINGER = (
    '<gazebo reference="l"><collision><max_contacts>10</max_contacts><surface><contact><ode>'
    '<max_vel>0</max_vel><min_depth>0.001</min_depth></ode></contact><friction><ode>'
    '<mu>1.13</mu><mu2>1.13</mu2></ode></friction><bounce/></surface></collision></gazebo>'
)


def test_a_collision_block_in_a_gazebo_reference_gives_the_links_surface():
    # sdformat's URDF reader inserts it into each of the link's collisions
    urdf = '<robot name="r"><link name="l"/>%s</robot>' % FINGER
    _, options = prepare_body(urdf, parse_urdf(urdf), 'r')
    assert options.surfaces['l'] == Surface(mu=1.13, mu2=1.13)
    # a flat tag of the link is written over the block's value, as sdformat does
    urdf = '<robot name="r"><link name="l"/>%s<gazebo reference="l"><mu1>0.5</mu1></gazebo></robot>'
    _, options = prepare_body(urdf % FINGER, parse_urdf(urdf % FINGER), 'r')
    assert options.surfaces['l'].mu == 0.5 and options.surfaces['l'].mu2 == 1.13
    bad = FINGER.replace('<mu>1.13</mu>', '<mu>lots</mu>')
    with pytest.raises(UrdfError, match="reference='l'.*collision.*friction/ode/mu"):
        parse_urdf('<robot name="r"><link name="l"/>%s</robot>' % bad)
