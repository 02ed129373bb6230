"""physics/sdf_world.py: what a Gazebo world file gives the pybullet world."""

import xml.etree.ElementTree as ET

import pytest
from conftest import WORLD_FILE

from _arm1sim.description.limits import Limits
from _arm1sim.description.resource_paths import ResourcePaths
from _arm1sim.description.sdf_world import SdfError, WorldConfig, parse_world, read_world


def world(body):
    return '<sdf version="1.6"><world name="default">%s</world></sdf>' % body


def test_the_projects_world_file():
    cfg = read_world(WORLD_FILE)
    assert cfg.max_step_size == pytest.approx(0.001)
    assert cfg.real_time_factor == pytest.approx(1.0)
    assert cfg.real_time_update_rate == pytest.approx(1000.0)
    assert cfg.gravity == (0.0, 0.0, -9.8)
    assert [m.name for m in cfg.models] == ['ground_plane']
    ground = cfg.models[0]
    assert [(s.kind, s.size) for s in ground.shapes] == [('plane', (0.0, 0.0, 1.0))]
    names = [name for name, _ in cfg.skipped]
    assert names == ['willowgarage']
    assert 'model://willowgarage' in cfg.skipped[0][1]


def test_physics_block_and_gravity():
    cfg = parse_world(
        world("""
        <gravity>0 0 -1.62</gravity>
        <physics name="p" type="ode"><max_step_size>0.002</max_step_size>
          <real_time_factor>0.5</real_time_factor>
          <real_time_update_rate>0</real_time_update_rate></physics>""")
    )
    assert (cfg.max_step_size, cfg.real_time_factor, cfg.real_time_update_rate) == (0.002, 0.5, 0.0)
    assert cfg.gravity == (0.0, 0.0, -1.62)


def test_defaults_are_gazebos():
    cfg = parse_world(world(''))
    d = WorldConfig()
    assert (cfg.max_step_size, cfg.real_time_factor, cfg.real_time_update_rate) == (
        0.001,
        1.0,
        1000.0,
    )
    assert cfg.gravity == d.gravity == (0.0, 0.0, -9.8)
    assert cfg.models == [] and cfg.skipped == []


def test_include_is_skipped_with_its_name_or_uri():
    cfg = parse_world(
        world("""
        <include><uri>model://sun</uri></include>
        <include><uri>model://table</uri><name>my_table</name></include>""")
    )
    assert [n for n, _ in cfg.skipped] == ['model://sun', 'my_table']
    assert all('cannot fetch' in why for _, why in cfg.skipped)


def test_static_primitive_models_become_fixed_base_urdf_spawns_with_their_poses():
    cfg = parse_world(
        world("""
      <model name="block"><static>true</static><pose>1 2 0 0 0 0</pose>
        <link name="l"><pose>0 0 0.5 0 0 0</pose>
          <collision name="c"><pose>0.1 0 0 0 0 0</pose>
            <geometry><box><size>1 2 3</size></box></geometry></collision>
          <collision name="c2"><geometry><sphere><radius>0.2</radius></sphere></geometry>
          </collision>
          <collision name="c3"><geometry><cylinder><radius>0.1</radius><length>0.4</length>
            </cylinder></geometry></collision>
        </link></model>""")
    )
    assert cfg.models == [] and cfg.skipped == []
    (spawn,) = cfg.spawns
    assert spawn.name == 'block' and spawn.position == pytest.approx((1.0, 2.0, 0.0))
    robot = ET.fromstring(spawn.urdf)
    assert robot.get('name') == 'block'
    assert [link.get('name') for link in robot.findall('link')] == ['world', 'l']
    (joint,) = robot.findall('joint')
    assert joint.get('type') == 'fixed' and joint.find('parent').get('link') == 'world'
    assert joint.find('origin').get('xyz') == '0 0 0.5'
    sizes = [c.find('geometry')[0].attrib for c in robot.iter('collision')]
    assert sizes == [{'size': '1.0 2.0 3.0'}, {'radius': '0.2'}, {'radius': '0.1', 'length': '0.4'}]
    assert robot.find('link/collision/origin').get('xyz') == '0.1 0 0'


def test_plane_only_static_models_stay_scenery():
    cfg = parse_world(
        world("""
      <model name="floor"><static>true</static><link name="l"><collision name="c">
        <geometry><plane><normal>0 0 1</normal><size>10 10</size></plane></geometry>
      </collision></link></model>""")
    )
    assert [(m.name, m.shapes[0].kind) for m in cfg.models] == [('floor', 'plane')]
    assert cfg.spawns == []


def test_dynamic_models_are_built_and_unbuildable_ones_skipped_with_a_reason():
    cfg = parse_world(
        world("""
      <model name="dynamic_box"><link name="l"><collision name="c">
        <geometry><box><size>1 1 1</size></box></geometry></collision></link></model>
      <model name="meshy"><static>1</static><link name="l"><collision name="c">
        <geometry><mesh><uri>model://x/m.dae</uri></mesh></geometry></collision></link></model>
      <model name="ghost"><static>true</static><link name="l"/></model>
      <model name="nolinks"><static>true</static></model>
      <model name="blob"><link name="l"><collision name="c">
        <geometry><heightmap/></geometry></collision></link></model>""")
    )
    assert [s.name for s in cfg.spawns] == ['dynamic_box', 'ghost']
    dynamic = ET.fromstring(cfg.spawns[0].urdf)
    assert [link.get('name') for link in dynamic.findall('link')] == ['l']  # free: no world
    reasons = dict(cfg.skipped)
    assert set(reasons) == {'meshy', 'nolinks', 'blob'}
    assert 'model://x/m.dae' in reasons['meshy']
    assert 'no <link>' in reasons['nolinks']
    assert 'heightmap' in reasons['blob'] and "'c'" in reasons['blob']


def test_include_of_a_model_on_the_model_path_is_built_with_its_mesh(tmp_path):
    folder = tmp_path / 'mug'
    (folder / 'meshes').mkdir(parents=True)
    (folder / 'meshes' / 'mug.stl').write_bytes(b'')
    (folder / 'model.sdf').write_text(
        '<sdf version="1.6"><model name="mug"><pose>0 0 1 0 0 0</pose><link name="body">'
        '<collision name="c"><geometry><mesh><uri>model://mug/meshes/mug.stl</uri>'
        '<scale>0.1 0.1 0.1</scale></mesh></geometry></collision>'
        '<visual name="v"><geometry><mesh><uri>meshes/mug.stl</uri></mesh></geometry></visual>'
        '</link></model></sdf>'
    )
    paths = ResourcePaths([], [str(tmp_path)])
    cfg = parse_world(
        world("""
      <include><uri>model://mug</uri><name>cup</name><pose>2 0 0 0 0 0</pose></include>
      <include><uri>model://nowhere</uri></include>"""),
        find_model=paths.find_model,
    )
    (spawn,) = cfg.spawns
    assert spawn.name == 'cup' and spawn.position == pytest.approx((2.0, 0.0, 0.0))
    meshes = [m.attrib for m in ET.fromstring(spawn.urdf).iter('mesh')]
    path = str(folder / 'meshes' / 'mug.stl')
    assert meshes == [
        {'filename': path, 'scale': '1.0 1.0 1.0'},
        {'filename': path, 'scale': '0.1 0.1 0.1'},
    ]
    ((name, why),) = cfg.skipped
    assert name == 'model://nowhere' and 'not found' in why


def test_malformed_xml_names_the_source_and_the_parser_message():
    with pytest.raises(SdfError) as exc:
        parse_world('<sdf><world name="w"><physics></world></sdf>', 'broken.world')
    assert 'broken.world' in str(exc.value)
    assert 'mismatched tag' in str(exc.value)


def test_missing_world_element():
    with pytest.raises(SdfError, match='<sdf><world>'):
        parse_world('<sdf version="1.6"><model name="m"/></sdf>', 'm.sdf')


@pytest.mark.parametrize(
    'body, culprit',
    [
        ('<gravity>0 0</gravity>', 'gravity'),
        ('<physics><max_step_size>fast</max_step_size></physics>', 'max_step_size'),
        ('<physics><max_step_size>0</max_step_size></physics>', 'max_step_size'),
    ],
)
def test_bad_numbers_name_the_element(body, culprit):
    with pytest.raises(SdfError, match=culprit):
        parse_world(world(body), 'w.world')


def test_unreadable_file(tmp_path):
    with pytest.raises(SdfError, match='cannot read world file'):
        read_world(str(tmp_path / 'nope.world'))


# ----------------------------------------------------------------------------- limits plugin
def limits_plugin(body, filename='libarm1_limits.so'):
    return '<plugin name="arm1_limits" filename="%s">%s</plugin>' % (filename, body)


def test_limits_plugin_sets_the_worlds_limits_over_the_defaults():
    cfg = parse_world(
        world(
            limits_plugin(
                '<camera_pixels>100000000</camera_pixels><models> 5 </models>'
                '<sensor_update_rate>2000.5</sensor_update_rate>'
            )
        )
    )
    assert cfg.limits.camera_pixels == 100000000
    assert cfg.limits.models == 5
    assert cfg.limits.sensor_update_rate == 2000.5
    assert cfg.limits.links_per_model == Limits().links_per_model


def test_without_the_plugin_the_limits_are_the_defaults():
    assert parse_world(world('')).limits == Limits()
    assert read_world(WORLD_FILE).limits == Limits()
    # another plugin's parameters are not limits
    other = limits_plugin('<camera_pixels>1</camera_pixels>', 'libgazebo_ros_api_plugin.so')
    assert parse_world(world(other)).limits == Limits()


@pytest.mark.parametrize(
    'body, words',
    [
        ('<camera_pixels>many</camera_pixels>', ['camera_pixels', "'many'", 'not a number']),
        ('<camera_pixels>-1</camera_pixels>', ['camera_pixels', 'positive']),
        ('<models>inf</models>', ['models', 'positive']),
        ('<camera_pxels>1</camera_pxels>', ['unknown limit', 'camera_pxels', 'camera_pixels']),
        ('<models>1</models><models>2</models>', ['models', 'given twice']),
    ],
)
def test_bad_limits_name_the_file_and_the_limit(body, words):
    with pytest.raises(SdfError) as exc:
        parse_world(world(limits_plugin(body)), 'mine.world')
    assert 'mine.world' in str(exc.value)
    for w in words:
        assert w in str(exc.value)


def test_world_file_with_a_dtd_is_refused():
    doc = (
        '<?xml version="1.0"?><!DOCTYPE sdf [<!ENTITY a "aaaaaaaaaa">'
        '<!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">]>' + world('<gravity>&b;</gravity>')
    )
    with pytest.raises(SdfError) as exc:
        parse_world(doc, 'laughs.world')
    assert 'laughs.world' in str(exc.value) and 'DOCTYPE' in str(exc.value)
