"""/gazebo/model_states' wall-time budget: every step at real time, bounded faster than that."""

from _arm1sim.ros.world.gazebo_state_api import BURST, MESSAGES_PER_SECOND, RateBudget


class Clock:
    def __init__(self) -> None:
        self.t = 0.0

    def __call__(self) -> float:
        return self.t


def run(budget: RateBudget, clock: Clock, steps: int, wake_every: float, per_wake: int) -> int:
    """Messages let through over ``steps`` steps run ``per_wake`` back to back a wake-up."""
    sent = 0
    for i in range(steps):
        if i % per_wake == 0:
            clock.t += wake_every
        sent += budget.take()
    return sent


def test_real_time_with_two_steps_a_wake_up_gets_every_step():
    clock = Clock()
    budget = RateBudget(MESSAGES_PER_SECOND, BURST, clock)
    assert run(budget, clock, 10_000, 0.002, 2) == 10_000  # 1 kHz: nothing dropped


def test_top_speed_is_capped_in_wall_time():
    clock = Clock()
    budget = RateBudget(MESSAGES_PER_SECOND, BURST, clock)
    sent = run(budget, clock, 60_000, 1 / 60_000, 1)  # one wall second at 60 000 steps/s
    assert MESSAGES_PER_SECOND - 10 <= sent <= MESSAGES_PER_SECOND + BURST
