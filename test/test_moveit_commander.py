#!/usr/bin/env python
"""moveit_commander, as the MoveIt tutorials use it, on the move_group stand-in with a robot of
our own (test/robots/six_arm and six_arm_moveit_config, laid out as the Setup Assistant writes
them). argv: the config's launch file and its arguments (demo_gazebo.launch: executed on the
simulated arm through its ros_control controllers; demo.launch: MoveIt's fake controllers).
The launch file is started unchanged by this node, with test/robots on ROS_PACKAGE_PATH."""

import math
import os
import signal
import subprocess
import sys
import time
import unittest

import moveit_commander
import rospy
import rostest
from geometry_msgs.msg import Pose, PoseStamped
from moveit_commander import MoveItCommanderException
from moveit_commander.conversions import pose_to_list

HERE = os.path.dirname(os.path.abspath(__file__))
ROBOTS = os.path.join(HERE, 'robots')
ARM = ['joint%d' % i for i in range(1, 7)]
READY = [0.0, 0.4, 1.2, 0.0, 1.5, 0.0]  # the config's 'ready' state, where the arm starts
JOINT_GOAL = [0.3, 0.6, 0.9, 0.2, 1.0, -0.3]
CUBE = 0.03  # m, the picked box's edge
DOWN = (0.0, 1.0, 0.0, 0.0)  # tool z pointing down (half a turn about y: joint6 at 0)


def wait_for(predicate, timeout, poll=0.05):
    deadline = rospy.get_time() + timeout
    while not predicate():
        if rospy.get_time() > deadline or rospy.is_shutdown():
            return False
        rospy.sleep(poll)
    return True


def pose(x, y, z, q=DOWN):
    p = Pose()
    p.position.x, p.position.y, p.position.z = x, y, z
    p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w = q
    return p


class MoveItCommander(unittest.TestCase):
    launch = None

    @classmethod
    def setUpClass(cls):
        try:
            cls._set_up()
        except BaseException:  # tearDownClass does not run after a failed setUpClass
            cls._stop_launch()
            raise

    @classmethod
    def _set_up(cls):
        args = [a for a in sys.argv[1:] if not a.startswith('__') and not a.startswith('--gtest')]
        cls.sim = args[0] == 'demo_gazebo.launch'
        env = dict(os.environ)
        env['ROS_PACKAGE_PATH'] = ROBOTS + os.pathsep + env.get('ROS_PACKAGE_PATH', '')
        cls.log = open(
            os.path.join(
                os.environ.get('ROS_LOG_DIR', '/tmp'), 'moveit_%s.log' % args[0].split('.')[0]
            ),
            'w',
        )
        cls.launch = subprocess.Popen(
            ['roslaunch', 'six_arm_moveit_config'] + args,
            env=env,
            stdout=cls.log,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
        # the launch file sets the model and, with the world, /use_sim_time: read before
        # init_node, which takes the clock it will keep
        deadline = time.monotonic() + 60
        while not rospy.has_param('/robot_description_semantic') or (
            cls.sim and not rospy.has_param('/use_sim_time')
        ):
            assert time.monotonic() < deadline, 'the launch file never set the robot model'
            assert cls.launch.poll() is None, 'roslaunch exited (%s)' % cls.launch.returncode
            time.sleep(0.2)
        moveit_commander.roscpp_initialize(sys.argv)
        rospy.init_node('test_moveit_commander', anonymous=True)
        cls.robot = moveit_commander.RobotCommander()  # waits for nothing: the model only
        cls.scene = moveit_commander.PlanningSceneInterface()
        cls.arm = moveit_commander.MoveGroupCommander('arm', wait_for_servers=90.0)
        cls.hand = moveit_commander.MoveGroupCommander('hand', wait_for_servers=30.0)
        for g in (cls.arm, cls.hand):  # the config's defaults are 0.1: keep the test short
            g.set_max_velocity_scaling_factor(1.0)
            g.set_max_acceleration_scaling_factor(1.0)
        assert wait_for(lambda: cls._at(READY, 0.05), 60), 'the arm never reported its start'

    @classmethod
    def tearDownClass(cls):
        moveit_commander.roscpp_shutdown()
        cls._stop_launch()

    @classmethod
    def _stop_launch(cls):
        if cls.launch is not None and cls.launch.poll() is None:
            os.killpg(cls.launch.pid, signal.SIGINT)
            try:
                cls.launch.wait(20)
            except subprocess.TimeoutExpired:
                os.killpg(cls.launch.pid, signal.SIGKILL)
        if getattr(cls, 'log', None) is not None:
            cls.log.close()

    @classmethod
    def _at(cls, goal, tol):
        q = cls.arm.get_current_joint_values()
        return all(abs(a - b) <= tol for a, b in zip(q, goal))

    def assert_joints(self, goal, tol=0.01):
        self.assertTrue(
            wait_for(lambda: self._at(goal, tol), 5.0),
            'joints %s, goal %s' % (self.arm.get_current_joint_values(), goal),
        )

    def assert_position(self, xyz, tol=0.01):
        p = self.arm.get_current_pose().pose.position
        self.assertLess(math.dist((p.x, p.y, p.z), xyz), tol, 'tcp at %s, goal %s' % (p, xyz))

    def test_1_the_model_as_the_setup_assistant_wrote_it(self):
        self.assertEqual(sorted(self.robot.get_group_names()), ['arm', 'hand'])
        self.assertEqual(self.arm.get_planning_frame(), 'world')
        self.assertEqual(self.arm.get_end_effector_link(), 'tcp')
        self.assertEqual(self.arm.get_active_joints(), ARM)
        self.assertEqual(
            self.robot.get_link_names(group='hand'), ['hand', 'left_finger', 'right_finger']
        )
        self.assertEqual(self.hand.get_end_effector_link(), '')  # not a chain
        self.assertEqual(sorted(self.arm.get_named_targets()), ['home', 'ready'])
        state = self.robot.get_current_state()
        self.assertIn('left_finger_joint', state.joint_state.name)
        with self.assertRaises(MoveItCommanderException):
            self.arm.set_joint_value_target([0.0] * 5)  # six values expected
        with self.assertRaises(MoveItCommanderException):
            self.arm.set_joint_value_target([0.0, 2.5, 0.0, 0.0, 0.0, 0.0])  # joint2 > 1.7

    def test_2_joint_goal_planned_then_executed(self):
        self.arm.set_joint_value_target(JOINT_GOAL)
        ok, plan, planning_time, error = self.arm.plan()
        self.assertTrue(ok, 'error code %d' % error.val)
        self.assertEqual(error.val, 1)
        self.assertGreater(planning_time, 0.0)
        traj = plan.joint_trajectory
        self.assertEqual(list(traj.joint_names), ARM)
        self.assertGreaterEqual(len(traj.points), 2)
        for a, b in zip(traj.points[-1].positions, JOINT_GOAL):
            self.assertAlmostEqual(a, b, delta=1e-3)
        self.assertTrue(self._at(READY, 0.05), 'planning alone moved the arm')
        self.assertTrue(self.arm.execute(plan, wait=True))
        self.assert_joints(JOINT_GOAL)

    def test_3_named_goals(self):
        self.arm.set_named_target('home')
        self.assertTrue(self.arm.go(wait=True))
        self.arm.stop()
        self.assert_joints([0.0] * 6)
        self.arm.set_named_target('ready')
        self.assertTrue(self.arm.go(wait=True))
        self.assert_joints(READY)
        with self.assertRaises(MoveItCommanderException):
            self.arm.set_named_target('nowhere')

    def test_4_pose_goal(self):
        start = self.arm.get_current_pose().pose
        goal = pose(
            start.position.x - 0.05,
            start.position.y + 0.05,
            start.position.z + 0.05,
            pose_to_list(start)[3:],
        )
        self.arm.set_pose_target(goal)
        self.assertTrue(self.arm.go(wait=True))
        self.arm.stop()
        self.arm.clear_pose_targets()
        now = self.arm.get_current_pose().pose
        self.assert_position((goal.position.x, goal.position.y, goal.position.z))
        q0, q1 = pose_to_list(goal)[3:], pose_to_list(now)[3:]
        self.assertGreater(abs(sum(a * b for a, b in zip(q0, q1))), math.cos(0.01 / 2))

    def test_5_cartesian_path(self):
        self.assertTrue(self.arm.go(READY, wait=True))
        start = self.arm.get_current_pose().pose
        waypoints = []
        w = pose(
            start.position.x, start.position.y, start.position.z - 0.05, pose_to_list(start)[3:]
        )
        waypoints.append(w)
        w = pose(w.position.x, w.position.y + 0.08, w.position.z, pose_to_list(start)[3:])
        waypoints.append(w)
        plan, fraction = self.arm.compute_cartesian_path(waypoints, 0.01, 0.0)
        self.assertAlmostEqual(fraction, 1.0, delta=1e-6)
        self.assertGreaterEqual(len(plan.joint_trajectory.points), 13)  # 0.13 m at 1 cm steps
        self.assertTrue(self._at(READY, 0.02), 'computing the path moved the arm')
        self.assertTrue(self.arm.execute(plan, wait=True))
        self.assert_position((w.position.x, w.position.y, w.position.z))

    def test_6_box_added_attached_detached_removed(self):
        box = PoseStamped()
        box.header.frame_id = 'tcp'
        box.pose.orientation.w = 1.0
        box.pose.position.z = 0.05
        self.scene.add_box('box', box, size=(0.04, 0.04, 0.04))
        self.assertTrue(wait_for(lambda: 'box' in self.scene.get_known_object_names(), 4))
        obj = self.scene.get_objects(['box'])['box']
        self.assertEqual(list(obj.primitives[0].dimensions), [0.04, 0.04, 0.04])
        touch = self.robot.get_link_names(group='hand')
        self.scene.attach_box('tcp', 'box', touch_links=touch)
        self.assertTrue(wait_for(lambda: 'box' in self.scene.get_attached_objects(['box']), 4))
        self.assertNotIn('box', self.scene.get_known_object_names())
        self.assertEqual(list(self.scene.get_attached_objects()['box'].touch_links), touch)
        self.scene.remove_attached_object('tcp', name='box')
        self.assertTrue(wait_for(lambda: 'box' in self.scene.get_known_object_names(), 4))
        self.assertEqual(self.scene.get_attached_objects(['box']), {})
        self.scene.remove_world_object('box')
        self.assertTrue(wait_for(lambda: 'box' not in self.scene.get_known_object_names(), 4))

    def test_7_pick_and_place_through_the_planning_scene(self):
        here, there = (0.35, 0.0), (0.3, 0.2)
        if self.sim:
            self._spawn_cube(here)
        cube = PoseStamped()
        cube.header.frame_id = 'world'
        cube.pose.position.x, cube.pose.position.y, cube.pose.position.z = here + (CUBE / 2,)
        cube.pose.orientation.w = 1.0
        self.scene.add_box('cube', cube, size=(CUBE, CUBE, CUBE))
        self.assertTrue(wait_for(lambda: 'cube' in self.scene.get_known_object_names(), 4))
        self.hand.set_named_target('open')
        self.assertTrue(self.hand.go(wait=True))
        # above the cube (planned around it), then straight down with the fingers about it
        self.arm.set_pose_target(pose(here[0], here[1], 0.15))
        self.assertTrue(self.arm.go(wait=True))
        self.arm.clear_pose_targets()
        self._line(here + (CUBE / 2,))
        # attached first, with the hand's links as touch links: closing on it is then allowed
        self.scene.attach_box('tcp', 'cube', touch_links=self.robot.get_link_names(group='hand'))
        self.assertTrue(wait_for(lambda: 'cube' in self.scene.get_attached_objects(), 4))
        self.hand.set_named_target('close')
        self.hand.go(wait=True)  # on the simulated arm the fingers stop on the cube
        fingers = self.hand.get_current_joint_values()
        if self.sim:
            self.assertGreater(fingers[0], 0.01, 'the fingers did not close: %s' % fingers)
            self.assertLess(fingers[0], 0.03, 'the fingers closed through the cube: %s' % fingers)
        self._line(here + (0.12,))
        if self.sim:
            self.assertGreater(self._cube_z(), 0.08, 'the cube was not lifted')
        self._line(there + (0.12,))
        self._line(there + (CUBE / 2 + 0.002,))
        self.hand.set_named_target('open')
        self.assertTrue(self.hand.go(wait=True))
        self.scene.remove_attached_object('tcp', name='cube')
        self.assertTrue(wait_for(lambda: 'cube' in self.scene.get_known_object_names(), 4))
        self._line(there + (0.12,))
        placed = self.scene.get_object_poses(['cube'])['cube'].position
        self.assertLess(math.dist((placed.x, placed.y), there), 0.01)
        if self.sim:
            from gazebo_msgs.srv import GetModelState

            p = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)('cube', 'world').pose
            self.assertLess(math.dist((p.position.x, p.position.y), there), 0.02, p)
            self.assertLess(p.position.z, CUBE, 'the cube is not on the floor: %s' % p)
        self.scene.remove_world_object('cube')

    def test_8_move_group_names_and_types_as_upstream(self):
        """MoveIt's names (move_group/capability_names.h) with moveit_msgs' types: a client
        built against upstream finds each one (md5sums: test/unit's moveit_msgs test)."""
        import rosgraph
        import rosservice
        from moveit_msgs import srv

        types = dict(rosgraph.Master('/test_moveit_commander').getTopicTypes())
        for topic, kind in [
            ('/move_group/goal', 'moveit_msgs/MoveGroupActionGoal'),
            ('/execute_trajectory/goal', 'moveit_msgs/ExecuteTrajectoryActionGoal'),
            ('/move_group/display_planned_path', 'moveit_msgs/DisplayTrajectory'),
            ('/move_group/monitored_planning_scene', 'moveit_msgs/PlanningScene'),
        ]:
            self.assertEqual(types.get(topic), kind, topic)
        for name, cls in [
            ('/compute_fk', srv.GetPositionFK),
            ('/compute_ik', srv.GetPositionIK),
            ('/compute_cartesian_path', srv.GetCartesianPath),
            ('/plan_kinematic_path', srv.GetMotionPlan),
            ('/get_planning_scene', srv.GetPlanningScene),
            ('/apply_planning_scene', srv.ApplyPlanningScene),
            ('/check_state_validity', srv.GetStateValidity),
            ('/query_planner_interface', srv.QueryPlannerInterfaces),
        ]:
            headers = rosservice.get_service_headers(name, rosservice.get_service_uri(name))
            self.assertEqual(headers.get('type'), cls._type, name)
            self.assertEqual(headers.get('md5sum'), cls._md5sum, name)

    def test_9_pick_and_place_actions(self):
        """pick() and place() through move_group's pickup and place actions, with a grasp and
        a place pose of the script's own (a planning-scene object, away from test 7's cube)."""
        from moveit_msgs.msg import Grasp
        from trajectory_msgs.msg import JointTrajectoryPoint

        part = PoseStamped()
        part.header.frame_id = 'world'
        part.pose.position.x, part.pose.position.y, part.pose.position.z = 0.35, -0.15, CUBE / 2
        part.pose.orientation.w = 1.0
        self.scene.add_box('part', part, size=(CUBE, CUBE, CUBE))
        self.assertTrue(wait_for(lambda: 'part' in self.scene.get_known_object_names(), 4))
        g = Grasp(id='from_above')
        g.grasp_pose.header.frame_id = 'world'
        g.grasp_pose.pose = pose(0.35, -0.15, CUBE / 2)
        for motion, z in ((g.pre_grasp_approach, -1.0), (g.post_grasp_retreat, 1.0)):
            motion.direction.header.frame_id = 'world'
            motion.direction.vector.z = z
            motion.min_distance, motion.desired_distance = 0.05, 0.08
        for posture, q in ((g.pre_grasp_posture, 0.0), (g.grasp_posture, 0.03)):
            posture.joint_names = ['left_finger_joint']
            posture.points = [
                JointTrajectoryPoint(positions=[q], time_from_start=rospy.Duration(0.5))
            ]
        self.assertTrue(self.arm.pick('part', [g]))
        self.assertIn('part', self.scene.get_attached_objects())
        goal = PoseStamped()
        goal.header.frame_id = 'world'
        goal.pose.position.x, goal.pose.position.y, goal.pose.position.z = 0.25, -0.25, CUBE / 2
        goal.pose.orientation.w = 1.0
        self.assertTrue(self.arm.place('part', goal))
        self.assertEqual(self.scene.get_attached_objects(['part']), {})
        placed = self.scene.get_object_poses(['part'])['part'].position
        self.assertLess(math.dist((placed.x, placed.y), (0.25, -0.25)), 0.02, placed)
        self.scene.remove_world_object('part')

    def _line(self, xyz):
        """The tcp straight to xyz (pointing down), as a Cartesian path, executed."""
        plan, fraction = self.arm.compute_cartesian_path([pose(*xyz)], 0.01, 0.0)
        self.assertAlmostEqual(fraction, 1.0, delta=1e-6, msg='path to %s' % (xyz,))
        self.assertTrue(self.arm.execute(plan, wait=True))
        self.assert_position(xyz)

    def _spawn_cube(self, xy):
        from gazebo_msgs.srv import SpawnModel

        rospy.wait_for_service('/gazebo/spawn_sdf_model', 30)
        inertia = 0.05 * CUBE * CUBE / 6
        sdf = (
            '<sdf version="1.6"><model name="cube"><link name="link">'
            '<inertial><mass>0.05</mass><inertia><ixx>{i}</ixx><iyy>{i}</iyy><izz>{i}</izz>'
            '</inertia></inertial>'
            '<collision name="c"><geometry><box><size>{s} {s} {s}</size></box></geometry>'
            '<surface><friction><ode><mu>1.0</mu><mu2>1.0</mu2></ode></friction></surface>'
            '</collision><visual name="v"><geometry><box><size>{s} {s} {s}</size></box>'
            '</geometry></visual></link></model></sdf>'
        ).format(i=inertia, s=CUBE)
        p = Pose()
        p.position.x, p.position.y, p.position.z = xy[0], xy[1], CUBE / 2
        p.orientation.w = 1.0
        res = rospy.ServiceProxy('/gazebo/spawn_sdf_model', SpawnModel)('cube', sdf, '', p, 'world')
        self.assertTrue(res.success, res.status_message)

    def _cube_z(self):
        from gazebo_msgs.srv import GetModelState

        return rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)(
            'cube', 'world'
        ).pose.position.z


if __name__ == '__main__':
    rostest.rosrun('arm1', 'test_moveit_commander', MoveItCommander)
