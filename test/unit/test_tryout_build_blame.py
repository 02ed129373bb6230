"""try_robot's package-by-package build verdict: which package a failed catkin_make log blames
(_arm1sim.tryout.workspace.blamed_packages), at CMake or at compile time."""

from _arm1sim.tryout.workspace import blamed_packages

CMAKE_LOG = '''-- ~~  - robot_description
-- ~~  - robot_gazebo
-- +++ processing catkin package: 'robot_description'
-- ==> add_subdirectory(robot_description)
-- +++ processing catkin package: 'robot_gazebo'
-- ==> add_subdirectory(robots/robot_gazebo)
CMake Error at /usr/share/catkin/cmake/catkinConfig.cmake:83 (find_package):
  Could not find a package configuration file provided by "fancy_plugin"
-- Configuring incomplete, errors occurred!
'''

# catkin_make's lines, too long for this file, joined from parts
COMPILE_LOG = '''[ 50%] Building CXX object robot_gazebo/CMakeFiles/plugin.dir/src/plugin.cpp.o
/ws/build/robot_gazebo/arm1_stand_in_include/arm1_stand_in/no_cxx_api.h:2:2: \
error: #error "robot_gazebo compiles against Gazebo's"
make[2]: *** [robot_gazebo/CMakeFiles/plugin.dir/build.make:76: \
robot_gazebo/CMakeFiles/plugin.dir/src/plugin.cpp.o] Error 1
make[1]: *** [CMakeFiles/Makefile2:780: robot_gazebo/CMakeFiles/plugin.dir/all] Error 2
make[1]: *** [CMakeFiles/Makefile2:700: robot_tools/CMakeFiles/tool.dir/all] Error 2
'''

NAMES = ['robot_description', 'robot_gazebo', 'robot_tools']


def test_cmake_error_blames_the_package_being_configured():
    blamed = blamed_packages(CMAKE_LOG, NAMES)
    assert list(blamed) == ['robot_gazebo']
    assert blamed['robot_gazebo']['stage'] == 'cmake'
    assert 'fancy_plugin' in blamed['robot_gazebo']['error']


def test_compile_errors_blame_each_failed_target_s_package_once():
    blamed = blamed_packages(COMPILE_LOG, NAMES)
    assert sorted(blamed) == ['robot_gazebo', 'robot_tools']
    assert blamed['robot_gazebo']['stage'] == 'compile'
    assert 'robot_gazebo compiles against' in blamed['robot_gazebo']['error']
    assert blamed['robot_tools']['error'] == 'make failed on robot_tools'


def test_names_outside_the_workspace_are_not_blamed():
    assert blamed_packages(COMPILE_LOG, ['robot_description']) == {}
