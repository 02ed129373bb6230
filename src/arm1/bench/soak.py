"""``make soak``: robot_spawn.launch under simple_mover with a camera viewer, for minutes on end.

Prints once a minute the real-time factor, sim time's drift against wall time, the world's
memory (RSS), threads and CPU, and the joint_states and image rates; ends with a summary
judged against the goals (RTF within 0.1 % of 1, RSS growth under 5 % after the warm-up),
and writes bench/soak.json, bench/soak.png and the "Soak" section of BENCHMARKS.md.
Exits non-zero if a goal is not met or the world stopped.
"""

import argparse
import json
import os
import statistics
import struct
import sys
import threading
import time
from typing import Dict, List, Optional, Tuple

from ..paths import repo_root

RTF_TOLERANCE = 0.001  # the goal: sim time within 0.1 % of wall time
RSS_GROWTH_LIMIT = 0.05  # the goal: world RSS grows less than 5 % after the warm-up
SAMPLE_S = 2.0  # wall seconds between samples
FRAME_PERIOD = 1.0 / 30  # the camera's update rate in sim time (urdf/arm1.gazebo.xacro)
SECTION_BEGIN = '<!-- soak: written by make soak (python -m arm1.bench.soak) -->'
SECTION_END = '<!-- soak end -->'


class Probe:
    """What the soak hears: /clock (with wall arrival), joint_states and camera image stamps."""

    def __init__(self) -> None:
        import rospy
        from rosgraph_msgs.msg import Clock
        from sensor_msgs.msg import JointState

        self.lock = threading.Lock()
        self.clock: Optional[Tuple[float, float]] = None  # (wall monotonic, sim s) of the last
        self.joint_states = 0
        self.images = 0
        self.images_late = 0  # a frame more than half a period after the one before
        self.last_image: Optional[float] = None
        rospy.Subscriber('/clock', Clock, self._on_clock, queue_size=10)
        rospy.Subscriber('/arm1/joint_states', JointState, self._on_state, queue_size=50)
        # AnyMsg: the stamp is read from the raw bytes, so 27 MB/s of pixels are never
        # deserialised in Python (the viewer should not load the machine it measures).
        rospy.Subscriber(
            '/rgb_camera/image_raw', rospy.AnyMsg, self._on_image, queue_size=10, buff_size=1 << 22
        )

    def _on_clock(self, msg) -> None:
        with self.lock:
            self.clock = (time.monotonic(), msg.clock.to_sec())

    def _on_state(self, msg) -> None:
        with self.lock:
            self.joint_states += 1

    def _on_image(self, msg) -> None:
        _, secs, nsecs = struct.unpack_from('<III', msg._buff, 0)  # std_msgs/Header first
        stamp = secs + nsecs * 1e-9
        with self.lock:
            if self.last_image is not None and stamp - self.last_image > 1.5 * FRAME_PERIOD:
                self.images_late += 1
            self.last_image = stamp
            self.images += 1

    def snapshot(self) -> Dict[str, float]:
        with self.lock:
            wall, sim = self.clock if self.clock else (float('nan'), float('nan'))
            return {
                'clock_wall': wall,
                'sim': sim,
                'joint_states': self.joint_states,
                'images': self.images,
                'images_late': self.images_late,
            }


class ProcessWatch:
    """RSS, threads and CPU of the world process (and its render processes), and of the rest."""

    def __init__(self, world_pid: int, ours: List[int]) -> None:
        import psutil

        self.psutil = psutil
        self.world = psutil.Process(world_pid)
        self.ours = [psutil.Process(p) for p in ours]

    def _tree(self, roots) -> list:
        seen = {}
        for root in roots:
            for p in [root] + root.children(recursive=True):
                seen[p.pid] = p
        return list(seen.values())

    def sample(self) -> Dict[str, float]:
        psutil = self.psutil
        world_cpu = self.world.cpu_times()
        out = {
            'world_rss_mb': self.world.memory_info().rss / 2**20,
            'world_threads': self.world.num_threads(),
            'world_cpu_s': world_cpu.user + world_cpu.system,
        }
        renders = rss = cpu = 0.0
        for p in self.world.children(recursive=True):
            try:
                rss += p.memory_info().rss / 2**20
                t = p.cpu_times()
                cpu += t.user + t.system
                renders += 1
            except psutil.NoSuchProcess:  # a render process restarting
                pass
        out.update(render_rss_mb=rss, render_cpu_s=cpu, render_processes=renders)
        ours = 0.0
        for p in self._tree(self.ours):
            try:
                t = p.cpu_times()
                ours += t.user + t.system + t.children_user + t.children_system
            except psutil.NoSuchProcess:
                pass
        machine = psutil.cpu_times()
        out['session_cpu_s'] = ours
        out['machine_busy_s'] = (
            machine.user
            + machine.nice
            + machine.system
            + machine.irq
            + machine.softirq
            + getattr(machine, 'steal', 0.0)
        )
        out['load1'] = os.getloadavg()[0]
        return out


def per_window(a: Dict[str, float], b: Dict[str, float]) -> Dict[str, float]:
    """Figures over the span between two samples."""
    wall = b['clock_wall'] - a['clock_wall']
    sim = b['sim'] - a['sim']
    cores = os.cpu_count() or 1
    return {
        'rtf': sim / wall,
        'joint_states_hz': (b['joint_states'] - a['joint_states']) / sim,
        'images_hz': (b['images'] - a['images']) / sim,
        'images_late': b['images_late'] - a['images_late'],
        'world_cpu_cores': (b['world_cpu_s'] - a['world_cpu_s']) / (b['t'] - a['t']),
        'render_cpu_cores': (b['render_cpu_s'] - a['render_cpu_s']) / (b['t'] - a['t']),
        # Everything else this machine ran meanwhile (other people's tests), in cores.
        'other_cpu_cores': max(
            0.0,
            (b['machine_busy_s'] - a['machine_busy_s']) - (b['session_cpu_s'] - a['session_cpu_s']),
        )
        / (b['t'] - a['t']),
        'cores': cores,
    }


def median_between(samples: List[dict], key: str, t0: float, t1: float) -> float:
    values = [s[key] for s in samples if t0 <= s['t'] <= t1]
    return statistics.median(values) if values else float('nan')


def judge(samples: List[dict], warmup_s: float) -> dict:
    """Whole-run figures after the warm-up, and the goals' verdicts."""
    start = next(s for s in samples if s['t'] >= warmup_s)
    end = samples[-1]
    window = per_window(start, end)
    span = end['t'] - start['t']
    # RSS over a minute (or a quarter of the run) at each end: one frame in flight is a few MB.
    edge = min(60.0, span / 4)
    rss0 = median_between(samples, 'world_rss_mb', start['t'], start['t'] + edge)
    rss1 = median_between(samples, 'world_rss_mb', end['t'] - edge, end['t'])
    tree0 = rss0 + median_between(samples, 'render_rss_mb', start['t'], start['t'] + edge)
    tree1 = rss1 + median_between(samples, 'render_rss_mb', end['t'] - edge, end['t'])
    drift_s = (end['sim'] - start['sim']) - (end['clock_wall'] - start['clock_wall'])
    out = dict(window)
    out.update(
        {
            'measured_s': span,
            'warmup_s': warmup_s,
            'drift_s': drift_s,
            'drift_pct': 100.0 * (window['rtf'] - 1.0),
            'world_rss_start_mb': rss0,
            'world_rss_end_mb': rss1,
            'world_rss_growth_pct': 100.0 * (rss1 / rss0 - 1.0),
            'world_and_render_rss_start_mb': tree0,
            'world_and_render_rss_end_mb': tree1,
            'world_and_render_rss_growth_pct': 100.0 * (tree1 / tree0 - 1.0),
            'world_threads_start': start['world_threads'],
            'world_threads_end': end['world_threads'],
            'world_threads_max': max(s['world_threads'] for s in samples if s['t'] >= warmup_s),
        }
    )
    # Sim time lost in one sampling interval: a world that falls behind in one hiccup (and,
    # like Gazebo, does not catch up) shows here, unlike a slow steady drift.
    after = [s for s in samples if s['t'] >= warmup_s]
    losses = [
        ((b['clock_wall'] - a['clock_wall']) - (b['sim'] - a['sim']), b['t'])
        for a, b in zip(after, after[1:])
    ]
    worst = max(losses) if losses else (0.0, 0.0)
    out.update(
        worst_loss_s=worst[0],
        worst_loss_at_s=worst[1],
        losses_over_50ms=sum(1 for lost, _ in losses if lost > 0.05),
    )
    out['rtf_ok'] = abs(window['rtf'] - 1.0) <= RTF_TOLERANCE
    out['rss_ok'] = out['world_rss_growth_pct'] < 100.0 * RSS_GROWTH_LIMIT
    return out


def minute_rows(samples: List[dict]) -> List[dict]:
    """One row per whole wall minute: the window's figures and the state at its end."""
    rows, last, minute = [], samples[0], 1
    for s in samples[1:]:
        if s['t'] >= 60.0 * minute:
            row = per_window(last, s)
            row.update(
                minute=minute,
                drift_s=(s['sim'] - samples[0]['sim'])
                - (s['clock_wall'] - samples[0]['clock_wall']),
                world_rss_mb=s['world_rss_mb'],
                render_rss_mb=s['render_rss_mb'],
                world_threads=s['world_threads'],
                load1=s['load1'],
            )
            rows.append(row)
            last, minute = s, minute + 1
    return rows


HEADER = '%4s %8s %9s %9s %9s %7s %6s %6s %7s %7s %5s %6s' % (
    'min',
    'RTF',
    'drift ms',
    'world MB',
    'render MB',
    'threads',
    'world',
    'render',
    'js Hz',
    'img Hz',
    'late',
    'others',
)


def format_row(r: dict) -> str:
    return '%4d %8.5f %9.1f %9.1f %9.1f %7d %6.2f %6.2f %7.2f %7.2f %5d %6.2f' % (
        r['minute'],
        r['rtf'],
        1000 * r['drift_s'],
        r['world_rss_mb'],
        r['render_rss_mb'],
        r['world_threads'],
        r['world_cpu_cores'],
        r['render_cpu_cores'],
        r['joint_states_hz'],
        r['images_hz'],
        r['images_late'],
        r['other_cpu_cores'],
    )


def summary_lines(fig: dict, minutes: List[dict]) -> List[str]:
    def med(key: str) -> float:
        return statistics.median(r[key] for r in minutes) if minutes else float('nan')

    return [
        'after a %.0f s warm-up, over %.1f min:' % (fig['warmup_s'], fig['measured_s'] / 60),
        '  real-time factor %.5f (sim time %+.3f %% of wall, %+.2f s): %s (goal within %.1f %%)'
        % (
            fig['rtf'],
            fig['drift_pct'],
            fig['drift_s'],
            'met' if fig['rtf_ok'] else 'NOT met',
            100 * RTF_TOLERANCE,
        ),
        '  largest sim time lost in one %.0f s sample: %.0f ms at minute %.1f; samples that lost '
        'more than 50 ms: %d'
        % (
            SAMPLE_S,
            1000 * fig['worst_loss_s'],
            fig['worst_loss_at_s'] / 60,
            fig['losses_over_50ms'],
        ),
        '  world RSS %.1f -> %.1f MB (%+.2f %%): %s (goal under +%.0f %%); with its render '
        'processes %.1f -> %.1f MB (%+.2f %%)'
        % (
            fig['world_rss_start_mb'],
            fig['world_rss_end_mb'],
            fig['world_rss_growth_pct'],
            'met' if fig['rss_ok'] else 'NOT met',
            100 * RSS_GROWTH_LIMIT,
            fig['world_and_render_rss_start_mb'],
            fig['world_and_render_rss_end_mb'],
            fig['world_and_render_rss_growth_pct'],
        ),
        '  world threads %d -> %d (max %d); CPU: world %.2f, render processes %.2f cores; '
        'others on the machine %.2f cores'
        % (
            fig['world_threads_start'],
            fig['world_threads_end'],
            fig['world_threads_max'],
            fig['world_cpu_cores'],
            fig['render_cpu_cores'],
            fig['other_cpu_cores'],
        ),
        '  joint_states %.3f Hz, images %.3f Hz of sim time (%d frames later than 1.5 periods); '
        'per-minute medians: RTF %.5f, joint_states %.3f Hz, images %.3f Hz'
        % (
            fig['joint_states_hz'],
            fig['images_hz'],
            fig['images_late'],
            med('rtf'),
            med('joint_states_hz'),
            med('images_hz'),
        ),
    ]


def write_plot(samples: List[dict], minutes: List[dict], warmup_s: float, path: str) -> None:
    import matplotlib

    matplotlib.use('Agg')
    import matplotlib.pyplot as plt

    t = [s['t'] / 60 for s in samples]
    fig, ax = plt.subplots(2, 2, figsize=(11, 7), sharex=True)
    drift = [
        1000 * ((s['sim'] - samples[0]['sim']) - (s['clock_wall'] - samples[0]['clock_wall']))
        for s in samples
    ]
    ax[0][0].plot(t, drift, color='tab:blue')
    ax[0][0].set_ylabel('sim − wall time (ms)')
    ax[0][0].set_title('Drift of sim time (per-minute RTF right axis)')
    twin = ax[0][0].twinx()
    twin.plot(
        [r['minute'] - 0.5 for r in minutes],
        [r['rtf'] for r in minutes],
        'o-',
        color='tab:green',
        ms=3,
    )
    twin.set_ylabel('RTF per minute', color='tab:green')
    ax[0][1].plot(t, [s['world_rss_mb'] for s in samples], label='world')
    ax[0][1].plot(
        t,
        [s['world_rss_mb'] + s['render_rss_mb'] for s in samples],
        label='world + render processes',
    )
    ax[0][1].set_ylabel('RSS (MB)')
    ax[0][1].set_title('Memory')
    ax[0][1].legend()
    ax[1][0].plot(t, [s['world_threads'] for s in samples], color='tab:purple')
    ax[1][0].set_ylabel('world threads')
    ax[1][0].set_xlabel('wall minutes')
    m = [r['minute'] - 0.5 for r in minutes]
    ax[1][1].plot(
        m, [r['joint_states_hz'] for r in minutes], 'o-', ms=3, label='joint_states (goal 50)'
    )
    ax[1][1].plot(m, [r['images_hz'] for r in minutes], 's-', ms=3, label='images (goal 30)')
    ax[1][1].set_ylabel('Hz of sim time, per minute')
    ax[1][1].set_xlabel('wall minutes')
    ax[1][1].legend()
    for a in (ax[0][0], ax[0][1], ax[1][0], ax[1][1]):
        a.axvline(warmup_s / 60, color='gray', ls=':', lw=1)
    fig.tight_layout()
    os.makedirs(os.path.dirname(path), exist_ok=True)
    fig.savefig(path, dpi=90)
    plt.close(fig)


def markdown(result: dict) -> str:
    """The Soak section of BENCHMARKS.md, from one run's results."""
    f, m, minutes = result['figures'], result['machine'], result['minutes']

    def med(key: str) -> float:
        return statistics.median(r[key] for r in minutes)

    rows = [
        (
            'real-time factor after the warm-up',
            '%.5f' % f['rtf'],
            '1 ± 0.001',
            'met' if f['rtf_ok'] else 'NOT met',
        ),
        (
            '  sim time minus wall time at the end',
            '%+.2f s (%+.3f %%)' % (f['drift_s'], f['drift_pct']),
            '',
            '',
        ),
        (
            '  real-time factor per minute, median (min – max)',
            '%.5f (%.5f – %.5f)'
            % (med('rtf'), min(r['rtf'] for r in minutes), max(r['rtf'] for r in minutes)),
            '',
            '',
        ),
        (
            '  largest sim time lost in one %.0f s sample; samples losing > 50 ms' % SAMPLE_S,
            '%.0f ms (minute %.1f); %d'
            % (1000 * f['worst_loss_s'], f['worst_loss_at_s'] / 60, f['losses_over_50ms']),
            '',
            '',
        ),
        (
            'world RSS growth after the warm-up',
            '%+.2f %% (%.1f → %.1f MB)'
            % (f['world_rss_growth_pct'], f['world_rss_start_mb'], f['world_rss_end_mb']),
            '< 5 %',
            'met' if f['rss_ok'] else 'NOT met',
        ),
        (
            '  world + render processes',
            '%+.2f %% (%.1f → %.1f MB)'
            % (
                f['world_and_render_rss_growth_pct'],
                f['world_and_render_rss_start_mb'],
                f['world_and_render_rss_end_mb'],
            ),
            '',
            '',
        ),
        (
            'world threads (start → end, max)',
            '%d → %d, %d'
            % (f['world_threads_start'], f['world_threads_end'], f['world_threads_max']),
            '',
            '',
        ),
        (
            'joint_states rate (Hz of sim time; per-minute median)',
            '%.3f; %.3f' % (f['joint_states_hz'], med('joint_states_hz')),
            '50',
            '',
        ),
        (
            'image rate (Hz of sim time; per-minute median)',
            '%.3f; %.3f' % (f['images_hz'], med('images_hz')),
            '30',
            '',
        ),
        ('  frames later than 1.5 periods after the one before', '%d' % f['images_late'], '', ''),
        (
            'CPU: world; its render processes (cores)',
            '%.2f; %.2f' % (f['world_cpu_cores'], f['render_cpu_cores']),
            '',
            '',
        ),
        (
            'other work on the machine meanwhile (cores of %d)' % f['cores'],
            '%.2f' % f['other_cpu_cores'],
            '',
            '',
        ),
    ]
    lines = [
        SECTION_BEGIN,
        '## Soak',
        '',
        '`make soak SOAK_MINUTES=%g` (`python -m arm1.bench.soak`): `roslaunch arm1 '
        'robot_spawn.launch gui:=false` (the world, arm1 with its camera, arm_mover, '
        'look_away), `rosrun arm1 simple_mover __name:=simple_mover` and a viewer of '
        '`/rgb_camera/image_raw` (stamps only), on a private master on loopback. '
        'One run, %s, code at %s; %s, %s cores. Raw samples in `bench/soak.json`, the '
        'plot in `bench/soak.png`. %s'
        % (
            result['minutes_asked'],
            m['date'],
            result.get('source', 'unknown'),
            m['cpu'] or 'unknown CPU',
            m['cores'],
            'Other work ran on the machine during the soak (the "other work" row): '
            'the figures are from a shared machine.'
            if f['other_cpu_cores'] >= 0.1
            else 'Nothing else of note ran on the machine.',
        ),
        '',
        '| figure | value | goal | |',
        '|---|---|---|---|',
    ]
    lines += ['| %s | %s | %s | %s |' % r for r in rows]
    extra = notes(result)
    if extra:
        lines += [''] + extra
    lines += [
        '',
        'Memory: RSS medians over the first and the last minute after the %.0f s '
        'warm-up (one 640 × 480 frame in flight is about 1 MB). Drift: sim time from '
        '`/clock` against the wall clock at its arrival. Rates: messages over the sim '
        'time between the samples.' % f['warmup_s'],
        SECTION_END,
        '',
    ]
    return '\n'.join(lines)


def notes(result: dict) -> List[str]:
    """Why a figure looks the way it does, from the run's own numbers."""
    from ..sim.pacer import Pacer

    f, minutes = result['figures'], result['minutes']
    out = []
    if f['losses_over_50ms']:
        after = [r for r in minutes if r['minute'] * 60 > f['warmup_s']]
        lost = [r for r in after if 60 * (1 - r['rtf']) > 0.05]
        kept = [r for r in after if 60 * (1 - r['rtf']) <= 0.05]

        def med(rows: List[dict]) -> float:
            return statistics.median(r['other_cpu_cores'] for r in rows) if rows else float('nan')

        out.append(
            '- Sim time falls behind in steps, not steadily (the plot): now and then the world '
            'is more than %.0f ms late (`Pacer.MAX_LAG`) and, as Gazebo, does not make that '
            'time up; the other minutes run at a median real-time factor of %.5f. %d of %d '
            'minutes lost more than 50 ms; other work on the machine took a median %.2f cores '
            'in those minutes and %.2f in the others.'
            % (
                1000 * Pacer.MAX_LAG,
                statistics.median(r['rtf'] for r in kept) if kept else float('nan'),
                len(lost),
                len(after),
                med(lost),
                med(kept),
            )
        )
    if f['images_hz'] < 29.5:
        out.append(
            '- Images arrive at %.1f Hz of sim time, not 30: physics does not wait for the '
            'camera, so a frame whose instant comes while both render processes are still busy '
            'is skipped (%d frames came more than 1.5 periods after the one before). '
            '`lockstep:=true` keeps every frame and lets rendering slow sim time instead.'
            % (f['images_hz'], f['images_late'])
        )
    return out


def replace_section(path: str, section: str) -> None:
    """Put the soak section into BENCHMARKS.md in place of the previous one (or at the end)."""
    text = open(path).read() if os.path.exists(path) else '# Benchmarks\n'
    if SECTION_BEGIN in text and SECTION_END in text:
        head, rest = text.split(SECTION_BEGIN, 1)
        tail = rest.split(SECTION_END, 1)[1].lstrip('\n')
        text = head + section + tail
    else:
        text = text.rstrip('\n') + '\n\n' + section
    with open(path, 'w') as f:
        f.write(text)


def existing_section(path: str) -> str:
    """The soak section BENCHMARKS.md holds now ('' if none): make bench keeps it."""
    if not os.path.exists(path):
        return ''
    text = open(path).read()
    if SECTION_BEGIN not in text or SECTION_END not in text:
        return ''
    return (
        SECTION_BEGIN
        + text.split(SECTION_BEGIN, 1)[1].split(SECTION_END, 1)[0]
        + SECTION_END
        + '\n'
    )


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


def run(minutes: float, warmup_s: float) -> Tuple[List[dict], Optional[str]]:
    """Start everything, sample until the time is up; (samples, why it stopped early or None)."""
    import rospy

    from ..session.launcher import RosSession, node_pid

    session = RosSession()
    session.activate()
    samples: List[dict] = []
    with session:
        print(
            'soak: roslaunch arm1 robot_spawn.launch gui:=false; '
            'rosrun arm1 simple_mover __name:=simple_mover; a viewer of the camera; '
            '%g min (warm-up %.0f s), a line a minute' % (minutes, warmup_s),
            flush=True,
        )
        launch = session.roslaunch('arm1', 'robot_spawn.launch', 'gui:=false')
        if not session.wait_for_master():
            return samples, 'the ROS master did not start'
        rospy.init_node('arm1_soak', anonymous=True, disable_signals=True)
        probe = Probe()
        try:
            rospy.wait_for_message('/arm1/joint_states', rospy.AnyMsg, timeout=60)
        except rospy.ROSException:
            return samples, 'no /arm1/joint_states within 60 s'
        # The seed's simple_mover calls itself arm_mover (rospy.init_node('arm_mover')):
        # beside robot_spawn.launch's arm_mover the master would shut the service node
        # down ("new node registered with same name"), so it runs under its own name.
        mover = session.start('rosrun', 'arm1', 'simple_mover', '__name:=simple_mover')
        world = ProcessWatch(
            node_pid('/gazebo', caller=rospy.get_name()), [launch.pid, mover.pid, os.getpid()]
        )
        print(HEADER, flush=True)
        t0 = time.monotonic()
        end, printed, why = t0 + 60.0 * minutes, 0, None
        while True:
            try:
                s = dict(probe.snapshot(), **world.sample())
            except Exception as e:  # psutil.NoSuchProcess: the world is gone
                why = 'the world process stopped: %s' % e
                break
            s['t'] = time.monotonic() - t0
            samples.append(s)
            rows = minute_rows(samples)
            for r in rows[printed:]:
                print(format_row(r), flush=True)
            printed = len(rows)
            if launch.poll() is not None:
                why = 'roslaunch exited (%s)' % launch.returncode
                break
            if time.monotonic() >= end:
                break
            time.sleep(min(SAMPLE_S, max(0.0, end - time.monotonic())))
        rospy.signal_shutdown('soak over')
    if why is None and len(samples) < 3:
        why = 'too few samples'
    return samples, why


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--minutes', type=float, default=10.0, help='wall minutes to run')
    parser.add_argument(
        '--warmup',
        type=float,
        default=None,
        help='wall seconds left out of the goals (default 60, or a quarter of a shorter run)',
    )
    parser.add_argument('--out', default=repo_root(), help='where bench/ and BENCHMARKS.md go')
    parser.add_argument(
        '--rewrite',
        action='store_true',
        help='no run: redo the plot and the BENCHMARKS.md section from bench/soak.json',
    )
    args = parser.parse_args(argv)
    if args.rewrite:
        with open(os.path.join(args.out, 'bench', 'soak.json')) as f:
            result = json.load(f)
        write_plot(
            result['samples'],
            result['minutes'],
            result['figures']['warmup_s'],
            os.path.join(args.out, 'bench', 'soak.png'),
        )
        replace_section(os.path.join(args.out, 'BENCHMARKS.md'), markdown(result))
        return 0
    if args.minutes <= 0:
        parser.error('--minutes must be positive, not %g' % args.minutes)
    warmup = args.warmup if args.warmup is not None else min(60.0, 15.0 * args.minutes)
    if not 0 <= warmup < 60.0 * args.minutes:
        parser.error(
            '--warmup %g s must be shorter than the run (%g s)' % (warmup, 60.0 * args.minutes)
        )
    source = source_state()
    samples, why = run(args.minutes, warmup)
    if why:
        print('soak: FAILED: %s' % why, file=sys.stderr)
        if len(samples) < 3 or samples[-1]['t'] <= warmup:
            return 1
    minutes = minute_rows(samples)
    fig = judge(samples, warmup)
    lines = summary_lines(fig, minutes)
    print('\n'.join(lines))
    from .probes import machine

    result = {
        'machine': machine(),
        'minutes_asked': args.minutes,
        'stopped_early': why,
        'source': source,
        'figures': fig,
        'minutes': minutes,
        'samples': samples,
    }
    os.makedirs(os.path.join(args.out, 'bench'), exist_ok=True)
    with open(os.path.join(args.out, 'bench', 'soak.json'), 'w') as f:
        json.dump(result, f, indent=1, sort_keys=True)
    write_plot(samples, minutes, warmup, os.path.join(args.out, 'bench', 'soak.png'))
    if minutes:
        replace_section(os.path.join(args.out, 'BENCHMARKS.md'), markdown(result))
    ok = fig['rtf_ok'] and fig['rss_ok'] and not why
    print(
        'soak: %s (bench/soak.json, bench/soak.png, BENCHMARKS.md)'
        % ('every goal met' if ok else 'FAILED')
    )
    return 0 if ok else 1


if __name__ == '__main__':
    sys.exit(main())
