"""simulation.py with real pybullet (headless DIRECT): arm1 and a robot with every joint kind,
driven through the ControllerManager with fake node handles, as the ROS layer would."""

import copy
import math

import pytest
from conftest import (
    JPC,
    MIXED_URDF,
    WORLD_FILE,
    FakeRos,
    box_link,
    control_plugin,
    mixed_params,
    transmission,
)

from _arm1sim.control.controller_manager import STRICT, ControllerManager
from _arm1sim.control.switching import switch_while_updating
from _arm1sim.description.sdf_world import WorldConfig, read_world
from _arm1sim.sim.simulation import Simulation, SpawnError

ARM1_JOINTS = ['joint1', 'joint2', 'joint3', 'joint4']
ARM1_CONTROLLERS = ['joint_state_controller'] + ['%s_position_controller' % j for j in ARM1_JOINTS]
SETTLE = 0.02  # rad


# ----------------------------------------------------------------------------- helpers
def steps_for(sim, seconds):
    return int(round(seconds / sim.period))


def travel_time(distance, velocity_limit=0.5):
    """Sim time to allow for a move: at the URDF velocity limit, plus time to settle."""
    return distance / velocity_limit + 1.5


def run(sim, seconds):
    for _ in range(steps_for(sim, seconds)):
        sim.step()


def switch_while_stepping(sim, cm, start, stop=(), strictness=STRICT):
    """The spawner's switch call, on a service thread, while physics runs."""
    return switch_while_updating(cm, start, stop, sim.step, strictness, poll=0.0005)


def positions(model):
    """Joint positions straight from pybullet (not through the handles)."""
    names = sorted(model.hw.handles)
    return dict(zip(names, [p for p, _ in model.robot.read(model.robot.indices(names))]))


class Rig:
    def __init__(self, sim, model, ros):
        self.sim, self.model, self.ros = sim, model, ros
        self.cm = model.controller_manager
        self.ns = model.namespace

    def start(self, names):
        for n in names:
            self.cm.load_controller(n)
        ok, steps = switch_while_stepping(self.sim, self.cm, names)
        assert ok
        return steps

    def command(self, controller, value):
        assert self.ros.publish('%s/%s/command' % (self.ns, controller), value) == 1

    def joint_states(self):
        return self.ros.messages(self.ns + '/joint_states')


def spawn(sim, ros, name, xml, find_package=None, **kw):
    return sim.spawn_urdf(
        name,
        xml,
        find_package=find_package,
        controller_manager_factory=lambda hw, ns: ControllerManager(hw, ros.node_handle, ns),
        **kw,
    )


@pytest.fixture
def sim():
    s = Simulation(read_world(WORLD_FILE))
    yield s
    s.close()


@pytest.fixture
def arm1(sim, arm1_urdf, controllers_params, find_package):
    ros = FakeRos(copy.deepcopy(controllers_params))
    model = spawn(sim, ros, 'arm1', arm1_urdf, find_package)
    rig = Rig(sim, model, ros)
    rig.switch_steps = rig.start(ARM1_CONTROLLERS)
    return rig


@pytest.fixture
def mixed(sim):
    ros = FakeRos(mixed_params())
    model = spawn(sim, ros, 'mixed', MIXED_URDF, robot_namespace='/spawn_arg_ns')
    rig = Rig(sim, model, ros)
    rig.start(sorted(mixed_params()['mixed_ns']))
    return rig


# ----------------------------------------------------------------------------- arm1
def test_arm1_spawns_fixed_with_its_controller_manager(sim, arm1_urdf, find_package):
    ros = FakeRos()
    model = spawn(sim, ros, 'arm1', arm1_urdf, find_package)
    assert model.namespace == '/arm1'
    assert model.hw.joint_names() == ARM1_JOINTS
    assert model.controller_manager is not None
    assert sim.models == {'arm1': model}
    base_before = model.robot.link_pose('base_link')[0]
    run(sim, 0.5)
    assert sim.time_ns == 500 * 10**6
    # pinned by the `world` joint: the base does not fall
    assert model.robot.link_pose('base_link')[0] == pytest.approx(base_before, abs=1e-6)
    # with no controller running nothing holds the arm: the elbow falls onto its lower
    # limit (-1.0), which the physics enforces
    assert -1.0 - SETTLE <= positions(model)['joint3'] < -0.5


def test_switch_through_the_manager_completes_at_a_physics_step(arm1):
    # the fixture's switch call returned only once the simulation had stepped
    assert arm1.switch_steps >= 1
    assert {s for _, _, s, _ in arm1.cm.list_controllers()} == {'running'}
    # the controllers started at that step: their first state and joint_states carry its time
    first = arm1.ros.messages('/arm1/joint1_position_controller/state')[0]['stamp']
    assert 0 <= first < arm1.sim.time_ns
    assert arm1.joint_states()[0]['stamp'] == first
    assert arm1.joint_states()[0]['name'] == ARM1_JOINTS


def test_started_controllers_hold_the_arm(arm1):
    start = positions(arm1.model)
    run(arm1.sim, 1.0)
    end = positions(arm1.model)
    for j in ARM1_JOINTS:
        assert end[j] == pytest.approx(start[j], abs=SETTLE), j


def test_joint_states_at_50_hz_in_sim_time(arm1):
    n0 = len(arm1.joint_states())
    run(arm1.sim, 2.0)
    msgs = arm1.joint_states()[n0:]
    assert len(msgs) == pytest.approx(100, abs=1)
    assert all(m['name'] == ARM1_JOINTS for m in msgs)
    gaps = {b['stamp'] - a['stamp'] for a, b in zip(msgs, msgs[1:])}
    assert gaps == {20 * 10**6}
    assert msgs[-1]['stamp'] <= arm1.sim.time_ns


def test_a_step_settles_within_tolerance(arm1):
    targets = {'joint1': 1.0, 'joint3': -0.5, 'joint4': 0.6}
    for j, v in targets.items():
        arm1.command('%s_position_controller' % j, v)
    run(arm1.sim, travel_time(1.0))
    pos = positions(arm1.model)
    for j, v in targets.items():
        assert pos[j] == pytest.approx(v, abs=SETTLE), j
    state = arm1.ros.messages('/arm1/joint1_position_controller/state')[-1]
    assert state['set_point'] == pytest.approx(1.0)
    assert state['process_value'] == pytest.approx(1.0, abs=SETTLE)
    # and it stays there
    run(arm1.sim, 0.5)
    assert positions(arm1.model)['joint1'] == pytest.approx(1.0, abs=SETTLE)


SAFE_POSE = {'joint1': 0.0, 'joint2': 1.2, 'joint3': 0.0, 'joint4': 0.0}  # upright, clear


@pytest.mark.parametrize(
    'joint, command, limit',
    [
        ('joint1', 5.0, 1.57),
        ('joint1', -5.0, -1.57),
        ('joint2', 9.0, 1.57),
        ('joint3', -9.0, -1.0),
        ('joint4', 9.0, 1.57),
        ('joint4', -9.0, -0.8),
    ],
)
def test_out_of_range_commands_end_at_the_urdf_limits(arm1, joint, command, limit):
    # From the upright pose, one joint at a time, so that no link meets the ground or
    # rests against a limit of another joint (arm1's 15 g links at 1 N·m are lively).
    for j, v in SAFE_POSE.items():
        arm1.command('%s_position_controller' % j, v)
    run(arm1.sim, travel_time(1.2))
    distance = abs(limit - positions(arm1.model)[joint])
    arm1.command('%s_position_controller' % joint, command)
    run(arm1.sim, travel_time(distance))
    assert positions(arm1.model)[joint] == pytest.approx(limit, abs=SETTLE)
    state = arm1.ros.messages('/arm1/%s_position_controller/state' % joint)[-1]
    assert state['set_point'] == pytest.approx(limit)


def test_beyond_the_velocity_limit_no_effort_pushes_faster(arm1):
    """Effort saturation as gazebo_ros_control has it: whenever a joint is faster than its
    URDF velocity limit, the effort applied in its direction of motion is zero. (The rule acts
    on the velocity read before the step, as Gazebo's does, so with arm1's 15 g links one 1 ms
    step at the 1 N·m limit can still overshoot 0.5 rad/s: the limit does not cap speed.)"""
    arm1.command('joint1_position_controller', 1.0)
    handle = arm1.model.hw.handles['joint1']
    fast_steps = 0
    for _ in range(steps_for(arm1.sim, 3.0)):
        arm1.sim.step()
        if abs(handle.velocity) > handle.limits.velocity:
            fast_steps += 1
            assert handle.effort * handle.velocity <= 0.0, (handle.velocity, handle.effort)
    assert fast_steps > 0  # the rule was exercised
    assert positions(arm1.model)['joint1'] == pytest.approx(1.0, abs=SETTLE)


def test_non_finite_command_holds_the_last_target(arm1):
    arm1.command('joint1_position_controller', 0.7)
    run(arm1.sim, travel_time(0.7))
    arm1.command('joint1_position_controller', math.nan)
    arm1.command('joint1_position_controller', math.inf)
    run(arm1.sim, 1.0)
    assert positions(arm1.model)['joint1'] == pytest.approx(0.7, abs=SETTLE)


def test_i_clamp_makes_the_integral_act(sim, arm1_urdf, controllers_params, find_package):
    """Seed gains (i without i_clamp): the integral does nothing and gravity leaves joint2
    short of its target; with an i_clamp the integral removes the offset."""
    finals = {}
    for label, extra in (('seed', {}), ('clamped', {'i': 1.0, 'i_clamp': 0.2})):
        params = copy.deepcopy(controllers_params)
        params['arm1']['joint2_position_controller']['pid'].update(extra)
        ros = FakeRos(params)
        model = spawn(sim, ros, 'arm1_' + label, arm1_urdf, find_package)
        rig = Rig(sim, model, ros)
        rig.start(ARM1_CONTROLLERS)
        rig.command('joint2_position_controller', 0.8)
        run(sim, 4.0)
        finals[label] = positions(model)['joint2']
        sim.delete_model(model.name)
    assert abs(finals['seed'] - 0.8) > 0.005  # a P controller against gravity
    assert finals['clamped'] == pytest.approx(0.8, abs=0.005)
    assert abs(finals['clamped'] - 0.8) < abs(finals['seed'] - 0.8)


def test_reset_simulation_brings_time_and_joints_to_zero(arm1):
    arm1.command('joint1_position_controller', 1.0)
    arm1.command('joint3_position_controller', 0.8)
    run(arm1.sim, 2.0)
    assert arm1.sim.time_ns > 0
    assert positions(arm1.model)['joint1'] > 0.5
    arm1.sim.reset_simulation()
    assert arm1.sim.time_ns == 0
    assert arm1.sim.steps == 0
    names = arm1.model.robot.indices(ARM1_JOINTS)
    for pos, vel in arm1.model.robot.read(names):
        assert (pos, vel) == (0.0, 0.0)
    arm1.sim.step()
    assert arm1.sim.time_ns == 10**6


def test_reset_world_keeps_time(arm1):
    arm1.command('joint1_position_controller', 1.0)
    run(arm1.sim, 1.0)
    t = arm1.sim.time_ns
    arm1.sim.reset_world()
    assert arm1.sim.time_ns == t
    assert positions(arm1.model)['joint1'] == 0.0


def test_set_model_configuration(arm1):
    arm1.sim.set_model_configuration('arm1', ['joint1', 'joint3'], [0.3, -0.2])
    pos = positions(arm1.model)
    assert (pos['joint1'], pos['joint3']) == (pytest.approx(0.3), pytest.approx(-0.2))
    with pytest.raises(SpawnError, match='elbow'):
        arm1.sim.set_model_configuration('arm1', ['elbow'], [0.0])
    with pytest.raises(SpawnError, match='joint1'):
        arm1.sim.set_model_configuration('arm1', ['joint1'], [math.nan])
    with pytest.raises(SpawnError, match='ghost'):
        arm1.sim.set_model_configuration('ghost', ['joint1'], [0.0])


# ----------------------------------------------------------------------------- another robot
def test_mixed_robot_namespace_and_joints(mixed):
    assert mixed.model.namespace == '/mixed_ns'  # the plugin's, not the spawn argument
    names = ['flap_joint', 'passive_joint', 'slider_joint', 'wheel_joint']
    assert mixed.model.hw.joint_names() == names
    run(mixed.sim, 0.05)
    m = mixed.joint_states()[-1]
    assert m['name'] == names


def test_continuous_joint_takes_the_short_way_across_pi(mixed):
    mixed.command('wheel_controller', 3.0)
    run(mixed.sim, 1.5)
    assert positions(mixed.model)['wheel_joint'] == pytest.approx(3.0, abs=SETTLE)
    mixed.command('wheel_controller', -3.0)
    run(mixed.sim, 1.5)
    pos = positions(mixed.model)['wheel_joint']
    # -3.0 is reached by turning +0.283 rad, not -6 rad
    assert pos == pytest.approx(2 * math.pi - 3.0, abs=SETTLE)
    assert math.remainder(pos - (-3.0), 2 * math.pi) == pytest.approx(0.0, abs=SETTLE)


def test_prismatic_joint_moves_and_stops_at_its_limit(mixed):
    mixed.command('slider_controller', 0.1)
    run(mixed.sim, 1.5)
    assert positions(mixed.model)['slider_joint'] == pytest.approx(0.1, abs=0.005)
    mixed.command('slider_controller', 5.0)
    run(mixed.sim, 1.5)
    assert positions(mixed.model)['slider_joint'] == pytest.approx(0.2, abs=0.005)
    mixed.command('slider_controller', -5.0)
    run(mixed.sim, 1.5)
    assert positions(mixed.model)['slider_joint'] == pytest.approx(-0.1, abs=0.005)


def test_revolute_joint_goes_the_long_way_inside_its_limits(mixed):
    mixed.command('flap_controller', 2.9)
    run(mixed.sim, 2.0)
    assert positions(mixed.model)['flap_joint'] == pytest.approx(2.9, abs=SETTLE)
    mixed.command('flap_controller', -2.9)
    highest = -math.inf
    for _ in range(steps_for(mixed.sim, 3.0)):
        mixed.sim.step()
        highest = max(highest, positions(mixed.model)['flap_joint'])
    assert positions(mixed.model)['flap_joint'] == pytest.approx(-2.9, abs=SETTLE)
    assert highest < 3.0 + SETTLE  # it never crossed +pi


def test_a_position_interface_joint_without_a_controller_is_held_at_its_command_zero(mixed):
    # Its transmission says PositionJointInterface and there are no pid gains: the joint is
    # set to the command (0 until a controller writes one), as Gazebo's SetPosition does.
    mixed.sim.set_model_configuration('mixed', ['passive_joint'], [0.5])
    run(mixed.sim, 1.0)
    assert positions(mixed.model)['passive_joint'] == pytest.approx(0.0, abs=1e-6)


# ----------------------------------------------------------------------------- spawn rules
def simple_robot(plugin_ns, extra=''):
    return (
        '<robot name="simple"><link name="world"/>'
        + box_link('base')
        + box_link('arm')
        + """<joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
            <joint name="hinge" type="revolute"><parent link="base"/><child link="arm"/>
              <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>"""
        + transmission('hinge')
        + extra
        + (control_plugin(plugin_ns) if plugin_ns != 'none' else '')
        + '</robot>'
    )


def test_namespace_falls_back_to_spawn_argument_then_model_name(sim):
    ros = FakeRos()
    a = spawn(sim, ros, 'one', simple_robot(None), robot_namespace='/given')
    b = spawn(sim, ros, 'two', simple_robot(None))
    c = spawn(sim, ros, 'three', simple_robot('none'))
    assert (a.namespace, b.namespace) == ('/given', '/two')
    assert c.hw is None and c.controller_manager is None  # no control plugin


def test_spawn_refuses_a_transmission_for_an_unknown_joint(sim):
    xml = simple_robot('/s', transmission('ghost_joint', name='tran_ghost'))
    with pytest.raises(SpawnError) as exc:
        spawn(sim, FakeRos(), 'bad', xml)
    assert "'bad'" in str(exc.value) and 'ghost_joint' in str(exc.value)
    assert 'bad' not in sim.models
    assert sim.world.robots == []
    sim.step()  # still steps


def test_spawn_leaves_a_missing_visual_mesh_out_and_the_model_spawns(sim, find_package, caplog):
    xml = (
        '<robot name="m"><link name="shell"><visual><geometry>'
        '<mesh filename="package://arm1/meshes/nothing.STL"/></geometry></visual></link></robot>'
    )
    with caplog.at_level('WARNING'):
        model = spawn(sim, FakeRos(), 'm', xml, find_package)
    assert 'm' in sim.models and model.robot.body >= 0
    assert any(
        "'shell'" in r.getMessage() and 'nothing.STL' in r.getMessage() for r in caplog.records
    )


def test_spawn_refuses_malformed_xml_and_duplicate_names(sim):
    with pytest.raises(SpawnError, match='not well-formed'):
        spawn(sim, FakeRos(), 'x', '<robot name="x"><link name="a"></robot>')
    spawn(sim, FakeRos(), 'dup', simple_robot('/d'))
    with pytest.raises(SpawnError, match='already exists'):
        spawn(sim, FakeRos(), 'dup', simple_robot('/d'))


def test_delete_model_stops_driving_it(sim):
    ros = FakeRos({'d': {'c': {'type': JPC, 'joint': 'hinge', 'pid': {'p': 1.0}}}})
    model = spawn(sim, ros, 'd', simple_robot('/d'))
    model.controller_manager.load_controller('c')
    assert switch_while_stepping(sim, model.controller_manager, ['c'])[0]
    sim.delete_model('d')
    assert sim.models == {} and sim.world.robots == []
    run(sim, 0.01)
    with pytest.raises(SpawnError, match="'d'"):
        sim.delete_model('d')


def test_step_period_comes_from_the_world():
    s = Simulation(WorldConfig(max_step_size=0.004))
    try:
        assert s.period == pytest.approx(0.004)
        for _ in range(5):
            s.step()
        assert s.time_ns == 20 * 10**6
    finally:
        s.close()


@pytest.mark.parametrize('gravity, expected_z', [((0.0, 0.0, -9.8), 0.05), ((0.0, 0.0, 0.0), 1.0)])
def test_robot_without_world_joint_is_free_and_feels_the_worlds_gravity(gravity, expected_z):
    cfg = read_world(WORLD_FILE)  # with its ground plane
    cfg.gravity = gravity
    s = Simulation(cfg)
    try:
        model = s.spawn_urdf(
            'crate', '<robot name="crate">%s</robot>' % box_link('crate'), position=(0, 0, 1.0)
        )
        assert model.hw is None
        run(s, 1.0)
        z = model.robot.link_pose('crate')[0][2]
        assert z == pytest.approx(expected_z, abs=0.01)
    finally:
        s.close()
