"""A position joint under gazebo_ros_control pid_gains is a PD whose effort is computed once
per step and held over it (DefaultRobotHWSim's POSITION_PID; the derivative is the error's
finite difference). Such a loop on inertia I at step h is stable only while
4 - 2 d h / I - p h^2 / I > 0; past that it chatters at the step rate, bounded by the effort
limit. The stand-in must land on the same side of that line as Gazebo would (TurtleBot3's
OpenMANIPULATOR sits on it: docs/compatibility.md)."""

import pytest
from conftest import FakeRos, control_plugin, transmission

from _arm1sim.control.controller_manager import ControllerManager
from _arm1sim.control.switching import switch_while_updating
from _arm1sim.description.sdf_world import WorldConfig
from _arm1sim.sim.simulation import Simulation

INERTIA, P, STEP = 5e-4, 300.0, 0.001


def urdf():
    # one joint about z: no gravity torque, the link's own inertia only
    return """<?xml version="1.0"?>
<robot name="one_joint">
  <link name="world"/>
  <joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint>
  <link name="base"><inertial><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <joint name="spin" type="revolute"><parent link="base"/><child link="rotor"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="10"/></joint>
  <link name="rotor"><inertial><mass value="0.1"/>
    <inertia ixx="%g" ixy="0" ixz="0" iyy="%g" iyz="0" izz="%g"/></inertial></link>
  %s %s
</robot>""" % (
        INERTIA,
        INERTIA,
        INERTIA,
        transmission('spin', 'hardware_interface/PositionJointInterface'),
        control_plugin(None),
    )


def hold(d):
    """Command 0.1 rad from rest; the joint's velocities over the last 0.2 s of 2 s."""
    ros = FakeRos(
        {
            'c': {'type': 'position_controllers/JointPositionController', 'joint': 'spin'},
        }
    )
    sim = Simulation(WorldConfig(max_step_size=STEP))
    try:
        model = sim.spawn_urdf(
            'one_joint',
            urdf(),
            robot_namespace='/',
            controller_manager_factory=lambda hw, ns: ControllerManager(hw, ros.node_handle, ns),
        )
        model.hw.set_pid_gains({'spin': {'p': P, 'd': d}})
        cm = model.controller_manager
        cm.load_controller('c')
        assert switch_while_updating(cm, ['c'], [], sim.step, 1, poll=0.0005)[0]
        assert ros.publish('/c/command', 0.1) == 1
        index = model.robot.indices(['spin'])
        velocities = []
        for k in range(2000):
            sim.step()
            if k >= 1800:
                velocities.append(model.robot.read(index)[0][1])
        return velocities
    finally:
        sim.close()


def margin(d):
    return 4 - 2 * d * STEP / INERTIA - P * STEP * STEP / INERTIA


def test_inside_the_discrete_stability_limit_it_settles():
    d = 0.7  # margin 0.6
    assert margin(d) > 0.3
    assert max(abs(v) for v in hold(d)) < 1e-3


def test_past_the_limit_it_chatters_at_the_step_rate_as_gazebo_would():
    d = 0.95  # margin -0.4
    assert margin(d) < -0.2
    velocities = hold(d)
    assert max(abs(v) for v in velocities) > 0.3
    # sign flips every step: the step-rate mode of an explicit PD, not a slow oscillation
    flips = sum(1 for a, b in zip(velocities, velocities[1:]) if a * b < 0)
    assert flips > 0.9 * (len(velocities) - 1)
    # the effort limit (1 N·m) bounds it: |dv| per step <= 2 h / I
    assert max(abs(v) for v in velocities) == pytest.approx(STEP / INERTIA / 2 * 1.0, rel=0.3)
