"""Top speed of the stand-in: steps per wall second with real_time_update_rate 0."""

from __future__ import annotations

import threading
import time
from typing import Any, Dict, List, Tuple

from .standin import listeners, start_standin
from .step_profile import profile_split


def standin(
    seconds: float,
    arms: int = 1,
    warmup: float = 1.0,
    profile: bool = False,
    camera: bool = False,
    trajectory: bool = False,
    model_states: bool = False,
) -> Dict[str, Any]:
    """Steps per wall second over ``seconds`` after ``warmup`` (with ``profile``: where the
    physics thread's time goes instead; with ``camera``: arm1's camera streaming)."""
    import rospy

    # With the camera: in lockstep, so that the figure says what a frame costs the physics.
    node, pacer = start_standin(arms, 0, lockstep=camera, trajectory=trajectory)
    procs = listeners(arms, camera, model_states)
    marks: List[Tuple[float, int, float]] = []

    def timer() -> None:
        time.sleep(warmup)
        marks.append((time.perf_counter(), node.sim.steps, time.process_time()))
        time.sleep(seconds)
        marks.append((time.perf_counter(), node.sim.steps, time.process_time()))
        rospy.signal_shutdown('measured')

    threading.Thread(target=timer, daemon=True).start()
    profiler = None
    if profile:
        import cProfile

        profiler = cProfile.Profile()
        profiler.enable()
    try:
        node.run(pacer)
    finally:
        if profiler:
            profiler.disable()
        for proc in procs:
            proc.terminate()
    (w0, s0, c0), (w1, s1, c1) = marks
    if profiler:
        import pstats

        return {
            'profile_share': profile_split(pstats.Stats(profiler)),
            'profiled_steps_per_s': (s1 - s0) / (w1 - w0),
        }
    return {
        'steps_per_s': (s1 - s0) / (w1 - w0),
        # CPU of the whole process (rospy's threads too) per step: on a loaded machine wall
        # time counts the waits for a core, CPU time does not
        'cpu_us_per_step': (c1 - c0) / max(s1 - s0, 1) * 1e6,
        'arms': arms,
        'camera': camera,
    }
