"""The message registry (control/message_types.py) against the real message classes: every
type the controllers register is filled with the fields the controllers publish (and their
actions' results and feedback, their services' responses), run in pybullet, through the
ROS layer's fills (ros/control/messages.py), and serialised by genpy, which refuses a
misspelt field or a value of the wrong type. The rospy-free fakes accept anything."""

import importlib.util
import io
import os

import pytest
from conftest import (
    MIXED_URDF,
    REPO_ROOT,
    WORLD_FILE,
    FakeNodeHandle,
    FakeRos,
    mixed_params,
    pump_switch,
)

from _arm1sim.control import message_types as types
from _arm1sim.control.controller_manager import ControllerManager
from _arm1sim.control.registry import CONTROLLER_TYPES
from _arm1sim.description.sdf_world import read_world
from _arm1sim.ros.control.messages import FILLS, MessageTypeError, action, message, service
from _arm1sim.sim.simulation import Simulation

_spec = importlib.util.spec_from_file_location(
    'toy_panda', os.path.join(REPO_ROOT, 'test', 'robots', 'toy_panda.py')
)
assert _spec is not None and _spec.loader is not None
toy_panda = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(toy_panda)

ARM = ['toy_joint%d' % i for i in range(1, 8)]
POSE = [0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785]
GAINS = {'p': 600.0, 'd': 30.0}
PANDA = {
    'arm_id': 'toy',
    'motion_generators': {'position': {'gains': {j: dict(GAINS) for j in ARM}}},
    'franka_state_controller': {
        'type': 'franka_control/FrankaStateController',
        'arm_id': 'toy',
        'joint_names': ARM,
    },
    'franka_gripper': {
        'type': 'franka_gazebo/FrankaGripperSim',
        'arm_id': 'toy',
        'finger1': {'gains': {'p': 100.0, 'd': 1.0}},
        'finger2': {'gains': {'p': 100.0, 'd': 1.0}},
    },
    'jtc': {'type': 'position_controllers/JointTrajectoryController', 'joints': ARM},
    # loaded only (they subscribe to their commands): the arm is the trajectory's
    'group': {'type': 'position_controllers/JointGroupPositionController', 'joints': ARM},
    'one': {'type': 'position_controllers/JointPositionController', 'joint': 'toy_joint1'},
}


class Recording(FakeNodeHandle):
    """A fake node handle that also keeps the type of every subscription."""

    def subscribe(self, topic, type_name, callback):
        self.ros.subscribed.add(type_name)
        return super().subscribe(topic, type_name, callback)


class RecordingRos(FakeRos):
    def __init__(self, params):
        super().__init__(params)
        self.subscribed = set()

    def node_handle(self, namespace):
        return Recording(self, namespace)


def serialised(msg):
    buffer = io.BytesIO()
    msg.serialize(buffer)  # genpy checks every field's type here
    return buffer.getvalue()


def filled(cls, fill, fields, what):
    msg = cls()
    try:
        fill(msg, fields)
        return serialised(msg)
    except Exception as exc:  # name the type and fields in the failure
        raise AssertionError('%s with %r: %s: %s' % (what, fields, type(exc).__name__, exc))


@pytest.fixture(scope='module')
def ran():
    """Every registered controller type's publishing, run: arm1-like joints (position
    controllers, joint states) and a Panda-like arm (trajectory, Franka state, gripper)."""
    sim = Simulation(read_world(WORLD_FILE))
    ros = RecordingRos({**mixed_params(), **PANDA})

    def spawn(name, urdf, namespace=''):
        model = sim.spawn_urdf(
            name,
            urdf,
            robot_namespace=namespace,
            controller_manager_factory=lambda hw, ns: ControllerManager(hw, ros.node_handle, ns),
        )
        model.hw.init_sim(ros.node_handle(model.namespace), model.namespace)
        return model.controller_manager

    mixed = spawn('mixed', MIXED_URDF)
    panda = spawn('toy', toy_panda.urdf('toy'), '/')
    sim.set_model_configuration('toy', ARM, POSE)
    names = ['joint_state_controller', 'flap_controller', 'slider_controller']
    for name in names:
        mixed.load_controller(name)
    assert pump_switch(mixed, names)[0]
    for name in ('franka_state_controller', 'franka_gripper', 'jtc', 'group', 'one'):
        panda.load_controller(name)
    assert pump_switch(panda, ['franka_state_controller', 'franka_gripper', 'jtc'])[0]

    def run(seconds):
        for _ in range(int(seconds / sim.period)):
            sim.step()

    run(0.1)
    servers = ros.action_servers
    point = dict(positions=POSE, velocities=[], accelerations=[], effort=[])
    servers['/jtc/follow_joint_trajectory'].send_goal(
        dict(
            trajectory=dict(
                stamp=0, joint_names=ARM, points=[dict(point, time_from_start=200_000_000)]
            ),
            path_tolerance=[],
            goal_tolerance=[],
            goal_time_tolerance=0,
        )
    )
    ros.services['/jtc/query_state'](dict(time=sim.time_ns))
    gripper = '/franka_gripper/'
    servers[gripper + 'move'].send_goal(dict(width=0.06, speed=0.1))
    run(0.3)
    servers[gripper + 'stop'].send_goal({})
    servers[gripper + 'grasp'].send_goal(
        dict(width=0.02, speed=0.1, force=5.0, epsilon=dict(inner=0.005, outer=0.005))
    )
    run(0.5)
    servers[gripper + 'gripper_action'].send_goal(dict(command=dict(position=0.03, max_effort=0)))
    run(0.4)
    servers[gripper + 'homing'].send_goal({})
    run(0.1)
    servers[gripper + 'stop'].send_goal({})  # homing takes seconds: interrupted, it ends
    run(0.01)
    yield ros
    sim.close()


def test_every_registered_message_is_published_or_subscribed_to_by_a_controller(ran):
    published = {p.type_name for pubs in ran.publishers.values() for p in pubs if p.messages}
    assert set(types.MESSAGES) == published | ran.subscribed
    assert {s.type_name for s in ran.action_servers.values()} == set(types.ACTIONS)
    assert CONTROLLER_TYPES  # the controllers' modules, imported, registered the types


def test_published_fields_fill_the_real_messages(ran):
    for pubs in ran.publishers.values():
        for pub in pubs:
            cls, fill, _ = message(pub.type_name)
            for fields in pub.messages[:3] + pub.messages[-3:]:
                filled(cls, fill, fields, '%s on %s' % (pub.type_name, pub.topic))


def test_action_results_and_feedback_fill_the_real_messages(ran):
    for server in ran.action_servers.values():
        spec, read_goal, result_cls, feedback_cls, fill_feedback = action(server.type_name)
        goal_cls = type(spec().action_goal.goal)
        read_goal(goal_cls())  # a goal as actionlib delivers it reads
        assert server.goals, server.name
        for gh in server.goals:
            assert gh.result is not None, (server.name, gh.status)
            filled(result_cls, FILLS[types.FIELDS], gh.result, server.type_name + ' result')
            for fields in gh.feedback[:3]:
                filled(feedback_cls, fill_feedback, fields, server.type_name + ' feedback')


def test_subscribed_types_read_the_real_messages_and_services_answer(ran):
    for type_name in ran.subscribed:
        cls, _, read = message(type_name)
        read(cls())
    for type_name in types.SERVICES:
        srv, read_request = service(type_name)
        read_request(srv._request_class())


def test_the_registry_refuses_a_conflict_and_names_an_unknown_type():
    types.register_message('sensor_msgs/JointState', types.STAMPED)  # again, the same: fine
    with pytest.raises(TypeError, match='sensor_msgs/JointState: registered as'):
        types.register_message('sensor_msgs/JointState', types.FIELDS)
    with pytest.raises(TypeError, match='none of'):
        types.register_message('std_msgs/String', 'as_yaml')
    with pytest.raises(TypeError, match='<package>/<Name>'):
        types.register_message('String', types.FIELDS)
    with pytest.raises(MessageTypeError, match='std_msgs/Int8 is registered by no controller'):
        message('std_msgs/Int8')
    types.MESSAGES['nonexistent_msgs/Thing'] = types.MessageType()
    try:
        with pytest.raises(MessageTypeError, match='nonexistent_msgs/Thing: no nonexistent_msgs'):
            message('nonexistent_msgs/Thing')
    finally:
        del types.MESSAGES['nonexistent_msgs/Thing']
