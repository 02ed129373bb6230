"""CAD inertias as Gazebo takes them: a tensor pybullet would zero (a principal moment above
the sum of the other two, or negative) is corrected by the least change pybullet accepts,
with one warning naming the link and both tensors; tiny masses and inertias behave.
Real pybullet through Simulation."""

import logging
import math

import numpy as np
import pybullet as p
import pytest

from _arm1sim.description.inertia import accepted, corrected, least_change, principal_moments
from _arm1sim.description.sdf_world import WorldConfig
from _arm1sim.sim.simulation import Simulation

# The SolidWorks finger of the report: izz 5.58e-6 > ixx + iyy 2.59e-6, positive definite.
FINGER = (1.21e-6, 1.38e-6, 5.58e-6, 0.0, 0.0, 0.0)


def rotated(t, rpy):
    """``t`` (ixx, iyy, izz, ixy, ixz, iyz) seen in axes turned by ``rpy``."""
    r = np.array(p.getMatrixFromQuaternion(p.getQuaternionFromEuler(rpy))).reshape(3, 3)
    ixx, iyy, izz, ixy, ixz, iyz = t
    m = r @ np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]]) @ r.T
    return (m[0, 0], m[1, 1], m[2, 2], m[0, 1], m[0, 2], m[1, 2])


def urdf(t, mass=0.01, name='finger'):
    """A base welded to the world and a link on a revolute joint (x axis), its centre of mass
    0.05 m out along y, with inertia ``t``."""
    ixx, iyy, izz, ixy, ixz, iyz = t
    return (
        '<robot name="r"><link name="world"/>'
        '<link name="base"><inertial><mass value="1"/>'
        '<inertia ixx="1e-3" iyy="1e-3" izz="1e-3" ixy="0" ixz="0" iyz="0"/></inertial></link>'
        '<joint name="fix" type="fixed"><parent link="world"/><child link="base"/>'
        '<origin xyz="0 0 1"/></joint>'
        '<link name="%s"><inertial><origin xyz="0 0.05 0"/><mass value="%r"/>'
        '<inertia ixx="%r" iyy="%r" izz="%r" ixy="%r" ixz="%r" iyz="%r"/></inertial></link>'
        '<joint name="hinge" type="revolute"><parent link="base"/><child link="%s"/>'
        '<axis xyz="1 0 0"/><limit lower="-10" upper="10" effort="1" velocity="100"/></joint>'
        '</robot>' % (name, mass, ixx, iyy, izz, ixy, ixz, iyz, name)
    )


@pytest.fixture
def sim():
    s = Simulation(WorldConfig())
    yield s
    s.close()


def pybullet_moments(sim, model, link='finger'):
    robot = model.robot
    info = p.getDynamicsInfo(robot.body, robot.link_index[link], physicsClientId=robot.client)
    return sorted(info[2])


def test_an_accepted_tensor_is_left_as_it_is():
    assert corrected((1e-6, 2e-6, 3e-6, 0.0, 0.0, 0.0)) is None  # on the boundary: accepted
    assert corrected(rotated((1e-6, 2e-6, 2.5e-6, 0, 0, 0), (0.3, -0.2, 1.1))) is None


def test_the_correction_is_the_nearest_accepted_moments():
    new = corrected(FINGER)
    assert new is not None and new[3:] == (0.0, 0.0, 0.0)
    assert accepted(new[:3])
    d = (5.58e-6 - 1.21e-6 - 1.38e-6) / 3  # the projection onto izz = ixx + iyy
    assert new[0] == pytest.approx(1.21e-6 + d, rel=1e-9)
    assert new[1] == pytest.approx(1.38e-6 + d, rel=1e-9)
    assert new[2] == pytest.approx(5.58e-6 - d, rel=1e-5)  # less the margin
    # Nearest: no accepted point on a grid around it is closer.
    dist = np.linalg.norm(np.subtract(new[:3], FINGER[:3]))
    rng = np.random.default_rng(1)
    for _ in range(2000):
        q = np.array(FINGER[:3]) + rng.normal(0, 1.5e-6, 3)
        if accepted(q):
            assert np.linalg.norm(q - FINGER[:3]) >= dist * (1 - 1e-4)
    assert least_change((-1e-7, 1e-6, 1e-6)) == [0.0, 1e-6, 1e-6]  # negative: to zero


def test_a_rotated_tensor_keeps_its_principal_axes():
    t = rotated(FINGER, (0.4, 0.7, -1.2))
    new = corrected(t)
    assert new is not None
    assert accepted(principal_moments(new))
    old_axes = np.linalg.eigh(_m(t))[1]
    new_axes = np.linalg.eigh(_m(new))[1]
    assert np.abs(np.abs(np.sum(old_axes * new_axes, axis=0)) - 1).max() < 1e-6


def _m(t):
    ixx, iyy, izz, ixy, ixz, iyz = t
    return np.array([[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]])


@pytest.mark.parametrize('rpy', [(0, 0, 0), (0.4, 0.7, -1.2)])
def test_pybullet_gets_the_corrected_inertia_not_zero_and_one_warning_says_so(sim, caplog, rpy):
    t = rotated(FINGER, rpy)
    with caplog.at_level(logging.WARNING):
        model = sim.spawn_urdf('r', urdf(t))
    warnings = [r.getMessage() for r in caplog.records if 'pybullet would set' in r.getMessage()]
    assert len(warnings) == 1
    assert "link 'finger'" in warnings[0] and "model 'r'" in warnings[0]
    assert 'izz=%.6g' % t[2] in warnings[0]  # the tensor as written
    new = corrected(t)
    assert 'izz=%.6g' % new[2] in warnings[0]  # and the one used
    got = pybullet_moments(sim, model)
    assert min(got) > 0  # not zeroed
    assert got == pytest.approx(sorted(principal_moments(new)), rel=1e-4)


def test_a_good_tensor_spawns_without_a_word(sim, caplog):
    with caplog.at_level(logging.WARNING):
        model = sim.spawn_urdf('r', urdf((2e-6, 2e-6, 3e-6, 0, 0, 0)))
    assert not [r for r in caplog.records if 'pybullet would set' in r.getMessage()]
    assert pybullet_moments(sim, model) == pytest.approx([2e-6, 2e-6, 3e-6])


@pytest.mark.parametrize('tensor', [(1e-9, 1e-9, 1e-9, 0, 0, 0), (1e-9, 1.2e-9, 4e-9, 0, 0, 0)])
def test_a_tiny_link_swings_as_a_pendulum(sim, tensor):
    """1e-5 kg, inertias of 1e-9 kg m^2 (the second one corrected): it falls from horizontal
    under gravity as a compound pendulum, finite, within energy conservation."""
    model = sim.spawn_urdf('r', urdf(tensor, mass=1e-5))
    robot = model.robot
    assert min(pybullet_moments(sim, model)) > 0
    hinge = robot.indices(['hinge'])
    m, r, g = 1e-5, 0.05, 9.8
    ixx = (corrected(tensor) or tensor)[0]
    pivot = ixx + m * r * r  # about the hinge
    top_speed = math.sqrt(2 * m * g * r / pivot)  # at the bottom, from horizontal at rest
    seen = []
    for _ in range(400):
        sim.step()
        seen.append(robot.read(hinge)[0])
    assert all(math.isfinite(q) and math.isfinite(v) for q, v in seen)
    angles = [q for q, _ in seen]
    assert min(angles) < -1.2  # it fell (about x: y toward -z is a negative turn)
    assert max(abs(v) for _, v in seen) <= top_speed * 1.02
    # Small-angle-free check: the quarter swing takes what a compound pendulum takes
    # (about 1.854 sqrt(I / (m g r)) for 90 degrees from rest), within 5 %.
    quarter = next(k for k, q in enumerate(angles) if q <= -math.pi / 2) * sim.period
    assert quarter == pytest.approx(1.8541 * math.sqrt(pivot / (m * g * r)), rel=0.05)
