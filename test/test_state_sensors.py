#!/usr/bin/env python
"""A rover of our own resting on the ground carries gazebo_ros_imu_sensor, gazebo_ros_imu,
gazebo_ros_p3d, gazebo_ros_bumper and gazebo_ros_ft_sensor: each topic publishes at its rate,
stamped in sim time, with the values physics gives, and only once someone subscribes."""

import os
import sys

import rosgraph
import rospy
import rostest
from gazebo_msgs.msg import ContactsState
from geometry_msgs.msg import WrenchStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Imu
from std_srvs.srv import Empty

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rostest_util import Recorder, SpawningTestCase, sim_wait, spawn_urdf, wait_for  # noqa: E402

G = 9.8
BASE_MASS, PAYLOAD_MASS = 2.0, 1.0


def inertial(mass):
    return (
        '<inertial><mass value="%g"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0"'
        ' izz="0.01"/></inertial>' % mass
    )


ROVER = """<robot name="rover">
  <link name="base">%s
    <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>
  <joint name="mount" type="fixed"><parent link="base"/><child link="payload"/>
    <origin xyz="0 0 0.15"/></joint>
  <link name="payload">%s</link>
  <gazebo reference="mount">
    <preserveFixedJoint>true</preserveFixedJoint><provideFeedback>true</provideFeedback>
  </gazebo>
  <gazebo reference="base">
    <sensor type="imu" name="imu">
      <update_rate>100</update_rate>
      <plugin name="imu_plugin" filename="libgazebo_ros_imu_sensor.so">
        <topicName>imu</topicName><frameName>rover_imu</frameName>
        <updateRateHZ>50</updateRateHZ>
      </plugin>
    </sensor>
    <sensor type="contact" name="bumper">
      <update_rate>20</update_rate>
      <contact><collision>base_collision</collision></contact>
      <plugin name="bumper_plugin" filename="libgazebo_ros_bumper.so">
        <bumperTopicName>bumper</bumperTopicName><frameName>world</frameName>
      </plugin>
    </sensor>
  </gazebo>
  <gazebo>
    <plugin name="truth" filename="libgazebo_ros_p3d.so">
      <bodyName>base</bodyName><topicName>odom</topicName><updateRate>25</updateRate>
    </plugin>
    <plugin name="ft" filename="libgazebo_ros_ft_sensor.so">
      <jointName>mount</jointName><topicName>ft</topicName><updateRate>10</updateRate>
    </plugin>
    <plugin name="old_imu" filename="libgazebo_ros_imu.so">
      <bodyName>base</bodyName><topicName>imu_old</topicName>
      <serviceName>imu_old_service</serviceName><updateRate>20</updateRate>
    </plugin>
  </gazebo>
</robot>""" % (inertial(BASE_MASS), inertial(PAYLOAD_MASS))

TOPICS = {  # topic: (type, rate in Hz)
    '/rover/imu': (Imu, 50),
    '/rover/imu_old': (Imu, 20),
    '/rover/odom': (Odometry, 25),
    '/rover/bumper': (ContactsState, 20),
    '/rover/ft': (WrenchStamped, 10),
}


def subscribers(topic):
    """The nodes subscribed to ``topic``, from the master."""
    _, subs, _ = rosgraph.Master('/test_state_sensors').getSystemState()
    return [nodes for name, nodes in subs if name == topic]


def collect(topic, seconds):
    """Subscribe, wait ``seconds`` of sim time after the first message, unsubscribe."""
    msg_type, _ = TOPICS[topic]
    recorder = Recorder(topic, msg_type)
    try:
        assert wait_for(lambda: recorder.last() is not None, 30), 'nothing on ' + topic
        first = recorder.last().header.stamp
        wait_for(lambda: (recorder.last().header.stamp - first).to_sec() >= seconds, 20 * seconds)
        return [m for _, m in recorder.msgs]
    finally:
        recorder.sub.unregister()


class StateSensors(SpawningTestCase):
    NODE = 'test_state_sensors'

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        # read by p3d, bumper and ft_sensor (tf::resolve), not by the IMU plugins
        rospy.set_param('/rover/tf_prefix', 'rv')
        spawn_urdf('rover', ROVER, '/rover', (0, 0, 0.1))
        sim_wait(1.0)  # let it settle on the ground: physics' time, not the machine's

    def test_01_nothing_is_sent_before_anyone_subscribes(self):
        for topic in TOPICS:
            self.assertEqual(subscribers(topic), [], topic)
        # a late subscriber gets fresh readings, not a backlog
        start = rospy.Time.now()
        msgs = collect('/rover/imu', 0.2)
        self.assertGreaterEqual(msgs[0].header.stamp, start - rospy.Duration(0.05))

    def test_02_each_topic_publishes_at_its_rate_in_sim_time(self):
        for topic, (_, rate) in TOPICS.items():
            msgs = collect(topic, 2.0)
            stamps = [m.header.stamp.to_sec() for m in msgs]
            gaps = [b - a for a, b in zip(stamps, stamps[1:])]
            self.assertGreaterEqual(len(gaps), 2 * rate - 2, topic)
            mean = sum(gaps) / len(gaps)
            self.assertAlmostEqual(mean, 1.0 / rate, delta=0.1 / rate, msg=topic)
            self.assertTrue(all(g > 0 for g in gaps), topic)

    def test_03_imu_reads_plus_g_at_rest_as_a_real_imu(self):
        msg = collect('/rover/imu', 0.2)[-1]
        self.assertEqual(msg.header.frame_id, 'rover_imu')
        a, o = msg.linear_acceleration, msg.orientation
        self.assertAlmostEqual(a.z, G, delta=0.05)
        self.assertAlmostEqual(abs(o.w), 1.0, delta=1e-3)
        for v in (a.x, a.y, msg.angular_velocity.x, msg.angular_velocity.z):
            self.assertAlmostEqual(v, 0.0, delta=0.05)

    def test_04_gazebo_ros_imu_reads_no_gravity_and_offers_its_service(self):
        msg = collect('/rover/imu_old', 0.2)[-1]
        self.assertEqual(msg.header.frame_id, 'base')
        self.assertAlmostEqual(msg.linear_acceleration.z, 0.0, delta=0.05)
        rospy.wait_for_service('/rover/imu_old_service', 10)
        rospy.ServiceProxy('/rover/imu_old_service', Empty)()

    def test_05_p3d_reports_the_resting_pose(self):
        msg = collect('/rover/odom', 0.2)[-1]
        self.assertEqual((msg.header.frame_id, msg.child_frame_id), ('rv/world', 'base'))
        p = msg.pose.pose.position
        self.assertAlmostEqual(p.x, 0.0, delta=0.01)
        self.assertAlmostEqual(p.z, 0.1, delta=0.01)
        self.assertAlmostEqual(msg.twist.twist.linear.z, 0.0, delta=0.01)

    def test_06_bumper_feels_the_whole_rover(self):
        msg = collect('/rover/bumper', 0.3)[-1]
        self.assertEqual(msg.header.frame_id, 'rv/world')
        (state,) = msg.states
        self.assertEqual(state.collision1_name, 'rover::base::base_collision')
        self.assertEqual(state.collision2_name, 'ground_plane::link::collision')
        self.assertAlmostEqual(
            state.total_wrench.force.z, (BASE_MASS + PAYLOAD_MASS) * G, delta=0.5
        )
        self.assertTrue(all(abs(n.z - 1.0) < 1e-6 for n in state.contact_normals))

    def test_07_ft_sensor_carries_the_payload(self):
        msg = collect('/rover/ft', 0.5)[-1]
        self.assertEqual(msg.header.frame_id, 'rv/payload')
        self.assertAlmostEqual(msg.wrench.force.z, PAYLOAD_MASS * G, delta=0.05)
        self.assertAlmostEqual(msg.wrench.torque.x, 0.0, delta=0.05)


if __name__ == '__main__':
    rostest.rosrun('arm1', 'state_sensors', StateSensors)
