"""A two-wheeled rover (a chassis on two frictionless casters) with gazebo_ros_diff_drive,
ROS-free: shared by test/unit/test_diff_drive.py and the rostest test/test_diff_drive.py."""

SEPARATION, RADIUS = 0.24, 0.04


def wheel(side, y):
    return """
  <link name="wheel_%(side)s_link">
    <inertial><mass value="0.2"/>
      <inertia ixx="1e-4" ixy="0" ixz="0" iyy="1.6e-4" iyz="0" izz="1e-4"/></inertial>
    <collision><origin rpy="1.5708 0 0"/>
      <geometry><cylinder radius="%(r)g" length="0.02"/></geometry></collision>
  </link>
  <joint name="wheel_%(side)s_joint" type="continuous">
    <parent link="base_footprint"/><child link="wheel_%(side)s_link"/>
    <origin xyz="0 %(y)g %(r)g"/><axis xyz="0 1 0"/>
  </joint>""" % dict(side=side, y=y, r=RADIUS)


def robot_urdf(**params):
    plugin = dict(
        leftJoint='wheel_left_joint',
        rightJoint='wheel_right_joint',
        wheelSeparation=SEPARATION,
        wheelDiameter=2 * RADIUS,
        wheelTorque=5,
        updateRate=50,
        legacyMode='false',
    )
    plugin.update(params)
    tags = ''.join('<%s>%s</%s>' % (k, v, k) for k, v in plugin.items() if v is not None)
    # a chassis on two frictionless casters, between two wheels
    return """<?xml version="1.0"?>
<robot name="two_wheels">
  <link name="base_footprint">
    <inertial><origin xyz="0 0 0.06"/><mass value="2"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.02" iyz="0" izz="0.02"/></inertial>
    <collision><origin xyz="0 0 0.07"/><geometry><box size="0.3 0.18 0.04"/></geometry>
    </collision>
    <collision><origin xyz="0.12 0 0.02"/><geometry><sphere radius="0.02"/></geometry>
    </collision>
    <collision><origin xyz="-0.12 0 0.02"/><geometry><sphere radius="0.02"/></geometry>
    </collision>
  </link>
  <gazebo reference="base_footprint"><mu1>0</mu1><mu2>0</mu2></gazebo>
  %s %s
  <gazebo>
    <plugin name="drive" filename="libgazebo_ros_diff_drive.so">%s</plugin>
  </gazebo>
</robot>""" % (wheel('left', SEPARATION / 2), wheel('right', -SEPARATION / 2), tags)
