#!/usr/bin/env python3
"""Write a user's own arm package, as the seed's tutorial path makes one: a catkin package
named ``arm1`` around a SolidWorks export (dense STL meshes, CAD inertials), with xacro,
transmissions, a camera, a controllers.yaml of effort PID position controllers, its own
``srv/GoToPosition.srv`` and a ``gazebo.launch`` through gazebo_ros and controller_manager.

    tools/ws-run python tools/make_own_arm.py DEST_DIR [--name arm1] [--triangles 15000]

It is what docs/own-arm.md walks through and what test/integration/test_own_arm.py builds
in a workspace of its own over ours. Four arm joints and two gripper fingers (joint1..joint6),
six ``effort_controllers/JointPositionController``s. The meshes are bench.dense_meshes'
closed, concave U-bracket, stretched to each link and tessellated to about ``--triangles``,
as a CAD exporter's are. Deterministic: same bytes on every run.
"""

from __future__ import annotations

import argparse
import os
import sys
from typing import Dict, List, Tuple

import numpy as np

REPO_ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(REPO_ROOT, 'src'))

from _arm1sim.bench import dense_meshes  # noqa: E402
from _arm1sim.physics.stl import write_binary_stl  # noqa: E402

Vec = Tuple[float, float, float]

# link: (size of its U-shaped block in m, mass kg); the arm's chain from the base up
LINKS: Dict[str, Tuple[Vec, float]] = {
    'base_link': ((0.10, 0.10, 0.04), 0.30),
    'link1': ((0.05, 0.05, 0.06), 0.08),
    'link2': ((0.03, 0.04, 0.12), 0.06),
    'link3': ((0.03, 0.04, 0.10), 0.05),
    'link4': ((0.04, 0.05, 0.04), 0.08),
    'finger_left': ((0.01, 0.012, 0.04), 0.02),
    'finger_right': ((0.01, 0.012, 0.04), 0.02),
}
# joint: (parent, child, type, origin xyz, axis, lower, upper)
JOINTS: List[Tuple[str, str, str, str, Vec, str, float, float]] = [
    ('joint1', 'base_link', 'link1', 'revolute', (0.0, 0.0, 0.04), '0 0 1', -1.57, 1.57),
    ('joint2', 'link1', 'link2', 'revolute', (0.0, 0.0, 0.06), '0 1 0', -1.2, 1.2),
    ('joint3', 'link2', 'link3', 'revolute', (0.0, 0.0, 0.12), '0 1 0', -1.5, 1.5),
    ('joint4', 'link3', 'link4', 'revolute', (0.0, 0.0, 0.10), '0 0 1', -1.57, 1.57),
    ('joint5', 'link4', 'finger_left', 'prismatic', (0.0, 0.012, 0.04), '0 1 0', 0.0, 0.015),
    ('joint6', 'link4', 'finger_right', 'prismatic', (0.0, -0.012, 0.04), '0 -1 0', 0.0, 0.015),
]
# position controller gains by joint type (a desk arm's small servos): the wrist's inertia
# about its axis is ~5e-5 kg m^2, so d stays well under I / dt (0.05) for a 1 ms step
GAINS = {'revolute': (1.0, 0.05, 0.01), 'prismatic': (50.0, 0.0, 1.0)}


def bracket(size: Vec, triangles: int) -> np.ndarray:
    """bench.dense_meshes' bumpy U-bracket (concave, dense, as a CAD export of a servo
    bracket), stretched to ``size`` and centred on the link's z axis, its base at z = 0."""
    tris = dense_meshes.u_bracket(triangles)
    scale = np.array(size) / np.array([dense_meshes.W, dense_meshes.D, dense_meshes.H])
    return tris * scale - np.array([size[0] / 2, size[1] / 2, 0.0])


def inertial(size: Vec, mass: float) -> str:
    """A solid block's inertia about its centre, written as SolidWorks writes it."""
    sx, sy, sz = size
    ixx, iyy, izz = (mass * (b * b + c * c) / 12 for b, c in ((sy, sz), (sx, sz), (sx, sy)))
    return (
        '    <inertial>\n      <origin xyz="0 0 %.6g" rpy="0 0 0"/>\n      <mass value="%.6g"/>\n'
        '      <inertia ixx="%.6g" ixy="0" ixz="0" iyy="%.6g" iyz="0" izz="%.6g"/>\n'
        '    </inertial>\n' % (0.4 * sz, mass, ixx, iyy, izz)
    )


def urdf(name: str) -> str:
    links = []
    for link, (size, mass) in LINKS.items():
        mesh = '<mesh filename="package://%s/meshes/%s.STL"/>' % (name, link)
        links.append(
            '  <link name="%s">\n%s'
            '    <visual>\n      <origin xyz="0 0 0" rpy="0 0 0"/>\n      <geometry>%s</geometry>\n'
            '    </visual>\n'
            '    <collision>\n      <origin xyz="0 0 0" rpy="0 0 0"/>\n'
            '      <geometry>%s</geometry>\n    </collision>\n  </link>\n'
            % (link, inertial(size, mass), mesh, mesh)
        )
    joints, transmissions = [], []
    for joint, parent, child, kind, xyz, axis, lower, upper in JOINTS:
        joints.append(
            '  <joint name="%s" type="%s">\n    <origin xyz="%g %g %g" rpy="0 0 0"/>\n'
            '    <parent link="%s"/>\n    <child link="%s"/>\n    <axis xyz="%s"/>\n'
            '    <limit lower="%g" upper="%g" effort="%g" velocity="%g"/>\n  </joint>\n'
            % (joint, kind, *xyz, parent, child, axis, lower, upper,
               2.0 if kind == 'revolute' else 20.0, 3.0 if kind == 'revolute' else 0.1)
        )  # fmt: skip
        transmissions.append(
            '  <transmission name="tran_%s">\n'
            '    <type>transmission_interface/SimpleTransmission</type>\n'
            '    <joint name="%s">\n'
            '      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>\n'
            '    </joint>\n    <actuator name="motor_%s">\n'
            '      <hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface>\n'
            '      <mechanicalReduction>1</mechanicalReduction>\n    </actuator>\n'
            '  </transmission>\n' % (joint, joint, joint)
        )
    return (
        '<?xml version="1.0" encoding="utf-8"?>\n'
        '<!-- As the SolidWorks to URDF exporter writes it, then wrapped in xacro by hand. -->\n'
        '<robot name="%s" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:property name="camera_rate" value="10"/>\n'
        '  <link name="world"/>\n'
        '  <joint name="fixed" type="fixed">\n    <parent link="world"/>\n'
        '    <child link="base_link"/>\n  </joint>\n'
        '%s%s%s'
        '  <joint name="camera_joint" type="fixed">\n    <origin xyz="0.03 0 0.02" rpy="0 0 0"/>\n'
        '    <parent link="link4"/>\n    <child link="camera_link"/>\n  </joint>\n'
        '  <link name="camera_link">\n    <inertial>\n      <mass value="0.001"/>\n'
        '      <inertia ixx="1e-8" ixy="0" ixz="0" iyy="1e-8" iyz="0" izz="1e-8"/>\n'
        '    </inertial>\n  </link>\n'
        '  <gazebo reference="camera_link">\n    <sensor type="camera" name="camera1">\n'
        '      <update_rate>${camera_rate}</update_rate>\n      <camera name="head">\n'
        '        <horizontal_fov>1.047</horizontal_fov>\n'
        '        <image><width>160</width><height>120</height><format>R8G8B8</format></image>\n'
        '        <clip><near>0.02</near><far>10</far></clip>\n      </camera>\n'
        '      <plugin name="camera_controller" filename="libgazebo_ros_camera.so">\n'
        '        <alwaysOn>true</alwaysOn>\n        <updateRate>0.0</updateRate>\n'
        '        <cameraName>%s/camera1</cameraName>\n'
        '        <imageTopicName>image_raw</imageTopicName>\n'
        '        <cameraInfoTopicName>camera_info</cameraInfoTopicName>\n'
        '        <frameName>camera_link</frameName>\n      </plugin>\n    </sensor>\n'
        '  </gazebo>\n'
        '  <gazebo>\n    <plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so">\n'
        '      <robotNamespace>/%s</robotNamespace>\n    </plugin>\n  </gazebo>\n'
        '</robot>\n' % (name, ''.join(links), ''.join(joints), ''.join(transmissions), name, name)
    )


def controllers_yaml(name: str) -> str:
    lines = [
        '%s:' % name,
        '  joint_state_controller:',
        '    type: joint_state_controller/JointStateController',
        '    publish_rate: 50',
    ]
    for joint, _, _, kind, *_ in JOINTS:
        p, i, d = GAINS[kind]
        lines += [
            '  %s_position_controller:' % joint,
            '    type: effort_controllers/JointPositionController',
            '    joint: %s' % joint,
            '    pid: {p: %g, i: %g, d: %g}' % (p, i, d),
        ]
    return '\n'.join(lines) + '\n'


def controller_names() -> List[str]:
    return ['joint_state_controller'] + ['%s_position_controller' % j[0] for j in JOINTS]


LAUNCH = '''<launch>
  <arg name="paused" default="false"/>
  <arg name="gui" default="true"/>
  <param name="robot_description" command="$(find xacro)/xacro '$(find {name})/urdf/{name}.xacro'"/>
  <include file="$(find gazebo_ros)/launch/empty_world.launch">
    <arg name="paused" value="$(arg paused)"/>
    <arg name="gui" value="$(arg gui)"/>
  </include>
  <node name="urdf_spawner" pkg="gazebo_ros" type="spawn_model" respawn="false" output="screen"
        args="-urdf -param robot_description -model {name}"/>
  <rosparam file="$(find {name})/config/controllers.yaml" command="load"/>
  <node name="controller_spawner" pkg="controller_manager" type="spawner" respawn="false"
        output="screen" ns="/{name}" args="{controllers}"/>
  <node name="robot_state_publisher" pkg="robot_state_publisher" type="robot_state_publisher"
        respawn="false" output="screen">
    <remap from="/joint_states" to="/{name}/joint_states"/>
  </node>
</launch>
'''

PACKAGE_XML = '''<?xml version="1.0"?>
<package format="2">
  <name>{name}</name>
  <version>1.0.0</version>
  <description>My own arm: a SolidWorks export in Gazebo, with its own GoToPosition.</description>
  <maintainer email="me@example.invalid">me</maintainer>
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
  <build_depend>message_generation</build_depend>
  <depend>rospy</depend>
  <depend>std_msgs</depend>
  <exec_depend>message_runtime</exec_depend>
  <exec_depend>xacro</exec_depend>
  <exec_depend>gazebo_ros</exec_depend>
  <exec_depend>gazebo_ros_control</exec_depend>
  <exec_depend>controller_manager</exec_depend>
  <exec_depend>effort_controllers</exec_depend>
  <exec_depend>joint_state_controller</exec_depend>
  <exec_depend>robot_state_publisher</exec_depend>
</package>
'''

CMAKELISTS = '''cmake_minimum_required(VERSION 3.0.2)
project({name})
find_package(catkin REQUIRED COMPONENTS rospy std_msgs message_generation)
add_service_files(FILES GoToPosition.srv)
generate_messages(DEPENDENCIES std_msgs)
catkin_package(CATKIN_DEPENDS rospy std_msgs message_runtime)
catkin_install_python(PROGRAMS scripts/go_to DESTINATION ${{CATKIN_PACKAGE_BIN_DESTINATION}})
'''

SRV = ''.join('float64 %s\n' % j[0] for j in JOINTS) + '---\nduration time_elapsed\n'

# The user's own node: their GoToPosition, their six command topics.
GO_TO = '''#!/usr/bin/env python
"""go_to: serves /{name}/go_to (my GoToPosition: six joints) by commanding each controller."""
import rospy
from std_msgs.msg import Float64
from {name}.srv import GoToPosition, GoToPositionResponse

JOINTS = {joints!r}


def main():
    rospy.init_node('go_to')
    pubs = [rospy.Publisher('/{name}/%s_position_controller/command' % j, Float64, queue_size=1)
            for j in JOINTS]

    def serve(req):
        start = rospy.Time.now()
        for pub, j in zip(pubs, JOINTS):
            pub.publish(getattr(req, j))
        return GoToPositionResponse(rospy.Time.now() - start)

    rospy.Service('/{name}/go_to', GoToPosition, serve)
    rospy.spin()


if __name__ == '__main__':
    main()
'''


def make(dest: str, name: str = 'arm1', triangles: int = 15000) -> str:
    """Write the package into dest/name; returns its folder."""
    root = os.path.join(dest, name)

    def write(rel: str, text: str, executable: bool = False) -> None:
        path = os.path.join(root, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, 'w') as f:
            f.write(text)
        if executable:
            os.chmod(path, 0o755)

    write('package.xml', PACKAGE_XML.format(name=name))
    write('CMakeLists.txt', CMAKELISTS.format(name=name))
    write('srv/GoToPosition.srv', SRV)
    write('urdf/%s.xacro' % name, urdf(name))
    write('config/controllers.yaml', controllers_yaml(name))
    write(
        'launch/gazebo.launch', LAUNCH.format(name=name, controllers=' '.join(controller_names()))
    )
    write('scripts/go_to', GO_TO.format(name=name, joints=[j[0] for j in JOINTS]), True)
    os.makedirs(os.path.join(root, 'meshes'), exist_ok=True)
    for link, (size, _) in LINKS.items():
        write_binary_stl(
            os.path.join(root, 'meshes', link + '.STL'),
            bracket(size, triangles),
            header='%s %s, tools/make_own_arm.py' % (name, link),
        )
    return root


def main(argv: List[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('dest', help='the catkin workspace src folder to write the package in')
    parser.add_argument('--name', default='arm1', help='package and robot name (arm1)')
    parser.add_argument(
        '--triangles', type=int, default=15000, help='triangles per link mesh (15000)'
    )
    args = parser.parse_args(argv)
    print(make(args.dest, args.name, args.triangles))
    return 0


if __name__ == '__main__':
    sys.exit(main())
