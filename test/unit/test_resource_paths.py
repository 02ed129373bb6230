"""Gazebo's resource paths: world names and model:// URIs found as Gazebo finds them, and
arm1's own standard worlds and built-in models (sun, ground_plane)."""

import os

import pybullet as p
import pytest

from _arm1sim.description.resource_paths import (
    SHARE,
    PackageExports,
    ResourceNotFound,
    gazebo_paths,
)
from _arm1sim.description.sdf_world import read_world
from _arm1sim.sim.simulation import Simulation

BOX = """<?xml version="1.0"?>
<robot name="box"><link name="box">
  <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
  </inertial>
  <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
</link></robot>"""


def write(path, text):
    os.makedirs(os.path.dirname(str(path)), exist_ok=True)
    with open(str(path), 'w') as f:
        f.write(text)
    return str(path)


def model_folder(base, name, sdf_name='model.sdf', config=True, z=0.0):
    folder = os.path.join(str(base), name)
    if config:
        write(
            os.path.join(folder, 'model.config'),
            '<model><name>%s</name><sdf version="1.6">%s</sdf></model>' % (name, sdf_name),
        )
    write(
        os.path.join(folder, sdf_name),
        '<sdf version="1.6"><model name="%s"><static>true</static><pose>0 0 %g 0 0 0</pose>'
        '<link name="l"><collision name="c"><geometry><box><size>1 1 1</size></box>'
        '</geometry></collision></link></model></sdf>' % (name, z),
    )
    return folder


def test_world_name_is_found_on_gazebo_resource_path(tmp_path):
    world = write(tmp_path / 'share' / 'worlds' / 'mine.world', '<sdf><world/></sdf>')
    paths = gazebo_paths({'GAZEBO_RESOURCE_PATH': str(tmp_path / 'share')})
    assert paths.find_world('worlds/mine.world', cwd=str(tmp_path)) == world


def test_world_name_relative_to_the_working_directory_comes_first(tmp_path):
    here = write(tmp_path / 'worlds' / 'empty.world', '<sdf><world/></sdf>')
    assert gazebo_paths({}).find_world('worlds/empty.world', cwd=str(tmp_path)) == here


def test_gazebo_standard_empty_world_is_ours_when_nobody_else_has_one(tmp_path):
    path = gazebo_paths({}).find_world('worlds/empty.world', cwd=str(tmp_path))
    assert path == os.path.join(SHARE, 'worlds', 'empty.world')


def test_users_resource_path_wins_over_our_share(tmp_path):
    mine = write(tmp_path / 'worlds' / 'empty.world', '<sdf><world/></sdf>')
    paths = gazebo_paths({'GAZEBO_RESOURCE_PATH': str(tmp_path)})
    assert paths.find_world('worlds/empty.world', cwd='/nonexistent') == mine


def test_missing_world_names_every_path_tried(tmp_path):
    paths = gazebo_paths({'GAZEBO_RESOURCE_PATH': '/first:/second'})
    with pytest.raises(ResourceNotFound) as err:
        paths.find_world('worlds/nope.world', cwd=str(tmp_path))
    msg = str(err.value)
    for tried in (
        str(tmp_path),
        '/first/worlds/nope.world',
        '/second/worlds/nope.world',
        os.path.join(SHARE, 'worlds', 'nope.world'),
    ):
        assert tried in msg


def test_missing_absolute_world_is_named(tmp_path):
    with pytest.raises(ResourceNotFound, match='nope.world'):
        gazebo_paths({}).find_world(str(tmp_path / 'nope.world'))


def test_model_uri_uses_model_config_sdf_on_gazebo_model_path(tmp_path):
    folder = model_folder(tmp_path, 'table', sdf_name='table.sdf')
    paths = gazebo_paths({'GAZEBO_MODEL_PATH': str(tmp_path)})
    assert paths.find_model('model://table') == os.path.join(folder, 'table.sdf')


def test_package_export_gazebo_model_path_is_searched(tmp_path):
    folder = model_folder(tmp_path / 'pkg' / 'models', 'gripper', config=False)
    exports = [PackageExports(model_paths=[str(tmp_path / 'pkg' / 'models')])]
    assert gazebo_paths({}, exports).find_model('model://gripper') == os.path.join(
        folder, 'model.sdf'
    )


def test_package_export_gazebo_media_path_joins_the_resource_path(tmp_path):
    world = write(tmp_path / 'media' / 'worlds' / 'cell.world', '<sdf><world/></sdf>')
    exports = [PackageExports(media_paths=[str(tmp_path / 'media')])]
    assert gazebo_paths({}, exports).find_world('worlds/cell.world', cwd='/') == world


def test_missing_model_names_the_paths_tried(tmp_path):
    paths = gazebo_paths({'GAZEBO_MODEL_PATH': str(tmp_path)})
    with pytest.raises(ResourceNotFound) as err:
        paths.find_model('model://nothing_here')
    assert os.path.join(str(tmp_path), 'nothing_here') in str(err.value)
    assert os.path.join(SHARE, 'models', 'nothing_here') in str(err.value)


def test_model_uri_cannot_climb_out_of_the_model_path():
    with pytest.raises(ResourceNotFound):
        gazebo_paths({}).find_model('model://../worlds')


def test_empty_world_builds_a_ground_plane_and_skips_only_nothing():
    paths = gazebo_paths({})
    cfg = read_world(paths.find_world('worlds/empty.world', cwd='/'), paths.find_model)
    assert [m.name for m in cfg.models] == ['ground_plane']
    assert cfg.models[0].shapes[0].kind == 'plane'
    assert cfg.skipped == []  # the sun is a light: nothing to build, nothing to warn about


def test_include_name_pose_and_static_override_the_models(tmp_path):
    model_folder(tmp_path, 'crate', z=5)
    write(
        tmp_path / 'w.world',
        '<sdf version="1.6"><world name="w"><include><uri>model://crate</uri>'
        '<name>crate_2</name><pose>1 2 3 0 0 0</pose></include></world></sdf>',
    )
    paths = gazebo_paths({'GAZEBO_MODEL_PATH': str(tmp_path)})
    cfg = read_world(str(tmp_path / 'w.world'), paths.find_model)
    # <include><pose> replaces the model's own <pose> (z=5), as in Gazebo
    assert [(m.name, m.position) for m in cfg.spawns] == [('crate_2', (1.0, 2.0, 3.0))]


def test_unknown_include_is_skipped_naming_the_paths(tmp_path):
    write(
        tmp_path / 'w.world',
        '<sdf version="1.6"><world name="w"><include><uri>model://ghost</uri></include>'
        '</world></sdf>',
    )
    cfg = read_world(str(tmp_path / 'w.world'), gazebo_paths({}).find_model)
    assert cfg.skipped[0][0] == 'model://ghost'
    assert os.path.join(SHARE, 'models', 'ghost') in cfg.skipped[0][1]


def test_box_dropped_in_empty_world_rests_on_the_ground():
    paths = gazebo_paths({})
    sim = Simulation(read_world(paths.find_world('worlds/empty.world', cwd='/'), paths.find_model))
    try:
        model = sim.spawn_urdf('box', BOX, position=(0, 0, 1.0))
        for _ in range(int(2.0 / sim.period)):
            sim.step()
        z = p.getBasePositionAndOrientation(model.robot.body, physicsClientId=model.robot.client)[
            0
        ][2]
        assert z == pytest.approx(0.1, abs=0.01)  # half the box's height above z=0
    finally:
        sim.close()
