"""description/semantic_model.py: planning groups resolved against the URDF as MoveIt does
(test robot six_arm and its Setup-Assistant-style six_arm_moveit_config)."""

import os

import pytest
import xacro

from _arm1sim.description import semantic_model as srdf

ROBOTS = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'robots')
SIX_ARM = os.path.join(ROBOTS, 'six_arm', 'urdf', 'six_arm.urdf.xacro')
SIX_ARM_SRDF = os.path.join(ROBOTS, 'six_arm_moveit_config', 'config', 'six_arm.srdf')
ARM = ['joint%d' % i for i in range(1, 7)]


@pytest.fixture(scope='module')
def texts():
    with open(SIX_ARM_SRDF) as f:
        return xacro.process_file(SIX_ARM).toprettyxml(), f.read()


@pytest.fixture(scope='module')
def model(texts):
    return srdf.load(*texts)


def test_chain_group_is_its_joints_from_base_to_tip(model):
    arm = model.groups['arm']
    # the chain adds joints up to, not including, the base link's parent joint (world_joint)
    assert arm.joints == ARM + ['hand_joint', 'tcp_joint']
    assert arm.variables == ARM
    assert arm.active_joints == ARM
    assert arm.links == ['link1', 'link2', 'link3', 'link4', 'link5', 'link6', 'hand', 'tcp']
    assert arm.is_chain
    assert arm.end_effector_link == 'tcp'


def test_link_group_takes_parent_joints_and_mimic_is_a_variable_not_active(model):
    hand = model.groups['hand']
    assert hand.joints == ['hand_joint', 'left_finger_joint', 'right_finger_joint']
    assert hand.variables == ['left_finger_joint', 'right_finger_joint']
    assert hand.active_joints == ['left_finger_joint']
    assert hand.links == ['hand', 'left_finger', 'right_finger']
    assert not hand.is_chain  # two fingers side by side: no end-effector link by default
    assert hand.end_effector_link == ''


def test_states_end_effectors_frame_and_limits(model):
    assert model.model_frame == 'world'  # no virtual joint: the URDF's root link
    assert model.group_states['arm']['ready']['joint3'] == pytest.approx(1.2)
    assert sorted(model.group_states['hand']) == ['close', 'open']
    assert [(e.name, e.parent_link, e.group) for e in model.end_effectors] == [
        ('hand', 'tcp', 'hand')
    ]
    assert model.limits['joint2'] == (-1.7, 1.7)
    assert model.joint_order.index('joint1') < model.joint_order.index('left_finger_joint')


def test_virtual_joint_names_the_model_frame(texts):
    urdf, semantic = texts
    semantic = semantic.replace(
        '<group name="arm">',
        '<virtual_joint name="vj" type="fixed" parent_frame="odom" child_link="world"/>'
        '<group name="arm">',
    )
    assert srdf.load(urdf, semantic).model_frame == 'odom'


def test_subgroups_resolve_in_any_order(texts):
    urdf, semantic = texts
    semantic = semantic.replace(
        '<group name="arm">',
        '<group name="both"><group name="arm"/><group name="hand"/></group><group name="arm">',
    )
    both = srdf.load(urdf, semantic).groups['both']
    assert both.variables == ARM + ['left_finger_joint', 'right_finger_joint']


@pytest.mark.parametrize(
    'change, culprit',
    [
        (('tip_link="tcp"', 'tip_link="nowhere"'), "chain from 'base_link' to 'nowhere'"),
        (('<link name="left_finger"/>', '<link name="thumb"/>'), "link 'thumb'"),
        (
            (
                '<group name="arm">',
                '<group name="x"><group name="ghost"/></group><group name="arm">',
            ),
            "subgroup 'ghost'",
        ),
        (('value="1.2"', 'value="high"'), "joint 'joint3' has no numeric value"),
        (
            ('<robot name="six_arm">', '<!DOCTYPE r [<!ENTITY a "b">]><robot name="six_arm">'),
            'document type declaration',
        ),
    ],
)
def test_bad_semantic_descriptions_name_the_culprit(texts, change, culprit):
    urdf, semantic = texts
    with pytest.raises(srdf.SrdfError, match=culprit):
        srdf.load(urdf, semantic.replace(*change, 1))


def test_default_disabled_links_collide_only_where_enabled():
    """<disable_default_collisions> and <enable_collisions>, as panda_moveit_config writes
    them for franka_description's *_sc links: MoveIt's ACM, a pair's entry before defaults."""
    from _arm1sim.description.srdf import parse_srdf

    s = parse_srdf(
        '<robot name="r"><disable_default_collisions link="a_sc"/>'
        '<disable_default_collisions link="b_sc"/>'
        '<enable_collisions link1="b_sc" link2="a_sc"/>'
        '<disable_collisions link1="a" link2="b"/></robot>'
    )
    assert s.collision_disabled('a_sc', 'box')  # not checked against objects either
    assert s.collision_disabled('c', 'a_sc')
    assert not s.collision_disabled('a_sc', 'b_sc')
    assert s.collision_disabled('b', 'a')
    assert not s.collision_disabled('a', 'c')
