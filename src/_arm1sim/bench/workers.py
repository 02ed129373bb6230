"""One measurement per process: ``python -m _arm1sim.bench.workers KIND [options]``.

It prints one JSON line. Each runs in a fresh process because a process holds one ROS
node, and so that one measurement's threads and memory do not colour the next.
"""

from __future__ import annotations

import argparse
import json
import sys
from typing import Any, Callable, Dict, List, Optional

from .bare_pybullet import bare
from .big_description import big_description_bench, big_description_client
from .big_goal import big_goal, big_goal_client
from .depth import depth_frame
from .idle import idle_world
from .latency import latency, publisher
from .launched import realtime, seed_goal, startup
from .meshes import cache_fill, concave_mesh
from .moveit import idle_move_group, planning_times
from .render import render
from .sensors import laser_scan
from .speed import standin
from .web import web_view

KINDS: Dict[str, Callable[..., Any]] = {
    'bare': bare,
    'standin': standin,
    'latency': latency,
    'publisher': publisher,
    'idle_world': idle_world,
    'startup': startup,
    'realtime': realtime,
    'seed_goal': seed_goal,
    'render': render,
    'laser': laser_scan,
    'depth': depth_frame,
    'web_view': web_view,
    'big_goal': big_goal,
    'big_goal_client': big_goal_client,
    'big_description': big_description_bench,
    'big_description_client': big_description_client,
    'concave_mesh': concave_mesh,
    'mesh_cache_fill': cache_fill,
    'moveit_planning': planning_times,
    'moveit_idle': idle_move_group,
}


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser()
    parser.add_argument('kind', choices=sorted(KINDS))
    parser.add_argument('--seconds', type=float)
    parser.add_argument('--arms', type=int)
    parser.add_argument('--commands', type=int)
    parser.add_argument('--count', type=int)
    parser.add_argument('--triangles', type=int)
    parser.add_argument('--rate', type=float)
    parser.add_argument('--profile', action='store_true', default=None)
    parser.add_argument('--camera', action='store_true', default=None)
    parser.add_argument('--trajectory', action='store_true', default=None)
    parser.add_argument('--model-states', action='store_true', default=None)
    args = parser.parse_args(argv)
    kwargs = {k: v for k, v in vars(args).items() if k != 'kind' and v is not None}
    result = KINDS[args.kind](**kwargs)
    if result is not None:
        # on a line of its own: C libraries (pybullet's URDF warnings) print without newlines
        print('\n' + json.dumps(result))
    return 0


if __name__ == '__main__':
    sys.exit(main())
