"""STL files through numpy-stl: binary writing with unit normals and a fixed header, reading.

The project's meshes (tools/generate_meshes.py) must come out byte for byte the same on
every run, so the header is ours (numpy-stl's default one carries the time of writing)
and the stored normals are unit normals of the float32 vertices actually stored.
"""

from __future__ import annotations

from struct import error as struct_error
from typing import Tuple, Union

import numpy as np
import stl
from numpy.typing import ArrayLike, NDArray

HEADER_SIZE = 80


class _FixedHeaderMesh(stl.Mesh):
    """A Mesh whose binary header is ``header``, space-padded (no timestamp, no file name)."""

    header = ''

    def get_header(self, name: object) -> str:
        return self.header.ljust(HEADER_SIZE, ' ')


def triangle_normals(triangles: ArrayLike) -> NDArray[np.float64]:
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


def write_binary_stl(path: str, triangles: ArrayLike, header: Union[str, bytes] = b'') -> None:
    """Write ``triangles`` (N x 3 x 3, metres) to ``path`` as binary STL.

    Normals are computed from the vertex order (see :func:`triangle_normals`).
    ``header`` (str or bytes, at most 80 ASCII bytes) is padded with spaces; it must
    not start with ``solid``, which would make readers take the file for ASCII
    STL. The output depends only on the arguments (same bytes every run)."""
    tri = np.asarray(triangles, dtype=np.float64).reshape(-1, 3, 3)
    text = header.decode('ascii') if isinstance(header, bytes) else header
    text.encode('ascii')  # UnicodeEncodeError for a header no STL reader could show
    if len(text) > HEADER_SIZE:
        raise ValueError('STL header longer than %d bytes' % HEADER_SIZE)
    if text[:5].lower() == 'solid':
        raise ValueError("binary STL header must not start with 'solid'")
    data = np.zeros(len(tri), dtype=stl.Mesh.dtype)
    data['vectors'] = tri.astype(np.float32)
    # normals from the float32 vertices actually stored, unit length (numpy-stl's own
    # update_normals leaves them scaled by twice the area)
    data['normals'] = triangle_normals(data['vectors']).astype(np.float32)
    out = _FixedHeaderMesh(data, calculate_normals=False)
    out.header = text
    out.save(path, mode=stl.Mode.BINARY, update_normals=False)


def read_stl(path: str) -> Tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Triangles (N x 3 x 3, float64; triangle, vertex, xyz) and their stored normals
    (N x 3) of an STL file, binary or ASCII; what numpy-stl finds malformed is a
    ValueError naming the file."""
    try:
        loaded = stl.Mesh.from_file(path, calculate_normals=False)
    except (AssertionError, RuntimeError, ValueError, struct_error) as exc:
        raise ValueError('%s: not an STL file (%s)' % (path, exc)) from None
    return (
        np.asarray(loaded.vectors, dtype=np.float64),
        np.asarray(loaded.normals, dtype=np.float64),
    )
