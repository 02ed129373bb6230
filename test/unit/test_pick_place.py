"""_arm1sim.goal.pick_place: the objects pick_arm picks, where its lift puts the finger tips, and
the hold verdict the pick rostests and the demo print."""

import pytest

from _arm1sim.description.urdf_model import parse_urdf
from _arm1sim.goal.pick_place import (
    OBJECTS,
    TABLE_TOP,
    TIP_CLEARANCE,
    TIPS_AT_ZERO_LIFT,
    judge_hold,
    pick_lift,
)


@pytest.mark.parametrize('obj', OBJECTS, ids=[o.name for o in OBJECTS])
def test_each_object_is_a_one_link_urdf_with_its_friction(obj):
    xml = obj.urdf()
    model = parse_urdf(xml)
    assert list(model.links) == ['link']
    assert '<mu1>1</mu1>' in xml and '<mu2>1</mu2>' in xml
    assert 0 < obj.height <= 0.06  # within the pads' 6 cm


def test_the_pick_height_puts_the_tips_just_above_the_table():
    lift = pick_lift(OBJECTS[0])
    assert TIPS_AT_ZERO_LIFT + lift == pytest.approx(TABLE_TOP + TIP_CLEARANCE)


def test_an_object_that_kept_up_is_held():
    v = judge_hold(0.5, 0.2, 0.6, 0.2998, [0.1, 0.1005, 0.0995])
    assert v.rise_ratio == pytest.approx(0.998)
    assert v.slip == pytest.approx(0.0005)
    assert v.held
    assert 'held' in str(v) and 'NOT' not in str(v)


def test_an_object_left_behind_or_sliding_is_not_held():
    assert not judge_hold(0.5, 0.2, 0.6, 0.29, [0.1, 0.1]).held  # 90 % of the rise
    assert not judge_hold(0.5, 0.2, 0.6, 0.3, [0.1, 0.1, 0.0975]).held  # 2.5 mm of slip
    assert 'NOT held' in str(judge_hold(0.5, 0.2, 0.5, 0.2, [0.0]))  # the gripper never rose


def test_a_hold_without_samples_is_refused():
    with pytest.raises(ValueError, match='no samples'):
        judge_hold(0.5, 0.2, 0.6, 0.3, [])
