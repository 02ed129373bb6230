"""What a concave collision mesh costs (physics/concave_meshes.py): its spawn with an empty
cache (concavity check, convex pieces written, pybullet loading them), its spawn from the
cache, and a physics step with a box resting on it (``box_resting``: it did, on both); each
next to the same mesh as pybullet's convex hull, and how many pieces it became. The mesh
is arm1's link2 (592 triangles, concave by 59 mm), on a moving link. In one process, no
master needed.
"""

from __future__ import annotations

import os
import signal
import tempfile
import time
from typing import Any, Dict, List

import pybullet as p

from ..description.limits import Limits
from ..description.sdf_world import WorldConfig
from ..paths import repo_root
from ..physics import mesh_jobs
from ..physics.mesh_cache import collision_mesh
from ..physics.mesh_reading import mesh_triangles
from ..sim.simulation import Simulation
from .dense_meshes import u_bracket, write_mesh
from .probes import median_ms

ROBOT = """<robot name="holder"><link name="world"/>
  <link name="part"><inertial><mass value="0.2"/>
    <inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><mesh filename="%s"/></geometry></collision></link>
  <joint name="slide" type="prismatic"><parent link="world"/><child link="part"/>
    <origin xyz="0 0 0.2"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="100" velocity="1"/><dynamics friction="100"/></joint>
</robot>"""


def _world(mesh: str, hull: bool, count: int) -> Dict[str, float]:
    """Spawn time (ms) and median step time (ms) with a box resting on the mesh."""
    config = WorldConfig()
    if hull:  # over the limit: the mesh collides as its convex hull
        config.limits = Limits(concave_mesh_triangles=1)
    sim = Simulation(config)
    try:
        t = time.perf_counter()
        model = sim.spawn_urdf('holder', ROBOT % mesh)
        spawn_ms = (time.perf_counter() - t) * 1000.0
        cid = sim.world.client
        low, high = p.getAABB(model.robot.body, 0, physicsClientId=cid)
        # the box goes over the part's highest point a ray straight down finds (the middle
        # of its bounds may be a hollow: a box dropped there misses it)
        grid = [
            (low[0] + (high[0] - low[0]) * i / 8, low[1] + (high[1] - low[1]) * j / 8)
            for i in range(1, 8)
            for j in range(1, 8)
        ]
        hits = p.rayTestBatch(
            [(x, y, high[2] + 0.1) for x, y in grid],
            [(x, y, low[2] - 0.1) for x, y in grid],
            physicsClientId=cid,
        )
        top = max((h[3] for h in hits if h[0] == model.robot.body), key=lambda h: h[2])
        shape = p.createCollisionShape(p.GEOM_BOX, halfExtents=(0.01,) * 3, physicsClientId=cid)
        box = p.createMultiBody(
            0.05, shape, basePosition=(top[0], top[1], top[2] + 0.012), physicsClientId=cid
        )
        for _ in range(500):  # the box falls onto the part and settles
            sim.step()
        resting = bool(p.getContactPoints(box, model.robot.body, physicsClientId=cid))
        return {
            'spawn_ms': spawn_ms,
            'step_ms': median_ms(sim.step, count),
            'resting': float(resting),
        }
    finally:
        sim.close()


def concave_mesh(count: int = 2000) -> Dict[str, Any]:
    mesh = os.path.join(repo_root(), 'meshes', 'link2.STL')
    with tempfile.TemporaryDirectory(prefix='arm1-bench-cache-') as cache:
        os.environ['XDG_CACHE_HOME'] = cache  # an empty cache: the first spawn computes
        first = _world(mesh, False, count)
        cached = _world(mesh, False, count)
        hull = _world(mesh, True, count)
        pieces_path = collision_mesh(mesh, (1.0, 1.0, 1.0)).path
        with open(pieces_path or mesh) as f:
            pieces = sum(line.startswith('o ') for line in f)
    return {
        'triangles': len(mesh_triangles(mesh)),
        'pieces': pieces,
        'box_resting': cached['resting'] and hull['resting'],
        'spawn_first_ms': first['spawn_ms'],
        'spawn_cached_ms': cached['spawn_ms'],
        'spawn_hull_ms': hull['spawn_ms'],
        'step_ms': cached['step_ms'],
        'step_hull_ms': hull['step_ms'],
    }


DENSE = 20000  # triangles per mesh: a SolidWorks export's link (14-18 k)


def _chain(meshes: List[str]) -> str:
    """A robot of one link per mesh, each on a revolute joint (not lumped)."""
    inertia = '<inertia ixx="1e-5" iyy="1e-5" izz="1e-5" ixy="0" ixz="0" iyz="0"/>'
    parts = []
    for i, mesh in enumerate(meshes):
        geometry = '<geometry><mesh filename="%s"/></geometry>' % mesh
        parts.append(
            '<link name="l%d"><inertial><mass value="0.05"/>%s</inertial><visual>%s</visual>'
            '<collision>%s</collision></link>' % (i, inertia, geometry, geometry)
        )
        if i:
            parts.append(
                '<joint name="j%d" type="revolute"><parent link="l%d"/><child link="l%d"/>'
                '<origin xyz="0 0 0.05"/><axis xyz="0 0 1"/>'
                '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>' % (i, i - 1, i)
            )
    return '<robot name="dense">%s</robot>' % ''.join(parts)


def cache_fill(triangles: int = DENSE) -> Dict[str, Any]:
    """The cache's first fill (bench/dense_meshes.py's bumpy U of ``triangles``): CPU
    seconds per 10 k triangles to read, check and cut a mesh into pieces with the cache
    empty (cold) and to find them there (warm), for .stl, .obj and .dae; and the wall time
    of a spawn of a 10-link model of such meshes with the cache empty (the pieces are made
    after it, off the world: physics/mesh_jobs.py), with the CPU time of its caller's
    share (reading, checking, hulls) and of the physics thread's (pybullet's loadURDF)."""
    out: Dict[str, Any] = {'triangles': triangles}
    tris = u_bracket(triangles)
    per = 10000.0 / len(tris)
    with tempfile.TemporaryDirectory(prefix='arm1-bench-fill-') as folder:
        for ext in ('stl', 'obj', 'dae'):
            path = os.path.join(folder, 'u.' + ext)
            write_mesh(path, tris)
            cache = os.path.join(folder, 'cache-' + ext)
            t = time.process_time()
            made = collision_mesh(path, (1.0, 1.0, 1.0), cache)
            out['cold_s_per_10k_' + ext] = (time.process_time() - t) * per
            t = time.process_time()
            again = collision_mesh(path, (1.0, 1.0, 1.0), cache)
            out['warm_s_per_10k_' + ext] = (time.process_time() - t) * per
            assert again.cached and again.path == made.path
        # ten files of distinct content (the cache keys by content), as a CAD export's
        meshes = [
            os.path.join(folder, 'l%d.' % i + ('stl', 'obj', 'dae')[i % 3]) for i in range(10)
        ]
        for i, mesh in enumerate(meshes):
            write_mesh(mesh, tris + 0.001 * i)
        os.environ['XDG_CACHE_HOME'] = os.path.join(folder, 'spawn-cache')
        sim = Simulation(WorldConfig())
        try:
            t, cpu = time.perf_counter(), time.thread_time()
            # as the ROS layer: prepared on the caller's thread, built on the physics one
            prepared = sim.prepare_urdf('dense', _chain(meshes))
            between = time.thread_time()
            sim.spawn_prepared(prepared)
            out['spawn_10_links_cold_s'] = time.perf_counter() - t
            out['spawn_10_links_caller_cpu_s'] = between - cpu
            out['spawn_10_links_physics_cpu_s'] = time.thread_time() - between
        finally:
            sim.close()
            for pid in mesh_jobs.pids:  # the cache it fills goes with this folder
                try:
                    os.kill(pid, signal.SIGKILL)
                    os.waitpid(pid, 0)
                except (ProcessLookupError, ChildProcessError):
                    pass
    return out
