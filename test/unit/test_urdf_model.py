"""physics/urdf_model.py: what the simulator reads from a URDF."""

import os
import xml.etree.ElementTree as ET

import pytest
from conftest import MIXED_URDF, REPO_ROOT, box_link, control_plugin, transmission

from _arm1sim.control.hardware_interface import EFFORT_JOINT_INTERFACE
from _arm1sim.description.limits import LimitError, Limits
from _arm1sim.description.urdf_model import UrdfError, parse_urdf, resolve_mesh_uris
from _arm1sim.physics.stl import write_binary_stl

ARM1_LIMITS = {
    'joint1': (-1.57, 1.57),
    'joint2': (0.01, 1.57),
    'joint3': (-1.0, 1.57),
    'joint4': (-0.8, 1.57),
}


def robot(body, name='r'):
    return '<robot name="%s">%s</robot>' % (name, body)


TWO_LINKS = (
    box_link('a')
    + box_link('b')
    + """
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="-1" upper="2" effort="3" velocity="4"/></joint>"""
)


# ----------------------------------------------------------------------------- arm1
def test_arm1_joints_and_limits(arm1_urdf):
    m = parse_urdf(arm1_urdf)
    assert m.name == 'arm1'
    assert m.root_link == 'world'
    names = list(m.joints)
    arm = ['fixed_base_joint', 'joint1', 'joint2', 'joint3', 'joint4']
    assert [n for n in names if n in arm] == arm  # in document order
    # every other joint is fixed (e.g. sensors mounted on a link)
    assert {m.joints[n].type for n in names if n not in arm} <= {'fixed'}
    assert m.joints['fixed_base_joint'].type == 'fixed'
    for name, (lo, hi) in ARM1_LIMITS.items():
        j = m.joints[name]
        assert j.type == 'revolute'
        assert (j.limits.lower, j.limits.upper) == (lo, hi)
        assert (j.limits.effort, j.limits.velocity) == (1.0, 0.5)
    assert (m.joints['joint2'].parent, m.joints['joint2'].child) == ('link1', 'link2')


def test_arm1_transmissions_and_plugin(arm1_urdf):
    m = parse_urdf(arm1_urdf)
    assert [(t.name, t.joint) for t in m.transmissions] == [
        ('tran1', 'joint1'),
        ('tran2', 'joint2'),
        ('tran3', 'joint3'),
        ('tran4', 'joint4'),
    ]
    assert all(t.interfaces == [EFFORT_JOINT_INTERFACE] for t in m.transmissions)
    assert [(j.name, i) for j, i in m.actuated_joints()] == [
        ('joint%d' % n, EFFORT_JOINT_INTERFACE) for n in range(1, 5)
    ]
    assert m.control_plugin.robot_namespace == '/arm1'
    assert m.control_plugin.robot_sim_type == 'gazebo_ros_control/DefaultRobotHWSim'
    assert m.control_plugin.control_period is None


def test_arm1_gazebo_reference_tags(arm1_urdf):
    m = parse_urdf(arm1_urdf)
    assert m.gazebo_refs['base_link'] == {'material': 'Gazebo/White'}
    assert m.gazebo_refs['link1'] == {'mu1': '0.2', 'mu2': '0.2', 'material': 'Gazebo/Orange'}
    assert {'base_link', 'link1', 'link2', 'link3', 'link4'} <= set(m.gazebo_refs)
    assert all(m.gazebo_refs[link]['material'].startswith('Gazebo/') for link in m.gazebo_refs)


# ----------------------------------------------------------------------------- other robots
def test_continuous_and_prismatic_joints_and_plugin_namespace():
    m = parse_urdf(MIXED_URDF)
    wheel, slider = m.joints['wheel_joint'], m.joints['slider_joint']
    assert wheel.type == 'continuous'
    assert wheel.limits.lower is None and wheel.limits.upper is None
    assert not wheel.limits.has_position_limits
    assert (wheel.limits.effort, wheel.limits.velocity) == (1.0, 20.0)
    assert slider.type == 'prismatic'
    assert (slider.limits.lower, slider.limits.upper) == (-0.1, 0.2)
    assert m.control_plugin.robot_namespace == '/mixed_ns'


def test_interface_names_with_and_without_prefix():
    m = parse_urdf(MIXED_URDF)
    ifaces = {j.name: i for j, i in m.actuated_joints()}
    assert ifaces['wheel_joint'] == EFFORT_JOINT_INTERFACE  # written without the prefix
    assert ifaces['slider_joint'] == EFFORT_JOINT_INTERFACE
    assert ifaces['passive_joint'] == 'hardware_interface/PositionJointInterface'


def test_transmission_naming_an_unknown_joint():
    m = parse_urdf(robot(TWO_LINKS + transmission('j') + transmission('ghost_joint', name='tg')))
    with pytest.raises(UrdfError) as exc:
        m.actuated_joints()
    assert "'tg'" in str(exc.value) and "'ghost_joint'" in str(exc.value)


def test_transmission_on_a_fixed_joint_is_not_actuated():
    body = (
        box_link('a')
        + box_link('b')
        + """
      <joint name="f" type="fixed"><parent link="a"/><child link="b"/></joint>"""
    )
    assert parse_urdf(robot(body + transmission('f'))).actuated_joints() == []


def test_no_plugin_and_plugin_without_namespace():
    assert parse_urdf(robot(TWO_LINKS)).control_plugin is None
    m = parse_urdf(robot(TWO_LINKS + control_plugin(None)))
    assert m.control_plugin is not None
    assert m.control_plugin.robot_namespace is None  # absent, unlike <robotNamespace/>
    empty = parse_urdf(robot(TWO_LINKS + control_plugin('')))
    assert empty.control_plugin.robot_namespace == ''


def test_control_period():
    xml = robot(
        TWO_LINKS
        + """<gazebo><plugin name="x" filename="libgazebo_ros_control.so">
        <robotNamespace>/ns</robotNamespace><controlPeriod>0.002</controlPeriod>
        </plugin></gazebo>"""
    )
    assert parse_urdf(xml).control_plugin.control_period == pytest.approx(0.002)


def test_other_plugins_are_not_the_control_plugin():
    xml = robot(
        TWO_LINKS
        + """<gazebo><plugin name="cam" filename="libgazebo_ros_camera.so">
        <robotNamespace>/cam</robotNamespace></plugin></gazebo>"""
    )
    assert parse_urdf(xml).control_plugin is None


def test_sensors_in_reference_blocks_are_collected():
    xml = robot(
        TWO_LINKS + '<gazebo reference="b"><sensor name="cam" type="camera"/>'
        '<mu1>0.5</mu1></gazebo>'
    )
    m = parse_urdf(xml)
    assert [(link, s.get('name')) for link, s in m.sensors] == [('b', 'cam')]
    assert m.gazebo_refs['b'] == {'mu1': '0.5'}


# ----------------------------------------------------------------------------- errors
def test_malformed_xml_gives_urdf_error_with_the_parser_message():
    bad = '<robot name="r"><link name="a"></robot>'
    with pytest.raises(ET.ParseError) as parser:
        ET.fromstring(bad)
    with pytest.raises(UrdfError) as exc:
        parse_urdf(bad)
    assert str(parser.value) in str(exc.value)
    assert 'line 1' in str(exc.value)


def test_wrong_root_element():
    with pytest.raises(UrdfError, match='<sdf>'):
        parse_urdf('<sdf version="1.6"><model name="m"/></sdf>')


def test_robot_without_links():
    with pytest.raises(UrdfError, match='no <link>'):
        parse_urdf('<robot name="empty"/>')


def test_non_numeric_limit_names_the_joint():
    body = TWO_LINKS.replace('upper="2"', 'upper="two"')
    with pytest.raises(UrdfError) as exc:
        parse_urdf(robot(body))
    assert "joint 'j'" in str(exc.value) and 'two' in str(exc.value)


def test_two_root_links_are_refused():
    with pytest.raises(UrdfError, match='one root link'):
        parse_urdf(robot(box_link('a') + box_link('b')))


def test_joint_without_child():
    body = box_link('a') + '<joint name="j" type="fixed"><parent link="a"/></joint>'
    with pytest.raises(UrdfError, match="'j'"):
        parse_urdf(robot(body))


# ----------------------------------------------------------------------------- meshes
def mesh_robot(uri, link='shell'):
    return robot(
        '<link name="%s"><visual><geometry><mesh filename="%s"/></geometry></visual>'
        '<collision><geometry><mesh filename="%s" scale="1 1 1"/></geometry></collision>'
        '</link>' % (link, uri, uri)
    )


def test_package_uri_resolves_through_find_package(find_package):
    out = resolve_mesh_uris(mesh_robot('package://arm1/meshes/link1.STL'), find_package)
    files = [m.get('filename') for m in ET.fromstring(out).iter('mesh')]
    assert files == [os.path.join(REPO_ROOT, 'meshes', 'link1.STL')] * 2
    assert all(os.path.isfile(f) for f in files)
    assert [m.get('scale') for m in ET.fromstring(out).iter('mesh')] == [None, '1 1 1']


def test_file_uri_and_plain_path(find_package):
    path = os.path.join(REPO_ROOT, 'meshes', 'link2.STL')
    for uri in ('file://' + path, path):
        out = resolve_mesh_uris(mesh_robot(uri), find_package)
        assert {m.get('filename') for m in ET.fromstring(out).iter('mesh')} == {path}


def test_a_missing_mesh_is_left_out_with_a_warning_naming_the_link_and_the_uri(
    find_package, caplog
):
    """As Gazebo's server: a missing visual is left out, a missing collision too (the link
    keeps its <inertial>), each said once; the model still spawns."""
    uri = 'package://arm1/meshes/elbow.STL'
    xml = robot(
        '<link name="forearm"><inertial><mass value="0.3"/>'
        '<inertia ixx="1e-3" iyy="1e-3" izz="1e-3" ixy="0" ixz="0" iyz="0"/></inertial>'
        '<visual><geometry><mesh filename="%s"/></geometry></visual>'
        '<collision><geometry><mesh filename="%s"/></geometry></collision>'
        '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>' % (uri, uri)
    )
    with caplog.at_level('WARNING'):
        out = ET.fromstring(resolve_mesh_uris(xml, find_package))
    link = out.find('link')
    assert link.find('visual') is None
    assert [c.find('geometry/box') is not None for c in link.findall('collision')] == [True]
    assert link.find('inertial/mass').get('value') == '0.3'
    said = [r.getMessage() for r in caplog.records]
    assert len(said) == 2 and all("'forearm'" in m and uri in m for m in said)
    assert 'visual' in said[0] and 'left out' in said[0]
    assert 'collision' in said[1] and 'keeps its inertia' in said[1]


def test_an_unknown_package_is_a_missing_mesh_named_with_its_link(find_package, caplog):
    with caplog.at_level('WARNING'):
        out = resolve_mesh_uris(mesh_robot('package://nowhere_pkg/m.stl', 'hand'), find_package)
    assert ET.fromstring(out).find('link').find('visual') is None
    assert any(
        "'hand'" in r.getMessage() and 'nowhere_pkg' in r.getMessage() for r in caplog.records
    )


def test_arm1_meshes_all_resolve(arm1_urdf, find_package):
    out = resolve_mesh_uris(arm1_urdf, find_package)
    files = {m.get('filename') for m in ET.fromstring(out).iter('mesh')}
    assert {
        os.path.join(REPO_ROOT, 'meshes', n + '.STL')
        for n in ('base_link', 'link1', 'link2', 'link3', 'link4')
    } <= files
    assert all(os.path.isabs(f) and os.path.isfile(f) for f in files)


# ----------------------------------------------------------------------------- limits
def chain(links):
    """A robot of ``links`` box links joined in a chain by fixed joints."""
    body = ''.join('<link name="l%d"/>' % i for i in range(links))
    body += ''.join(
        '<joint name="j%d" type="fixed"><parent link="l%d"/><child link="l%d"/>'
        '</joint>' % (i, i, i + 1)
        for i in range(links - 1)
    )
    return robot(body, 'chain')


def test_links_over_the_limit_are_refused_naming_limit_value_and_parameter():
    parse_urdf(chain(10), Limits(links_per_model=10))
    with pytest.raises(LimitError) as exc:
        parse_urdf(chain(11), Limits(links_per_model=10))
    msg = str(exc.value)
    assert "robot 'chain'" in msg and 'links per model is 11' in msg
    assert 'limit of 10' in msg and '~limits/links_per_model' in msg
    assert isinstance(exc.value, UrdfError)  # callers catching UrdfError see it too


def test_joints_over_the_limit_are_refused():
    with pytest.raises(LimitError, match='joints per model is 10, over the limit of 9'):
        parse_urdf(chain(11), Limits(joints_per_model=9))


def test_long_link_and_joint_names_are_refused_shortened():
    for kind, body in (
        ('link', box_link('a' * 300)),
        ('joint', TWO_LINKS.replace('name="j"', 'name="%s"' % ('j' * 300))),
    ):
        if kind == 'link':
            body += box_link(
                'b'
            ) + '<joint name="j" type="fixed"><parent link="%s"/><child link="b"/></joint>' % (
                'a' * 300
            )
        with pytest.raises(LimitError) as exc:
            parse_urdf(robot(body))
        msg = str(exc.value)
        assert msg.startswith('%s name' % kind) and 'name length is 300' in msg
        assert '~limits/name_length' in msg and len(msg) < 300


def test_link_without_a_name_is_refused():
    with pytest.raises(UrdfError, match='a <link> has no name'):
        parse_urdf(robot('<link/>'))


def test_oversized_description_is_refused_before_parsing():
    xml = robot(TWO_LINKS)
    parse_urdf(xml, Limits(description_bytes=len(xml)))
    with pytest.raises(LimitError) as exc:
        parse_urdf(xml + ' ', Limits(description_bytes=len(xml)))
    assert 'robot description: description bytes is %d' % (len(xml) + 1) in str(exc.value)


def test_arm1_fits_the_default_limits(arm1_urdf, find_package):
    parse_urdf(arm1_urdf, Limits())
    resolve_mesh_uris(arm1_urdf, find_package, Limits())


# ----------------------------------------------------------------------------- mesh guards
@pytest.fixture
def package(tmp_path):
    """A package 'pkg' in tmp_path/pkg with meshes/m.stl (12 triangles); secret.stl outside."""
    pkg = tmp_path / 'pkg'
    (pkg / 'meshes').mkdir(parents=True)
    cube = [[(0, 0, 0), (1, 0, 0), (0, 1, 0)]] * 12
    write_binary_stl(str(pkg / 'meshes' / 'm.stl'), cube)
    write_binary_stl(str(tmp_path / 'secret.stl'), cube)

    def find(name):
        if name == 'pkg':
            return str(pkg)
        raise LookupError(name)

    return pkg, find


@pytest.mark.parametrize(
    'uri',
    [
        'package://pkg/../secret.stl',
        'package://pkg/meshes/../../secret.stl',
        'package://pkg//etc/secret.stl',  # an absolute part would replace the package directory
    ],
)
def test_package_uri_that_climbs_out_is_refused(package, uri):
    pkg, find = package
    with pytest.raises(UrdfError) as exc:
        resolve_mesh_uris(mesh_robot(uri, 'hand'), find)
    msg = str(exc.value)
    assert "'hand'" in msg and uri in msg and "leaves package 'pkg'" in msg


def test_package_uri_with_dotdot_inside_the_package_resolves(package):
    pkg, find = package
    out = resolve_mesh_uris(mesh_robot('package://pkg/meshes/../meshes/m.stl'), find)
    assert {m.get('filename') for m in ET.fromstring(out).iter('mesh')} == {
        str(pkg / 'meshes' / 'm.stl')
    }


def test_symlink_the_package_holds_is_followed(package, tmp_path):
    # devel-space packages are trees of symlinks into the source: what the package holds counts
    pkg, find = package
    os.symlink(str(tmp_path / 'secret.stl'), str(pkg / 'meshes' / 'linked.stl'))
    out = resolve_mesh_uris(mesh_robot('package://pkg/meshes/linked.stl'), find)
    assert {m.get('filename') for m in ET.fromstring(out).iter('mesh')} == {
        str(pkg / 'meshes' / 'linked.stl')
    }


@pytest.mark.parametrize('name', ['passwd', 'm.png', 'm.stl.txt'])
def test_only_mesh_extensions_are_read(package, name):
    pkg, find = package
    (pkg / name).write_text('root:x:0:0:secret\n')
    with pytest.raises(UrdfError) as exc:
        resolve_mesh_uris(mesh_robot('package://pkg/' + name), find)
    assert 'only .stl, .obj, .dae meshes' in str(exc.value)
    assert 'secret' not in str(exc.value)


def test_mesh_that_is_not_a_regular_file_is_refused(package):
    pkg, find = package
    os.mkfifo(str(pkg / 'pipe.stl'))  # opening it would block the world
    (pkg / 'dir.obj').mkdir()
    for name in ('pipe.stl', 'dir.obj'):
        with pytest.raises(UrdfError, match='is not a regular file'):
            resolve_mesh_uris(mesh_robot('package://pkg/' + name), find)


def test_unsupported_uri_scheme_is_refused(find_package):
    with pytest.raises(UrdfError, match="scheme 'http://' is not supported"):
        resolve_mesh_uris(mesh_robot('http://example.com/m.stl'), find_package)


def test_mesh_over_the_byte_limit_is_refused(package):
    pkg, find = package
    size = os.path.getsize(str(pkg / 'meshes' / 'm.stl'))
    with pytest.raises(LimitError) as exc:
        resolve_mesh_uris(
            mesh_robot('package://pkg/meshes/m.stl'), find, Limits(mesh_bytes=size - 1)
        )
    assert 'mesh bytes is %d, over the limit of %d' % (size, size - 1) in str(exc.value)
    assert 'package://pkg/meshes/m.stl' in str(exc.value)


def test_mesh_over_the_triangle_limit_is_refused(package):
    pkg, find = package
    resolve_mesh_uris(mesh_robot('package://pkg/meshes/m.stl'), find, Limits(mesh_triangles=12))
    with pytest.raises(LimitError, match='mesh triangles is 12, over the limit of 11'):
        resolve_mesh_uris(mesh_robot('package://pkg/meshes/m.stl'), find, Limits(mesh_triangles=11))


def test_broken_mesh_is_refused_without_its_contents(package):
    pkg, find = package
    (pkg / 'broken.stl').write_text('root:x:0:0:secret-line\n' * 10)
    with pytest.raises(UrdfError) as exc:
        resolve_mesh_uris(mesh_robot('package://pkg/broken.stl'), find)
    assert 'neither a binary STL' in str(exc.value) and 'secret' not in str(exc.value)
