"""rosrun arm1 try_robot: build a robot package repository unchanged beside arm1, run its
Gazebo bringup headless on the stand-in, and report what loaded, what moved, what did not.

    rosrun arm1 try_robot ~/src/universal_robot ur_gazebo ur5_bringup.launch gui:=false
    rosrun arm1 try_robot ~/src/open_manipulator_simulations \\
        --also ~/src/open_manipulator open_manipulator_gazebo open_manipulator_gazebo.launch

Writes OUT/report.txt, OUT/report.json, OUT/roslaunch.log, OUT/ros_log/ and the workspace's
build.log; prints the report. Exit status 0 when the bringup came up and every check passed.
"""

import argparse
import datetime
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from typing import Any, Callable, Dict, List, Optional

from _arm1sim.description import safe_xml
from _arm1sim.session.launcher import RosSession, loopback_env
from _arm1sim.tryout import logs, report, workspace


class Progress:
    """One line per step on stderr, with the seconds since the start."""

    def __init__(self) -> None:
        self.t0 = time.monotonic()

    def __call__(self, text: str) -> None:
        sys.stderr.write('try_robot [%5.1f s] %s\n' % (time.monotonic() - self.t0, text))
        sys.stderr.flush()


def parse_args(argv: Optional[List[str]]) -> argparse.Namespace:
    p = argparse.ArgumentParser(
        prog='try_robot', description=__doc__, formatter_class=argparse.RawTextHelpFormatter
    )
    p.add_argument('checkout', help='a checkout of the robot package repository (a path)')
    p.add_argument('package', help='the package holding the launch file')
    p.add_argument('launch', help='the launch file, e.g. ur5_bringup.launch')
    p.add_argument('args', nargs='*', help='launch arguments, name:=value')
    p.add_argument(
        '--also',
        action='append',
        default=[],
        metavar='CHECKOUT',
        help='another checkout whose packages the launch needs (repeatable)',
    )
    p.add_argument(
        '--then',
        nargs=2,
        action='append',
        default=[],
        metavar=('PACKAGE', 'LAUNCH'),
        help='another launch file started once the world is up (e.g. the controllers)',
    )
    p.add_argument(
        '--unignore',
        action='append',
        default=[],
        metavar='DIR',
        help="a checkout's dir whose CATKIN_IGNORE the vendor's install script removes "
        '(repeatable)',
    )
    p.add_argument('--out', help='report directory (default: ./try_robot_<package>_<time>)')
    p.add_argument('--workspace', help='build here instead of a throw-away dir (kept)')
    p.add_argument('--keep', action='store_true', help='keep the throw-away workspace')
    p.add_argument(
        '--up-timeout', type=float, default=90.0, help='seconds for the world to come up'
    )
    p.add_argument(
        '--controllers-timeout',
        type=float,
        default=60.0,
        help='seconds for the controller spawners to finish',
    )
    p.add_argument('--no-motion', action='store_true', help='do not command any joint')
    a = p.parse_args(argv)
    for arg in a.args:
        if ':=' not in arg:
            p.error('launch argument %r is not name:=value' % arg)
    return a


# Arguments bringups commonly have for a GUI or RViz, and their headless value.
HEADLESS_ARGS = (
    ('gui', 'false'),
    ('gazebo_gui', 'false'),
    ('headless', 'true'),
    ('rviz', 'false'),
    ('start_rviz', 'false'),
    ('use_rviz', 'false'),
)


def launch_args(launch_path: str, given: List[str]) -> List[str]:
    """given, plus the headless value of each GUI/RViz arg of the launch file the caller did
    not set."""
    names = {a.split(':=', 1)[0] for a in given}
    try:
        with open(launch_path, 'rb') as f:
            root = safe_xml.parse(f.read(), launch_path)
    except (OSError, ValueError, SyntaxError):
        return list(given)
    # Settable args: the <launch>'s own <arg>s without a fixed value (not those in <include>s).
    settable = {a.get('name') for a in root.findall('arg') if a.get('value') is None}
    extra = [
        '%s:=%s' % (name, value)
        for name, value in HEADLESS_ARGS
        if name in settable and name not in names
    ]
    return list(given) + extra


def find_launch(packages: List[workspace.Package], package: str, launch: str) -> Optional[str]:
    """The launch file's path in the package (roslaunch finds it anywhere below the package)."""
    root = next(p.path for p in packages if p.name == package)
    if os.path.sep in launch:
        path = os.path.join(root, launch)
        return path if os.path.isfile(path) else None
    for dirpath, dirs, files in os.walk(root):
        dirs.sort()
        if launch in files:
            return os.path.join(dirpath, launch)
    return None


# What a tool built on try_robot does once the bringup's controllers are up (try_grasp's
# pick); its dict goes into the report under 'work'.
Work = Callable[[Progress], Dict[str, Any]]


def run(
    a: argparse.Namespace, work: Optional[Work] = None, tool: str = 'try_robot'
) -> Dict[str, Any]:
    progress = Progress()
    stamp = datetime.datetime.now(datetime.timezone.utc)
    out = os.path.abspath(a.out or '%s_%s_%s' % (tool, a.package, stamp.strftime('%Y%m%dT%H%M%S')))
    os.makedirs(out, exist_ok=True)
    rep: Dict[str, Any] = {
        'tool': 'arm1 ' + tool,
        'date': stamp.isoformat(timespec='seconds'),
        'launch': {'package': a.package, 'file': a.launch, 'args': list(a.args)},
        'checkouts': [workspace.checkout_info(c) for c in [a.checkout, *a.also]],
        'out': out,
    }
    available: Dict[str, workspace.Package] = {}
    for c in [a.checkout, *a.also]:
        if not os.path.isdir(c):
            raise SystemExit('try_robot: %s is not a directory' % c)
        for name, pkg in workspace.find_packages(c, a.unignore).items():
            available.setdefault(name, pkg)
    try:
        packages = workspace.needed_packages(available, a.package)
        for pkg, _ in a.then:
            more = workspace.needed_packages(available, pkg)
            packages += [p for p in more if p.name not in {q.name for q in packages}]
    except ValueError as e:
        raise SystemExit('try_robot: %s' % e)
    launch_path = find_launch(packages, a.package, a.launch)
    if launch_path is None:
        raise SystemExit('try_robot: no %s in package %s' % (a.launch, a.package))
    args = launch_args(launch_path, a.args)
    rep['launch']['args'] = args
    rep['launch']['then'] = [list(t) for t in a.then]
    rep['launch']['unignore'] = list(a.unignore)

    ws = a.workspace or tempfile.mkdtemp(prefix='try_robot_ws_')
    progress(
        'building %s in %s (catkin_make over arm1)' % (', '.join(p.name for p in packages), ws)
    )
    built, last, per_package = workspace.build_each(ws, packages)
    # ok: plain catkin_make passed with the packages unchanged (what a user's first try sees)
    rep['build'] = {
        'ok': built.ok,
        'packages': built.packages,
        'seconds': round(built.seconds, 1),
        'log': built.log,
        'per_package': per_package,
        'rest_ok': last.ok,
    }
    if built.ok:
        progress('built in %.1f s' % built.seconds)
        env = workspace.workspace_env(ws, packages)
    else:
        shutil.copy(built.log, os.path.join(out, 'build.log'))
        rep['build']['log_tail'] = built.log_tail
        failed = sorted(n for n, v in per_package.items() if not v['built'])
        if last.ok:
            # the others built: run from that workspace (its src dir keeps the left-out
            # packages on ROS_PACKAGE_PATH)
            progress('build FAILED for %s; the others built without them' % ', '.join(failed))
            env = workspace.workspace_env(ws, packages)
        else:
            progress('build FAILED (%s); running from the sources instead' % built.log)
            env = workspace.workspace_env(None, packages)
    try:
        rep.update(bringup(a, env, args, out, progress, work))
    finally:
        if not a.workspace and not a.keep:
            shutil.rmtree(ws, ignore_errors=True)
    rep['verdict'] = report.verdict(rep) if work is None else report.work_verdict(rep)
    with open(os.path.join(out, 'report.json'), 'w') as f:
        json.dump(rep, f, indent=2, default=str)
    text = report.text(rep)
    with open(os.path.join(out, 'report.txt'), 'w') as f:
        f.write(text)
    progress('report: %s' % os.path.join(out, 'report.json'))
    return rep


def bringup(
    a: argparse.Namespace,
    ws_env: Dict[str, str],
    args: List[str],
    out: str,
    progress: Progress,
    work: Optional[Work] = None,
) -> Dict[str, Any]:
    """Launch on a private loopback master, probe, stop; the bringup's part of the report."""
    from _arm1sim.tryout import probe

    res: Dict[str, Any] = {}
    log_dir = os.path.join(out, 'ros_log')
    shutil.rmtree(log_dir, ignore_errors=True)  # an earlier run's warnings are not this one's
    session = RosSession(log_dir=log_dir)
    port = int(session.env['ROS_MASTER_URI'].rsplit(':', 1)[1])
    session.env = loopback_env(ws_env, port)
    session.env['ROS_LOG_DIR'] = log_dir
    launch_log = os.path.join(out, 'roslaunch.log')
    started = time.monotonic()
    try:
        with open(launch_log, 'w') as log:
            proc = subprocess.Popen(
                ['roslaunch', a.package, a.launch, *args],
                env=session.env,
                start_new_session=True,
                stdout=log,
                stderr=subprocess.STDOUT,
            )
        session.procs.append(proc)
        progress('roslaunch %s %s %s (log: %s)' % (a.package, a.launch, ' '.join(args), launch_log))
        deadline = time.monotonic() + 30.0
        while not session.wait_for_master(1.0):
            if proc.poll() is not None or time.monotonic() > deadline:
                res['bringup'] = {
                    'up': False,
                    'error': 'roslaunch exited (%d) before its master was up' % proc.returncode
                    if proc.poll() is not None
                    else 'the master did not start in 30 s',
                }
                return res
        session.activate()
        deadline = time.monotonic() + a.up_timeout
        while not probe.node_registered('/gazebo'):
            if proc.poll() is not None:
                res['bringup'] = {'up': False, 'error': 'roslaunch exited (%d)' % proc.returncode}
                return res
            if time.monotonic() > deadline:
                res['bringup'] = {
                    'up': False,
                    'error': 'the world /gazebo did not register in %.0f s' % a.up_timeout,
                }
                return res
            time.sleep(0.2)
        res['bringup'] = {'up': True, 'seconds': round(time.monotonic() - started, 1)}
        for pkg, launch in a.then:
            progress('roslaunch %s %s' % (pkg, launch))
            with open(launch_log, 'a') as log:
                session.procs.append(
                    subprocess.Popen(
                        ['roslaunch', pkg, launch],
                        env=session.env,
                        start_new_session=True,
                        stdout=log,
                        stderr=subprocess.STDOUT,
                    )
                )
        progress('world /gazebo is up; waiting for the controller spawners')
        import rospy

        if not rospy.core.is_initialized():
            rospy.init_node('try_robot', anonymous=True, disable_signals=True)
        # A bringup may start the world paused for its user to press play (open_manipulator)
        # or unpause it itself once spawned (franka's spawn_model -unpause): give it time.
        deadline = time.monotonic() + 10.0
        while probe.paused() and time.monotonic() < deadline:
            time.sleep(0.5)
        if probe.paused():
            progress('the world is still paused: unpausing it, as its user would press play')
            probe.unpause()
            res['bringup']['unpaused_by_try_robot'] = True
        managers = probe.settle_controllers(
            a.controllers_timeout, 4.0, progress, lambda: probe.node_alive('/gazebo')
        )
        res['controller_managers'] = managers
        if work is not None:
            res['work'] = work(progress)
            res['bringup']['alive'] = proc.poll() is None
            res['bringup']['world_alive'] = probe.node_alive('/gazebo')
            return res
        res['models'] = probe.models()
        res['gazebo_topics'] = probe.gazebo_topics()
        descs = {}
        limits: Dict[str, dict] = {}
        for name, urdf in probe.descriptions().items():
            try:
                d = probe.describe(urdf)
            except Exception as e:  # a description the stand-in refuses is reported too
                d = {'error': str(e)}
            descs[name] = d
            limits.update(d.get('joints', {}))
        res['descriptions'] = descs
        res['motion'] = [] if a.no_motion else motion(managers, limits, progress)
        res['bringup']['alive'] = proc.poll() is None
        res['bringup']['world_alive'] = probe.node_alive('/gazebo')
    finally:
        progress('stopping the bringup')
        session.stop(timeout=15.0)
        # also when the bringup never came up: its logs say why
        problems = logs.rosout_problems(log_dir)
        res['warnings'] = problems
        res['unimplemented'] = logs.unimplemented(problems)
        res['launch_problems'] = logs.launch_problems(launch_log)
    return res


def motion(
    managers: Dict[str, List[Dict[str, Any]]], limits: Dict[str, dict], progress: Progress
) -> List[Dict[str, Any]]:
    """A trajectory goal to each running trajectory controller; a command to each running
    position controller (up to 8)."""
    import rosgraph

    from _arm1sim.tryout import probe

    states = probe.JointStates()
    checks: List[Dict[str, Any]] = []
    trajectory = tuple(
        rosgraph.names.ns_join(ns, str(c['name']))
        for ns, controllers in managers.items()
        for c in controllers
        if str(c.get('type')).endswith(probe.JTC_SUFFIX)
    )
    commanded = 0
    try:
        for ns, controllers in managers.items():
            for c in controllers:
                if c.get('state') != 'running':
                    continue
                ctype = str(c.get('type'))
                try:
                    if ctype.endswith(probe.JTC_SUFFIX):
                        progress('FollowJointTrajectory goal to %s (%s)' % (c['name'], ctype))
                        check = probe.trajectory_goal(ns, c, states, limits, siblings=trajectory)
                    elif (
                        ctype in probe.POSITION_TYPES or ctype in probe.GROUP_POSITION_TYPES
                    ) and commanded < 8:
                        commanded += 1
                        progress('command to %s (%s)' % (c['name'], ctype))
                        check = probe.position_command(ns, c, states, limits)
                    else:
                        continue
                except Exception as e:  # one controller's failure must not end the run
                    check = {'controller': c['name'], 'type': ctype, 'ok': False, 'error': str(e)}
                progress('  %s: %s' % (c['name'], 'ok' if check.get('ok') else 'FAILED'))
                checks.append(check)
    finally:
        states.close()
    return checks


def main(argv: Optional[List[str]] = None) -> int:
    a = parse_args(argv)
    rep = run(a)
    sys.stdout.write(report.text(rep))
    return 0 if rep['verdict']['ok'] else 1
