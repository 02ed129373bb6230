"""Gain search: per joint, the gains whose steps settle fastest with overshoot <= 5 % and
no jitter (metrics.Criteria), found by running the step protocol (steps.py).

The joints of an arm push on each other (arm1's joints 2-4 are strongly coupled),
so the joints are tuned in turn, each with the others at their latest gains
(Gauss-Seidel), for ``rounds`` rounds. For one joint, candidates are the gains in
force, a seeded random sample of the search space (log-uniform p, d and i) and
then random steps around the best so far, shrinking. Every candidate is one run of
the protocol (two steps); candidates are spread over ``workers`` processes, each
with its own headless simulation. The random generator is seeded: the same inputs
give the same gains.

A candidate's score is its worse step's settling time when it meets the criteria,
else the hold time plus penalties for how far it misses them, so that the search is
led towards feasible gains even when it starts far from them.
"""
import math
import multiprocessing
import random
import time
from dataclasses import dataclass, field

from .metrics import Criteria, worst


@dataclass
class SearchSpace:
    p: tuple = (0.1, 100.0)
    d: tuple = (1e-5, 0.05)
    i: tuple = (0.1, 300.0)  # a quarter of the samples use i = 0
    i_clamp: float = 0.05  # fraction of the joint's effort limit (holds arm1 against gravity)
    antiwindup: bool = True  # clamp the integral itself, so it does not wind up during a step


@dataclass
class Candidate:
    joint: str
    gains: dict
    feasible: bool = False
    score: float = math.inf
    summary: object = None  # worst-of-steps StepMetrics
    metrics: list = field(default_factory=list)
    others_wobble: float = 0.0
    failures: list = field(default_factory=list)


def score(metrics, criteria, hold, others_jitter=0.0):
    """(feasible, score, worst StepMetrics, failures) of a run's step metrics; the other
    joints must be as still as the stepped one at the end of each hold."""
    w = worst(metrics)
    fails = criteria.failures(w)
    if others_jitter > criteria.max_jitter:
        fails.append('other joints jitter %.2g rad' % others_jitter)
        w.jitter = max(w.jitter, others_jitter)
    if not fails:
        return True, w.settling_time, w, fails
    s = hold + (w.settling_time if math.isfinite(w.settling_time) else hold)
    s += max(0.0, w.overshoot - criteria.max_overshoot) / max(criteria.max_overshoot, 1e-9)
    if w.jitter > criteria.max_jitter:
        s += 1.0 + math.log10(w.jitter / criteria.max_jitter)
    if not math.isfinite(w.settling_time):
        s += 1.0 + 10.0 * abs(w.steady_state_error) / max(abs(w.size), 1e-9)
    return False, s, w, fails


# --------------------------------------------------------------------------- evaluation
_RIG = None


def _init_worker(rig_factory):
    global _RIG
    _RIG = rig_factory()


def _evaluate(task):
    joint, all_gains, protocol = task
    rig = _RIG
    rig.gains = {j: dict(g) for j, g in all_gains.items()}
    run = rig.run(joint, protocol)
    return run.metrics, run.others_wobble, run.others_jitter


class Evaluator:
    """Runs protocol runs, in this process (workers <= 1) or in a pool of processes."""

    def __init__(self, rig_factory, workers=1):
        self.workers = max(1, int(workers))
        self.pool = None
        if self.workers > 1:
            ctx = multiprocessing.get_context('fork')
            self.pool = ctx.Pool(self.workers, _init_worker, (rig_factory,))
        else:
            _init_worker(rig_factory)
        self.runs = 0

    def map(self, tasks):
        self.runs += len(tasks)
        if self.pool is None:
            return [_evaluate(t) for t in tasks]
        return self.pool.map(_evaluate, tasks, chunksize=1)

    def close(self):
        if self.pool is not None:
            self.pool.terminate()
            self.pool.join()
            self.pool = None


class GainSearch:
    def __init__(self, evaluator, joints, initial_gains, effort_limits, protocol,
                 criteria=None, space=None, rounds=2, runs_per_joint=60, seed=0, progress=None):
        self.evaluator = evaluator
        self.joints = list(joints)
        self.gains = {j: dict(g) for j, g in initial_gains.items()}
        self.effort_limits = effort_limits
        self.protocol = protocol
        self.criteria = criteria or Criteria()
        self.space = space or SearchSpace()
        self.rounds = rounds
        self.runs_per_joint = runs_per_joint
        self.rng = random.Random(seed)
        self.progress = progress or (lambda done, total, text: None)
        self.best = {}  # joint -> Candidate
        self.total = rounds * len(self.joints) * runs_per_joint
        self.done = 0

    # -- candidates ---------------------------------------------------------------
    def _base(self, joint):
        g = dict(self.gains[joint])
        limit = self.effort_limits.get(joint) or 1.0
        clamp = float('%.4g' % (self.space.i_clamp * limit))
        g.update(i_clamp_max=clamp, i_clamp_min=-clamp, antiwindup=self.space.antiwindup)
        return g

    def _random(self, joint):
        s, rng = self.space, self.rng
        g = self._base(joint)
        g['p'] = _log_uniform(rng, *s.p)
        g['d'] = _log_uniform(rng, *s.d)
        g['i'] = 0.0 if rng.random() < 0.25 else _log_uniform(rng, *s.i)
        return _rounded(g)

    def _near(self, joint, around, spread):
        s, rng = self.space, self.rng
        g = dict(around)
        g['p'] = _clip(around['p'] * 10 ** rng.gauss(0, spread), *s.p)
        g['d'] = _clip(around['d'] * 10 ** rng.gauss(0, spread), *s.d)
        if around['i'] > 0:
            g['i'] = _clip(around['i'] * 10 ** rng.gauss(0, spread), *s.i)
        elif rng.random() < 0.3:
            g['i'] = _log_uniform(rng, *s.i)
        return _rounded(g)

    # -- running ------------------------------------------------------------------
    def _evaluate(self, joint, candidates, label):
        tasks = []
        for g in candidates:
            all_gains = {j: dict(g) for j, g in self.gains.items()}
            all_gains[joint] = g
            tasks.append((joint, all_gains, self.protocol))
        out = []
        batch = max(1, self.evaluator.workers) * 2
        for k in range(0, len(tasks), batch):
            results = self.evaluator.map(tasks[k:k + batch])
            for g, (metrics, wobble, jitter) in zip(candidates[k:k + batch], results):
                feasible, s, w, fails = score(metrics, self.criteria, self.protocol.hold, jitter)
                out.append(Candidate(joint, g, feasible, s, w, metrics, wobble, fails))
            self.done += len(results)
            best = min(out + ([self.best[joint]] if joint in self.best else []),
                       key=lambda c: c.score)
            self.progress(self.done, self.total, '%s %s  best %s' % (joint, label, describe(best)))
        return out

    def tune_joint(self, joint, round_index):
        n = self.runs_per_joint
        label = 'round %d/%d' % (round_index + 1, self.rounds)
        incumbent = dict(self.gains[joint])
        n_global = n // 3 if round_index == 0 else n // 6
        first = [incumbent] + [self._random(joint) for _ in range(n_global - 1)]
        pool = self._evaluate(joint, first, label)
        best = min(pool, key=lambda c: c.score)
        spread, left = 0.4, n - len(first)
        while left > 0:
            k = min(left, max(2, self.evaluator.workers) * 2)
            batch = [self._near(joint, best.gains, spread) for _ in range(k)]
            results = self._evaluate(joint, batch, label)
            left -= k
            top = min(results, key=lambda c: c.score)
            if top.score < best.score:
                best = top
            else:
                spread = max(0.05, spread * 0.7)
        return best

    def set_score(self, gains):
        """Sum over the joints of their scores with ``gains`` for every joint."""
        tasks = [(j, {k: dict(g) for k, g in gains.items()}, self.protocol) for j in self.joints]
        results = self.evaluator.map(tasks)
        self.done += len(tasks)
        self._last_set = {j: score(m, self.criteria, self.protocol.hold, jit)
                          for j, (m, _, jit) in zip(self.joints, results)}
        return sum(v[1] for v in self._last_set.values())

    def run(self):
        """Gauss-Seidel over the joints; a joint's new gains are kept only if the whole set
        scores better with them (the joints are coupled), so the result is never worse than
        the gains it started from."""
        self.total += (1 + self.rounds * len(self.joints)) * len(self.joints)
        current = self.set_score(self.gains)
        self.set_results = self._last_set  # joint -> (feasible, score, worst, failures)
        for r in range(self.rounds):
            for joint in self.joints:
                best = self.tune_joint(joint, r)
                if best.gains == self.gains[joint]:
                    continue
                trial = dict(self.gains)
                trial[joint] = dict(best.gains)
                value = self.set_score(trial)
                if value < current:
                    current = value
                    self.set_results = self._last_set
                    self.gains = trial
                    self.best[joint] = best
        self.set_value = current
        return self.gains


def describe(c):
    if c.summary is None:
        return '-'
    w = c.summary
    return '%s settle %s, overshoot %.1f%%, jitter %.2g rad' % (
        'ok' if c.feasible else 'NOT ok', fmt_time(w.settling_time), w.overshoot, w.jitter)


def fmt_time(t):
    return '%.3f s' % t if math.isfinite(t) else 'never'


def _rounded(g):
    """Gains as the yaml snippet prints them (4 significant digits): what is evaluated is
    exactly what is shipped."""
    return {k: (v if isinstance(v, bool) else float('%.4g' % v)) for k, v in g.items()}


def _log_uniform(rng, lo, hi):
    return 10 ** rng.uniform(math.log10(lo), math.log10(hi))


def _clip(v, lo, hi):
    return min(max(v, lo), hi)


class ProgressBar:
    """``[#####-----]  45%  12.3 s  text`` on one line of a terminal (or plain lines)."""

    def __init__(self, stream, width=30):
        self.stream, self.width = stream, width
        self.start = time.monotonic()
        self.tty = hasattr(stream, 'isatty') and stream.isatty()
        self._last = 0.0

    def __call__(self, done, total, text):
        now = time.monotonic()
        if not self.tty and now - self._last < 2.0 and done < total:
            return
        self._last = now
        frac = min(1.0, done / total) if total else 1.0
        bar = '#' * int(frac * self.width) + '-' * (self.width - int(frac * self.width))
        line = '[%s] %3d%%  %5.1f s  %s' % (bar, frac * 100, now - self.start, text)
        if self.tty:
            self.stream.write('\r\x1b[K' + line[:160])
        else:
            self.stream.write(line + '\n')
        self.stream.flush()

    def finish(self):
        if self.tty:
            self.stream.write('\n')
            self.stream.flush()
