"""Contacts reach the solver once the shapes touch, as ODE makes them."""

import pybullet as p
import pytest
from helpers import box, robot, world

SIZE = 0.2  # m, the test box's edge


def bottom_gap(sim, model):
    """Height of the box's bottom face over the ground (negative: sunk into it)."""
    (x, y, z), _ = p.getBasePositionAndOrientation(
        model.robot.body, physicsClientId=sim.world.client
    )
    return z - SIZE / 2


@pytest.mark.parametrize('sink', [0.0005, 0.001])
def test_a_falling_box_is_stopped_once_it_touches_not_before(sink):
    # ODE makes a contact when two shapes overlap and pushes them apart from there (ERP);
    # Bullet would also solve a manifold's points that are still apart, stopping a body
    # short of the ground on the step it would reach it. A box 1.5 mm above the ground
    # (within its manifold's reach), sent down fast enough to end the step 0.5-1 mm into
    # it, does sink in, as in Gazebo.
    sim = world(ground=True)
    try:
        model = sim.spawn_urdf(
            'b', robot(box('base', 1.0, SIZE)), position=(0, 0, SIZE / 2 + 0.0015)
        )
        client, body = sim.world.client, model.robot.body
        sim.step()  # the manifold is made while the box is still apart
        gap = bottom_gap(sim, model)
        assert gap == pytest.approx(0.0015, abs=1e-4)
        p.resetBaseVelocity(body, (0, 0, -(gap + sink) / 0.001), (0, 0, 0), physicsClientId=client)
        sim.step()
        assert bottom_gap(sim, model) == pytest.approx(-sink, abs=1e-4)
        for _ in range(500):  # then is pushed back out, resting as a box set down does
            sim.step()
        assert 0.0 < bottom_gap(sim, model) < 0.0015  # within pybullet's 1 mm margin
        velocity, _ = p.getBaseVelocity(body, physicsClientId=client)
        assert abs(velocity[2]) < 1e-3
    finally:
        sim.close()
