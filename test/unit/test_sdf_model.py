"""description/sdf_model.py (reading) and sdf_to_urdf.py (writing): an SDF <model> as a link tree
and as URDF the spawn path loads."""

import math
import xml.etree.ElementTree as ET

import pytest

from _arm1sim.description.limits import Limits
from _arm1sim.description.pose_math import quat_from_rpy, rpy_from_quat
from _arm1sim.description.sdf_model import (
    IDENTITY,
    SdfModelError,
    Tf,
    compose,
    inverse,
    model_dir_finder,
    parse_model,
    parse_sdf_text,
)
from _arm1sim.description.sdf_to_urdf import sdf_spawn, to_urdf
from _arm1sim.description.sdf_world import parse_world
from _arm1sim.description.urdf_model import parse_urdf


def model(body, name='m', attrs=''):
    return ET.fromstring('<model name="%s" %s>%s</model>' % (name, attrs, body))


BOX = '<geometry><box><size>0.1 0.2 0.3</size></box></geometry>'
LINK = '<link name="%s"><pose>%s</pose><collision name="c">' + BOX + '</collision></link>'


def close(a, b, tol=1e-9):
    return all(abs(x - y) <= tol for x, y in zip(a, b))


def same_tf(a, b, tol=1e-9):
    # q and -q are the same rotation
    return close(a.p, b.p, tol) and (close(a.q, b.q, tol) or close(a.q, [-c for c in b.q], tol))


# ------------------------------------------------------------------------------- transforms
def test_rpy_round_trip_and_inverse():
    for rpy in [(0.1, -0.2, 0.3), (1.0, 0.5, -2.0), (0, 0, math.pi / 2)]:
        assert close(rpy_from_quat(quat_from_rpy(*rpy)), rpy)
    a = Tf((1.0, 2.0, 3.0), quat_from_rpy(0.3, 0.2, 0.1))
    assert same_tf(compose(a, inverse(a)), IDENTITY)
    # a quarter turn about z takes x onto y
    b = compose(Tf((0.0, 0.0, 0.0), quat_from_rpy(0, 0, math.pi / 2)), Tf((1.0, 0, 0), IDENTITY.q))
    assert close(b.p, (0.0, 1.0, 0.0))


# ---------------------------------------------------------------------------------- parsing
def test_links_inertials_geometry_and_colors():
    m = parse_model(
        model(
            """
      <pose>1 2 3 0 0 0</pose>
      <link name="base"><pose>0 0 0.5 0 0 0</pose>
        <inertial><pose>0.1 0 0 0 0 0</pose><mass>2.5</mass>
          <inertia><ixx>0.1</ixx><ixy>0.01</ixy><iyy>0.2</iyy><izz>0.3</izz></inertia>
        </inertial>
        <collision name="box">"""
            + BOX
            + """</collision>
        <collision name="ball"><pose>0 0 1 0 0 0</pose>
          <geometry><sphere><radius>0.05</radius></sphere></geometry></collision>
        <collision name="can"><geometry><cylinder><radius>0.04</radius><length>0.12</length>
          </cylinder></geometry></collision>
        <visual name="red"><geometry><sphere><radius>0.05</radius></sphere></geometry>
          <material><ambient>1 0 0 1</ambient><diffuse>0.5 0 0 0.5</diffuse></material>
        </visual>
        <visual name="blue">"""
            + BOX
            + """
          <material><script><name>Gazebo/Blue</name></script></material></visual>
      </link>
      <link name="plain"/>"""
        )
    )
    assert m.name == 'm' and not m.static and m.root == 'base'
    assert close(m.pose.p, (1, 2, 3))
    base = m.links['base']
    assert close(base.pose.p, (0, 0, 0.5))
    assert base.inertial.mass == 2.5
    assert base.inertial.inertia == (0.1, 0.01, 0.0, 0.2, 0.0, 0.3)
    assert close(base.inertial.pose.p, (0.1, 0, 0))
    assert [(g.name, g.kind, g.size) for g in base.collisions] == [
        ('box', 'box', (0.1, 0.2, 0.3)),
        ('ball', 'sphere', (0.05,)),
        ('can', 'cylinder', (0.04, 0.12)),
    ]
    assert close(base.collisions[1].pose.p, (0, 0, 1))
    assert [v.color for v in base.visuals] == [(0.5, 0.0, 0.0, 0.5), (0.0, 0.0, 1.0, 1.0)]
    # two links and no joint: the second is not tied to the first, and says so
    assert 'plain' not in m.links
    assert any("'plain'" in w and 'dropped' in w for w in m.warnings)
    # SDFormat's defaults where <inertial> is absent: mass 1, unit inertia
    plain = parse_model(model('<link name="plain"/>')).links['plain']
    assert plain.inertial.mass == 1.0
    assert plain.inertial.inertia == (1.0, 0.0, 0.0, 1.0, 0.0, 1.0)


def test_pose_relative_to_frames_degrees_and_quaternions():
    m = parse_model(
        model("""
      <frame name="shelf"><pose>0 0 1 0 0 0</pose></frame>
      <link name="a"><pose relative_to="shelf">0.5 0 0 0 0 0</pose></link>
      <link name="b"><pose relative_to="a" degrees="true">0 0 0.2 0 0 90</pose></link>
      <link name="c"><pose rotation_format="quat_xyzw">0 1 0 0 0 0 2</pose></link>
      <joint name="ab" type="fixed"><parent>a</parent><child>b</child></joint>
      <joint name="ac" type="fixed"><parent>a</parent><child>c</child></joint>""")
    )
    assert close(m.links['a'].pose.p, (0.5, 0, 1))
    assert same_tf(m.links['b'].pose, Tf((0.5, 0, 1.2), quat_from_rpy(0, 0, math.pi / 2)))
    assert same_tf(m.links['c'].pose, Tf((0, 1, 0), (0, 0, 0, 1)))  # normalised
    assert m.warnings == []


@pytest.mark.parametrize(
    'body, culprit',
    [
        ('<link name="a"><pose relative_to="nowhere">0 0 0 0 0 0</pose></link>', 'nowhere'),
        (
            '<frame name="f"><pose relative_to="g"/></frame><frame name="g">'
            '<pose relative_to="f"/></frame><link name="a"><pose relative_to="f"/></link>',
            'cycle',
        ),
        ('<link name="a"><pose>0 0 0</pose></link>', "link 'a' <pose>"),
        ('<link name="a"><pose>0 0 nan 0 0 0</pose></link>', 'finite'),
        ('<link name="a"/><link name="a"/>', 'used twice'),
        (
            '<link name="a"><collision name="k"><geometry><box/></geometry></collision></link>',
            "'k'",
        ),
        ('<link name="a"><inertial><mass>-1</mass></inertial></link>', 'negative'),
        ('<link name="a::b"/>', "'::'"),
        ('', 'no <link>'),
        (
            '<link name="a"/><joint name="j" type="revolute"><parent>a</parent>'
            '<child>ghost</child></joint>',
            'ghost',
        ),
    ],
)
def test_bad_models_name_the_culprit(body, culprit):
    with pytest.raises(SdfModelError, match=culprit):
        parse_model(model(body))


def test_limits_bound_links_joints_and_names():
    links = ''.join('<link name="l%d"/>' % i for i in range(5))
    with pytest.raises(SdfModelError, match='links per model'):
        parse_model(model(links), Limits(links_per_model=4))
    with pytest.raises(SdfModelError, match='name_length'):
        parse_model(model('<link name="%s"/>' % ('x' * 40)), Limits(name_length=30))
    with pytest.raises(SdfModelError, match='description bytes'):
        parse_sdf_text(
            '<sdf><model name="m">%s</model></sdf>' % links, Limits(description_bytes=50)
        )
    with pytest.raises(SdfModelError, match='more than'):
        parse_sdf_text(
            '<sdf><model name="m">%s</model></sdf>' % ('<frame/>' * 500),
            Limits(links_per_model=1, joints_per_model=1),
        )


# ----------------------------------------------------------------------------------- joints
PENDULUM = (
    """
  <link name="base"><pose>0 0 1 0 0 0</pose></link>
  <link name="arm"><pose>0 0 0.5 0 0 0</pose>
    <collision name="c">"""
    + BOX
    + """</collision></link>
  <joint name="hinge" type="revolute"><pose>0 0 0.5 0 0 0</pose>
    <parent>base</parent><child>arm</child>
    <axis><xyz>1 0 0</xyz><limit><lower>-1</lower><upper>1.5</upper><effort>10</effort>
      <velocity>2</velocity></limit><dynamics><damping>0.3</damping></dynamics></axis>
  </joint>"""
)


def test_joint_frame_is_in_the_child_link_frame_and_urdf_origins_chain():
    m = parse_model(model(PENDULUM))
    (j,) = m.joints
    assert (j.type, j.parent, j.child, j.axis) == ('revolute', 'base', 'arm', (1.0, 0.0, 0.0))
    assert close(j.pose.p, (0, 0, 1.0))  # arm at 0.5, joint 0.5 above it in its frame
    assert (j.lower, j.upper, j.effort, j.velocity, j.damping) == (-1, 1.5, 10, 2, 0.3)
    robot = ET.fromstring(to_urdf(m))
    joint = robot.find('joint')
    # the root link's URDF frame is the model frame: the joint sits 1 above it
    assert joint.find('origin').get('xyz') == '0 0 1.0'
    assert joint.find('limit').attrib == {
        'effort': '10.0',
        'velocity': '2.0',
        'lower': '-1.0',
        'upper': '1.5',
    }
    assert joint.find('dynamics').get('damping') == '0.3'
    # the arm's collision moves into the joint frame: 0.5 below it
    arm = [link for link in robot.findall('link') if link.get('name') == 'arm'][0]
    assert arm.find('collision/origin').get('xyz') == '0 0 -0.5'
    parsed = parse_urdf(to_urdf(m))
    assert parsed.root_link == 'base' and parsed.joints['hinge'].type == 'revolute'


def test_axis_in_the_parent_model_frame_and_unlimited_revolute_is_continuous():
    m = parse_model(
        model("""
      <link name="a"/><link name="b"><pose>0 0 0 0 0 1.5707963267948966</pose></link>
      <joint name="j" type="revolute"><parent>a</parent><child>b</child>
        <axis><xyz>1 0 0</xyz><use_parent_model_frame>true</use_parent_model_frame></axis>
      </joint>""")
    )
    assert close(m.joints[0].axis, (0.0, -1.0, 0.0))  # model x seen from the turned joint
    assert ET.fromstring(to_urdf(m)).find('joint').get('type') == 'continuous'


def test_loops_unsupported_joints_and_loose_links_are_dropped_with_warnings():
    m = parse_model(
        model("""
      <link name="a"/><link name="b"/><link name="c"/><link name="d"/>
      <joint name="ab" type="revolute"><parent>a</parent><child>b</child></joint>
      <joint name="bc" type="prismatic"><parent>b</parent><child>c</child></joint>
      <joint name="ca" type="fixed"><parent>c</parent><child>b</child></joint>
      <joint name="ball" type="ball"><parent>a</parent><child>d</child></joint>
      <model name="inner"><link name="x"/></model>
      <include><uri>model://gripper</uri></include>""")
    )
    assert set(m.links) == {'a', 'b', 'c'}
    assert [j.name for j in m.joints] == ['ab', 'bc']
    text = ' | '.join(m.warnings)
    assert "'ca' closes a kinematic loop" in text
    assert "joint 'ball': type 'ball' is not built" in text
    assert "link 'd'" in text
    assert "nested model 'inner'" in text
    assert "nested <include> 'model://gripper'" in text
    parse_urdf(to_urdf(m))  # one root, a tree


def test_static_models_and_world_joints_get_a_world_root():
    m = parse_model(model(PENDULUM + '<static>true</static>'))
    assert m.root == 'world' and all(j.type == 'fixed' for j in m.joints)
    urdf = parse_urdf(to_urdf(m))
    assert urdf.root_link == 'world'
    assert urdf.joints['base_world_joint'].parent == 'world'
    # two unjoined links of a static model both stay, fixed where they are
    two = parse_model(model(LINK % ('a', '0 0 0 0 0 0') + LINK % ('b', '1 0 0 0 0 0'), attrs=''))
    assert set(two.links) == {'a'}
    two = parse_model(
        model('<static>1</static>' + LINK % ('a', '0 0 0 0 0 0') + LINK % ('b', '1 0 0 0 0 0'))
    )
    assert set(two.links) == {'a', 'b'} and two.warnings == []
    fixed = parse_model(
        model(
            PENDULUM.replace('<parent>base</parent>', '<parent>world</parent>').replace(
                '<link name="base"><pose>0 0 1 0 0 0</pose></link>', ''
            )
        )
    )
    assert fixed.root == 'world' and fixed.joints[0].type == 'revolute'


# ----------------------------------------------------------------------------------- meshes
def test_mesh_uris_resolve_through_the_model_path_and_stay_inside(tmp_path):
    (tmp_path / 'cup' / 'meshes').mkdir(parents=True)
    find = model_dir_finder([str(tmp_path / 'none'), str(tmp_path)])
    mesh = (
        '<link name="l"><visual name="v"><geometry><mesh><uri>%s</uri>%s</mesh></geometry>'
        '</visual></link>'
    )
    m = parse_model(
        model(mesh % ('model://cup/meshes/cup.dae', '<scale>2 2 2</scale>')), find_model_dir=find
    )
    g = m.links['l'].visuals[0]
    assert (g.kind, g.uri, g.scale) == ('mesh', str(tmp_path / 'cup/meshes/cup.dae'), (2, 2, 2))
    rel = parse_model(model(mesh % ('meshes/x.stl', '')), base_dir='/models/thing')
    assert rel.links['l'].visuals[0].uri == '/models/thing/meshes/x.stl'
    pkg = parse_model(model(mesh % ('package://pkg/m.stl', '')))
    assert pkg.links['l'].visuals[0].uri == 'package://pkg/m.stl'  # for resolve_mesh_uris
    for uri, culprit in [
        ('model://cup/../../etc/passwd.stl', 'leaves model'),
        ('model://mug/m.stl', 'model://mug not found'),
        ('meshes/x.stl', 'relative mesh URI'),
        ('http://x/m.stl', 'not supported'),
    ]:
        with pytest.raises(SdfModelError, match=culprit):
            parse_model(model(mesh % (uri, '')), find_model_dir=find)


# ----------------------------------------------------------------------------- spawn request
def test_spawn_request_renames_the_model_and_composes_the_initial_pose():
    sdf = '<sdf version="1.6"><model name="old"><pose>0 0 0.5 0 0 0</pose>%s</model></sdf>' % (
        LINK % ('body', '0.1 0 0 0 0 0')
    )
    q = quat_from_rpy(0, 0, math.pi / 2)
    spawn = sdf_spawn(sdf, 'new', (1, 2, 3), q)
    assert spawn.name == 'new' and ET.fromstring(spawn.urdf).get('name') == 'new'
    # initial pose, then the model's pose in it; the root link's own pose goes into the URDF
    assert close(spawn.position, (1, 2, 3.5))
    assert ET.fromstring(spawn.urdf).find('link/collision/origin').get('xyz') == '0.1 0 0'
    assert close(spawn.orientation, q)
    assert sdf_spawn('<robot name="r"><link name="l"/></robot>', 'r') is None  # URDF
    for text, culprit in [
        ('<sdf><light name="sun"/></sdf>', 'light'),
        ('<sdf><world name="w"/></sdf>', 'no <sdf><model>'),
        ('<sdf><model name="a"/><model name="b"/></sdf>', '2 <model>s'),
        ('<!DOCTYPE x [<!ENTITY a "b">]><sdf/>', 'DOCTYPE'),
    ]:
        with pytest.raises(SdfModelError, match=culprit):
            sdf_spawn(text, 'x')


# --------------------------------------------------------------------------------- physics
def test_world_models_load_into_pybullet_where_the_sdf_puts_them():
    """A static table keeps a dynamic can on it; a pendulum's links start where SDF says."""
    pytest.importorskip('pybullet')
    from _arm1sim.sim import model_state as ms
    from _arm1sim.sim.simulation import Simulation

    cfg = parse_world(
        '<sdf version="1.6"><world name="w">'
        '<model name="table"><static>true</static><pose>1 0 0 0 0 0</pose><link name="l">'
        '<collision name="top"><pose>0 0 0.7 0 0 0</pose>'
        '<geometry><box><size>0.8 0.6 0.04</size></box></geometry></collision></link></model>'
        '<model name="can"><pose>1 0 0.8 0 0 0</pose><link name="body"><inertial>'
        '<mass>0.3</mass><inertia><ixx>0.0005</ixx><iyy>0.0005</iyy><izz>0.0003</izz></inertia>'
        '</inertial><collision name="c"><geometry><cylinder><radius>0.04</radius>'
        '<length>0.12</length></cylinder></geometry></collision></link></model>'
        '<model name="pendulum"><pose>-1 0 0 0 0 0</pose>'
        + PENDULUM.replace('<pose>0 0 0.5 0 0 0</pose>\n    <parent>', '<parent>').replace(
            '<link name="base">', '<link name="base"><inertial><mass>5</mass></inertial>'
        )
        + '<joint name="fix" type="fixed"><parent>world</parent><child>base</child></joint>'
        '</model><model name="lifted"><pose>0 3 0 0 0 0.5</pose>'
        + LINK % ('l', '0 0 2 0 0 0')
        + '</model></world></sdf>'
    )
    names = ['table', 'can', 'pendulum', 'lifted']
    assert [s.name for s in cfg.spawns] == names and cfg.skipped == []
    sim = Simulation(cfg)
    try:
        for s in cfg.spawns:
            sim.spawn_urdf(s.name, s.urdf, s.position, s.orientation)
        arm = ms.get_link_state(sim, 'pendulum::arm', '')
        assert close(arm.position, (-1, 0, 0.5), 1e-6)
        # the model's pose is its model frame, as Gazebo's, not its link's
        lifted = ms.get_model_state(sim, 'lifted', 'world')
        assert close(lifted.position, (0, 3, 0), 1e-6)
        assert close(lifted.orientation, quat_from_rpy(0, 0, 0.5), 1e-6)
        for _ in range(2000):  # 2 s
            sim.step()
        can = ms.get_model_state(sim, 'can', 'world')
        assert can.position[2] == pytest.approx(0.72 + 0.06, abs=0.005)
        assert can.position[0] == pytest.approx(1.0, abs=0.01)
        assert ms.get_model_state(sim, 'table', 'world').position == pytest.approx((1, 0, 0))
        assert ms.get_model_state(sim, 'pendulum', 'world').position == pytest.approx((-1, 0, 0))
    finally:
        sim.close()


CUBE_FACES = [  # a unit cube's faces, outward vertex order
    ((0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 0, 0)),
    ((0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)),
    ((0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)),
    ((0, 1, 0), (0, 1, 1), (1, 1, 1), (1, 1, 0)),
    ((0, 0, 0), (0, 0, 1), (0, 1, 1), (0, 1, 0)),
    ((1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1)),
]


def test_mesh_models_from_the_model_path_rest_on_a_static_box(tmp_path):
    """An STL and an OBJ cube (centred, scaled to 0.1 m) from model:// fall onto a static box."""
    pytest.importorskip('pybullet')
    from _arm1sim.description.resource_paths import ResourcePaths
    from _arm1sim.physics.stl import write_binary_stl
    from _arm1sim.sim import model_state as ms
    from _arm1sim.sim.simulation import Simulation

    meshes = tmp_path / 'cubes' / 'meshes'
    meshes.mkdir(parents=True)
    centred = [[[c - 0.5 for c in v] for v in face] for face in CUBE_FACES]
    write_binary_stl(
        str(meshes / 'cube.stl'),
        [t for f in centred for t in ([f[0], f[1], f[2]], [f[0], f[2], f[3]])],
    )
    obj = ['v %g %g %g' % tuple(v) for f in centred for v in f]
    obj += ['f %d %d %d %d' % tuple(4 * i + k for k in (1, 2, 3, 4)) for i in range(6)]
    (meshes / 'cube.obj').write_text('\n'.join(obj) + '\n')
    (tmp_path / 'cubes' / 'model.sdf').write_text('<sdf version="1.6"/>')
    cube = (
        '<model name="%s"><pose>%s 0 1 0 0 0</pose><link name="l"><inertial><mass>0.1</mass>'
        '<inertia><ixx>0.0002</ixx><iyy>0.0002</iyy><izz>0.0002</izz></inertia></inertial>'
        '<collision name="c"><geometry><mesh><uri>model://cubes/meshes/%s</uri>'
        '<scale>0.1 0.1 0.1</scale></mesh></geometry></collision></link></model>'
    )
    cfg = parse_world(
        '<sdf version="1.6"><world name="w"><model name="block"><static>1</static><link name="l">'
        '<collision name="c"><pose>0 0 0.25 0 0 0</pose><geometry><box><size>2 1 0.5</size>'
        '</box></geometry></collision></link></model>'
        + cube % ('stl_cube', '-0.5', 'cube.stl')
        + cube % ('obj_cube', '0.5', 'cube.obj')
        + '</world></sdf>',
        find_model=ResourcePaths([], [str(tmp_path)]).find_model,
    )
    assert [s.name for s in cfg.spawns] == ['block', 'stl_cube', 'obj_cube'] and not cfg.skipped
    sim = Simulation(cfg)
    try:
        for s in cfg.spawns:
            sim.spawn_urdf(s.name, s.urdf, s.position, s.orientation)
        for _ in range(1500):
            sim.step()
        for name in ('stl_cube', 'obj_cube'):
            z = ms.get_model_state(sim, name, 'world').position[2]
            assert z == pytest.approx(0.5 + 0.05, abs=0.01), name
    finally:
        sim.close()


def test_spawn_of_a_world_include_finds_the_model_and_takes_the_include_pose(tmp_path):
    """spawn_model -database sends <sdf><world><include>: the model on the model path is built,
    its relative mesh URIs from its own folder, at initial pose * the include's <pose>."""
    from _arm1sim.description.resource_paths import ResourcePaths

    (tmp_path / 'crate').mkdir()
    (tmp_path / 'crate' / 'model.sdf').write_text(
        '<sdf version="1.6"><model name="crate"><pose>5 5 5 0 0 0</pose><link name="l">'
        '<visual name="v"><geometry><mesh><uri>crate.obj</uri></mesh></geometry></visual>'
        '</link></model></sdf>'
    )
    paths = ResourcePaths([], [str(tmp_path)])
    include = (
        '<sdf version="1.5"><world name="default"><include><uri>model://%s</uri>'
        '<pose>0 0 0.5 0 0 0</pose></include></world></sdf>'
    )
    spawn = sdf_spawn(
        include % 'crate',
        'box1',
        (1, 0, 0),
        (0, 0, 0, 1),
        None,
        model_dir_finder(paths.model),
        paths.find_model,
    )
    assert spawn.name == 'box1' and close(spawn.position, (1, 0, 0.5))
    mesh = ET.fromstring(spawn.urdf).find('link/visual/geometry/mesh')
    assert mesh.get('filename') == str(tmp_path / 'crate' / 'crate.obj')
    with pytest.raises(SdfModelError, match='model://nothing not found'):
        sdf_spawn(include % 'nothing', 'x', find_model=paths.find_model)
    with pytest.raises(SdfModelError, match='no model path'):
        sdf_spawn(include % 'crate', 'x')


def test_sensors_and_model_plugins_become_gazebo_blocks_of_the_urdf():
    m = parse_model(
        model("""
      <link name="head"><sensor name="cam" type="camera"><update_rate>10</update_rate>
        <plugin name="p" filename="libgazebo_ros_camera.so"/></sensor></link>
      <plugin name="mover" filename="libgazebo_ros_planar_move.so">
        <robotNamespace>/bot</robotNamespace></plugin>""")
    )
    urdf = parse_urdf(to_urdf(m))
    assert [(link, s.get('name')) for link, s in urdf.sensors] == [('head', 'cam')]
    assert [p.get('filename') for p in urdf.model_plugins] == ['libgazebo_ros_planar_move.so']


def test_a_long_chain_of_relative_frames_resolves_without_recursion():
    frames = ''.join(
        '<frame name="f%d"><pose relative_to="f%d">0 0 0.001 0 0 0</pose></frame>' % (i, i - 1)
        for i in range(1, 5000)
    )
    m = parse_model(
        model('<frame name="f0"/>' + frames + '<link name="l"><pose relative_to="f4999"/></link>')
    )
    assert m.links['l'].pose.p[2] == pytest.approx(4.999)


def test_fixed_joints_of_an_sdf_model_are_not_lumped():
    """Gazebo lumps fixed joints of URDFs only: an SDF model's links stay links."""
    pytest.importorskip('pybullet')
    from _arm1sim.sim import model_state as ms
    from _arm1sim.sim.simulation import Simulation

    cfg = parse_world(
        '<sdf version="1.6"><world name="w"><model name="cart"><pose>0 0 1 0 0 0</pose>'
        + LINK % ('base', '0 0 0 0 0 0')
        + LINK % ('flag', '0 0 0.2 0 0 0')
        + '<joint name="mast" type="fixed"><parent>base</parent><child>flag</child></joint>'
        '</model></world></sdf>'
    )
    sim = Simulation(cfg)
    try:
        for spawn in cfg.spawns:
            sim.spawn_urdf(spawn.name, spawn.urdf, spawn.position, spawn.orientation)
        assert 'flag' in sim.models['cart'].robot.link_index
        names, _ = ms.link_states(sim)
        assert 'cart::flag' in names
    finally:
        sim.close()
