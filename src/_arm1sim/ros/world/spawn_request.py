"""gazebo_msgs/SpawnModel with its request decoded a piece at a time.

genpy decodes a request's strings with one ``bytes.decode`` each, which holds the
interpreter lock throughout: 70-80 ms for a 50 MB ``model_xml`` on a busy 2-core machine,
during which the physics thread cannot step. Decoded PIECE bytes at a time (an incremental
decoder keeps a character split between pieces whole), other threads run between pieces.
Same type and md5sum on the wire: clients see gazebo_ros's service.
"""

from __future__ import annotations

import codecs
import struct
from typing import Any

import genpy
from gazebo_msgs.srv import SpawnModel, SpawnModelRequest, SpawnModelResponse

PIECE = 1 << 18  # bytes decoded in one call
_LENGTH = struct.Struct('<I')
_POSE = struct.Struct('<7d')


def decode_in_pieces(data: memoryview) -> str:
    """``data`` as UTF-8 text with genpy's error handler ('rosmsg'), PIECE bytes a call."""
    if len(data) <= PIECE:
        return bytes(data).decode('utf-8', 'rosmsg')
    decoder = codecs.getincrementaldecoder('utf-8')('rosmsg')
    pieces = [decoder.decode(data[i : i + PIECE]) for i in range(0, len(data), PIECE)]
    pieces.append(decoder.decode(b'', final=True))
    return ''.join(pieces)


class _Reader:
    """Fields of a serialised message in order, as genpy lays them out."""

    def __init__(self, data: Any) -> None:
        self.view, self.pos = memoryview(data), 0

    def take(self, size: int) -> memoryview:
        end = self.pos + size
        if end > len(self.view):
            raise genpy.DeserializationError('buffer underfill')  # as genpy's struct.error
        out, self.pos = self.view[self.pos : end], end
        return out

    def string(self) -> str:
        (length,) = _LENGTH.unpack(self.take(4))
        return decode_in_pieces(self.take(length))


class PiecewiseSpawnModelRequest(SpawnModelRequest):
    def deserialize(self, str: Any) -> PiecewiseSpawnModelRequest:  # noqa: A002 (genpy's name)
        read = _Reader(str)
        self.model_name = read.string()
        self.model_xml = read.string()
        self.robot_namespace = read.string()
        position, orientation = self.initial_pose.position, self.initial_pose.orientation
        (
            position.x,
            position.y,
            position.z,
            orientation.x,
            orientation.y,
            orientation.z,
            orientation.w,
        ) = _POSE.unpack(read.take(_POSE.size))
        self.reference_frame = read.string()
        return self


class PiecewiseSpawnModel:
    """The service class rospy.Service takes: SpawnModel with the request above."""

    _type = SpawnModel._type
    _md5sum = SpawnModel._md5sum
    _request_class = PiecewiseSpawnModelRequest
    _response_class = SpawnModelResponse
