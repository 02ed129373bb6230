"""gazebo_ros_diff_drive (physics.diff_drive) on a two-wheeled robot of our own, with real
pybullet: it drives at the commanded speed, turns at the commanded rate, and its odometry
(world and encoder sources) follows the model's pose."""

import logging
import math

import pytest
from helpers import GROUND, run, spawn
from two_wheels import SEPARATION, robot_urdf

from _arm1sim.description.sdf_world import parse_world
from _arm1sim.physics.diff_drive import DiffDrive
from _arm1sim.physics.link_motion import point_state
from _arm1sim.sim.simulation import Simulation


@pytest.fixture
def sim():
    s = Simulation(parse_world(GROUND))
    yield s
    s.close()


def base(model):
    pos, orn, v, w = point_state(model.robot, -1)
    qx, qy, qz, qw = orn
    yaw = math.atan2(2 * (qw * qz + qx * qy), 1 - 2 * (qy * qy + qz * qz))
    return pos, yaw, v, w


def test_drives_straight_at_the_commanded_speed(sim):
    model, drive, readings = spawn(sim)
    run(sim, 0.3)  # settle on the ground
    start, yaw0, _, _ = base(model)
    drive.set_command(0.2, 0.0)
    run(sim, 1.0)  # accelerate
    mid, _, v, _ = base(model)
    run(sim, 2.0)
    end, yaw1, _, _ = base(model)
    speed = math.hypot(end[0] - mid[0], end[1] - mid[1]) / 2.0
    assert speed == pytest.approx(0.2, rel=0.05)
    assert end[0] - start[0] > 0.5  # forward is +x of the base
    assert abs(end[1] - start[1]) < 0.02
    assert abs(yaw1 - yaw0) < 0.03
    assert v[0] == pytest.approx(0.2, rel=0.05)


def test_turns_at_the_commanded_rate(sim):
    model, drive, readings = spawn(sim)
    run(sim, 0.3)
    drive.set_command(0.0, 1.0)
    run(sim, 1.0)
    _, yaw0, _, w = base(model)
    run(sim, 1.0)
    _, yaw1, _, _ = base(model)
    turned = math.remainder(yaw1 - yaw0, 2 * math.pi)
    assert turned == pytest.approx(1.0, rel=0.08)  # counter-clockwise, as REP 103
    assert w[2] == pytest.approx(1.0, rel=0.08)


def test_legacy_mode_turns_the_other_way(sim):
    # upstream's default: left and right mixed up, so a positive angular.z turns clockwise
    model, drive, _ = spawn(sim, legacyMode=None)
    run(sim, 0.3)
    _, yaw0, _, _ = base(model)
    drive.set_command(0.0, 1.0)
    run(sim, 1.5)
    _, yaw1, _, _ = base(model)
    assert math.remainder(yaw1 - yaw0, 2 * math.pi) < -0.5


@pytest.mark.parametrize('source', ['world', 'encoder'])
def test_odometry_follows_the_model(sim, source):
    model, drive, readings = spawn(sim, odometrySource=source)
    run(sim, 0.3)
    start, yaw_start, _, _ = base(model)
    drive.set_command(0.15, 0.4)  # an arc
    run(sim, 3.0)
    end, yaw_end, v, w = base(model)
    stamp, r = readings[-1]
    assert stamp == sim.time_ns
    ox, oy, oz, ow = r.orientation
    odom_yaw = math.atan2(2 * (ow * oz + ox * oy), 1 - 2 * (oy * oy + oz * oz))
    if source == 'world':
        # the model's own pose and its velocity in the base frame
        assert r.position[:2] == pytest.approx(end[:2], abs=1e-6)
        assert odom_yaw == pytest.approx(yaw_end, abs=1e-6)
        c, s = math.cos(yaw_end), math.sin(yaw_end)
        assert r.linear[0] == pytest.approx(c * v[0] + s * v[1], abs=1e-6)
        assert r.linear[1] == pytest.approx(c * v[1] - s * v[0], abs=1e-6)
        assert r.linear[0] == pytest.approx(0.15, rel=0.1)
        assert abs(r.linear[1]) < 0.01
    else:
        # integrated wheel speeds from zero at spawn: the path travelled, within a few %
        travelled = math.hypot(end[0] - start[0], end[1] - start[1])
        assert math.hypot(r.position[0], r.position[1]) == pytest.approx(travelled, rel=0.05)
        assert odom_yaw == pytest.approx(math.remainder(yaw_end - yaw_start, 2 * math.pi), rel=0.05)
        assert math.hypot(*r.linear[:2]) == pytest.approx(0.15, rel=0.1)
    assert r.angular[2] == pytest.approx(0.4, rel=0.05)


def test_reports_at_its_update_rate_with_nobody_listening(sim):
    # wanted() is left False: a diff drive acts and reports regardless
    model, drive, readings = spawn(sim, updateRate=25)
    assert not drive.wanted()
    run(sim, 2.0)
    assert len(readings) == pytest.approx(50, abs=1)


def test_wheel_states_when_asked(sim):
    model, drive, readings = spawn(sim, publishWheelJointState='true', publishWheelTF='true')
    drive.set_command(0.1, 0.0)
    run(sim, 1.0)
    r = readings[-1][1]
    names = [n for n, _ in r.wheel_positions]
    assert names == ['wheel_left_joint', 'wheel_right_joint']
    assert all(pos > 1.0 for _, pos in r.wheel_positions)  # 0.1 m/s over 0.04 m: rad/s 2.5
    assert [(a, b) for a, b, _, _ in r.wheel_frames] == [
        ('base_footprint', 'wheel_left_link'),
        ('base_footprint', 'wheel_right_link'),
    ]
    assert r.wheel_frames[0][2][1] == pytest.approx(SEPARATION / 2, abs=1e-3)


@pytest.mark.parametrize('reset', ['reset_simulation', 'reset_world'])
def test_a_reset_clears_the_command_and_the_encoder(sim, reset):
    model, drive, readings = spawn(sim, odometrySource='encoder')
    drive.set_command(0.2, 0.0)
    run(sim, 1.0)
    assert readings[-1][1].position[0] > 0.1
    getattr(sim, reset)()  # Gazebo calls the plugin's Reset() on both
    run(sim, 0.5)
    _, _, v, _ = base(model)
    assert abs(v[0]) < 0.01  # no command after Reset
    assert abs(readings[-1][1].position[0]) < 0.01


def test_a_missing_wheel_joint_leaves_the_plugin_out(sim, caplog):
    with caplog.at_level(logging.WARNING):
        model = sim.spawn_urdf('two_wheels', robot_urdf(rightJoint='no_such_joint'))
    assert not [s for s in model.sensors if isinstance(s, DiffDrive)]
    assert "rightJoint 'no_such_joint' is not a joint of the model" in caplog.text
