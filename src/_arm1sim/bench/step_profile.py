"""Where the physics thread's time goes: a cProfile of it bucketed into the stand-in's parts."""

from __future__ import annotations

import pstats
from typing import Callable, Dict, List, Tuple

# (label, predicate on pstats' (file, function) of an entry)
PROFILE_PARTS: List[Tuple[str, Callable[[str, str], bool]]] = [
    ('pybullet stepSimulation', lambda f, fn: 'stepSimulation' in fn),
    (
        'pybullet joint read / torque write',
        lambda f, fn: 'getJointStates' in fn or 'setJointMotorControlArray' in fn,
    ),
    ('controllers, PID, controller manager (Python)', lambda f, fn: '/_arm1sim/control/' in f),
    (
        'hardware interface, robot, simulation step (Python)',
        lambda f, fn: any(m in f for m in ('robot_hw_sim.py', 'physics/robot.py', 'simulation.py')),
    ),
    (
        'ROS publishing (messages, rospy, sockets)',
        lambda f, fn: (
            any(m in f for m in ('rospy', 'genpy', '_msgs/msg', 'node_handle.py'))
            or 'sendall' in fn
        ),
    ),
    (
        'world loop, clock, pacing',
        lambda f, fn: any(
            m in f for m in ('world_loop.py', 'sim_clock.py', 'sim_thread.py', 'pacer.py')
        ),
    ),
]
OTHER = 'Python built-ins (min, max, isfinite, ...) and the rest'


def profile_split(stats: pstats.Stats) -> Dict[str, float]:
    """Share of the profiled time per PROFILE_PARTS label, the rest under OTHER."""
    shares = {label: 0.0 for label, _ in PROFILE_PARTS}
    shares[OTHER] = 0.0
    total = 0.0
    entries = stats.stats  # type: ignore[attr-defined]  # pstats keeps its table here
    for (path, _, fn), (_, _, tottime, _, _) in entries.items():
        total += tottime
        label = next((part for part, match in PROFILE_PARTS if match(path, fn)), OTHER)
        shares[label] += tottime
    return {k: v / total for k, v in shares.items()}
