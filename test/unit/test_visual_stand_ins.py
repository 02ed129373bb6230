"""physics/visual_stand_ins.py: large visual meshes are not parsed on the physics thread."""

import os
import time

import pytest

from _arm1sim.bench.dense_meshes import u_bracket, write_mesh
from _arm1sim.description.sdf_world import WorldConfig
from _arm1sim.physics.visual_stand_ins import VISUAL_LOAD_BUDGET, light_visuals, over_budget
from _arm1sim.ros.web.web_snapshot import visuals_of
from _arm1sim.sim.simulation import Simulation


def urdf(*meshes):
    visuals = ''.join(
        '<visual><origin xyz="0 0 0.1"/><geometry><mesh filename="%s" scale="2 2 2"/></geometry>'
        '<material name="m"><color rgba="0.1 0.2 0.3 1"/></material></visual>' % m
        for m in meshes
    )
    return (
        '<robot name="r"><link name="base"><inertial><mass value="1"/>'
        '<inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>%s'
        '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link></robot>'
        % visuals
    )


@pytest.fixture(scope='module')
def meshes(tmp_path_factory):
    """A 200 k-triangle STL (10 MB) and Collada (24 MB), and a 2 k-triangle STL."""
    folder = tmp_path_factory.mktemp('meshes')
    out = {}
    for name, triangles in (('big.stl', 200000), ('big.dae', 200000), ('small.stl', 2000)):
        out[name] = str(folder / name)
        write_mesh(out[name], u_bracket(triangles))
    return out


def test_only_files_over_their_formats_budget_are_stood_in(meshes, tmp_path):
    assert os.path.getsize(meshes['big.stl']) > VISUAL_LOAD_BUDGET['.stl']
    assert over_budget(meshes['big.stl']) and over_budget(meshes['big.dae'])
    assert not over_budget(meshes['small.stl'])
    assert not over_budget(str(tmp_path / 'missing.stl'))  # pybullet warns of it, as before
    xml = urdf(meshes['small.stl'])
    assert light_visuals(xml, str(tmp_path)) == (xml, {})
    light, stand_ins = light_visuals(urdf(meshes['small.stl'], meshes['big.dae']), str(tmp_path))
    ((stand_in, real),) = stand_ins.items()
    assert real == meshes['big.dae'] and os.path.dirname(stand_in) == str(tmp_path)
    assert os.path.getsize(stand_in) < 1000
    assert stand_in in light and meshes['small.stl'] in light and meshes['big.dae'] not in light
    assert 'scale="2 2 2"' in light and 'rgba="0.1 0.2 0.3 1"' in light


def test_a_spawn_with_large_visuals_costs_the_physics_thread_no_parse(meshes):
    sim = Simulation(WorldConfig())
    try:
        prepared = sim.prepare_urdf('m', urdf(meshes['big.stl'], meshes['big.dae']))
        start = time.process_time()
        model = sim.spawn_prepared(prepared)
        took = time.process_time() - start
        # pybullet took 0.22 s (STL) and 0.81 s (Collada) of CPU parsing these
        assert took < 0.05, 'spawn on the physics thread took %.3f s of CPU' % took
        with open(model.file) as f:  # the render processes' URDF names the real meshes
            rendered = f.read()
        assert meshes['big.stl'] in rendered and meshes['big.dae'] in rendered
        shown = visuals_of(sim.world.client, model.robot.body, model.visual_stand_ins)
        assert sorted(v.mesh for v in shown) == sorted([meshes['big.stl'], meshes['big.dae']])
        assert all(v.size == (2.0, 2.0, 2.0) for v in shown)
        assert all(v.rgba == pytest.approx((0.1, 0.2, 0.3, 1.0)) for v in shown)
        assert all(v.pose[0] == pytest.approx((0.0, 0.0, 0.1)) for v in shown)
        files = [model.file, model.physics_file, *model.visual_stand_ins]
        sim.delete_model('m')
        assert not any(os.path.exists(f) for f in files)
    finally:
        sim.close()
