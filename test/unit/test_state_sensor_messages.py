"""The state sensors' readings as ROS messages: fields, frames, stamps and covariances as
upstream fills them (no master needed)."""

from _arm1sim.physics.contact import ContactPair
from _arm1sim.physics.force_torque import WrenchReading
from _arm1sim.physics.imu import ImuReading
from _arm1sim.physics.p3d import P3dReading
from _arm1sim.ros.plugins.state_sensor_plugins import (
    contacts_message,
    imu_message,
    odometry_message,
    resolve_frame,
    wrench_message,
)

STAMP = 12_345_000_000 + 678


def test_imu_message_fields_and_covariances():
    r = ImuReading((0.1, 0.2, 0.3, 0.9), (1.0, 2.0, 3.0), (4.0, 5.0, 9.8), 0.5)
    msg = imu_message(STAMP, 'imu_link', r)
    assert (msg.header.stamp.secs, msg.header.stamp.nsecs) == (12, 345_000_678)
    assert msg.header.frame_id == 'imu_link'
    o = msg.orientation
    assert (o.x, o.y, o.z, o.w) == (0.1, 0.2, 0.3, 0.9)
    assert (msg.angular_velocity.x, msg.angular_velocity.z) == (1.0, 3.0)
    assert msg.linear_acceleration.z == 9.8
    for cov in (
        msg.orientation_covariance,
        msg.angular_velocity_covariance,
        msg.linear_acceleration_covariance,
    ):
        assert list(cov) == [0.25, 0, 0, 0, 0.25, 0, 0, 0, 0.25]


def test_odometry_message_frames_and_diagonals():
    r = P3dReading((1.0, 2.0, 3.0), (0.0, 0.0, 0.0, 1.0), (0.1, 0.2, 0.3), (0.4, 0.5, 0.6), 0.1)
    msg = odometry_message(STAMP, 'world', 'base', r)
    assert (msg.header.frame_id, msg.child_frame_id) == ('world', 'base')
    assert msg.pose.pose.position.y == 2.0 and msg.pose.pose.orientation.w == 1.0
    assert (msg.twist.twist.linear.z, msg.twist.twist.angular.x) == (0.3, 0.4)
    for cov in (msg.pose.covariance, msg.twist.covariance):
        assert [i for i, v in enumerate(cov) if v] == [0, 7, 14, 21, 28, 35]
        assert abs(cov[35] - 0.01) < 1e-12


def test_contacts_message_sums_each_pair_and_names_them():
    pair = ContactPair(
        'rover::base::base_collision',
        'ground_plane::link::collision',
        [((0.0, 0.0, 4.0), (0.1, 0.0, 0.0)), ((0.0, 1.0, 6.0), (0.0, 0.2, 0.0))],
        [(0.1, 0.1, 0.0), (-0.1, -0.1, 0.0)],
        [(0.0, 0.0, 1.0), (0.0, 0.0, 1.0)],
        [0.001, 0.002],
    )
    msg = contacts_message(STAMP, 'world', [pair, ContactPair('a', 'b')])
    assert msg.header.frame_id == 'world' and len(msg.states) == 2
    state = msg.states[0]
    assert (state.collision1_name, state.collision2_name) == (pair.collision1, pair.collision2)
    assert state.info.startswith('Debug:  i:(0/2)     my geom:rover::base::base_collision')
    assert 'time:12.345000678' in state.info
    total = state.total_wrench
    assert (total.force.y, total.force.z, total.torque.x, total.torque.y) == (1.0, 10.0, 0.1, 0.2)
    assert [w.force.z for w in state.wrenches] == [4.0, 6.0]
    assert [n.z for n in state.contact_normals] == [1.0, 1.0]
    assert state.contact_positions[1].x == -0.1 and list(state.depths) == [0.001, 0.002]
    assert msg.states[1].wrenches == [] and msg.states[1].total_wrench.force.z == 0


def test_wrench_message_and_frames():
    msg = wrench_message(STAMP, 'payload', WrenchReading((1.0, 2.0, 3.0), (4.0, 5.0, 6.0)))
    assert msg.header.frame_id == 'payload'
    assert (msg.wrench.force.z, msg.wrench.torque.x) == (3.0, 4.0)
    assert resolve_frame('/world') == 'world' and resolve_frame('base') == 'base'
