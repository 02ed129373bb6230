"""Helpers of the GUI rostests: an Xvfb display, a launch on it, and its screen as pixels."""

import os
import shutil
import signal
import struct
import subprocess
import tempfile

import numpy as np
import rospkg

from _arm1sim.goal.image import png

SCREEN = (1024, 768)


def read_xwd(path):
    """RGB pixels (H x W x 3) of an X window dump (Xvfb -fbdir keeps the screen as one)."""
    with open(path, 'rb') as f:
        data = f.read()
    h = struct.unpack('>25I', data[:100])
    header_size, width, height, byte_order = h[0], h[4], h[5], h[7]
    bits_per_pixel, bytes_per_line, masks, ncolors = h[11], h[12], h[14:17], h[19]
    assert bits_per_pixel == 32, 'a %d-bit screen' % bits_per_pixel
    px = np.frombuffer(
        data,
        '<u4' if byte_order == 0 else '>u4',
        count=height * bytes_per_line // 4,
        offset=header_size + 12 * ncolors,
    ).reshape(height, -1)[:, :width]
    shift = lambda m: (m & -m).bit_length() - 1  # noqa: E731
    return np.stack([(px & m) >> shift(m) for m in masks], axis=-1).astype(np.uint8)


def orange(rgb):
    """Pixels of arm1's orange links (URDF colour 1 0.5 0, lit and shaded)."""
    r, g, b = (rgb[:, :, i].astype(int) for i in range(3))
    return (r > 120) & (r - g > 50) & (g - b > 30) & (b < 100)


def colours(rgb):
    return len(np.unique(rgb.reshape(-1, 3), axis=0))


class Display:
    """An Xvfb server on a free display number, and what is launched on it."""

    def __init__(self):
        self.dir = tempfile.mkdtemp(prefix='arm1-xvfb-')
        read_end, write_end = os.pipe()
        self.xvfb = subprocess.Popen(
            [
                'Xvfb',
                '-displayfd',
                str(write_end),
                '-screen',
                '0',
                '%dx%dx24' % SCREEN,
                '-fbdir',
                self.dir,
                '-nolisten',
                'tcp',
            ],
            pass_fds=[write_end],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        os.close(write_end)
        with os.fdopen(read_end) as f:
            self.name = ':' + f.readline().strip()  # chosen by Xvfb
        self.launches = []

    def roslaunch(self, *args):
        """roslaunch on this display, against the test's master."""
        self.launches.append(
            subprocess.Popen(
                ['roslaunch'] + list(args),
                start_new_session=True,
                env=dict(os.environ, DISPLAY=self.name),
                stdout=subprocess.DEVNULL,
                stderr=subprocess.STDOUT,
            )
        )

    def screen(self):
        return read_xwd(os.path.join(self.dir, 'Xvfb_screen0'))

    def save(self, rgb, name):
        """Keep a screenshot as a PNG in ROS_HOME; returns its path."""
        path = os.path.join(rospkg.get_ros_home(), name)
        h, w = rgb.shape[:2]
        with open(path, 'wb') as f:
            f.write(png(rgb.tobytes(), w, h, w * 3, 'rgb8'))
        return path

    def close(self):
        for proc in self.launches:
            _stop(proc, lambda sig: os.killpg(proc.pid, sig), signal.SIGINT)
        _stop(self.xvfb, self.xvfb.send_signal, signal.SIGTERM)
        shutil.rmtree(self.dir, ignore_errors=True)


def _stop(proc, kill, sig):
    if proc.poll() is not None:
        return
    kill(sig)
    try:
        proc.wait(20)
    except subprocess.TimeoutExpired:
        kill(signal.SIGKILL)
        proc.wait()
