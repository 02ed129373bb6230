"""PNG plots of step runs (matplotlib, Agg backend: no display needed)."""

import os

import matplotlib

matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402

from .metrics import BAND  # noqa: E402


def _band(ax, run, color):
    for name, t_step, start, target in run.steps:
        tol = BAND * abs(target - start)
        ax.axhspan(target - tol, target + tol, color=color, alpha=0.08)


def plot_runs(directory, before, after=None, protocol=None):
    """One PNG per joint (position and effort, current gains against found ones) and an
    overview; returns the paths."""
    os.makedirs(directory, exist_ok=True)
    paths = []
    for joint, run in before.items():
        fig, (ax, ax_e) = plt.subplots(
            2, 1, figsize=(9, 6), sharex=True, gridspec_kw={'height_ratios': [3, 1]}
        )
        series = [('current gains', run, 'tab:red')]
        if after and joint in after:
            series.append(('found gains', after[joint], 'tab:blue'))
        target = [(0.0, run.steps[0][2])]
        for _, t_step, _, value in run.steps:
            target += [(t_step, target[-1][1]), (t_step, value)]
        target.append((run.times[-1], target[-1][1]))
        ax.plot([t for t, _ in target], [v for _, v in target], 'k--', lw=1, label='command')
        for label, r, color in series:
            m = r.metrics
            text = ', '.join(
                '%s: %.1f%% / %s'
                % (name, mm.overshoot, '%.2f s' % mm.settling_time if mm.settled else 'not settled')
                for (name, *_), mm in zip(r.steps, m)
            )
            ax.plot(
                r.times,
                r.positions,
                color=color,
                lw=1,
                label='%s (overshoot / settling: %s)' % (label, text),
            )
            ax_e.plot(r.times, r.efforts, color=color, lw=0.6)
            _band(ax, r, color)
        ax.set_ylabel('%s position (rad)' % joint)
        ax.set_title(
            '%s step responses%s'
            % (
                joint,
                ''
                if protocol is None
                else ' (step %g rad, band +-%g %%)' % (protocol.step, BAND * 100),
            )
        )
        ax.legend(fontsize=8, loc='best')
        ax.grid(alpha=0.3)
        ax_e.set_ylabel('effort (N m)')
        ax_e.set_xlabel('time (s)')
        ax_e.grid(alpha=0.3)
        fig.tight_layout()
        path = os.path.join(directory, '%s.png' % joint)
        fig.savefig(path, dpi=90)
        plt.close(fig)
        paths.append(path)
    # overview: every joint's steps, zoomed on the first second after each step
    fig, axes = plt.subplots(len(before), 2, figsize=(10, 2.2 * len(before)), squeeze=False)
    for row, (joint, run) in zip(axes, before.items()):
        for ax, step_index in zip(row, (0, 1)):
            for label, r, color in [('current', run, 'tab:red')] + (
                [('found', after[joint], 'tab:blue')] if after and joint in after else []
            ):
                _, t_step, start, target = r.steps[step_index]
                pts = [
                    (t - t_step, x)
                    for t, x in zip(r.times, r.positions)
                    if t_step - 0.05 <= t <= t_step + 1.0
                ]
                ax.plot([t for t, _ in pts], [x for _, x in pts], color=color, lw=1, label=label)
            ax.axhline(target, color='k', ls='--', lw=0.8)
            ax.set_title('%s %s' % (joint, ('out', 'back')[step_index]), fontsize=9)
            ax.grid(alpha=0.3)
        row[0].legend(fontsize=7)
    fig.tight_layout()
    path = os.path.join(directory, 'overview.png')
    fig.savefig(path, dpi=80)
    plt.close(fig)
    paths.append(path)
    return paths
