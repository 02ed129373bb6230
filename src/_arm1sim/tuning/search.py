"""Gain search: the gains of all the tuned joints at once, chosen so that every joint's steps
settle fastest with overshoot <= 5 % and no jitter (metrics.Criteria), found by running the
step protocol (steps.py).

arm1's joints push on each other too hard to be tuned one at a time: the inertia
joint3 sees is 6e-6 kg m^2 with joints 2 and 4 free and 1e-4 with them held, so
joint3's best gains depend on joint2's stiffness and joint4's damping, and a
joint tuned alone can set a neighbour shaking. So one candidate is a whole gain
set (p, d, i, i_clamp of every tuned joint) and its value is the sum of the
scores of every tuned joint's protocol run from every start pose of the
protocol (in which the other joints must stay still too): gains that suit one
pose alone can shake at another.

The search is a cross-entropy method in log-gain space: each generation samples
``population`` gain sets from a normal distribution (mean: the gains in force at
first), keeps the ``elite`` best and moves the mean and spread towards them. A set
is run from the protocol's first start pose, and from the others only if it is
steady there or among the best two of its generation (racing): a set that shakes at one
pose is not worth trying at more, and this about halves the cost. The
random generator is seeded and candidates are run by an ``Evaluator`` (evaluator.py: in
``workers`` processes, or Ray actors on many machines with ``--ray``, each with its own
headless simulation): the same inputs give the same gains. The
gains in force are the first candidate, so the result is never worse than them.

A run's score is its worse step's settling time when it meets the
criteria, else the hold time plus penalties for how far it misses them, so that the
search is led towards feasible gains even when it starts far from them.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass, field
from typing import (
    TYPE_CHECKING,
    Any,
    Callable,
    Dict,
    Iterable,
    List,
    Mapping,
    Optional,
    Sequence,
    Tuple,
)

from .evaluator import Evaluator, Gains
from .metrics import Criteria, StepMetrics, worst

if TYPE_CHECKING:
    from .steps import Protocol

Score = Tuple[bool, float, StepMetrics, List[str]]  # feasible, score, worst step, failures
Progress = Callable[[int, int, str], None]  # (done, total, text)


@dataclass
class SearchSpace:
    p: Tuple[float, float] = (0.03, 100.0)
    d: Tuple[float, float] = (3e-5, 0.1)
    i: Tuple[float, float] = (0.1, 1000.0)  # the bottom decade of the sampled range means i = 0
    i_clamp: Tuple[float, float] = (0.01, 0.3)  # fraction of the joint's effort limit
    antiwindup: bool = True  # clamp the integral itself, so it does not wind up during a step
    spread: float = 0.25  # first generation's standard deviation, a fraction of each range

    def bounds(self) -> List[Tuple[float, float]]:
        """(low, high) of the four log10 coordinates of one joint: p, d, i, i_clamp."""

        def log(r: Tuple[float, float]) -> Tuple[float, float]:
            return math.log10(r[0]), math.log10(r[1])

        return [
            log(self.p),
            log(self.d),
            (math.log10(self.i[0]) - 1.0, math.log10(self.i[1])),
            log(self.i_clamp),
        ]


@dataclass
class Candidate:
    gains: Gains  # every joint of the robot
    value: float = math.inf  # sum of the scores of the tuned joints' runs
    # (joint, start pose index) -> its run's Score
    results: Dict[Tuple[str, int], Score] = field(default_factory=dict)
    complete: bool = True  # run from every start pose (else value is an estimate)

    @property
    def feasible(self) -> bool:
        return all(r[0] for r in self.results.values())


UNSTEADY = 20.0  # score penalty for not settling or jitter: shaking is worse than overshoot


def score(
    metrics: Sequence[StepMetrics], criteria: Criteria, hold: float, others_jitter: float = 0.0
) -> Score:
    """(feasible, score, worst StepMetrics, failures) of a run's step metrics; the other
    joints must be as still as the stepped one at the end of each hold.

    Lower is better. Feasible: the worse step's settling time (< hold). Otherwise
    hold + settling time + overshoot beyond the limit in units of the limit, and
    UNSTEADY more when the joint does not settle or jitters, so that gains which
    do not shake but overshoot rank before gains which shake."""
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
        s += UNSTEADY + math.log10(w.jitter / criteria.max_jitter)
    if not math.isfinite(w.settling_time):
        s += UNSTEADY + 10.0 * abs(w.steady_state_error) / max(abs(w.size), 1e-9)
    return False, s, w, fails


class GainSearch:
    def __init__(
        self,
        evaluator: Optional[Evaluator],
        joints: Sequence[str],
        initial_gains: Mapping[str, Mapping[str, Any]],
        effort_limits: Mapping[str, Optional[float]],
        protocol: Optional[Protocol],
        criteria: Optional[Criteria] = None,
        space: Optional[SearchSpace] = None,
        generations: int = 14,
        population: int = 16,
        elite: int = 6,
        seed: int = 0,
        progress: Optional[Progress] = None,
    ) -> None:
        self.evaluator = evaluator
        self.joints = list(joints)  # the tuned joints: their gains change, their runs are scored
        self.initial = {j: dict(g) for j, g in initial_gains.items()}
        self.effort_limits = effort_limits
        self.protocol = protocol
        self.variants = protocol.variants() if protocol is not None else []
        self.criteria = criteria or Criteria()
        self.space = space or SearchSpace()
        self.generations = generations
        self.population = population
        self.elite = max(2, min(elite, population))
        self.rng = random.Random(seed)
        self.progress: Progress = progress or (lambda done, total, text: None)
        self.total = generations * population
        self.done = 0
        self.best: Optional[Candidate] = None

    # -- coordinates: per tuned joint log10 p, d, i, i_clamp/effort --------------------
    def _limit(self, joint: str) -> float:
        return self.effort_limits.get(joint) or 1.0

    def _encode(self, joint: str, g: Mapping[str, Any]) -> List[float]:
        (p0, p1), (d0, d1), (i0, i1), (c0, c1) = self.space.bounds()
        clamp = max(abs(g.get('i_clamp_max', 0.0)), abs(g.get('i_clamp_min', 0.0)))
        return [
            _clip(math.log10(g['p']) if g['p'] > 0 else p0, p0, p1),
            _clip(math.log10(g['d']) if g['d'] > 0 else d0, d0, d1),
            _clip(math.log10(g['i']) if g['i'] > 0 else i0, i0, i1),
            _clip(
                math.log10(clamp / self._limit(joint)) if clamp > 0 else math.log10(0.05), c0, c1
            ),
        ]

    def _decode(self, x: Sequence[float]) -> Gains:
        i_on = math.log10(self.space.i[0])
        bounds = self.space.bounds()
        gains = {j: dict(g) for j, g in self.initial.items()}
        for k, joint in enumerate(self.joints):
            lp, ld, li, lc = (_clip(v, lo, hi) for v, (lo, hi) in zip(x[4 * k : 4 * k + 4], bounds))
            clamp = 10**lc * self._limit(joint)
            g = gains[joint]
            g.update(
                p=10**lp,
                d=10**ld,
                i=10**li if li >= i_on else 0.0,
                i_clamp_max=clamp,
                i_clamp_min=-clamp,
                antiwindup=self.space.antiwindup,
            )
            gains[joint] = _rounded(g)
        return gains

    # -- running ------------------------------------------------------------------
    def evaluate(
        self, gain_sets: List[Gains], label: str = '', always: Iterable[int] = ()
    ) -> List[Candidate]:
        """Candidates for whole gain sets: every tuned joint's run from the first start pose,
        and from the other poses only for the sets steady at the first one, the two best
        and those whose index is in ``always`` (racing: a set that shakes at one pose need
        not be tried at more). The others' values are estimates (the first pose's sum
        once per pose): they steer the search but are never chosen as the best."""
        first = self._scores(gain_sets, [0], label)
        cands = [
            Candidate(g, sum(r[1] for r in res.values()), res) for g, res in zip(gain_sets, first)
        ]
        if len(self.variants) < 2:
            return cands
        ranked = sorted(range(len(cands)), key=lambda n: cands[n].value)
        more = sorted(
            set(ranked[:2]) | set(always) | {n for n, c in enumerate(cands) if self.steady(c)}
        )
        rest = self._scores([gain_sets[n] for n in more], range(1, len(self.variants)), None)
        for n, res in zip(more, rest):
            cands[n].results.update(res)
            cands[n].value = sum(r[1] for r in cands[n].results.values())
        for n, c in enumerate(cands):
            if n not in more:
                c.value *= len(self.variants)
                c.complete = False
        return cands

    def steady(self, c: Candidate) -> bool:
        """Every run of a Candidate settles without jitter (its own or the other joints',
        which score folds into the worst step's), however far it overshoots."""
        return all(self.criteria.steady(r[2]) for r in c.results.values())

    def _scores(
        self, gain_sets: List[Gains], poses: Iterable[int], label: Optional[str]
    ) -> List[Dict[Tuple[str, int], Score]]:
        """Per gain set, {(joint, pose index): score tuple} of the tuned joints' runs."""
        evaluator, protocol = self.evaluator, self.protocol
        assert evaluator is not None and protocol is not None, 'no evaluator or protocol'
        keys = [(j, k) for j in self.joints for k in poses]
        out = []
        step = max(1, evaluator.workers) * 2
        for n in range(0, len(gain_sets), step):
            sets = gain_sets[n : n + step]
            results = evaluator.map([(j, g, self.variants[k]) for g in sets for j, k in keys])
            for m in range(len(sets)):
                runs = results[m * len(keys) : (m + 1) * len(keys)]
                out.append(
                    {
                        key: score(metrics, self.criteria, protocol.hold, jitter)
                        for key, (metrics, _, jitter) in zip(keys, runs)
                    }
                )
            if label is not None:
                self.done += len(sets)
                self.progress(self.done, self.total, label)
        return out

    def run(self) -> Gains:
        """The best gain set found; the gains in force are the first candidate."""
        bounds = self.space.bounds() * len(self.joints)
        mean = []
        for j in self.joints:
            mean += self._encode(j, self.initial[j])
        spread = [(hi - lo) * self.space.spread for lo, hi in bounds]
        incumbent = {j: dict(g) for j, g in self.initial.items()}
        for g in range(self.generations):
            xs = [
                [
                    _clip(m + s * self.rng.gauss(0, 1), lo, hi)
                    for m, s, (lo, hi) in zip(mean, spread, bounds)
                ]
                for _ in range(self.population - (1 if g == 0 else 0))
            ]
            sets = ([incumbent] if g == 0 else []) + [self._decode(x) for x in xs]
            if g == 0:
                xs = [list(mean)] + xs
            label = 'generation %d/%d  best %s' % (
                g + 1,
                self.generations,
                self.describe(self.best),
            )
            cands = self.evaluate(sets, label, always=[0] if g == 0 else [])
            order = sorted(range(len(cands)), key=lambda n: cands[n].value)
            complete = [c for c in cands if c.complete]
            top = min(complete, key=lambda c: c.value) if complete else None
            if top is not None and (self.best is None or top.value < self.best.value):
                self.best = top
            elite = [xs[n] for n in order[: self.elite]]
            for k in range(len(mean)):
                values = [e[k] for e in elite]
                m = sum(values) / len(values)
                sd = math.sqrt(sum((v - m) ** 2 for v in values) / len(values))
                mean[k] = 0.7 * m + 0.3 * mean[k]
                spread[k] = max(0.03, 0.7 * sd + 0.3 * spread[k])
        self.progress(self.total, self.total, 'done  best %s' % self.describe(self.best))
        assert self.best is not None  # generation 0 runs the gains in force from every pose
        return self.best.gains

    def describe(self, c: Optional[Candidate]) -> str:
        """One line on a Candidate: per joint ok, or its worst overshoot and whether it is
        unsteady (does not settle or jitters)."""
        if c is None:
            return '-'
        joints: Dict[str, List[Score]] = {}
        for (joint, _), r in c.results.items():
            joints.setdefault(joint, []).append(r)

        def one(rs: List[Score]) -> str:
            if all(r[0] for r in rs):
                return 'ok'
            unsteady = not all(self.criteria.steady(r[2]) for r in rs)
            return '%.0f%%%s' % (max(r[2].overshoot for r in rs), ' unsteady' if unsteady else '')

        return ', '.join('%s %s' % (j, one(rs)) for j, rs in joints.items())

    @property
    def set_results(self) -> Dict[Tuple[str, int], Score]:
        assert self.best is not None, 'run() first'
        return self.best.results

    @property
    def set_value(self) -> float:
        assert self.best is not None, 'run() first'
        return self.best.value


def fmt_time(t: float) -> str:
    return '%.3f s' % t if math.isfinite(t) else 'never'


def _rounded(g: Mapping[str, Any]) -> Dict[str, Any]:
    """Gains as the yaml snippet prints them (4 significant digits): what is evaluated is
    exactly what is shipped."""
    return {k: (v if isinstance(v, bool) else float('%.4g' % v)) for k, v in g.items()}


def _clip(v: float, lo: float, hi: float) -> float:
    return min(max(v, lo), hi)
