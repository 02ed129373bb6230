"""Contacts with the world's static scenery reach the solver once the shapes touch, as ODE
makes them."""

import pybullet as p
import pytest
from helpers import box, robot, world

SIZE = 0.2  # m, the test box's edge
START = 0.0018  # m over the ground: in the manifold's reach, beyond SCENERY_CONTACT_WITHIN


def bottom_of(sim, body):
    """Height of the box's bottom face over the ground (negative: sunk into it)."""
    (x, y, z), _ = p.getBasePositionAndOrientation(body, physicsClientId=sim.world.client)
    return z - SIZE / 2


@pytest.mark.parametrize('sink', [0.0005, 0.001])
def test_a_box_falling_onto_the_ground_stops_once_it_touches_not_before(sink):
    # ODE makes a contact when two shapes overlap and pushes them apart from there (ERP);
    # Bullet would also solve a manifold's points that are still apart, stopping a body
    # short of the ground on the step it would reach it. Sent down fast enough to end the
    # step 0.5-1 mm into the ground, the box does sink in, as in Gazebo.
    sim = world(ground=True)
    try:
        model = sim.spawn_urdf(
            'b', robot(box('base', 1.0, SIZE)), position=(0, 0, SIZE / 2 + START)
        )
        client, body = sim.world.client, model.robot.body
        sim.step()  # the manifold is made while the box is still apart
        gap = bottom_of(sim, body)
        assert gap == pytest.approx(START, abs=1e-4)
        p.resetBaseVelocity(
            body, (0, 0, -(gap + sink) / sim.period), (0, 0, 0), physicsClientId=client
        )
        sim.step()
        assert bottom_of(sim, body) == pytest.approx(-sink, abs=1e-4)
        for _ in range(500):  # then is pushed back out, resting as a box set down does
            sim.step()
        assert 0.0 < bottom_of(sim, body) < 0.0015  # within pybullet's 1 mm margin
        velocity, _ = p.getBaseVelocity(body, physicsClientId=client)
        assert abs(velocity[2]) < 1e-3
    finally:
        sim.close()
