"""Package exports read from package.xml as gazebo_ros reads them (rospack over a package path
of our own making)."""

import os

import rospkg

from _arm1sim.description.resource_paths import gazebo_paths
from _arm1sim.ros.common.packages import gazebo_exports

PACKAGE_XML = """<?xml version="1.0"?>
<package format="2">
  <name>%s</name><version>0.0.1</version><description>test</description>
  <maintainer email="a@example.com">a</maintainer><license>MIT</license>
  <buildtool_depend>catkin</buildtool_depend>
  <export>%s</export>
</package>"""


def package(root, name, export):
    folder = os.path.join(str(root), name)
    os.makedirs(folder)
    with open(os.path.join(folder, 'package.xml'), 'w') as f:
        f.write(PACKAGE_XML % (name, export))
    return folder


def test_gazebo_model_and_media_paths_with_prefix_expanded(tmp_path):
    cell = package(
        tmp_path,
        'cell_description',
        '<gazebo_ros gazebo_model_path="${prefix}/models" gazebo_media_path="${prefix}"/>',
    )
    package(tmp_path, 'plain_pkg', '')
    exports = gazebo_exports(rospkg.RosPack([str(tmp_path)]))
    assert len(exports) == 1  # the package without the export adds nothing
    assert exports[0].model_paths == [os.path.join(cell, 'models')]
    assert exports[0].media_paths == [cell]


def test_exported_model_folder_resolves_model_uris(tmp_path):
    cell = package(
        tmp_path, 'cell_description', '<gazebo_ros gazebo_model_path="${prefix}/models"/>'
    )
    os.makedirs(os.path.join(cell, 'models', 'fixture'))
    sdf = os.path.join(cell, 'models', 'fixture', 'model.sdf')
    with open(sdf, 'w') as f:
        f.write('<sdf version="1.6"><model name="fixture"/></sdf>')
    paths = gazebo_paths({}, gazebo_exports(rospkg.RosPack([str(tmp_path)])))
    assert paths.find_model('model://fixture') == sdf


def test_a_broken_package_xml_elsewhere_is_passed_over(tmp_path):
    package(tmp_path, 'good_pkg', '<gazebo_ros gazebo_model_path="${prefix}/m"/>')
    bad = package(tmp_path, 'bad_pkg', '<gazebo_ros gazebo_model_path="${prefix}/m"/>')
    with open(os.path.join(bad, 'package.xml'), 'w') as f:
        f.write('<package format="2"><name>bad_pkg</name></package>')  # invalid manifest
    exports = gazebo_exports(rospkg.RosPack([str(tmp_path)]))
    assert [e.model_paths for e in exports] == [[os.path.join(str(tmp_path), 'good_pkg', 'm')]]
