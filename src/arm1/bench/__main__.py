"""``make bench``: measure the stand-in next to bare pybullet, in one run, on this machine.

Writes bench/results.json, the table in BENCHMARKS.md and bench/bench.png.
``--quick`` runs each measurement once and briefly (the smoke test in ``make test``).
"""
import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import time

from .report import write_markdown, write_plot
from .workers import ROOT

# (key, worker kind, worker args, runs, quick args, quick runs)
PLAN = [
    ('bare', 'bare', ['--seconds', '5'], 3, ['--seconds', '1.5'], 1),
    ('standin_1', 'standin', ['--seconds', '5', '--arms', '1'], 3,
     ['--seconds', '1.5', '--arms', '1'], 1),
    ('standin_2', 'standin', ['--seconds', '4', '--arms', '2'], 3, None, 0),
    ('standin_4', 'standin', ['--seconds', '4', '--arms', '4'], 3, None, 0),
    ('standin_8', 'standin', ['--seconds', '4', '--arms', '8'], 3, None, 0),
    ('standin_camera', 'standin', ['--seconds', '6', '--arms', '1', '--camera'], 3, None, 0),
    ('profile', 'standin', ['--seconds', '4', '--arms', '1', '--profile'], 1, None, 0),
    ('latency', 'latency', ['--commands', '1000'], 3, ['--commands', '100'], 1),
    ('startup', 'startup', [], 5, [], 1),
    ('realtime', 'realtime', ['--seconds', '60'], 3, ['--seconds', '4'], 1),
    ('idle_world', 'idle_world', ['--seconds', '20'], 3, None, 0),
]
NEEDS_MASTER = {'standin', 'latency'}  # they run the world in-process against a shared master


def progress(done, total, label, width=30):
    filled = int(width * done / total)
    sys.stdout.write('\r[%s%s] %2d/%d %-40s' % ('#' * filled, '.' * (width - filled), done, total,
                                                 label))
    sys.stdout.flush()


def run_worker(kind, args, env):
    proc = subprocess.run([sys.executable, '-m', 'arm1.bench.workers', kind] + args, env=env,
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=600)
    lines = [l for l in proc.stdout.splitlines() if l.startswith('{')]
    if proc.returncode != 0 or not lines:
        raise RuntimeError('bench worker %s %s failed (exit %d):\n%s' % (
            kind, ' '.join(args), proc.returncode, proc.stderr[-3000:]))
    return json.loads(lines[-1])


def start_master(env):
    from ..launcher import RosSession
    session = RosSession()
    env['ROS_MASTER_URI'] = session.env['ROS_MASTER_URI']
    session.start('rosmaster', '--core', '-p', session.env['ROS_MASTER_URI'].rsplit(':', 1)[1])
    if not session.wait_for_master():
        raise RuntimeError('rosmaster did not start')
    return session


def summarise(samples):
    """Median and spread (min, max) of every numeric field over the runs."""
    out = {}
    for key in samples[0]:
        values = [s[key] for s in samples if isinstance(s.get(key), (int, float))]
        if values and not isinstance(samples[0][key], bool):
            out[key] = {'median': statistics.median(values), 'min': min(values),
                        'max': max(values), 'runs': len(values)}
    return out


def machine():
    model = ''
    try:
        with open('/proc/cpuinfo') as f:
            model = next((l.split(':', 1)[1].strip() for l in f if l.startswith('model name')), '')
    except OSError:
        pass
    import pybullet
    return {'cpu': model, 'cores': os.cpu_count(), 'python': platform.python_version(),
            'kernel': platform.release(), 'pybullet': getattr(pybullet, '__version__', '3.2.7'),
            'date': time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--quick', action='store_true', help='one short run of each (smoke)')
    parser.add_argument('--out', default=ROOT, help='where bench/ and BENCHMARKS.md go')
    args = parser.parse_args(argv)
    plan = [(key, kind, qargs if args.quick else full, qruns if args.quick else runs)
            for key, kind, full, runs, qargs, qruns in PLAN if not (args.quick and not qruns)]
    total = sum(runs for *_, runs in plan)
    env = dict(os.environ)
    master = start_master(env)
    raw, done = {}, 0
    try:
        for key, kind, wargs, runs in plan:
            for k in range(runs):
                progress(done, total, '%s run %d/%d' % (key, k + 1, runs))
                raw.setdefault(key, []).append(run_worker(kind, wargs, env))
                done += 1
        progress(done, total, 'done')
        print()
    finally:
        master.stop()
    results = {'machine': machine(), 'quick': args.quick,
               'figures': {key: summarise(samples) for key, samples in raw.items()}, 'raw': raw}
    fig = results['figures']
    one = fig['standin_1']['steps_per_s']['median']
    fig['speed_ratio'] = {'median': one / fig['bare']['steps_per_s']['median']}
    if 'standin_camera' in fig:  # wall time a 30 Hz frame adds to each simulated second
        cam = fig['standin_camera']['steps_per_s']['median']
        fig['camera_frame_ms'] = {'median': (1000.0 / cam - 1000.0 / one) / 30 * 1000}
    os.makedirs(os.path.join(args.out, 'bench'), exist_ok=True)
    with open(os.path.join(args.out, 'bench', 'results.json'), 'w') as f:
        json.dump(results, f, indent=1, sort_keys=True)
    table = write_markdown(results, os.path.join(args.out, 'BENCHMARKS.md'))
    write_plot(results, os.path.join(args.out, 'bench', 'bench.png'))
    print(table)
    return 0


if __name__ == '__main__':
    sys.exit(main())
