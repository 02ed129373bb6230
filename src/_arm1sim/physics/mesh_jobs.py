"""Convex pieces made off the world's process: a spawn never waits on them.

A dense mesh's pieces take seconds of CPU (about 0.3 ms per triangle: 5.5 s for a 20k
bumpy part), longer than upstream's spawner waits under load. Such a mesh collides as its
hull in the spawn that finds the cache empty, and one process per spawn, at the lowest
priority, fills the cache (physics/mesh_cache.py) for the spawns after it. It outlives the
world if it must: the cache is written whole or not at all.

    python -m _arm1sim.physics.mesh_jobs '<json: cache_dir, limits, [[path, scale], ...]>'
"""

from __future__ import annotations

import dataclasses
import json
import logging
import os
import subprocess
import sys
from typing import List, Optional, Sequence, Set, Tuple

from ..description.limits import Limits

log = logging.getLogger('_arm1sim.physics')

Job = Tuple[str, Tuple[float, float, float]]
_started: Set[Tuple[str, Tuple[float, float, float], str]] = set()  # once per world process
pids: List[int] = []  # the processes started, for whoever must wait for or end them


def fill_later(jobs: Sequence[Job], cache_dir: str, limits: Limits) -> Optional[int]:
    """Start one low-priority process that makes the pieces of these meshes into the
    cache; meshes already started by this process are skipped. Its pid, None if none."""
    todo = [(path, scale) for path, scale in jobs if (path, scale, cache_dir) not in _started]
    if not todo:
        return None
    _started.update((path, scale, cache_dir) for path, scale in todo)
    os.makedirs(cache_dir, exist_ok=True)  # its going away later tells the process to stop
    argument = json.dumps(
        {'cache_dir': cache_dir, 'limits': dataclasses.asdict(limits), 'jobs': todo}
    )
    proc = subprocess.Popen(
        [sys.executable, '-m', __name__, argument],
        stdin=subprocess.DEVNULL,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        preexec_fn=lambda: os.nice(19),
        start_new_session=True,  # a Ctrl-C to the world's group leaves it to finish
    )
    log.info('convex pieces of %d mesh(es) being made in process %d', len(todo), proc.pid)
    pids.append(proc.pid)
    return proc.pid


def main(argv: List[str]) -> int:
    from .mesh_cache import collision_mesh
    from .mesh_reading import MeshReadError

    spec = json.loads(argv[0])
    limits = Limits(**spec['limits'])
    for path, scale in spec['jobs']:
        if not os.path.isdir(spec['cache_dir']):
            break  # the cache was removed (a test's, a bench's): nobody waits for it
        try:
            collision_mesh(path, scale, spec['cache_dir'], limits)
        except (MeshReadError, OSError, ValueError):
            continue  # the spawn said what was wrong; the next one says it again
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
