"""The benchmark's plot (bench/bench.png) from results.json's data."""

from __future__ import annotations

import os

from .report import Results


def write_plot(results: Results, path: str) -> None:
    import matplotlib

    matplotlib.use('Agg')
    import matplotlib.pyplot as plt

    raw = results['raw']
    fig, axes = plt.subplots(1, 4, figsize=(21, 4))
    arms = (1, 2, 4, 8, 16)
    keys = [k for k in ['bare'] + ['standin_%d' % n for n in arms] if k in raw]
    labels = [
        'bare\npybullet' if k == 'bare' else '%s arm%s' % (k[8:], '' if k == 'standin_1' else 's')
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
        if 'seed_goal' in raw:
            seed = sorted(r['cpu_core_fraction'] for r in raw['seed_goal'])
            axes[1].bar(
                ['robot_spawn.launch\n(cores, all)'], [seed[len(seed) // 2]], color='tab:red'
            )
            axes[1].axhline(0.5, color='tab:red', lw=1, ls='--')
        axes[1].set_title('At real time (goal lines dashed)')
    scaled = [(n, results['figures'].get('scaling_%d' % n, {}).get('median')) for n in arms]
    scaled = [(1, 1.0)] + [(n, v) for n, v in scaled[1:] if v is not None]
    if len(scaled) > 1:
        axes[2].plot([n for n, _ in scaled], [v for _, v in scaled], 'o-', color='tab:blue')
        axes[2].axhline(0.8, color='tab:orange', lw=1, ls='--', label='goal at 8 arms (0.8)')
        axes[2].axhline(1.0, color='tab:gray', lw=1, ls=':', label='linear')
        axes[2].set_xscale('log', base=2)
        axes[2].set_xticks(arms, [str(n) for n in arms])
        axes[2].set_xlabel('arms in one world')
        axes[2].set_ylabel("N × steps/s ÷ 1 arm's steps/s")
        axes[2].set_ylim(0, 1.3)
        axes[2].set_title('Scaling (1 = linear)')
        axes[2].legend()
    frames = results['figures'].get('render', {})
    sizes = ('320x240', '640x480', '800x800')
    for i, name in enumerate(('gl', 'egl', 'tiny')):
        ms = [frames.get('%s_%s_ms' % (name, size), {}).get('median') for size in sizes]
        if all(v is not None for v in ms):
            xs = [x + (i - 1) * 0.27 for x in range(len(sizes))]
            axes[3].bar(xs, ms, width=0.27, label=name + (' (default)' if name == 'gl' else ''))
    if frames:
        axes[3].axhline(8.0, color='tab:orange', lw=1, ls='--', label='goal at 640x480 (8 ms)')
        axes[3].set_xticks(range(len(sizes)), sizes)
        axes[3].set_ylabel('ms per frame (median)')
        axes[3].set_title('Camera frame per renderer, no GPU')
        axes[3].legend()
    fig.tight_layout()
    os.makedirs(os.path.dirname(path), exist_ok=True)
    fig.savefig(path, dpi=100)
    plt.close(fig)
