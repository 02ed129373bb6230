"""``rosrun arm1 tune``: step responses of a robot's position controllers, and a gain search.

Runs headless, at top speed, without a ROS master: the same Simulation,
ControllerManager, JointPositionController and Pid as ``roslaunch arm1
gazebo.launch``, with parameters from the controllers yaml (see steps.py for the
step protocol, metrics.py for the figures). ``--bag`` measures a recorded run
instead.
"""
import argparse
import copy
import math
import os
import sys
import time

import yaml

from .. import xacro_bridge
from .metrics import BAND, FINAL_WINDOW, Criteria
from .search import Evaluator, GainSearch, ProgressBar, SearchSpace, fmt_time, score
from .steps import ARM1_POSES, ARM1_START, Protocol, StepRig, pose_text, yaml_pid

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))


def _arm1(rel):
    try:
        base = xacro_bridge.find_package('arm1')
    except Exception:
        base = ROOT
    return os.path.join(base, rel)


def find_package(name):
    try:
        return xacro_bridge.find_package(name)
    except Exception:
        raise LookupError(name)


def parse_args(argv):
    ap = argparse.ArgumentParser(prog='tune', description=(
        "Step responses of a robot's effort position controllers in a headless simulation "
        '(rise time, overshoot, 2 %% settling time, steady-state error, jitter), and a search '
        'for gains that settle fastest with little overshoot and no jitter.'))
    ap.add_argument('--urdf', help='robot description: URDF or xacro file (default: arm1)')
    ap.add_argument('--xacro-arg', action='append', default=[], metavar='NAME:=VALUE',
                    help='xacro argument for --urdf (repeatable)')
    ap.add_argument('--controllers', help='controllers yaml, as for rosparam load '
                    '(default: arm1 config/controllers.yaml)')
    ap.add_argument('--world', help='SDF world (default: arm1 worlds/willow_garage.world for '
                    'arm1, an empty world otherwise)')
    ap.add_argument('--joints', help='comma-separated joints to test (default: all with a '
                    'position controller)')
    ap.add_argument('--start', action='append', default=[], metavar='JOINT=RAD',
                    help='start pose (repeatable; default for arm1: joint2=%g, others 0)'
                    % ARM1_START['joint2'])
    ap.add_argument('--pose', action='append', metavar='JOINT=RAD[,JOINT=RAD...]',
                    help='another start pose to step from, joints not named at 0 (repeatable; '
                    'default for arm1: %s; "none" for the start pose only)'
                    % ','.join('%s=%g' % kv for kv in sorted(ARM1_POSES[0].items())))
    ap.add_argument('--step', type=float, default=Protocol.step, help='step size, rad (%(default)s)')
    ap.add_argument('--settle', type=float, default=Protocol.settle,
                    help='s of holding before the first step (%(default)s)')
    ap.add_argument('--hold', type=float, default=Protocol.hold,
                    help='s after each step (%(default)s)')
    ap.add_argument('--max-overshoot', type=float, default=Criteria.max_overshoot,
                    help='%% (%(default)s)')
    ap.add_argument('--max-jitter', type=float, default=Criteria.max_jitter,
                    help='rad peak to peak once settled (%(default)s)')
    ap.add_argument('--search', action='store_true', help='search for better gains')
    ap.add_argument('--generations', type=int, default=14,
                    help='search generations (%(default)s)')
    ap.add_argument('--population', type=int, default=16,
                    help='gain sets tried per generation (%(default)s)')
    ap.add_argument('--workers', type=int, default=min(2, os.cpu_count() or 1),
                    help='processes for the search (%(default)s)')
    ap.add_argument('--seed', type=int, default=0, help='random seed of the search')
    ap.add_argument('--plot', metavar='DIR', help='write PNG plots of the responses to DIR')
    ap.add_argument('--save', metavar='YAML', help='write the controllers yaml with the found '
                    'gains to this file')
    ap.add_argument('--bag', help='measure the steps of a recorded run (rosbag of joint_states '
                    'and the controllers\' command topics) instead of simulating')
    ap.add_argument('--namespace', help='robot namespace in the bag (default: from the yaml)')
    ap.add_argument('--min-step', type=float, default=0.05,
                    help='with --bag: smallest command change that counts as a step, rad')
    return ap.parse_args(argv)


class Setup:
    """What the arguments name: description, parameters, world, protocol."""

    def __init__(self, args):
        self.arm1 = args.urdf is None
        urdf_path = args.urdf or _arm1('urdf/arm1.urdf.xacro')
        self.urdf_path = urdf_path
        if urdf_path.endswith('.xacro'):
            mappings = dict(a.split(':=', 1) for a in args.xacro_arg)
            self.urdf = xacro_bridge.expand(urdf_path, mappings)
        else:
            with open(urdf_path) as f:
                self.urdf = f.read()
        self.controllers_path = args.controllers or _arm1('config/controllers.yaml')
        with open(self.controllers_path) as f:
            self.params = yaml.safe_load(f) or {}
        self.world = args.world or (_arm1('worlds/willow_garage.world') if self.arm1 else None)
        start = dict(ARM1_START) if self.arm1 else {}
        start.update(parse_pose(args.start))
        if args.pose is None:
            poses = [dict(p) for p in ARM1_POSES] if self.arm1 else []
        else:
            poses = [parse_pose(p.split(',')) for p in args.pose if p.strip() != 'none']
        self.protocol = Protocol(start, args.step, args.settle, args.hold, poses)
        self.criteria = Criteria(args.max_overshoot, args.max_jitter)

    def rig(self, params=None):
        return StepRig(self.urdf, params or self.params, self.world, find_package)


def parse_pose(items):
    """``['joint2=0.6', 'joint3=0.5']`` -> ``{'joint2': 0.6, 'joint3': 0.5}``."""
    pose = {}
    for item in items:
        joint, sep, value = item.partition('=')
        try:
            pose[joint.strip()] = float(value)
        except ValueError:
            raise SystemExit("tune: a pose is JOINT=RAD, not '%s'" % item)
        if not sep or not joint.strip():
            raise SystemExit("tune: a pose is JOINT=RAD, not '%s'" % item)
    return pose


def with_gains(params, namespace, controllers, gains):
    """A copy of the parameter tree with each controller's ``pid`` replaced."""
    out = copy.deepcopy(params)
    node = out
    for part in [p for p in namespace.split('/') if p]:
        node = node.setdefault(part, {})
    for joint, cname in controllers.items():
        if joint in gains:
            node[cname]['pid'] = yaml_pid(gains[joint])
    return out


# --------------------------------------------------------------------------- reporting
HEADER = '%-8s %-5s %8s %8s %8s %10s %9s %9s  %s' % (
    'joint', 'step', 'start', 'target', 'rise', 'overshoot', 'settle', 'sse', 'jitter')


def verdict(run, criteria):
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


def metric_rows(joint, run, criteria):
    rows = []
    for name, m in zip(('out', 'back'), run.metrics):
        rows.append('%-8s %-5s %+8.3f %+8.3f %8s %9.1f%% %9s %+9.4f  %.2g rad' % (
            joint, name, m.start, m.target,
            '%.3f s' % m.rise_time if not math.isnan(m.rise_time) else '-',
            m.overshoot, fmt_time(m.settling_time), m.steady_state_error, m.jitter))
    rows.append('%-8s %s (other joints moved up to %.3f rad)' % (
        '', verdict(run, criteria), run.others_wobble))
    return rows


def gains_text(g):
    return 'p %.4g, i %.4g, d %.4g, i_clamp %.4g%s' % (
        g['p'], g['i'], g['d'], g['i_clamp_max'], ', antiwindup' if g.get('antiwindup') else '')


def measure_all(rig, joints, protocol):
    """``[{joint: StepRun}]``, one dict per start pose of the protocol."""
    return [{j: rig.run(j, v) for j in joints} for v in protocol.variants()]


def report(title, runs_by_pose, gains, criteria, protocol, out):
    print('\n%s' % title, file=out)
    for j in runs_by_pose[0]:
        print('%-8s %s' % (j, gains_text(gains[j])), file=out)
    for variant, runs in zip(protocol.variants(), runs_by_pose):
        print('start pose %s:' % pose_text(variant.start), file=out)
        print(HEADER, file=out)
        for j, run in runs.items():
            for row in metric_rows(j, run, criteria):
                print(row, file=out)


def failing(runs_by_pose, criteria):
    """Joints whose runs miss the criteria from any start pose."""
    return sorted({j for runs in runs_by_pose for j, run in runs.items()
                   if verdict(run, criteria) != 'ok'})


def snippet(namespace, controllers, gains):
    ns = namespace.strip('/')
    lines = ['%s:' % ns]
    for joint in sorted(controllers):
        pid = yaml_pid(gains[joint])
        inner = ', '.join('%s: %s' % (k, ('true' if v is True else repr(v))) for k, v in pid.items())
        lines += ['  %s:' % controllers[joint],
                  '    type: effort_controllers/JointPositionController',
                  '    joint: %s' % joint,
                  '    pid: {%s}' % inner]
    return '\n'.join(lines)


# --------------------------------------------------------------------------- main
def run_bag(args, setup, out):
    from ..ros.bag import read_run
    from .recorded import recorded_steps
    rig = setup.rig()
    try:
        namespace = args.namespace or rig.namespace
        controllers = {c: j for j, c in rig.controllers.items()}
        limits = {j: rig.limits(j) for j in rig.joints}
    finally:
        rig.close()
    data = read_run(args.bag, namespace, controllers)
    print('steps in %s (namespace %s; command changes >= %g rad held >= 0.5 s)' % (
        args.bag, namespace, args.min_step), file=out)
    print(HEADER.replace('step ', 't    '), file=out)
    found = 0
    for joint in sorted(data):
        commands, samples = data[joint]
        lo, hi = limits[joint]
        for t, m in recorded_steps(commands, samples, lo, hi, args.min_step):
            found += 1
            print('%-8s %5.1f %+8.3f %+8.3f %8s %9.1f%% %9s %+9.4f  %.2g rad  %s' % (
                joint, t, m.start, m.target,
                '%.3f s' % m.rise_time if not math.isnan(m.rise_time) else '-', m.overshoot,
                fmt_time(m.settling_time), m.steady_state_error, m.jitter,
                'ok' if setup.criteria.ok(m) else 'NOT ok'), file=out)
    if not found:
        print('no steps found (commands must change by >= %g rad and then hold)' % args.min_step,
              file=out)
    return 0


def main(argv=None, out=sys.stdout):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    setup = Setup(args)
    if args.bag:
        return run_bag(args, setup, out)
    t0 = time.monotonic()
    evaluator = None
    if args.search:  # fork the workers before this process builds a world of its own
        evaluator = Evaluator(setup.rig, args.workers)
    rig = setup.rig()
    try:
        joints = args.joints.split(',') if args.joints else rig.joints
        unknown = [j for j in joints if j not in rig.controllers]
        if unknown:
            print('tune: no position controller for %s (have: %s)' % (
                ', '.join(unknown), ', '.join(rig.joints)), file=sys.stderr)
            return 2
        posed = sorted({j for v in setup.protocol.variants() for j in v.start} - set(rig.hw.handles))
        if posed:
            print('tune: a start pose names %s, not an actuated joint of %s (have: %s)' % (
                ', '.join(posed), rig.model.name, ', '.join(rig.joints)), file=sys.stderr)
            return 2
        print('robot %s (%s), controllers %s, namespace %s' % (
            rig.model.name, setup.urdf_path, setup.controllers_path, rig.namespace), file=out)
        print('protocol: %s' % setup.protocol.describe(), file=out)
        print('metrics: rise 10-90 %%, overshoot in %% of the step, settling into +-%g %% of the '
              'step, sse and jitter (peak to peak) over the last %g s of each hold; ok = '
              'settled, overshoot <= %g %%, jitter <= %g rad' % (
                  BAND * 100, FINAL_WINDOW, setup.criteria.max_overshoot,
                  setup.criteria.max_jitter), file=out)
        current = {j: dict(rig.gains[j]) for j in rig.joints}
        before = measure_all(rig, joints, setup.protocol)
        report('current gains (%s):' % setup.controllers_path, before, current, setup.criteria,
               setup.protocol, out)
        found = None
        if args.search:
            effort = {j: rig.hw.handles[j].limits.effort for j in rig.joints}
            bar = ProgressBar(sys.stderr)
            search = GainSearch(evaluator, joints, current, effort, setup.protocol,
                                setup.criteria, SearchSpace(), args.generations,
                                args.population, seed=args.seed, progress=bar)
            try:
                found = search.run()
            finally:
                bar.finish()
                evaluator.close()
            # independent check: a fresh simulation loaded from the new parameters
            new_params = with_gains(setup.params, rig.namespace, rig.controllers, found)
            check = setup.rig(new_params)
            try:
                after = measure_all(check, joints, setup.protocol)
                found_full = {j: dict(check.gains[j]) for j in check.joints}
            finally:
                check.close()
            report('found gains (%d runs in %.1f s), checked in a fresh simulation:' % (
                evaluator.runs, time.monotonic() - t0), after, found_full, setup.criteria,
                setup.protocol, out)
            bad = failing(after, setup.criteria)
            print('\n%s' % ('all joints meet the criteria' if not bad else
                            'NOT met for %s: the best found is shown' % ', '.join(bad)), file=out)
            print('\n# for config/controllers.yaml (tune --search, seed %d):' % args.seed, file=out)
            print(snippet(rig.namespace, rig.controllers, found_full), file=out)
            if args.save:
                with open(args.save, 'w') as f:
                    f.write('# Gains found by `rosrun arm1 tune --search` (%s).\n'
                            % setup.protocol.describe())
                    yaml.safe_dump(new_params, f, default_flow_style=None, sort_keys=False)
                print('wrote %s' % args.save, file=out)
        if args.plot:
            from .plot import plot_runs
            # the first start pose's runs: one figure per joint, current against found
            paths = plot_runs(args.plot, before[0], after[0] if found else None,
                              setup.protocol.variants()[0])
            print('\nplots: %s' % ', '.join(paths), file=out)
        print('done in %.1f s' % (time.monotonic() - t0), file=out)
        return 0
    finally:
        rig.close()


if __name__ == '__main__':
    sys.exit(main())
