"""Broken meshes never reach pybullet (physics/mesh_reading.py, mesh_cache.py,
concave_meshes.py): NaN and infinite vertices, out-of-range face indices (OBJ, COLLADA)
and meshes without a triangle are repaired or left out, each with a warning naming the
link and the file; a repaired part still rests on the ground. A dense mesh whose pieces
are not cached collides as its hull at once and gets its pieces made off the world
(physics/mesh_jobs.py). Every broken file is made here."""

import os
import time

import helpers
import numpy as np
import pybullet as p
import pytest

from _arm1sim.bench.dense_meshes import u_bracket, write_mesh
from _arm1sim.physics import concave_meshes, mesh_jobs
from _arm1sim.physics.concave_meshes import concave_collisions
from _arm1sim.physics.mesh_reading import MeshReadError, checked_triangles
from _arm1sim.physics.stl import write_binary_stl


def cube_triangles(size=0.03):
    """A closed cube of 12 triangles, wound outward."""
    c = [(x, y, z) for x in (0, size) for y in (0, size) for z in (0, size)]
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    return np.array(
        [t for a, b, d, e in quads for t in ((c[a], c[b], c[d]), (c[a], c[d], c[e]))], dtype=float
    )


INERTIA = '<inertia ixx="1e-5" iyy="1e-5" izz="1e-5" ixy="0" ixz="0" iyz="0"/>'


def part(path, z=0.1):
    return (
        '<robot name="r"><link name="l"><inertial><mass value="0.1"/>%s</inertial>'
        '<collision><origin xyz="0 0 %r"/><geometry><mesh filename="%s"/></geometry>'
        '</collision></link></robot>' % (INERTIA, z, path)
    )


def nan_cube(value=np.nan):
    tris = np.concatenate([cube_triangles(), cube_triangles()[:2] + 0.01])
    tris[-1, 1, 2] = value
    return tris


def test_nan_and_infinite_vertices_are_left_out_naming_the_file(tmp_path):
    for value in (np.nan, np.inf, -np.inf):
        path = str(tmp_path / 'v.stl')
        write_binary_stl(path, nan_cube(value))
        tris, notes = checked_triangles(path)
        assert len(tris) == 13 and np.isfinite(tris).all()
        assert notes == ['1 of 14 triangles have a NaN or infinite vertex: left out']


def test_obj_faces_out_of_range_are_left_out_naming_the_file(tmp_path):
    path = str(tmp_path / 'i.obj')
    with open(path, 'w') as f:
        f.write('v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n')
        f.write('f 1 2 3\nf 1 2 99\nf 0 1 2\nf -1 -2 -3\nf 1 2 -9\nf 2 3 4 5\n')
    tris, notes = checked_triangles(path)
    assert len(tris) == 2  # 'f 1 2 3' and 'f -1 -2 -3'
    assert notes == ['4 faces name a vertex that is not in the file: left out']


def test_collada_indices_out_of_range_refuse_the_mesh_naming_the_file(tmp_path, caplog):
    path = str(tmp_path / 'i.dae')
    write_mesh(path, cube_triangles())
    text = open(path).read()
    head, _, tail = text.rpartition('<p>')
    indices, _, rest = tail.partition('</p>')
    numbers = indices.split()
    numbers[4] = '4000'  # the second triangle
    with open(path, 'w') as f:
        f.write(head + '<p>' + ' '.join(numbers) + '</p>' + rest)
    with pytest.raises(MeshReadError, match='beyond the limits') as exc:
        checked_triangles(path)
    assert path in str(exc.value)
    out = concave_collisions(part(path), str(tmp_path / 'cache'))
    assert '<collision' not in out and "link 'l'" in caplog.text and path in caplog.text


@pytest.mark.parametrize('ext', ['.stl', '.obj', '.dae'])
def test_a_mesh_without_a_triangle_is_left_out_and_the_link_keeps_its_inertia(
    tmp_path, ext, caplog
):
    path = str(tmp_path / ('empty' + ext))
    if ext == '.stl':
        write_binary_stl(path, np.zeros((0, 3, 3)))
    elif ext == '.obj':
        open(path, 'w').write('# nothing\nv 0 0 0\n')
    else:
        write_mesh(path, np.zeros((0, 3, 3)))
    out = concave_collisions(part(path), str(tmp_path / 'cache'))
    assert '<collision' not in out and '<mass value="0.1"' in out
    assert "link 'l'" in caplog.text and 'no triangle' in caplog.text and path in caplog.text


def test_a_repaired_mesh_hands_pybullet_its_checked_triangles_and_rests_on_the_ground(
    tmp_path, monkeypatch, caplog
):
    monkeypatch.setenv('XDG_CACHE_HOME', str(tmp_path / 'cache'))
    bad = {'nan.stl': nan_cube(), 'inf.stl': nan_cube(np.inf)}
    for name, tris in bad.items():
        write_binary_stl(str(tmp_path / name), tris)
    with open(str(tmp_path / 'range.obj'), 'w') as f:
        corners = cube_triangles().reshape(-1, 3)
        f.writelines('v %r %r %r\n' % tuple(v) for v in corners)
        f.writelines('f %d %d %d\n' % (3 * i + 1, 3 * i + 2, 3 * i + 3) for i in range(12))
        f.write('f 1 2 100000\n')
    sim = helpers.world(ground=True)
    try:
        for i, name in enumerate(['nan.stl', 'inf.stl', 'range.obj']):
            path = str(tmp_path / name)
            out = concave_collisions(part(path))
            handed = out.split('filename="')[1].split('"')[0]
            assert handed != path and handed.endswith('.obj')
            values = [float(v) for line in open(handed) if line[0] == 'v' for v in line.split()[1:]]
            assert np.isfinite(values).all()
            assert "link 'l'" in caplog.text and path in caplog.text
            model = sim.spawn_urdf('part%d' % i, part(path).replace('<link', '<link', 1))
            p.resetBasePositionAndOrientation(
                model.robot.body, (i * 0.2, 0, 0.05), (0, 0, 0, 1), physicsClientId=sim.world.client
            )
        for _ in range(400):
            sim.step()
        for i in range(3):
            z = sim.models['part%d' % i].robot.link_pose('l')[0][2]
            assert -0.12 < z < -0.09  # the cube's bottom (0.1 below the link) on the ground
    finally:
        sim.close()


def test_a_dense_mesh_collides_as_its_hull_at_once_and_its_pieces_come_later(tmp_path, monkeypatch):
    cache = str(tmp_path / 'cache')
    path = str(tmp_path / 'dense.stl')
    write_mesh(path, u_bracket(3000))
    started = []
    monkeypatch.setattr(concave_meshes, 'fill_later', lambda jobs, *a: started.append(jobs))
    t = time.process_time()
    first = concave_collisions(part(path), cache)
    assert time.process_time() - t < 0.5  # read and checked, no pieces made
    # its hull, made here: pybullet is handed its points (physics/mesh_hulls.py)
    hull = first.split('filename="')[1].split('"')[0]
    assert hull.startswith(cache) and hull.endswith('.hull.obj')
    assert 8 <= sum(line.startswith('v ') for line in open(hull)) <= 1026
    assert started == [[(path, (1.0, 1.0, 1.0))]]
    # what the low-priority process runs, here in-process
    import dataclasses
    import json

    from _arm1sim.description.limits import Limits

    spec = {'cache_dir': cache, 'limits': dataclasses.asdict(Limits()), 'jobs': started[0]}
    import shutil

    shutil.rmtree(cache)  # the cache removed (a test's, a bench's): the process stops
    assert mesh_jobs.main([json.dumps(spec)]) == 0 and not os.path.exists(cache)
    os.makedirs(cache, exist_ok=True)  # as fill_later makes it
    assert mesh_jobs.main([json.dumps(spec)]) == 0
    later = concave_collisions(part(path), cache)
    pieces = later.split('filename="')[1].split('"')[0]
    assert pieces.startswith(cache) and os.path.exists(pieces)
    assert sum(line.startswith('o ') for line in open(pieces)) > 10


def test_fill_later_starts_one_process_per_mesh_once(tmp_path):
    path = str(tmp_path / 'u.stl')
    write_binary_stl(path, u_bracket(200))
    from _arm1sim.description.limits import Limits

    cache = str(tmp_path / 'cache')
    pid = mesh_jobs.fill_later([(path, (1.0, 1.0, 1.0))], cache, Limits())
    assert pid is not None
    assert mesh_jobs.fill_later([(path, (1.0, 1.0, 1.0))], cache, Limits()) is None
    os.waitpid(pid, 0)
    assert any(name.endswith('.obj') for name in os.listdir(cache))
