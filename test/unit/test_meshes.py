"""The link meshes: size, closedness, and that meshes/ is what the generator makes.

numpy, numpy-stl and pytest; no ROS (conftest puts src/ on the path).
"""

import os
import subprocess
import sys

import numpy as np
import pytest

from _arm1sim.paths import repo_path
from _arm1sim.physics.stl import read_stl, triangle_normals, write_binary_stl

MESH_DIR = repo_path('meshes')
GENERATOR = repo_path('tools', 'generate_meshes.py')

# Bounding boxes of the original CAD meshes (reference arm1-model.md, "Meshes").
REFERENCE_BBOX = {
    'base_link': ((-0.0275, -0.0275, 0.0), (0.0275, 0.0275, 0.0358)),
    'link1': ((-0.0205, -0.0200, -0.0038), (0.0200, 0.0209, 0.0240)),
    'link2': ((-0.0591, -0.0086, -0.0347), (0.0084, 0.0314, 0.0011)),
    'link3': ((-0.0607, -0.0198, -0.0348), (0.0080, 0.0080, 0.0010)),
    'link4': ((-0.0431, -0.0367, -0.0348), (0.0080, 0.0080, 0.0032)),
}
TOLERANCE = 0.15  # of the reference extent, per axis
LINKS = sorted(REFERENCE_BBOX)


def mesh_path(link):
    return os.path.join(MESH_DIR, link + '.STL')


@pytest.fixture(scope='module', params=LINKS)
def mesh(request):
    link = request.param
    triangles, normals = read_stl(mesh_path(link))
    return link, triangles, normals


def test_bounding_box_matches_reference(mesh):
    link, tri, _ = mesh
    ref_min, ref_max = (np.array(v) for v in REFERENCE_BBOX[link])
    ref_extent = ref_max - ref_min
    pts = tri.reshape(-1, 3)
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    tol = TOLERANCE * ref_extent
    for axis, name in enumerate('xyz'):
        assert abs((hi - lo)[axis] - ref_extent[axis]) <= tol[axis], (
            '%s: %s extent %.4f, reference %.4f' % (link, name, (hi - lo)[axis], ref_extent[axis])
        )
        assert abs(lo[axis] - ref_min[axis]) <= tol[axis], '%s: %s min %.4f, reference %.4f' % (
            link,
            name,
            lo[axis],
            ref_min[axis],
        )
        assert abs(hi[axis] - ref_max[axis]) <= tol[axis], '%s: %s max %.4f, reference %.4f' % (
            link,
            name,
            hi[axis],
            ref_max[axis],
        )


def test_triangle_count(mesh):
    link, tri, _ = mesh
    assert 50 <= len(tri) <= 2000, '%s: %d triangles' % (link, len(tri))


def test_closed(mesh):
    """Every edge is shared by exactly two triangles, traversed once each way."""
    link, tri, _ = mesh
    keys = [tuple(v) for v in tri.reshape(-1, 3)]
    index = {}
    ids = np.array([index.setdefault(k, len(index)) for k in keys]).reshape(-1, 3)
    directed = {}
    for a, b, c in ids:
        for e in ((a, b), (b, c), (c, a)):
            directed[e] = directed.get(e, 0) + 1
    undirected = {}
    for (a, b), count in directed.items():
        key = (min(a, b), max(a, b))
        undirected[key] = undirected.get(key, 0) + count
    bad = [e for e, count in undirected.items() if count != 2]
    assert not bad, '%s: %d edges not shared by exactly two triangles' % (link, len(bad))
    # consistent winding: each edge is used once in each direction
    assert all(count == 1 for count in directed.values()), '%s: inconsistent winding' % link


def test_outward_normals(mesh):
    link, tri, normals = mesh
    # stored normals agree with the winding ...
    computed = triangle_normals(tri)
    assert np.all(np.einsum('ij,ij->i', computed, normals) > 0.99), link
    # ... and the winding is outward: positive enclosed volume (divergence theorem)
    volume = np.einsum('ij,ij->i', tri[:, 0], np.cross(tri[:, 1], tri[:, 2])).sum() / 6.0
    assert volume > 0, '%s: signed volume %g' % (link, volume)


def test_stl_round_trip(tmp_path):
    tri = (
        np.array(
            [[[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 0, 0], [0, 0, 1], [1, 0, 0]]], dtype=float
        )
        * 0.01
    )
    path = str(tmp_path / 'two.STL')
    write_binary_stl(path, tri, 'test header')
    with open(path, 'rb') as f:
        data = f.read()
    assert len(data) == 84 + 2 * 50
    assert data[:11] == b'test header'
    back, normals = read_stl(path)
    assert back.shape == (2, 3, 3)
    np.testing.assert_allclose(back, tri, atol=1e-7)
    np.testing.assert_allclose(normals, [[0, 0, 1], [0, 1, 0]], atol=1e-6)


def test_committed_meshes_match_generator(tmp_path):
    out = tmp_path / 'meshes'
    subprocess.run([sys.executable, GENERATOR, str(out)], check=True, stdout=subprocess.DEVNULL)
    for link in LINKS:
        with open(mesh_path(link), 'rb') as f:
            committed = f.read()
        with open(str(out / (link + '.STL')), 'rb') as f:
            generated = f.read()
        assert committed == generated, (
            'meshes/%s.STL differs from tools/generate_meshes.py output; rerun it' % link
        )
