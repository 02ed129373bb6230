"""Camera updates after each physics step: Gazebo's sensor manager for the stand-in.

Two timings, as Gazebo's:

- Default: physics never waits for rendering. At a camera's update instant a
  frame request goes to a free render process with the robots' state of that
  instant; a camera may have one frame out per render process. When none is
  free (or the camera has as many out), the instant is skipped and the camera
  is owed a frame: as soon as a render process frees up, it renders the newest
  state, stamped with that state's sim time. Finished frames are picked up
  with a poll each step. A slow camera delivers fewer images; the world's
  real-time factor does not drop.
- Lockstep (``WorldConfig.lockstep``, gzserver ``--lockstep``): every update
  instant gets its frame; with as many frames out as there are render
  processes the physics waits for the oldest. Deterministic, for tests and
  faster-than-real-time runs; rendering slower than real time lowers the
  real-time factor instead.

Either way frames are handed over in the order they were asked for, a rate of 0
renders as fast as the render processes go (never waiting), nothing is rendered
(and no process started) while nobody wants images, and a render process that
dies or hangs is replaced (after a growing delay; after MAX_RESTARTS failures in
a row without a frame in between the cameras give up and say so) while the
world steps on.

Render budget: the sum over the world's cameras of width x height x update
rate (sim-time pixels per second) must stay within
``Limits.render_pixels_per_second``. A camera with rate 0 ("as fast as
possible") is charged RATE_ZERO_CHARGED_HZ: its real rate is whatever the
render processes give it, which never holds the physics in either timing.
"""

from __future__ import annotations

import logging
import os
import time
from dataclasses import dataclass
from typing import Any, Callable, Dict, Iterable, List, Optional, Protocol, Union

from ..description.camera_sensor import CameraSensor
from ..description.limits import Limits
from .render_process import RenderError, RenderProcess, Reply, render_timeout

log = logging.getLogger('_arm1sim.physics')

RATE_ZERO_CHARGED_HZ = 60.0  # what an "as fast as possible" camera counts for in the budget
MAX_RESTARTS = 5  # render process failures in a row (no frame between) before giving up
RESTART_DELAY = 0.5  # s of wall time before the first replacement; doubles with each failure
RENDER_NICENESS = 10  # default timing: rendering yields the CPU to the physics thread

States = Callable[[], Dict[str, Any]]
# a frame's image bytes, ``sensor.step`` per row (a depth camera's depth after them: frame_bytes)
Pixels = Union[bytes, memoryview]


class Renderer(Protocol):
    """What the sensor manager needs of a render process (RenderProcess, or a test's fake)."""

    in_flight: int

    def send(self, message: Any) -> None: ...

    def ready(self) -> bool: ...

    def receive(self, timeout: Optional[float] = ...) -> Reply: ...

    def close(self, kill: bool = False) -> None: ...


RendererFactory = Callable[[Any, Dict[str, tuple]], Renderer]


def _nobody() -> bool:
    return False


class Camera:
    """A camera of a spawned model, as the world updates it.

    Whoever publishes its output sets ``wants_image`` / ``wants_info`` (is
    anyone listening?) and ``on_image(stamp_ns, data)`` / ``on_info(stamp_ns)``.
    ``frames``, ``skipped`` and ``lost`` count frames handed over, update
    instants skipped because rendering was behind, and frames a failed render
    process took with it.
    """

    def __init__(self, model: str, sensor: CameraSensor) -> None:
        self.model, self.sensor = model, sensor
        self.period_ns = int(round(1e9 / sensor.update_rate)) if sensor.update_rate > 0 else 0
        self.next_ns = 0
        self.last_ns = -1
        self.in_flight = 0  # frames asked for and not handed over yet
        self.out: List[_Frame] = []  # those frames, oldest first
        self.owed_since: Optional[int] = None  # default timing: an instant was skipped since
        self.removed = False  # its model was deleted: late frames go nowhere
        self.frames = 0  # rendered and handed over
        self.skipped = 0
        self.lost = 0
        self.last_error: Optional[str] = None
        self.wants_image: Callable[[], bool] = _nobody
        self.wants_info: Callable[[], bool] = _nobody
        self.on_image: Optional[Callable[[int, Pixels], None]] = None
        self.on_info: Optional[Callable[[int], None]] = None

    def due(self, now_ns: int) -> bool:
        """True at the sensor's update instants (always, if its rate is 0)."""
        if not self.period_ns:
            return True
        if now_ns < self.last_ns:  # time went back (reset_simulation)
            self.next_ns = now_ns
            self.owed_since = None
        self.last_ns = now_ns
        if now_ns < self.next_ns:
            return False
        self.next_ns += self.period_ns
        if self.next_ns <= now_ns:  # e.g. the first update
            self.next_ns = now_ns + self.period_ns
        return True

    def deliver(self, stamp_ns: int, data: Pixels) -> None:
        self.frames += 1
        if self.on_image is not None:
            self.on_image(stamp_ns, data)


@dataclass(eq=False)
class _Frame:
    camera: Camera
    stamp_ns: int
    renderer: Renderer
    sent_at: float  # wall time, for the hang check
    reply: Optional[Reply] = None


def default_render_processes() -> int:
    """Two where there are two cores: frame k+1 renders while frame k does."""
    return max(1, min(2, os.cpu_count() or 1))


def charged_rate(sensor: CameraSensor) -> float:
    """Frames per sim second a camera counts for in the render budget."""
    return sensor.update_rate if sensor.update_rate > 0 else RATE_ZERO_CHARGED_HZ


class SensorManager:
    """Updates the cameras after each physics step; see the module doc for the timing."""

    def __init__(
        self,
        world_config: Any,
        render_processes: Optional[int] = None,
        renderer_factory: Optional[RendererFactory] = None,
        restart_delay: float = RESTART_DELAY,
        max_restarts: int = MAX_RESTARTS,
    ) -> None:
        """``world_config``: a sdf_world.WorldConfig (its ``lockstep`` and ``limits`` count)."""
        self.world_config = world_config
        self.lockstep = bool(getattr(world_config, 'lockstep', False))
        self.render_processes = render_processes or default_render_processes()
        self.cameras: List[Camera] = []
        self._robots: Dict[str, tuple] = {}  # model name -> World.load_robot arguments, to mirror
        if renderer_factory is None:
            niceness = 0 if self.lockstep else RENDER_NICENESS
            renderer_factory = lambda config, robots: RenderProcess(config, robots, niceness)  # noqa: E731
        self._renderer_factory = renderer_factory
        self.renderers: List[Renderer] = []  # started at the first frame anyone wants
        self._started = False
        self._in_flight: List[_Frame] = []  # every frame out, oldest first
        self.restart_delay, self.max_restarts = restart_delay, max_restarts
        self.failures = 0  # render process failures since the last frame
        self.restarts = 0  # render processes started to replace one
        self._restart_at = 0.0  # wall time (monotonic) the next replacement may start
        self.failed = False  # gave up: no more images

    @property
    def limits(self) -> Limits:
        return getattr(self.world_config, 'limits', None) or Limits()

    # -- models ----------------------------------------------------------------------
    def add_robot(
        self, name: str, load_args: tuple, sensors: Iterable[CameraSensor] = ()
    ) -> List[Camera]:
        """Mirror a spawned robot; returns Camera objects for its ``camera_sensors``.

        Raises limits.LimitError, before anything changes, if the world's cameras
        together would render more than ``render_pixels_per_second``.
        """
        sensors = list(sensors)
        if sensors:
            total = sum(c.sensor.pixels * charged_rate(c.sensor) for c in self.cameras) + sum(
                s.pixels * charged_rate(s) for s in sensors
            )
            others = len(self.cameras)
            self.limits.check(
                'render_pixels_per_second',
                total,
                '%s%s'
                % (
                    ', '.join(s.describe() for s in sensors),
                    ' with the world\'s %d other camera(s)' % others if others else '',
                ),
            )
        cameras = [Camera(name, s) for s in sensors]
        self._robots[name] = load_args
        self._to_renderers(('add', name, load_args))
        self.cameras.extend(cameras)
        return cameras

    def remove_robot(self, name: str) -> None:
        """Forget a robot and its cameras: frames still out for them go nowhere."""
        for cam in self.cameras:
            if cam.model == name:
                cam.removed = True
                cam.on_image = cam.on_info = None
                cam.wants_image = cam.wants_info = _nobody
        self.cameras = [c for c in self.cameras if c.model != name]
        if self._robots.pop(name, None) is not None:
            self._to_renderers(('remove', name))

    def _to_renderers(self, message: Any) -> None:
        for r in list(self.renderers):
            try:
                r.send(message)
            except RenderError as exc:
                self._renderer_failed(r, exc)

    # -- each step -------------------------------------------------------------------
    def update(self, now_ns: int, states: States) -> None:
        """After a physics step at ``now_ns``; ``states()`` gives every robot's state."""
        if self.lockstep:
            self._update_lockstep(now_ns, states)
        else:
            self._update(now_ns, states)

    def _update(self, now_ns: int, states: States) -> None:
        """Default timing: never wait for a render process."""
        if self._in_flight:
            self._collect()
        if self._started and len(self.renderers) < self.render_processes:
            self._replace()
        owed = []
        for cam in self.cameras:
            if cam.due(now_ns):
                if cam.wants_image() and not self.failed:
                    if cam.owed_since is None:
                        cam.owed_since = now_ns
                    elif cam.period_ns:
                        cam.skipped += 1  # the last instant's frame is not out yet
                else:
                    cam.owed_since = None
                    if cam.period_ns and cam.wants_info() and cam.on_info is not None:
                        cam.on_info(now_ns)
            if cam.owed_since is not None:
                owed.append(cam)
        if not owed:
            return
        self._start()
        snapshot = None
        owed.sort(key=lambda c: c.owed_since or 0)  # the longest waiting first
        for cam in owed:
            if cam.in_flight >= len(self.renderers):
                continue
            free = next((r for r in self.renderers if not r.in_flight), None)
            if free is None:
                break
            if snapshot is None:
                snapshot = states()
            if self._request(cam, now_ns, snapshot, free):
                cam.owed_since = None

    def _update_lockstep(self, now_ns: int, states: States) -> None:
        """Lockstep: every update instant gets its frame; the world waits for the oldest."""
        while self._in_flight and self._in_flight[0].renderer.ready():
            self._hand_over()
        if self._started and len(self.renderers) < self.render_processes:
            self._replace()
        for cam in self.cameras:
            if not cam.due(now_ns):
                continue
            if cam.wants_image() and not self.failed:
                self._start()
                if not cam.period_ns and cam.in_flight >= len(self.renderers):
                    continue  # rate 0: as fast as the renderers go
                while self.renderers and cam.in_flight >= len(self.renderers):
                    self._hand_over()  # lockstep: the world waits for the renderers
                if self.renderers:
                    renderer = min(self.renderers, key=lambda r: r.in_flight)
                    self._request(cam, now_ns, states(), renderer)
                else:
                    cam.skipped += 1  # every render process failed; replacements are due
            elif cam.period_ns and cam.wants_info() and cam.on_info is not None:
                cam.on_info(now_ns)

    # -- render processes ------------------------------------------------------------
    def _start(self) -> None:
        if self._started:
            return
        self._started = True
        for _ in range(self.render_processes):
            self._spawn_renderer()
        if self.renderers:
            log.info(
                'cameras: %d render process(es) started (pid %s)%s',
                len(self.renderers),
                ', '.join(str(getattr(r, 'pid', '?')) for r in self.renderers),
                ' in lockstep' if self.lockstep else '',
            )

    def _spawn_renderer(self) -> None:
        try:
            self.renderers.append(self._renderer_factory(self.world_config, self._robots))
        except (OSError, RenderError) as exc:
            self._note_failure('cannot start a render process: %s' % exc)

    def _replace(self) -> None:
        """Start one replacement for a failed render process, once its delay is over."""
        if self.failed or time.monotonic() < self._restart_at:
            return
        self.restarts += 1
        before = len(self.renderers)
        self._spawn_renderer()
        if len(self.renderers) > before:
            log.warning(
                'cameras: render process %s started in place of a failed one',
                getattr(self.renderers[-1], 'pid', '?'),
            )

    def _renderer_failed(self, renderer: Renderer, exc: Exception) -> None:
        """Drop a dead or hung render process and the frames it had; a replacement follows."""
        lost = [f for f in self._in_flight if f.renderer is renderer]
        for f in lost:
            self._in_flight.remove(f)
            cam = f.camera
            cam.out.remove(f)
            cam.in_flight -= 1
            cam.lost += 1
            if not cam.removed and not self.lockstep and cam.owed_since is None:
                cam.owed_since = f.stamp_ns  # render the newest state instead, when it can
        if renderer in self.renderers:
            self.renderers.remove(renderer)
        renderer.in_flight = 0
        try:
            renderer.close(kill=True)
        except Exception as close_exc:  # it is gone either way
            log.debug('cameras: closing a failed render process: %s', close_exc)
        names = sorted({f.camera.sensor.name for f in lost}) or [
            c.sensor.name for c in self.cameras
        ]
        log.error(
            "cameras: %s; camera(s) %s lost %d frame(s)",
            exc,
            ', '.join("'%s'" % n for n in names) or 'none',
            len(lost),
        )
        self._note_failure(str(exc))
        for cam in {f.camera for f in lost}:
            self._deliver_ready(cam)

    def _note_failure(self, why: str) -> None:
        self.failures += 1
        if self.failures > self.max_restarts:
            if not self.failed:
                log.error(
                    'cameras: %d render process failures in a row (last: %s); no more '
                    'images from %s',
                    self.failures,
                    why,
                    ', '.join("'%s'" % c.sensor.name for c in self.cameras) or 'any camera',
                )
            self.failed = True
            for r in list(self.renderers):
                self._renderer_failed_quietly(r)
            return
        delay = self.restart_delay * 2 ** (self.failures - 1)
        self._restart_at = time.monotonic() + delay
        log.warning(
            'cameras: a new render process in %.1f s (failure %d of at most %d)',
            delay,
            self.failures,
            self.max_restarts,
        )

    def _renderer_failed_quietly(self, renderer: Renderer) -> None:
        for f in [f for f in self._in_flight if f.renderer is renderer]:
            self._in_flight.remove(f)
            f.camera.out.remove(f)
            f.camera.in_flight -= 1
        self.renderers.remove(renderer)
        renderer.close(kill=True)

    # -- frames ----------------------------------------------------------------------
    def _request(
        self, cam: Camera, now_ns: int, states: Dict[str, Any], renderer: Renderer
    ) -> bool:
        try:
            renderer.send(('render', cam.model, cam.sensor, states))
        except RenderError as exc:
            self._renderer_failed(renderer, exc)
            return False
        frame = _Frame(cam, now_ns, renderer, time.monotonic())
        renderer.in_flight += 1
        cam.in_flight += 1
        cam.out.append(frame)
        self._in_flight.append(frame)
        return True

    def _collect(self) -> None:
        """Default timing: take every finished frame, fail hung or dead processes; no waiting."""
        now = time.monotonic()
        for renderer in list(self.renderers):
            try:
                while renderer.in_flight and renderer.ready():
                    self._finish(renderer, renderer.receive(0))
                oldest = next((f for f in self._in_flight if f.renderer is renderer), None)
                if oldest is not None and now - oldest.sent_at > render_timeout(
                    oldest.camera.sensor
                ):
                    raise RenderError(
                        'render process %s sent no frame of camera \'%s\' in %.0f s'
                        % (
                            getattr(renderer, 'pid', '?'),
                            oldest.camera.sensor.name,
                            now - oldest.sent_at,
                        )
                    )
            except RenderError as exc:
                self._renderer_failed(renderer, exc)

    def _hand_over(self) -> None:
        """Lockstep: wait for the oldest frame out and hand it to its camera."""
        frame = self._in_flight[0]
        try:
            reply = frame.renderer.receive(render_timeout(frame.camera.sensor))
        except RenderError as exc:
            self._renderer_failed(frame.renderer, exc)
            return
        self._finish(frame.renderer, reply)

    def _finish(self, renderer: Renderer, reply: Reply) -> None:
        """A reply of ``renderer``: it answers its oldest request."""
        frame = next(f for f in self._in_flight if f.renderer is renderer)
        self._in_flight.remove(frame)
        renderer.in_flight -= 1
        frame.reply = reply
        self._deliver_ready(frame.camera)

    def _deliver_ready(self, cam: Camera) -> None:
        """Hand a camera its finished frames, in the order they were asked for."""
        while cam.out and cam.out[0].reply is not None:
            frame = cam.out.pop(0)
            cam.in_flight -= 1
            kind, payload = frame.reply  # type: ignore[misc]  # not None: checked above
            if cam.removed:
                continue
            if kind == 'frame':
                self.failures = 0
                cam.last_error = None
                cam.deliver(frame.stamp_ns, payload)
            elif payload != cam.last_error:  # once per distinct error, not 30 times a second
                cam.last_error = payload
                log.error(
                    "camera '%s' of model '%s': render failed: %s",
                    cam.sensor.name,
                    cam.model,
                    payload,
                )

    def drain(self) -> None:
        """Wait for every frame out and hand it over (for tests, in either timing)."""
        while self._in_flight:
            self._hand_over()

    def close(self) -> None:
        for r in self.renderers:
            r.close()
        self.renderers = []
        self._in_flight.clear()
        self._started = False
        for cam in self.cameras:
            cam.in_flight = 0
            cam.out = []
            cam.owed_since = None
