"""All five state-sensor plugins on one robot: none measures while nobody listens, each
does at its own rate once someone does, and delete releases them."""

from helpers import box, inertial, robot, steps, world

GAZEBO = """
<gazebo reference="base">
  <sensor type="imu" name="imu"><plugin name="i" filename="libgazebo_ros_imu_sensor.so">
    <frameName>imu</frameName><updateRateHZ>100</updateRateHZ></plugin></sensor>
  <sensor type="contact" name="bumper"><update_rate>50</update_rate>
    <contact><collision>base_collision</collision></contact>
    <plugin name="b" filename="libgazebo_ros_bumper.so"/></sensor>
</gazebo>
<gazebo>
  <plugin name="p3d" filename="libgazebo_ros_p3d.so">
    <bodyName>base</bodyName><topicName>odom</topicName><updateRate>20</updateRate></plugin>
  <plugin name="ft" filename="libgazebo_ros_ft_sensor.so">
    <jointName>mount</jointName><topicName>ft</topicName><updateRate>10</updateRate></plugin>
  <plugin name="old_imu" filename="libgazebo_ros_imu.so">
    <bodyName>base</bodyName><updateRate>5</updateRate></plugin>
</gazebo>"""

BODY = box('base', 2.0) + (
    '<joint name="mount" type="fixed"><parent link="base"/><child link="payload"/>'
    '<origin xyz="0 0 0.15"/></joint><link name="payload">%s</link>'
    '<gazebo reference="mount"><preserveFixedJoint>true</preserveFixedJoint></gazebo>'
    % inertial(1.0)
)


def test_idle_until_wanted_then_each_at_its_rate():
    sim = world(ground=True)
    try:
        model = sim.spawn_urdf('rover', robot(BODY, GAZEBO), position=(0, 0, 0.1))
        sensors = {s.name: s for s in model.sensors}
        assert sorted(sensors) == ['bumper', 'ft', 'imu', 'old_imu', 'p3d']
        counts = {name: [] for name in sensors}
        for name, s in sensors.items():
            s.deliver = lambda t, r, got=counts[name]: got.append(t)
        steps(sim, 1000)
        assert all(s.readings == 0 for s in sensors.values())
        assert all(got == [] for got in counts.values())
        assert not sensors['ft']._enabled
        for s in sensors.values():
            s.wanted = lambda: True
        steps(sim, 1000)
        rates = {name: len(got) for name, got in counts.items()}
        assert 100 <= rates['imu'] <= 101 and 50 <= rates['bumper'] <= 51
        assert 20 <= rates['p3d'] <= 21 and 10 <= rates['ft'] <= 11 and 5 <= rates['old_imu'] <= 6
        sim.delete_model('rover')
        assert all(s.deliver is None for s in sensors.values())
        assert not sensors['ft']._enabled
    finally:
        sim.close()
