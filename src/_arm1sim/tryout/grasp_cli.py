"""rosrun arm1 try_grasp: a vendor gripper picks a box on the stand-in, its package unchanged.

    rosrun arm1 try_grasp omx ~/src/open_manipulator_simulations \\
        --also ~/src/open_manipulator open_manipulator_gazebo open_manipulator_gazebo.launch
    rosrun arm1 try_grasp jaco ~/src/kinova-ros kinova_gazebo robot_launch.launch
    rosrun arm1 try_grasp panda ~/src/franka_ros franka_gazebo panda.launch \\
        controller:=effort_joint_trajectory_controller

Builds and brings the robot up as try_robot does, then per try: a box between the open fingers
(on a thin static column), the gripper closed and the arm lifted through the package's own
controllers, a 5 s hold, rise and slip judged (>= 40 mm, >= 95 % of the gripper's rise,
<= 2 mm slip). Exit status 0 when every try lifted.
"""

import argparse
import dataclasses
import sys
from typing import List, Optional

from _arm1sim.tryout import cli, grasp


def parse_args(argv: Optional[List[str]]) -> argparse.Namespace:
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv or argv[0] not in grasp.GRIPPERS:
        raise SystemExit(
            'try_grasp: the first argument names the robot: %s' % ', '.join(grasp.GRIPPERS)
        )
    robot, rest = argv[0], argv[1:]
    own = argparse.ArgumentParser(add_help=False)
    own.add_argument('--tries', type=int, default=3)
    own.add_argument(
        '--size', type=float, help='box edge (m); 0.03 for omx and tb3_omx, 0.04 for jaco, panda'
    )
    own.add_argument('--mass', type=float, default=0.03, help='box mass (kg)')
    own.add_argument('--mu', type=float, default=1.0, help="box's <mu1>/<mu2>")
    own.add_argument(
        '--offset', type=float, nargs=3, help="box from the fingers' centroid (palm frame, m)"
    )
    own.add_argument('--lift', type=float, nargs='+', help='arm pose change that lifts (rad)')
    own.add_argument('--closed', type=float, nargs='+', help='gripper command that closes it')
    mine, rest = own.parse_known_args(rest)
    a = cli.parse_args(rest)
    for k, v in vars(mine).items():
        setattr(a, k, v)
    a.robot = robot
    return a


def profile(a: argparse.Namespace) -> grasp.Gripper:
    """The robot's profile with the command line's --lift and --closed (or, for a franka
    grasp, --size: the grasp names the object's width)."""
    g = grasp.GRIPPERS[a.robot]
    if a.lift:
        if len(a.lift) != len(g.arm_joints):
            raise SystemExit(
                'try_grasp: --lift takes %d values (%s)'
                % (len(g.arm_joints), ', '.join(g.arm_joints))
            )
        g = dataclasses.replace(g, lift=tuple(a.lift))
    if a.closed:
        if len(a.closed) != len(g.closed_position):
            raise SystemExit('try_grasp: --closed takes %d values' % len(g.closed_position))
        g = dataclasses.replace(g, closed_position=tuple(a.closed))
    elif g.kind == 'franka' and a.size:
        g = dataclasses.replace(g, closed_position=(a.size,))
    return g


def main(argv: Optional[List[str]] = None) -> int:
    a = parse_args(argv)
    g = profile(a)

    def work(progress: cli.Progress) -> dict:
        from _arm1sim.tryout import grasp_ros

        return grasp_ros.tries(g, a, progress)

    rep = cli.run(a, work, tool='try_grasp')
    from _arm1sim.tryout import report

    sys.stdout.write(report.text(rep))
    return 0 if rep['verdict']['ok'] else 1
