"""Gazebo's grasp plugin (libgazebo_grasp_fix.so): upstream's attach and detach rules on
synthetic contacts (physics.grasp.GraspLogic), its parameters as GazeboGraspFix::Load reads
them, and in real pybullet a box too heavy for the fingers' friction held by the plugin."""

import logging
import math

import pytest
from conftest import WORLD_FILE, FakeRos

from _arm1sim.control.controller_manager import ControllerManager
from _arm1sim.control.switching import switch_while_updating
from _arm1sim.description.gazebo_plugins import model_plugins
from _arm1sim.description.sdf_world import read_world
from _arm1sim.description.urdf_model import parse_urdf
from _arm1sim.physics.grasp import GraspLogic, GraspParams, opposing
from _arm1sim.sim.plugins.grasp import grasp_params
from _arm1sim.sim.simulation import Simulation

LEFT, RIGHT = (0.0, -2.0, 0.0), (0.0, 2.0, 0.0)  # forces on the box from two fingers


def logic(**kw):
    return GraspLogic(GraspParams(**kw), ['arm'])


def squeeze(g, obj='box', left=LEFT, right=RIGHT):
    """One update's worth of contacts: each finger touching the box 1 cm from its centre."""
    g.add_contact(obj, 'l', 'arm', left, (0.0, 0.01, 0.0), (0.0, 0.02, 0.0))
    g.add_contact(obj, 'r', 'arm', right, (0.0, -0.01, 0.0), (0.0, -0.02, 0.0))


def still(obj, link, contact):
    """Nothing moved: each first contact point still 1 cm from the box's centre."""
    return 0.01


def test_opposing_forces_are_more_than_the_tolerance_apart_and_comparable():
    tol = math.radians(120)
    assert opposing([LEFT, RIGHT], tol)
    assert not opposing([LEFT, (2.0, 0.0, 0.0)], tol)  # 90 degrees
    assert not opposing([LEFT, (0.0, 0.5, 0.0)], tol)  # the weaker under 0.3 of the other
    assert opposing([LEFT, (0.0, 0.7, 0.0)], tol)
    assert not opposing([LEFT, RIGHT], math.radians(80))  # upstream refuses under 90


def test_an_object_gripped_for_more_than_the_threshold_updates_is_attached():
    g = logic(max_grip_count=10, grip_count_threshold=5)
    for _ in range(5):
        squeeze(g)
        assert g.update(still) == []
    squeeze(g)
    assert g.update(still) == [('arm', 'box', True)]
    assert g.attached == {'arm': 'box'}
    squeeze(g)
    assert g.update(still) == []  # attached once


def test_contacts_that_do_not_oppose_never_attach():
    g = logic(grip_count_threshold=1)
    for _ in range(20):
        squeeze(g, right=(2.0, 0.0, 0.0))
        g.add_contact('cup', 'l', 'arm', LEFT, (0, 0, 0), (0, 0, 0))  # one finger alone
        assert g.update(still) == []


def test_a_grip_broken_in_between_counts_down():
    g = logic(max_grip_count=4, grip_count_threshold=2)
    squeeze(g)
    g.update(still)
    squeeze(g)
    g.update(still)  # count 2
    g.update(still)  # no contact: 1
    squeeze(g)
    assert g.update(still) == []  # 2: not yet over the threshold
    squeeze(g)
    assert g.update(still) == [('arm', 'box', True)]


def test_an_attached_object_is_let_go_when_the_fingers_open_by_the_release_tolerance():
    g = logic(max_grip_count=4, grip_count_threshold=2, release_tolerance=0.005)
    for _ in range(4):
        squeeze(g)
        g.update(still)  # attached at the third, count 4
    assert g.attached == {'arm': 'box'}
    assert g.update(still) == []  # count 3: above the threshold
    assert g.update(still) == []  # count 2: fingers still where they were: held
    opened = lambda obj, link, contact: 0.01 + (0.006 if link == 'l' else 0.0)  # noqa: E731
    assert g.update(opened) == [('arm', 'box', False)]
    assert g.attached == {} and g.grip_counts['box'] == 0
    slightly = lambda obj, link, contact: 0.014  # noqa: E731
    for _ in range(4):
        squeeze(g)
        g.update(still)
    g.update(slightly)
    g.update(slightly)
    assert g.update(slightly) == []  # 4 mm: within the tolerance, held


def test_an_arm_holding_one_object_does_not_take_a_second():
    g = logic(max_grip_count=2, grip_count_threshold=0)
    squeeze(g, 'box')
    assert g.update(still) == [('arm', 'box', True)]
    squeeze(g, 'box')
    squeeze(g, 'cup')
    assert g.update(still) == []
    assert g.attached == {'arm': 'box'}


GRASP = """<gazebo><plugin name="gazebo_grasp_fix" filename="libgazebo_grasp_fix.so">
  <arm><arm_name>hand</arm_name><palm_link>lift_link</palm_link>
    <gripper_link>left_link</gripper_link><gripper_link>right_link</gripper_link></arm>
  %s
</plugin></gazebo>"""


def plugin_spec(params):
    from helpers import GRIPPER

    model = parse_urdf(GRIPPER.replace('</robot>', GRASP % params + '</robot>'))
    (spec,) = [s for s in model_plugins(model) if s.filename == 'libgazebo_grasp_fix.so']
    return spec


def test_parameters_and_upstreams_defaults():
    d = grasp_params(plugin_spec(''))
    assert (
        math.degrees(d.forces_angle_tolerance),
        d.update_rate,
        d.max_grip_count,
        d.grip_count_threshold,
        d.release_tolerance,
        d.disable_collisions_on_attach,
    ) == pytest.approx((120.0, 5.0, 10, 5, 0.005, False))
    given = grasp_params(
        plugin_spec(
            '<forces_angle_tolerance>100</forces_angle_tolerance><update_rate>4</update_rate>'
            '<grip_count_threshold>3</grip_count_threshold><max_grip_count>8</max_grip_count>'
            '<release_tolerance>0.01</release_tolerance>'
            '<disable_collisions_on_attach>1</disable_collisions_on_attach>'
            '<contact_topic>__default_topic__</contact_topic>'
        )
    )
    assert math.degrees(given.forces_angle_tolerance) == pytest.approx(100.0)
    assert (given.update_rate, given.grip_count_threshold, given.max_grip_count) == (4.0, 3, 8)
    assert given.release_tolerance == 0.01 and given.disable_collisions_on_attach
    # the threshold defaults to half of a given max_grip_count
    assert grasp_params(plugin_spec('<max_grip_count>7</max_grip_count>')).grip_count_threshold == 3


def test_an_angle_under_90_degrees_is_named(caplog):
    with caplog.at_level(logging.WARNING, logger='_arm1sim.physics'):
        grasp_params(plugin_spec('<forces_angle_tolerance>60</forces_angle_tolerance>'))
    assert 'forces_angle_tolerance' in caplog.text and 'gazebo_grasp_fix' in caplog.text


# ------------------------------------------------------------------------ real pybullet
@pytest.fixture
def sim():
    s = Simulation(read_world(WORLD_FILE))
    yield s
    s.close()


def run(sim, seconds):
    for _ in range(int(round(seconds / sim.period))):
        sim.step()


def weak_gripper(params=''):
    """test_position_carry's gripper with fingers of 2 N: friction (4 N at most, with mu 1)
    cannot lift the 1 kg box."""
    from helpers import GRIPPER

    weak = GRIPPER.replace('effort="10"', 'effort="2"')
    return weak.replace('</robot>', GRASP % params + '</robot>')


def pick(sim, urdf):
    from helpers import BOX, CONTROLLERS, LIFT_TOP

    ros = FakeRos({'carrier': CONTROLLERS})
    model = sim.spawn_urdf(
        'carrier',
        urdf,
        controller_manager_factory=lambda hw, ns: ControllerManager(hw, ros.node_handle, ns),
    )
    heavy = BOX.replace('<mass value="0.05"/>', '<mass value="1"/>')
    box = sim.spawn_urdf('box', heavy, position=(0.5, 0, 0.0205))
    names = sorted(CONTROLLERS)
    for n in names:
        model.controller_manager.load_controller(n)
    ok, _ = switch_while_updating(model.controller_manager, names, [], sim.step, 2, poll=0.0005)
    assert ok
    events = []
    (fix,) = [s for s in model.sensors if s.kind == 'grasp plugin'] or [None]
    if fix is not None:
        fix.deliver = lambda stamp, evs: events.extend((stamp, e) for e in evs)
    run(sim, 0.3)
    ros.publish('/carrier/left_controller/command', 0.03)
    ros.publish('/carrier/right_controller/command', 0.03)
    run(sim, 2.5)  # 5 Hz: over the threshold of 5 updates within 1.2 s
    start = box.robot.link_pose('box')[0][2]
    ros.publish('/carrier/lift_controller/command', LIFT_TOP)
    run(sim, 1.0)
    risen = box.robot.link_pose('box')[0][2] - start
    return ros, model, box, events, risen


def test_without_the_plugin_weak_fingers_cannot_lift_the_heavy_box(sim):
    from helpers import GRIPPER

    weak = GRIPPER.replace('effort="10"', 'effort="2"')
    _, _, _, _, risen = pick(sim, weak)
    assert risen < 0.01


def test_the_plugin_attaches_the_gripped_box_to_the_palm_and_lets_go_when_opened(sim):
    from helpers import LIFT_TOP

    ros, model, box, events, risen = pick(sim, weak_gripper())
    assert risen == pytest.approx(LIFT_TOP, abs=2e-3)
    ((stamp, event),) = events
    assert event == ('hand', 'box::box::box_collision', True)
    # the sixth update (5 Hz, in sim time) after the fingers closed at 0.3 s
    assert 1.3 <= stamp * 1e-9 <= 1.7
    held = box.robot.link_pose('box')[0][2]
    run(sim, 1.0)
    assert box.robot.link_pose('box')[0][2] == pytest.approx(held, abs=1e-3)
    ros.publish('/carrier/left_controller/command', 0.0)
    ros.publish('/carrier/right_controller/command', 0.0)
    run(sim, 3.0)  # the count runs down from 10 to 5 at 5 Hz, then the open fingers release
    assert [e for _, e in events] == [
        ('hand', 'box::box::box_collision', True),
        ('hand', 'box::box::box_collision', False),
    ]
    assert box.robot.link_pose('box')[0][2] < 0.03  # fell back to the ground
