"""State sensors on links that fixed-joint lumping merged into their parent: the sensor keeps
its frame (as Gazebo moves the sensor to the parent with the joint's transform)."""

import math

from helpers import G, box, listen, robot, steps, world

BODY = (
    '<link name="world"/><joint name="bolt" type="fixed"><parent link="world"/>'
    '<child link="base"/><origin xyz="0 0 1"/></joint>'
    + box('base')
    + '<joint name="imu_joint" type="fixed"><parent link="base"/><child link="imu_link"/>'
    '<origin xyz="0.1 0 0" rpy="%r 0 0"/></joint><link name="imu_link"/>' % (math.pi / 2)
)
GAZEBO = """<gazebo reference="imu_link"><sensor type="imu" name="imu">
  <plugin name="i" filename="libgazebo_ros_imu_sensor.so"><frameName>imu_link</frameName>
  <updateRateHZ>0</updateRateHZ></plugin></sensor></gazebo>
<gazebo><plugin name="truth" filename="libgazebo_ros_p3d.so"><bodyName>imu_link</bodyName>
  <topicName>odom</topicName></plugin>
<plugin name="ft" filename="libgazebo_ros_ft_sensor.so"><jointName>imu_joint</jointName>
  <topicName>ft</topicName></plugin></gazebo>"""


def close(a, b, tol=1e-6):
    return all(abs(x - y) <= tol for x, y in zip(a, b))


def test_sensors_on_a_lumped_link_keep_its_frame():
    sim = world(ground=False)
    try:
        model = sim.spawn_urdf('r', robot(BODY, GAZEBO))
        assert 'imu_link' not in model.robot.link_index  # lumped into base, as in Gazebo
        # the ft sensor's joint is gone with the lumping: not loaded, as in Gazebo
        assert sorted(s.name for s in model.sensors) == ['imu', 'truth']
        got = listen(model)
        steps(sim, 10)
        s = math.sin(math.pi / 4)
        imu = got['imu'][-1][1]
        assert close(imu.orientation, (s, 0, 0, s)) and close(imu.linear_acceleration, (0, G, 0))
        truth = got['truth'][-1][1]
        assert close(truth.position, (0.1, 0, 1)) and close(truth.orientation, (s, 0, 0, s))
    finally:
        sim.close()


def test_a_bumper_on_a_lumped_link_belongs_to_its_parent():
    sim = world(ground=True)
    try:
        body = box('base') + (
            '<joint name="skin_joint" type="fixed"><parent link="base"/><child link="skin"/>'
            '</joint><link name="skin"/>'
            '<gazebo reference="skin"><sensor type="contact" name="touch">'
            '<contact><collision>base_collision</collision></contact>'
            '<plugin name="b" filename="libgazebo_ros_bumper.so"/></sensor></gazebo>'
        )
        model = sim.spawn_urdf('crate', robot(body), position=(0, 0, 0.1))
        (sensor,) = model.sensors
        assert sensor.collision == 'crate::base::base_collision'
        got = listen(model)
        steps(sim, 100)
        (pair,) = got['touch'][-1][1]
        assert abs(sum(w[0][2] for w in pair.wrenches) - G) < 0.02 * G
    finally:
        sim.close()
