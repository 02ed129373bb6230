"""physics/urdf_model.py: what the simulator reads from a URDF."""
import os
import xml.etree.ElementTree as ET

import pytest

from arm1.control.hardware_interface import EFFORT_JOINT_INTERFACE
from arm1.physics.urdf_model import UrdfError, parse_urdf, resolve_mesh_uris
from conftest import MIXED_URDF, REPO_ROOT, box_link, control_plugin, transmission

ARM1_LIMITS = {
    'joint1': (-1.57, 1.57), 'joint2': (0.01, 1.57),
    'joint3': (-1.0, 1.57), 'joint4': (-0.8, 1.57),
}


def robot(body, name='r'):
    return '<robot name="%s">%s</robot>' % (name, body)


TWO_LINKS = box_link('a') + box_link('b') + """
  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>
    <limit lower="-1" upper="2" effort="3" velocity="4"/></joint>"""


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
        ('tran1', 'joint1'), ('tran2', 'joint2'), ('tran3', 'joint3'), ('tran4', 'joint4')]
    assert all(t.interfaces == [EFFORT_JOINT_INTERFACE] for t in m.transmissions)
    assert [(j.name, i) for j, i in m.actuated_joints()] == [
        ('joint%d' % n, EFFORT_JOINT_INTERFACE) for n in range(1, 5)]
    assert m.control_plugin.robot_namespace == '/arm1'
    assert m.control_plugin.robot_sim_type == 'gazebo_ros_control/DefaultRobotHWSim'
    assert m.control_plugin.control_period is None


def test_arm1_gazebo_reference_tags(arm1_urdf):
    m = parse_urdf(arm1_urdf)
    assert m.gazebo_refs['base_link'] == {'material': 'Gazebo/White'}
    assert m.gazebo_refs['link1'] == {'mu1': '0.2', 'mu2': '0.2', 'material': 'Gazebo/Orange'}
    assert {'base_link', 'link1', 'link2', 'link3', 'link4'} <= set(m.gazebo_refs)
    assert all(m.gazebo_refs[l]['material'].startswith('Gazebo/') for l in m.gazebo_refs)


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
    body = box_link('a') + box_link('b') + """
      <joint name="f" type="fixed"><parent link="a"/><child link="b"/></joint>"""
    assert parse_urdf(robot(body + transmission('f'))).actuated_joints() == []


def test_no_plugin_and_plugin_without_namespace():
    assert parse_urdf(robot(TWO_LINKS)).control_plugin is None
    m = parse_urdf(robot(TWO_LINKS + control_plugin(None)))
    assert m.control_plugin is not None
    assert m.control_plugin.robot_namespace == ''


def test_control_period():
    xml = robot(TWO_LINKS + """<gazebo><plugin name="x" filename="libgazebo_ros_control.so">
        <robotNamespace>/ns</robotNamespace><controlPeriod>0.002</controlPeriod>
        </plugin></gazebo>""")
    assert parse_urdf(xml).control_plugin.control_period == pytest.approx(0.002)


def test_other_plugins_are_not_the_control_plugin():
    xml = robot(TWO_LINKS + """<gazebo><plugin name="cam" filename="libgazebo_ros_camera.so">
        <robotNamespace>/cam</robotNamespace></plugin></gazebo>""")
    assert parse_urdf(xml).control_plugin is None


def test_sensors_in_reference_blocks_are_collected():
    xml = robot(TWO_LINKS + '<gazebo reference="b"><sensor name="cam" type="camera"/>'
                '<mu1>0.5</mu1></gazebo>')
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
    return robot('<link name="%s"><visual><geometry><mesh filename="%s"/></geometry></visual>'
                 '<collision><geometry><mesh filename="%s" scale="1 1 1"/></geometry></collision>'
                 '</link>' % (link, uri, uri))


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


def test_missing_mesh_names_the_path_and_the_link(find_package):
    with pytest.raises(UrdfError) as exc:
        resolve_mesh_uris(mesh_robot('package://arm1/meshes/elbow.STL', 'forearm'), find_package)
    msg = str(exc.value)
    assert "'forearm'" in msg
    assert os.path.join(REPO_ROOT, 'meshes', 'elbow.STL') in msg


def test_unknown_package_names_the_package_and_the_link(find_package):
    with pytest.raises(UrdfError) as exc:
        resolve_mesh_uris(mesh_robot('package://nowhere_pkg/m.stl', 'hand'), find_package)
    assert "'nowhere_pkg'" in str(exc.value) and "'hand'" in str(exc.value)


def test_arm1_meshes_all_resolve(arm1_urdf, find_package):
    out = resolve_mesh_uris(arm1_urdf, find_package)
    files = {m.get('filename') for m in ET.fromstring(out).iter('mesh')}
    assert {os.path.join(REPO_ROOT, 'meshes', n + '.STL')
            for n in ('base_link', 'link1', 'link2', 'link3', 'link4')} <= files
    assert all(os.path.isabs(f) and os.path.isfile(f) for f in files)
