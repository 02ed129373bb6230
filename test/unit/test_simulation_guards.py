"""Simulation's guards (issues 12 and 15): models without joints are ordinary models, names are
only names, requests are checked whole, and deleting a model releases everything it brought."""

import copy
import glob
import math
import os

import pytest
from conftest import WORLD_FILE, FakeRos, box_link, control_plugin, pump_switch

from _arm1sim.control.controller_manager import ControllerManager
from _arm1sim.control.switching import SwitchRequest
from _arm1sim.description.limits import Limits
from _arm1sim.description.sdf_world import WorldConfig, read_world
from _arm1sim.sim.simulation import Simulation, SpawnError

CRATE = '<robot name="crate">%s</robot>' % box_link('crate')
FIXED_ONLY = (
    '<robot name="table">%s%s<joint name="top_joint" type="fixed"><parent link="legs"/>'
    '<child link="top"/><origin xyz="0 0 0.1"/></joint></robot>'
    % (box_link('legs'), box_link('top'))
)


@pytest.fixture
def sim():
    s = Simulation(read_world(WORLD_FILE))
    yield s
    s.close()


def run(sim, steps):
    for _ in range(steps):
        sim.step()


@pytest.mark.parametrize('xml', [CRATE, FIXED_ONLY], ids=['no joints', 'fixed joints only'])
def test_a_model_without_movable_joints_steps_reports_state_and_resets(sim, xml):
    model = sim.spawn_urdf('thing', xml, position=(0, 0, 0.5))
    # state() gives the base's centre of mass: the table's top is lumped into its legs
    start = model.robot.state()[0][2]
    run(sim, 300)
    pos, orn, joints = model.robot.state()
    assert joints == [] and pos[2] < start - 0.1  # it fell, and has no joint positions
    assert model.robot.read([]) == []
    model.robot.apply_efforts([], [])
    sim.reset_world()
    assert model.robot.state()[0][2] == pytest.approx(start)
    sim.delete_model('thing')
    run(sim, 10)


def test_a_controlled_model_without_actuated_joints_gets_an_idle_controller_manager(sim):
    ros = FakeRos({})
    xml = '<robot name="crate">%s%s</robot>' % (box_link('crate'), control_plugin('/crate'))
    model = sim.spawn_urdf(
        'crate',
        xml,
        controller_manager_factory=lambda hw, ns: ControllerManager(hw, ros.node_handle, ns),
    )
    assert model.hw.joint_names() == []
    run(sim, 50)


@pytest.mark.parametrize(
    'name, rule',
    [
        ('/tmp/arm1-guard/x', 'not a path'),
        ('../../x', 'not a path'),
        ('a' * 5000, 'over the limit of 255'),
        ('', 'empty'),
        (' padded', 'white space'),
        ('bad\nname', 'control character'),
        ('scoped::name', "'::'"),
        ('__model__', 'reserved'),
        ('world', 'reserved'),
    ],
)
def test_a_model_name_is_only_a_name(sim, name, rule):
    with pytest.raises(SpawnError, match=rule.replace('(', r'\(')):
        sim.spawn_urdf(name, CRATE)
    assert not sim.models and not sim.world.robots
    assert not os.path.exists('/tmp/arm1-guard')


def test_the_world_names_its_files_itself_inside_its_own_folder(sim):
    sim.spawn_urdf('crate.urdf', CRATE)
    sim.spawn_urdf('x', CRATE, position=(1, 0, 0))
    files = sorted(os.path.basename(f) for f in glob.glob(os.path.join(sim.folder, '*')))
    assert files == ['model-1.urdf', 'model-2.urdf']


def test_models_per_world_and_description_size_are_bounded():
    cfg = WorldConfig(limits=Limits(models=2, description_bytes=4000))
    s = Simulation(cfg)
    try:
        s.spawn_urdf('a', CRATE)
        s.spawn_urdf('b', CRATE, position=(1, 0, 0))
        with pytest.raises(SpawnError, match=r'models is 3, over the limit of 2 .*~limits/models'):
            s.spawn_urdf('c', CRATE)
        s.delete_model('a')
        big = CRATE.replace('</robot>', '<!-- %s --></robot>' % ('x' * 5000))
        with pytest.raises(SpawnError, match='description_bytes'):
            s.spawn_urdf('c', big)
        s.spawn_urdf('c', CRATE, position=(2, 0, 0))
    finally:
        s.close()


@pytest.mark.parametrize(
    'position, orientation',
    [((math.nan, 0, 0), (0, 0, 0, 1)), ((0, 0, 0), (0, math.inf, 0, 1)), ((0, 0), (0, 0, 0, 1))],
)
def test_a_non_finite_pose_is_refused(sim, position, orientation):
    with pytest.raises(SpawnError, match='pose'):
        sim.spawn_urdf('crate', CRATE, position=position, orientation=orientation)


def test_set_model_configuration_refuses_lists_of_different_lengths(sim, arm1_urdf, find_package):
    sim.spawn_urdf('arm1', arm1_urdf, find_package=find_package)
    with pytest.raises(SpawnError, match='2 joint.* 1 value'):
        sim.set_model_configuration('arm1', ['joint1', 'joint2'], [0.5])
    with pytest.raises(SpawnError, match='1 joint.* 2 value'):
        sim.set_model_configuration('arm1', ['joint1'], [0.5, 0.2])
    sim.set_model_configuration('arm1', ['joint1', 'joint2'], [0.5, 0.2])


class Plugin:
    def __init__(self):
        self.down = 0

    def shutdown(self):
        self.down += 1


def test_delete_releases_controllers_plugins_and_the_name(
    sim, arm1_urdf, controllers_params, find_package
):
    ros = FakeRos(copy.deepcopy(controllers_params))
    plugins = []

    def attach(model):
        plugins.append(Plugin())
        model.plugins.append(plugins[-1])

    def spawn():
        return sim.spawn_urdf(
            'arm1',
            arm1_urdf,
            find_package=find_package,
            attach=attach,
            controller_manager_factory=lambda hw, ns: ControllerManager(hw, ros.node_handle, ns),
        )

    for _ in range(3):
        model = spawn()
        cm = model.controller_manager
        cm.load_controller('joint1_position_controller')
        ok, _ = pump_switch(cm, ['joint1_position_controller'])
        assert ok
        assert ros.subscribers['/arm1/joint1_position_controller/command']
        sim.delete_model('arm1')
        assert plugins[-1].down == 1
        assert not ros.subscribers['/arm1/joint1_position_controller/command']
        assert cm.list_controllers() == []
    assert not sim.models and len(sim.world.robots) == 0


def test_a_spawn_that_fails_in_its_plugins_leaves_nothing_behind(sim, arm1_urdf, find_package):
    def attach(model):
        model.plugins.append(Plugin())
        raise SpawnError('namespace taken')

    with pytest.raises(SpawnError, match="cannot spawn 'arm1': namespace taken"):
        sim.spawn_urdf('arm1', arm1_urdf, find_package=find_package, attach=attach)
    assert not sim.models and not sim.world.robots and not sim.sensors.cameras
    sim.spawn_urdf('arm1', arm1_urdf, find_package=find_package)


def test_a_switch_waiting_when_its_model_is_deleted_fails_instead_of_hanging(
    sim, arm1_urdf, controllers_params, find_package
):
    ros = FakeRos(copy.deepcopy(controllers_params))
    model = sim.spawn_urdf(
        'arm1',
        arm1_urdf,
        find_package=find_package,
        controller_manager_factory=lambda hw, ns: ControllerManager(hw, ros.node_handle, ns),
    )
    cm = model.controller_manager
    cm.load_controller('joint1_position_controller')
    waiter = SwitchRequest(cm, ['joint1_position_controller'])
    waiter.wait(0.2)  # physics does not step: the switch waits
    assert waiter.waiting
    sim.delete_model('arm1')
    assert waiter.wait(2.0) is False


OFFSET_INERTIA = (
    '<robot name="plank"><link name="plank"><inertial><origin xyz="0.2 0 0"/>'
    '<mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" '
    'iyz="0"/></inertial><collision><geometry><box size="0.5 0.1 0.02"/></geometry>'
    '</collision></link></robot>'
)


def test_a_base_link_with_an_offset_centre_of_mass_is_posed_and_reset_by_its_frame():
    s = Simulation(WorldConfig(gravity=(0.0, 0.0, 0.0)))
    try:
        model = s.spawn_urdf('plank', OFFSET_INERTIA, position=(1.0, 2.0, 0.5))
        pos, orn = model.robot.link_pose('plank')
        assert pos == pytest.approx((1.0, 2.0, 0.5), abs=1e-6)
        s.set_model_configuration('plank', [], [])
        run(s, 10)
        s.reset_world()
        assert model.robot.link_pose('plank')[0] == pytest.approx((1.0, 2.0, 0.5), abs=1e-6)
    finally:
        s.close()


def test_a_free_body_keeps_its_speed_as_in_gazebo_no_velocity_damping():
    import pybullet as p

    s = Simulation(WorldConfig(gravity=(0.0, 0.0, 0.0)))
    try:
        model = s.spawn_urdf('crate', CRATE, position=(0, 0, 1.0))
        body, cid = model.robot.body, model.robot.client
        p.resetBaseVelocity(body, (1.0, 0, 0), (0, 0, 0.5), physicsClientId=cid)
        run(s, 1000)  # one second
        linear, angular = p.getBaseVelocity(body, physicsClientId=cid)
        assert linear[0] == pytest.approx(1.0, abs=1e-6)
        assert angular[2] == pytest.approx(0.5, abs=1e-6)
    finally:
        s.close()
