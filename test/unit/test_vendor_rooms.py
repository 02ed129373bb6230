"""Vendor rooms (src/_arm1sim/vendors/): the core names no vendor, a room plugs in through the
registries alone (robotSimType, controller types), and the toy room's RobotHWSim drives a
robot in pybullet with what it reads from the parameter server."""

import os
import re

import pytest
from conftest import JSC, REPO_ROOT, WORLD_FILE, FakeRos, box_link, pump_switch, transmission

from _arm1sim.control.controller_manager import ControllerManager
from _arm1sim.control.interfaces import RobotHWSimError
from _arm1sim.control.registry import CONTROLLER_TYPES, CPP_ONLY_PACKAGES
from _arm1sim.description.gazebo_plugins import unimplemented
from _arm1sim.description.sdf_world import read_world
from _arm1sim.description.urdf_model import parse_urdf
from _arm1sim.sim.robot_hw_sim import DefaultRobotHWSim
from _arm1sim.sim.robot_hw_sims import robot_hw_sim_class
from _arm1sim.sim.simulation import Simulation, SpawnError
from _arm1sim.vendors import load, rooms
from _arm1sim.vendors.tinkerbot.hw_sim import TinkerHWSim

# The core: the layers and the ROS rooms every robot goes through (ros/tools and tryout/
# name vendors' launch files and profiles as examples, which is their job).
CORE = ['description', 'physics', 'control', 'sim', 'ros/world', 'ros/control', 'ros/plugins']
SRC = os.path.join(REPO_ROOT, 'src', '_arm1sim')
TINKER = 'tinkerbot_gazebo/TinkerHWSim'


def vendor_words():
    """Each room's name and the packages its manifest names (robotSimType, controllers')."""
    words = set()
    for room in rooms():
        words.add(room.name)
        words.update(t.split('/')[0] for t in room.robot_hw_sims)
        words.update(room.cpp_only_packages)
    words.add('panda')  # Franka's robot, named in its URDFs' joints
    return words


def test_the_core_names_no_vendor():
    words = vendor_words()
    assert {'franka', 'tinkerbot'} <= words
    pattern = re.compile('|'.join(sorted(words)), re.IGNORECASE)
    hits = []
    for folder in CORE:
        for root, _, files in os.walk(os.path.join(SRC, folder)):
            for name in files:
                if name.endswith('.py'):
                    path = os.path.join(root, name)
                    with open(path, encoding='utf-8') as f:
                        for number, line in enumerate(f, 1):
                            if pattern.search(line):
                                hits.append('%s:%d: %s' % (path, number, line.strip()))
    assert hits == []


def test_rooms_plug_in_through_the_registries():
    assert robot_hw_sim_class('gazebo_ros_control/DefaultRobotHWSim') is DefaultRobotHWSim
    assert robot_hw_sim_class(TINKER) is TinkerHWSim
    assert robot_hw_sim_class('franka_gazebo/FrankaHWSim').__name__ == 'FrankaHWSim'
    assert robot_hw_sim_class('acme_gazebo/AcmeHWSim') is DefaultRobotHWSim  # warned at spawn
    for room in rooms():
        for ref in room.controllers:
            cls = load(room, ref)
            assert CONTROLLER_TYPES[cls.type_name] is cls
    assert CPP_ONLY_PACKAGES['franka_example_controllers'] == 'franka_ros'


def tinkerbot(sim_type=TINKER, interface='hardware_interface/EffortJointInterface'):
    return (
        '<?xml version="1.0"?>\n<robot name="tinker">\n  <link name="world"/>'
        + box_link('base', '0.2 0.2 0.05', 2.0)
        + box_link('arm', '0.4 0.04 0.04', 0.4, xyz='0.2 0 0')
        + """
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/>
    <origin xyz="0 0 0.5"/></joint>
  <joint name="spin" type="continuous"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit effort="0.25" velocity="10"/></joint>"""
        + transmission('spin', interface)
        + """
  <gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so">
    <robotNamespace>/tinker</robotNamespace><robotSimType>%s</robotSimType>
  </plugin></gazebo>
</robot>
"""
        % sim_type
    )


def spawn(sim, ros, urdf):
    model = sim.spawn_urdf(
        'tinker',
        urdf,
        controller_manager_factory=lambda hw, ns: ControllerManager(hw, ros.node_handle, ns),
    )
    model.hw.init_sim(ros.node_handle(model.namespace), model.namespace)
    return model


@pytest.fixture
def sim():
    s = Simulation(read_world(WORLD_FILE))
    yield s
    s.close()


def test_the_toy_room_drives_its_joint_through_its_gear_ratio(sim):
    assert not unimplemented(parse_urdf(tinkerbot()), 'tinker')  # a known robotSimType
    ros = FakeRos(
        {
            'tinker': {
                'tinkerbot': {'gear_ratio': 2.0},
                'effort': {'type': 'effort_controllers/JointEffortController', 'joint': 'spin'},
                'joint_state_controller': {'type': JSC, 'publish_rate': 50},
            }
        }
    )
    model = spawn(sim, ros, tinkerbot())
    assert isinstance(model.hw, TinkerHWSim) and model.hw.gear_ratio == 2.0
    cm = model.controller_manager
    for name in ('effort', 'joint_state_controller'):
        cm.load_controller(name)
    assert pump_switch(cm, ['effort', 'joint_state_controller'])[0]
    ros.publish('/tinker/effort/command', 0.1)  # N·m asked; the gearbox doubles it
    for _ in range(200):
        sim.step()
    assert model.hw.applied == [pytest.approx(0.2)]
    ros.publish('/tinker/effort/command', 1.0)  # beyond the 0.25 N·m limit
    for _ in range(200):
        sim.step()
    assert model.hw.applied == [pytest.approx(0.25)]
    states = ros.messages('/tinker/joint_states')
    assert states and states[-1]['name'] == ['spin'] and states[-1]['velocity'][0] > 1.0


def test_the_toy_room_refuses_what_it_cannot_simulate_naming_the_robot_sim_type(sim):
    ros = FakeRos({'tinker': {'tinkerbot': {'gear_ratio': -1}}})
    with pytest.raises(RobotHWSimError, match='tinkerbot/gear_ratio'):
        spawn(sim, ros, tinkerbot())
    sim.delete_model('tinker')
    with pytest.raises(SpawnError, match=TINKER + ".*'spin'.*PositionJointInterface"):
        spawn(sim, FakeRos({}), tinkerbot(interface='hardware_interface/PositionJointInterface'))
    assert 'tinker' not in sim.models
