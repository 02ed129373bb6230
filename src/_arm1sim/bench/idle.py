"""The floor at real time: the world node's CPU with no robot, and the CPU of one wake-up."""

from __future__ import annotations

import threading
import time
from typing import Dict

from .arm import WORLD


def idle_world(seconds: float) -> Dict[str, float]:
    """A 1 kHz world sleeps and wakes 1 000 times a wall second whatever it simulates;
    what each wake-up costs in CPU is measured apart, with plain 0.9 ms sleeps."""
    import rospy

    from ..ros.world.world_node import parse_args, start_world

    n = 2000
    c0 = time.process_time()
    for _ in range(n):
        time.sleep(0.0009)
    sleep_cpu = (time.process_time() - c0) / n
    node, pacer = start_world(parse_args([WORLD]))

    def stop_later() -> None:
        time.sleep(seconds)
        rospy.signal_shutdown('measured')

    threading.Thread(target=stop_later, daemon=True).start()
    w0, c0 = time.perf_counter(), time.process_time()
    node.run(pacer)
    w1, c1 = time.perf_counter(), time.process_time()
    return {'cpu_core_fraction': (c1 - c0) / (w1 - w0), 'sleep_wakeup_cpu_us': sleep_cpu * 1e6}
