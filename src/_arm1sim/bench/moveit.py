"""The move_group stand-in: planning time of the MoveIt tutorial's goals (and in a cluttered
scene) on its ROS-free core, and what a running, idle move_group node costs in CPU.

The robot is test/robots/toy_panda.py (a Panda's joints, limits and link lengths) with its
test SRDF and configuration; the goals are move_group_python_interface_tutorial.py's: the
joint goal, the pose goal (position 0.4, 0.1, 0.4, orientation w = 1) and the Cartesian
path (down 10 cm then sideways 20 cm, back up and to the side, eef_step 1 cm).
"""

from __future__ import annotations

import math
import os
import random
import statistics
import subprocess
import sys
import time
from typing import Any, Dict, List

from ..paths import repo_root

TAU = 2 * math.pi
TUTORIAL_JOINT_GOAL = [0.0, -TAU / 8, 0.0, -TAU / 4, 0.0, TAU / 6, 0.0]


def _toy() -> Any:
    sys.path.insert(0, os.path.join(repo_root(), 'test', 'robots'))
    import toy_panda
    import toy_panda_moveit
    import yaml

    with open(os.path.join(repo_root(), 'test', 'config', 'toy_panda_moveit.yaml')) as f:
        params = yaml.safe_load(f)
    return toy_panda, toy_panda_moveit, params


def _pipeline(seed: int) -> Any:
    from ..description.srdf import parse_srdf
    from ..planning import config as cfg
    from ..planning.kinematics import RobotKinematics
    from ..planning.pipeline import PlanningPipeline
    from ..planning.scene import CollisionWorld

    toy_panda, toy_moveit, params = _toy()
    srdf = parse_srdf(toy_moveit.srdf())
    robot = RobotKinematics(
        toy_panda.urdf(), srdf, cfg.joint_limits_config(params['robot_description_planning'])
    )
    world = CollisionWorld(robot)
    pipe = PlanningPipeline(
        robot,
        world,
        cfg.ompl_config(params['move_group'], list(srdf.groups)),
        cfg.kinematics_config(params['robot_description_kinematics']),
        seed=seed,
    )
    return robot, world, pipe


def _stats(values: List[float]) -> Dict[str, float]:
    ordered = sorted(values)
    p95 = ordered[min(len(ordered) - 1, int(math.ceil(0.95 * len(ordered))) - 1)]
    return {'median': statistics.median(ordered), 'p95': p95}


def planning_times(count: int = 20, boxes: int = 20) -> Dict[str, Any]:
    """Median and p95 of each tutorial goal's planning: wall seconds (the machine as it is)
    and the process's CPU seconds (what another session's load does not inflate)."""
    from ..planning.pipeline import (
        Constraints,
        JointGoal,
        MotionRequest,
        OrientationConstraint,
        PositionConstraint,
    )
    from ..planning.scene import SceneObject, Shape

    robot, world, pipe = _pipeline(seed=7)
    arm = robot.group_joints('toy_arm')
    ready = {j: robot.default_position(j) for j in robot.variables}
    ready.update(robot.srdf.group_states['toy_arm']['ready'])
    joint_goal = Constraints(joints=[JointGoal(j, v) for j, v in zip(arm, TUTORIAL_JOINT_GOAL)])
    pose_goal = Constraints(
        positions=[PositionConstraint('toy_link8', (0.4, 0.1, 0.4))],
        orientations=[OrientationConstraint('toy_link8', (0.0, 0.0, 0.0, 1.0))],
    )
    out: Dict[str, Any] = {}
    failures = 0

    def record(key: str, wall: List[float], cpu: List[float]) -> None:
        for k, v in _stats(wall).items():
            out['%s_%s_s' % (key, k)] = v
        for k, v in _stats(cpu).items():  # the process's CPU: what load does not inflate
            out['%s_cpu_%s_s' % (key, k)] = v

    def run(key: str, goal: Constraints) -> None:
        nonlocal failures
        wall, cpu = [], []
        for _ in range(count):
            c0 = time.process_time()
            r = pipe.plan(MotionRequest('toy_arm', dict(ready), [goal], allowed_planning_time=5.0))
            cpu.append(time.process_time() - c0)
            failures += r.error_code != 1
            wall.append(r.planning_time)
        record(key, wall, cpu)

    run('joint_goal', joint_goal)
    run('pose_goal', pose_goal)
    robot.set_positions(ready)
    pos, orn = robot.link_pose('toy_link8')
    waypoints = []
    p = list(pos)
    for dx, dy, dz in ((0, 0, -0.1), (0, 0.2, 0), (0.1, 0, 0)):  # the tutorial's three
        p = [p[0] + dx, p[1] + dy, p[2] + dz]
        waypoints.append((list(p), list(orn)))
    wall, cpu, fractions = [], [], []
    for _ in range(count):
        t0, c0 = time.perf_counter(), time.process_time()
        result, _ = pipe.cartesian('toy_arm', 'toy_link8', dict(ready), waypoints, 0.01, 0.0, True)
        wall.append(time.perf_counter() - t0)
        cpu.append(time.process_time() - c0)
        fractions.append(result.fraction)
    record('cartesian', wall, cpu)
    out['cartesian_fraction'] = min(fractions)
    # clutter: boxes of 5-10 cm around the arm, none on the start or the goal
    rng = random.Random(3)
    goal_state = {**ready, **dict(zip(arm, TUTORIAL_JOINT_GOAL))}
    placed = 0
    while placed < boxes:
        x, y, z = rng.uniform(-0.7, 0.7), rng.uniform(-0.7, 0.7), rng.uniform(0.0, 1.0)
        if math.hypot(x, y) < 0.2:
            continue
        size = rng.uniform(0.05, 0.1)
        world.add_object(
            SceneObject('box%d' % placed, ((x, y, z), (0, 0, 0, 1)), [Shape('box', (size,) * 3)])
        )
        if world.in_collision(ready) or world.in_collision(goal_state):
            world.remove('box%d' % placed)
            continue
        placed += 1
    run('cluttered_joint_goal', joint_goal)
    out['boxes'] = boxes
    out['failures'] = failures
    out['runs_per_goal'] = count
    return out


def idle_move_group(seconds: float = 20.0, rate: float = 100.0) -> Dict[str, float]:
    """The CPU of a running move_group with nothing asked of it, while the robot's
    joint_states arrive at ``rate`` Hz (a joint_state_controller's usual rate)."""
    import psutil
    import rospy
    from sensor_msgs.msg import JointState

    toy_panda, toy_moveit, params = _toy()
    rospy.init_node('bench_move_group', anonymous=True)
    rospy.set_param('/robot_description', toy_panda.urdf())
    rospy.set_param('/robot_description_semantic', toy_moveit.srdf())
    for key in ('robot_description_kinematics', 'robot_description_planning', 'move_group'):
        rospy.set_param('/' + key, params[key])
    proc = subprocess.Popen(
        [
            sys.executable,
            '-c',
            'import sys; from _arm1sim.ros.moveit.move_group import main; sys.exit(main())',
        ],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    pub = rospy.Publisher('/joint_states', JointState, queue_size=10)
    names = ['toy_joint%d' % i for i in range(1, 8)] + ['toy_finger_joint1', 'toy_finger_joint2']
    msg = JointState(name=names, position=[0.0] * len(names))
    try:
        rospy.wait_for_service('/plan_kinematic_path', 60)
        ps = psutil.Process(proc.pid)
        period = 1.0 / rate
        end = time.monotonic() + 2.0  # settle
        while time.monotonic() < end:
            msg.header.stamp = rospy.Time.now()
            pub.publish(msg)
            time.sleep(period)
        c0, w0 = sum(ps.cpu_times()[:2]), time.monotonic()
        end = w0 + seconds
        while time.monotonic() < end:
            msg.header.stamp = rospy.Time.now()
            pub.publish(msg)
            time.sleep(period)
        c1, w1 = sum(ps.cpu_times()[:2]), time.monotonic()
    finally:
        proc.terminate()
        proc.wait(10)
    return {'cpu_core_fraction': (c1 - c0) / (w1 - w0), 'joint_states_hz': rate}
