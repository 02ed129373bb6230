"""``tune --bag``: the steps of a recorded run (a rosbag), measured like simulated ones."""

from __future__ import annotations

import argparse
from typing import IO

from .inputs import Setup
from .recorded import recorded_steps
from .report import HEADER, recorded_rows


def run_bag(args: argparse.Namespace, setup: Setup, out: IO[str]) -> int:
    """Print every step found in ``args.bag`` with its metrics and verdict."""
    from ..ros.tools.bag import read_run

    rig = setup.rig()  # for the namespace, the controllers and the joint limits
    try:
        namespace = args.namespace or rig.namespace
        controllers = {c: j for j, c in rig.controllers.items()}
        limits = {j: rig.limits(j) for j in rig.joints}
    finally:
        rig.close()
    data = read_run(args.bag, namespace, controllers)
    print(
        'steps in %s (namespace %s; command changes >= %g rad held >= 0.5 s)'
        % (args.bag, namespace, args.min_step),
        file=out,
    )
    print(HEADER.replace('step ', 't    '), file=out)
    found = 0
    for joint in sorted(data):
        commands, samples = data[joint]
        lo, hi = limits[joint]
        steps = recorded_steps(commands, samples, lo, hi, args.min_step)
        for row in recorded_rows(joint, steps, setup.criteria):
            print(row, file=out)
        found += len(steps)
    if not found:
        print(
            'no steps found (commands must change by >= %g rad and then hold)' % args.min_step,
            file=out,
        )
    return 0
