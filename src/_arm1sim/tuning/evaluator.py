"""Where the gain search's protocol runs happen: in this process, in a pool of processes, or on a
Ray cluster, one headless simulation (StepRig) per worker.

Every task is a whole protocol run from a fresh start, so where it runs does not change its
outcome.
"""

from __future__ import annotations

import math
import multiprocessing
from typing import TYPE_CHECKING, Any, Callable, Dict, List, Optional, Tuple

from .metrics import StepMetrics

if TYPE_CHECKING:
    from multiprocessing.pool import Pool

    from .steps import Protocol, StepRig

Gains = Dict[str, Dict[str, Any]]  # joint -> p, i, d, i_clamp_max, i_clamp_min, antiwindup
Task = Tuple[str, Gains, 'Protocol']  # the joint stepped, every joint's gains, the protocol
Outcome = Tuple[List[StepMetrics], float, float]  # step metrics, others' wobble and jitter

_RIG: Optional[StepRig] = None  # this process's rig (one per pool worker)


def _init_worker(rig_factory: Callable[[], StepRig]) -> None:
    global _RIG
    _RIG = rig_factory()


def _evaluate(task: Task) -> Outcome:
    joint, all_gains, protocol = task
    rig = _RIG
    assert rig is not None, 'the worker has no rig (_init_worker not run)'
    rig.gains = {j: dict(g) for j, g in all_gains.items()}
    run = rig.run(joint, protocol)
    return run.metrics, run.others_wobble, run.others_jitter


class EvaluatorError(RuntimeError):
    """The simulations cannot be run where asked (no Ray, no cluster at the address)."""


def _reachable(address: str, timeout: float = 5.0) -> None:
    """Raise EvaluatorError unless a TCP connection to a HOST:PORT ``address`` opens."""
    import socket

    host, sep, port = address.rpartition(':')
    if not sep or not port.isdigit():
        return  # 'auto' and other forms: Ray's own to resolve
    try:
        socket.create_connection((host, int(port)), timeout).close()
    except OSError as exc:
        raise EvaluatorError(
            'no Ray head at %s (%s): start one there with `ray start --head --port %s`'
            % (address, exc, port)
        ) from None


class RigActor:
    """A Ray actor: one headless simulation on some node of the cluster, running tasks."""

    def __init__(self, rig_factory: Callable[[], StepRig]) -> None:
        _init_worker(rig_factory)

    def evaluate(self, tasks: List[Task]) -> List[Outcome]:
        return [_evaluate(t) for t in tasks]


RAY_LOCAL = 'local'  # --ray local: start a Ray of this machine's own
RAY_QUEUE = 2  # chunks of tasks out per actor at once


class Evaluator:
    """Runs protocol runs, in this process (workers <= 1), in a pool of processes, or on a
    Ray cluster (``ray``: a head's address, or RAY_LOCAL) with one actor per worker.

    Every task is a whole protocol run from a fresh start, so where it runs does not
    change its outcome: the same seed gives the same gains on any of them.
    """

    def __init__(
        self, rig_factory: Callable[[], StepRig], workers: int = 1, ray: Optional[str] = None
    ) -> None:
        self.pool: Optional[Pool] = None
        self.actors: List[Any] = []
        self._ray: Any = None
        self.runs = 0
        if ray:
            self._start_ray(rig_factory, workers, ray)
            return
        self.workers = max(1, int(workers))
        if self.workers > 1:
            ctx = multiprocessing.get_context('fork')
            self.pool = ctx.Pool(self.workers, _init_worker, (rig_factory,))
        else:
            _init_worker(rig_factory)

    def _start_ray(self, rig_factory: Callable[[], StepRig], workers: int, address: str) -> None:
        """Connect to (or start) Ray; ``workers`` <= 0 means one actor per CPU of the cluster."""
        import logging

        try:
            import ray
        except ImportError as exc:
            raise EvaluatorError('--ray needs Ray (requirements.txt pins it): %s' % exc) from None
        if address != RAY_LOCAL:
            _reachable(address)  # ray.init would retry an unreachable head for minutes
        self._ray = ray
        self._own_ray = address == RAY_LOCAL
        quiet = dict(include_dashboard=False, logging_level=logging.WARNING, log_to_driver=False)
        if self._own_ray:
            cpus = workers if workers > 0 else None
            ray.init(num_cpus=cpus, **quiet)  # type: ignore[arg-type]
        else:
            try:
                ray.init(address=address, **quiet)  # type: ignore[arg-type]
            except (ConnectionError, RuntimeError) as exc:
                raise EvaluatorError('no Ray cluster at %s: %s' % (address, exc)) from None
        cpus = int(ray.cluster_resources().get('CPU', 1))
        self.workers = workers if workers > 0 else max(1, cpus)
        actor = ray.remote(num_cpus=1)(RigActor)
        self.actors = [actor.remote(rig_factory) for _ in range(self.workers)]

    def _ray_map(self, tasks: List[Task]) -> List[Outcome]:
        """Tasks in chunks (a run takes ~0.1 s: one remote call each would cost Ray about
        as much again), each actor kept RAY_QUEUE chunks deep so it never waits for the
        next, the next chunk to whichever finishes first; outcomes in the order of ``tasks``."""
        ray = self._ray
        # twice as many chunks as the queues hold: a slow actor does not hold the batch up
        size = max(1, math.ceil(len(tasks) / (RAY_QUEUE * 2 * len(self.actors))))
        chunks = iter(range(0, len(tasks), size))
        out: List[Any] = [None] * len(tasks)
        pending: Dict[Any, Tuple[int, Any]] = {}  # object ref -> (first task's index, actor)

        def submit(actor: Any) -> None:
            n = next(chunks, None)
            if n is not None:
                pending[actor.evaluate.remote(tasks[n : n + size])] = (n, actor)

        for _ in range(RAY_QUEUE):
            for a in self.actors:
                submit(a)
        while pending:
            [ref], _ = ray.wait(list(pending), num_returns=1)
            n, a = pending.pop(ref)
            try:
                results = ray.get(ref)
            except ray.exceptions.RayError as exc:  # a node lost, an actor killed
                raise EvaluatorError('a Ray worker failed: %s' % exc) from None
            out[n : n + len(results)] = results
            submit(a)
        return out

    def map(self, tasks: List[Task]) -> List[Outcome]:
        """Outcomes in the order of ``tasks``."""
        self.runs += len(tasks)
        if self.actors:
            return self._ray_map(tasks)
        if self.pool is None:
            return [_evaluate(t) for t in tasks]
        return self.pool.map(_evaluate, tasks, chunksize=1)

    def close(self) -> None:
        if self.pool is not None:
            self.pool.terminate()
            self.pool.join()
            self.pool = None
        if self._ray is not None:
            for a in self.actors:
                self._ray.kill(a)
            self.actors = []
            self._ray.shutdown()  # a local Ray ends; a cluster's goes on without us
            self._ray = None
