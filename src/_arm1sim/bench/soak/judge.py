"""The soak's figures from its samples: per window and per minute, and the goals' verdicts
(real-time factor within 0.1 % of 1, world RSS growing less than 5 % after the warm-up)."""

import os
import statistics
from typing import Dict, List

RTF_TOLERANCE = 0.001  # the goal: sim time within 0.1 % of wall time
RSS_GROWTH_LIMIT = 0.05  # the goal: world RSS grows less than 5 % after the warm-up


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
