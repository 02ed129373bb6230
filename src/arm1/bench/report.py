"""The benchmark's table (BENCHMARKS.md) and plot (bench/bench.png) from results.json's data."""

from __future__ import annotations

import os
from typing import Any, Dict, Iterator, Optional, Tuple

# (label, figure, field, goal text, check(median) -> bool or None, format)
ROWS = [
    (
        'real-time factor over the run, at factor 1',
        'realtime',
        'rtf',
        '1.00 ± 0.01',
        lambda v: abs(v - 1.0) <= 0.01,
        '%.4f',
    ),
    (
        'joint_states rate in sim time (Hz)',
        'realtime',
        'joint_states_hz',
        '50 ± 0.5 %',
        lambda v: abs(v - 50.0) <= 0.25,
        '%.3f',
    ),
    (
        'world CPU at real time (fraction of a core)',
        'realtime',
        'cpu_core_fraction',
        '≤ 0.10',
        lambda v: v <= 0.10,
        '%.3f',
    ),
    (
        '  the floor: empty world, no robot (fraction of a core)',
        'idle_world',
        'cpu_core_fraction',
        '',
        None,
        '%.3f',
    ),
    (
        '  CPU of one 1 ms sleep and wake-up (µs)',
        'idle_world',
        'sleep_wakeup_cpu_us',
        '',
        None,
        '%.1f',
    ),
    (
        'world peak resident memory (MB)',
        'realtime',
        'peak_rss_mb',
        '≤ 200',
        lambda v: v <= 200,
        '%.0f',
    ),
    ('bare pybullet loop (steps/s)', 'bare', 'steps_per_s', 'the ceiling', None, '%.0f'),
    ('stand-in top speed, 1 arm (steps/s)', 'standin_1', 'steps_per_s', '', None, '%.0f'),
    ('stand-in / bare speed ratio', 'speed_ratio', None, '≥ 0.6', lambda v: v >= 0.6, '%.2f'),
    (
        'stand-in top speed, 1 arm, one JointTrajectoryController (steps/s)',
        'standin_trajectory',
        'steps_per_s',
        'next to the position controllers',
        None,
        '%.0f',
    ),
    ('stand-in top speed, 2 arms (steps/s)', 'standin_2', 'steps_per_s', '', None, '%.0f'),
    ('stand-in top speed, 4 arms (steps/s)', 'standin_4', 'steps_per_s', '', None, '%.0f'),
    ('stand-in top speed, 8 arms (steps/s)', 'standin_8', 'steps_per_s', '', None, '%.0f'),
    (
        'stand-in top speed, 1 arm, camera streaming 30 Hz in lockstep (steps/s)',
        'standin_camera',
        'steps_per_s',
        '',
        None,
        '%.0f',
    ),
    ('  wall time each camera frame adds (ms)', 'camera_frame_ms', None, '', None, '%.1f'),
    (
        'start-up: roslaunch to first joint_states (s)',
        'startup',
        'startup_s',
        '≤ 3',
        lambda v: v <= 3.0,
        '%.2f',
    ),
    ('command latency p50 (ms)', 'latency', 'p50_ms', '', None, '%.3f'),
    ('command latency p99 (ms)', 'latency', 'p99_ms', '≤ 2', lambda v: v <= 2.0, '%.3f'),
]


Results = Dict[str, Any]  # results.json: machine, quick, figures, raw


def rows(results: Results) -> Iterator[Tuple[str, str, str, str, str]]:
    fig = results['figures']
    for label, key, field, goal, check, fmt in ROWS:
        if key not in fig:
            continue
        value = fig[key] if field is None else fig[key].get(field)
        if value is None:
            continue
        median = value['median']
        spread = (
            '%s – %s (%d runs)' % (fmt % value['min'], fmt % value['max'], value['runs'])
            if 'min' in value
            else ''
        )
        verdict = '' if check is None else ('met' if check(median) else 'NOT met')
        yield label, fmt % median, spread, goal, verdict


def table(results: Results) -> str:
    lines = ['| figure | median | spread | goal | |', '|---|---|---|---|---|']
    lines += ['| %s | %s | %s | %s | %s |' % r for r in rows(results)]
    return '\n'.join(lines)


def write_markdown(results: Results, path: str) -> str:
    m = results['machine']
    text = table(results)
    from .soak import existing_section

    soak = existing_section(path)  # make soak's section outlives a new make bench
    with open(path, 'w') as f:
        f.write(
            '# Benchmarks\n\n'
            'Made by `make bench` (`python -m arm1.bench`); the raw numbers are in '
            '`bench/results.json`, the plot in `bench/bench.png`. Every figure below comes '
            'from one run of that command, the stand-in and the bare pybullet loop measured '
            'side by side.\n\n'
            'Machine: %s, %s cores, Linux %s, Python %s, pybullet %s; %s.%s\n\n'
            % (
                m['cpu'] or 'unknown CPU',
                m['cores'],
                m['kernel'],
                m['python'],
                m['pybullet'],
                m['date'],
                ' **Quick run (smoke): one short run each.**' if results['quick'] else '',
            )
        )
        f.write(text + '\n')
        f.write(unmet_section(results))
        f.write(profile_section(results))
        f.write(METHOD)
        if soak:
            f.write('\n' + soak)
    return text


def unmet_section(results: Results) -> str:
    """Why a goal is not met, with this run's own figures."""
    fig = results['figures']

    def med(key: str, field: str) -> Optional[float]:
        return fig[key][field]['median'] if key in fig and field in fig[key] else None

    out = []
    ratio = fig.get('speed_ratio', {}).get('median')
    bare, standin = med('bare', 'steps_per_s'), med('standin_1', 'steps_per_s')
    if ratio is not None and ratio < 0.6 and bare and standin:
        out.append(
            '- **Speed ratio %.2f (goal 0.6).** A bare step takes %.1f µs, '
            'a stand-in step %.1f µs. '
            'The difference is Python doing what ros_control does: four controller objects with '
            'a control_toolbox PID each, effort saturation per joint, the hardware interface '
            'and the controller manager: about %.1f µs more per joint per step in CPython than '
            'the bare loop\'s inline PD. The profile below shows Python taking most of the '
            'physics thread; joint_states and /clock cost the rest. Closing the gap '
            'means moving the per-joint path out of Python.'
            % (ratio, 1e6 / bare, 1e6 / standin, (1e6 / standin - 1e6 / bare) / 4)
        )
    cpu, floor = med('realtime', 'cpu_core_fraction'), med('idle_world', 'cpu_core_fraction')
    wake = med('idle_world', 'sleep_wakeup_cpu_us')
    if cpu is not None and cpu > 0.10 and floor is not None:
        out.append(
            '- **CPU at real time %.3f of a core (goal 0.10).** An empty world already costs '
            '%.3f: a 1 kHz world sleeps and wakes 1 000 times a second, and one wake-up costs '
            '%.0f µs of CPU on this virtual machine. arm1 with its five controllers and its '
            'subscribers (robot_state_publisher, joint_state_publisher, the spawner and this '
            'benchmark read /clock) adds %.0f µs of CPU per step, several times what a step '
            'costs back to back at top speed (%.0f µs): a step that starts after a sleep '
            'finds cold caches, and every /clock goes out to each subscriber. '
            'Running two steps per wake-up would cut the wake-ups but hold a command up to a '
            'step longer, against the 2 ms latency goal, so the world keeps one step per '
            'wake-up.'
            % (
                cpu,
                floor,
                float('nan') if wake is None else wake,
                (cpu - floor) * 1000,
                1e6 / standin if standin else float('nan'),
            )
        )
    if not out:
        return ''
    return '\n## Goals not met, and why\n\n' + '\n'.join(out) + '\n'


def profile_section(results: Results) -> str:
    """Where the stand-in's step goes, from the profiled top-speed run."""
    runs = results['raw'].get('profile')
    if not runs:
        return ''
    shares = runs[0]['profile_share']
    lines = [
        '',
        '## Where a stand-in step goes',
        '',
        'cProfile of the physics thread at top speed (1 arm). Profiling slows Python code '
        'more than pybullet\'s C++, so Python\'s real share is somewhat smaller.',
        '',
        '| part | share of the physics thread |',
        '|---|---|',
    ]
    lines += [
        '| %s | %.0f %% |' % (k, 100 * v) for k, v in sorted(shares.items(), key=lambda kv: -kv[1])
    ]
    return '\n'.join(lines) + '\n'


METHOD = '''
## How each figure is measured

- **bare pybullet loop**: arm1 (same URDF and meshes) in pybullet DIRECT, a ground plane; each
  step reads the four joints, computes a PD in plain Python, applies the torques and steps.
  No ROS, none of our classes: the ceiling for anything built on pybullet in Python.
- **stand-in top speed**: the world node's own code (`start_world`, `WorldNode.run`) with
  `real_time_update_rate` 0, all five controllers running, `/clock` at 100 Hz sim time and
  joint_states at 50 Hz sim time with a subscriber in another process (`rostopic hz`, as
  robot_state_publisher would be). N arms: N copies of arm1, each in its own namespace
  (`/arm1` … `/armN`) with its own controller manager and five controllers.
- **real time**: `roslaunch arm1 gazebo.launch gui:=false`, watched from another process:
  real-time factor = sim time advanced (from `/clock`) over wall time, joint_states rate =
  messages over their sim-time span; CPU = user+system time of the world process (`/gazebo`)
  over wall time; peak memory = its VmHWM.
- **start-up**: from starting `roslaunch arm1 gazebo.launch gui:=false` (master included,
  nothing running before) to the first `/arm1/joint_states` message.
- **command latency**: a separate process publishes 1 000 distinct joint1 targets at 100 Hz;
  the world records the wall time of the first control update that uses each one.
- **the floor**: the world node with no robot at real time (CPU over 20 s), and the CPU of
  one 0.9 ms `time.sleep` (2 000 of them).
'''


def write_plot(results: Results, path: str) -> None:
    import matplotlib

    matplotlib.use('Agg')
    import matplotlib.pyplot as plt

    raw = results['raw']
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    keys = [k for k in ('bare', 'standin_1', 'standin_2', 'standin_4', 'standin_8') if k in raw]
    labels = [
        'bare\npybullet' if k == 'bare' else '%s arm%s' % (k[-1], '' if k[-1] == '1' else 's')
        for k in keys
    ]
    for x, k in enumerate(keys):
        values = [r['steps_per_s'] / 1000.0 for r in raw[k]]
        axes[0].scatter([x] * len(values), values, color='tab:blue' if k != 'bare' else 'tab:gray')
        axes[0].bar(
            x,
            sorted(values)[len(values) // 2],
            alpha=0.3,
            color='tab:blue' if k != 'bare' else 'tab:gray',
        )
    axes[0].axhline(1.0, color='tab:red', lw=1, ls='--', label='real time (1 kHz step)')
    axes[0].set_xticks(range(len(keys)), labels)
    axes[0].set_ylabel('thousand steps per wall second')
    axes[0].set_title('Top speed (median bar, each run a dot)')
    axes[0].legend()
    if 'realtime' in raw:
        rtf = [r['rtf'] for r in raw['realtime']]
        cpu = [r['cpu_core_fraction'] for r in raw['realtime']]
        axes[1].bar(
            ['real-time\nfactor', 'CPU\n(cores)'],
            [sorted(rtf)[len(rtf) // 2], sorted(cpu)[len(cpu) // 2]],
            color=['tab:green', 'tab:orange'],
        )
        axes[1].axhline(1.0, color='tab:green', lw=1, ls='--')
        axes[1].axhline(0.10, color='tab:orange', lw=1, ls='--')
        axes[1].set_title('At real time (goal lines dashed)')
    fig.tight_layout()
    os.makedirs(os.path.dirname(path), exist_ok=True)
    fig.savefig(path, dpi=100)
    plt.close(fig)
