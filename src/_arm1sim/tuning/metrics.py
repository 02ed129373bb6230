"""Step-response figures of one joint, from any sampled response (simulated or recorded).

A step starts at ``t_step`` from position ``start`` towards ``target``; ``times``
and ``positions`` are the samples from the step on, up to the end of the hold.
With ``size = target - start``:

- rise time: from the first 10 % to the first 90 % crossing of the step (s);
- overshoot: the furthest excursion beyond the target, in % of |size|;
- settling time: from the step until the response enters, for good, the band of
  ±2 % of |size| around the target (s); ``inf`` if it is outside at the end;
- steady-state error: target − mean position over the final window (rad);
- jitter: peak-to-peak position over the final window (rad): the wobble left
  once the response has settled.

The final window is the last ``final_window`` seconds of the hold. Crossing
times are interpolated linearly between samples, so sparse recordings (50 Hz
joint_states) still give usable numbers.
"""

import math
from dataclasses import asdict, dataclass

BAND = 0.02  # settling band, fraction of the step size
FINAL_WINDOW = 0.5  # s at the end of a hold for the steady-state error and the jitter


@dataclass
class StepMetrics:
    start: float
    target: float
    rise_time: float  # s; nan if 90 % was never reached
    overshoot: float  # % of |target - start|, >= 0
    settling_time: float  # s; inf if not settled at the end
    steady_state_error: float  # rad
    jitter: float  # rad, peak to peak over the final window

    @property
    def size(self):
        return self.target - self.start

    @property
    def settled(self):
        return math.isfinite(self.settling_time)

    def as_dict(self):
        return asdict(self)


@dataclass
class Criteria:
    """What a good step looks like: the search's constraints and the pass/fail of a report."""

    max_overshoot: float = 5.0  # %
    max_jitter: float = 0.001  # rad peak to peak once settled (about 0.06 degrees)

    def failures(self, m):
        """Why ``m`` (a StepMetrics) is not good enough; empty when it is."""
        out = []
        if not m.settled:
            out.append('not settled within %g %%' % (BAND * 100))
        if m.overshoot > self.max_overshoot:
            out.append('overshoot %.1f %% > %g %%' % (m.overshoot, self.max_overshoot))
        if not m.jitter <= self.max_jitter:
            out.append('jitter %.2g rad > %g rad' % (m.jitter, self.max_jitter))
        return out

    def ok(self, m):
        return not self.failures(m)

    def steady(self, m):
        """Settled and still at the end (it does not shake), whatever the overshoot."""
        return m.settled and m.jitter <= self.max_jitter


def _crossing(times, values, i, level):
    """Time where the segment (i-1, i) crosses ``level`` (values[i-1] < level <= values[i])."""
    if i == 0:
        return times[0]
    v0, v1 = values[i - 1], values[i]
    if v1 == v0:
        return times[i]
    return times[i - 1] + (times[i] - times[i - 1]) * (level - v0) / (v1 - v0)


def step_metrics(
    times, positions, target, start=None, t_step=None, band=BAND, final_window=FINAL_WINDOW
):
    """StepMetrics of one step; see the module docstring for the definitions.

    ``start`` defaults to the first position, ``t_step`` to the first time.
    """
    times = [float(t) for t in times]
    positions = [float(x) for x in positions]
    if len(times) != len(positions) or len(times) < 2:
        raise ValueError('a step response needs at least two (time, position) samples')
    t_step = times[0] if t_step is None else float(t_step)
    start = positions[0] if start is None else float(start)
    target = float(target)
    size = target - start
    if not abs(size) > 1e-9:
        raise ValueError('step of size %g: nothing to measure' % size)
    sign = 1.0 if size > 0 else -1.0
    # progress: 0 at the start, 1 at the target, > 1 beyond it
    progress = [(x - start) / size for x in positions]

    rise_time = math.nan
    t10 = t90 = None
    for i, f in enumerate(progress):
        if t10 is None and f >= 0.1:
            t10 = _crossing(times, progress, i, 0.1)
        if f >= 0.9:
            t90 = _crossing(times, progress, i, 0.9)
            break
    if t10 is not None and t90 is not None:
        rise_time = t90 - t10

    overshoot = max(0.0, max(sign * (x - target) for x in positions) / abs(size) * 100.0)

    tol = band * abs(size)
    last_out = None
    for i in range(len(positions) - 1, -1, -1):
        if abs(positions[i] - target) > tol:
            last_out = i
            break
    if last_out is None:
        settling_time = 0.0
    elif last_out == len(positions) - 1:
        settling_time = math.inf
    else:
        # interpolate where the error comes back inside the band
        e0 = abs(positions[last_out] - target)
        e1 = abs(positions[last_out + 1] - target)
        t0, t1 = times[last_out], times[last_out + 1]
        t_in = t1 if e0 == e1 else t0 + (t1 - t0) * (e0 - tol) / (e0 - e1)
        settling_time = max(0.0, t_in - t_step)

    t_end = times[-1]
    tail = [x for t, x in zip(times, positions) if t >= t_end - final_window] or positions[-1:]
    steady_state_error = target - sum(tail) / len(tail)
    jitter = max(tail) - min(tail)
    return StepMetrics(
        start, target, rise_time, overshoot, settling_time, steady_state_error, jitter
    )


def worst(metrics):
    """One StepMetrics-like summary of several steps: the worst value of each figure."""
    metrics = list(metrics)
    if not metrics:
        raise ValueError('no steps')

    def nanmax(values):
        values = list(values)
        return math.nan if any(math.isnan(v) for v in values) else max(values)

    return StepMetrics(
        metrics[0].start,
        metrics[0].target,
        nanmax(m.rise_time for m in metrics),
        max(m.overshoot for m in metrics),
        max(m.settling_time for m in metrics),
        max((m.steady_state_error for m in metrics), key=abs),
        max(m.jitter for m in metrics),
    )
