"""Catkin stand-ins for the build-time names of Gazebo, gazebo_ros_pkgs and ros_control.

A robot's Gazebo package names these in its CMakeLists (`find_package(gazebo REQUIRED)`,
`find_package(catkin REQUIRED COMPONENTS gazebo_ros_control effort_controllers ...)`) and
often builds nothing but roscpp nodes. Debian 12 has none of them, so without these
`catkin_make` stops at CMake. Each stand-in is a catkin package exporting what its upstream
exports at configure time (roscpp and message packages; for `gazebo`, the GAZEBO_* variables
Gazebo 11's CMake config sets), so such a package configures and builds unchanged.

Their C++ APIs are not here (arm1 simulates in Python). Each stand-in's include dir holds
the headers robot packages include most, and each of those stops the compile with one
message naming the package that includes it and how to leave it out of the build, instead
of a bare 'No such file'. Written into .ws/src by make_compat_packages.py.
"""

from __future__ import annotations

import os
from typing import Callable, Dict, List, Tuple

# dynamic_reconfigure definitions a stand-in generates, by package (control_toolbox's PID)
CFG_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'compat_cfg')

GAZEBO_VERSION = '11.10.2'  # Debian 12's and Ubuntu 20.04's Gazebo 11
GAZEBO_ROS_PKGS_VERSION = '2.9.2'
ROS_CONTROL_VERSION = '0.20.0'
ROS_CONTROLLERS_VERSION = '0.21.2'

# Upstream's controller headers follow one pattern: <package>/<controller>.h
_JOINT_CONTROLLERS = [
    'joint_position_controller.h',
    'joint_velocity_controller.h',
    'joint_effort_controller.h',
    'joint_group_position_controller.h',
    'joint_group_velocity_controller.h',
    'joint_group_effort_controller.h',
]

# package -> (version, catkin packages its config exports, headers under include/<package>/)
STAND_INS: Dict[str, Tuple[str, List[str], List[str]]] = {
    'gazebo': (
        GAZEBO_VERSION,
        [],
        [
            'gazebo.hh',
            'gazebo_client.hh',
            'gazebo_config.h',
            'common/common.hh',
            'common/Plugin.hh',
            'common/Events.hh',
            'common/Time.hh',
            'common/UpdateInfo.hh',
            'physics/physics.hh',
            'physics/World.hh',
            'physics/Model.hh',
            'physics/Link.hh',
            'physics/Joint.hh',
            'sensors/sensors.hh',
            'sensors/Sensor.hh',
            'sensors/RaySensor.hh',
            'sensors/CameraSensor.hh',
            'sensors/ContactSensor.hh',
            'rendering/rendering.hh',
            'transport/transport.hh',
            'msgs/msgs.hh',
            'plugins/RayPlugin.hh',
            'plugins/CameraPlugin.hh',
            'plugins/DepthCameraPlugin.hh',
            'gui/gui.hh',
        ],
    ),
    'gazebo_dev': (GAZEBO_ROS_PKGS_VERSION, ['gazebo'], []),
    'gazebo_ros': (
        GAZEBO_ROS_PKGS_VERSION,
        ['roscpp', 'std_srvs', 'geometry_msgs', 'gazebo_msgs', 'gazebo_dev'],
        ['gazebo_ros_api_plugin.h', 'utils.h'],
    ),
    'gazebo_plugins': (
        GAZEBO_ROS_PKGS_VERSION,
        ['roscpp', 'std_msgs', 'sensor_msgs', 'geometry_msgs', 'nav_msgs', 'gazebo_msgs'],
        [
            'gazebo_ros_utils.h',
            'gazebo_ros_camera.h',
            'gazebo_ros_camera_utils.h',
            'gazebo_ros_laser.h',
            'gazebo_ros_diff_drive.h',
            'gazebo_ros_imu.h',
            'gazebo_ros_p3d.h',
            'gazebo_ros_range.h',
            'gazebo_ros_bumper.h',
            'gazebo_ros_ft_sensor.h',
            'gazebo_ros_joint_state_publisher.h',
            'gazebo_ros_planar_move.h',
            'PubQueue.h',
        ],
    ),
    'gazebo_ros_control': (
        GAZEBO_ROS_PKGS_VERSION,
        [
            'roscpp',
            'gazebo_ros',
            'controller_manager',
            'hardware_interface',
            'transmission_interface',
            'joint_limits_interface',
            'control_toolbox',
        ],
        ['robot_hw_sim.h', 'default_robot_hw_sim.h', 'gazebo_ros_control_plugin.h'],
    ),
    'hardware_interface': (
        ROS_CONTROL_VERSION,
        ['roscpp'],
        [
            'hardware_interface.h',
            'robot_hw.h',
            'joint_handle.h',
            'joint_command_interface.h',
            'joint_state_interface.h',
            'joint_mode_interface.h',
            'posvel_command_interface.h',
            'posvelacc_command_interface.h',
            'actuator_command_interface.h',
            'actuator_state_interface.h',
            'imu_sensor_interface.h',
            'force_torque_sensor_interface.h',
            'controller_info.h',
            'interface_resources.h',
            'internal/hardware_resource_manager.h',
        ],
    ),
    'controller_interface': (
        ROS_CONTROL_VERSION,
        ['roscpp', 'hardware_interface'],
        ['controller.h', 'controller_base.h', 'multi_interface_controller.h'],
    ),
    'controller_manager': (
        ROS_CONTROL_VERSION,
        ['roscpp', 'hardware_interface', 'controller_interface', 'controller_manager_msgs'],
        ['controller_manager.h', 'controller_loader.h', 'controller_loader_interface.h'],
    ),
    'transmission_interface': (
        ROS_CONTROL_VERSION,
        ['roscpp', 'hardware_interface'],
        [
            'transmission.h',
            'transmission_interface.h',
            'simple_transmission.h',
            'differential_transmission.h',
            'four_bar_linkage_transmission.h',
            'transmission_info.h',
            'transmission_parser.h',
            'transmission_interface_loader.h',
            'robot_transmissions.h',
        ],
    ),
    'joint_limits_interface': (
        ROS_CONTROL_VERSION,
        ['roscpp', 'hardware_interface'],
        [
            'joint_limits.h',
            'joint_limits_interface.h',
            'joint_limits_urdf.h',
            'joint_limits_rosparam.h',
        ],
    ),
    'combined_robot_hw': (
        ROS_CONTROL_VERSION,
        ['roscpp', 'hardware_interface'],
        ['combined_robot_hw.h'],
    ),
    'realtime_tools': (
        '1.16.1',
        ['roscpp'],
        [
            'realtime_publisher.h',
            'realtime_buffer.h',
            'realtime_box.h',
            'realtime_clock.h',
            'realtime_server_goal_handle.h',
        ],
    ),
    'control_toolbox': (
        '1.19.0',
        ['roscpp', 'realtime_tools'],
        ['pid.h', 'pid_gains_setter.h', 'limited_proxy.h', 'sine_sweep.h'],
    ),
    'forward_command_controller': (
        ROS_CONTROLLERS_VERSION,
        ['controller_interface', 'hardware_interface', 'std_msgs', 'realtime_tools'],
        ['forward_command_controller.h', 'forward_joint_group_command_controller.h'],
    ),
    'effort_controllers': (
        ROS_CONTROLLERS_VERSION,
        ['controller_interface', 'forward_command_controller', 'control_toolbox', 'realtime_tools'],
        _JOINT_CONTROLLERS,
    ),
    'position_controllers': (
        ROS_CONTROLLERS_VERSION,
        ['controller_interface', 'forward_command_controller'],
        ['joint_position_controller.h', 'joint_group_position_controller.h'],
    ),
    'velocity_controllers': (
        ROS_CONTROLLERS_VERSION,
        ['controller_interface', 'forward_command_controller', 'control_toolbox'],
        [
            'joint_velocity_controller.h',
            'joint_group_velocity_controller.h',
            'joint_position_controller.h',
        ],
    ),
    'joint_state_controller': (
        ROS_CONTROLLERS_VERSION,
        ['controller_interface', 'hardware_interface', 'sensor_msgs', 'realtime_tools'],
        ['joint_state_controller.h'],
    ),
    'joint_trajectory_controller': (
        ROS_CONTROLLERS_VERSION,
        [
            'controller_interface',
            'hardware_interface',
            'control_msgs',
            'trajectory_msgs',
            'control_toolbox',
            'realtime_tools',
        ],
        [
            'joint_trajectory_controller.h',
            'joint_trajectory_controller_impl.h',
            'joint_trajectory_segment.h',
            'hardware_interface_adapter.h',
            'init_joint_trajectory.h',
            'tolerances.h',
        ],
    ),
    'gripper_action_controller': (
        ROS_CONTROLLERS_VERSION,
        ['controller_interface', 'control_msgs', 'control_toolbox', 'realtime_tools'],
        ['gripper_action_controller.h', 'hardware_interface_adapter.h'],
    ),
    'diff_drive_controller': (
        ROS_CONTROLLERS_VERSION,
        ['controller_interface', 'nav_msgs', 'geometry_msgs', 'realtime_tools'],
        ['diff_drive_controller.h', 'odometry.h', 'speed_limiter.h'],
    ),
    'imu_sensor_controller': (
        ROS_CONTROLLERS_VERSION,
        ['controller_interface', 'sensor_msgs', 'realtime_tools'],
        ['imu_sensor_controller.h'],
    ),
    'force_torque_sensor_controller': (
        ROS_CONTROLLERS_VERSION,
        ['controller_interface', 'geometry_msgs', 'realtime_tools'],
        ['force_torque_sensor_controller.h'],
    ),
    # metapackages robot packages list as run dependencies
    'ros_control': (ROS_CONTROL_VERSION, [], []),
    'ros_controllers': (ROS_CONTROLLERS_VERSION, [], []),
    'gazebo_ros_pkgs': (GAZEBO_ROS_PKGS_VERSION, [], []),
}

PACKAGE_XML = '''<?xml version="1.0"?>
<package format="2">
  <name>{name}</name>
  <version>{version}</version>
  <description>{description} Generated by arm1/tools/make_compat_packages.py.</description>
  <maintainer email="arm1@example.invalid">arm1 developers</maintainer>
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
{depends}</package>
'''

CMAKELISTS = '''cmake_minimum_required(VERSION 3.12)
project({name})
find_package(catkin REQUIRED{components})
{before}catkin_package({exports}CFG_EXTRAS {name}-extras.cmake)
'''

# Run in the package that finds the stand-in (its PROJECT_NAME, its build dir): the
# headers above include arm1_stand_in/no_cxx_api.h, written here to name that package.
EXTRAS = '''# {name} stand-in (arm1): its C++ API is not here. The headers in its include dir
# include the file written below, which stops the compile naming the package that uses them.
if(PROJECT_NAME)
  set(_arm1_no_api_dir "${{CMAKE_CURRENT_BINARY_DIR}}/arm1_stand_in_include")
  file(CONFIGURE OUTPUT "${{_arm1_no_api_dir}}/arm1_stand_in/no_cxx_api.h" CONTENT
"// Included by a stand-in header: this package compiles against an API arm1 lacks.
#error \\"${{PROJECT_NAME}} compiles against Gazebo's or ros_control's C++ API (the header \\
included above), which arm1 does not provide: arm1 simulates in Python, and Debian 12 has \\
neither. This package cannot build here; build the others with \\
catkin_make -DCATKIN_BLACKLIST_PACKAGES=${{PROJECT_NAME}} (see arm1's docs/building.md).\\"
#include <arm1_stand_in_stops_the_build_here>
" @ONLY)
  list(APPEND {name}_INCLUDE_DIRS "${{_arm1_no_api_dir}}")
endif()
{more}'''

# Gazebo 11's config variables (gazebo-config.cmake): robot packages use them as
# include_directories(${{GAZEBO_INCLUDE_DIRS}}), link_directories(${{GAZEBO_LIBRARY_DIRS}}),
# target_link_libraries(... ${{GAZEBO_LIBRARIES}}), CMAKE_CXX_FLAGS += GAZEBO_CXX_FLAGS.
GAZEBO_EXTRAS = '''set(GAZEBO_VERSION {version})
set(GAZEBO_MAJOR_VERSION {major})
set(GAZEBO_MINOR_VERSION {minor})
set(GAZEBO_PATCH_VERSION {patch})
set(GAZEBO_INCLUDE_DIRS ${{gazebo_INCLUDE_DIRS}})
get_filename_component(_arm1_prefix "${{gazebo_DIR}}/../../.." ABSOLUTE)
set(GAZEBO_LIBRARY_DIRS "${{_arm1_prefix}}/lib")
# No libraries: a target that links them but calls nothing of Gazebo's links.
set(GAZEBO_LIBRARIES "")
set(GAZEBO_CXX_FLAGS "-std=c++17")
set(GAZEBO_FOUND TRUE)
'''

# gazebo_dev-extras.cmake upstream: Gazebo's flags for whoever finds gazebo_dev.
GAZEBO_DEV_EXTRAS = '''set(CMAKE_CXX_FLAGS "${CMAKE_CXX_FLAGS} ${GAZEBO_CXX_FLAGS}")
'''

HEADER = '''// {package}/{header}: {package}'s C++ API, which arm1 (in Python) does not provide.
#include <arm1_stand_in/no_cxx_api.h>
'''

DESCRIPTION = (
    "Stand-in for {name}'s build-time name: what its CMake config exports, without its C++ API."
)


def dynamic_reconfigure_files(name: str) -> List[str]:
    """The stand-in's dynamic_reconfigure definitions (tools/compat_cfg/<name>/*.cfg)."""
    folder = os.path.join(CFG_DIR, name)
    return (
        sorted(f for f in os.listdir(folder) if f.endswith('.cfg')) if os.path.isdir(folder) else []
    )


def make_stand_ins(
    dest: str, write: Callable[..., None], extra_depends: Dict[str, List[str]]
) -> None:
    """Write every stand-in under ``dest``; ``extra_depends``: packages make_compat_packages
    gives scripts too (gazebo_ros, controller_manager) keep those, and get these exports."""
    for name, (version, depends, headers) in STAND_INS.items():
        depends = depends + [d for d in extra_depends.get(name, []) if d not in depends]
        cfgs = dynamic_reconfigure_files(name)
        if cfgs and 'dynamic_reconfigure' not in depends:
            depends = depends + ['dynamic_reconfigure']
        root = os.path.join(dest, name)
        for cfg in cfgs:
            with open(os.path.join(CFG_DIR, name, cfg)) as f:
                write(os.path.join(root, 'cfg', cfg), f.read(), executable=True)
        write(
            os.path.join(root, 'package.xml'),
            PACKAGE_XML.format(
                name=name,
                version=version,
                description=DESCRIPTION.format(name=name),
                depends=''.join('  <depend>%s</depend>\n' % d for d in depends),
            ),
        )
        exports = 'INCLUDE_DIRS include ' if headers else ''
        if depends:
            exports += 'CATKIN_DEPENDS %s ' % ' '.join(depends)
        write(
            os.path.join(root, 'CMakeLists.txt'),
            CMAKELISTS.format(
                name=name,
                components=' COMPONENTS ' + ' '.join(depends) if depends else '',
                before=(
                    'generate_dynamic_reconfigure_options(%s)\n'
                    % ' '.join('cfg/' + c for c in cfgs)
                    if cfgs
                    else ''
                ),
                exports=exports,
            ),
        )
        write(
            os.path.join(root, 'cmake', name + '-extras.cmake'),
            EXTRAS.format(name=name, more=extras_for(name, version)),
        )
        for header in headers:
            write(
                os.path.join(root, 'include', name, header),
                HEADER.format(package=name, header=header),
            )


def extras_for(name: str, version: str) -> str:
    if name == 'gazebo':
        major, minor, patch = version.split('.')
        return GAZEBO_EXTRAS.format(version=version, major=major, minor=minor, patch=patch)
    if name == 'gazebo_dev':
        return GAZEBO_DEV_EXTRAS
    return ''
