"""What several unit-test modules share: rigs, robots and fakes a test module imports.

Fixtures and fakes every module uses are in conftest.py; URDF pieces the rostests share too
are in urdf_snippets.py and two_wheels.py. A helper a second test module needs moves here
rather than being imported from the test module that first had it.
"""

from __future__ import annotations

import importlib
import os
from typing import Any, Dict, List, Sequence, Tuple

import pytest
import yaml
from conftest import (
    JPC,
    JSC,
    MIXED_URDF,
    REPO_ROOT,
    FakeRobot,
    FakeRos,
    box_link,
    control_plugin,
    transmission,
)
from two_wheels import robot_urdf

from _arm1sim.control.controller import ControllerError
from _arm1sim.control.controller_manager import ControllerManager
from _arm1sim.control.hardware_interface import EFFORT_JOINT_INTERFACE, JointHandle
from _arm1sim.control.joint_position_controller import JointPositionController
from _arm1sim.control.joint_trajectory_controller import JointTrajectoryController
from _arm1sim.control.switching import switch_while_updating
from _arm1sim.control.trajectory import sample
from _arm1sim.description.sdf_world import Shape, StaticModel, WorldConfig, parse_world
from _arm1sim.description.urdf_model import parse_urdf
from _arm1sim.physics.diff_drive import DiffDrive
from _arm1sim.sim.robot_hw_sim import DefaultRobotHWSim
from _arm1sim.sim.simulation import Model, Simulation

MS = 1000000  # a 1 ms physics step, ns
S = 10**9
MIXED_NS = '/mixed_ns'  # the controller namespace of conftest's MIXED_URDF rigs
TRAJECTORY_NS = '/arm'


# ------------------------------------------------------ controller manager (mixed joints)
PERIOD_NS = 1000000  # a 1 ms physics step
PARAMS = {
    'mixed_ns': {
        'joint_state_controller': {'type': JSC, 'publish_rate': 50},
        'wheel_controller': {'type': JPC, 'joint': 'wheel_joint', 'pid': {'p': 1.0}},
        'slider_controller': {'type': JPC, 'joint': 'slider_joint', 'pid': {'p': 1.0}},
        'flap_controller': {'type': JPC, 'joint': 'flap_joint', 'pid': {'p': 1.0}},
        'flap_other_controller': {'type': JPC, 'joint': 'flap_joint', 'pid': {'p': 5.0}},
        'no_type_controller': {'joint': 'flap_joint', 'pid': {'p': 1.0}},
        'bad_type_controller': {
            'type': 'velocity_controllers/JointPositionController',
            'joint': 'flap_joint',
        },
        'bad_joint_controller': {'type': JPC, 'joint': 'elbow_joint', 'pid': {'p': 1.0}},
        'passive_controller': {'type': JPC, 'joint': 'passive_joint', 'pid': {'p': 1.0}},
        'no_p_controller': {'type': JPC, 'joint': 'flap_joint', 'pid': {'i': 1.0, 'd': 0.1}},
        'no_rate_controller': {'type': JSC},
    }
}


@pytest.fixture(name='rig')
def mixed_rig():
    """A controller manager over DefaultRobotHWSim of MIXED_URDF: (cm, hw, robot, ros)."""
    model = parse_urdf(MIXED_URDF)
    robot = FakeRobot(list(model.joints))
    hw = DefaultRobotHWSim(model, robot)
    ros = FakeRos(PARAMS)
    cm = ControllerManager(hw, ros.node_handle, MIXED_NS + '/')
    return cm, hw, robot, ros


def states(cm):
    return {name: state for name, _, state, _ in cm.list_controllers()}


# ------------------------------------------------------------- joint position controller
class PositionControllerRig:
    """One JointPositionController on a fake robot with the mixed joints."""

    def __init__(self, joint, pid):
        self.robot = FakeRobot(list(parse_urdf(MIXED_URDF).joints))
        self.hw = DefaultRobotHWSim(parse_urdf(MIXED_URDF), self.robot)
        self.ros = FakeRos({'mixed_ns': {'c': {'type': JPC, 'joint': joint, 'pid': pid}}})
        self.c = JointPositionController()
        self.c.name = 'c'
        self.c.init(self.hw, self.ros.node_handle(MIXED_NS), self.ros.node_handle(MIXED_NS + '/c'))
        self.joint = joint
        self.t = 0

    def at(self, position, velocity=0.0):
        self.robot.set(self.joint, position, velocity)
        self.hw.read()

    def start(self):
        self.c.start_request(self.t)

    def stop(self):
        self.c.stop_request(self.t)

    def update(self, n=1):
        for _ in range(n):
            self.c.update(self.t, MS)
            self.t += MS
        return self.hw.handles[self.joint].command

    def command(self, value):
        return self.ros.publish(MIXED_NS + '/c/command', value)

    def states(self):
        return self.ros.messages(MIXED_NS + '/c/state')


# ------------------------------------------------------------ joint trajectory controller
class FakeHW:
    def __init__(self, joints, interface=EFFORT_JOINT_INTERFACE):
        self.handles = {n: JointHandle(n, t, interface=interface) for n, t in joints.items()}

    def joint_names(self):
        return sorted(self.handles)

    def get_handle(self, name, interface, controller_ns):
        if name not in self.handles or self.handles[name].interface != interface:
            raise ControllerError('no joint %s with %s for %s' % (name, interface, controller_ns))
        return self.handles[name]


def params(**extra):
    p = {
        'type': 'effort_controllers/JointTrajectoryController',
        'joints': ['j1', 'j2'],
        'gains': {'j1': {'p': 100.0, 'd': 10.0}, 'j2': {'p': 50.0, 'd': 5.0}},
        # Linear segments end at speed: a perfectly following joint needs one update to
        # stop, and upstream's goal_time 0 would abort at once on stopped_velocity_tolerance.
        'constraints': {'goal_time': 0.1},
    }
    p.update(extra)
    return p


class TrajectoryRig:
    """A JTC over j1 (revolute) and j2 (continuous). ``follow`` makes the joints track the
    desired state exactly, so the goal logic is seen apart from the dynamics."""

    def __init__(self, **extra):
        self.hw = FakeHW({'j1': 'revolute', 'j2': 'continuous'})
        self.ros = FakeRos({'arm': {'jtc': params(**extra)}})
        self.c = JointTrajectoryController()
        self.c.name = 'jtc'
        self.c.init_request(
            self.hw,
            self.ros.node_handle(TRAJECTORY_NS),
            self.ros.node_handle(TRAJECTORY_NS + '/jtc'),
        )
        self.server = self.ros.action_servers[TRAJECTORY_NS + '/jtc/follow_joint_trajectory']
        self.t = 5 * S  # sim time when started
        self.follow = True
        self.stuck = set()

    def joint(self, name):
        return self.hw.handles[name]

    def start(self):
        self.c.start_request(self.t)

    def step(self, n=1):
        for _ in range(n):
            self.t += MS
            self.c.update(self.t, MS)
            if self.follow:
                for i, name in enumerate(self.c.joint_names):
                    if name in self.stuck:
                        continue
                    _, (p, v, _) = sample(self.c.trajectory[i], self.c.uptime)
                    self.joint(name).position, self.joint(name).velocity = p, v

    def desired(self, i=0):
        return sample(self.c.trajectory[i], self.c.uptime)[1]

    def goal(self, points, names=('j1', 'j2'), stamp=0, **goal):
        traj = dict(
            stamp=stamp,
            joint_names=list(names),
            points=[
                dict(positions=list(p), time_from_start=int(t * S), **kw)
                for t, p, kw in ((pt[0], pt[1], pt[2] if len(pt) > 2 else {}) for pt in points)
            ],
        )
        return self.server.send_goal(dict(trajectory=traj, **goal))


# ------------------------------------------------------------------- trajectory chatter
JOINTS = ['joint1', 'joint2', 'joint3', 'joint4']
START_STEP = 50  # the controller starts 50 ms after spawn, mid-fall


def trajectory_params():
    with open(os.path.join(REPO_ROOT, 'config', 'controllers_trajectory.yaml')) as f:
        return yaml.safe_load(f)


def largest_speed_at_the_end(arm1_urdf, joint_limits):
    """The test's first goal from a mid-fall start; the joints' largest |velocity| over the
    last half second of 2 s after the trajectory's end."""
    ros = FakeRos(trajectory_params())
    with open(os.path.join(REPO_ROOT, 'worlds', 'willow_garage.world')) as f:
        sim = Simulation(parse_world(f.read()))
    try:
        model = sim.spawn_urdf(
            'arm1',
            arm1_urdf,
            robot_namespace='/arm1',
            find_package=lambda pkg: REPO_ROOT,
            controller_manager_factory=lambda hw, ns: ControllerManager(hw, ros.node_handle, ns),
        )
        model.hw.set_joint_limits(joint_limits)
        cm = model.controller_manager
        for _ in range(START_STEP):
            sim.step()
        cm.load_controller('arm_controller')
        assert switch_while_updating(cm, ['arm_controller'], [], sim.step, 1, poll=0.0005)[0]
        for _ in range(200):
            sim.step()
        points = [
            dict(positions=[0.5, 0.7, 0.3, 0.2], time_from_start=2 * S),
            dict(positions=[-0.4, 1.0, 0.1, -0.1], time_from_start=4 * S),
        ]
        cm.controller('arm_controller').on_command(dict(stamp=0, joint_names=JOINTS, points=points))
        index = model.robot.indices(JOINTS)
        largest = 0.0
        for k in range(6000):
            sim.step()
            if k >= 5500:
                largest = max(largest, max(abs(v) for _, v in model.robot.read(index)))
        return largest
    finally:
        sim.close()


# ------------------------------------------------------------------------------ pacer
class FakeClock:
    def __init__(self, t=100.0):
        self.t = t
        self.sleeps = []  # (kind, seconds)
        self.wake_after = None  # a nap is cut short after this many seconds, once

    def __call__(self):
        return self.t

    def sleep(self, dt):
        assert dt > 0
        self.sleeps.append(('sleep', dt))
        self.t += dt

    def nap(self, dt):
        assert dt > 0
        if self.wake_after is not None and self.wake_after < dt:
            self.sleeps.append(('woken', self.wake_after))
            self.t += self.wake_after
            self.wake_after = None
            return True
        self.sleeps.append(('nap', dt))
        self.t += dt
        return False


# -------------------------------------------------------------------- diff drive rover
GROUND = """<?xml version="1.0"?>
<sdf version="1.6"><world name="default">
  <physics type="ode"><max_step_size>0.001</max_step_size></physics>
  <model name="ground_plane"><static>true</static><link name="link">
    <collision name="collision"><geometry><plane><normal>0 0 1</normal><size>100 100</size>
    </plane></geometry></collision></link></model>
</world></sdf>"""


def spawn(sim, **params):
    model = sim.spawn_urdf('two_wheels', robot_urdf(**params))
    drives = [s for s in model.sensors if isinstance(s, DiffDrive)]
    assert len(drives) == 1
    drive = drives[0]
    readings = []
    drive.deliver = lambda stamp, reading: readings.append((stamp, reading))
    return model, drive, readings


def run(sim, seconds):
    for _ in range(int(round(seconds / 0.001))):
        sim.step()


# ------------------------------------------------- position-driven gripper and its box
POS = 'hardware_interface/PositionJointInterface'
LIFT_TOP = 0.12  # the lift's travel, m


def prismatic(name, parent, xyz, axis, lower, upper, effort):
    return """
  <joint name="%s" type="prismatic"><parent link="%s"/><child link="%s_link"/>
    <origin xyz="%s"/><axis xyz="%s"/>
    <limit lower="%g" upper="%g" effort="%g" velocity="0.5"/></joint>""" % (
        name,
        parent,
        name,
        xyz,
        axis,
        lower,
        upper,
        effort,
    )


# A palm on a vertical lift, two fingers 8 cm apart sliding toward each other (closed at
# 0.03 each: inner faces 2 cm apart), 10 N each; the 4 cm box between them on the ground.
GRIPPER = (
    '<robot name="carrier"><link name="world"/>'
    + box_link('base', '0.05 0.05 0.02', 1.0)
    + box_link('lift_link', '0.06 0.12 0.02', 0.3)
    + box_link('left_link', '0.04 0.02 0.08', 0.05, xyz='0 0 -0.04')
    + box_link('right_link', '0.04 0.02 0.08', 0.05, xyz='0 0 -0.04')
    + '<joint name="fix" type="fixed"><parent link="world"/><child link="base"/>'
    '<origin xyz="0.5 0 0.5"/></joint>'
    + prismatic('lift', 'base', '0 0 -0.38', '0 0 1', 0, LIFT_TOP, 50)
    + prismatic('left', 'lift_link', '0 0.05 -0.01', '0 -1 0', 0, 0.03, 10)
    + prismatic('right', 'lift_link', '0 -0.05 -0.01', '0 1 0', 0, 0.03, 10)
    + ''.join(transmission(j, POS) for j in ('lift', 'left', 'right'))
    + control_plugin('/carrier')
    + '</robot>'
)
BOX = '<robot name="box">%s</robot>' % box_link('box', '0.04 0.04 0.04', 0.05)

CONTROLLERS = {
    '%s_controller' % j: {'type': 'position_controllers/JointPositionController', 'joint': j}
    for j in ('lift', 'left', 'right')
}


# ----------------------------------------------------------------------- state sensors
G = 9.8


def world(ground: bool = True, gravity: Tuple[float, float, float] = (0.0, 0.0, -G)) -> Simulation:
    models = [StaticModel('ground_plane', (0, 0, 0, 0, 0, 0), [Shape('plane', (0, 0, 1))])]
    return Simulation(WorldConfig(gravity=gravity, models=models if ground else []))


def inertial(mass: float, xyz: str = '0 0 0', i: float = 0.01) -> str:
    return (
        '<inertial><origin xyz="%s"/><mass value="%g"/>'
        '<inertia ixx="%g" ixy="0" ixz="0" iyy="%g" iyz="0" izz="%g"/></inertial>'
        % (xyz, mass, i, i, i)
    )


def box(name: str, mass: float = 1.0, size: float = 0.2) -> str:
    i = mass * size * size / 6
    return (
        '<link name="%s">%s<collision><geometry><box size="%g %g %g"/></geometry></collision>'
        '</link>' % (name, inertial(mass, i=i), size, size, size)
    )


def robot(body: str, gazebo: str = '', name: str = 'r') -> str:
    return '<robot name="%s">%s%s</robot>' % (name, body, gazebo)


def listen(model: Model) -> Dict[str, List[Tuple[int, Any]]]:
    """Every sensor of the model wanted, its readings by sensor name."""
    got: Dict[str, List[Tuple[int, Any]]] = {}
    for sensor in model.sensors:
        readings = got.setdefault(sensor.name, [])
        sensor.wanted = lambda: True
        sensor.deliver = lambda t, r, readings=readings: readings.append((t, r))
    return got


def steps(sim: Simulation, n: int) -> None:
    for _ in range(n):
        sim.step()


# ----------------------------------------------------------------- generated messages
DEFINITIONS = os.path.join(REPO_ROOT, 'tools', 'compat_msgs')
ACTION_PARTS = (
    'Goal',
    'Result',
    'Feedback',
    'ActionGoal',
    'ActionResult',
    'ActionFeedback',
    'Action',
)


def generated_class(type_name: str) -> Any:
    """The python class genpy made for a msg or srv type ('pkg/Name')."""
    pkg, name = type_name.split('/')
    for kind in ('msg', 'srv'):
        module = importlib.import_module('%s.%s' % (pkg, kind))
        if hasattr(module, name):
            return getattr(module, name)
    raise AssertionError('%s: no generated class in %s.msg or %s.srv' % (type_name, pkg, pkg))


# the packages tools/make_compat_packages.py builds from tools/compat_msgs
COMPAT_PACKAGES = ('gazebo_msgs', 'control_msgs', 'controller_manager_msgs')


def types_defined_here(packages: Sequence[str] = COMPAT_PACKAGES) -> List[str]:
    """Every type the definition files yield, actions expanded as genaction does."""
    names = []
    for pkg in packages:
        for kind in ('msg', 'srv', 'action'):
            folder = os.path.join(DEFINITIONS, pkg, kind)
            for fname in sorted(os.listdir(folder)) if os.path.isdir(folder) else []:
                base = fname.rsplit('.', 1)[0]
                if kind == 'action':
                    names += ['%s/%s%s' % (pkg, base, part) for part in ACTION_PARTS]
                else:
                    names.append('%s/%s' % (pkg, base))
    return sorted(names)
