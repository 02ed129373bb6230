"""``tune --search --ray``: the search's simulations on Ray give the local pool's gains."""

import multiprocessing
import time

from _arm1sim.tuning import cli
from _arm1sim.tuning.evaluator import RAY_LOCAL, Evaluator
from _arm1sim.tuning.inputs import Setup
from _arm1sim.tuning.search import GainSearch


def search(make, evaluator, tuned, seed):
    probe = make()
    try:
        gains = {j: dict(g) for j, g in probe.gains.items()}
        effort = {j: probe.hw.handles[j].limits.effort for j in probe.joints}
    finally:
        probe.close()
    setup = Setup(cli.parse_args(['--pose', 'none']))  # one start pose: a short protocol
    runs = []
    s = GainSearch(
        evaluator,
        tuned,
        gains,
        effort,
        setup.protocol,
        setup.criteria,
        generations=2,
        population=4,
        seed=seed,
    )
    try:
        found = s.run()
        runs.append(evaluator.runs)
    finally:
        evaluator.close()
    return found, s.set_value, runs


def test_ray_local_gives_the_local_pools_gains_for_the_same_seed():
    # Ray leaves its gRPC threads in the process that started it, and a pool forked after
    # them (this test's own, test_tuning_search's) can hang for good on a lock one of them
    # held at the fork (it did, once in a make test): Ray runs in a child of its own.
    child = multiprocessing.get_context('spawn').Process(target=compare_ray_with_the_pool)
    child.start()
    child.join(600)
    assert child.exitcode == 0, 'the comparison failed in its process (its output above)'


def compare_ray_with_the_pool():
    make = Setup(cli.parse_args([])).rig  # as tune's: arm1 and config/controllers.yaml
    pool = search(make, Evaluator(make, workers=2), ['joint2'], seed=3)
    t0 = time.monotonic()
    ray = Evaluator(make, workers=2, ray=RAY_LOCAL)
    assert len(ray.actors) == 2 and ray.workers == 2
    on_ray = search(make, ray, ['joint2'], seed=3)
    print('ray local: %.1f s' % (time.monotonic() - t0))
    assert on_ray == pool  # gains, the best set's value, runs made
    other_seed = search(make, Evaluator(make, workers=2), ['joint2'], seed=4)
    assert other_seed[0] != pool[0]  # the seed matters: the equality above is not a given


def test_the_cli_takes_a_ray_address_and_workers_follow_the_cluster():
    args = cli.parse_args(['--search', '--ray', 'head.example:6379'])
    assert (args.ray, args.workers) == ('head.example:6379', None)  # one per cluster CPU
    args = cli.parse_args(['--search', '--ray', 'local'])
    assert args.ray == 'local' and args.workers >= 1
    assert cli.parse_args(['--workers', '3']).workers == 3
    assert cli.parse_args([]).ray is None


def test_an_address_without_a_ray_head_is_said_at_once(capsys):
    import socket

    with socket.socket() as s:  # a port nobody listens on
        s.bind(('127.0.0.1', 0))
        port = s.getsockname()[1]
    t = time.monotonic()
    code = cli.main(['--search', '--generations', '1', '--ray', '127.0.0.1:%d' % port])
    assert code == 2 and time.monotonic() - t < 60
    err = capsys.readouterr().err
    assert 'no Ray head at 127.0.0.1:%d' % port in err and 'ray start --head' in err
