"""The one-pass update paths (JointPositionController.update_group, the controller manager's
runs of one type, DefaultRobotHWSim's inline effort saturation) give what the one-by-one
paths give, to the bit."""

import math
import random

from conftest import JPC, MIXED_URDF, FakeRobot, FakeRos

from _arm1sim.control.controller import Controller
from _arm1sim.control.controller_manager import _grouped
from _arm1sim.control.hardware_interface import saturate_effort
from _arm1sim.control.joint_position_controller import JointPositionController
from _arm1sim.control.joint_velocity_controller import JointVelocityController
from _arm1sim.description.urdf_model import parse_urdf
from _arm1sim.sim.robot_hw_sim import DefaultRobotHWSim

NS = '/mixed_ns'
JOINTS = ['wheel_joint', 'slider_joint', 'flap_joint']  # continuous, prismatic, revolute


def same(a, b):
    """Equal to the bit, NaN equal to NaN."""
    return repr(a) == repr(b)


class Rig:
    def __init__(self, cls):
        model = parse_urdf(MIXED_URDF)
        self.robot = FakeRobot(list(model.joints))
        self.hw = DefaultRobotHWSim(model, self.robot)
        params = {
            'c%d' % k: {'type': JPC, 'joint': j, 'pid': {'p': 3.0, 'i': 0.5, 'd': 0.2}}
            for k, j in enumerate(JOINTS)
        }
        self.ros = FakeRos({'mixed_ns': params})
        self.controllers = []
        for k in range(len(JOINTS)):
            c = cls()
            c.name = 'c%d' % k
            c.init(self.hw, self.ros.node_handle(NS), self.ros.node_handle('%s/c%d' % (NS, k)))
            c.start_request(0)
            self.controllers.append(c)

    def snapshot(self):
        out = []
        for c in self.controllers:
            pid = c.pid
            out.append(
                (c.joint.command, c._loop_count, pid.p_error_last, pid.p_error, pid.i_error)
                + (pid.d_error, pid.cmd, pid.p, pid.i, pid.d, pid.i_max, pid.i_min)
                + (pid.antiwindup,)
            )
            out.append(self.ros.messages('%s/%s/state' % (NS, c.name)))
        return out


def random_sequence(seed, n=3000):
    """Per update: (period_ns, [(position, velocity, target or None, gains or None)])."""
    rng = random.Random(seed)
    out = []
    for _ in range(n):
        period = rng.choice([1000000] * 8 + [0, 2000000, 1])
        joints = []
        for _ in JOINTS:
            position = rng.choice([rng.uniform(-4, 4)] * 20 + [math.nan, 1e308, -1e308])
            target = rng.uniform(-5, 5) if rng.random() < 0.05 else None
            gains = None
            if rng.random() < 0.01:
                clamp = rng.choice([0.0, 0.1, 2.0])
                gains = {
                    'p': rng.uniform(0, 10),
                    'i': rng.choice([0.0, rng.uniform(-2, 5)]),
                    'd': rng.uniform(0, 1),
                    'i_clamp_max': clamp,
                    'i_clamp_min': -clamp,
                    'antiwindup': rng.random() < 0.5,
                }
            joints.append((position, rng.uniform(-3, 3), target, gains))
        out.append((period, joints))
    return out


def drive(rig, sequence, one_pass):
    t = 0
    for period, joints in sequence:
        for name, c, (position, velocity, target, gains) in zip(JOINTS, rig.controllers, joints):
            rig.robot.set(name, position, velocity)
            if target is not None:
                c.set_target(target)
            if gains is not None:
                c.set_gains(gains)
        rig.hw.read()
        t += period
        if one_pass:
            type(rig.controllers[0]).update_group(rig.controllers, t, period)
        else:
            for c in rig.controllers:
                c.update(t, period)
    return rig.snapshot()


def test_position_controllers_in_one_pass_match_one_by_one_to_the_bit():
    for seed in range(3):
        sequence = random_sequence(seed)
        one = drive(Rig(JointPositionController), sequence, one_pass=True)
        each = drive(Rig(JointPositionController), sequence, one_pass=False)
        assert len(one) == len(each)
        for a, b in zip(one, each):
            assert same(a, b)
        # The sequences reach every branch: antiwindup, zero periods, non-finite errors.
        assert any(math.isnan(x) for x in [m['error'] for m in one[1]])


def test_velocity_controller_keeps_its_own_update_in_a_group():
    sequence = random_sequence(7, n=500)
    one = drive(Rig(JointVelocityController), sequence, one_pass=True)
    each = drive(Rig(JointVelocityController), sequence, one_pass=False)
    assert all(same(a, b) for a, b in zip(one, each))


def test_manager_groups_runs_of_one_type_in_order():
    a1, a2, a3 = JointPositionController(), JointPositionController(), JointPositionController()
    v = JointVelocityController()
    groups = _grouped([a1, a2, v, a3])
    assert [g[1] for g in groups] == [(a1, a2), (v,), (a3,)]
    assert groups[0][0] == JointPositionController.update_group
    assert groups[1][0] == JointVelocityController.update_group
    assert _grouped([]) == ()

    order = []

    class Recording(Controller):
        def update(self, time_ns, period_ns):
            order.append((self, time_ns, period_ns))

    r1, r2 = Recording(), Recording()
    for update_group, controllers in _grouped([r1, r2]):
        update_group(controllers, 5, 1)
    assert order == [(r1, 5, 1), (r2, 5, 1)]


def test_inline_effort_saturation_matches_saturate_effort():
    model = parse_urdf(MIXED_URDF)
    robot = FakeRobot(list(model.joints))
    hw = DefaultRobotHWSim(model, robot)
    torque = [d for d in hw._torque]
    assert hw._plain_efforts and len(hw._plain_efforts) == len(torque)
    rng = random.Random(3)
    values = [math.nan, math.inf, -math.inf, 0.0, 1e9, -1e9]
    for _ in range(3000):
        for d in torque:
            h = d.handle
            h.command = rng.choice([rng.uniform(-20, 20)] * 10 + values)
            h.position = rng.choice([rng.uniform(-4, 4)] * 10 + values)
            h.velocity = rng.choice([rng.uniform(-30, 30)] * 10 + values)
        hw.write()
        indices, efforts = robot.applied[-1]
        expected = [
            saturate_effort(d.handle.command, d.handle.position, d.handle.velocity, *d.bounds)
            for d in torque
        ]
        assert indices == [d.index for d in torque]
        assert all(same(a, b) for a, b in zip(efforts, expected))
        assert all(same(d.handle.effort, e) for d, e in zip(torque, expected))


def test_a_controller_with_an_update_of_its_own_instance_is_updated_alone():
    a1, a2, a3 = JointPositionController(), JointPositionController(), JointPositionController()
    seen = []
    a2.update = lambda time_ns, period_ns: seen.append((time_ns, period_ns))
    groups = _grouped([a1, a2, a3])
    assert [g[1] for g in groups] == [(a1,), (a2,), (a3,)]
    groups[1][0](groups[1][1], 3, 1)
    assert seen == [(3, 1)]
