"""effort_controllers/JointTrajectoryController (control/joint_trajectory_controller.py and
control/trajectory.py) against joint_trajectory_controller's semantics, without ROS: goals
go through the in-process action server of tuning/local_ros.py."""

import math

import pytest
from conftest import FakeRos
from helpers import FakeHW, params
from helpers import TrajectoryRig as Rig

from _arm1sim.control.controller import ControllerError
from _arm1sim.control.hardware_interface import (
    POSITION_JOINT_INTERFACE,
    VELOCITY_JOINT_INTERFACE,
)
from _arm1sim.control.joint_trajectory_controller import (
    GOAL_TOLERANCE_VIOLATED,
    INVALID_GOAL,
    INVALID_JOINTS,
    PATH_TOLERANCE_VIOLATED,
    SUCCESSFUL,
    JointTrajectoryController,
    PositionJointTrajectoryController,
    VelocityJointTrajectoryController,
)
from _arm1sim.control.registry import CONTROLLER_TYPES
from _arm1sim.control.trajectory import Segment, State, hold_segment, sample

NS = '/arm'
DT_NS = 1000000  # 1 kHz
S = 1000000000
JTC = 'effort_controllers/JointTrajectoryController'


@pytest.fixture
def rig():
    r = Rig()
    r.start()
    return r


# --------------------------------------------------------------------------- splines
def test_positions_only_interpolate_linearly():
    seg = Segment(1.0, State(0.0), 3.0, State(2.0))
    assert seg.sample(2.0) == pytest.approx((1.0, 1.0, 0.0))


def test_velocities_make_a_cubic_meeting_both_velocities():
    seg = Segment(0.0, State(0.0, 0.0), 2.0, State(1.0, 0.5))
    assert seg.sample(0.0)[1] == pytest.approx(0.0)
    assert seg.sample(2.0)[:2] == pytest.approx((1.0, 0.5))
    assert seg.coefs[4] == seg.coefs[5] == 0.0


def test_accelerations_make_a_quintic_meeting_all_three():
    seg = Segment(0.0, State(0.0, 1.0, 2.0), 1.5, State(3.0, -1.0, 0.5))
    assert seg.sample(0.0) == pytest.approx((0.0, 1.0, 2.0))
    assert seg.sample(1.5) == pytest.approx((3.0, -1.0, 0.5))


def test_mixed_end_points_fall_to_the_lower_order():
    seg = Segment(0.0, State(0.0, 1.0, 2.0), 1.0, State(1.0))
    assert seg.sample(0.5) == pytest.approx((0.5, 1.0, 0.0))  # linear


def test_outside_a_segment_the_joint_is_at_rest():
    seg = Segment(1.0, State(0.0, 1.0), 2.0, State(1.0, 1.0))
    assert seg.sample(0.5) == (0.0, 0.0, 0.0)
    assert seg.sample(5.0) == pytest.approx((1.0, 0.0, 0.0))


def test_hold_with_stop_duration_comes_to_rest_from_the_current_velocity():
    seg = hold_segment(0.0, 1.0, 2.0, stop_duration=0.5)
    assert seg.sample(0.0)[:2] == pytest.approx((1.0, 2.0))
    p, v, a = seg.sample(0.5)
    assert p > 1.0 and v == pytest.approx(0.0, abs=1e-9) and a == pytest.approx(0.0, abs=1e-9)


# --------------------------------------------------------------------------- init
def test_registered_under_upstreams_type_name():
    assert CONTROLLER_TYPES[JTC] is JointTrajectoryController


def test_missing_gains_fail_the_load_naming_the_joint():
    hw = FakeHW({'j1': 'revolute', 'j2': 'revolute'})
    ros = FakeRos({'arm': {'jtc': params(gains={'j1': {'p': 1.0}})}})
    c = JointTrajectoryController()
    with pytest.raises(ControllerError, match='gains/j2'):
        c.init_request(hw, ros.node_handle(NS), ros.node_handle(NS + '/jtc'))


def test_unknown_joint_in_joints_fails_the_load():
    hw = FakeHW({'j1': 'revolute'})
    ros = FakeRos({'arm': {'jtc': params()}})
    with pytest.raises(ControllerError, match='j2'):
        JointTrajectoryController().init_request(
            hw, ros.node_handle(NS), ros.node_handle(NS + '/jtc')
        )


# --------------------------------------------------------------------------- goals
def test_start_holds_the_measured_position():
    r = Rig()
    r.joint('j1').position = 0.7
    r.start()
    r.follow = False
    r.step(10)
    assert r.desired(0) == (0.7, 0.0, 0.0)


def test_goal_reached_succeeds_with_code_0(rig):
    gh = rig.goal([(0.5, (0.2, 0.1)), (1.0, (0.4, -0.3))])
    assert gh.status == 'ACTIVE'
    rig.step(900)
    assert gh.status == 'ACTIVE'
    assert rig.desired(0)[0] == pytest.approx(0.36, abs=1e-3)  # linear, second segment
    rig.step(200)
    assert gh.status == 'SUCCEEDED'
    assert gh.result == {'error_code': SUCCESSFUL, 'error_string': ''}
    assert rig.joint('j1').position == pytest.approx(0.4)
    assert gh.feedback and gh.feedback[-1]['joint_names'] == ['j1', 'j2']


def test_unknown_joint_is_rejected_with_invalid_joints_naming_it(rig):
    before = [list(t) for t in rig.c.trajectory]
    gh = rig.goal([(1.0, (0.2, 0.1))], names=('j1', 'elbow'))
    assert gh.status == 'REJECTED'
    assert gh.result['error_code'] == INVALID_JOINTS
    assert "'elbow'" in gh.result['error_string']
    assert rig.c.trajectory == before


@pytest.mark.parametrize(
    'points, culprit',
    [
        ([(1.0, (0.2,))], 'Point 0 has 1 positions for 2 joints'),
        ([(1.0, (0.2, float('nan')))], 'positions of joint j2 is nan'),
        ([(1.0, (0.2, 0.1), dict(velocities=[0.0]))], 'Size mismatch'),
        ([(1.0, (0.2, 0.1)), (1.0, (0.3, 0.1))], 'not strictly increasing'),
        ([(0.0, (0.2, 0.1))], 'Dropping all 1 trajectory point(s)'),
    ],
)
def test_bad_goal_is_rejected_with_invalid_goal_naming_the_culprit(rig, points, culprit):
    gh = rig.goal(points)
    assert gh.status == 'REJECTED'
    assert gh.result['error_code'] == INVALID_GOAL
    assert culprit in gh.result['error_string']
    rig.step(5)
    assert rig.desired(0) == (0.0, 0.0, 0.0)  # still holding


def test_partial_goal_needs_allow_partial_joints_goal(rig):
    gh = rig.goal([(0.5, (0.3,))], names=('j1',))
    assert gh.status == 'REJECTED' and gh.result['error_code'] == INVALID_JOINTS
    assert 'missing: j2' in gh.result['error_string']


def test_partial_goal_moves_only_its_joints_when_allowed():
    r = Rig(allow_partial_joints_goal=True)
    r.joint('j2').position = 1.0
    r.start()
    gh = r.goal([(0.5, (0.3,))], names=('j1',))
    assert gh.status == 'ACTIVE'
    r.step(600)
    assert gh.status == 'SUCCEEDED'
    assert r.joint('j1').position == pytest.approx(0.3)
    assert r.desired(1)[0] == 1.0


def test_empty_goal_holds_and_succeeds_at_the_next_update(rig):
    gh = rig.goal([])
    assert gh.status == 'ACTIVE'
    rig.step(1)
    assert gh.status == 'SUCCEEDED'


def test_new_goal_preempts_and_bridges_from_the_desired_state(rig):
    first = rig.goal([(1.0, (1.0, 0.0))])
    rig.step(500)
    p_before, v_before, _ = rig.desired(0)
    second = rig.goal([(1.0, (-1.0, 0.0))])
    assert first.status == 'PREEMPTED' and first.result['error_code'] == SUCCESSFUL
    assert second.status == 'ACTIVE'
    rig.step(1)
    p_after, _, _ = rig.desired(0)
    assert abs(p_after - p_before) < 2 * abs(v_before) * 1e-3 + 1e-6  # no jump
    rig.step(1100)
    assert second.status == 'SUCCEEDED' and rig.joint('j1').position == pytest.approx(-1.0)


def test_future_stamp_lets_the_old_trajectory_run_until_then(rig):
    rig.goal([(2.0, (2.0, 0.0))])
    rig.step(100)
    stamp = rig.t + S // 2  # new trajectory starts 0.5 s from now
    rig.goal([(1.0, (0.0, 0.0))], stamp=stamp)
    rig.step(400)
    assert rig.desired(0)[1] == pytest.approx(1.0)  # still the first one's velocity


def test_topic_command_preempts_the_goal(rig):
    gh = rig.goal([(1.0, (1.0, 0.0))])
    rig.ros.publish(
        NS + '/jtc/command',
        dict(
            stamp=0,
            joint_names=['j2', 'j1'],
            points=[dict(positions=[0.5, -0.5], time_from_start=S)],
        ),
    )
    assert gh.status == 'PREEMPTED'
    rig.step(1100)
    assert rig.joint('j1').position == pytest.approx(-0.5)
    assert rig.joint('j2').position == pytest.approx(0.5)


def test_cancel_preempts_and_holds_where_the_arm_is(rig):
    gh = rig.goal([(1.0, (1.0, 0.0))])
    rig.step(300)
    here = rig.joint('j1').position
    rig.server.cancel(gh)
    assert gh.status == 'PREEMPTED'
    rig.step(1000)
    assert rig.joint('j1').position == pytest.approx(here)


def test_path_tolerance_violation_aborts_with_upstreams_string_and_keeps_moving():
    r = Rig(constraints={'j1': {'trajectory': 0.05}})
    r.start()
    r.stuck.add('j1')
    gh = r.goal([(1.0, (1.0, 0.0))])
    r.step(100)
    assert gh.status == 'ABORTED'
    assert gh.result['error_code'] == PATH_TOLERANCE_VIOLATED
    assert gh.result['error_string'].startswith('j1 path error 0.05')
    assert len(gh.result['error_string'].split()[-1].split('.')[1]) == 6  # std::to_string
    r.step(100)
    assert r.desired(0)[0] > 0.1  # an aborted trajectory keeps executing, as upstream


def test_goal_tolerance_waits_goal_time_then_aborts():
    r = Rig(constraints={'goal_time': 0.5, 'j1': {'goal': 0.01}})
    r.start()
    gh = r.goal([(0.5, (0.3, 0.0))])
    r.step(400)
    r.stuck.add('j1')  # stops 0.06 short
    r.step(500)
    assert gh.status == 'ACTIVE'  # within goal_time
    r.step(600)
    assert gh.status == 'ABORTED' and gh.result['error_code'] == GOAL_TOLERANCE_VIOLATED
    assert gh.result['error_string'].startswith('j1 goal error 0.0')


def test_goal_tolerances_override_the_defaults(rig):
    rig.stuck.add('j1')
    gh = rig.goal([(0.2, (0.3, 0.0))], goal_tolerance=[dict(name='j1', position=0.01)])
    rig.step(300)
    assert gh.status == 'ABORTED' and gh.result['error_code'] == GOAL_TOLERANCE_VIOLATED


def test_default_goal_check_succeeds_wherever_a_still_arm_is(rig):
    rig.stuck.add('j1')  # never moves, but is still: upstream's defaults say success
    gh = rig.goal([(0.2, (0.3, 0.0))])
    rig.step(300)
    assert gh.status == 'SUCCEEDED'


def test_continuous_joint_takes_the_short_way_round(rig):
    gh = rig.goal([(1.0, (0.0, 2 * math.pi + 0.1))])
    rig.step(1100)
    assert gh.status == 'SUCCEEDED'
    assert rig.joint('j2').position == pytest.approx(0.1)


def test_velocities_in_points_give_a_cubic_path(rig):
    rig.goal([(1.0, (1.0, 0.0), dict(velocities=[0.0, 0.0]))])
    rig.step(250)
    assert rig.desired(0)[0] == pytest.approx(3 * 0.25**2 - 2 * 0.25**3, abs=1e-3)


def test_effort_is_pid_on_position_error_with_d_on_velocity_error(rig):
    rig.follow = False
    rig.goal([(1.0, (1.0, 0.0))])
    rig.joint('j1').velocity = 0.2
    rig.step(1)
    p, v, _ = rig.desired(0)
    assert rig.joint('j1').command == pytest.approx(100.0 * p + 10.0 * (v - 0.2))


def test_time_going_back_keeps_the_trajectory_running(rig):
    gh = rig.goal([(1.0, (1.0, 0.0))])
    rig.step(300)
    rig.t = 0  # reset_simulation
    rig.step(800)
    assert gh.status == 'SUCCEEDED'
    gh2 = rig.goal([(0.5, (0.0, 0.0))], stamp=rig.t)  # stamped in the new time base
    assert gh2.status == 'ACTIVE'
    rig.step(600)
    assert gh2.status == 'SUCCEEDED' and rig.joint('j1').position == pytest.approx(0.0)


def test_query_state_samples_the_future(rig):
    rig.goal([(1.0, (1.0, 0.0))])
    rig.step(1)
    out = rig.ros.services[NS + '/jtc/query_state'](dict(time=rig.t + S // 2))
    assert out['name'] == ['j1', 'j2']
    assert out['position'][0] == pytest.approx(0.5, abs=2e-3)


def test_goals_are_rejected_when_not_running():
    r = Rig()
    gh = r.goal([(1.0, (1.0, 0.0))])
    assert gh.status == 'REJECTED' and gh.result['error_code'] == INVALID_GOAL


def test_stopping_preempts_the_goal_and_zeroes_the_effort(rig):
    gh = rig.goal([(1.0, (1.0, 0.0))])
    rig.step(10)
    rig.c.stop_request(rig.t)
    assert gh.status == 'PREEMPTED'
    assert rig.joint('j1').command == 0.0


def test_state_published_at_the_state_rate(rig):
    rig.step(1000)
    msgs = rig.ros.messages(NS + '/jtc/state')
    assert 45 <= len(msgs) <= 51
    assert set(msgs[-1]) >= {'desired', 'actual', 'error', 'joint_names', 'stamp'}


# --------------------------------------------------------------------------- variants
def load(cls, interface, **extra):
    hw = FakeHW({'j1': 'revolute', 'j2': 'continuous'}, interface)
    ros = FakeRos({'arm': {'jtc': params(**extra)}})
    c = cls()
    c.init_request(hw, ros.node_handle(NS), ros.node_handle(NS + '/jtc'))
    return c, hw, ros


def test_variants_registered_under_upstreams_type_names():
    assert (
        CONTROLLER_TYPES['position_controllers/JointTrajectoryController']
        is PositionJointTrajectoryController
    )
    assert (
        CONTROLLER_TYPES['velocity_controllers/JointTrajectoryController']
        is VelocityJointTrajectoryController
    )


def test_effort_variant_refuses_position_joints():
    with pytest.raises(ControllerError, match='EffortJointInterface'):
        load(JointTrajectoryController, POSITION_JOINT_INTERFACE)


def test_position_variant_commands_the_desired_position_without_gains():
    c, hw, ros = load(PositionJointTrajectoryController, POSITION_JOINT_INTERFACE, gains={})
    hw.handles['j1'].position = 0.3
    c.start_request(0)
    assert hw.handles['j1'].command == 0.3  # holds where it is
    gh = ros.action_servers[NS + '/jtc/follow_joint_trajectory'].send_goal(
        dict(
            trajectory=dict(
                stamp=0,
                joint_names=['j1', 'j2'],
                points=[dict(positions=[1.3, 0.0], time_from_start=S)],
            )
        )
    )
    assert gh.status == 'ACTIVE'
    for k in range(1, 501):
        c.update(k * DT_NS, DT_NS)
    assert hw.handles['j1'].command == pytest.approx(0.8, abs=2e-3)


def test_velocity_variant_commands_ff_plus_pid():
    c, hw, ros = load(
        VelocityJointTrajectoryController, VELOCITY_JOINT_INTERFACE, velocity_ff={'j1': 1.0}
    )
    c.start_request(0)
    ros.publish(
        NS + '/jtc/command',
        dict(
            stamp=0,
            joint_names=['j1', 'j2'],
            points=[dict(positions=[1.0, 0.0], time_from_start=S)],
        ),
    )
    c.update(DT_NS, DT_NS)
    _, (p, v, _) = sample(c.trajectory[0], c.uptime)
    assert hw.handles['j1'].command == pytest.approx(1.0 * v + 100.0 * p + 10.0 * v)
    c.stop_request(DT_NS)
    assert hw.handles['j1'].command == 0.0


def test_restart_holds_the_new_measured_position_also_with_a_stop_duration():
    r = Rig(stop_trajectory_duration=0.2)
    r.start()
    r.goal([(0.5, (0.5, 0.0))])
    r.step(700)
    r.c.stop_request(r.t)
    r.joint('j1').position, r.joint('j1').velocity = -0.2, 0.0
    r.start()
    r.follow = False
    r.step(300)
    assert r.desired(0) == pytest.approx((-0.2, 0.0, 0.0))
