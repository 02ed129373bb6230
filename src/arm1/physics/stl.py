"""Binary STL reading and writing (numpy + struct only; no ROS, no pybullet).

A binary STL file is an 80-byte header, a little-endian uint32 triangle count
and, per triangle, 12 float32 (normal, then the three vertices) and a uint16
attribute word: 50 bytes a triangle.
"""

import struct

import numpy as np

HEADER_SIZE = 80
_RECORD = np.dtype([
    ('normal', '<f4', (3,)),
    ('vertices', '<f4', (3, 3)),
    ('attribute', '<u2'),
])
assert _RECORD.itemsize == 50


def triangle_normals(triangles):
    """Unit normals (N x 3, float64) of triangles (N x 3 x 3) from their
    winding: counter-clockwise seen from outside gives an outward normal.
    Degenerate triangles get a zero normal."""
    tri = np.asarray(triangles, dtype=np.float64).reshape(-1, 3, 3)
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    length = np.sqrt(np.einsum('ij,ij->i', n, n))
    out = np.zeros_like(n)
    ok = length > 0
    out[ok] = n[ok] / length[ok, None]
    return out


def write_binary_stl(path, triangles, header=b''):
    """Write ``triangles`` (N x 3 x 3, metres) to ``path`` as binary STL.

    Normals are computed from the vertex order (see :func:`triangle_normals`).
    ``header`` (str or bytes, at most 80 bytes) is padded with spaces; it must
    not start with ``solid``, which would make readers take the file for ASCII
    STL. The output depends only on the arguments (same bytes every run)."""
    tri = np.asarray(triangles, dtype=np.float64).reshape(-1, 3, 3)
    if isinstance(header, str):
        header = header.encode('ascii')
    header = bytes(header)
    if len(header) > HEADER_SIZE:
        raise ValueError('STL header longer than %d bytes' % HEADER_SIZE)
    if header[:5].lower() == b'solid':
        raise ValueError("binary STL header must not start with 'solid'")
    records = np.zeros(len(tri), dtype=_RECORD)
    records['vertices'] = tri.astype('<f4')
    # normals from the float32 vertices actually stored
    records['normal'] = triangle_normals(records['vertices']).astype('<f4')
    with open(path, 'wb') as f:
        f.write(header.ljust(HEADER_SIZE, b' '))
        f.write(struct.pack('<I', len(tri)))
        f.write(records.tobytes())


def read_binary_stl(path, with_normals=False):
    """Read a binary STL file.

    Returns the triangles as a float64 array of shape (N, 3, 3) (triangle,
    vertex, xyz), or ``(triangles, normals)`` with the stored normals (N x 3)
    when ``with_normals`` is true. Raises ValueError for a file whose size does
    not match its triangle count (e.g. an ASCII STL)."""
    with open(path, 'rb') as f:
        data = f.read()
    if len(data) < HEADER_SIZE + 4:
        raise ValueError('%s: too short for a binary STL file' % path)
    (count,) = struct.unpack_from('<I', data, HEADER_SIZE)
    expected = HEADER_SIZE + 4 + count * _RECORD.itemsize
    if len(data) != expected:
        raise ValueError('%s: not a binary STL file (%d bytes, %d expected for %d triangles)'
                         % (path, len(data), expected, count))
    records = np.frombuffer(data, dtype=_RECORD, count=count, offset=HEADER_SIZE + 4)
    triangles = records['vertices'].astype(np.float64)
    if with_normals:
        return triangles, records['normal'].astype(np.float64)
    return triangles
