"""Render processes: headless pybullet mirrors of the world that render camera frames.

A 640 x 480 frame costs 2 to 5 ms of CPU with the default renderer (OpenGL on
Mesa's llvmpipe) and 10 to 55 ms with pybullet's TinyRenderer (renderers.py,
``ARM1_RENDERER``; no GPU, no display needed either way), and a renderer that
crashes must not take the world with it, so frames are rendered in child
processes: DIRECT pybullet clients with the world's scenery and URDFs; each
request carries every robot's base pose and joint positions. The world's side
(RenderProcess) reads replies on a thread of its own, so that a large frame is
never copied on the physics thread and a child that dies is noticed at once,
busy or idle.

Protocol on a socket pair (multiprocessing.connection framing): world -> child
``(world_config, {name: load args})`` once, then ``('add', name, load args)``,
``('remove', name)``, ``('render', model, sensor, states)``; child -> world, one
reply per render request in order: ``('frame', nbytes)`` followed by the image
bytes (then a depth camera's depth), raw (no framing), or ``('error', text)``. The world
receives those bytes straight into a buffer of its own with the GIL released: the pages
of a fresh 108 MB buffer fault in then, not on a copy that would hold the physics thread.
"""

from __future__ import annotations

import collections
import logging
import os
import signal
import socket
import subprocess
import sys
import threading
from multiprocessing.connection import Connection
from typing import Any, Dict, Optional, Sequence, Tuple

import numpy as np

from ..description.camera_sensor import CameraSensor
from . import renderers
from .camera_geometry import depth_metres

log = logging.getLogger('_arm1sim.physics')

RENDER_TIMEOUT = 30.0  # s of wall time one frame may take before the renderer counts as hung
SECONDS_PER_PIXEL = 1e-6  # on top of RENDER_TIMEOUT: a 6000x6000 frame takes 4 s unloaded

Reply = Tuple[str, Any]  # ('frame', bytes-like) or ('error', text)


class RenderError(RuntimeError):
    """A render process died or hung."""


def render_timeout(sensor: CameraSensor) -> float:
    """Wall seconds a frame of ``sensor`` may take before its render process counts as hung."""
    return RENDER_TIMEOUT + SECONDS_PER_PIXEL * sensor.pixels


def encode(rgba: np.ndarray, fmt: str) -> bytes:
    """Image bytes in the sensor's format from pybullet's RGBA (height x width x 4) pixels."""
    if fmt == 'B8G8R8':
        return np.ascontiguousarray(rgba[:, :, 2::-1]).tobytes()
    if fmt == 'L8':  # luma, ITU-R BT.601
        return np.rint(rgba[:, :, :3] @ np.array([0.299, 0.587, 0.114])).astype(np.uint8).tobytes()
    return np.ascontiguousarray(rgba[:, :, :3]).tobytes()


def render(
    client: int,
    sensor: CameraSensor,
    link_position: Sequence[float],
    link_orientation: Sequence[float],
    backend: Optional[renderers.Backend] = None,
) -> bytes:
    """One frame of ``sensor`` from a pybullet client, as image bytes (``sensor.step`` per row),
    for a depth camera followed by its depth in metres (``sensor.frame_bytes`` in all);
    TinyRenderer's unless a ``backend`` (renderers.py) is given."""
    rgba, depth = renderers.render(
        backend or renderers.Backend(), client, sensor, link_position, link_orientation
    )
    if sensor.depth_plugin:
        return encode(rgba, sensor.format) + depth_metres(depth, sensor.near, sensor.far).tobytes()
    return encode(rgba, sensor.format)


# ---------------------------------------------------------------------- the child
def _serve(conn: Connection) -> None:
    """The render process: a headless mirror of the world that answers render requests."""
    world = backend = None
    raw = socket.socket(fileno=os.dup(conn.fileno()))  # the same socket, for the pixels
    raw.setblocking(True)
    try:
        world_config, robots = conn.recv()
        backend = renderers.open_backend()  # $ARM1_RENDERER, inherited from the world
        world = backend.open_world(world_config)
        mirror: Dict[str, Any] = {}  # name -> Robot, or the text of why it could not be loaded
        broken: Dict[str, str] = {}

        def load(name: str, args: tuple) -> None:
            try:
                mirror[name] = world.load_robot(*args)
                broken.pop(name, None)
            except Exception as exc:  # reported with each frame that needs it
                broken[name] = '%s: %s' % (type(exc).__name__, exc)

        for name, args in robots.items():
            load(name, args)
        while True:
            request = conn.recv()
            kind = request[0]
            if kind == 'add':
                load(request[1], request[2])
            elif kind == 'remove':
                broken.pop(request[1], None)
                robot = mirror.pop(request[1], None)
                if robot is not None:
                    world.remove_robot(robot)
            elif kind == 'render':
                _, model, sensor, states = request
                try:
                    if model in broken:
                        raise RuntimeError(
                            "model '%s' could not be mirrored: %s" % (model, broken[model])
                        )
                    for name, state in states.items():
                        if name in mirror:
                            mirror[name].set_state(state)
                    position, orientation = mirror[model].link_pose(sensor.link)
                    data = render(world.client, sensor, position, orientation, backend)
                except Exception as exc:  # reported to the world, which logs it
                    conn.send(('error', '%s: %s' % (type(exc).__name__, exc)))
                else:
                    conn.send(('frame', len(data)))
                    raw.sendall(data)
    except (EOFError, OSError):  # the world has gone
        pass
    finally:
        raw.close()
        if backend is not None:
            backend.close()
        if world is not None:
            world.close()


def render_process_main(fd: int, niceness: int = 0) -> None:
    """Entry point of the render process; ``fd`` is its end of a socket pair."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # a Ctrl-C of the launch is the world's to handle
    if niceness:
        os.nice(niceness)
    _serve(Connection(fd))


# ---------------------------------------------------------------------- the world's side
class RenderProcess:
    """One render process, seen from the world: requests go in, replies come back in order.

    A plain child interpreter (not multiprocessing's 'spawn', which re-runs the
    parent's main script) on a socket pair; it exits when the world's end closes.
    ``niceness`` > 0 lets the physics thread win the CPU when both want it.
    """

    def __init__(self, world_config: Any, robots: Dict[str, tuple], niceness: int = 0) -> None:
        """``robots``: {model name: World.load_robot arguments} to mirror from the start."""
        try:
            renderers.backend_name()  # a bad $ARM1_RENDERER said here, not in a child's traceback
        except renderers.BackendError as exc:
            raise RenderError(str(exc)) from None
        ours, theirs = socket.socketpair()
        for end in (ours, theirs):
            end.setblocking(True)  # rospy sets a default socket timeout, which means non-blocking
        env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
        self.process = subprocess.Popen(
            [
                sys.executable,
                '-c',
                'import sys; from _arm1sim.physics.render_process import '
                'render_process_main; render_process_main(int(sys.argv[1]), int(sys.argv[2]))',
                str(theirs.fileno()),
                str(niceness),
            ],
            pass_fds=[theirs.fileno()],
            env=env,
            stdout=subprocess.DEVNULL,
        )
        theirs.close()
        self.pid = self.process.pid
        self._conn = Connection(ours.detach())
        self._raw = socket.socket(fileno=os.dup(self._conn.fileno()))
        self._raw.setblocking(True)
        self.in_flight = 0  # render requests not answered yet (the sensor manager counts)
        self._replies: collections.deque = collections.deque()
        self._gone: Optional[str] = None  # why no more replies will come
        self._cond = threading.Condition()
        self._reader = threading.Thread(
            target=self._read, name='render-reader-%d' % self.pid, daemon=True
        )
        self._reader.start()
        self.send((world_config, dict(robots)))

    def _read(self) -> None:
        """Reader thread: replies into the queue, the process's end noted when it comes."""
        try:
            while True:
                kind, payload = self._conn.recv()
                if kind == 'frame':
                    payload = self._receive_pixels(payload)
                with self._cond:
                    self._replies.append((kind, payload))
                    self._cond.notify()
        except (EOFError, OSError, ValueError) as exc:
            why = self._exit_reason(exc)
            with self._cond:
                self._gone = 'render process %d is gone: %s' % (self.pid, why)
                self._cond.notify()

    def _exit_reason(self, exc: BaseException, wait: float = 1.0) -> str:
        """Why the connection broke, as the process's exit says it (waits ``wait`` s for it:
        its end of the socket closes a moment before it can be reaped)."""
        code = self.process.poll()
        if code is None:
            try:
                code = self.process.wait(wait)
            except subprocess.TimeoutExpired:
                pass
        if code is None:
            return 'its connection closed (%s)' % (exc or type(exc).__name__)
        if code >= 0:
            return 'it exited with status %s' % code
        return 'it was killed by signal %d' % -code

    def _receive_pixels(self, nbytes: int) -> memoryview:
        # np.empty: no zeroing; recv_into fills it without the GIL
        view = memoryview(np.empty(nbytes, np.uint8))  # type: ignore[arg-type]
        got = 0
        while got < nbytes:
            n = self._raw.recv_into(view[got:])
            if not n:
                raise EOFError('the render process closed the connection mid-frame')
            got += n
        return view

    def send(self, message: Any) -> None:
        if self._gone:
            raise RenderError(self._gone)
        try:
            self._conn.send(message)
        except (OSError, ValueError) as exc:
            # A write can find the pipe broken before the reader has seen the end: name the
            # cause the same way, waiting only briefly (this is the physics thread).
            why = self._exit_reason(exc, wait=0.05)
            raise RenderError('render process %d is gone: %s' % (self.pid, why))

    def ready(self) -> bool:
        """Is a reply waiting (or is the process gone, which receive() then raises)?"""
        return bool(self._replies) or self._gone is not None

    def receive(self, timeout: Optional[float] = RENDER_TIMEOUT) -> Reply:
        """The next reply, ``('frame', data)`` (a memoryview of the pixels) or ``('error', text)``;
        waits up to ``timeout``."""
        with self._cond:
            self._cond.wait_for(lambda: self._replies or self._gone, timeout)
            if self._replies:
                return self._replies.popleft()
            if self._gone:
                raise RenderError(self._gone)
        raise RenderError('no frame from render process %d in %s s' % (self.pid, timeout))

    def close(self, kill: bool = False) -> None:
        """End the process: by closing its connection (it sees EOF), or at once with ``kill``."""
        if kill and self.process.poll() is None:
            self.process.kill()
        try:  # wake the reader and the child; closing the fd under a reading thread would race
            self._raw.shutdown(socket.SHUT_RDWR)
        except OSError:
            pass
        try:
            self.process.wait(2.0)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()
        self._reader.join(2.0)
        self._raw.close()
        self._conn.close()
