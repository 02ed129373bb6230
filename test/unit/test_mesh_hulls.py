"""A dense mesh's hull is made on the spawn caller's thread (physics/mesh_hulls.py): it is
within 0.004 r of the exact hull, and a 2 M-triangle collision mesh costs the
physics thread (pybullet's loadURDF) well under 0.1 s of CPU, where pybullet's own hull
of it took 6-11 s. Every mesh is made here."""

import os
import time

import numpy as np

from _arm1sim.bench.dense_meshes import cube_grid_stl
from _arm1sim.description.sdf_world import WorldConfig
from _arm1sim.physics.mesh_cache import collision_mesh
from _arm1sim.physics.mesh_hulls import hull_points
from _arm1sim.sim.simulation import Simulation


def sphere(radius, rings):
    """A UV sphere of 2 x rings x 2 rings triangles: every vertex on its hull."""
    theta = np.linspace(0, np.pi, rings + 1)
    phi = np.linspace(0, 2 * np.pi, 2 * rings + 1)
    grid = radius * np.stack(
        [
            np.sin(theta)[:, None] * np.cos(phi)[None, :],
            np.sin(theta)[:, None] * np.sin(phi)[None, :],
            np.cos(theta)[:, None] * np.ones_like(phi)[None, :],
        ],
        axis=2,
    )
    a, b, c, d = grid[:-1, :-1], grid[1:, :-1], grid[1:, 1:], grid[:-1, 1:]
    return np.concatenate(
        [
            np.stack([a, b, c], axis=2).reshape(-1, 3, 3),
            np.stack([a, c, d], axis=2).reshape(-1, 3, 3),
        ]
    )


def support(points, directions):
    return (points @ directions.T).max(axis=0)


def test_the_hull_of_a_dense_round_mesh_is_within_0_004_r_of_the_exact_one():
    r = 0.1
    tris = sphere(r, 120)  # 57 600 triangles, 14 000 vertices all on the hull
    points = hull_points(tris)
    assert 100 < len(points) <= 1026
    corners = tris.reshape(-1, 3)
    # every point is a vertex of the mesh
    assert np.abs(points[:, None, :] - corners[None, ::7, :]).sum(axis=2).min(axis=1).max() < 0.02
    assert all(np.isclose(np.abs(corners - p).sum(axis=1), 0).any() for p in points[:50])
    exact = corners  # the exact hull's support is its vertices'
    rng = np.random.default_rng(1)
    directions = rng.normal(size=(5000, 3))
    directions /= np.linalg.norm(directions, axis=1)[:, None]
    gap = support(exact, directions) - support(points, directions)
    assert gap.min() > -1e-7 * r  # inside the exact hull (float32 ties)
    assert gap.max() < 0.004 * r  # measured 0.0033 r
    box = np.eye(3)
    assert np.allclose(support(points, np.concatenate([box, -box])), r, atol=1e-3 * r)


def test_a_small_mesh_keeps_all_its_corners():
    tris = sphere(0.05, 8)
    points = hull_points(tris)
    corners = tris.reshape(-1, 3)
    assert len(points) <= 2 * 8 * 9  # each corner once
    assert np.abs(corners[:, None, :] - points[None]).max(axis=2).min(axis=1).max() < 1e-12


def test_a_2m_triangle_collision_mesh_costs_the_physics_thread_under_0_1_s(tmp_path, monkeypatch):
    path = str(tmp_path / 'dense.stl')
    extent = cube_grid_stl(path, 2_000_000 // 12 + 1)
    monkeypatch.setenv('XDG_CACHE_HOME', str(tmp_path / 'cache'))
    urdf = (
        '<robot name="dense"><link name="l"><inertial><mass value="1"/><inertia ixx="1e-3" '
        'iyy="1e-3" izz="1e-3" ixy="0" ixz="0" iyz="0"/></inertial><collision><geometry>'
        '<mesh filename="%s"/></geometry></collision></link></robot>' % path
    )
    sim = Simulation(WorldConfig())
    try:
        prepared = sim.prepare_urdf('dense', urdf, position=(0, 0, 1))  # the caller's thread
        cpu = time.thread_time()
        model = sim.spawn_prepared(prepared)  # what the physics thread does
        cpu = time.thread_time() - cpu
        assert cpu < 0.1, cpu
        import pybullet as p

        low, high = p.getAABB(model.robot.body, -1, physicsClientId=sim.world.client)
        size = np.subtract(high, low)
        # the whole grid's hull, with pybullet's margins
        assert (size > extent).all() and (size < extent + 0.01).all(), (size, extent)
    finally:
        sim.close()
    # the next spawn finds it in the cache
    found = collision_mesh(path, (1, 1, 1), str(tmp_path / 'cache' / 'arm1' / 'collision_meshes'))
    assert found.cached and found.path and os.path.getsize(found.path) < 100_000


def test_a_plain_obj_is_read_by_numpy_as_line_by_line(tmp_path, monkeypatch):
    from _arm1sim.physics import mesh_reading

    plain = (
        '# plain\no part\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\n'
        'f 1 2 3\nf 1 2 4\nf 1 2 9\nf 0 3 4\n'
    )
    others = [
        plain.replace('f 1 2 4', 'f 1/1 2/1 4/1'),  # slashes
        plain.replace('f 1 2 4', 'f 1 2 -1'),  # counted back
        plain.replace('v 0 0 1', ' v 0 0 1'),  # indented
        plain.replace('f 1 2 4', 'f 1 2 4 3'),  # a quad
    ]
    assert mesh_reading._plain_obj_triangles(plain.encode()) is not None
    for text in others:
        assert mesh_reading._plain_obj_triangles(text.encode()) is None
    for i, text in enumerate([plain] + others):
        path = str(tmp_path / ('m%d.obj' % i))
        with open(path, 'w') as f:
            f.write(text)
        fast = mesh_reading._obj_triangles(path)
        with monkeypatch.context() as m:
            m.setattr(mesh_reading, '_plain_obj_triangles', lambda data: None)
            slow = mesh_reading._obj_triangles(path)
        assert fast[1] == slow[1] == 2 and np.array_equal(fast[0], slow[0])
