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
import sys
from typing import List, Optional

from ...paths import repo_root
from ..probes import source_state
from .judge import judge, minute_rows
from .plot import write_plot
from .report import markdown, replace_section, summary_lines
from .run import run


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(
        prog='python -m _arm1sim.bench.soak', description=__doc__.splitlines()[0]
    )
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
    from ..probes import machine

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
