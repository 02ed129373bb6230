"""Long trajectories (faults, third round): a 100 000-point goal costs the physics update no
more than a short one (binary search for the segment, no scan for the goal's end), and its
segments are built without the lock the update needs."""

import time

from helpers import TrajectoryRig as Rig

from _arm1sim.control import joint_trajectory_controller as jtc_module
from _arm1sim.control.trajectory import Segment, State, find_segment

POINTS = 100000


class CountingSegment(Segment):
    """A Segment that counts how often its start is read."""

    reads = 0

    @property  # type: ignore[override]
    def start(self):
        CountingSegment.reads += 1
        return self.__dict__['_start']

    @start.setter
    def start(self, value):
        self.__dict__['_start'] = value


def test_find_segment_is_a_binary_search():
    traj = [CountingSegment(k, State(0.0), k + 1, State(0.0)) for k in range(POINTS)]
    for t, expected in (
        (-1.0, 0),
        (0.0, 0),
        (5.5, 5),
        (POINTS - 0.5, POINTS - 1),
        (1e9, POINTS - 1),
    ):
        CountingSegment.reads = 0
        assert find_segment(traj, t) == expected
        assert CountingSegment.reads <= 2 * POINTS.bit_length(), CountingSegment.reads
    assert find_segment([], 1.0) == -1


def long_goal(rig, points=POINTS, seconds=100.0):
    return rig.goal([((k + 1) * seconds / points, (0.001 * k, 0.0)) for k in range(points)])


def update_cpu(rig, steps=50):
    t0 = time.process_time()
    rig.step(steps)
    return (time.process_time() - t0) / steps


def test_an_update_under_a_100000_point_goal_costs_what_one_under_a_short_goal_does():
    short, long = Rig(), Rig()
    for r in (short, long):
        r.start()
    assert long_goal(short, 10, 100.0).status == 'ACTIVE'
    assert long_goal(long).status == 'ACTIVE'
    update_cpu(short), update_cpu(long)  # warm up
    base, big = update_cpu(short, 200), update_cpu(long, 200)
    # CPU time of this process (not wall time): the old scans took ~100x a short goal's update
    assert big < 10 * base + 2e-4, (big, base)
    assert long.c.uptime > 0.2 and long.desired(0)[0] > 0.0


def test_segments_are_built_without_the_lock_the_update_needs(monkeypatch):
    rig = Rig()
    rig.start()
    held = []

    class Watched(Segment):
        __slots__ = ()

        def __init__(self, *args, **kwargs):
            held.append(rig.c._lock.locked())
            super().__init__(*args, **kwargs)

    monkeypatch.setattr(jtc_module, 'Segment', Watched)
    gh = long_goal(rig, 2000, 10.0)
    assert gh.status == 'ACTIVE'
    assert len(held) == 2 * 2000 and not any(held), 'segments built under the update lock'
