"""What a mesh file costs before anyone loads it: its triangle count, read cheaply.

STL (binary: the header's count; ASCII: ``endfacet`` lines), OBJ (``f`` lines,
polygons fan-triangulated) and COLLADA (``<triangles>``, ``<polylist>``,
``<polygons>``, ``<trifans>``, ``<tristrips>``). Files are read in chunks, so
memory stays bounded whatever their size; the caller bounds the size itself
(``Limits.mesh_bytes``) first. Errors name the file and what is wrong with it,
never its contents.
"""

from __future__ import annotations

import os
import re
import struct
import xml.sax
from typing import Any, BinaryIO, List, Optional

from defusedxml import DefusedXmlException
from defusedxml.expatreader import create_parser

MESH_EXTENSIONS = ('.stl', '.obj', '.dae')
CHUNK = 1 << 20

_STL_HEADER = 80
_STL_RECORD = 50
# A face line with at least three vertex references; group 1 is everything after the 'f'.
_OBJ_FACE = re.compile(rb'^[ \t]*f[ \t]+(\S+[ \t]+\S+[ \t]+\S[^\n]*)', re.M)
_OBJ_FACE_START = re.compile(rb'[ \t]*f[ \t]')


class MeshError(ValueError):
    """The mesh cannot be read as what its extension says; the message names the file."""


def mesh_kind(path: str) -> Optional[str]:
    """'.stl', '.obj' or '.dae' (by extension, any case), or None for anything else."""
    ext = os.path.splitext(path)[1].lower()
    return ext if ext in MESH_EXTENSIONS else None


def count_triangles(path: str, stop_above: Optional[int] = None) -> int:
    """Triangles the mesh at ``path`` holds (polygons counted as fans).

    With ``stop_above``, reading may stop once the count passes it: the result is
    then more than ``stop_above`` but may be less than the whole file's count.
    """
    stop = float('inf') if stop_above is None else stop_above
    kind = mesh_kind(path)
    if kind is None:
        raise MeshError('%s: not a mesh file (%s)' % (path, ', '.join(MESH_EXTENSIONS)))
    try:
        with open(path, 'rb') as f:
            if kind == '.stl':
                return _stl_triangles(f, os.fstat(f.fileno()).st_size, path)
            if kind == '.obj':
                return _obj_triangles(f, stop)
            return _dae_triangles(f, path, stop)
    except OSError as exc:
        raise MeshError('%s: cannot be read: %s' % (path, exc.strerror)) from None


def _chunks(f: BinaryIO):
    while True:
        chunk = f.read(CHUNK)
        if not chunk:
            return
        yield chunk


def _stl_triangles(f: BinaryIO, size: int, path: str) -> int:
    head = f.read(_STL_HEADER + 4)
    if len(head) == _STL_HEADER + 4:
        (count,) = struct.unpack_from('<I', head, _STL_HEADER)
        if size == _STL_HEADER + 4 + _STL_RECORD * count:
            return count  # binary, even when the header starts with 'solid'
    if not head.lstrip().startswith(b'solid'):
        raise MeshError(
            '%s: neither a binary STL (its size does not match the triangle count '
            'in its header) nor an ASCII STL' % path
        )
    # ASCII: one 'endfacet' per triangle; a word cut at a chunk border is caught by the overlap.
    f.seek(0)
    count, tail = 0, b''
    for chunk in _chunks(f):
        data = (tail + chunk).lower()
        count += data.count(b'endfacet')
        tail = data[-7:]  # shorter than the word: no match is counted twice
    return count


def _face_triangles(lines: bytes) -> int:
    faces = _OBJ_FACE.findall(lines)
    return len(b' '.join(faces).split()) - 2 * len(faces)


def _obj_triangles(f: BinaryIO, stop: float) -> int:
    total = 0
    carry = b''  # an unfinished line from the previous chunk
    long_face = None  # inside a line over a chunk long: True if it is a face line
    for chunk in _chunks(f):
        if total > stop:
            return total
        if long_face is not None:
            end = chunk.find(b'\n')
            if long_face:
                # a vertex reference cut by the chunk border counts twice: on the safe side
                total += len((chunk if end < 0 else chunk[:end]).split())
            if end < 0:
                continue
            long_face, chunk = None, chunk[end + 1 :]
        data = carry + chunk
        cut = data.rfind(b'\n') + 1
        total += _face_triangles(data[:cut])
        carry = data[cut:]
        if len(carry) >= CHUNK:  # one line longer than a chunk: stream it
            start = _OBJ_FACE_START.match(carry)
            long_face = start is not None
            if start is not None:
                total += max(0, len(carry[start.end() :].split()) - 2)
            carry = b''
    return total + _face_triangles(carry)


class _DaeCounter(xml.sax.ContentHandler):
    """Counts the triangles of COLLADA primitives from their index lists (<p>)."""

    PRIMITIVES = ('triangles', 'polylist', 'polygons', 'ph', 'trifans', 'tristrips')

    def __init__(self) -> None:
        super().__init__()
        self.triangles = 0
        self.primitive: Optional[str] = None
        self.count = 0  # the primitive's count attribute
        self.offsets: List[int] = []
        self.p_tokens = 0  # indices in the current <p>
        self.primitive_tokens = 0  # indices in every <p> of the primitive
        self.in_p = False
        self.in_token = False

    def startElement(self, name: str, attrs: Any) -> None:
        tag = name.rpartition(':')[2]
        if tag in self.PRIMITIVES and self.primitive is None:
            self.primitive, self.offsets, self.primitive_tokens = tag, [], 0
            self.count = _int(attrs.get('count', '0'))
        elif self.primitive and tag == 'input':
            self.offsets.append(_int(attrs.get('offset', '0')))
        elif self.primitive and tag == 'p':
            self.in_p, self.in_token, self.p_tokens = True, False, 0

    def characters(self, content: str) -> None:
        if self.in_p and content:
            n = len(content.split())
            if self.in_token and not content[0].isspace() and n:
                n -= 1  # the token began in the previous piece
            self.p_tokens += n
            self.in_token = not content[-1].isspace()

    def endElement(self, name: str) -> None:
        tag = name.rpartition(':')[2]
        if tag == 'p' and self.in_p:
            self.in_p = False
            self.primitive_tokens += self.p_tokens
            if self.primitive in ('polygons', 'ph', 'trifans', 'tristrips'):
                self.triangles += max(0, self.p_tokens // self.stride() - 2)
            self.p_tokens = 0
        elif tag == self.primitive:
            vertices = self.primitive_tokens // self.stride()
            if tag == 'triangles':
                self.triangles += max(self.count, vertices // 3)
            elif tag == 'polylist':
                self.triangles += max(0, vertices - 2 * self.count)
            self.primitive = None

    def pending(self) -> int:
        """Triangles of the open primitive seen so far: its count can only grow."""
        if self.primitive is None:
            return 0
        vertices = (self.primitive_tokens + self.p_tokens) // self.stride()
        if self.primitive == 'triangles':
            return max(self.count, vertices // 3)
        if self.primitive == 'polylist':
            return max(0, vertices - 2 * self.count)
        return max(0, self.p_tokens // self.stride() - 2) if self.in_p else 0

    def stride(self) -> int:
        return max(self.offsets, default=0) + 1


def _int(text: str) -> int:
    try:
        return max(0, int(text))
    except ValueError:
        raise MeshError('a count or offset attribute is not an integer') from None


def _dae_triangles(f: BinaryIO, path: str, stop: float) -> int:
    counter = _DaeCounter()
    parser = create_parser(forbid_dtd=True)  # COLLADA needs no DTD: no entity can expand
    parser.setContentHandler(counter)
    try:
        for chunk in _chunks(f):
            if counter.triangles + counter.pending() > stop:
                return counter.triangles + counter.pending()
            parser.feed(chunk)
        parser.close()
    except DefusedXmlException:
        raise MeshError('%s: a COLLADA file with a DTD or entities: refused' % path) from None
    except xml.sax.SAXParseException as exc:
        raise MeshError(
            '%s: not well-formed XML (line %d): %s'
            % (path, exc.getLineNumber() or 0, exc.getMessage())
        ) from None
    except MeshError as exc:
        raise MeshError('%s: %s' % (path, exc)) from None
    return counter.triangles
