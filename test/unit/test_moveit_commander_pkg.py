"""The moveit_commander stand-in: the generated catkin package re-exports
_arm1sim.ros.commander under upstream's module names, and conversions behave as upstream's."""

import importlib
import os
import sys

import pytest
from geometry_msgs.msg import Pose

sys.path.insert(
    0,
    os.path.join(
        os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), 'tools'
    ),
)
import compat_moveit_commander  # noqa: E402
from make_compat_packages import write  # noqa: E402

from _arm1sim.ros.commander import conversions  # noqa: E402
from _arm1sim.ros.commander.exception import MoveItCommanderException  # noqa: E402


@pytest.fixture
def generated(tmp_path, monkeypatch):
    compat_moveit_commander.make_moveit_commander(str(tmp_path), write)
    monkeypatch.syspath_prepend(str(tmp_path / 'moveit_commander' / 'src'))
    for name in [
        m for m in sys.modules if m == 'moveit_commander' or m.startswith('moveit_commander.')
    ]:
        monkeypatch.delitem(sys.modules, name)
    return tmp_path / 'moveit_commander'


def test_package_layout_is_a_python_catkin_package(generated):
    assert 'catkin_python_setup()' in (generated / 'CMakeLists.txt').read_text()
    assert "packages=['moveit_commander']" in (generated / 'setup.py').read_text()
    assert '<name>moveit_commander</name>' in (generated / 'package.xml').read_text()


def test_every_upstream_import_path_reaches_the_same_classes(generated):
    mc = importlib.import_module('moveit_commander')
    from _arm1sim.ros import commander

    for name in (
        'MoveGroupCommander',
        'PlanningSceneInterface',
        'RobotCommander',
        'MoveItCommanderException',
        'roscpp_initialize',
        'roscpp_shutdown',
    ):
        assert getattr(mc, name) is getattr(commander, name)
    conv = importlib.import_module('moveit_commander.conversions')
    assert conv.pose_to_list is conversions.pose_to_list
    assert (
        importlib.import_module('moveit_commander.move_group').MoveGroupCommander
        is commander.MoveGroupCommander
    )
    assert (
        importlib.import_module('moveit_commander.exception').MoveItCommanderException
        is MoveItCommanderException
    )


def test_pose_lists_round_trip_and_rpy_lists_become_quaternions():
    p = conversions.list_to_pose([1, 2, 3, 0, 0, 0.6, 0.8])
    assert conversions.pose_to_list(p) == [1, 2, 3, 0, 0, 0.6, 0.8]
    q = conversions.pose_to_list(conversions.list_to_pose([0, 0, 0, 0, 0, 3.141592653589793 / 2]))
    assert q[3:] == pytest.approx([0, 0, 0.7071068, 0.7071068])
    with pytest.raises(MoveItCommanderException, match='6 or 7 elements'):
        conversions.list_to_pose([1, 2, 3])
    t = conversions.list_to_transform([1, 2, 3, 0, 0, 0, 1])
    assert conversions.transform_to_list(t) == [1, 2, 3, 0, 0, 0, 1]


def test_messages_serialize_both_ways():
    p = conversions.list_to_pose([0.1, 0.2, 0.3, 0, 0, 0, 1])
    data = conversions.msg_to_string(p)
    assert isinstance(data, bytes) and len(data) == 7 * 8
    back = Pose()
    conversions.msg_from_string(back, data)
    assert back == p
