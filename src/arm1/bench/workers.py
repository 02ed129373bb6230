"""One measurement per process: ``python -m arm1.bench.workers KIND [options]`` prints one JSON line.

Each runs in a fresh process because a process holds one ROS node, and so that
one measurement's threads and memory do not colour the next.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import threading
import time

import yaml

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
WORLD = os.path.join(ROOT, 'worlds', 'willow_garage.world')
XACRO = os.path.join(ROOT, 'urdf', 'arm1.urdf.xacro')
CONTROLLERS = os.path.join(ROOT, 'config', 'controllers.yaml')
NAMES = ['joint_state_controller'] + ['joint%d_position_controller' % i for i in range(1, 5)]
JOINTS = ['joint1', 'joint2', 'joint3', 'joint4']
STEP = 0.001


def arm1_urdf(namespace='/arm1'):
    from ..xacro_bridge import expand
    xml = expand(XACRO)
    return xml.replace('<robotNamespace>/arm1</robotNamespace>',
                       '<robotNamespace>%s</robotNamespace>' % namespace)


def proc_cpu_seconds(pid):
    with open('/proc/%d/stat' % pid) as f:
        fields = f.read().rsplit(')', 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK')


def proc_peak_rss_mb(pid):
    with open('/proc/%d/status' % pid) as f:
        for line in f:
            if line.startswith('VmHWM:'):
                return int(line.split()[1]) / 1024.0
    return float('nan')


# -- bare pybullet: the ceiling -------------------------------------------------------------
def bare(seconds):
    """Read joints, PID, apply torques, step: the same robot without ROS or our classes."""
    import tempfile
    import pybullet as p
    from ..description.urdf_model import resolve_mesh_uris
    from ..ros.packages import find_package
    xml = resolve_mesh_uris(arm1_urdf(), find_package)
    with tempfile.NamedTemporaryFile('w', suffix='.urdf', delete=False) as f:
        f.write(xml)
    cid = p.connect(p.DIRECT)
    p.setTimeStep(STEP, physicsClientId=cid)
    p.setGravity(0, 0, -9.8, physicsClientId=cid)
    p.createMultiBody(0, p.createCollisionShape(p.GEOM_PLANE, physicsClientId=cid),
                      physicsClientId=cid)
    body = p.loadURDF(f.name, useFixedBase=True, flags=p.URDF_USE_INERTIA_FROM_FILE,
                      physicsClientId=cid)
    os.unlink(f.name)
    index = {p.getJointInfo(body, i, physicsClientId=cid)[1].decode(): i
             for i in range(p.getNumJoints(body, physicsClientId=cid))}
    idx = [index[j] for j in JOINTS]
    p.setJointMotorControlArray(body, idx, p.VELOCITY_CONTROL, forces=[0] * 4,
                                physicsClientId=cid)
    target, kp, kd = [0.5, 1.2, 0.0, 0.0], 1.0, 0.002
    last_err = [0.0] * 4
    steps, start = 0, time.perf_counter()
    deadline = start + seconds
    while True:
        for _ in range(1000):
            states = p.getJointStates(body, idx, physicsClientId=cid)
            efforts = []
            for k in range(4):
                err = target[k] - states[k][0]
                u = kp * err + kd * (err - last_err[k]) / STEP
                last_err[k] = err
                efforts.append(max(-1.0, min(1.0, u)))
            p.setJointMotorControlArray(body, idx, p.TORQUE_CONTROL, forces=efforts,
                                        physicsClientId=cid)
            p.stepSimulation(physicsClientId=cid)
        steps += 1000
        now = time.perf_counter()
        if now >= deadline:
            return {'steps_per_s': steps / (now - start)}


# -- the stand-in, in this process, with ROS ------------------------------------------------
def _start_standin(arms, real_time_update_rate):
    """The world node of gzserver with ``arms`` arm1s, each in /armK, controllers started."""
    import rospy
    from ..ros.world_node import parse_args, start_world
    argv = [WORLD]
    if real_time_update_rate is not None:
        argv += ['--real-time-update-rate', str(real_time_update_rate)]
    import rosparam
    rosparam.set_param('/use_sim_time', 'true')  # as gazebo.launch sets it
    api, pacer = start_world(parse_args(argv))
    with open(CONTROLLERS) as f:
        params = yaml.safe_load(f)['arm1']
    managers = []
    for k in range(1, arms + 1):
        ns = '/arm%d' % k
        rospy.set_param(ns, params)
        model = api.spawn('arm%d' % k, arm1_urdf(ns), (0.4 * (k - 1), 0, 0), (0, 0, 0, 1))
        for name in NAMES:
            model.controller_manager.load_controller(name)
        managers.append(model.controller_manager)
    # A switch waits for the next update: ask from a thread, the loop does it.
    threading.Thread(target=lambda: [m.switch_controller(NAMES, []) for m in managers],
                     daemon=True).start()
    return api, pacer


def _listeners(arms, camera=False):
    """A subscriber to every arm's joint_states in another process, as robot_state_publisher
    would be; one process for all, so that N arms do not bring N Python listeners. With
    ``camera``, it also watches arm1's camera, which makes the world render it."""
    topics = ['/arm%d/joint_states' % k for k in range(1, arms + 1)]
    topics += ['/rgb_camera/image_raw'] if camera else []
    return [subprocess.Popen(['rostopic', 'hz'] + topics, stdout=subprocess.DEVNULL,
                             stderr=subprocess.DEVNULL)]


# Where a step's time goes: (label, predicate on pstats' (file, line, function) key)
PROFILE_PARTS = [
    ('pybullet stepSimulation', lambda f, fn: 'stepSimulation' in fn),
    ('pybullet joint read / torque write',
     lambda f, fn: 'getJointStates' in fn or 'setJointMotorControlArray' in fn),
    ('controllers, PID, controller manager (Python)', lambda f, fn: '/arm1/control/' in f),
    ('hardware interface, robot, simulation step (Python)',
     lambda f, fn: any(m in f for m in ('robot_hw_sim.py', 'physics/robot.py', 'simulation.py'))),
    ('ROS publishing (messages, rospy, sockets)',
     lambda f, fn: any(m in f for m in ('rospy', 'genpy', '_msgs/msg', 'node_handle.py'))
     or 'sendall' in fn),
    ('world loop, clock, pacing', lambda f, fn: any(m in f for m in (
        'world_loop.py', 'sim_clock.py', 'sim_thread.py', 'pacer.py'))),
]


OTHER = 'Python built-ins (min, max, isfinite, ...) and the rest'


def _profile_split(stats):
    """Share of the physics thread's time per PROFILE_PARTS label, the rest under OTHER."""
    shares = {label: 0.0 for label, _ in PROFILE_PARTS}
    shares[OTHER] = 0.0
    total = 0.0
    for (path, _, fn), (_, _, tottime, _, _) in stats.stats.items():
        total += tottime
        label = next((l for l, match in PROFILE_PARTS if match(path, fn)), OTHER)
        shares[label] += tottime
    return {k: v / total for k, v in shares.items()}


def standin(seconds, arms=1, warmup=1.0, profile=False, camera=False):
    """Top speed: steps per wall second with real_time_update_rate 0 (optionally profiled,
    or with arm1's camera streaming)."""
    import rospy
    api, pacer = _start_standin(arms, 0)
    listeners = _listeners(arms, camera)
    marks = []

    def timer():
        time.sleep(warmup)
        marks.append((time.perf_counter(), api.sim.steps))
        time.sleep(seconds)
        marks.append((time.perf_counter(), api.sim.steps))
        rospy.signal_shutdown('measured')
    threading.Thread(target=timer, daemon=True).start()
    profiler = None
    if profile:
        import cProfile
        profiler = cProfile.Profile()
        profiler.enable()
    try:
        api.run(pacer)
    finally:
        if profiler:
            profiler.disable()
        for proc in listeners:
            proc.terminate()
    (w0, s0), (w1, s1) = marks
    result = {'steps_per_s': (s1 - s0) / (w1 - w0), 'arms': arms, 'camera': camera}
    if profiler:
        import pstats
        result = {'profile_share': _profile_split(pstats.Stats(profiler))}
    return result


def idle_world(seconds):
    """The floor at real time: CPU of the world node with no robot, and of one wake-up.

    A 1 kHz world sleeps and wakes 1 000 times a wall second whatever it simulates;
    what each wake-up costs in CPU is measured apart, with plain 0.9 ms sleeps.
    """
    import rospy
    from ..ros.world_node import parse_args, start_world
    n = 2000
    c0 = time.process_time()
    for _ in range(n):
        time.sleep(0.0009)
    sleep_cpu = (time.process_time() - c0) / n
    api, pacer = start_world(parse_args([WORLD]))
    threading.Thread(target=lambda: (time.sleep(seconds), rospy.signal_shutdown('measured')),
                     daemon=True).start()
    w0, c0 = time.perf_counter(), time.process_time()
    api.run(pacer)
    w1, c1 = time.perf_counter(), time.process_time()
    return {'cpu_core_fraction': (c1 - c0) / (w1 - w0), 'sleep_wakeup_cpu_us': sleep_cpu * 1e6}


def latency(commands, rate=100.0):
    """Wall time from publishing a command to the step that first applies it."""
    import rospy
    api, pacer = _start_standin(1, None)
    ctrl = api.sim.models['arm1'].controller_manager.controller('joint1_position_controller')
    applied = {}
    original = ctrl.update

    def update(time_ns, period):  # record the first update that sees each new command
        cmd = ctrl.command
        if cmd not in applied:
            applied[cmd] = time.time()
        original(time_ns, period)
    ctrl.update = update
    out = {}

    def publisher():
        time.sleep(2.0)  # controllers started, connections made
        proc = subprocess.run([sys.executable, '-m', 'arm1.bench.workers', 'publisher',
                               '--count', str(commands), '--rate', str(rate)],
                              stdout=subprocess.PIPE, text=True)
        out['sent'] = json.loads(proc.stdout.strip().splitlines()[-1])
        time.sleep(0.2)
        rospy.signal_shutdown('measured')
    threading.Thread(target=publisher, daemon=True).start()
    api.run(pacer)
    lat = sorted((applied[v] - t) * 1e3 for v, t in out['sent'] if v in applied)
    return {'n': len(lat), 'sent': len(out['sent']), 'p50_ms': _pct(lat, 50),
            'p99_ms': _pct(lat, 99), 'max_ms': lat[-1] if lat else float('nan')}


def publisher(count, rate):
    """Publishes ``count`` distinct joint1 targets; prints [(value, wall time)]."""
    import rospy
    from std_msgs.msg import Float64
    rospy.init_node('bench_publisher', anonymous=True)
    pub = rospy.Publisher('/arm1/joint1_position_controller/command', Float64, queue_size=10)
    while pub.get_num_connections() == 0:
        time.sleep(0.05)
    time.sleep(0.5)
    sent = []
    for k in range(count):
        value = 0.1 + 1e-4 * k  # unique, within joint1's limits
        sent.append((value, time.time()))
        pub.publish(value)
        time.sleep(1.0 / rate)
    print(json.dumps(sent))
    return None


def _pct(values, q):
    if not values:
        return float('nan')
    return values[min(len(values) - 1, int(math.ceil(q / 100.0 * len(values))) - 1)]


# -- the real launch, watched from outside ----------------------------------------------------
def _launch_and_wait(session, timeout=60):
    import rospy
    session.roslaunch('arm1', 'gazebo.launch', 'gui:=false')
    if not session.wait_for_master(timeout):
        raise RuntimeError('master did not start')
    rospy.init_node('bench_probe', anonymous=True, disable_signals=True)


def startup():
    """Wall seconds from starting roslaunch to the first /arm1/joint_states (master included)."""
    import rospy
    from ..launcher import RosSession
    session = RosSession()
    session.activate()
    with session:
        t0 = time.time()
        _launch_and_wait(session)
        msg = rospy.wait_for_message('/arm1/joint_states', rospy.AnyMsg, timeout=60)
        t1 = time.time()
        rospy.signal_shutdown('measured')
    return {'startup_s': t1 - t0, 'ok': msg is not None}


def realtime(seconds):
    """At real_time_factor 1: measured RTF, joint_states rate in sim time, CPU and peak RSS."""
    import rosgraph
    import rospy
    from rosgraph_msgs.msg import Clock
    from sensor_msgs.msg import JointState
    from ..launcher import RosSession
    session = RosSession()
    session.activate()
    with session:
        _launch_and_wait(session)
        clock, stamps = [], []
        rospy.Subscriber('/clock', Clock, lambda m: clock.append((time.perf_counter(),
                                                                  m.clock.to_sec())))
        rospy.Subscriber('/arm1/joint_states', JointState,
                         lambda m: stamps.append(m.header.stamp.to_sec()), queue_size=100)
        rospy.wait_for_message('/arm1/joint_states', JointState, timeout=60)
        time.sleep(2.0)
        pids = _node_pids(rosgraph, ['/gazebo'])
        cpu0 = sum(proc_cpu_seconds(p) for p in pids)
        w0, c0, n0 = time.perf_counter(), clock[-1], len(stamps)
        time.sleep(seconds)
        w1, c1, n1 = time.perf_counter(), clock[-1], len(stamps)
        cpu1 = sum(proc_cpu_seconds(p) for p in pids)
        rss = sum(proc_peak_rss_mb(p) for p in pids)
        window = stamps[n0:n1]
        rospy.signal_shutdown('measured')
    return {'rtf': (c1[1] - c0[1]) / (c1[0] - c0[0]),
            'joint_states_hz': (len(window) - 1) / (window[-1] - window[0]),
            'cpu_core_fraction': (cpu1 - cpu0) / (w1 - w0), 'peak_rss_mb': rss,
            'seconds': w1 - w0}


def _node_pids(rosgraph, names):
    import xmlrpc.client
    master = rosgraph.Master('/bench_probe')
    pids = []
    for name in names:
        code, _, pid = xmlrpc.client.ServerProxy(master.lookupNode(name)).getPid('/bench_probe')
        pids.append(pid)
    return pids


KINDS = {'bare': bare, 'standin': standin, 'latency': latency, 'publisher': publisher,
         'idle_world': idle_world,
         'startup': startup, 'realtime': realtime}


def main(argv=None):
    parser = argparse.ArgumentParser()
    parser.add_argument('kind', choices=sorted(KINDS))
    parser.add_argument('--seconds', type=float)
    parser.add_argument('--arms', type=int)
    parser.add_argument('--commands', type=int)
    parser.add_argument('--count', type=int)
    parser.add_argument('--rate', type=float)
    parser.add_argument('--profile', action='store_true', default=None)
    parser.add_argument('--camera', action='store_true', default=None)
    args = parser.parse_args(argv)
    kwargs = {k: v for k, v in vars(args).items() if k != 'kind' and v is not None}
    result = KINDS[args.kind](**kwargs)
    if result is not None:
        print(json.dumps(result))
    return 0


if __name__ == '__main__':
    sys.exit(main())
