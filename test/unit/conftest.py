"""Shared fakes and fixtures for the ROS-free unit tests.

Nothing here imports rospy: controllers and the controller manager talk to a
``FakeRos`` (a parameter tree plus recorded publishers and subscribers) through
``FakeNodeHandle``s, which implement the NodeHandle Protocol of
``arm1/control/interfaces.py``.
"""

from __future__ import annotations

import os
import sys
from typing import TYPE_CHECKING, Any, Callable, Dict, List, Optional, Sequence, Tuple

import pytest

# src/ first on the path (pytest may run outside the workspace); the root then comes from arm1.
SRC = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'src'))
if SRC not in sys.path:
    sys.path.insert(0, SRC)

from _arm1sim.control.controller_manager import ControllerManager  # noqa: E402  (after SRC)
from _arm1sim.control.interfaces import Fields, NodeFactory, Params  # noqa: E402
from _arm1sim.control.switching import switch_while_updating  # noqa: E402
from _arm1sim.paths import repo_root  # noqa: E402
from _arm1sim.tuning.local_ros import LocalNodeHandle, LocalRos  # noqa: E402

REPO_ROOT = repo_root()

ARM1_XACRO = os.path.join(REPO_ROOT, 'urdf', 'arm1.urdf.xacro')
CONTROLLERS_YAML = os.path.join(REPO_ROOT, 'config', 'controllers.yaml')
WORLD_FILE = os.path.join(REPO_ROOT, 'worlds', 'willow_garage.world')

JPC = 'effort_controllers/JointPositionController'
JSC = 'joint_state_controller/JointStateController'


# --------------------------------------------------------------------------- node handles
class FakePublisher:
    def __init__(self, topic: str, type_name: str, queue_size: int) -> None:
        self.topic, self.type_name, self.queue_size = topic, type_name, queue_size
        self.messages: List[Fields] = []
        self.subscribed = True  # a test sets False: nobody listens (what wanted() says)

    def wanted(self) -> bool:
        return self.subscribed

    def publish(self, fields: Fields) -> None:
        self.messages.append(fields)


class FakeNodeHandle(LocalNodeHandle):
    """The tuner's in-process node handle, also keeping every publisher it made."""

    ros: FakeRos

    def __init__(self, ros: FakeRos, namespace: str) -> None:
        super().__init__(ros, namespace)
        self.publishers: List[FakePublisher] = []
        self.is_shutdown = False
        ros.handles.append(self)

    @property
    def subscriptions(self) -> List[Tuple[str, Callable[[Any], object]]]:
        return self._subscriptions

    def advertise(self, topic: str, type_name: str, queue_size: int) -> FakePublisher:
        pub = FakePublisher(self.resolve(topic), type_name, queue_size)
        self.publishers.append(pub)
        self.ros.publishers.setdefault(pub.topic, []).append(pub)
        return pub

    def shutdown(self) -> None:
        self.is_shutdown = True
        super().shutdown()
        for pub in self.publishers:
            self.ros.publishers[pub.topic].remove(pub)
        self.publishers = []


class FakeRos(LocalRos):
    """LocalRos (parameters as a dict tree, topics as lists) that keeps every message."""

    def __init__(self, params: Optional[Params] = None) -> None:
        super().__init__(params)
        self.handles: List[FakeNodeHandle] = []
        self.publishers: Dict[str, List[FakePublisher]] = {}

    def node_handle(self, namespace: str) -> FakeNodeHandle:
        """The ``node_factory`` a ControllerManager takes."""
        return FakeNodeHandle(self, namespace)

    def messages(self, topic: str) -> List[Fields]:
        out: List[Fields] = []
        for pub in self.publishers.get(topic, []):
            out.extend(pub.messages)
        return out


if TYPE_CHECKING:  # mypy holds both in-process node handles to the NodeHandle Protocol
    _factories: Tuple[NodeFactory, ...] = (LocalRos().node_handle, FakeRos().node_handle)


# --------------------------------------------------------------------------- physics fakes
class FakeRobot:
    """Stands in for physics.robot.Robot under DefaultRobotHWSim."""

    def __init__(self, joint_names: Sequence[str]) -> None:
        self.joint_index = {n: i for i, n in enumerate(joint_names)}
        self.state = {i: (0.0, 0.0) for i in self.joint_index.values()}
        self.applied: List[Tuple[List[int], List[float]]] = []  # per write
        self.motors: List[Tuple[List[int], List[float], List[float]]] = []  # velocity motors
        self.placed: List[Tuple[List[int], List[float]]] = []  # move_positions, per write
        self.position_forces: List[List[float]] = []  # move_positions' max forces, per write

    def indices(self, names: Sequence[str]) -> List[int]:
        return [self.joint_index[n] for n in names]

    def read(self, indices: Sequence[int]) -> List[Tuple[float, float]]:
        return [self.state[i] for i in indices]

    def apply_efforts(self, indices: Sequence[int], efforts: Sequence[float]) -> None:
        self.applied.append((list(indices), list(efforts)))

    def set_velocity_motors(
        self, indices: Sequence[int], velocities: Sequence[float], max_forces: Sequence[float]
    ) -> None:
        self.motors.append((list(indices), list(velocities), list(max_forces)))

    def move_positions(
        self,
        indices: Sequence[int],
        positions: Sequence[float],
        max_forces: Sequence[float],
        dt: float,
    ) -> None:
        self.placed.append((list(indices), list(positions)))
        self.position_forces.append(list(max_forces))

    def set(self, name: str, position: float, velocity: float = 0.0) -> None:
        self.state[self.joint_index[name]] = (position, velocity)


# --------------------------------------------------------------------------- URDF snippets
def transmission(
    joint: str,
    interface: str = 'hardware_interface/EffortJointInterface',
    name: Optional[str] = None,
) -> str:
    return """
  <transmission name="%s">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="%s"><hardwareInterface>%s</hardwareInterface></joint>
    <actuator name="m_%s"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>""" % (name or 'tran_' + joint, joint, interface, joint)


def box_link(name: str, size: str = '0.1 0.1 0.1', mass: float = 0.5, xyz: str = '0 0 0') -> str:
    sx, sy, sz = (float(v) for v in size.split())
    ixx, iyy, izz = (mass / 12.0 * (b * b + c * c) for b, c in ((sy, sz), (sx, sz), (sx, sy)))
    return """
  <link name="%s">
    <inertial><origin xyz="%s"/><mass value="%g"/>
      <inertia ixx="%g" ixy="0" ixz="0" iyy="%g" iyz="0" izz="%g"/></inertial>
    <visual><origin xyz="%s"/><geometry><box size="%s"/></geometry></visual>
    <collision><origin xyz="%s"/><geometry><box size="%s"/></geometry></collision>
  </link>""" % (name, xyz, mass, ixx, iyy, izz, xyz, size, xyz, size)


def cylinder_link(name: str, radius: float = 0.05, length: float = 0.02, mass: float = 0.5) -> str:
    izz = 0.5 * mass * radius**2
    ixx = mass * (3 * radius**2 + length**2) / 12.0
    return """
  <link name="%s">
    <inertial><mass value="%g"/>
      <inertia ixx="%g" ixy="0" ixz="0" iyy="%g" iyz="0" izz="%g"/></inertial>
    <visual><geometry><cylinder radius="%g" length="%g"/></geometry></visual>
    <collision><geometry><cylinder radius="%g" length="%g"/></geometry></collision>
  </link>""" % (name, mass, ixx, ixx, izz, radius, length, radius, length)


def control_plugin(namespace: Optional[str]) -> str:
    inner = '<robotNamespace>%s</robotNamespace>' % namespace if namespace is not None else ''
    return (
        """
  <gazebo>
    <plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so">%s
      <robotSimType>gazebo_ros_control/DefaultRobotHWSim</robotSimType>
    </plugin>
  </gazebo>"""
        % inner
    )


# A robot with one joint of each actuated kind, geometry made of primitives only.
#   world -fixed- base -continuous(z)- wheel
#                      -prismatic(x)-  slider  [-0.1, 0.2] m
#                      -revolute(z)-   flap    [-3, 3] rad (limits almost the full circle)
#                      -revolute(z)-   passive (PositionJointInterface: not simulated)
MIXED_URDF = (
    '<?xml version="1.0"?>\n<robot name="mixed">\n  <link name="world"/>'
    + box_link('base', '0.2 0.2 0.05', 2.0)
    + cylinder_link('wheel')
    + box_link('slider', '0.05 0.05 0.05', 0.5)
    + box_link('flap', '0.1 0.02 0.02', 0.2, xyz='0.05 0 0')
    + box_link('passive_link', '0.02 0.02 0.02', 0.05)
    + """
  <joint name="fixed_base_joint" type="fixed">
    <parent link="world"/><child link="base"/><origin xyz="0 0 0.5"/>
  </joint>
  <joint name="wheel_joint" type="continuous">
    <parent link="base"/><child link="wheel"/><origin xyz="0 0 0.1"/>
    <axis xyz="0 0 1"/><limit effort="1" velocity="20"/>
  </joint>
  <joint name="slider_joint" type="prismatic">
    <parent link="base"/><child link="slider"/><origin xyz="0 0 -0.1"/>
    <axis xyz="1 0 0"/><limit lower="-0.1" upper="0.2" effort="10" velocity="1"/>
  </joint>
  <joint name="flap_joint" type="revolute">
    <parent link="base"/><child link="flap"/><origin xyz="0 0 0.3"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="20"/>
  </joint>
  <joint name="passive_joint" type="revolute">
    <parent link="base"/><child link="passive_link"/><origin xyz="0.2 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>"""
    + transmission('wheel_joint', 'EffortJointInterface')
    + transmission('slider_joint')
    + transmission('flap_joint')
    + transmission('passive_joint', 'hardware_interface/PositionJointInterface')
    + control_plugin('/mixed_ns')
    + '\n</robot>\n'
)

MIXED_GAINS = {
    'wheel_joint': {'p': 2.0, 'd': 0.1},
    'slider_joint': {'p': 100.0, 'd': 20.0},
    'flap_joint': {'p': 1.0, 'd': 0.1},
}


def mixed_params() -> Params:
    ns = {'joint_state_controller': {'type': JSC, 'publish_rate': 100}}
    for joint, gains in MIXED_GAINS.items():
        ns[joint.replace('_joint', '') + '_controller'] = {
            'type': JPC,
            'joint': joint,
            'pid': dict(gains),
        }
    return {'mixed_ns': ns}


# --------------------------------------------------------------------------- helpers
def pump_switch(
    cm: ControllerManager,
    start: Sequence[str],
    stop: Sequence[str] = (),
    strictness: int = 2,
    timeout: float = 0.0,
    time_ns: int = 0,
    period_ns: int = 1000000,
    deadline: float = 2.0,
) -> Tuple[bool, int]:
    """``cm.switch_controller`` from a thread, as a ROS service calls it, while this thread
    keeps calling ``cm.update`` (the simulation loop). Returns what the call returned and
    how many updates ran before it did."""
    return switch_while_updating(
        cm,
        start,
        stop,
        lambda: cm.update(time_ns, period_ns),
        strictness,
        timeout,
        deadline,
        poll=0.002,
    )


# --------------------------------------------------------------------------- fixtures
@pytest.fixture
def fake_ros() -> FakeRos:
    return FakeRos()


@pytest.fixture(scope='session')
def arm1_urdf() -> str:
    """The arm1 description expanded by PyPI's xacro with ``$(find arm1)`` = this repo."""
    import xacro
    import xacro.substitution_args as sa

    saved = sa._eval_find, sa._eval_dict.get('find')
    sa._eval_find = lambda pkg: REPO_ROOT
    sa._eval_dict['find'] = sa._eval_find
    try:
        return xacro.process_file(ARM1_XACRO).toprettyxml()
    finally:
        sa._eval_find = saved[0]
        sa._eval_dict['find'] = saved[1]


@pytest.fixture(scope='session')
def controllers_params() -> Params:
    """config/controllers.yaml as the parameter server would hold it."""
    import yaml

    with open(CONTROLLERS_YAML) as f:
        return yaml.safe_load(f)


@pytest.fixture
def find_package() -> Callable[[str], str]:
    def find(pkg: str) -> str:
        if pkg == 'arm1':
            return REPO_ROOT
        raise LookupError(pkg)

    return find
