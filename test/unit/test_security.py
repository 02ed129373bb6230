"""Hostile documents and meshes cost bounded time and memory and get a clear refusal (no ROS)."""

import resource
import struct
import time

import pytest

from _arm1sim.description import safe_xml
from _arm1sim.description.limits import LimitError, Limits
from _arm1sim.description.mesh_limits import MeshError, count_triangles
from _arm1sim.description.urdf_model import UrdfError, parse_urdf, resolve_mesh_uris
from _arm1sim.physics.stl import write_binary_stl

LAUGHS = (
    '<?xml version="1.0"?><!DOCTYPE robot [<!ENTITY lol "lol">'
    + ''.join(
        '<!ENTITY lol%d "%s">' % (i, ('&lol%s;' % (i - 1 if i > 1 else '')) * 10)
        for i in range(1, 10)
    )
    + ']><robot name="r"><link name="&lol9;"/></robot>'
)


def refused(fn, *args):
    """The UrdfError ``fn(*args)`` raises and the CPU time it took (the work a request costs;
    wall time would also count what other processes of a busy machine took)."""
    start = time.process_time()
    with pytest.raises(UrdfError) as exc:
        fn(*args)
    return str(exc.value), time.process_time() - start


def max_rss_mb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


# ----------------------------------------------------------------------------- XML attacks
def test_billion_laughs_is_refused_at_once():
    before = max_rss_mb()
    msg, took = refused(parse_urdf, LAUGHS)
    assert 'robot description has a document type declaration' in msg
    assert took < 0.5 and max_rss_mb() - before < 50


@pytest.mark.parametrize(
    'doc',
    [
        '<!DOCTYPE robot [<!ENTITY x SYSTEM "file:///etc/passwd">]><robot name="&x;"/>',
        '<!DOCTYPE robot SYSTEM "file:///etc/passwd"><robot name="r"><link name="a"/></robot>',
        '<!DOCTYPE robot [<!ENTITY % p SYSTEM "http://127.0.0.1:9/x.dtd"> %p;]><robot/>',
    ],
)
def test_external_entities_are_refused_without_reading_them(doc):
    msg, took = refused(parse_urdf, doc)
    assert 'document type declaration' in msg and 'root:' not in msg
    assert took < 0.5


def test_entity_without_declaration_is_an_xml_error():
    msg, _ = refused(parse_urdf, '<robot name="&passwd;"><link name="a"/></robot>')
    assert 'not well-formed XML: undefined entity' in msg


def test_xacro_output_has_no_doctype(arm1_urdf):
    assert '<!DOCTYPE' not in arm1_urdf
    assert parse_urdf(arm1_urdf).name == 'arm1'


def test_deep_nesting_is_refused_before_it_reaches_a_recursive_serialiser():
    doc = '<robot name="r"><link name="a"/>' + '<gazebo>' * 5000 + '</gazebo>' * 5000 + '</robot>'
    msg, took = refused(parse_urdf, doc)
    assert 'nests XML elements more than %d deep' % safe_xml.MAX_DEPTH in msg
    assert took < 1.0


def test_element_flood_stops_at_the_budget_in_bounded_memory():
    limits = Limits(links_per_model=10, joints_per_model=10)  # 2000 elements allowed
    doc = '<robot name="r">' + '<gazebo/>' * 1_000_000 + '</robot>'
    before = max_rss_mb()
    start = time.process_time()
    with pytest.raises(LimitError) as exc:
        parse_urdf(doc, limits)
    assert time.process_time() - start < 1.0
    assert max_rss_mb() - before < 50
    assert 'more than 2000 XML elements' in str(exc.value)
    assert '~limits/links_per_model' in str(exc.value)


def test_default_limits_bound_the_parse_of_the_largest_document():
    # the largest document the defaults let through parses in seconds and a few hundred MB
    limits = Limits()
    budget = 100 * (limits.links_per_model + limits.joints_per_model)
    doc = '<robot name="r">' + '<g/>' * (budget + 10) + '</robot>'
    start = time.process_time()
    with pytest.raises(LimitError, match='more than %d XML elements' % budget):
        parse_urdf(doc, limits)
    assert time.process_time() - start < 10.0


def test_description_bytes_counts_utf8_bytes_not_characters():
    doc = '<robot name="r"><link name="%s"/></robot>' % ('\u00e9' * 100)
    with pytest.raises(LimitError, match='description bytes is %d' % len(doc.encode())):
        parse_urdf(doc, Limits(description_bytes=len(doc)))


def test_malformed_documents_are_refused_quickly():
    for doc in (
        '',
        '<robot',
        '<robot name="r"><link name="a"></robot>',
        '\x00<robot/>',
        '<robot name="r"/><robot/>',
        b'\xff\xfe<\x00r\x00',
        '<robot name="\ud800"/>',
    ):
        msg, took = refused(parse_urdf, doc)
        assert 'robot description' in msg and took < 0.5


# ----------------------------------------------------------------------------- meshes
def robot_with_mesh(uri):
    return (
        '<robot name="r"><link name="shell"><visual><geometry><mesh filename="%s"/>'
        '</geometry></visual></link></robot>' % uri
    )


def finder(root):
    def find(name):
        if name == 'pkg':
            return str(root)
        raise LookupError(name)

    return find


def test_stl_triangles_binary_and_ascii(tmp_path):
    write_binary_stl(str(tmp_path / 'b.stl'), [[(0, 0, 0), (1, 0, 0), (0, 1, 0)]] * 7)
    assert count_triangles(str(tmp_path / 'b.stl')) == 7
    facet = (
        'facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n'
        'endloop\nendfacet\n'
    )
    (tmp_path / 'a.STL').write_text('solid x\n' + facet * 5 + 'endsolid x\n')
    assert count_triangles(str(tmp_path / 'a.STL')) == 5


def test_binary_stl_that_starts_with_solid_is_read_as_binary(tmp_path):
    path = str(tmp_path / 's.stl')
    write_binary_stl(path, [[(0, 0, 0), (1, 0, 0), (0, 1, 0)]] * 3)
    with open(path, 'r+b') as f:
        f.write(b'solid but binary')
    assert count_triangles(path) == 3


def test_stl_whose_header_lies_is_refused(tmp_path):
    path = tmp_path / 'lie.stl'
    path.write_bytes(b'\0' * 80 + struct.pack('<I', 10**9) + b'\0' * 50)
    with pytest.raises(MeshError, match='neither a binary STL'):
        count_triangles(str(path))


def test_obj_faces_are_counted_as_fans(tmp_path):
    path = tmp_path / 'm.obj'
    path.write_text(
        '# comment f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n'
        'f 1 2 3\n  f 1/1/1 2/2/2 3/3/3 4/4/4\r\nf\t1 2 3 4 5\nf 1 2\nf \nvt 0 0\n'
        'f 1 2 3'
    )  # last line without newline
    assert count_triangles(str(path)) == 1 + 2 + 3 + 1


def test_obj_with_a_line_longer_than_a_chunk(tmp_path):
    path = tmp_path / 'long.obj'
    n = 600_000  # 1.2 MB of vertex references on one face line
    path.write_bytes(b'v 0 0 0\nf ' + b'1 ' * n + b'\nf 1 2 3\n')
    assert n - 2 + 1 <= count_triangles(str(path)) <= n - 2 + 1 + 2


def test_obj_counting_stops_past_the_limit(tmp_path):
    path = tmp_path / 'big.obj'
    path.write_bytes(b'f 1 2 3\n' * 2_000_000)
    start = time.process_time()
    count = count_triangles(str(path), stop_above=100_000)
    assert 100_000 < count < 2_000_000
    assert time.process_time() - start < 2.0


DAE = """<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
 <library_geometries><geometry id="g"><mesh>
  <triangles count="2"><input semantic="VERTEX" offset="0"/><input semantic="NORMAL" offset="1"/>
   <p>0 0 1 0 2 0  0 0 2 0 3 0</p></triangles>
  <polylist count="2"><input semantic="VERTEX" offset="0"/><vcount>4 3</vcount>
   <p>0 1 2 3 0 1 2</p></polylist>
  <polygons count="1"><input semantic="VERTEX" offset="0"/><p>0 1 2 3 4</p></polygons>
  <tristrips count="1"><input semantic="VERTEX" offset="0"/><p>0 1 2 3</p></tristrips>
  <lines count="1"><input semantic="VERTEX" offset="0"/><p>0 1</p></lines>
 </mesh></geometry></library_geometries></COLLADA>"""


def test_collada_primitives_are_counted(tmp_path):
    path = tmp_path / 'm.dae'
    path.write_text(DAE)
    assert count_triangles(str(path)) == 2 + 3 + 3 + 2


def test_collada_with_a_dtd_is_refused(tmp_path):
    path = tmp_path / 'laughs.dae'
    path.write_text(LAUGHS.replace('robot', 'COLLADA'))
    with pytest.raises(MeshError, match='COLLADA file with a DTD'):
        count_triangles(str(path))


def test_package_uri_climbing_out_is_refused_without_its_contents(tmp_path):
    pkg = tmp_path / 'pkg'
    pkg.mkdir()
    secret = tmp_path / 'secret.obj'
    secret.write_text('top-secret-words\n')
    msg, _ = refused(resolve_mesh_uris, robot_with_mesh('package://pkg/../secret.obj'), finder(pkg))
    assert "leaves package 'pkg'" in msg and 'top-secret' not in msg


def test_mesh_that_fails_to_parse_is_named_but_never_quoted(tmp_path):
    pkg = tmp_path / 'pkg'
    pkg.mkdir()
    (pkg / 'bad.dae').write_text('<COLLADA>root:x:0:0:top-secret<p>1 2</COLLADA>')
    (pkg / 'bad.stl').write_text('root:x:0:0:top-secret\n' * 3)
    for name, words in (
        ('bad.dae', 'not well-formed XML (line 1): mismatched tag'),
        ('bad.stl', 'neither a binary STL'),
    ):
        msg, _ = refused(resolve_mesh_uris, robot_with_mesh('package://pkg/' + name), finder(pkg))
        assert words in msg and 'top-secret' not in msg and "'shell'" in msg


def test_huge_mesh_is_refused_by_size_before_it_is_read(tmp_path):
    pkg = tmp_path / 'pkg'
    pkg.mkdir()
    with open(str(pkg / 'huge.stl'), 'wb') as f:
        f.truncate(2 * 1024**3)  # sparse: 2 GiB on paper, nothing on disk
    start = time.process_time()
    with pytest.raises(LimitError) as exc:
        resolve_mesh_uris(robot_with_mesh('package://pkg/huge.stl'), finder(pkg))
    assert time.process_time() - start < 0.5
    assert 'mesh bytes is 2147483648, over the limit of 268435456' in str(exc.value)
    assert '~limits/mesh_bytes' in str(exc.value)


def test_obj_over_the_triangle_limit_says_counting_stopped(tmp_path):
    pkg = tmp_path / 'pkg'
    pkg.mkdir()
    (pkg / 'many.obj').write_bytes(b'f 1 2 3\n' * 300_000)
    with pytest.raises(LimitError) as exc:
        resolve_mesh_uris(
            robot_with_mesh('package://pkg/many.obj'), finder(pkg), Limits(mesh_triangles=1000)
        )
    msg = str(exc.value)
    assert "link 'shell': mesh 'package://pkg/many.obj' (counted until past the limit)" in msg
    assert 'over the limit of 1000' in msg and '~limits/mesh_triangles' in msg
