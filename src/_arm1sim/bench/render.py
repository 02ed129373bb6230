"""Camera frame cost per renderer backend (physics/renderers.py) and image size.

Each backend renders arm1's own camera (urdf/arm1.gazebo.xacro) in the willow_garage
world, as a render process does, with the arm at its start pose as robot_spawn.launch
shows it (the horizon: ground and sky fill the picture): wall and CPU milliseconds per
frame (CPU counts every thread of the process: Mesa's llvmpipe rasterises on several),
median over ``count`` frames after a warm-up frame, the encoding into image bytes included.
"""

from __future__ import annotations

import dataclasses
import statistics
import time
from typing import Any, Dict, Optional, Sequence

from ..description.sdf_world import read_world
from ..paths import repo_root
from ..physics import renderers
from ..physics.render_process import encode
from .arm import WORLD, arm1_urdf

SIZES = ((320, 240), (640, 480), (800, 800))


def _find(pkg: str) -> str:
    if pkg == 'arm1':
        return repo_root()
    raise LookupError(pkg)


def frame_costs(
    count: int = 30, backends: Sequence[str] = renderers.BACKENDS, sizes: Sequence[Any] = SIZES
) -> Dict[str, Any]:
    """{'<backend>_<w>x<h>_ms': wall ms, '..._cpu_ms': CPU ms} per frame, and errors by name."""
    from ..sim.simulation import Simulation

    out: Dict[str, Any] = {'default': renderers.DEFAULT}
    sim = Simulation(read_world(WORLD))
    try:
        urdf = arm1_urdf()
        prepared = sim.prepare_urdf('arm1', urdf, find_package=_find)
        sensor = sim.spawn_urdf('arm1', urdf, find_package=_find).cameras[0].sensor
        for name in backends:
            backend: Optional[renderers.Backend] = None
            world = None
            try:
                backend = renderers.open_backend(name)
                world = backend.open_world(read_world(WORLD))
                robot = world.load_robot(*prepared.load_args)
                pose = robot.link_pose(sensor.link)
                for w, h in sizes:
                    s = dataclasses.replace(sensor, width=w, height=h)
                    walls, cpus = [], []
                    for k in range(count + 1):
                        w0, c0 = time.perf_counter(), time.process_time()
                        rgba, _ = renderers.render(backend, world.client, s, *pose)
                        encode(rgba, s.format)
                        if k:  # the first frame sets up buffers
                            walls.append(time.perf_counter() - w0)
                            cpus.append(time.process_time() - c0)
                    key = '%s_%dx%d' % (name, w, h)
                    out[key + '_ms'] = 1000.0 * statistics.median(walls)
                    out[key + '_cpu_ms'] = 1000.0 * statistics.median(cpus)
            except renderers.BackendError as exc:  # not here: said, not dropped
                out['%s_error' % name] = str(exc)
            finally:
                if backend is not None:
                    backend.close()
                if world is not None:
                    world.close()
    finally:
        sim.close()
    return out


def render(count: int = 30) -> Dict[str, Any]:
    """The bench worker ``render``."""
    return frame_costs(count)


NOTES = """
`gl` is the default: the only one under the 8 ms goal at 640 × 480, and its picture is
TinyRenderer's (mean absolute difference about 1 of 255 on arm1, the arm's outline and the
depth buffer the same; `test/unit/test_renderers.py`). It draws pybullet's visual shapes in
an OpenGL 3.3 context of its own (moderngl, headless EGL, Mesa's llvmpipe on the CPU) with
TinyRenderer's lighting, and reads back colour and depth straight into numpy. `tiny`
rasterises on one thread inside pybullet; its cost grows with the pixels the ground and
the robot cover (10 ms for sky, 55 ms for mostly ground at 640 × 480). `egl`, pybullet's
own EGL plugin on the same llvmpipe, costs 40–60 ms of CPU at every size measured, 64 × 48
too (a fixed cost per frame, not per pixel), and its picture differs (it casts shadows, with acne on
the ground, and lights otherwise), so it stays selectable only. Measured in one process per run
(`bench/render.py`): arm1's own camera at the arm's start pose (the horizon, as
robot_spawn.launch shows it), median of 30 frames after a warm-up frame, encoding into
image bytes included; CPU counts all threads (llvmpipe uses several).
"""


def render_section(results: Dict[str, Any]) -> str:
    """BENCHMARKS.md's section on the renderers, from this run's ``render`` figures."""
    fig = results.get('figures', {}).get('render')
    if not fig:
        return ''

    def cell(name: str, w: int, h: int) -> str:
        key = '%s_%dx%d' % (name, w, h)
        wall, cpu = fig.get(key + '_ms'), fig.get(key + '_cpu_ms')
        if wall is None or cpu is None:
            return 'not run'
        return '%.1f (CPU %.1f)' % (wall['median'], cpu['median'])

    lines = [
        '\n## Camera frames per renderer\n',
        'Wall ms per frame (CPU ms, all threads), medians over the runs; `ARM1_RENDERER` '
        'chooses ([docs/sensors.md](docs/sensors.md#renderers)).\n',
        '| renderer | %s |' % ' | '.join('%d × %d' % s for s in SIZES),
        '|---|%s' % ('---|' * len(SIZES)),
    ]
    for name in renderers.BACKENDS:
        label = '`%s`%s' % (name, ' (default)' if name == renderers.DEFAULT else '')
        lines.append('| %s | %s |' % (label, ' | '.join(cell(name, w, h) for w, h in SIZES)))
    return '\n'.join(lines) + '\n' + NOTES
