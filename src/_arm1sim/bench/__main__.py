"""``make bench``: measure the stand-in next to bare pybullet, in one run, on this machine.

Writes bench/results.json, the table in BENCHMARKS.md and bench/bench.png.
``--quick`` runs each measurement once and briefly (the smoke test in ``make test``).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
from typing import Any, Dict, List, Optional, Tuple

from tqdm import tqdm

from ..paths import repo_root
from ..session.launcher import RosSession
from .plot import write_plot
from .probes import machine
from .report import write_markdown

# (key, worker kind, worker args, runs, quick args, quick runs)
PLAN = [
    ('bare', 'bare', ['--seconds', '5'], 3, ['--seconds', '1.5'], 1),
    (
        'standin_1',
        'standin',
        ['--seconds', '5', '--arms', '1'],
        3,
        ['--seconds', '1.5', '--arms', '1'],
        1,
    ),
    ('standin_2', 'standin', ['--seconds', '4', '--arms', '2'], 3, None, 0),
    ('standin_4', 'standin', ['--seconds', '4', '--arms', '4'], 3, None, 0),
    ('standin_8', 'standin', ['--seconds', '4', '--arms', '8'], 3, None, 0),
    ('standin_16', 'standin', ['--seconds', '4', '--arms', '16'], 3, None, 0),
    ('standin_camera', 'standin', ['--seconds', '6', '--arms', '1', '--camera'], 3, None, 0),
    (
        'standin_model_states',
        'standin',
        ['--seconds', '5', '--arms', '1', '--model-states'],
        3,
        ['--seconds', '1.5', '--arms', '1', '--model-states'],
        1,
    ),
    (
        'standin_trajectory',
        'standin',
        ['--seconds', '5', '--arms', '1', '--trajectory'],
        3,
        ['--seconds', '1.5', '--arms', '1', '--trajectory'],
        1,
    ),
    ('render', 'render', ['--count', '30'], 3, ['--count', '2'], 1),
    ('laser', 'laser', ['--count', '300'], 3, ['--count', '10'], 1),
    ('depth_camera', 'depth', ['--count', '60'], 3, ['--count', '3'], 1),
    ('concave_mesh', 'concave_mesh', ['--count', '2000'], 3, ['--count', '50'], 1),
    ('mesh_cache_fill', 'mesh_cache_fill', ['--triangles', '20000'], 3, ['--triangles', '2000'], 1),
    ('profile', 'standin', ['--seconds', '4', '--arms', '1', '--profile'], 1, None, 0),
    ('latency', 'latency', ['--commands', '1000'], 3, ['--commands', '100'], 1),
    ('startup', 'startup', [], 5, [], 1),
    ('seed_goal', 'seed_goal', ['--seconds', '20'], 3, ['--seconds', '3'], 1),
    ('realtime', 'realtime', ['--seconds', '60'], 3, ['--seconds', '4'], 1),
    ('idle_world', 'idle_world', ['--seconds', '20'], 3, None, 0),
    ('web_view', 'web_view', ['--seconds', '20'], 3, None, 0),
    ('big_goal', 'big_goal', ['--count', '100000'], 3, None, 0),
    ('big_description', 'big_description', [], 3, None, 0),
    ('moveit_planning', 'moveit_planning', ['--count', '20'], 3, None, 0),
    ('moveit_idle', 'moveit_idle', ['--seconds', '20'], 3, None, 0),
]
SCALING_ARMS = (2, 4, 8, 16)
NEEDS_MASTER = {'standin', 'latency'}  # they run the world in-process against a shared master


def run_worker(kind: str, args: List[str], env: Dict[str, str]) -> Dict[str, Any]:
    proc = subprocess.run(
        [sys.executable, '-m', '_arm1sim.bench.workers', kind] + args,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        timeout=600,
    )
    lines = [ln for ln in proc.stdout.splitlines() if ln.startswith('{')]
    if proc.returncode != 0 or not lines:
        raise RuntimeError(
            'bench worker %s %s failed (exit %d):\n%s'
            % (kind, ' '.join(args), proc.returncode, proc.stderr[-3000:])
        )
    return json.loads(lines[-1])


def start_master(env: Dict[str, str]) -> RosSession:
    session = RosSession()
    env['ROS_MASTER_URI'] = session.env['ROS_MASTER_URI']
    session.start('rosmaster', '--core', '-p', session.env['ROS_MASTER_URI'].rsplit(':', 1)[1])
    if not session.wait_for_master():
        raise RuntimeError('rosmaster did not start')
    return session


def summarise(samples: List[Dict[str, Any]]) -> Dict[str, Dict[str, float]]:
    """Median and spread (min, max) of every numeric field over the runs."""
    out = {}
    for key in samples[0]:
        values = [s[key] for s in samples if isinstance(s.get(key), (int, float))]
        if values and not isinstance(samples[0][key], bool):
            out[key] = {
                'median': statistics.median(values),
                'min': min(values),
                'max': max(values),
                'runs': len(values),
            }
    return out


Plan = List[Tuple[str, str, List[str], int]]  # (key, worker kind, worker args, runs)
Raw = Dict[str, List[Dict[str, Any]]]  # key -> each run's result


def plan_for(quick: bool) -> Plan:
    return [
        (key, kind, (qargs if quick else full) or [], qruns if quick else runs)
        for key, kind, full, runs, qargs, qruns in PLAN
        if not (quick and not qruns)
    ]


def run_plan(plan: Plan) -> Raw:
    """Every run of the plan, each worker in a process of its own, against one master."""
    env = dict(os.environ)
    master = start_master(env)
    raw: Raw = {}
    try:
        with tqdm(
            total=sum(runs for *_, runs in plan), unit='run', file=sys.stdout, dynamic_ncols=True
        ) as bar:
            for key, kind, wargs, runs in plan:
                for k in range(runs):
                    bar.set_description('%s run %d/%d' % (key, k + 1, runs))
                    raw.setdefault(key, []).append(run_worker(kind, wargs, env))
                    bar.update()
            bar.set_description('done')
    finally:
        master.stop()
    return raw


def figures(raw: Raw) -> Dict[str, Dict[str, Any]]:
    """Each key's summary, and the figures derived from several: speed ratio, camera cost."""
    fig: Dict[str, Dict[str, Any]] = {key: summarise(samples) for key, samples in raw.items()}
    one = fig['standin_1']['steps_per_s']['median']
    fig['speed_ratio'] = {'median': one / fig['bare']['steps_per_s']['median']}
    cpu = [fig[k].get('cpu_us_per_step', {}).get('median') for k in ('bare', 'standin_1')]
    if all(cpu):  # the same ratio in CPU time per step: what a loaded machine leaves alone
        fig['speed_ratio_cpu'] = {'median': cpu[0] / cpu[1]}
    for n in SCALING_ARMS:  # N arms' steps in a second (each arm steps) over one arm's
        if 'standin_%d' % n in fig:
            many = fig['standin_%d' % n]['steps_per_s']['median']
            fig['scaling_%d' % n] = {'median': n * many / one}
    if 'standin_model_states' in fig:  # gathering the states before each step, at top speed
        states = fig['standin_model_states']['steps_per_s']['median']
        fig['model_states_us'] = {'median': (1e6 / states - 1e6 / one)}
    if 'standin_camera' in fig:  # wall time a 30 Hz frame adds to each simulated second
        cam = fig['standin_camera']['steps_per_s']['median']
        fig['camera_frame_ms'] = {'median': (1000.0 / cam - 1000.0 / one) / 30 * 1000}
    return fig


def write_results(results: Dict[str, Any], out: str) -> str:
    """bench/results.json, BENCHMARKS.md and bench/bench.png under ``out``; returns the table."""
    os.makedirs(os.path.join(out, 'bench'), exist_ok=True)
    with open(os.path.join(out, 'bench', 'results.json'), 'w') as f:
        json.dump(results, f, indent=1, sort_keys=True)
    table = write_markdown(results, os.path.join(out, 'BENCHMARKS.md'))
    write_plot(results, os.path.join(out, 'bench', 'bench.png'))
    return table


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or '').splitlines()[0])
    parser.add_argument('--quick', action='store_true', help='one short run of each (smoke)')
    parser.add_argument('--out', default=repo_root(), help='where bench/ and BENCHMARKS.md go')
    parser.add_argument(
        '--only',
        metavar='KEY[,KEY...]',
        help='run only these measurements (keys of PLAN, e.g. bare,standin_1,latency) and '
        'print their summary; nothing is written',
    )
    args = parser.parse_args(argv)
    if args.only:
        keys = args.only.split(',')
        unknown = [k for k in keys if k not in {row[0] for row in PLAN}]
        if unknown:
            parser.error('unknown key(s) %s; known: %s' % (unknown, [row[0] for row in PLAN]))
        raw = run_plan([row for row in plan_for(args.quick) if row[0] in keys])
        print(json.dumps({k: summarise(v) for k, v in raw.items()}, indent=1))
        return 0
    raw = run_plan(plan_for(args.quick))
    results = {'machine': machine(), 'quick': args.quick, 'figures': figures(raw), 'raw': raw}
    print(write_results(results, args.out))
    return 0


if __name__ == '__main__':
    sys.exit(main())
