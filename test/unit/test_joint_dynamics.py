"""<dynamics damping friction> as Gazebo applies them (ODEJoint): damping a viscous torque
-d q', friction the joint motor's fmax at velocity 0 (Coulomb). Checked numerically on a
one-joint arm of our own: I = 0.01 + 1 kg * (0.1 m)^2 = 0.02 kg m^2 about the axis, no gravity."""

import math

import pybullet as p
import pytest

from _arm1sim.description.sdf_world import WorldConfig
from _arm1sim.sim.simulation import Simulation

INERTIA = 0.02
STEP = 0.001


def arm(damping=0.0, friction=0.0):
    return (
        '<robot name="a"><link name="world"/>'
        '<link name="arm"><inertial><origin xyz="0.1 0 0"/><mass value="1"/>'
        '<inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>'
        '<joint name="j" type="continuous"><parent link="world"/><child link="arm"/>'
        '<axis xyz="0 0 1"/><limit effort="100" velocity="100"/>'
        '<dynamics damping="%g" friction="%g"/></joint></robot>' % (damping, friction)
    )


@pytest.fixture
def sim():
    s = Simulation(WorldConfig(max_step_size=STEP, gravity=(0.0, 0.0, 0.0)))
    yield s
    s.close()


def run(sim, robot, seconds, effort=0.0):
    index = robot.indices(['j'])
    for _ in range(int(round(seconds / STEP))):
        robot.apply_efforts(index, [effort])
        sim.step()
    return robot.read(index)[0][:2]


def test_damping_is_a_viscous_torque(sim):
    robot = sim.spawn_urdf('a', arm(damping=0.01)).robot
    p.resetJointState(robot.body, robot.joint_index['j'], 0.0, 1.0, physicsClientId=robot.client)
    _, v = run(sim, robot, 1.0)
    # q'' = -d q' / I: the speed decays as exp(-d t / I) = exp(-0.5) after 1 s
    assert v == pytest.approx(math.exp(-0.01 / INERTIA), rel=0.02)


def test_friction_holds_below_it_and_subtracts_above_it(sim):
    robot = sim.spawn_urdf('a', arm(friction=0.2)).robot
    assert robot.joint_friction == {robot.joint_index['j']: pytest.approx(0.2)}
    q, v = run(sim, robot, 0.5, effort=0.15)  # less than the friction: stays put
    assert abs(q) < 1e-6 and abs(v) < 1e-6
    q, v = run(sim, robot, 1.0, effort=0.3)  # (0.3 - 0.2) / I = 5 rad/s^2
    assert v == pytest.approx((0.3 - 0.2) / INERTIA * 1.0, rel=0.1)
    _, v = run(sim, robot, 3.0, effort=0.0)  # friction alone stops it: 0.2 / I = 10 rad/s^2
    assert abs(v) < 1e-6


def test_no_dynamics_means_free_joint(sim):
    robot = sim.spawn_urdf('a', arm()).robot
    _, v = run(sim, robot, 1.0, effort=0.02)
    assert v == pytest.approx(0.02 / INERTIA, rel=0.02)


# A JACO2 finger: 10 g, 22 mm to its centre of mass, stops at 0 and 1.51 rad, 2 N m.
FINGER = (
    '<robot name="f"><link name="world"/>'
    '<link name="finger"><inertial><origin xyz="0.022 0 0"/><mass value="0.01"/>'
    '<inertia ixx="7.9e-7" iyy="7.9e-7" izz="8e-8" ixy="0" ixz="0" iyz="0"/></inertial></link>'
    '<joint name="j" type="revolute"><parent link="world"/><child link="finger"/>'
    '<axis xyz="0 0 1"/><limit effort="2" lower="0" upper="1.51" velocity="1"/></joint></robot>'
)


@pytest.mark.parametrize('past', [0.005, 0.05, 0.3])
def test_a_joint_past_its_stop_returns_to_it_as_with_odes_stop_erp(sim, past):
    # ODE's joint stop (Gazebo's default stop ERP 0.2, CFM 0) removes a fifth of the overshoot
    # each step, however deep. pybullet corrected only overshoots under its split-impulse
    # threshold (0.04): deeper ones stayed, since Bullet's multibodies never apply the split
    # part. Pressed outward with the finger's full effort, as a contact would press it.
    robot = sim.spawn_urdf('f', FINGER).robot
    p.resetJointState(robot.body, robot.joint_index['j'], -past, physicsClientId=robot.client)
    q, _ = run(sim, robot, 0.1, effort=-2.0)
    assert abs(q) < 1e-3


def test_a_joint_driven_through_its_stop_in_one_step_ends_at_it(sim):
    # 2 N m on 5e-6 kg m^2 reaches pybullet's 100 rad/s cap: 0.1 rad a step, from 1.3 to 1.6
    robot = sim.spawn_urdf('f', FINGER).robot
    p.resetJointState(robot.body, robot.joint_index['j'], 1.3, physicsClientId=robot.client)
    q, _ = run(sim, robot, 0.1, effort=2.0)
    assert q == pytest.approx(1.51, abs=1e-3)


def test_a_free_joint_past_its_stop_comes_back_into_its_range(sim):
    # the correction is a velocity, as in ODE: the joint pops back in (and may cross its range)
    robot = sim.spawn_urdf('f', FINGER).robot
    p.resetJointState(robot.body, robot.joint_index['j'], -0.3, physicsClientId=robot.client)
    q, _ = run(sim, robot, 0.2)
    assert -1e-3 < q < 1.51 + 1e-3
