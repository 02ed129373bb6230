"""Command latency: wall time from publishing a joint1 target to the first control update
that uses it, the publisher in a process of its own."""

from __future__ import annotations

import json
import math
import subprocess
import sys
import threading
import time
from typing import Any, Dict, List, Tuple

from ..control.joint_position_controller import JointPositionController
from .standin import start_standin


def latency(commands: int, rate: float = 100.0) -> Dict[str, Any]:
    """``commands`` distinct targets at ``rate`` Hz: p50, p99 and max latency (ms)."""
    import rospy

    node, pacer = start_standin(1, None)
    manager = node.sim.models['arm1'].controller_manager
    ctrl = manager.controller('joint1_position_controller') if manager else None
    if not isinstance(ctrl, JointPositionController):
        raise RuntimeError('arm1 has no joint1_position_controller')
    applied: Dict[float, float] = {}
    original = ctrl.update

    def update(*args: Any) -> None:  # record the first update that sees each new target
        target = ctrl.target
        if target not in applied:
            applied[target] = time.time()
        original(*args)

    ctrl.update = update  # type: ignore[method-assign,assignment]  # instrumented for this measurement
    out: Dict[str, List[Tuple[float, float]]] = {}

    def publish() -> None:
        time.sleep(2.0)  # controllers started, connections made
        proc = subprocess.run(
            [
                sys.executable,
                '-m',
                '_arm1sim.bench.workers',
                'publisher',
                '--count',
                str(commands),
                '--rate',
                str(rate),
            ],
            stdout=subprocess.PIPE,
            text=True,
        )
        out['sent'] = json.loads(proc.stdout.strip().splitlines()[-1])
        time.sleep(0.2)
        rospy.signal_shutdown('measured')

    threading.Thread(target=publish, daemon=True).start()
    node.run(pacer)
    lat = sorted((applied[v] - t) * 1e3 for v, t in out['sent'] if v in applied)
    return {
        'n': len(lat),
        'sent': len(out['sent']),
        'p50_ms': percentile(lat, 50),
        'p99_ms': percentile(lat, 99),
        'max_ms': lat[-1] if lat else float('nan'),
    }


def publisher(count: int, rate: float) -> None:
    """Publishes ``count`` distinct joint1 targets; prints [(value, wall time)]."""
    import rospy
    from std_msgs.msg import Float64

    rospy.init_node('bench_publisher', anonymous=True)
    pub = rospy.Publisher('/arm1/joint1_position_controller/command', Float64, queue_size=10)
    while pub.get_num_connections() == 0:
        time.sleep(0.05)
    time.sleep(0.5)
    sent = []
    for k in range(count):
        value = 0.1 + 1e-4 * k  # unique, within joint1's limits
        sent.append((value, time.time()))
        pub.publish(value)
        time.sleep(1.0 / rate)
    print(json.dumps(sent))


def percentile(values: List[float], q: float) -> float:
    """The ``q`` th percentile (nearest rank) of sorted ``values``; nan for none."""
    if not values:
        return float('nan')
    return values[min(len(values) - 1, int(math.ceil(q / 100.0 * len(values))) - 1)]
