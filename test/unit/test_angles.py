"""control/angles.py against the ROS ``angles`` package."""

import math

import pytest

from _arm1sim.control.angles import (
    normalize_angle,
    shortest_angular_distance,
    shortest_angular_distance_with_large_limits,
    two_pi_complement,
)

PI = math.pi


@pytest.mark.parametrize(
    'angle, expected',
    [
        (0.0, 0.0),
        (1.0, 1.0),
        (-1.0, -1.0),
        (PI / 2, PI / 2),
        (3 * PI / 2, -PI / 2),
        (-3 * PI / 2, PI / 2),
        (2 * PI, 0.0),
        (-2 * PI, 0.0),
        (7 * PI / 2, -PI / 2),
        (10.5 * PI, 0.5 * PI),
        (-10.5 * PI, -0.5 * PI),
        (PI, PI),
        (-PI, PI),  # the range is (-pi, pi]
    ],
)
def test_normalize_angle(angle, expected):
    assert normalize_angle(angle) == pytest.approx(expected, abs=1e-9)


@pytest.mark.parametrize('angle', [x * 0.37 for x in range(-60, 61)])
def test_normalize_angle_range_and_equivalence(angle):
    a = normalize_angle(angle)
    assert -PI < a <= PI
    assert math.cos(a) == pytest.approx(math.cos(angle), abs=1e-9)
    assert math.sin(a) == pytest.approx(math.sin(angle), abs=1e-9)


@pytest.mark.parametrize(
    'frm, to, expected',
    [
        (0.0, 1.0, 1.0),
        (1.0, 0.0, -1.0),
        (3.0, -3.0, 2 * PI - 6.0),  # across +-pi: the short way is positive
        (-3.0, 3.0, 6.0 - 2 * PI),
        (0.0, 3 * PI / 2, -PI / 2),
        (PI / 4, -PI / 4, -PI / 2),
        (0.0, 4 * PI + 0.1, 0.1),
    ],
)
def test_shortest_angular_distance(frm, to, expected):
    assert shortest_angular_distance(frm, to) == pytest.approx(expected, abs=1e-9)


@pytest.mark.parametrize(
    'angle, expected',
    [
        (0.5, 0.5 - 2 * PI),
        (-0.5, 2 * PI - 0.5),
        (0.0, 2 * PI),
    ],
)
def test_two_pi_complement(angle, expected):
    assert two_pi_complement(angle) == pytest.approx(expected)


# The cases of the angles package's own tests (test_shortestDistanceWithLargeLimits).
def test_large_limits_delta_is_valid():
    d, ok = shortest_angular_distance_with_large_limits(0, 10.5 * PI, -2 * PI, 2 * PI)
    assert ok
    assert d == pytest.approx(0.5 * PI)


def test_large_limits_only_the_complement_is_valid():
    d, ok = shortest_angular_distance_with_large_limits(0, 10.5 * PI, -2 * PI, 0.1 * PI)
    assert ok
    assert d == pytest.approx(-1.5 * PI)


def test_large_limits_neither_way_is_valid():
    d, ok = shortest_angular_distance_with_large_limits(2 * PI, PI, 2 * PI - 0.1, 2 * PI + 0.1)
    assert not ok


def test_large_limits_start_outside_the_limits():
    d, ok = shortest_angular_distance_with_large_limits(10.5 * PI, 0, -2 * PI, 2 * PI)
    assert not ok


def test_large_limits_inverted_limits_are_refused():
    d, ok = shortest_angular_distance_with_large_limits(0, 0.1, 2 * PI, -2 * PI)
    assert not ok
    assert d == pytest.approx(0.1)


def test_limits_force_the_long_way_round():
    """Limits [-3, 3] exclude the short way across +-pi: go the long way."""
    d, ok = shortest_angular_distance_with_large_limits(2.9, -2.9, -3.0, 3.0)
    assert ok
    assert d == pytest.approx(-5.8)
    # without limits in the way the short way wins
    assert shortest_angular_distance(2.9, -2.9) == pytest.approx(2 * PI - 5.8)


def test_limits_wider_than_two_pi_allow_both_ways_and_take_the_short_one():
    # from 3.5 to 3.5 - 2pi + 0.2: limits [-7, 7] allow both; the short way is +0.2
    d, ok = shortest_angular_distance_with_large_limits(3.5, 3.7 - 2 * PI, -7.0, 7.0)
    assert ok
    assert d == pytest.approx(0.2)


def test_limits_wider_than_two_pi_when_the_short_way_leaves_them():
    # at 6.5 with upper limit 6.6: +0.2 would leave, so turn 2pi - 0.2 the other way
    d, ok = shortest_angular_distance_with_large_limits(6.5, 6.7, -7.0, 6.6)
    assert ok
    assert d == pytest.approx(0.2 - 2 * PI)


def test_from_just_outside_a_limit_the_distance_leads_back_in():
    """arm1's joint2 rests at 0 below its lower limit 0.01: the error must push it up."""
    d, ok = shortest_angular_distance_with_large_limits(0.0, 0.01, 0.01, 1.57)
    assert not ok  # the start is outside
    assert d == pytest.approx(0.01)
    d, ok = shortest_angular_distance_with_large_limits(1.6, 1.57, -1.57, 1.57)
    assert not ok
    assert d == pytest.approx(-0.03)


@pytest.mark.parametrize('frm, to', [(0.0, 1.0), (-1.5, 1.5), (1.0, -1.2), (0.3, 0.3)])
def test_inside_small_limits_the_distance_is_the_plain_difference(frm, to):
    d, ok = shortest_angular_distance_with_large_limits(frm, to, -1.57, 1.57)
    assert ok
    assert d == pytest.approx(to - frm)
