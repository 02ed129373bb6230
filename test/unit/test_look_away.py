"""arm_nodes.py, look_away's part: the uniform-image test and when to look away."""

import numpy as np
import pytest

from _arm1sim.goal.image import is_uniform
from _arm1sim.goal.look_away import LookAwayPolicy


def image(pixels, step=None):
    """(data, width, height, step) of an H x W x C uint8 array, rows padded to ``step``."""
    h, w, c = pixels.shape
    step = step or w * c
    rows = np.zeros((h, step), np.uint8)
    rows[:, : w * c] = pixels.reshape(h, w * c)
    return rows.tobytes(), w, h, step


def test_a_blank_view_is_uniform():
    assert is_uniform(*image(np.full((48, 64, 3), 255, np.uint8)))  # pybullet's empty sky
    assert is_uniform(*image(np.full((4, 4, 1), 7, np.uint8)))  # mono8


def test_one_different_pixel_is_structure():
    img = np.full((48, 64, 3), 191, np.uint8)
    img[47, 63] = (191, 191, 190)
    assert not is_uniform(*image(img))


def test_a_blank_coloured_view_is_uniform_too():
    # simple_arm compares every byte with the first one; the pixels here
    assert is_uniform(*image(np.tile(np.array([90, 160, 230], np.uint8), (48, 64, 1))))


def test_row_padding_is_not_part_of_the_picture():
    data, w, h, step = image(np.full((4, 5, 3), 9, np.uint8), step=16)
    padded = bytearray(data)
    padded[15] = 1  # the last padding byte of row 0
    assert is_uniform(bytes(padded), w, h, step)


@pytest.mark.parametrize('data,w,h,step', [(b'', 0, 0, 0), (b'\x00' * 10, 4, 4, 12)])
def test_empty_or_short_images_are_not_evidence_of_a_blank_view(data, w, h, step):
    assert not is_uniform(data, w, h, step)


def policy_after(*joint_states, threshold=0.0005):
    policy = LookAwayPolicy(threshold)
    for positions in joint_states:
        policy.joint_positions(positions)
    return policy


def test_uniform_view_and_still_arm_looks_away():
    policy = policy_after([0, 1.57, 0, 0], [0.0001, 1.5702, 0, -0.0004])
    assert policy.still
    assert policy.decide(True)


def test_structure_in_view_does_not_look_away():
    assert not policy_after([0, 1.57, 0, 0], [0, 1.57, 0, 0]).decide(False)


def test_a_moving_arm_does_not_look_away():
    policy = policy_after([0, 1.0, 0, 0], [0, 1.0006, 0, 0])
    assert not policy.still and not policy.decide(True)
    assert not policy_after([0, 1.0, 0, 0]).decide(True)  # one state: no motion known yet


def test_one_move_at_a_time():
    policy = policy_after([0, 1.57, 0, 0], [0, 1.57, 0, 0])
    assert policy.decide(True)
    assert not policy.decide(True)  # still busy with the first
    policy.done()
    assert policy.decide(True)
