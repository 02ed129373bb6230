"""The real launch (``roslaunch arm1 gazebo.launch gui:=false``), watched from outside."""

from __future__ import annotations

import os
import time
from typing import Any, Dict, List, Tuple

from ..paths import repo_path
from .probes import cpu_seconds, peak_rss_mb

PROBE = '/bench_probe'
WINDOW = 4.0  # wall s a pace is watched over, before a hostile request and from its send on


def launch_and_wait(session: Any, *args: str, timeout: float = 60) -> None:
    """``roslaunch arm1 gazebo.launch gui:=false ARGS``, then this process's probe node. By
    path: another file named gazebo.launch in the package (a test robot's MoveIt config)
    makes roslaunch refuse the package-relative name."""
    import rospy

    launch = repo_path('launch', 'gazebo.launch')
    session.start('roslaunch', launch, 'gui:=false', *args, quiet=True)
    if not session.wait_for_master(timeout):
        raise RuntimeError('master did not start')
    rospy.init_node(PROBE.lstrip('/'), anonymous=True, disable_signals=True)


def record_clock() -> List[Tuple[float, float]]:
    """(wall perf_counter, sim s) of each /clock message from now on, appended as they come."""
    import rospy
    from rosgraph_msgs.msg import Clock

    clock: List[Tuple[float, float]] = []
    rospy.Subscriber(
        '/clock', Clock, lambda m: clock.append((time.perf_counter(), m.clock.to_sec()))
    )
    return clock


def clock_pace(clock: List[Tuple[float, float]], since: float) -> Tuple[float, float]:
    """(longest gap between /clock arrivals in wall s, real-time factor) after ``since``."""
    msgs = [m for m in clock if m[0] >= since]
    gaps = [b[0] - a[0] for a, b in zip(msgs, msgs[1:])]
    rtf = (msgs[-1][1] - msgs[0][1]) / max(msgs[-1][0] - msgs[0][0], 1e-9)
    return max(gaps), rtf


def startup() -> Dict[str, Any]:
    """Wall seconds from starting roslaunch to the first /arm1/joint_states (master included)."""
    import rospy

    from ..session.launcher import RosSession

    session = RosSession()
    session.activate()
    with session:
        t0 = time.time()
        launch_and_wait(session)
        msg = rospy.wait_for_message('/arm1/joint_states', rospy.AnyMsg, timeout=60)
        t1 = time.time()
        rospy.signal_shutdown('measured')
    return {'startup_s': t1 - t0, 'ok': msg is not None}


# arm1 upright: no link touches the ground (as the top-speed bench holds it)
UPRIGHT = {'joint%d' % k: 0.0 for k in range(1, 5)}
RISE = 3.0  # wall s for arm1 to rise from where it lay and settle
UPRIGHT_WINDOW = 20.0  # wall s at most the upright CPU is measured over


def realtime(seconds: float) -> Dict[str, float]:
    """At real_time_factor 1: measured RTF, joint_states rate in sim time, the world's CPU
    (per wall second, and per simulated second: what a step costs, whatever the RTF a loaded
    machine allowed) and peak RSS, with the 1-minute load average. Then the CPU again with
    arm1 commanded upright (``*_upright``): as launched it lies limp where it fell before the
    spawner started its controllers, link4 resting on the ground, and that resting contact
    is most of a step's physics."""
    import rospy
    from sensor_msgs.msg import JointState
    from std_msgs.msg import Float64

    from ..session.launcher import RosSession, node_pid

    session = RosSession()
    session.activate()
    with session:
        launch_and_wait(session)
        clock, stamps = record_clock(), []
        rospy.Subscriber(
            '/arm1/joint_states',
            JointState,
            lambda m: stamps.append(m.header.stamp.to_sec()),
            queue_size=100,
        )
        rospy.wait_for_message('/arm1/joint_states', JointState, timeout=60)
        time.sleep(2.0)
        world = [node_pid('/gazebo', caller=PROBE)]
        cpu0 = cpu_seconds(world)
        w0, c0, n0 = time.perf_counter(), clock[-1], len(stamps)
        time.sleep(seconds)
        w1, c1, n1 = time.perf_counter(), clock[-1], len(stamps)
        cpu1 = cpu_seconds(world)
        load = os.getloadavg()[0]
        rss = sum(peak_rss_mb(p) for p in world)
        window = stamps[n0:n1]
        pubs = [
            rospy.Publisher(
                '/arm1/%s_position_controller/command' % joint, Float64, queue_size=1, latch=True
            )
            for joint in UPRIGHT
        ]
        for pub, target in zip(pubs, UPRIGHT.values()):
            pub.publish(target)
        time.sleep(RISE)
        cpu2, w2, c2 = cpu_seconds(world), time.perf_counter(), clock[-1]
        time.sleep(min(seconds, UPRIGHT_WINDOW))
        cpu3, w3, c3 = cpu_seconds(world), time.perf_counter(), clock[-1]
        rospy.signal_shutdown('measured')
    return {
        'rtf': (c1[1] - c0[1]) / (c1[0] - c0[0]),
        'joint_states_hz': (len(window) - 1) / (window[-1] - window[0]),
        'cpu_core_fraction': (cpu1 - cpu0) / (w1 - w0),
        'cpu_per_sim_s': (cpu1 - cpu0) / max(c1[1] - c0[1], 1e-9),
        'cpu_core_fraction_upright': (cpu3 - cpu2) / (w3 - w2),
        'cpu_per_sim_s_upright': (cpu3 - cpu2) / max(c3[1] - c2[1], 1e-9),
        'load_1min': load,
        'peak_rss_mb': rss,
        'seconds': w1 - w0,
    }


def _role(proc: Any) -> str:
    """What a process of robot_spawn.launch is, for the CPU split."""
    cmd = ' '.join(proc.cmdline())
    for role, marks in (
        ('render processes', ('render_process', 'multiprocessing')),
        ('world (gzserver)', ('gzserver',)),
        ('look_away', ('look_away',)),
        ('arm_mover', ('arm_mover',)),
        ('robot_state_publisher', ('robot_state_publisher',)),
        ('spawner', ('spawner',)),
        ('rosmaster and rosout', ('rosmaster', 'rosout')),
        ('roslaunch', ('roslaunch',)),
    ):
        if any(m in cmd for m in marks):
            return role
    return 'other'


def seed_goal(seconds: float) -> Dict[str, Any]:
    """``roslaunch arm1 robot_spawn.launch gui:=false`` (the world, arm1 and its camera,
    arm_mover, look_away watching the camera) at real time: CPU of every process the launch
    started, master included, over ``seconds`` after the camera is streaming."""
    import psutil
    import rospy

    from ..session.launcher import RosSession

    session = RosSession()
    session.activate()
    with session:
        launch = session.roslaunch('arm1', 'robot_spawn.launch', 'gui:=false')
        if not session.wait_for_master(60):
            raise RuntimeError('master did not start')
        rospy.init_node(PROBE.lstrip('/'), anonymous=True, disable_signals=True)
        rospy.wait_for_message('/arm1/joint_states', rospy.AnyMsg, timeout=60)
        time.sleep(5.0)  # look_away subscribed, render processes up, spawner gone
        root = psutil.Process(launch.pid)
        procs = [root] + root.children(recursive=True)
        before = {p.pid: _cpu(p) for p in procs}
        w0 = time.perf_counter()
        time.sleep(seconds)
        wall = time.perf_counter() - w0
        split: Dict[str, float] = {}
        for p in procs:
            used = max(0.0, _cpu(p) - before[p.pid])  # 0: it ended meanwhile
            split[_role(p)] = split.get(_role(p), 0.0) + used / wall
        rospy.signal_shutdown('measured')
    main = {'world (gzserver)': 'cpu_world', 'render processes': 'cpu_render'}
    main['look_away'] = 'cpu_look_away'
    out: Dict[str, Any] = {key: split.pop(role, 0.0) for role, key in main.items()}
    out['cpu_rest'] = sum(split.values())
    out['cpu_core_fraction'] = sum(v for k, v in out.items() if k.startswith('cpu_'))
    out['seconds'] = wall
    return out


def _cpu(proc: Any) -> float:
    try:
        t = proc.cpu_times()
    except Exception:  # gone (the spawner ends): its CPU no longer counts
        return 0.0
    return float(t.user + t.system)
