"""franka_gazebo's FrankaHWSim, FrankaGripperSim and franka_control's FrankaStateController
without ROS, on a Panda-like arm of our own (test/robots/toy_panda.py) in pybullet: the model
interface's figures (mass matrix, gravity, Jacobian), the arm holding while idle, an effort
controller's switch, the state published, the gripper's move and grasp, and the C++
example controllers refused by name."""

import importlib.util
import math
import os

import numpy as np
import pybullet as p
import pytest
from conftest import REPO_ROOT, WORLD_FILE, FakeRos

from _arm1sim.control.controller_manager import ControllerManager, ControllerManagerError
from _arm1sim.control.switching import switch_while_updating
from _arm1sim.description.sdf_world import read_world
from _arm1sim.sim.simulation import Simulation, SpawnError
from _arm1sim.vendors.franka.gripper_sim import FrankaGripperSim
from _arm1sim.vendors.franka.hw_sim import FrankaHWSim
from _arm1sim.vendors.franka.interfaces import ROBOT_MODE_IDLE, ROBOT_MODE_MOVE

_spec = importlib.util.spec_from_file_location(
    'toy_panda', os.path.join(REPO_ROOT, 'test', 'robots', 'toy_panda.py')
)
assert _spec is not None and _spec.loader is not None
toy_panda = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(toy_panda)

ARM = ['toy_joint%d' % i for i in range(1, 8)]
POSE = [0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785]  # franka_gazebo's default start pose
FINGERS = ['toy_finger_joint1', 'toy_finger_joint2']
# franka_gazebo's sim_controllers.yaml gains
PD = [(600, 30), (600, 30), (600, 30), (600, 30), (250, 10), (150, 10), (50, 5)]
GAINS = {
    'motion_generators': {
        'position': {'gains': {j: {'p': kp, 'd': kd, 'i': 0.0} for j, (kp, kd) in zip(ARM, PD)}},
    },
    'arm_id': 'toy',
    'm_ee': 0.76,
}


@pytest.fixture
def rig():
    """A world with the toy Panda at POSE, FrankaHWSim set up from ``GAINS``, a manager."""
    sim = Simulation(read_world(WORLD_FILE))
    params = {
        **GAINS,
        'franka_state_controller': {
            'type': 'franka_control/FrankaStateController',
            'arm_id': 'toy',
            'publish_rate': 30,
            'joint_names': ARM,
        },
        'effort_ctrl': {'type': 'effort_controllers/JointGroupEffortController', 'joints': ARM},
        'position_ctrl': {
            'type': 'position_controllers/JointGroupPositionController',
            'joints': ARM,
        },
        'franka_gripper': {
            'type': 'franka_gazebo/FrankaGripperSim',
            'arm_id': 'toy',
            'finger1': {'gains': {'p': 100.0, 'd': 1.0}},
            'finger2': {'gains': {'p': 100.0, 'd': 1.0}},
        },
        'impedance': {'type': 'franka_example_controllers/CartesianImpedanceExampleController'},
    }
    ros = FakeRos(params)
    model = sim.spawn_urdf(
        'toy',
        toy_panda.urdf('toy'),
        robot_namespace='/',
        controller_manager_factory=lambda hw, ns: ControllerManager(hw, ros.node_handle, ns),
    )
    sim.set_model_configuration('toy', ARM + FINGERS, POSE + [0.02, 0.02])
    assert isinstance(model.hw, FrankaHWSim)
    model.hw.init_sim(ros.node_handle('/'), '/')
    yield sim, model, ros
    sim.close()


def run(sim, seconds):
    for _ in range(int(round(seconds / sim.period))):
        sim.step()


def positions(model, joints):
    return [pos for pos, _ in model.robot.read(model.robot.indices(joints))]


def test_the_robot_sim_type_makes_a_franka_hw_sim_with_each_transmissions_interfaces(rig):
    sim, model, ros = rig
    hw = model.hw
    assert hw.arm_id == 'toy' and hw.root_link == 'toy_link0' and hw.tip_link == 'toy_link8'
    for interface in ('Effort', 'Position', 'Velocity'):
        name = 'hardware_interface/%sJointInterface' % interface
        assert hw.get_handle('toy_joint4', name, '/c').interface == name
    with pytest.raises(Exception, match='toy_finger_joint1'):
        hw.get_handle('toy_finger_joint1', 'hardware_interface/PositionJointInterface', '/c')
    assert ros.messages('/initialized') == [{'data': False}]


def test_model_interface_mass_matrix_gravity_and_jacobian(rig):
    sim, model, _ = rig
    run(sim, 0.01)
    m = model.hw.franka_model('toy_model', '/c')
    mass = np.array(m.mass())
    assert mass.shape == (7, 7)
    assert np.allclose(mass, mass.T, atol=1e-9)
    assert np.all(np.linalg.eigvalsh(mass) > 0)
    # Gravity: pybullet's inverse dynamics at rest, and what holds the arm up (below).
    q = model.hw.q_all  # the state as last read
    zero = [0.0] * len(q)
    tau = p.calculateInverseDynamics(
        model.robot.body, q, zero, zero, physicsClientId=model.robot.client
    )
    columns = model.hw.dynamics.columns
    assert m.gravity() == pytest.approx([tau[c] for c in columns], abs=1e-9)
    assert abs(m.gravity()[1]) > 1.0  # the shoulder carries the arm
    # Jacobian: its linear rows move the end effector as a small joint step does.
    jac = np.array(m.zero_jacobian())
    before = np.array(m.pose()[12:15])
    dq = 1e-4
    j2 = model.robot.joint_index['toy_joint2']
    p.resetJointState(model.robot.body, j2, q[columns[1]] + dq, physicsClientId=model.robot.client)
    after = np.array(m.pose()[12:15])
    assert (after - before) / dq == pytest.approx(jac[:3, 1], abs=2e-3)


def test_idle_arm_holds_its_pose_with_gravity_compensation(rig):
    sim, model, ros = rig
    run(sim, 1.0)
    assert positions(model, ARM) == pytest.approx(POSE, abs=0.01)
    assert model.hw.state.robot_mode == ROBOT_MODE_IDLE
    assert ros.messages('/initialized')[-1] == {'data': True}


def test_effort_controller_switch_moves_the_arm_and_gravity_stays_compensated(rig):
    sim, model, ros = rig
    cm = model.controller_manager
    cm.load_controller('effort_ctrl')
    cm.load_controller('franka_state_controller')
    switch_while_updating(cm, ['effort_ctrl', 'franka_state_controller'], [], sim.step)
    assert model.hw.state.robot_mode == ROBOT_MODE_MOVE
    # Zero effort commanded: gravity compensation alone leaves the arm nearly where it was.
    run(sim, 0.3)
    assert positions(model, ARM) == pytest.approx(POSE, abs=0.05)
    states = ros.messages('/franka_state_controller/franka_states')
    assert len(states) >= 9  # 30 Hz over 0.3 s
    last = states[-1]
    assert last['q'] == pytest.approx(positions(model, ARM), abs=0.01)
    assert last['robot_mode'] == ROBOT_MODE_MOVE
    assert last['m_ee'] == 0.76 and last['m_total'] == 0.76
    joints = ros.messages('/franka_state_controller/joint_states')[-1]
    assert joints['name'] == ARM
    assert ros.messages('/franka_state_controller/F_ext')[-1]['frame_id'] == 'toy_K'
    # O_T_EE is a rigid transform with the end effector below the flange's reach
    o_t_ee = np.array(last['O_T_EE']).reshape(4, 4).T
    assert np.allclose(o_t_ee[:3, :3] @ o_t_ee[:3, :3].T, np.eye(3), atol=1e-6)
    assert 0.0 < o_t_ee[2, 3] < 1.3


def test_gripper_moves_and_grasps(rig):
    sim, model, ros = rig
    cm = model.controller_manager
    cm.load_controller('franka_gripper')
    switch_while_updating(cm, ['franka_gripper'], [], sim.step)
    move = ros.action_servers['/franka_gripper/move'].send_goal(dict(width=0.07, speed=0.1))
    run(sim, 1.0)
    assert move.status == 'SUCCEEDED' and move.result['success'] is True
    assert sum(positions(model, FINGERS)) == pytest.approx(0.07, abs=0.003)
    close = ros.action_servers['/franka_gripper/gripper_action'].send_goal(
        dict(command=dict(position=0.01, max_effort=0.0))
    )
    run(sim, 1.0)
    assert close.status == 'SUCCEEDED' and close.result['reached_goal'] is True
    assert sum(positions(model, FINGERS)) == pytest.approx(0.02, abs=0.003)
    bad = ros.action_servers['/franka_gripper/move'].send_goal(dict(width=0.2, speed=0.1))
    assert bad.status == 'ABORTED' and 'between 0 .. 0.08' in bad.result['error']


def test_gripper_grasp_holds_when_the_fingers_are_blocked():
    """A grasp ends when the fingers rest, then presses with half the force on each."""
    from _arm1sim.control.hardware_interface import EFFORT_JOINT_INTERFACE, JointHandle

    class Hand:
        def __init__(self):
            self.h = {
                n: JointHandle(n, 'prismatic', interface=EFFORT_JOINT_INTERFACE) for n in FINGERS
            }

        def joint_names(self):
            return FINGERS

        def get_handle(self, name, interface, ns):
            return self.h[name]

    hand = Hand()
    for h in hand.h.values():
        h.position = 0.02  # blocked here: the fingers never move
    gains = {'gains': {'p': 100.0}}
    ros = FakeRos({'g': {'arm_id': 'toy', 'finger1': gains, 'finger2': gains}})
    c = FrankaGripperSim()
    c.init_request(hand, ros.node_handle('/'), ros.node_handle('/g'))
    c.start_request(0)
    goal = dict(width=0.038, speed=0.1, force=30.0, epsilon=dict(inner=0.005, outer=0.005))
    gh = ros.action_servers['/g/grasp'].send_goal(goal)
    for k in range(20):
        c.update(k * 1000000, 1000000)
    assert gh.status == 'SUCCEEDED' and gh.result['success'] is True
    assert c.mode == 'holding'
    assert hand.h[FINGERS[0]].command == pytest.approx(-15.0, abs=1.0)  # closing, 30 N / 2
    wide = ros.action_servers['/g/grasp'].send_goal(dict(goal, width=0.02))
    for k in range(20, 40):
        c.update(k * 1000000, 1000000)
    assert wide.status == 'SUCCEEDED' and wide.result['success'] is False
    assert 'was not at' in wide.result['error']


def test_cpp_example_controllers_are_refused_by_name(rig):
    _, model, _ = rig
    with pytest.raises(ControllerManagerError) as err:
        model.controller_manager.load_controller('impedance')
    message = str(err.value)
    assert 'franka_example_controllers/CartesianImpedanceExampleController' in message
    assert 'C++ controller plugin of franka_ros' in message


def test_a_franka_robot_without_the_state_transmission_is_refused_by_name():
    text = toy_panda.urdf('toy')
    start = text.index('<transmission name="toy_franka_state">')
    end = text.index('</transmission>', start) + len('</transmission>')
    sim = Simulation(read_world(WORLD_FILE))
    try:
        with pytest.raises(SpawnError, match='FrankaStateInterface'):
            sim.spawn_urdf('toy', text[:start] + text[end:])
        assert 'toy' not in sim.models
    finally:
        sim.close()


def test_gravity_torques_hold_the_arm_still_in_pybullet(rig):
    """The gravity vector is what the physics needs: applied alone (no PID), the arm stays."""
    sim, model, _ = rig
    hw = model.hw
    hw.do_switch([[('hardware_interface/EffortJointInterface', ARM)]], [])
    run(sim, 0.5)
    assert positions(model, ARM) == pytest.approx(POSE, abs=0.02)
    assert all(math.isfinite(v) for v in hw.state.tau_ext_hat_filtered)
    assert max(abs(v) for v in hw.state.tau_ext_hat_filtered) < 1.0


def test_gripper_grasp_closing_on_nothing_holds_at_the_joint_limit(rig):
    """Closed on nothing, the fingers stop at their limit (where pybullet leaves them
    jittering step to step) and the grasp of width 0 succeeds, holding."""
    sim, model, ros = rig
    cm = model.controller_manager
    cm.load_controller('franka_gripper')
    switch_while_updating(cm, ['franka_gripper'], [], sim.step)
    goal = dict(width=0.0, speed=0.1, force=20.0, epsilon=dict(inner=0.005, outer=0.005))
    gh = ros.action_servers['/franka_gripper/grasp'].send_goal(goal)
    run(sim, 1.0)
    assert gh.status == 'SUCCEEDED' and gh.result['success'] is True
    assert cm.controller('franka_gripper').mode == 'holding'
    assert sum(positions(model, FINGERS)) == pytest.approx(0.0, abs=0.002)


def test_position_commands_go_through_the_motion_generator_pids_and_stopping_holds(rig):
    """A position controller's commands are the hardware's PID setpoints; once it stops, the
    arm holds where it was (idle) and the state says IDLE."""
    sim, model, ros = rig
    cm = model.controller_manager
    cm.load_controller('position_ctrl')
    switch_while_updating(cm, ['position_ctrl'], [], sim.step)
    target = [0.3, -0.5, 0.2, -2.0, 0.2, 1.8, 0.5]
    ros.publish('/position_ctrl/command', target)
    run(sim, 2.0)
    assert positions(model, ARM) == pytest.approx(target, abs=0.02)
    assert model.hw.state.q_d == pytest.approx(target)
    switch_while_updating(cm, [], ['position_ctrl'], sim.step)
    assert model.hw.state.robot_mode == ROBOT_MODE_IDLE
    held = positions(model, ARM)
    run(sim, 1.0)
    assert positions(model, ARM) == pytest.approx(held, abs=0.01)


MIMIC_PLUGIN = (
    '<gazebo><plugin name="finger_mimic" '
    'filename="libroboticsgroup_upatras_gazebo_mimic_joint_plugin.so">'
    '<joint>toy_finger_joint1</joint><mimicJoint>toy_finger_joint2</mimicJoint></plugin></gazebo>'
)


@pytest.mark.parametrize('declared', ['urdf', 'plugin'])
def test_a_mimic_finger_is_driven_as_gazebo_drives_it(declared):
    """franka_description's finger_joint2 has a URDF <mimic> of finger_joint1, which Gazebo 11
    ignores (sdformat 9 reads none): FrankaHWSim drops it and applies the gripper's effort to
    both fingers (an effort of 50 N opens finger 2 to its stop). A mimic plugin acts in Gazebo:
    its follower stays a mimic and gets no effort from the hardware (issue 21), so 50 N is
    not applied on top of the mimic's motor."""
    from _arm1sim.control.hardware_interface import EFFORT_JOINT_INTERFACE

    sim = Simulation(read_world(WORLD_FILE))
    text = toy_panda.urdf('toy')
    if declared == 'urdf':
        marker = '<joint name="toy_finger_joint2" type="prismatic">'
        head, joint2 = text.split(marker)
        text = (
            head
            + marker
            + joint2.replace(
                '<axis xyz="0 -1 0"/>', '<axis xyz="0 -1 0"/><mimic joint="toy_finger_joint1"/>', 1
            )
        )
        assert text.count('<mimic') == 1
    else:
        text = text.replace('</robot>', MIMIC_PLUGIN + '</robot>')
    ros = FakeRos(dict(GAINS))
    model = sim.spawn_urdf(
        'toy',
        text,
        robot_namespace='/',
        controller_manager_factory=lambda hw, ns: ControllerManager(hw, ros.node_handle, ns),
    )
    try:
        sim.set_model_configuration('toy', ARM + FINGERS, POSE + [0.02, 0.02])
        model.hw.init_sim(ros.node_handle('/'), '/')
        follower = model.hw.get_handle(FINGERS[1], EFFORT_JOINT_INTERFACE, '/test')
        follower.command = 50.0  # pushes it open at 50 N, when applied
        run(sim, 0.5)
        index = model.robot.indices([FINGERS[1]])[0]
        motor = p.getJointState(model.robot.body, index, physicsClientId=model.robot.client)[3]
        leader, follower_q = positions(model, FINGERS)
        if declared == 'urdf':
            assert model.robot.mimics == [] and follower.effort == pytest.approx(50.0)
            assert follower_q == pytest.approx(0.04, abs=1e-3)  # at its stop
        else:
            # the mimic's motor holds the follower at its leader without fighting 50 N (what
            # it does push: the free leader's and follower's own drift as the arm holds)
            assert len(model.robot.mimics) == 1 and abs(motor) < 5.0
            assert follower_q == pytest.approx(leader, abs=1e-4)
    finally:
        sim.close()
