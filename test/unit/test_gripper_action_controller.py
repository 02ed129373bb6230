"""gripper_action_controller's semantics without ROS: goals to a position, success within
goal_tolerance, stall detection (ABORTED, stalled), preemption, cancel and the two
hardware_interface adapters."""

import logging
import os

import pytest
from conftest import REPO_ROOT, WORLD_FILE, FakeRos

from _arm1sim.control.controller import ControllerError
from _arm1sim.control.gripper_action_controller import (
    GripperActionController,
    PositionGripperActionController,
)
from _arm1sim.control.hardware_interface import (
    EFFORT_JOINT_INTERFACE,
    POSITION_JOINT_INTERFACE,
    JointHandle,
)
from _arm1sim.control.registry import CONTROLLER_TYPES
from _arm1sim.description.sdf_world import read_world
from _arm1sim.sim.simulation import Simulation

NS = '/bot'
DT_NS = 1000000  # 1 kHz
S = 1000000000


class FakeHW:
    def __init__(self, interface):
        self.handle = JointHandle('finger', 'prismatic', interface=interface)

    def joint_names(self):
        return ['finger']

    def get_handle(self, name, interface, controller_ns):
        if name != 'finger' or interface != self.handle.interface:
            raise ControllerError('no joint %s with %s for %s' % (name, interface, controller_ns))
        return self.handle


class Rig:
    """A gripper controller over one finger joint; ``wall`` stops the finger there (the
    object), and the joint otherwise moves at ``speed`` toward its command (position) or
    with the sign of the effort (effort)."""

    def __init__(self, cls=GripperActionController, **params):
        interface = POSITION_JOINT_INTERFACE if cls.commands_position else EFFORT_JOINT_INTERFACE
        self.hw = FakeHW(interface)
        p = {'type': cls.type_name, 'joint': 'finger', 'gains': {'finger': {'p': 100.0}}}
        p.update(params)
        self.ros = FakeRos({'bot': {'gripper': p}})
        self.c = cls()
        self.c.name = 'gripper'
        self.c.init_request(
            self.hw, self.ros.node_handle(NS), self.ros.node_handle(NS + '/gripper')
        )
        self.server = self.ros.action_servers[NS + '/gripper/gripper_cmd']
        self.t = 3 * S
        self.wall = None
        self.speed = 0.05  # m/s

    @property
    def joint(self):
        return self.hw.handle

    def step(self, n=1):
        j = self.joint
        for _ in range(n):
            self.t += DT_NS
            self.c.update(self.t, DT_NS)
            if self.c.commands_position:
                delta = j.command - j.position
            else:
                delta = j.command
            v = 0.0 if abs(delta) < 1e-9 else self.speed * (1 if delta > 0 else -1)
            if self.c.commands_position and abs(delta) < self.speed * 1e-3:
                v = delta / 1e-3
            new = j.position + v * 1e-3
            if self.wall is not None and new > self.wall:
                new, v = self.wall, 0.0
            j.position, j.velocity = new, v

    def goal(self, position, max_effort=10.0):
        return self.server.send_goal(dict(command=dict(position=position, max_effort=max_effort)))


def test_both_types_are_registered_with_their_interfaces():
    assert CONTROLLER_TYPES['effort_controllers/GripperActionController'].interface == (
        EFFORT_JOINT_INTERFACE
    )
    assert CONTROLLER_TYPES['position_controllers/GripperActionController'].interface == (
        POSITION_JOINT_INTERFACE
    )


def test_upstream_defaults():
    c = Rig().c
    assert (
        c.goal_tolerance,
        c.default_max_effort,
        c.stall_velocity_threshold,
        c.stall_timeout,
    ) == (
        0.01,
        0.0,
        0.001,
        1.0,
    )


def test_a_missing_joint_parameter_fails_the_load_naming_the_namespace():
    with pytest.raises(ControllerError, match="'joint' not set in namespace /bot/gripper"):
        _load_without_joint()


def _load_without_joint():
    ros = FakeRos({'bot': {'gripper': {'type': 'effort_controllers/GripperActionController'}}})
    GripperActionController().init_request(
        FakeHW(EFFORT_JOINT_INTERFACE), ros.node_handle(NS), ros.node_handle(NS + '/gripper')
    )


def test_a_goal_while_stopped_is_rejected():
    r = Rig()
    assert r.goal(0.03).status == 'REJECTED'


def test_a_reached_goal_succeeds_with_reached_goal_and_the_measured_position():
    r = Rig()
    r.c.start_request(r.t)
    gh = r.goal(0.03)
    assert gh.status == 'ACTIVE'
    r.step(2000)
    assert gh.status == 'SUCCEEDED'
    assert gh.result['reached_goal'] is True and gh.result['stalled'] is False
    assert abs(gh.result['position'] - 0.03) < 0.01
    assert gh.feedback == []  # upstream publishes none


def test_closing_on_an_object_aborts_as_stalled_after_the_stall_timeout():
    r = Rig(stall_timeout=0.5)
    r.c.start_request(r.t)
    r.wall = 0.02
    gh = r.goal(0.05, max_effort=3.0)
    r.step(400)  # 0.02 m at 0.05 m/s: at the wall from 0.4 s
    assert gh.status == 'ACTIVE'
    r.step(450)  # still within the 0.5 s stall timeout
    assert gh.status == 'ACTIVE'
    r.step(150)
    assert gh.status == 'ABORTED'
    assert gh.result['stalled'] is True and gh.result['reached_goal'] is False
    assert gh.result['position'] == pytest.approx(0.02)
    assert gh.result['effort'] == pytest.approx(3.0)  # the clamped PID effort


def test_effort_is_clamped_to_the_goals_max_effort():
    r = Rig()
    r.c.start_request(r.t)
    r.goal(0.05, max_effort=-2.0)  # the magnitude counts
    r.step()
    assert r.joint.command == pytest.approx(2.0)


def test_zero_max_effort_never_moves_and_stalls():
    r = Rig()
    r.c.start_request(r.t)
    gh = r.goal(0.05, max_effort=0.0)
    r.step(1100)
    assert r.joint.position == 0.0
    assert gh.status == 'ABORTED' and gh.result['stalled'] is True


def test_position_variant_writes_the_goal_position_and_reports_max_effort():
    r = Rig(PositionGripperActionController)
    r.c.start_request(r.t)
    r.wall = 0.02
    gh = r.goal(0.05, max_effort=4.0)
    r.step()
    assert r.joint.command == 0.05
    r.step(1500)
    assert gh.status == 'ABORTED'
    assert gh.result['effort'] == 4.0 and gh.result['stalled'] is True


def test_a_new_goal_preempts_the_active_one():
    r = Rig()
    r.c.start_request(r.t)
    first = r.goal(0.05)
    second = r.goal(0.01)
    assert first.status == 'PREEMPTED' and second.status == 'ACTIVE'


def test_cancel_holds_the_current_position_at_the_default_max_effort():
    r = Rig(max_effort=1.5)
    r.c.start_request(r.t)
    gh = r.goal(0.05, max_effort=5.0)
    r.step(200)
    r.server.cancel(gh)
    assert gh.status == 'PREEMPTED'
    assert r.c.position == pytest.approx(r.joint.position)
    assert r.c.max_effort == 1.5


def test_start_holds_where_the_joint_is():
    r = Rig(max_effort=2.0)
    r.joint.position = 0.015
    r.c.start_request(r.t)
    assert (r.c.position, r.c.max_effort) == (0.015, 2.0)


def test_a_non_finite_goal_is_rejected_and_logged(caplog):
    r = Rig()
    r.c.start_request(r.t)
    with caplog.at_level(logging.ERROR, logger='_arm1sim.control'):
        gh = r.goal(float('nan'))
    assert gh.status == 'REJECTED'
    assert 'must be finite' in caplog.text


def test_missing_gains_only_warn_and_leave_the_finger_without_effort(caplog):
    with caplog.at_level(logging.WARNING, logger='_arm1sim.control'):
        r = Rig(gains={})
    r.c.start_request(r.t)
    r.goal(0.05, max_effort=5.0)
    r.step()
    assert r.joint.command == 0.0
    assert 'No p gain' in caplog.text


def test_stopping_cancels_the_active_goal():
    r = Rig()
    r.c.start_request(r.t)
    gh = r.goal(0.05)
    r.c.stop_request(r.t)
    assert gh.status == 'PREEMPTED' and r.joint.command == 0.0


# ------------------------------------------------------------- in real pybullet physics
def _closing_on_a_box(cls, interface, pid_gains=None):
    """gripper_bot (its right finger a mimic) closing on a box: the goal handle and finger
    positions after 3 s of sim time."""
    with open(os.path.join(REPO_ROOT, 'test', 'config', 'gripper_bot.urdf')) as f:
        urdf = f.read().replace(
            'left_finger_joint"><hardwareInterface>hardware_interface/EffortJointInterface',
            'left_finger_joint"><hardwareInterface>hardware_interface/' + interface,
        )
    with open(os.path.join(REPO_ROOT, 'test', 'config', 'gripper_box.urdf')) as f:
        box = f.read()
    sim = Simulation(read_world(WORLD_FILE))
    try:
        model = sim.spawn_urdf('gripper', urdf)
        sim.spawn_urdf('box', box, position=(0, 0, 0.335))
        if pid_gains:
            model.hw.set_pid_gains({'left_finger_joint': pid_gains})
        params = {
            'joint': 'left_finger_joint',
            'gains': {'left_finger_joint': {'p': 200.0, 'd': 5.0}},
            'stall_timeout': 0.5,
            'stall_velocity_threshold': 0.02,  # contact jitter: see docs/controllers.md
        }
        ros = FakeRos({'gripper_bot': {'g': params}})
        c = cls()
        c.init_request(model.hw, ros.node_handle('/gripper_bot'), ros.node_handle('/gripper_bot/g'))
        c.start_request(sim.time_ns)
        gh = ros.action_servers['/gripper_bot/g/gripper_cmd'].send_goal(
            dict(command=dict(position=0.06, max_effort=2.0))
        )
        for _ in range(3000):
            model.hw.read()
            c.update(sim.time_ns, sim.step_ns)
            model.hw.write()
            sim.step()
        idx = model.robot.indices(['left_finger_joint', 'right_finger_joint'])
        return gh, [pos for pos, _ in model.robot.read(idx)]
    finally:
        sim.close()


def test_effort_gripper_stalls_on_a_box_in_physics_and_the_mimic_finger_mirrors():
    gh, (left, right) = _closing_on_a_box(GripperActionController, 'EffortJointInterface')
    assert gh.status == 'ABORTED' and gh.result['stalled'] is True
    assert left == pytest.approx(0.04, abs=0.003)  # the box's face
    assert right == pytest.approx(-left, abs=0.002)


def test_position_gripper_stalls_with_the_hardwares_pid_gains():
    gh, (left, _) = _closing_on_a_box(
        PositionGripperActionController, 'PositionJointInterface', {'p': 200.0, 'd': 5.0}
    )
    assert gh.status == 'ABORTED' and gh.result['stalled'] is True
    assert left == pytest.approx(0.04, abs=0.003)


def test_position_gripper_set_directly_stops_on_the_box_beyond_gazebo():
    # Gazebo's SetPosition puts the finger through the box (reached_goal); ours moves it
    # with a motor capped at its effort limit, so it stops on the box's face and stalls
    # (docs/manipulation.md, "Position joints").
    gh, (left, _) = _closing_on_a_box(PositionGripperActionController, 'PositionJointInterface')
    assert gh.status == 'ABORTED' and gh.result['stalled'] is True
    assert left == pytest.approx(0.04, abs=0.003)
