"""What a process or a call costs, and what machine and code the benchmark ran on."""

from __future__ import annotations

import os
import platform
import statistics
import time
from typing import Callable, Dict, Iterable, List

import psutil

from ..paths import repo_root


def median_ms(fn: Callable[[], object], count: int) -> float:
    """Median wall milliseconds of ``count`` calls of ``fn``."""
    times: List[float] = []
    for _ in range(count):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times) * 1000.0


def cpu_seconds(pids: Iterable[int]) -> float:
    """User + system CPU seconds the processes have used so far (their threads included)."""
    total = 0.0
    for pid in pids:
        times = psutil.Process(pid).cpu_times()
        total += times.user + times.system
    return total


def peak_rss_mb(pid: int) -> float:
    """The process's peak resident memory (MB) since it started: the kernel's VmHWM.

    psutil has no peak RSS on Linux (giampaolo/psutil#1096, open), and sampling the current
    RSS would miss the start-up peak, so this one field is read from /proc itself.
    """
    with open('/proc/%d/status' % pid) as f:
        for line in f:
            if line.startswith('VmHWM:'):
                return int(line.split()[1]) / 1024.0
    return float('nan')


def cpu_model() -> str:
    """The CPU's model name ('' if unknown); psutil does not report it."""
    try:
        with open('/proc/cpuinfo') as f:
            return next(
                (ln.split(':', 1)[1].strip() for ln in f if ln.startswith('model name')), ''
            )
    except OSError:
        return ''


def machine() -> Dict[str, object]:
    """CPU, cores, Python, kernel, pybullet, date and load, for the report's header."""
    import pybullet

    return {
        'cpu': cpu_model(),
        'cores': psutil.cpu_count(),
        'python': platform.python_version(),
        'kernel': platform.release(),
        'pybullet': getattr(pybullet, '__version__', '3.2.7'),
        'date': time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime()),
        # Other work on a shared machine colours every figure: the 1, 5 and 15 min load
        # averages as the run ends (the 15 min one spans most of it).
        'load_average': list(os.getloadavg()),
    }


def source_state() -> str:
    """The commit the run used, and whether src/ differed from it (others may be mid-change)."""
    import subprocess

    try:
        head = subprocess.run(
            ['git', '-C', repo_root(), 'rev-parse', '--short', 'HEAD'],
            capture_output=True,
            text=True,
            check=True,
        ).stdout.strip()
        dirty = subprocess.run(
            [
                'git',
                '-C',
                repo_root(),
                'status',
                '--porcelain',
                'src',
                'scripts',
                'launch',
                'urdf',
                'worlds',
                'config',
            ],
            capture_output=True,
            text=True,
            check=True,
        ).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return 'unknown'
    return head + (' with uncommitted changes under src/ etc.' if dirty else '')
