"""The move_group stand-in's ROS-free planning core (_arm1sim.planning): SRDF groups,
kinematics, IK, the collision world, OMPL planning, time parameterization and Cartesian
paths, on test/robots/toy_panda.py (a seven-joint arm with two fingers) and its SRDF."""

from __future__ import annotations

import math
import os
import sys

import numpy as np
import pytest
import yaml

from _arm1sim.description.srdf import SrdfError, parse_srdf, resolve_group
from _arm1sim.planning import config as cfg
from _arm1sim.planning.cartesian import _cut_jumps
from _arm1sim.planning.ik import IkRequest, solve_ik
from _arm1sim.planning.kinematics import RobotKinematics
from _arm1sim.planning.pipeline import (
    Constraints,
    JointGoal,
    MotionRequest,
    OrientationConstraint,
    PlanningPipeline,
    PositionConstraint,
)
from _arm1sim.planning.scene import CollisionWorld, SceneObject, Shape
from _arm1sim.planning.time_parameterization import time_parameterize

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, 'test', 'robots'))
import toy_panda  # noqa: E402
import toy_panda_moveit  # noqa: E402

with open(os.path.join(REPO, 'test', 'config', 'toy_panda_moveit.yaml')) as _f:
    PARAMS = yaml.safe_load(_f)
ARM = ['toy_joint%d' % i for i in range(1, 8)]


@pytest.fixture(scope='module')
def robot():
    srdf = parse_srdf(toy_panda_moveit.srdf())
    model = RobotKinematics(
        toy_panda.urdf(), srdf, cfg.joint_limits_config(PARAMS['robot_description_planning'])
    )
    yield model
    model.close()


@pytest.fixture
def world(robot):
    w = CollisionWorld(robot)
    yield w
    w.clear()


@pytest.fixture
def pipeline(robot, world):
    srdf = robot.srdf
    return PlanningPipeline(
        robot,
        world,
        cfg.ompl_config(PARAMS['move_group'], list(srdf.groups)),
        cfg.kinematics_config(PARAMS['robot_description_kinematics']),
        seed=1,
    )


def ready(robot):
    state = {j: robot.default_position(j) for j in robot.variables}
    state.update(robot.srdf.group_states['toy_arm']['ready'])
    return state


# --- SRDF ------------------------------------------------------------------------------------


def test_srdf_groups_states_end_effectors_and_disabled_pairs(robot):
    srdf = robot.srdf
    assert set(srdf.groups) == {'toy_arm', 'hand', 'toy_arm_hand'}
    assert robot.group_joints('toy_arm') == ARM
    assert robot.group_joints('hand') == ['toy_finger_joint1', 'toy_finger_joint2']
    # a subgroup's joints join its parent's
    assert robot.group_joints('toy_arm_hand') == ARM + ['toy_finger_joint1', 'toy_finger_joint2']
    # the chain includes the fixed joint to the flange, which planning leaves out
    assert 'toy_joint8' in resolve_group(srdf, 'toy_arm', robot.tree)
    assert srdf.group_states['hand']['open'] == {
        'toy_finger_joint1': 0.035,
        'toy_finger_joint2': 0.035,
    }
    assert srdf.end_effectors[0].parent_link == 'toy_link8'
    assert robot.group_tip('toy_arm') == 'toy_link8'
    assert robot.model_frame == 'world'
    assert srdf.collision_disabled('toy_link2', 'toy_link1')
    assert not srdf.collision_disabled('toy_link1', 'toy_link7')


@pytest.mark.parametrize(
    'text, culprit',
    [
        ('<robot name="r"><group name="a"><group name="missing"/></group></robot>', "'missing'"),
        ('<robot name="r"><group name="a"><chain base_link="x"/></group></robot>', 'tip_link'),
        (
            '<robot name="r"><virtual_joint name="v" type="hinge" parent_frame="w" '
            'child_link="b"/></robot>',
            'hinge',
        ),
        (
            '<robot name="r"><group_state name="s" group="a"><joint name="j" value="x"/>'
            '</group_state></robot>',
            "'j'",
        ),
        ('<robot', 'not well-formed'),
    ],
)
def test_bad_srdf_names_the_culprit(text, culprit):
    with pytest.raises(SrdfError, match=culprit):
        parse_srdf(text)


def test_default_disabled_links_and_enabled_pairs_as_srdfdom_reads_them():
    # panda_moveit_config's self-collision capsules: a link colliding with nothing by
    # default, but the pairs <enable_collisions> names; an explicit pair wins over defaults
    srdf = parse_srdf(
        '<robot name="r"><disable_default_collisions link="a_sc"/>'
        '<enable_collisions link1="b_sc" link2="a_sc"/>'
        '<disable_collisions link1="x" link2="y"/></robot>'
    )
    assert srdf.collision_disabled('a_sc', 'world_box')
    assert not srdf.collision_disabled('a_sc', 'b_sc')
    assert srdf.collision_disabled('y', 'x')
    assert not srdf.collision_disabled('x', 'z')


def test_joint_limits_yaml_overrides_the_urdf(robot):
    b = robot.bounds['toy_joint2']
    assert (b.max_velocity, b.max_acceleration) == (2.175, 1.875)
    assert (b.lower, b.upper) == (-1.7628, 1.7628)  # no has_position_limits: the URDF's
    assert robot.bounds['toy_finger_joint1'].max_acceleration is None


def test_planner_configs_are_found_as_move_group_finds_them():
    o = cfg.ompl_config(PARAMS['move_group'], ['toy_arm', 'hand'])
    assert o.planner_for('toy_arm', '').name == 'RRTConnect'  # the group's default
    assert o.planner_for('toy_arm', 'RRT').params['goal_bias'] == 0.05
    assert o.planner_for('toy_arm', 'toy_arm[PRM]').type == 'geometric::PRM'
    assert o.planner_for('hand', '') is None  # no default: OMPL's own (RRTConnect)
    assert o.groups['toy_arm'].longest_valid_segment_fraction == 0.005


# --- kinematics ------------------------------------------------------------------------------


def test_jacobian_matches_finite_differences(robot):
    state = ready(robot)
    robot.set_positions(state)
    jac = robot.jacobian('toy_link8', ARM)
    p0 = robot.link_pose('toy_link8')[0]
    h = 1e-4  # pybullet keeps link frames in single precision
    for k, joint in enumerate(ARM):
        robot.set_positions({**state, joint: state[joint] + h})
        numeric = (robot.link_pose('toy_link8')[0] - p0) / h
        assert np.allclose(jac[:3, k], numeric, atol=2e-3), joint
    robot.set_positions(state)


def test_ik_reaches_a_reachable_pose_within_limits(robot):
    target_state = {**ready(robot), 'toy_joint1': 0.4, 'toy_joint2': -0.3, 'toy_joint4': -2.0}
    robot.set_positions(target_state)
    pos, orn = robot.link_pose('toy_link8')
    solution = solve_ik(robot, IkRequest(ARM, 'toy_link8', pos, orn, ready(robot), timeout=0.5))
    assert solution is not None
    robot.set_positions({**ready(robot), **solution})
    got_p, got_q = robot.link_pose('toy_link8')
    assert np.linalg.norm(got_p - pos) < 1e-4
    assert abs(abs(float(np.dot(got_q, orn))) - 1.0) < 1e-6
    assert robot.within_bounds(solution)


def test_ik_of_an_unreachable_pose_fails(robot):
    req = IkRequest(ARM, 'toy_link8', (3.0, 0.0, 0.5), (0, 0, 0, 1), ready(robot), timeout=0.05)
    assert solve_ik(robot, req) is None


# --- collision world ---------------------------------------------------------------------------


def test_objects_attached_objects_and_touch_links(robot, world):
    state = ready(robot)
    assert not world.in_collision(state)
    robot.set_positions(state)
    tip = robot.link_pose('toy_hand')[0]
    world.add_object(
        SceneObject('box', (tuple(tip), (0, 0, 0, 1)), [Shape('box', (0.05, 0.05, 0.05))])
    )
    assert {'box'} & {n for pair in world.contacts(state) for n in pair[:2]}
    world.remove('box')
    assert not world.in_collision(state)
    # a cylinder between the fingers, attached to the hand: allowed to touch its touch links
    cyl = SceneObject(
        'can',
        ((0, 0, 0.1), (0, 0, 0, 1)),
        [Shape('cylinder', (0.06, 0.03))],
        link='toy_hand',
        touch_links=['toy_leftfinger', 'toy_rightfinger'],
    )
    world.attach(cyl)
    assert not world.in_collision(state)
    # carried into a wall, it collides
    robot.set_positions(state)
    where = world.attached_pose(world.attached['can'])[0]
    world.add_object(
        SceneObject('wall', (tuple(where), (0, 0, 0, 1)), [Shape('box', (0.01, 0.5, 0.5))])
    )
    assert any('can' in c[:2] and 'wall' in c[:2] for c in world.contacts(state))
    world.remove('wall')
    # detached, it stays where it was, in the world
    world.detach('can')
    assert 'can' in world.objects and 'can' not in world.attached


def test_snapshot_and_restore_put_the_scene_back(robot, world):
    world.add_object(SceneObject('a', ((1, 0, 0), (0, 0, 0, 1)), [Shape('box', (0.1, 0.1, 0.1))]))
    world.attach(
        SceneObject('b', ((0, 0, 0.1), (0, 0, 0, 1)), [Shape('sphere', (0.02,))], link='toy_hand')
    )
    world.allow('a', 'toy_link1')
    snap = world.snapshot()
    world.remove('a')
    world.add_object(SceneObject('c', ((0, 1, 0), (0, 0, 0, 1)), [Shape('box', (0.1, 0.1, 0.1))]))
    world.allow('a', 'toy_link1', False)
    world.restore(snap)
    assert list(world.objects) == ['a'] and list(world.attached) == ['b']
    assert world.attached['b'].link == 'toy_hand' and ('a', 'toy_link1') in world.allowed
    assert world.objects['a'].bodies  # built again in the collision world


# --- time parameterization -------------------------------------------------------------------


def test_time_parameterization_keeps_velocity_and_acceleration_limits():
    path = [[0.0, 0.0], [0.5, 0.1], [1.0, 0.4], [1.5, 0.4], [2.0, 0.0]]
    times, vel, acc = time_parameterize(path, [1.0, 0.5], [2.0, 1.0])
    assert times[0] == 0.0 and all(b > a for a, b in zip(times, times[1:]))
    seg = np.abs(np.diff(np.array(path), axis=0)) / np.diff(times)[:, None]
    assert np.all(seg <= np.array([1.0, 0.5]) + 1e-9)
    assert np.all(np.abs(acc) <= np.array([2.0, 1.0]) + 0.01 + 1e-9)
    assert np.allclose(vel[0], 0) and np.allclose(vel[-1], 0)
    slow, _, _ = time_parameterize(path, [1.0, 0.5], [2.0, 1.0], 0.5, 0.5)
    assert slow[-1] > times[-1] * 1.5  # half speed and acceleration: well over 1.5 x as long


def test_unlimited_joints_get_moveits_default_limits():
    times, _, _ = time_parameterize([[0.0], [1.0]], [None], [None])
    assert times[-1] >= 1.0  # 1 rad/s


# --- planning --------------------------------------------------------------------------------


def test_joint_goal_around_an_obstacle_is_collision_free(robot, world, pipeline):
    start = ready(robot)
    goal = {**start, 'toy_joint1': 1.5}
    robot.set_positions({**start, 'toy_joint1': 0.75})
    mid = robot.link_pose('toy_hand')[0]
    world.add_object(
        SceneObject('post', (tuple(mid), (0, 0, 0, 1)), [Shape('box', (0.1, 0.1, 0.1))])
    )
    req = MotionRequest(
        'toy_arm',
        start,
        [Constraints(joints=[JointGoal('toy_joint1', 1.5)])],
        allowed_planning_time=10.0,
        max_velocity_scaling_factor=1.0,
    )
    result = pipeline.plan(req)
    assert result.error_code == 1, result.message
    traj = result.trajectory
    assert traj.joint_names == ARM
    assert np.allclose(traj.positions[0], [start[j] for j in ARM])
    assert np.allclose(traj.positions[-1], [goal[j] for j in ARM])
    for q in traj.positions:
        assert not world.in_collision({**start, **dict(zip(ARM, q))})
    # interpolated at the motion-checking resolution: no jump between waypoints
    steps = np.max(np.abs(np.diff(np.array(traj.positions), axis=0)))
    assert steps < 0.2


def test_several_planning_attempts_share_the_planning_time(robot, pipeline):
    start = ready(robot)
    goal = Constraints(joints=[JointGoal('toy_joint1', 1.0), JointGoal('toy_joint3', -0.5)])
    one = pipeline.plan(MotionRequest('toy_arm', start, [goal], num_planning_attempts=1))
    three = pipeline.plan(
        MotionRequest('toy_arm', start, [goal], num_planning_attempts=3, allowed_planning_time=3.0)
    )
    assert one.error_code == three.error_code == 1
    assert three.planning_time < 3.0 + 0.5  # the attempts share it
    assert np.allclose(three.trajectory.positions[-1][0], 1.0)


def test_goal_in_collision_and_start_in_collision_give_moveits_codes(robot, world, pipeline):
    start = ready(robot)
    robot.set_positions(start)
    tip = robot.link_pose('toy_hand')[0]
    # the goal: joint 1 at 1.0; put a box where the hand will be
    robot.set_positions({**start, 'toy_joint1': 1.0})
    there = robot.link_pose('toy_hand')[0]
    world.add_object(SceneObject('b', (tuple(there), (0, 0, 0, 1)), [Shape('sphere', (0.08,))]))
    req = MotionRequest('toy_arm', start, [Constraints(joints=[JointGoal('toy_joint1', 1.0)])])
    assert pipeline.plan(req).error_code == -12  # GOAL_IN_COLLISION
    world.remove('b')
    world.add_object(SceneObject('c', (tuple(tip), (0, 0, 0, 1)), [Shape('sphere', (0.3,))]))
    assert pipeline.plan(req).error_code == -10  # START_STATE_IN_COLLISION
    assert pipeline.plan(MotionRequest('nope', start, [])).error_code == -15


def test_bad_requests_get_moveits_codes_naming_the_culprit(robot, pipeline):
    start = ready(robot)
    on_nothing = Constraints(positions=[PositionConstraint('no_such_link', (0.4, 0, 0.4))])
    result = pipeline.plan(MotionRequest('toy_arm', start, [on_nothing]))
    assert result.error_code == -18 and 'no_such_link' in result.message  # INVALID_LINK_NAME
    nan_goal = Constraints(joints=[JointGoal('toy_joint1', float('nan'))])
    assert pipeline.plan(MotionRequest('toy_arm', start, [nan_goal])).error_code == -16
    bad_start = {**start, 'toy_joint2': float('inf')}
    result = pipeline.plan(MotionRequest('toy_arm', bad_start, [nan_goal]))
    assert result.error_code == -17 and 'toy_joint2' in result.message
    unknown_joint = Constraints(joints=[JointGoal('elbow', 0.3)])
    assert pipeline.plan(MotionRequest('toy_arm', start, [unknown_joint])).error_code == -16


def test_pose_goal_and_orientation_path_constraint(robot, pipeline):
    start = ready(robot)
    robot.set_positions(start)
    pos, orn = robot.link_pose('toy_link8')
    target = pos + np.array([0.0, 0.15, -0.1])
    goal = Constraints(
        positions=[PositionConstraint('toy_link8', target)],
        orientations=[OrientationConstraint('toy_link8', orn)],
    )
    path = Constraints(orientations=[OrientationConstraint('toy_link8', orn, (0.3, 0.3, math.pi))])
    result = pipeline.plan(
        MotionRequest('toy_arm', start, [goal], path_constraints=path, allowed_planning_time=10.0)
    )
    assert result.error_code == 1, result.message
    for q in result.trajectory.positions:
        assert pipeline.satisfies(path, {**start, **dict(zip(ARM, q))}, tolerance=1e-6)
    robot.set_positions({**start, **dict(zip(ARM, result.trajectory.positions[-1]))})
    assert np.linalg.norm(robot.link_pose('toy_link8')[0] - target) < 1e-3
    # out of reach: MoveIt's NO_IK_SOLUTION
    far = Constraints(
        positions=[PositionConstraint('toy_link8', (2.0, 0, 0.5))],
        orientations=[OrientationConstraint('toy_link8', orn)],
    )
    assert (
        pipeline.plan(MotionRequest('toy_arm', start, [far], allowed_planning_time=0.3)).error_code
        == -31
    )


def test_cartesian_path_is_straight_and_stops_at_an_obstacle(robot, world, pipeline):
    start = ready(robot)
    robot.set_positions(start)
    pos, orn = robot.link_pose('toy_link8')
    down = pos + np.array([0.0, 0.0, -0.15])
    result, traj = pipeline.cartesian('toy_arm', 'toy_link8', start, [(down, orn)], 0.01, 0.0, True)
    assert result.fraction == 1.0
    assert len(result.states) >= 16  # 0.15 m in 1 cm steps, and the start
    for s in result.states:
        robot.set_positions({**start, **s})
        p = robot.link_pose('toy_link8')[0]
        assert abs(p[0] - pos[0]) < 1e-3 and abs(p[1] - pos[1]) < 1e-3
    assert traj.times[-1] > 0
    # a small slab in the way, below the fingers
    world.add_object(
        SceneObject(
            'slab',
            ((pos[0], pos[1], pos[2] - 0.15), (0, 0, 0, 1)),
            [Shape('box', (0.1, 0.1, 0.02))],
        )
    )
    blocked, _ = pipeline.cartesian('toy_arm', 'toy_link8', start, [(down, orn)], 0.01, 0.0, True)
    assert 0.0 < blocked.fraction < 1.0
    unchecked, _ = pipeline.cartesian(
        'toy_arm', 'toy_link8', start, [(down, orn)], 0.01, 0.0, False
    )
    assert unchecked.fraction == 1.0


def test_jump_threshold_cuts_a_path_at_a_joint_space_jump(robot):
    joints = ['a', 'b']
    states = [{'a': 0.01 * i, 'b': 0.0} for i in range(10)] + [{'a': 2.0, 'b': 0.0}]
    kept = list(states)
    fraction = _cut_jumps(kept, joints, 2.0)
    assert len(kept) == 10 and fraction == pytest.approx(10 / 11)
    assert math.isclose(_cut_jumps(list(states[:10]), joints, 2.0), 1.0)
