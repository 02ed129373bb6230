"""bench/soak.png: drift, memory, threads and rates over the soak."""

import os
from typing import List


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
