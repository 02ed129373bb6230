"""rosrun arm1 try_moveit_tutorial: MoveIt's own move_group_python_interface_tutorial.py,
unchanged, against a robot's *_moveit_config (its demo.launch or demo_gazebo.launch) on arm1's
move_group and moveit_commander stand-ins; checks what each step did.

    rosrun arm1 try_moveit_tutorial ~/src/moveit_tutorials ~/src/panda_moveit_config \\
        --also ~/src/franka_ros demo.launch use_rviz:=false
    rosrun arm1 try_moveit_tutorial ~/src/moveit_tutorials ~/src/panda_moveit_config \\
        --also ~/src/franka_ros demo_gazebo.launch gazebo_gui:=false use_rviz:=false

The checkouts are used as they are (nothing is fetched): the config's packages and those it
needs are built beside arm1 (try_robot's workspace), the launch file is started on a private
master, and the tutorial script (doc/move_group_python_interface/scripts/ of the
moveit_tutorials checkout) is run; a newline is fed at each of its `Press Enter` prompts.
Between prompts the state is read independently (joint_states, move_group's compute_fk and
get_planning_scene): each step passes only if the arm and the scene are where the tutorial
asked. Exit status 0 when every step passed.
"""

from __future__ import annotations

import argparse
import math
import os
import queue
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional

from _arm1sim.session.launcher import RosSession, loopback_env
from _arm1sim.tryout import workspace

SCRIPT = os.path.join(
    'doc', 'move_group_python_interface', 'scripts', 'move_group_python_interface_tutorial.py'
)
PROMPT = 'Press `Enter`'
DONE = 'Python tutorial demo complete!'
TAU = 2 * math.pi
# the tutorial's joint goal and pose goal (its go_to_joint_state, go_to_pose_goal)
JOINT_GOAL = [0.0, -TAU / 8, 0.0, -TAU / 4, 0.0, TAU / 6, 0.0]
POSE_GOAL = (0.4, 0.1, 0.4)
# its Cartesian path (scale 1): the end effector ends displaced by this much
CARTESIAN_SHIFT = (0.1, 0.1, -0.1)
TOLERANCE = 0.01  # the tutorial's own all_close tolerance (rad, m)


@dataclass
class Step:
    prompt: str  # a piece of the prompt printed before the step runs
    name: str
    check: Callable[['Probe', Dict[str, Any]], str]  # '' when the step did what it should
    result: Dict[str, Any] = field(default_factory=dict)


class Probe:
    """Reads the robot and the scene from outside the tutorial (rospy in this process)."""

    def __init__(self, group: str, eef: str, arm_joints: List[str]) -> None:
        import rospy
        from moveit_msgs.srv import GetPlanningScene, GetPositionFK
        from sensor_msgs.msg import JointState

        rospy.init_node('try_moveit_tutorial', anonymous=True, disable_signals=True)
        self.group, self.eef, self.arm_joints = group, eef, arm_joints
        self.positions: Dict[str, float] = {}
        rospy.Subscriber('/joint_states', JointState, self._on_state, queue_size=10)
        self._fk = rospy.ServiceProxy('/compute_fk', GetPositionFK)
        self._scene = rospy.ServiceProxy('/get_planning_scene', GetPlanningScene)

    def _on_state(self, msg) -> None:
        self.positions.update(zip(msg.name, msg.position))

    def joints(self) -> List[float]:
        return [self.positions.get(j, float('nan')) for j in self.arm_joints]

    def settled_joints(self, timeout: float = 5.0) -> List[float]:
        """Joint values once they stop changing (the arm may still be finishing a move)."""
        last = self.joints()
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            time.sleep(0.3)
            now = self.joints()
            if max(abs(a - b) for a, b in zip(now, last)) < 1e-4:
                return now
            last = now
        return last

    def eef_position(self) -> List[float]:
        from moveit_msgs.msg import RobotState

        state = RobotState()
        state.joint_state.name = list(self.positions)
        state.joint_state.position = [self.positions[n] for n in state.joint_state.name]
        res = self._fk(header=_header('world'), fk_link_names=[self.eef], robot_state=state)
        p = res.pose_stamped[0].pose.position
        return [p.x, p.y, p.z]

    def objects(self) -> Dict[str, List[str]]:
        from moveit_msgs.msg import PlanningSceneComponents

        comps = PlanningSceneComponents(
            components=PlanningSceneComponents.WORLD_OBJECT_NAMES
            | PlanningSceneComponents.ROBOT_STATE_ATTACHED_OBJECTS
        )
        scene = self._scene(components=comps).scene
        return {
            'world': [o.id for o in scene.world.collision_objects],
            'attached': [a.object.id for a in scene.robot_state.attached_collision_objects],
        }


def _header(frame: str):
    from std_msgs.msg import Header

    return Header(frame_id=frame)


def _close(a: List[float], b: List[float], tol: float = TOLERANCE) -> bool:
    return all(abs(x - y) <= tol for x, y in zip(a, b))


def _fmt(values: List[float]) -> str:
    return '[%s]' % ', '.join('%.3f' % v for v in values)


def _scene_is(world: bool, attached: bool) -> Callable[[Probe, Dict[str, Any]], str]:
    def check(probe: Probe, memo: Dict[str, Any]) -> str:
        objs = probe.objects()
        memo['scene'] = objs
        if ('box' in objs['world']) != world or ('box' in objs['attached']) != attached:
            return 'box: world %s, attached %s; expected world %s, attached %s' % (
                'box' in objs['world'],
                'box' in objs['attached'],
                world,
                attached,
            )
        return ''

    return check


def _joint_goal(probe: Probe, memo: Dict[str, Any]) -> str:
    q = probe.settled_joints()
    memo['joints'] = q
    return '' if _close(q, JOINT_GOAL) else 'joints %s, goal %s' % (_fmt(q), _fmt(JOINT_GOAL))


def _pose_goal(probe: Probe, memo: Dict[str, Any]) -> str:
    probe.settled_joints()
    p = probe.eef_position()
    memo['eef'] = p
    memo['start_of_path'] = p
    return (
        ''
        if _close(p, list(POSE_GOAL))
        else 'end effector at %s, goal %s' % (_fmt(p), _fmt(list(POSE_GOAL)))
    )


def _unmoved(probe: Probe, memo: Dict[str, Any]) -> str:
    p = probe.eef_position()
    return (
        ''
        if _close(p, memo['start_of_path'])
        else 'the arm moved while only planning: %s' % _fmt(p)
    )


def _shifted(sign: float, base_key: str):
    def check(probe: Probe, memo: Dict[str, Any]) -> str:
        probe.settled_joints()
        p = probe.eef_position()
        want = [b + sign * s for b, s in zip(memo[base_key], CARTESIAN_SHIFT)]
        memo['eef_after_path'] = p
        return '' if _close(p, want) else 'end effector at %s, expected %s' % (_fmt(p), _fmt(want))

    return check


def steps() -> List[Step]:
    """The tutorial's prompts in order; each check runs when the next prompt appears."""
    return [
        Step('begin the tutorial', 'set up moveit_commander', lambda p, m: ''),
        Step('joint state goal', 'joint goal', _joint_goal),
        Step('pose goal', 'pose goal', _pose_goal),
        Step('plan and display a Cartesian path', 'plan a Cartesian path', _unmoved),
        Step('display a saved trajectory', 'display the trajectory', _unmoved),
        Step('execute a saved path', 'execute the Cartesian path', _shifted(1.0, 'start_of_path')),
        Step('add a box', 'add a box', _scene_is(world=True, attached=False)),
        Step('attach a Box', 'attach the box', _scene_is(world=False, attached=True)),
        Step(
            'attached collision object',
            'Cartesian path back with the box',
            _shifted(-1.0, 'eef_after_path'),
        ),
        Step('detach the box', 'detach the box', _scene_is(world=True, attached=False)),
        Step('remove the box', 'remove the box', _scene_is(world=False, attached=False)),
    ]


def parse_args(argv: Optional[List[str]]) -> argparse.Namespace:
    p = argparse.ArgumentParser(
        prog='try_moveit_tutorial',
        description=__doc__,
        formatter_class=argparse.RawTextHelpFormatter,
    )
    p.add_argument('tutorials', help='a checkout of ros-planning/moveit_tutorials (a path)')
    p.add_argument('config', help="a checkout holding the robot's *_moveit_config package")
    p.add_argument('launch', help='demo.launch or demo_gazebo.launch')
    p.add_argument('args', nargs='*', help='launch arguments, name:=value')
    p.add_argument('--package', default='panda_moveit_config', help='the *_moveit_config package')
    p.add_argument(
        '--also',
        action='append',
        default=[],
        metavar='CHECKOUT',
        help='another checkout the config needs (franka_ros for the Panda)',
    )
    p.add_argument('--group', default='panda_arm', help="the tutorial's planning group")
    p.add_argument('--eef', default='panda_link8', help="the group's end-effector link")
    p.add_argument('--up-timeout', type=float, default=120.0)
    p.add_argument('--step-timeout', type=float, default=120.0)
    p.add_argument('--out', help='log directory (default: a temporary one, printed)')
    return p.parse_args(argv)


def _reader(stream, lines: 'queue.Queue[Optional[str]]', log) -> None:
    """Lines of the tutorial's output; its prompts end without a newline, so read chunks."""
    buf = ''
    while True:
        chunk = stream.read1(4096) if hasattr(stream, 'read1') else stream.read(1)
        if not chunk:
            break
        text = chunk.decode('utf-8', 'replace')
        log.write(text)
        log.flush()
        buf += text
        while '\n' in buf or (PROMPT in buf and buf.rstrip().endswith('...')):
            if '\n' in buf:
                line, buf = buf.split('\n', 1)
            else:  # a prompt, whole (each ends in '...'), waiting for its newline
                line, buf = buf, ''
            lines.put(line)
    if buf:
        lines.put(buf)
    lines.put(None)


def run(a: argparse.Namespace) -> Dict[str, Any]:
    script = os.path.join(a.tutorials, SCRIPT)
    if not os.path.isfile(script):
        raise SystemExit('try_moveit_tutorial: no %s in %s' % (SCRIPT, a.tutorials))
    available: Dict[str, workspace.Package] = {}
    for c in [a.config, *a.also]:
        for name, pkg in workspace.find_packages(c).items():
            available.setdefault(name, pkg)
    try:
        packages = workspace.needed_packages(available, a.package)
    except ValueError as e:
        raise SystemExit('try_moveit_tutorial: %s' % e)
    out = os.path.abspath(a.out or tempfile.mkdtemp(prefix='try_moveit_tutorial_'))
    os.makedirs(out, exist_ok=True)
    ws = tempfile.mkdtemp(prefix='try_moveit_ws_')
    rep: Dict[str, Any] = {'launch': [a.package, a.launch, *a.args], 'out': out, 'steps': []}
    say('building %s in %s' % (', '.join(p.name for p in packages), ws))
    built, last, per_package = workspace.build_each(ws, packages)
    rep['build'] = {n: v['built'] for n, v in per_package.items()}
    env = workspace.workspace_env(ws if last.ok else None, packages)
    session = RosSession(log_dir=os.path.join(out, 'ros_log'))
    port = int(session.env['ROS_MASTER_URI'].rsplit(':', 1)[1])
    session.env = loopback_env(env, port)
    session.env['ROS_LOG_DIR'] = os.path.join(out, 'ros_log')
    try:
        with open(os.path.join(out, 'roslaunch.log'), 'w') as log:
            session.procs.append(
                subprocess.Popen(
                    ['roslaunch', a.package, a.launch, *a.args],
                    env=session.env,
                    start_new_session=True,
                    stdout=log,
                    stderr=subprocess.STDOUT,
                )
            )
        say('roslaunch %s %s %s' % (a.package, a.launch, ' '.join(a.args)))
        if not session.wait_for_master(30.0):
            rep['error'] = 'the master did not come up'
            return rep
        session.activate()
        launch_log = os.path.join(out, 'roslaunch.log')
        if not _wait_for_move_group(a.up_timeout, launch_log):
            rep['error'] = "move_group's action did not come up in %.0f s (%s)" % (
                a.up_timeout,
                _died(launch_log) or 'see roslaunch.log',
            )
            return rep
        say('move_group is up')
        rep['steps'] = _run_tutorial(a, script, session, out)
    finally:
        session.stop()
        shutil.rmtree(ws, ignore_errors=True)
    return rep


def _died(launch_log: str) -> str:
    """move_group's last words when roslaunch saw it die, else ''."""
    with open(launch_log, errors='replace') as f:
        text = f.read()
    if '[move_group-' not in text or 'process has died' not in text:
        return ''
    fatal = [line for line in text.splitlines() if '[FATAL]' in line or '[ERROR]' in line]
    return 'move_group died: %s' % (fatal[-1].strip() if fatal else 'see roslaunch.log')


def _wait_for_move_group(timeout: float, launch_log: str) -> bool:
    import rosgraph

    master = rosgraph.Master('/try_moveit_tutorial')
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline and not _died(launch_log):
        try:
            _, subs, _ = master.getSystemState()
            if any(t == '/move_group/goal' for t, _ in subs):
                return True
        except Exception:  # master not answering yet
            pass
        time.sleep(0.5)
    return False


def _run_tutorial(a: argparse.Namespace, script: str, session: RosSession, out: str) -> list:
    todo = steps()
    probe = Probe(a.group, a.eef, ['%s_joint%d' % (a.group.split('_')[0], i) for i in range(1, 8)])
    memo: Dict[str, Any] = {}
    lines: 'queue.Queue[Optional[str]]' = queue.Queue()
    with open(os.path.join(out, 'tutorial.log'), 'w') as log:
        proc = subprocess.Popen(
            [sys.executable, '-u', script],
            env=session.env,
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
        session.procs.append(proc)
        threading.Thread(target=_reader, args=(proc.stdout, lines, log), daemon=True).start()
        results: List[Dict[str, Any]] = []
        current: Optional[Step] = None
        started = time.monotonic()
        finished = False
        while True:
            try:
                line = lines.get(timeout=a.step_timeout)
            except queue.Empty:
                results.append(
                    {
                        'step': current.name if current else 'start',
                        'ok': False,
                        'detail': 'no prompt within %.0f s' % a.step_timeout,
                    }
                )
                break
            if line is None:
                break
            if DONE in line:
                finished = True
            prompt = line if PROMPT in line else ''
            if not prompt and not finished:
                continue
            if current is not None:  # the previous step ran: check it
                detail = current.check(probe, memo)
                results.append(
                    {
                        'step': current.name,
                        'ok': not detail,
                        'detail': detail,
                        'seconds': round(time.monotonic() - started, 1),
                    }
                )
                say('%-34s %s %s' % (current.name, 'ok' if not detail else 'FAILED', detail))
            if finished:
                break
            current = next((s for s in todo if s.prompt in prompt), None)
            started = time.monotonic()
            assert proc.stdin is not None
            proc.stdin.write(b'\n')
            proc.stdin.flush()
        try:
            rc = proc.wait(30)
        except subprocess.TimeoutExpired:
            rc = None
        results.append(
            {
                'step': 'tutorial ends',
                'ok': finished and rc == 0,
                'detail': ''
                if finished and rc == 0
                else 'exit status %s, completion line %s'
                % (rc, 'seen' if finished else 'not seen'),
            }
        )
    return results


def say(text: str) -> None:
    sys.stderr.write('try_moveit_tutorial: %s\n' % text)
    sys.stderr.flush()


def main(argv: Optional[List[str]] = None) -> int:
    a = parse_args(argv)
    rep = run(a)
    steps_run = rep.get('steps', [])
    passed = sum(1 for s in steps_run if s['ok'])
    if 'error' in rep:
        say('ERROR: %s (logs in %s)' % (rep['error'], rep['out']))
        return 1
    say('%d of %d steps passed (logs in %s)' % (passed, len(steps_run), rep['out']))
    return 0 if steps_run and passed == len(steps_run) else 1
