"""Raw 8-bit images as sensor_msgs/Image carries them (data, width, height, step, encoding).

ROS-free and numpy-only (rostest nodes run on the system python, without pybullet).
"""
import struct
import zlib

import numpy as np


def is_uniform(data, width, height, step):
    """True when every pixel of a raw image equals the first one: a blank sky or wall.

    simple_arm compares bytes, which is the same for a grey or white view;
    comparing pixels also calls a blank coloured view uniform.
    """
    if not width or not height or step < width or len(data) < height * step:
        return False  # empty or malformed: no evidence of a blank view
    rows = np.frombuffer(data, np.uint8, count=height * step).reshape(height, step)
    bpp = step // width
    pixels = rows[:, :width * bpp].reshape(-1, bpp)
    return bool((pixels == pixels[0]).all())


# PNG colour type and channels of the encodings png() can write
PNG_TYPES = {'rgb8': (2, 3), 'bgr8': (2, 3), 'mono8': (0, 1), 'rgba8': (6, 4), 'bgra8': (6, 4)}


def png(data, width, height, step, encoding):
    """A PNG file's bytes of a raw 8-bit image (as in sensor_msgs/Image)."""
    kind, channels = PNG_TYPES[encoding]
    rows = np.frombuffer(data, np.uint8, count=height * step).reshape(height, step)
    px = rows[:, :width * channels].reshape(height, width, channels)
    if encoding.startswith('bgr'):
        px = px[:, :, [2, 1, 0, 3][:channels]]
    raw = np.concatenate([np.zeros((height, 1), np.uint8), px.reshape(height, -1)], axis=1)

    def chunk(tag, body):
        return (struct.pack('>I', len(body)) + tag + body
                + struct.pack('>I', zlib.crc32(tag + body) & 0xffffffff))
    return (b'\x89PNG\r\n\x1a\n'
            + chunk(b'IHDR', struct.pack('>IIBBBBB', width, height, 8, kind, 0, 0, 0))
            + chunk(b'IDAT', zlib.compress(raw.tobytes())) + chunk(b'IEND', b''))
