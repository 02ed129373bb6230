"""try_robot's ROS-free parts: which packages a launch needs, the headless args, warnings read
from ROS logs, the target of each joint, and the verdict."""

import os

import pytest

from _arm1sim.tryout import logs, report, workspace
from _arm1sim.tryout.cli import launch_args, parse_args
from _arm1sim.tryout.probe import STEP, _target, answers, remapped

PACKAGE = '''<?xml version="1.0"?>
<package format="2"><name>{name}</name><version>1.0.0</version>
<description>x</description><maintainer email="a@b.c">a</maintainer><license>BSD</license>
<buildtool_depend>catkin</buildtool_depend>{deps}</package>
'''


def package(root, name, deps=(), files=None):
    d = root / name
    d.mkdir(parents=True)
    tags = ''.join('<exec_depend>%s</exec_depend>' % x for x in deps)
    (d / 'package.xml').write_text(PACKAGE.format(name=name, deps=tags))
    for rel, text in (files or {}).items():
        (d / rel).parent.mkdir(parents=True, exist_ok=True)
        (d / rel).write_text(text)
    return d


def test_needed_packages_follow_depends_and_find_but_stay_in_the_checkout(tmp_path):
    package(
        tmp_path,
        'robot_gazebo',
        ['robot_description', 'gazebo_ros'],
        {'launch/a.launch': '<launch><include file="$(find robot_control)/x.launch"/></launch>'},
    )
    package(
        tmp_path,
        'robot_description',
        files={'urdf/r.xacro': '<mesh filename="package://robot_meshes/base.stl"/>'},
    )
    package(tmp_path, 'robot_control')
    package(tmp_path, 'robot_meshes')  # named by a mesh's package:// only
    package(tmp_path, 'robot_moveit_config', ['moveit_ros'])  # not needed: not built
    package(tmp_path / 'ignored', 'skipped')
    (tmp_path / 'ignored' / 'CATKIN_IGNORE').write_text('')
    found = workspace.find_packages(str(tmp_path))
    assert sorted(found) == [
        'robot_control',
        'robot_description',
        'robot_gazebo',
        'robot_meshes',
        'robot_moveit_config',
    ]
    needed = workspace.needed_packages(found, 'robot_gazebo')
    assert [p.name for p in needed] == [
        'robot_control',
        'robot_description',
        'robot_gazebo',
        'robot_meshes',
    ]
    ws = tmp_path / 'ws'
    workspace.make_workspace(str(ws), needed)
    assert os.readlink(ws / 'src' / 'robot_gazebo') == str(tmp_path / 'robot_gazebo')


def test_unignore_opens_one_catkin_ignored_dir_and_not_those_below_it(tmp_path):
    # Interbotix's interbotix_ros_xsarms ships a CATKIN_IGNORE its install script removes;
    # interbotix_xsarm_perception's own stays.
    arms = tmp_path / 'xsarms'
    package(arms, 'xsarm_gazebo', ['xsarm_descriptions'])
    package(arms, 'xsarm_descriptions')
    package(arms, 'xsarm_perception')
    (arms / 'CATKIN_IGNORE').write_text('')
    (arms / 'xsarm_perception' / 'CATKIN_IGNORE').write_text('')
    assert workspace.find_packages(str(tmp_path)) == {}
    found = workspace.find_packages(str(tmp_path), [str(arms)])
    assert sorted(found) == ['xsarm_descriptions', 'xsarm_gazebo']
    args = parse_args(['co', 'xsarm_gazebo', 'x.launch', '--unignore', str(arms)])
    assert args.unignore == [str(arms)]


def test_a_package_twice_in_a_checkout_is_refused_by_name(tmp_path):
    package(tmp_path / 'a', 'twin')
    package(tmp_path / 'b', 'twin')
    with pytest.raises(ValueError, match='twin is twice'):
        workspace.find_packages(str(tmp_path))


def test_headless_values_only_for_args_the_launch_itself_declares(tmp_path):
    launch = tmp_path / 'x.launch'
    launch.write_text(
        '<launch><arg name="gui" default="true"/><arg name="rviz" default="true"/>'
        '<arg name="headless" value="false"/>'
        '<include file="y"><arg name="gazebo_gui" value="true"/></include></launch>'
    )
    assert launch_args(str(launch), []) == ['gui:=false', 'rviz:=false']
    assert launch_args(str(launch), ['gui:=true']) == ['gui:=true', 'rviz:=false']


def test_warnings_from_rosout_and_from_a_nodes_own_log_once_each(tmp_path):
    run = tmp_path / 'run1'
    run.mkdir()
    (run / 'rosout.log').write_text(
        '1.5 WARN /spawner [s.py:9(f)] [topics: /rosout] manager slow\n'
        '1.6 WARN /spawner [s.py:9(f)] [topics: /rosout] manager slow\n'
        '1.7 INFO /gazebo [w.py:1(f)] [topics: /rosout] fine\n'
    )
    (run / 'gazebo-2.log').write_text(
        "[rosout][WARNING] 2026-11-23 16:09:27,715: model 'm': plugin 'p' (libp.so) "
        'of the model is not implemented by the stand-in\n'
        '[rosout][INFO] 2026-11-23 16:09:27,716: world ready\n'
    )
    problems = logs.rosout_problems(str(tmp_path))
    assert problems == [
        {'level': 'WARN', 'node': '/spawner', 'message': 'manager slow', 'count': 2},
        {
            'level': 'WARN',
            'node': '/gazebo',
            'message': "model 'm': plugin 'p' (libp.so) of the model is not implemented by "
            'the stand-in',
            'count': 1,
        },
    ]
    assert logs.unimplemented(problems) == [problems[1]['message']]


def test_each_joint_steps_towards_zero_or_into_its_range():
    assert _target(0.3, None) == pytest.approx(0.3 - STEP)
    assert _target(-2.0, {'lower': -3.0, 'upper': 3.0}) == pytest.approx(-2.0 + STEP)
    assert _target(0.0, {'lower': -0.1, 'upper': 2.0}) == pytest.approx(STEP)
    assert _target(0.0, {'lower': -2.0, 'upper': 0.05}) == pytest.approx(-STEP)
    assert _target(0.05, {'lower': 0.0, 'upper': 0.1}) == 0.1  # clamped to the range


def test_verdict_names_each_failure():
    rep = {
        'build': {'ok': False},
        'bringup': {'up': True, 'alive': True},
        'controller_managers': {'/': [{'name': 'c', 'type': 't', 'state': 'running'}]},
        'motion': [
            {
                'controller': '/arm',
                'ok': False,
                'finished': True,
                'error_code': -4,
                'error_string': 'j path error 0.3',
                'joints': ['j'],
                'seconds': 0.0,
                'max_abs_error': 0.3,
            },
        ],
    }
    v = report.verdict(rep)
    assert not v['ok']
    assert v['problems'][0].startswith('the workspace did not build')
    assert 'PATH_TOLERANCE_VIOLATED (j path error 0.3)' in v['problems'][1]
    # the rest built without the failed package: the bringup ran from that workspace
    rep['build'] = {
        'ok': False,
        'rest_ok': True,
        'per_package': {'realsense2_camera': {'built': False}, 'stretch_gazebo': {'built': True}},
    }
    assert report.verdict(rep)['problems'][0] == (
        'the workspace did not build with realsense2_camera (ran from it built without)'
    )
    assert report.verdict({'build': {'ok': True}, 'bringup': {'up': False, 'error': 'x'}}) == {
        'ok': False,
        'problems': ['the bringup did not come up: x'],
    }


def test_a_remapped_action_is_the_one_offered_name_no_controller_has_by_default():
    # ROS-Industrial's abb_irb120_gazebo: <remap from="/arm_controller/follow_joint_trajectory"
    # to="/joint_trajectory_action"/> before the world; the gripper's stays where it was.
    offered = ['/gripper_controller/follow_joint_trajectory', '/joint_trajectory_action']
    defaults = [
        '/arm_controller/follow_joint_trajectory',
        '/gripper_controller/follow_joint_trajectory',
    ]
    assert remapped(defaults[0], offered, defaults) == '/joint_trajectory_action'
    assert remapped(defaults[1], offered, defaults) == defaults[1]
    # two remapped names: which is whose cannot be told; none: nothing to find
    assert remapped(defaults[0], offered + ['/other_action'], defaults) is None
    assert remapped(defaults[0], offered[:1], defaults) is None


def test_a_node_too_busy_to_answer_is_alive_and_a_closed_port_is_not():
    # a world spawning a big model under load may not answer getPid for seconds: not dead
    import socket

    busy = socket.socket()
    busy.bind(('127.0.0.1', 0))
    busy.listen(1)  # accepts, never answers
    closed = socket.socket()
    closed.bind(('127.0.0.1', 0))
    port = closed.getsockname()[1]
    closed.close()  # nothing listens there
    try:
        assert answers('http://127.0.0.1:%d/' % busy.getsockname()[1], 0.3) == 'busy'
        assert answers('http://127.0.0.1:%d/' % port, 0.3) == 'no'
    finally:
        busy.close()
