"""`make bench --quick` runs end to end and its figures are sane (not the goals: machines are
noisy)."""

import json
import subprocess
import sys

import pytest


@pytest.fixture(scope='module')
def quick_bench(tmp_path_factory):
    out = tmp_path_factory.mktemp('bench')
    proc = subprocess.run(
        [sys.executable, '-m', '_arm1sim.bench', '--quick', '--out', str(out)],
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        timeout=600,
    )
    assert proc.returncode == 0, proc.stdout[-3000:]
    with open(out / 'bench' / 'results.json') as f:
        return out, json.load(f), proc.stdout


def median(results, key, field):
    return results['figures'][key][field]['median']


def test_writes_table_json_and_plot(quick_bench):
    out, results, stdout = quick_bench
    assert (out / 'bench' / 'bench.png').stat().st_size > 10000
    table = (out / 'BENCHMARKS.md').read_text()
    for figure in (
        'real-time factor',
        'stand-in / bare speed ratio',
        'command latency p99',
        'start-up',
        'peak resident memory',
    ):
        assert figure in table
    assert '| figure | median |' in stdout


def test_figures_are_sane(quick_bench):
    _, r, _ = quick_bench
    assert median(r, 'bare', 'steps_per_s') > 5000
    assert r['figures']['speed_ratio']['median'] > 0.2  # the stand-in is not far off bare pybullet
    assert 0.2 < r['figures']['speed_ratio_cpu']['median'] < 1.5  # in CPU time per step too
    # the trajectory-controlled arm runs, at a speed of the same order as the position one
    assert median(r, 'standin_trajectory', 'steps_per_s') > 0.3 * median(
        r, 'standin_1', 'steps_per_s'
    )
    assert 0.9 < median(r, 'realtime', 'rtf') < 1.1
    assert abs(median(r, 'realtime', 'joint_states_hz') - 50.0) < 1.0
    assert 0 < median(r, 'realtime', 'cpu_core_fraction') < 0.8
    # arm1 commanded upright, off the ground: measured, and no dearer than a core
    assert 0 < median(r, 'realtime', 'cpu_core_fraction_upright') < 1.0
    assert 20 < median(r, 'realtime', 'peak_rss_mb') < 1000
    assert 0.2 < median(r, 'startup', 'startup_s') < 20
    assert r['raw']['latency'][0]['n'] >= 95  # nearly every command seen applied
    assert 0 < median(r, 'latency', 'p99_ms') < 50
