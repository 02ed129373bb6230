"""The build-time stand-ins (tools/compat_stand_ins.py) with real catkin_make, in a throw-away
workspace overlaying arm1's, on two packages of our own making: one that only names Gazebo,
gazebo_ros_pkgs and ros_control (and the ROS build dependencies make setup installs) and
builds a roscpp node (it must build unchanged), one
whose sources include Gazebo's and ros_control's headers (it must stop with our one message
naming it, and the rest must build once it is blacklisted, as that message says).
"""

import os
import subprocess

import pytest

from _arm1sim.tryout import workspace

NAMED = (
    'roscpp std_msgs gazebo_dev gazebo_ros gazebo_plugins gazebo_ros_control controller_manager '
    'hardware_interface controller_interface transmission_interface joint_limits_interface '
    'realtime_tools control_toolbox forward_command_controller effort_controllers '
    'position_controllers velocity_controllers joint_state_controller joint_trajectory_controller '
    'gripper_action_controller diff_drive_controller '
    # Debian's, from make setup's ROBOT_BUILD_DEPENDS
    'robot_state_publisher rviz tf2_ros tf urdf kdl_parser actionlib'
).split()

PACKAGE_XML = '''<?xml version="1.0"?>
<package format="2">
  <name>{name}</name>
  <version>0.0.1</version>
  <description>arm1 test package</description>
  <maintainer email="t@example.invalid">t</maintainer>
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
{depends}
</package>
'''

# As robot packages write it: Gazebo 11's variables, catkin components, a roscpp node.
NAMES_ONLY_CMAKE = '''cmake_minimum_required(VERSION 3.12)
project(names_only)
find_package(catkin REQUIRED COMPONENTS {components})
find_package(gazebo REQUIRED)
foreach(v GAZEBO_INCLUDE_DIRS GAZEBO_LIBRARY_DIRS GAZEBO_CXX_FLAGS GAZEBO_VERSION)
  if(NOT DEFINED ${{v}} OR "${{${{v}}}}" STREQUAL "")
    message(FATAL_ERROR "${{v}} not set by find_package(gazebo)")
  endif()
endforeach()
if(NOT DEFINED GAZEBO_LIBRARIES)
  message(FATAL_ERROR "GAZEBO_LIBRARIES not defined")
endif()
message(STATUS "names_only: Gazebo ${{GAZEBO_VERSION}}")
set(CMAKE_CXX_FLAGS "${{CMAKE_CXX_FLAGS}} ${{GAZEBO_CXX_FLAGS}}")
catkin_package(CATKIN_DEPENDS {components})
include_directories(${{catkin_INCLUDE_DIRS}} ${{GAZEBO_INCLUDE_DIRS}})
link_directories(${{GAZEBO_LIBRARY_DIRS}})
add_executable(gripper_sub_publisher src/node.cpp)
target_link_libraries(gripper_sub_publisher ${{catkin_LIBRARIES}} ${{GAZEBO_LIBRARIES}})
'''

NODE_CPP = '''#include <ros/ros.h>
#include <std_msgs/Float64.h>
#include <cstdio>
#include <cstring>
int main(int argc, char **argv) {
  if (argc > 1 && std::strcmp(argv[1], "--check") == 0) {
    std::puts("names_only node runs");
    return 0;
  }
  ros::init(argc, argv, "gripper_sub_publisher");
  ros::NodeHandle nh;
  ros::Publisher pub = nh.advertise<std_msgs::Float64>("gripper_sub_position", 10);
  ros::spin();
}
'''

USES_API_CMAKE = '''cmake_minimum_required(VERSION 3.12)
project(uses_api)
find_package(catkin REQUIRED COMPONENTS roscpp gazebo_ros hardware_interface)
find_package(gazebo REQUIRED)
catkin_package()
include_directories(${catkin_INCLUDE_DIRS} ${GAZEBO_INCLUDE_DIRS})
add_library(my_world_plugin src/plugin.cpp)
add_library(my_robot_hw src/hw.cpp)
'''
PLUGIN_CPP = '''#include <gazebo/gazebo.hh>
#include <gazebo/physics/physics.hh>
namespace gazebo {
class P : public WorldPlugin { void Load(physics::WorldPtr, sdf::ElementPtr) {} };
}
'''
HW_CPP = '''#include <hardware_interface/robot_hw.h>
class Hw : public hardware_interface::RobotHW {};
'''


def _write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, 'w') as f:
        f.write(text)


def _package(root, name, depends, files):
    deps = '\n'.join('  <depend>%s</depend>' % d for d in depends)
    _write(os.path.join(root, 'package.xml'), PACKAGE_XML.format(name=name, depends=deps))
    for rel, text in files.items():
        _write(os.path.join(root, rel), text)
    return workspace.Package(name, root, depends)


@pytest.fixture(scope='module')
def packages(tmp_path_factory):
    src = tmp_path_factory.mktemp('checkout')
    names_only = _package(
        str(src / 'names_only'),
        'names_only',
        NAMED,
        {
            'CMakeLists.txt': NAMES_ONLY_CMAKE.format(components=' '.join(NAMED)),
            'src/node.cpp': NODE_CPP,
        },
    )
    uses_api = _package(
        str(src / 'uses_api'),
        'uses_api',
        ['roscpp', 'gazebo_ros', 'hardware_interface'],
        {'CMakeLists.txt': USES_API_CMAKE, 'src/plugin.cpp': PLUGIN_CPP, 'src/hw.cpp': HW_CPP},
    )
    return names_only, uses_api


@pytest.fixture(scope='module')
def builds(packages, tmp_path_factory):
    ws = str(tmp_path_factory.mktemp('ws'))
    first = workspace.build(ws, list(packages), timeout=600)
    with open(first.log) as f:
        first_log = f.read()
    second = workspace.build(ws, list(packages), timeout=600, blacklist=['uses_api'])
    return ws, first, first_log, second


def test_a_package_using_the_cxx_api_stops_with_one_message_naming_it(builds):
    ws, first, log, second = builds
    assert not first.ok
    # one message per translation unit (two here; gcc quotes the line under each), naming
    # the package and the remedy
    errors = [line for line in log.splitlines() if 'error: #error' in line]
    assert len(errors) == 2, log[-3000:]
    for line in errors:
        assert 'uses_api compiles against Gazebo' in line
        assert 'catkin_make -DCATKIN_BLACKLIST_PACKAGES=uses_api' in line
    assert 'gazebo/gazebo.hh' in log and 'hardware_interface/robot_hw.h' in log
    # not a bare missing header of Gazebo's or ros_control's
    assert 'gazebo/gazebo.hh: No such file' not in log
    assert 'robot_hw.h: No such file' not in log
    assert 'Could NOT find' not in log and 'Could not find a package configuration' not in log


def test_a_package_that_only_names_them_builds_unchanged_and_runs(builds):
    ws, first, log, second = builds
    assert second.ok, second.log_tail
    with open(second.log) as f:
        assert 'names_only: Gazebo 11.10.2' in f.read()
    exe = os.path.join(ws, 'devel', 'lib', 'names_only', 'gripper_sub_publisher')
    out = subprocess.run([exe, '--check'], stdout=subprocess.PIPE, check=True, timeout=30)
    assert out.stdout.decode() == 'names_only node runs\n'
