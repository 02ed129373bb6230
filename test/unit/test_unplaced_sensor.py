"""A <gazebo reference> sensor on a link the URDF does not have (open_manipulator's camera,
commented out of its URDF but not of its .gazebo.xacro) is left out with a warning at spawn,
as Gazebo's URDF->SDF leaves it out, instead of refusing the model."""

from _arm1sim.description.gazebo_plugins import sensor_specs, unimplemented
from _arm1sim.description.urdf_model import parse_urdf

URDF = '''<robot name="r">
  <link name="base"/>
  <link name="tip"/>
  <joint name="j" type="revolute"><parent link="base"/><child link="tip"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <gazebo reference="tip">
    <sensor type="camera" name="kept"><camera/></sensor>
  </gazebo>
  <gazebo reference="camera_link">
    <sensor type="camera" name="r200"><camera/></sensor>
  </gazebo>
</robot>'''


def test_a_sensor_on_a_missing_link_is_left_out_and_named():
    model = parse_urdf(URDF)
    assert [(link, s.get('name')) for link, s in model.sensors] == [('tip', 'kept')]
    assert [(link, s.get('name')) for link, s in model.unplaced_sensors] == [
        ('camera_link', 'r200')
    ]
    assert [s.name for s in sensor_specs(model)] == ['kept']  # no UrdfError
    lines = unimplemented(model, 'r')
    assert any("'r200'" in line and "'camera_link'" in line for line in lines), lines


def test_a_robot_sim_type_the_stand_in_lacks_is_named_at_spawn():
    def with_type(sim_type):
        return URDF.replace(
            '</robot>',
            '<gazebo><plugin name="c" filename="libgazebo_ros_control.so">'
            '<robotSimType>%s</robotSimType></plugin></gazebo></robot>' % sim_type,
        )

    lines = unimplemented(parse_urdf(with_type('acme_gazebo/AcmeHWSim')), 'acme')
    assert any('robotSimType acme_gazebo/AcmeHWSim' in line for line in lines), lines
    franka = unimplemented(parse_urdf(with_type('franka_gazebo/FrankaHWSim')), 'panda')
    assert not any('robotSimType' in line for line in franka), franka  # vendors/franka/hw_sim.py
    default = URDF.replace(
        '</robot>',
        '<gazebo><plugin name="c" filename="libgazebo_ros_control.so"/></gazebo></robot>',
    )
    assert not any('robotSimType' in line for line in unimplemented(parse_urdf(default), 'r'))
