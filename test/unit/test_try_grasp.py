"""try_grasp's ROS-free part: the box placed from the finger links' poses, the lift verdict,
the command line."""

import math

import pytest

from _arm1sim.tryout import grasp, grasp_cli


def quat_about_z(angle):
    return (0.0, 0.0, math.sin(angle / 2), math.cos(angle / 2))


def close(a, b, tol=1e-9):
    return all(abs(x - y) < tol for x, y in zip(a, b))


def test_rotate_and_to_frame_are_inverse():
    q = (0.1, -0.3, 0.2, 0.9)
    n = math.sqrt(sum(c * c for c in q))
    q = tuple(c / n for c in q)
    p, v = (0.5, -1.0, 2.0), (0.3, 0.2, -0.1)
    w = grasp.rotate(q, v)
    world = (p[0] + w[0], p[1] + w[1], p[2] + w[2])
    assert close(grasp.to_frame(p, q, world), v)
    assert close(grasp.rotate(quat_about_z(math.pi / 2), (1, 0, 0)), (0, 1, 0))


def test_box_between_two_fingers_moved_ahead_in_the_palm_frame():
    # palm turned 90 degrees about z: its x (ahead) is the world's y
    centre, q = grasp.box_pose(
        [(0.2, 0.1, 0.05), (0.2, 0.14, 0.05)], quat_about_z(math.pi / 2), (0.045, 0, 0)
    )
    assert close(centre, (0.2, 0.165, 0.05))
    assert close(q, quat_about_z(math.pi / 2))


def test_box_at_the_centroid_of_three_fingers():
    fingers = [(1, 0, 0.3), (-0.5, 0.866, 0.3), (-0.5, -0.866, 0.3)]
    centre, _ = grasp.box_pose(fingers, (0, 0, 0, 1), (0, 0, 0))
    assert close(centre, (0, 0, 0.3), 1e-3)
    with pytest.raises(ValueError):
        grasp.box_pose([], (0, 0, 0, 1), (0, 0, 0))


def test_lift_verdict_rise_and_slip():
    held = grasp.judge_lift(
        (0, 0, 0.2), (0, 0, 0.1), (0, 0, 0.25), (0, 0, 0.1495), [(0.05, 0, 0), (0.0505, 0, 0)]
    )
    assert held.ok and abs(held.rise - 0.0495) < 1e-9 and abs(held.slip - 0.0005) < 1e-9
    # rose with the gripper but slid 3 mm along the fingers during the hold
    slid = grasp.judge_lift(
        (0, 0, 0.2), (0, 0, 0.1), (0, 0, 0.25), (0, 0, 0.15), [(0.05, 0, 0), (0.05, 0.003, 0)]
    )
    assert not slid.ok and abs(slid.slip - 0.003) < 1e-9
    # held, but the gripper only rose 30 mm: short of the 40 mm lift
    short = grasp.judge_lift((0, 0, 0.2), (0, 0, 0.1), (0, 0, 0.23), (0, 0, 0.13), [(0, 0, 0)] * 3)
    assert not short.ok
    # left on the ground
    dropped = grasp.judge_lift((0, 0, 0.2), (0, 0, 0.1), (0, 0, 0.26), (0, 0, 0.1), [(0, 0, 0)])
    assert not dropped.ok and 'NOT lifted' in str(dropped)
    assert dropped.as_dict()['box_rise_mm'] == 0.0
    with pytest.raises(ValueError):
        grasp.judge_lift((0, 0, 0), (0, 0, 0), (0, 0, 0), (0, 0, 0), [])


def test_profiles_are_consistent():
    for g in grasp.GRIPPERS.values():
        assert len(g.start) == len(g.lift) == len(g.arm_joints)
        assert len(g.open_position) == len(g.closed_position)
        if g.kind == 'topics':
            assert len(g.arm_topics) == len(g.arm_joints) and g.gripper_topic
        elif g.kind == 'franka':
            # widths: the hand opens to 80 mm; a grasp needs a speed and a force
            assert g.open_position == (0.08,) and 0 < g.closed_position[0] < 0.08
            assert g.grasp_speed > 0 and g.grasp_force > 0 and g.arm_action
        else:
            assert g.kind == 'trajectory'
            assert len(g.finger_joints) == len(g.open_position) and g.arm_action


def test_pedestal_is_static_and_below_its_pose():
    sdf = grasp.pedestal_sdf('p', 0.01, 0.2)
    assert '<static>true</static>' in sdf and '<pose>0 0 -0.1 0 0 0</pose>' in sdf


def test_command_line():
    a = grasp_cli.parse_args(
        ['omx', '/src/x', 'pkg', 'x.launch', '--size', '0.04', '--tries', '2', '--also', '/y']
    )
    assert (a.robot, a.size, a.tries, a.mass, a.mu) == ('omx', 0.04, 2, 0.03, 1.0)
    assert (a.checkout, a.package, a.launch, a.also) == ('/src/x', 'pkg', 'x.launch', ['/y'])
    assert a.lift is None and a.closed is None
    a = grasp_cli.parse_args(
        ['jaco', '/k', 'pkg', 'x.launch', '--lift', '0', '0', '0.3', '0', '0', '0']
    )
    assert a.lift == [0, 0, 0.3, 0, 0, 0]
    with pytest.raises(SystemExit):
        grasp_cli.parse_args(['ur5', '/src/x', 'pkg', 'x.launch'])


def test_profile_overrides():
    def profile(*more):
        return grasp_cli.profile(grasp_cli.parse_args(list(more)))

    # a franka grasp names the box's width: --size sets it, --closed wins over it
    assert profile('panda', '/f', 'franka_gazebo', 'panda.launch').closed_position == (0.04,)
    g = profile('panda', '/f', 'franka_gazebo', 'panda.launch', '--size', '0.03')
    assert g.closed_position == (0.03,)
    g = profile(
        'panda', '/f', 'franka_gazebo', 'panda.launch', '--size', '0.03', '--closed', '0.02'
    )
    assert g.closed_position == (0.02,)
    # other grippers keep their closing command whatever the box
    g = profile(
        'tb3_omx', '/t', 'pkg', 'x.launch', '--size', '0.02', '--lift', '0', '-0.3', '0', '0.3'
    )
    assert g.closed_position == (-0.01,) and g.lift == (0, -0.3, 0, 0.3)
    with pytest.raises(SystemExit):
        profile('tb3_omx', '/t', 'pkg', 'x.launch', '--lift', '0.1')
    with pytest.raises(SystemExit):
        profile('panda', '/f', 'pkg', 'x.launch', '--closed', '0.02', '0.02')


def test_angle_between_orientations():
    assert abs(grasp.angle_between((0, 0, 0, 1), quat_about_z(0.5)) - 0.5) < 1e-9
    # q and -q are the same orientation
    q = quat_about_z(0.3)
    assert grasp.angle_between(q, tuple(-c for c in q)) < 1e-6


def test_command_topics_another_node_could_command_on():
    # kinova-ros's move_robot.py homes JACO2 on its trajectory controllers' command topics
    assert grasp.JACO.command_topics() == (
        '/j2n6s300/effort_joint_trajectory_controller/command',
        '/j2n6s300/effort_finger_trajectory_controller/command',
    )
    assert grasp.OMX.command_topics() == (
        '/gripper_position/command',
        *('/joint%d_position/command' % i for i in range(1, 5)),
    )
    # the franka hand has actions only: its arm's trajectory controller
    assert grasp.PANDA.command_topics() == ('/effort_joint_trajectory_controller/command',)


def test_goal_outcome_names_the_state_and_error_code():
    from control_msgs.msg import FollowJointTrajectoryResult

    from _arm1sim.tryout.grasp_ros import goal_outcome

    assert goal_outcome(3, FollowJointTrajectoryResult(error_code=0)) == 'SUCCEEDED'
    aborted = FollowJointTrajectoryResult(error_code=-5)
    assert goal_outcome(4, aborted) == 'ABORTED GOAL_TOLERANCE_VIOLATED'
    assert goal_outcome(4, None) == 'ABORTED'
    assert goal_outcome(42, FollowJointTrajectoryResult(error_code=-99)) == '42 -99'
