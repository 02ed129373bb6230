"""The soak's report: the lines printed once a minute and at the end, and the Soak section of
BENCHMARKS.md (written in place of the previous one)."""

import os
import statistics
from typing import List

from .judge import RSS_GROWTH_LIMIT, RTF_TOLERANCE
from .probes import SAMPLE_S

SECTION_BEGIN = '<!-- soak: written by make soak (python -m _arm1sim.bench.soak) -->'
SECTION_END = '<!-- soak end -->'


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
        '`make soak SOAK_MINUTES=%g` (`python -m _arm1sim.bench.soak`): `roslaunch arm1 '
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
    from ...sim.pacer import Pacer

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
