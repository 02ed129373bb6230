"""sim/model_state.py with real pybullet: gazebo_ros's state services, ROS-free."""

import math

import pytest
from conftest import box_link

from _arm1sim.description.sdf_world import WorldConfig
from _arm1sim.sim import model_state as ms
from _arm1sim.sim.model_state import State, StateError
from _arm1sim.sim.simulation import Simulation
from _arm1sim.sim.wrenches import JointEfforts, Wrenches

# The inertial sits off the link frame, so pybullet's centre-of-mass pose must be converted.
BOX = '<robot name="box">%s</robot>' % box_link('body', xyz='0.02 0 0')
TWO = (
    '<robot name="two">%s%s<joint name="hinge" type="revolute"><parent link="base"/>'
    '<child link="arm"/><origin xyz="0 0 0.2"/><axis xyz="0 1 0"/>'
    '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>'
    % (box_link('base'), box_link('arm'))
)


@pytest.fixture
def sim():
    s = Simulation(WorldConfig())
    s.spawn_urdf('box', BOX, (0, 0, 1))
    s.spawn_urdf('two', TWO, (1, 0, 0))
    yield s
    s.close()


def close(a, b, tol=1e-6):
    return all(abs(x - y) < tol for x, y in zip(a, b))


def test_quaternion_helpers_compose_and_invert():
    q = (0, 0, math.sin(math.pi / 4), math.cos(math.pi / 4))  # 90 deg about z
    assert close(ms.rotate(q, (1, 0, 0)), (0, 1, 0))
    assert close(ms.q_mul(q, ms.q_inv(q)), (0, 0, 0, 1))
    assert ms.normalized((0, 0, 0, 0)) == (0, 0, 0, 1)
    frame = State((1, 2, 3), q, (0, 0, 0), (0, 0, 0))
    target = State((1, 0, 0), (0, 0, 0, 1), (1, 0, 0), (0, 0, 1))
    world = ms.compose(frame, target)
    assert close(world.position, (1, 3, 3)) and close(world.linear, (0, 1, 0))
    back = ms.relative(world, frame)
    assert close(back.position, target.position) and close(back.orientation, target.orientation)


def test_model_state_is_the_link_frame_at_the_spawn_pose(sim):
    s = ms.get_model_state(sim, 'box', '')
    assert close(s.position, (0, 0, 1)) and close(s.orientation, (0, 0, 0, 1))


def test_set_model_state_round_trips_pose_and_twist(sim):
    q = ms.normalized((0, 0, 1, 1))
    ms.set_model_state(sim, 'box', State((0.5, -0.2, 2.0), q, (0.1, 0, 0), (0, 0, 0.3)), 'world')
    s = ms.get_model_state(sim, 'box', 'world')
    assert close(s.position, (0.5, -0.2, 2.0)) and close(s.orientation, q)
    assert close(s.linear, (0.1, 0, 0)) and close(s.angular, (0, 0, 0.3))


def test_set_model_state_relative_to_another_model(sim):
    ms.set_model_state(sim, 'box', State((0, 0, 0.5)), 'two')
    assert close(ms.get_model_state(sim, 'box', '').position, (1, 0, 0.5))
    assert close(ms.get_model_state(sim, 'box', 'two').position, (0, 0, 0.5))
    # A scoped link as the frame: 'two::arm' sits 0.2 above two's base.
    assert close(ms.get_model_state(sim, 'box', 'two::arm').position, (0, 0, 0.3))


def test_set_model_state_moves_the_links_rigidly_and_stops_joints(sim):
    sim.models['two'].robot.set_joint_positions({'hinge': 0.5})
    ms.set_model_state(sim, 'two', State((3, 0, 0)), '')
    arm = ms.get_link_state(sim, 'two::arm', '')
    assert close(arm.position, (3, 0, 0.2))
    assert ms.get_joint_properties(sim, 'hinge') == pytest.approx((0.5, 0.0))


def test_unknown_names_and_nan_are_refused_naming_them(sim):
    with pytest.raises(StateError, match=r'GetModelState: model \[nobox\] does not exist'):
        ms.get_model_state(sim, 'nobox', '')
    with pytest.raises(StateError, match=r'relative_entity_name \[nowhere\] not found'):
        ms.get_model_state(sim, 'box', 'nowhere')
    with pytest.raises(StateError, match=r'SetModelState: model \[box\].*finite'):
        ms.set_model_state(sim, 'box', State((math.nan, 0, 0)), '')
    with pytest.raises(StateError, match=r'GetLinkState: link \[two::nolink\] not found'):
        ms.get_link_state(sim, 'two::nolink', '')
    with pytest.raises(StateError, match=r'GetJointProperties: joint \[nojoint\] not found'):
        ms.get_joint_properties(sim, 'nojoint')
    assert close(ms.get_model_state(sim, 'box', '').position, (0, 0, 1))
    sim.step()  # the world runs on


def test_properties_list_links_joints_and_models(sim):
    props = ms.get_model_properties(sim, 'two')
    assert props.body_names == ['base', 'arm'] and props.joint_names == ['hinge']
    mass, com, _ = ms.get_link_properties(sim, 'box::body')
    assert mass == pytest.approx(0.5) and close(com, (0.02, 0, 0))
    names, states = ms.model_states(sim)
    assert names == ['box', 'two'] and close(states[0].position, (0, 0, 1))
    links, _ = ms.link_states(sim)
    assert links == ['box::body', 'two::base', 'two::arm']


def test_gravity_change_lets_a_free_box_float(sim):
    props = ms.get_physics_properties(sim)
    assert props.gravity == pytest.approx((0, 0, -9.8))
    ms.set_physics_properties(sim, ms.PhysicsProperties(props.time_step, 500.0, (0, 0, 0)))
    for _ in range(200):
        sim.step()
    assert close(ms.get_model_state(sim, 'box', '').position, (0, 0, 1), 1e-6)
    with pytest.raises(StateError, match='time_step'):
        ms.set_physics_properties(sim, ms.PhysicsProperties(0.002, 500.0, (0, 0, 0)))


def test_wrench_with_duration_pushes_then_stops(sim):
    props = ms.get_physics_properties(sim)
    ms.set_physics_properties(sim, ms.PhysicsProperties(props.time_step, 1000.0, (0, 0, 0)))
    wrenches = Wrenches()
    sim.before_step.append(lambda now: wrenches.apply(sim, now))
    # 1 N on 0.5 kg for 0.1 s: 0.2 m/s along +x, then coasting at that speed.
    wrenches.add(sim, 'box::body', '', (0, 0, 0), (1, 0, 0), (0, 0, 0), 0, 100_000_000)
    for _ in range(100):
        sim.step()
    v = ms.get_model_state(sim, 'box', '').linear
    assert v[0] == pytest.approx(0.2, rel=0.05) and abs(v[1]) < 1e-6
    for _ in range(100):
        sim.step()
    # Still pushed, it would reach 0.4 m/s (pybullet's base damping costs a little).
    assert ms.get_model_state(sim, 'box', '').linear[0] == pytest.approx(v[0], rel=0.02)
    assert wrenches.jobs == []
    assert ms.get_model_state(sim, 'box', '').position[0] > 0.02


def test_wrench_unknown_body_and_frame_are_named(sim):
    w = Wrenches()
    with pytest.raises(StateError, match=r'ApplyBodyWrench: body \[ghost\] does not exist'):
        w.add(sim, 'ghost', '', (0, 0, 0), (1, 0, 0), (0, 0, 0), 0, -1)
    with pytest.raises(StateError, match=r'reference_frame \[nope\] not found'):
        w.add(sim, 'box::body', 'nope', (0, 0, 0), (1, 0, 0), (0, 0, 0), 0, -1)


def test_joint_effort_turns_a_free_joint_for_its_duration(sim):
    props = ms.get_physics_properties(sim)
    ms.set_physics_properties(sim, ms.PhysicsProperties(props.time_step, 1000.0, (0, 0, 0)))
    efforts = JointEfforts()
    sim.before_step.append(lambda now: efforts.apply(sim, now))
    efforts.add(sim, 'hinge', 0.01, 0, 50_000_000)
    for _ in range(50):
        sim.step()
    q, rate = ms.get_joint_properties(sim, 'hinge')
    assert rate > 0.05 and q > 0
    for _ in range(50):
        sim.step()
    assert efforts.jobs == []
    assert ms.get_joint_properties(sim, 'hinge')[1] == pytest.approx(rate, rel=0.1)
    with pytest.raises(StateError, match=r'ApplyJointEffort: joint \[nojoint\] not found'):
        efforts.add(sim, 'nojoint', 1.0, 0, -1)


def test_set_link_state_moves_a_root_link_and_refuses_a_jointed_one(sim):
    ms.set_link_state(sim, 'two::base', State((2, 2, 0)), 'box::body')
    assert close(ms.get_link_state(sim, 'two::base', '').position, (2, 2, 1))
    with pytest.raises(StateError, match=r'SetLinkState: link \[two::arm\] is not the root'):
        ms.set_link_state(sim, 'two::arm', State(), '')
    with pytest.raises(StateError, match=r'SetLinkState: failed: reference_frame \[two\]'):
        ms.set_link_state(sim, 'two::base', State(), 'two')
    with pytest.raises(StateError, match=r'SetLinkState: link \[ghost\] does not exist'):
        ms.set_link_state(sim, 'ghost', State(), '')


def test_world_file_scenery_is_listed_and_readable():
    from _arm1sim.description.sdf_world import StaticModel

    config = WorldConfig()
    config.models = [StaticModel('ground_plane', (0, 0, 0, 0, 0, math.pi / 2), [])]
    sim = Simulation(config)
    try:
        sim.spawn_urdf('box', BOX, (0, 0, 1))
        assert ms.model_names(sim) == ['ground_plane', 'box']
        names, states = ms.model_states(sim)
        assert names == ['ground_plane', 'box'] and close(states[0].linear, (0, 0, 0))
        ground = ms.get_model_state(sim, 'ground_plane', '')
        assert close(ground.orientation, ms.normalized((0, 0, 1, 1)))
        assert ms.get_model_properties(sim, 'ground_plane').is_static
        # The box seen from the (turned) ground: its x axis is the world's y.
        ms.set_model_state(sim, 'box', State((1, 0, 0.5)), 'ground_plane')
        assert close(ms.get_model_state(sim, 'box', '').position, (0, 1, 0.5))
    finally:
        sim.close()


def test_set_joint_properties_stops_hold_a_pushed_joint(sim):
    props = ms.get_physics_properties(sim)
    ms.set_physics_properties(sim, ms.PhysicsProperties(props.time_step, 1000.0, (0, 0, 0)))
    sim.models['two'].robot.set_joint_positions({'hinge': 0.0})
    ms.set_model_state(sim, 'two', State((1, 0, 0)), '')
    ms.set_joint_properties(sim, 'two::hinge', [0.0], [-0.2], [0.2])
    efforts = JointEfforts()
    sim.before_step.append(lambda now: efforts.apply(sim, now))
    efforts.add(sim, 'hinge', 0.05, 0, -1)
    for _ in range(1000):
        sim.step()
    q = ms.get_joint_properties(sim, 'hinge')[0]
    assert 0.1 < q < 0.25  # pushed up to the new stop, not the URDF's 1 rad
    ms.set_joint_properties(sim, 'hinge', [], [], [])  # empty arrays change nothing
    with pytest.raises(StateError, match=r'SetJointProperties: joint \[nojoint\] not found'):
        ms.set_joint_properties(sim, 'nojoint', [], [], [])
    with pytest.raises(StateError, match=r'joint \[hinge\]: values must be finite'):
        ms.set_joint_properties(sim, 'hinge', [math.nan], [], [])
