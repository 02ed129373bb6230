"""``rosrun arm1 tune``: step responses of a robot's position controllers, and a gain search.

Runs headless, at top speed, without a ROS master: the same Simulation,
ControllerManager, JointPositionController and Pid as ``roslaunch arm1
gazebo.launch``, with parameters from the controllers yaml (see steps.py for the
step protocol, metrics.py for the figures). ``--bag`` measures a recorded run
instead. This module reads the command line and hands over: inputs.py (what the
arguments name), session.py (measure, search, check, save, plot), bag_report.py.
"""

from __future__ import annotations

import argparse
import os
import sys
from typing import IO, List, Optional

from .bag_report import run_bag
from .evaluator import EvaluatorError
from .inputs import Setup
from .metrics import Criteria
from .session import tune
from .steps import ARM1_POSES, ARM1_START, Protocol


def parse_args(argv: List[str]) -> argparse.Namespace:
    ap = argparse.ArgumentParser(
        prog='tune',
        description=(
            "Step responses of a robot's effort position controllers in a headless simulation "
            '(rise time, overshoot, 2 %% settling time, steady-state error, jitter), and a search '
            'for gains that settle fastest with little overshoot and no jitter.'
        ),
    )
    ap.add_argument('--urdf', help='robot description: URDF or xacro file (default: arm1)')
    ap.add_argument(
        '--xacro-arg',
        action='append',
        default=[],
        metavar='NAME:=VALUE',
        help='xacro argument for --urdf (repeatable)',
    )
    ap.add_argument(
        '--controllers',
        help='controllers yaml, as for rosparam load (default: arm1 config/controllers.yaml)',
    )
    ap.add_argument(
        '--world',
        help='SDF world (default: arm1 worlds/willow_garage.world for '
        'arm1, an empty world otherwise)',
    )
    ap.add_argument(
        '--joints', help='comma-separated joints to test (default: all with a position controller)'
    )
    ap.add_argument(
        '--start',
        action='append',
        default=[],
        metavar='JOINT=RAD',
        help='start pose (repeatable; default for arm1: joint2=%g, others 0)'
        % ARM1_START['joint2'],
    )
    ap.add_argument(
        '--pose',
        action='append',
        metavar='JOINT=RAD[,JOINT=RAD...]',
        help='another start pose to step from, joints not named at 0 (repeatable; '
        'default for arm1: %s; "none" for the start pose only)'
        % ','.join('%s=%g' % kv for kv in sorted(ARM1_POSES[0].items())),
    )
    ap.add_argument(
        '--step', type=float, default=Protocol.step, help='step size, rad (%(default)s)'
    )
    ap.add_argument(
        '--settle',
        type=float,
        default=Protocol.settle,
        help='s of holding before the first step (%(default)s)',
    )
    ap.add_argument(
        '--hold', type=float, default=Protocol.hold, help='s after each step (%(default)s)'
    )
    ap.add_argument(
        '--max-overshoot', type=float, default=Criteria.max_overshoot, help='%% (%(default)s)'
    )
    ap.add_argument(
        '--max-jitter',
        type=float,
        default=Criteria.max_jitter,
        help='rad peak to peak once settled (%(default)s)',
    )
    ap.add_argument('--search', action='store_true', help='search for better gains')
    ap.add_argument('--generations', type=int, default=14, help='search generations (%(default)s)')
    ap.add_argument(
        '--population', type=int, default=16, help='gain sets tried per generation (%(default)s)'
    )
    ap.add_argument(
        '--workers',
        type=int,
        help='simulations run at once by the search (default: %d here; with --ray ADDRESS, one '
        'per CPU of the cluster)' % min(2, os.cpu_count() or 1),
    )
    ap.add_argument(
        '--ray',
        metavar='ADDRESS',
        help='run the search\'s simulations on the Ray cluster whose head is at ADDRESS '
        '(HOST:6379, or auto), or on a Ray started here with "local"; the same seed gives '
        'the same gains as without',
    )
    ap.add_argument('--seed', type=int, default=0, help='random seed of the search')
    ap.add_argument('--plot', metavar='DIR', help='write PNG plots of the responses to DIR')
    ap.add_argument(
        '--save',
        metavar='YAML',
        help='write the controllers yaml with the found gains to this file',
    )
    ap.add_argument(
        '--bag',
        help='measure the steps of a recorded run (rosbag of joint_states '
        'and the controllers\' command topics) instead of simulating',
    )
    ap.add_argument('--namespace', help='robot namespace in the bag (default: from the yaml)')
    ap.add_argument(
        '--min-step',
        type=float,
        default=0.05,
        help='with --bag: smallest command change that counts as a step, rad',
    )
    args = ap.parse_args(argv)
    if args.workers is None and args.ray in (None, 'local'):  # a cluster's: its CPU count
        args.workers = min(2, os.cpu_count() or 1)
    return args


def main(argv: Optional[List[str]] = None, out: IO[str] = sys.stdout) -> int:
    args = parse_args(sys.argv[1:] if argv is None else argv)
    setup = Setup(args)
    if args.bag:
        return run_bag(args, setup, out)
    try:
        return tune(args, setup, out)
    except EvaluatorError as exc:
        print('tune: %s' % exc, file=sys.stderr)
        return 2


if __name__ == '__main__':
    sys.exit(main())
