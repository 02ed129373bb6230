"""Raw 8-bit images as sensor_msgs/Image carries them (data, width, height, step, encoding).

ROS-free: numpy, and Pillow to write PNG files.
"""

import io

import numpy as np
from PIL import Image


def is_uniform(data, width, height, step):
    """True when every pixel of a raw image equals the first one: a blank sky or wall.

    simple_arm compares bytes, which is the same for a grey or white view;
    comparing pixels also calls a blank coloured view uniform.
    """
    if not width or not height or step < width or len(data) < height * step:
        return False  # empty or malformed: no evidence of a blank view
    bpp = step // width
    if step == width * bpp:  # no row padding: one C comparison, 0.05 ms for 640 x 480 rgb8
        return bytes(data[:bpp]) * (width * height) == data[: height * step]
    rows = np.frombuffer(data, np.uint8, count=height * step).reshape(height, step)
    pixels = rows[:, : width * bpp].reshape(-1, bpp)
    return bool((pixels == pixels[0]).all())


# Channels of the encodings png() can write (as PNG RGB, grey and RGBA)
PNG_TYPES = {'rgb8': 3, 'bgr8': 3, 'mono8': 1, 'rgba8': 4, 'bgra8': 4}


def png(data: bytes, width: int, height: int, step: int, encoding: str) -> bytes:
    """A PNG file's bytes of a raw 8-bit image (as in sensor_msgs/Image), written by Pillow."""
    channels = PNG_TYPES[encoding]
    rows = np.frombuffer(data, np.uint8, count=height * step).reshape(height, step)
    px = rows[:, : width * channels].reshape(height, width, channels)
    if encoding.startswith('bgr'):
        px = px[:, :, [2, 1, 0, 3][:channels]]
    out = io.BytesIO()
    pixels = px.reshape(height, width) if channels == 1 else px  # Pillow: 2-D is grey
    Image.fromarray(np.ascontiguousarray(pixels)).save(out, 'PNG')
    return out.getvalue()
