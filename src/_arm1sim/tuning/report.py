"""What ``tune`` prints: the metrics table, verdicts, gains, the yaml snippet, and the
search's progress bar (tqdm)."""

from __future__ import annotations

import math
from typing import IO, Any, Dict, List, Mapping, Optional, Sequence

from tqdm import tqdm

from .metrics import BAND, FINAL_WINDOW, Criteria, StepMetrics
from .search import fmt_time, score
from .steps import Protocol, StepRun, pose_text, yaml_pid

Gains = Mapping[str, Any]  # one joint's: p, i, d, i_clamp_max, i_clamp_min, antiwindup
RunsByPose = List[Dict[str, StepRun]]  # per start pose of the protocol: joint -> run

HEADER = '%-8s %-5s %8s %8s %8s %10s %9s %9s  %s' % (
    'joint',
    'step',
    'start',
    'target',
    'rise',
    'overshoot',
    'settle',
    'sse',
    'jitter',
)


def verdict(run: StepRun, criteria: Criteria) -> str:
    """'ok', or what is wrong: whether the joint shakes (jitters, or leaves the other
    joints jittering), does not settle, or only overshoots."""
    feasible, _, w, fails = score(run.metrics, criteria, 0.0, run.others_jitter)
    if feasible:
        return 'ok'
    if w.jitter > criteria.max_jitter:  # score folds the other joints' jitter in
        return 'NOT ok, shakes: ' + '; '.join(fails)
    if not criteria.steady(w):
        return 'NOT ok: ' + '; '.join(fails)
    return 'does not shake, but ' + '; '.join(fails)


def rise_text(m: StepMetrics) -> str:
    return '%.3f s' % m.rise_time if not math.isnan(m.rise_time) else '-'


def metric_columns(m: StepMetrics) -> str:
    """A step's start, target, rise, overshoot, settling, steady-state error and jitter."""
    return '%+8.3f %+8.3f %8s %9.1f%% %9s %+9.4f  %.2g rad' % (
        m.start,
        m.target,
        rise_text(m),
        m.overshoot,
        fmt_time(m.settling_time),
        m.steady_state_error,
        m.jitter,
    )


def metric_rows(joint: str, run: StepRun, criteria: Criteria) -> List[str]:
    rows = []
    for name, m in zip(('out', 'back'), run.metrics):
        rows.append('%-8s %-5s %s' % (joint, name, metric_columns(m)))
    rows.append(
        '%-8s %s (other joints moved up to %.3f rad)'
        % ('', verdict(run, criteria), run.others_wobble)
    )
    return rows


def gains_text(g: Gains) -> str:
    return 'p %.4g, i %.4g, d %.4g, i_clamp %.4g%s' % (
        g['p'],
        g['i'],
        g['d'],
        g['i_clamp_max'],
        ', antiwindup' if g.get('antiwindup') else '',
    )


def intro(
    model: str,
    urdf_path: str,
    controllers_path: str,
    namespace: str,
    protocol: Protocol,
    criteria: Criteria,
    out: IO[str],
) -> None:
    """What is tuned, with which protocol, and what the figures mean."""
    print(
        'robot %s (%s), controllers %s, namespace %s'
        % (model, urdf_path, controllers_path, namespace),
        file=out,
    )
    print('protocol: %s' % protocol.describe(), file=out)
    print(
        'metrics: rise 10-90 %%, overshoot in %% of the step, settling into +-%g %% of the '
        'step, sse and jitter (peak to peak) over the last %g s of each hold; ok = '
        'settled, overshoot <= %g %%, jitter <= %g rad'
        % (BAND * 100, FINAL_WINDOW, criteria.max_overshoot, criteria.max_jitter),
        file=out,
    )


def report(
    title: str,
    runs_by_pose: RunsByPose,
    gains: Mapping[str, Gains],
    criteria: Criteria,
    protocol: Protocol,
    out: IO[str],
) -> None:
    print('\n%s' % title, file=out)
    for j in runs_by_pose[0]:
        print('%-8s %s' % (j, gains_text(gains[j])), file=out)
    for variant, runs in zip(protocol.variants(), runs_by_pose):
        print('start pose %s:' % pose_text(variant.start), file=out)
        print(HEADER, file=out)
        for j, run in runs.items():
            for row in metric_rows(j, run, criteria):
                print(row, file=out)


def failing(runs_by_pose: RunsByPose, criteria: Criteria) -> List[str]:
    """Joints whose runs miss the criteria from any start pose."""
    return sorted(
        {j for runs in runs_by_pose for j, run in runs.items() if verdict(run, criteria) != 'ok'}
    )


def snippet(namespace: str, controllers: Mapping[str, str], gains: Mapping[str, Gains]) -> str:
    """The controllers yaml lines of the gains, for config/controllers.yaml."""
    ns = namespace.strip('/')
    lines = ['%s:' % ns]
    for joint in sorted(controllers):
        pid = yaml_pid(gains[joint])
        inner = ', '.join(
            '%s: %s' % (k, ('true' if v is True else repr(v))) for k, v in pid.items()
        )
        lines += [
            '  %s:' % controllers[joint],
            '    type: effort_controllers/JointPositionController',
            '    joint: %s' % joint,
            '    pid: {%s}' % inner,
        ]
    return '\n'.join(lines)


class SearchProgress:
    """GainSearch's ``progress(done, total, text)`` as a tqdm bar on ``stream``; on a stream
    that is no terminal (a log), a line every 2 s at most."""

    def __init__(self, stream: IO[str]) -> None:
        self.stream = stream
        self.bar: Optional[tqdm] = None  # drawn from the first report on, when total is known

    def __call__(self, done: int, total: int, text: str) -> None:
        if self.bar is None:
            tty = hasattr(self.stream, 'isatty') and self.stream.isatty()
            self.bar = tqdm(
                total=total,
                file=self.stream,
                unit='set',
                dynamic_ncols=True,
                mininterval=0.1 if tty else 2.0,
            )
        self.bar.set_postfix_str(text, refresh=False)
        self.bar.update(done - self.bar.n)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def recorded_rows(joint: str, steps: Sequence[Any], criteria: Criteria) -> List[str]:
    """Rows of the steps found in a recorded run: ``[(t, StepMetrics)]`` of one joint."""
    return [
        '%-8s %5.1f %s  %s' % (joint, t, metric_columns(m), 'ok' if criteria.ok(m) else 'NOT ok')
        for t, m in steps
    ]
