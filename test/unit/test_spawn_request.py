"""The spawn services' request is decoded a piece at a time, as genpy decodes it whole."""

import io

import genpy
import pytest
from gazebo_msgs.srv import SpawnModelRequest
from geometry_msgs.msg import Point, Pose, Quaternion

from _arm1sim.ros.world import spawn_request
from _arm1sim.ros.world.spawn_request import PiecewiseSpawnModel, PiecewiseSpawnModelRequest


def _wire(xml, name='m€', namespace='/ns', frame='world'):
    request = SpawnModelRequest(
        model_name=name,
        model_xml=xml,
        robot_namespace=namespace,
        initial_pose=Pose(Point(1.5, -2, 3), Quaternion(0.1, 0.2, 0.3, 0.9)),
        reference_frame=frame,
    )
    buf = io.BytesIO()
    request.serialize(buf)
    return buf.getvalue()


@pytest.mark.parametrize(
    'xml', ['', '<robot name="r"/>', 'é€𝄞' * 37 + 'x' * 11, '<robot>%s</robot>' % ('ü' * 5000)]
)
def test_the_request_decodes_as_genpys_with_characters_split_between_pieces(xml, monkeypatch):
    monkeypatch.setattr(spawn_request, 'PIECE', 7)  # splits inside multi-byte characters
    data = _wire(xml)
    mine = PiecewiseSpawnModelRequest().deserialize(data)
    theirs = SpawnModelRequest().deserialize(data)
    for field in SpawnModelRequest.__slots__:
        assert getattr(mine, field) == getattr(theirs, field), field
    assert mine.model_xml == xml


def test_bytes_that_are_not_utf8_are_replaced_as_genpy_does(monkeypatch):
    monkeypatch.setattr(spawn_request, 'PIECE', 3)
    data = _wire('abcdefgh').replace(b'abcdefgh', b'ab\xffcd\xc3\xe2\x82')
    mine = PiecewiseSpawnModelRequest().deserialize(data)
    assert mine.model_xml == SpawnModelRequest().deserialize(data).model_xml


def test_a_truncated_request_is_a_deserialization_error():
    data = _wire('<robot/>')
    for cut in (3, 10, len(data) - 1):
        with pytest.raises(genpy.DeserializationError):
            PiecewiseSpawnModelRequest().deserialize(data[:cut])


def test_the_service_is_gazebo_msgs_spawn_model_on_the_wire():
    from gazebo_msgs.srv import SpawnModel

    assert PiecewiseSpawnModel._type == SpawnModel._type == 'gazebo_msgs/SpawnModel'
    assert PiecewiseSpawnModel._md5sum == SpawnModel._md5sum
    assert issubclass(PiecewiseSpawnModel._request_class, SpawnModel._request_class)
