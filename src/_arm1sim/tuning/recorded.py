"""The step metrics of a recorded run: the steps a user commanded and how the joint followed.

Input is plain series (ROS-free): command samples ``(t, value)`` of a position
controller and position samples ``(t, position)`` of its joint, e.g. from a rosbag
of ``<ns>/joint_states`` and ``<ns>/<controller>/command`` (_arm1sim.ros.tools.bag reads one).
A step is a command change of at least ``min_step`` rad that is then held for at
least ``min_hold`` s; each is measured up to the next command change (or the end
of the recording) exactly like a simulated step (metrics.step_metrics), with the
command clamped to the joint's limits as the controller does. Slowly varying
commands (simple_mover's sine, 10 Hz) contain no such steps.

Sparse samples can only miss what happens between them: at joint_states' 50 Hz a
fast wobble (arm1's is at up to 500 Hz) may go unseen, so recorded overshoot, jitter
and settling time are lower bounds of what a 1 kHz record would show.
"""

import bisect
from typing import List, Tuple

from .metrics import step_metrics

MIN_STEP = 0.05  # rad
MIN_HOLD = 0.5  # s


def find_steps(commands, min_step=MIN_STEP, min_hold=MIN_HOLD, end_time=None):
    """``[(t_step, previous command, target, t_end)]`` from ``[(t, value)]`` commands."""
    commands = sorted(commands)
    changes: List[Tuple[float, float]] = []  # (t, value) where the value changes
    for t, v in commands:
        if not changes or abs(v - changes[-1][1]) > 1e-9:
            changes.append((t, v))
    end_time = commands[-1][0] if end_time is None and commands else end_time
    out = []
    for k in range(1, len(changes)):
        t, v = changes[k]
        t_end = changes[k + 1][0] if k + 1 < len(changes) else end_time
        prev = changes[k - 1][1]
        if abs(v - prev) >= min_step and t_end - t >= min_hold:
            out.append((t, prev, v, t_end))
    return out


def _position_at(times, positions, t):
    k = bisect.bisect_left(times, t)
    if k <= 0:
        return positions[0]
    if k >= len(times):
        return positions[-1]
    t0, t1 = times[k - 1], times[k]
    x0, x1 = positions[k - 1], positions[k]
    return x0 if t1 == t0 else x0 + (x1 - x0) * (t - t0) / (t1 - t0)


def recorded_steps(commands, samples, lower=None, upper=None, min_step=MIN_STEP, min_hold=MIN_HOLD):
    """``[(t_step, StepMetrics)]`` for the steps in ``commands`` measured on ``samples``
    (``[(t, position)]``, the joint's positions)."""
    samples = sorted(samples)
    if len(samples) < 2:
        return []
    times = [t for t, _ in samples]
    positions = [x for _, x in samples]
    out = []
    for t_step, _, target, t_end in find_steps(commands, min_step, min_hold, times[-1]):
        if lower is not None and upper is not None:
            target = min(max(target, lower), upper)
        start = _position_at(times, positions, t_step)
        seg = [(t, x) for t, x in samples if t_step < t <= t_end]
        if len(seg) < 2 or abs(target - start) < 1e-6:
            continue
        ts = [t_step] + [t for t, _ in seg]
        xs = [start] + [x for _, x in seg]
        out.append((t_step, step_metrics(ts, xs, target, start=start, t_step=t_step)))
    return out
