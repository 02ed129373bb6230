"""Issue 22, case 7: pybullet is handed only what it reads of a description, parsed once.

pybullet's loadURDF parses its file in one call on the physics thread: a 50 MB request of
comments, whitespace or <gazebo> text stopped physics for 0.26-1.3 s while it was loaded.
"""

import os
import sys
import xml.etree.ElementTree as ET

import pytest

from _arm1sim.description import safe_xml
from _arm1sim.description.compact_urdf import compact_urdf
from _arm1sim.description.gazebo_tags import PYBULLET_LINE
from _arm1sim.description.limits import Limits
from _arm1sim.description.sdf_world import WorldConfig
from _arm1sim.description.urdf_model import UrdfError, UrdfLimitError, parse_description, parse_urdf
from _arm1sim.sim.simulation import Simulation, SpawnError

INERTIAL = (
    '<inertial><origin xyz="0 0 0.1"/><mass value="0.5"/>'
    '<inertia ixx="1e-3" iyy="1e-3" izz="1e-3" ixy="0" ixz="0" iyz="0"/></inertial>'
)
ROBOT = (
    '<robot name="r"><!-- a comment -->\n'
    '  <material name="red"><color rgba="1 0 0 1"/></material>\n'
    '  <link name="base">%s<visual name="v"><geometry><box size="0.1 0.2 0.3"/></geometry>'
    '<material name="red"/></visual>'
    '<collision><geometry><cylinder radius="0.1" length="0.2"/></geometry></collision>'
    '<contact><lateral_friction value="0.7"/></contact><notes>some words</notes></link>\n'
    '  <link name="arm">%s</link>\n'
    '  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>'
    '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="5" velocity="2"/>'
    '<dynamics damping="0.1" friction="0.2"/><calibration rising="0"/></joint>\n'
    '  <transmission name="t"><type>transmission_interface/SimpleTransmission</type>'
    '<joint name="j"><hardwareInterface>EffortJointInterface</hardwareInterface></joint>'
    '</transmission>\n'
    '  <gazebo reference="base"><mu1>0.5</mu1></gazebo>\n'
    '  <gazebo><plugin name="p" filename="libgazebo_ros_control.so"/></gazebo>\n'
    '  <unknown_tool_tag a="b">text</unknown_tool_tag>\n'
    '</robot>'
) % (INERTIAL, INERTIAL)


def _shape(element):
    """(tag, attributes, children) of a tree, without text."""
    return (element.tag, dict(element.attrib), [_shape(c) for c in element])


def test_links_joints_and_materials_are_kept_whole_and_the_rest_dropped():
    root = parse_description(ROBOT)
    before = ET.tostring(root, encoding='unicode')
    text = compact_urdf(root)
    assert ET.tostring(root, encoding='unicode') == before, 'the parsed tree was changed'
    out = ET.fromstring(text)
    assert out.tag == 'robot' and out.get('name') == 'r'
    assert [c.tag for c in out] == ['material', 'link', 'link', 'joint']
    kept = [c for c in root if c.tag in ('material', 'link', 'joint')]
    for mine, theirs in zip(out, kept):
        expected = _shape(theirs)
        if theirs.get('name') == 'base':  # <notes> is no URDF element pybullet reads
            expected[2].pop()
        assert _shape(mine) == expected
    for word in ('comment', 'gazebo', 'transmission', 'unknown_tool_tag', 'some words', 'mu1'):
        assert word not in text
    # one element per line: pybullet loses pieces of long lines
    assert all(line.count('<') <= 1 for line in text.splitlines())
    # the same robot for the simulator
    assert parse_urdf(text).joints['j'] == parse_urdf(ROBOT).joints['j']


def test_an_element_longer_than_pybullet_reads_on_a_line_is_refused_naming_it():
    long = (
        '<robot name="r"><link name="base"><visual><origin xyz="0 0 0" junk="%s"/>'
        % ('y' * PYBULLET_LINE)
        + '<geometry><box size="1 1 1"/></geometry></visual></link></robot>'
    )
    with pytest.raises(UrdfError) as info:
        compact_urdf(parse_description(long))
    message = str(info.value)
    assert "<origin> of link 'base'" in message and 'junk' in message
    assert str(PYBULLET_LINE) in message


def test_utf8_size_counts_as_encode_does_across_pieces(monkeypatch):
    monkeypatch.setattr(safe_xml, 'PIECE', 5)
    for text in ('', 'plain ascii text', 'é' * 11 + 'x€𝄞' * 7, 'a\ud800b' * 4):
        assert safe_xml.utf8_size(text) == len(text.encode('utf-8', 'surrogatepass'))
    assert safe_xml.utf8_size(b'\xff\xfe') == 2


BULK = 50 * 1000 * 1000  # characters: issue 22's 50 MB, inside the 64 MiB default limit


def _big(kind):
    if kind == 'comments':
        line = '<!-- %s -->\n' % ('x' * 90)
        pad = line * (BULK // len(line))
    elif kind == 'gazebo text':
        pad = '<gazebo><plugin name="p" filename="libx.so"><blob>%s</blob></plugin></gazebo>' % (
            'y' * BULK
        )
    else:
        pad = ' ' * BULK
    return ROBOT.replace('</robot>', pad + '</robot>')


@pytest.mark.parametrize('kind', ['comments', 'gazebo text', 'whitespace'])
def test_a_50_mb_description_is_parsed_once_and_pybullet_loads_a_small_file(kind, monkeypatch):
    text = _big(kind)
    assert len(text) > BULK
    big_parses = []
    feed = safe_xml.feed_in_pieces

    def counted(parser, doc):
        if len(doc) > 1e6:
            big_parses.append(len(doc))
        return feed(parser, doc)

    monkeypatch.setattr(safe_xml, 'feed_in_pieces', counted)
    sim = Simulation(WorldConfig(models=[]))
    try:
        prepared = sim.prepare_urdf('big', text)
        assert len(big_parses) == 1, 'the request was parsed %d times' % len(big_parses)
        path = prepared.load_args[0]
        # what the physics thread hands loadURDF: the robot's 4 parts, not 50 MB
        assert os.path.getsize(path) < 4096, os.path.getsize(path)
        model = sim.spawn_prepared(prepared)
        assert sorted(model.robot.joint_index) == ['j']
        assert model.description.control_plugin is not None  # read from the request's <gazebo>
        sim.step()
        sim.delete_model('big')
        assert not os.path.exists(path)
    finally:
        sim.close()


def test_a_description_over_the_limit_in_utf8_bytes_is_refused_naming_it():
    sim = Simulation(WorldConfig(models=[]))
    try:
        sim.limits.description_bytes = len(ROBOT) + 900
        text = ROBOT.replace('</robot>', 'é' * 600 + '</robot>')  # 600 characters, 1200 bytes
        assert len(text) < sim.limits.description_bytes
        with pytest.raises(SpawnError) as info:
            sim.prepare_urdf('big', text)
    finally:
        sim.close()
    assert "'big'" in str(info.value) and 'description bytes' in str(info.value)


def _shapes(boxes, cylinders):
    visual = '<visual><geometry>%s</geometry></visual>'
    return '<robot name="many"><link name="base">%s%s%s</link></robot>' % (
        INERTIAL,
        visual % '<box size="0.1 0.1 0.1"/>' * boxes,
        visual % '<cylinder radius="0.1" length="0.1"/>' * cylinders,
    )


def test_shapes_per_model_counts_a_round_shape_as_20_boxes_and_refuses_past_the_limit():
    limits = Limits()
    assert limits.shapes_per_model == 2000  # what pybullet builds in ~50 ms (limits.py)
    parse_urdf(_shapes(2000, 0), limits)
    parse_urdf(_shapes(1980, 1), limits)
    parse_urdf(_shapes(0, 100), limits)
    for boxes, cylinders in ((2001, 0), (0, 101), (1981, 1)):
        with pytest.raises(UrdfLimitError) as info:
            parse_urdf(_shapes(boxes, cylinders), limits)
        message = str(info.value)
        assert "robot 'many'" in message and 'shapes per model is' in message
        assert 'over the limit of 2000' in message and '~limits/shapes_per_model' in message
        assert 'a sphere, cylinder or capsule counts 20' in message


def test_a_spawn_past_the_shape_limit_is_refused_naming_the_model_and_leaves_nothing():
    sim = Simulation(WorldConfig(models=[]))
    try:
        files = set(os.listdir(sim._tmp.name))
        with pytest.raises(SpawnError) as info:
            sim.spawn_urdf('many', _shapes(0, 500))
        assert "cannot spawn 'many'" in str(info.value) and 'shapes per model' in str(info.value)
        assert 'many' not in sim.models and not sim.world.robots
        assert set(os.listdir(sim._tmp.name)) == files
        sim.spawn_urdf('many', _shapes(0, 100))  # the name is free
    finally:
        sim.close()


def test_comments_of_a_request_cost_no_python_call_and_text_around_them_is_joined():
    text = '<robot name="r"><gazebo><mu1>0.<!-- c -->5</mu1></gazebo>%s</robot>' % (
        '<!-- padding -->' * 1000
    )
    calls = []

    def profile(frame, event, arg):
        if event == 'call':
            calls.append(frame.f_code.co_name)

    sys.setprofile(profile)
    try:
        root = safe_xml.parse(text, 'robot description')
    finally:
        sys.setprofile(None)
    assert root.find('gazebo/mu1').text == '0.5'
    # before: ElementTree's Comment() was called for each (50 MB of comments: 4.1 s, 0.31 now)
    assert 'Comment' not in calls and 'comment' not in calls
