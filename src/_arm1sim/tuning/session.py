"""``tune`` on a simulated robot: measure the gains in force, search for better ones,
check what was found in a fresh simulation, save it and plot both."""

from __future__ import annotations

import argparse
import sys
import time
from typing import IO, Any, Dict, List, Optional, Tuple

from .evaluator import Evaluator
from .inputs import Setup
from .report import RunsByPose, SearchProgress, failing, intro, report, snippet
from .save import save_params, with_gains
from .search import GainSearch, SearchSpace
from .steps import Protocol, StepRig

Gains = Dict[str, Dict[str, Any]]  # joint -> its gains


def measure_all(rig: StepRig, joints: List[str], protocol: Protocol) -> RunsByPose:
    """``[{joint: StepRun}]``, one dict per start pose of the protocol."""
    return [{j: rig.run(j, v) for j in joints} for v in protocol.variants()]


def selection_problem(rig: StepRig, joints: List[str], protocol: Protocol) -> Optional[str]:
    """Why the joints to tune or the start poses do not fit the robot, or None."""
    unknown = [j for j in joints if j not in rig.controllers]
    if unknown:
        return 'no position controller for %s (have: %s)' % (
            ', '.join(unknown),
            ', '.join(rig.joints),
        )
    posed = sorted({j for v in protocol.variants() for j in v.start} - set(rig.hw.handles))
    if posed:
        return 'a start pose names %s, not an actuated joint of %s (have: %s)' % (
            ', '.join(posed),
            rig.model.name,
            ', '.join(rig.joints),
        )
    return None


def search_gains(
    setup: Setup,
    rig: StepRig,
    joints: List[str],
    current: Gains,
    evaluator: Evaluator,
    args: argparse.Namespace,
) -> Gains:
    """The search's best gain set (progress on stderr); closes the evaluator."""
    effort = {j: rig.hw.handles[j].limits.effort for j in rig.joints}
    bar = SearchProgress(sys.stderr)
    search = GainSearch(
        evaluator,
        joints,
        current,
        effort,
        setup.protocol,
        setup.criteria,
        SearchSpace(),
        args.generations,
        args.population,
        seed=args.seed,
        progress=bar,
    )
    try:
        return search.run()
    finally:
        bar.close()
        evaluator.close()


def check_gains(
    setup: Setup, rig: StepRig, joints: List[str], found: Gains
) -> Tuple[Dict[str, Any], RunsByPose, Gains]:
    """An independent check: a fresh simulation loaded from the parameters with ``found``.
    Returns those parameters, its runs and the gains it runs with."""
    params = with_gains(setup.params, rig.namespace, rig.controllers, found)
    check = setup.rig(params)
    try:
        return (
            params,
            measure_all(check, joints, setup.protocol),
            {j: dict(check.gains[j]) for j in check.joints},
        )
    finally:
        check.close()


def tune(args: argparse.Namespace, setup: Setup, out: IO[str]) -> int:
    t0 = time.monotonic()
    # fork the search's workers before this process builds a world of its own
    evaluator = Evaluator(setup.rig, args.workers or 0, args.ray) if args.search else None
    rig = setup.rig()
    try:
        joints = args.joints.split(',') if args.joints else rig.joints
        problem = selection_problem(rig, joints, setup.protocol)
        if problem:
            print('tune: %s' % problem, file=sys.stderr)
            return 2
        intro(
            rig.model.name,
            setup.urdf_path,
            setup.controllers_path,
            rig.namespace,
            setup.protocol,
            setup.criteria,
            out,
        )
        current = {j: dict(rig.gains[j]) for j in rig.joints}
        before = measure_all(rig, joints, setup.protocol)
        report(
            'current gains (%s):' % setup.controllers_path,
            before,
            current,
            setup.criteria,
            setup.protocol,
            out,
        )
        after = None
        if evaluator is not None:
            found = search_gains(setup, rig, joints, current, evaluator, args)
            params, after, found_full = check_gains(setup, rig, joints, found)
            report(
                'found gains (%d runs in %.1f s), checked in a fresh simulation:'
                % (evaluator.runs, time.monotonic() - t0),
                after,
                found_full,
                setup.criteria,
                setup.protocol,
                out,
            )
            bad = failing(after, setup.criteria)
            print(
                '\n%s'
                % (
                    'all joints meet the criteria'
                    if not bad
                    else 'NOT met for %s: the best found is shown' % ', '.join(bad)
                ),
                file=out,
            )
            print('\n# for config/controllers.yaml (tune --search, seed %d):' % args.seed, file=out)
            print(snippet(rig.namespace, rig.controllers, found_full), file=out)
            if args.save:
                save_params(args.save, params, setup.protocol)
                print('wrote %s' % args.save, file=out)
        if args.plot:
            from .plot import plot_runs

            # the first start pose's runs: one figure per joint, current against found
            paths = plot_runs(
                args.plot, before[0], after[0] if after else None, setup.protocol.variants()[0]
            )
            print('\nplots: %s' % ', '.join(paths), file=out)
        print('done in %.1f s' % (time.monotonic() - t0), file=out)
        return 0
    finally:
        rig.close()
        if evaluator is not None:
            evaluator.close()
