#!/usr/bin/env python
"""The move_group stand-in under a real master (arm1_move_group.test): MoveIt's services and
actions under their names and types; a joint goal planned and executed on the simulated arm
through its FollowJointTrajectory controller; a named hand state through GripperCommand; a
pose goal, IK and FK agreeing; a box added, found in the planning scene, in collision,
attached, detached and removed; a Cartesian path executed through execute_trajectory; a
trajectory starting away from the arm refused as MoveIt refuses it; bad requests answered;
a second move_group (/rc) with the ros_control controller manager executing."""

import os
import sys

import actionlib
import numpy as np
import rospy
import rosservice
import rostest
from geometry_msgs.msg import Pose, PoseStamped
from moveit_msgs.msg import (
    AttachedCollisionObject,
    CollisionObject,
    Constraints,
    DisplayTrajectory,
    ExecuteTrajectoryAction,
    ExecuteTrajectoryGoal,
    JointConstraint,
    MoveGroupAction,
    MoveGroupGoal,
    MoveItErrorCodes,
    OrientationConstraint,
    PlanningSceneComponents,
    PositionConstraint,
    RobotState,
)
from moveit_msgs.srv import (
    GetCartesianPath,
    GetCartesianPathRequest,
    GetMotionPlan,
    GetMotionPlanRequest,
    GetPlanningScene,
    GetPositionFK,
    GetPositionIK,
    GetPositionIKRequest,
    GetStateValidity,
    GetStateValidityRequest,
)
from sensor_msgs.msg import JointState
from shape_msgs.msg import SolidPrimitive
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rostest_util import Recorder, WorldTestCase, wait_for, wait_for_controllers  # noqa: E402

ARM = ['toy_joint%d' % i for i in range(1, 8)]
READY = [0.0, -0.785398163, 0.0, -2.35619449, 0.0, 1.57079632679, 0.785398163397]
GOAL = [0.4, -0.5, 0.2, -2.0, 0.2, 1.8, 0.5]
SERVICES = {
    'plan_kinematic_path': 'moveit_msgs/GetMotionPlan',
    'compute_ik': 'moveit_msgs/GetPositionIK',
    'compute_fk': 'moveit_msgs/GetPositionFK',
    'compute_cartesian_path': 'moveit_msgs/GetCartesianPath',
    'check_state_validity': 'moveit_msgs/GetStateValidity',
    'get_planning_scene': 'moveit_msgs/GetPlanningScene',
    'apply_planning_scene': 'moveit_msgs/ApplyPlanningScene',
    'query_planner_interface': 'moveit_msgs/QueryPlannerInterfaces',
    'get_planner_params': 'moveit_msgs/GetPlannerParams',
    'set_planner_params': 'moveit_msgs/SetPlannerParams',
    'clear_octomap': 'std_srvs/Empty',
}


def joint_goal(group, names, values):
    goal = MoveGroupGoal()
    goal.request.group_name = group
    goal.request.allowed_planning_time = 10.0
    goal.request.num_planning_attempts = 1
    goal.request.max_velocity_scaling_factor = 0.5
    goal.request.max_acceleration_scaling_factor = 0.5
    goal.request.start_state.is_diff = True
    c = Constraints()
    for n, v in zip(names, values):
        c.joint_constraints.append(
            JointConstraint(
                joint_name=n, position=v, tolerance_above=1e-4, tolerance_below=1e-4, weight=1.0
            )
        )
    goal.request.goal_constraints.append(c)
    goal.planning_options.planning_scene_diff.is_diff = True
    goal.planning_options.planning_scene_diff.robot_state.is_diff = True
    return goal


class MoveGroupTest(WorldTestCase):
    NODE = 'test_move_group'

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.joints = Recorder('/joint_states', JointState)
        cls.display = Recorder('/move_group/display_planned_path', DisplayTrajectory)
        wait_for_controllers(3, '')
        assert wait_for(
            lambda: cls.joints.last() is not None and 'toy_finger_joint1' in cls.joints.last().name,
            60,
        )
        for name in SERVICES:
            rospy.wait_for_service(name, 60)
        cls.move = actionlib.SimpleActionClient('move_group', MoveGroupAction)
        cls.execute = actionlib.SimpleActionClient('execute_trajectory', ExecuteTrajectoryAction)
        assert cls.move.wait_for_server(rospy.Duration(60))
        assert cls.execute.wait_for_server(rospy.Duration(60))
        cls.fk = rospy.ServiceProxy('compute_fk', GetPositionFK)
        cls.ik = rospy.ServiceProxy('compute_ik', GetPositionIK)

    def position(self, names):
        msg = self.joints.last()
        values = dict(zip(msg.name, msg.position))
        return np.array([values[n] for n in names])

    def link_pose(self, link, names=None, values=None):
        state = RobotState()
        if names:
            state.joint_state.name, state.joint_state.position = list(names), list(values)
        reply = self.fk(
            header=rospy.Header(frame_id='world'), fk_link_names=[link], robot_state=state
        )
        self.assertEqual(reply.error_code.val, MoveItErrorCodes.SUCCESS)
        return reply.pose_stamped[0].pose

    def test_01_moveit_names_and_types(self):
        for name, kind in SERVICES.items():
            self.assertEqual(rosservice.get_service_type('/' + name), kind)

    def test_02_joint_goal_planned_and_executed(self):
        since = len(self.display.since(0))
        self.move.send_goal(joint_goal('toy_arm', ARM, GOAL))
        self.assertTrue(self.move.wait_for_result(rospy.Duration(90)))
        result = self.move.get_result()
        self.assertEqual(result.error_code.val, MoveItErrorCodes.SUCCESS)
        traj = result.planned_trajectory.joint_trajectory
        self.assertEqual(traj.joint_names, ARM)
        times = [p.time_from_start.to_sec() for p in traj.points]
        self.assertTrue(all(b > a for a, b in zip(times, times[1:])))
        np.testing.assert_allclose(traj.points[-1].positions, GOAL, atol=1e-3)
        # settled where it was sent (the effort controller's goal tolerance is loose)
        self.assertTrue(wait_for(lambda: np.max(np.abs(self.position(ARM) - GOAL)) < 0.03, 10))
        self.assertGreater(len(self.display.since(0)), since)

    def test_03_named_hand_state_through_the_gripper_controller(self):
        names = ['toy_finger_joint1', 'toy_finger_joint2']
        self.move.send_goal(joint_goal('hand', names, [0.03, 0.03]))
        self.assertTrue(self.move.wait_for_result(rospy.Duration(60)))
        self.assertEqual(self.move.get_result().error_code.val, MoveItErrorCodes.SUCCESS)
        self.assertTrue(wait_for(lambda: np.all(np.abs(self.position(names) - 0.03) < 0.005), 10))

    def test_04_pose_goal_ik_and_fk_agree(self):
        target = self.link_pose('toy_link8', ARM, READY)
        ik = GetPositionIKRequest()
        ik.ik_request.group_name = 'toy_arm'
        ik.ik_request.avoid_collisions = True
        ik.ik_request.pose_stamped = PoseStamped(header=rospy.Header(frame_id='world'), pose=target)
        reply = self.ik(ik)
        self.assertEqual(reply.error_code.val, MoveItErrorCodes.SUCCESS)
        sol = dict(zip(reply.solution.joint_state.name, reply.solution.joint_state.position))
        got = self.link_pose('toy_link8', ARM, [sol[j] for j in ARM])
        self.assertLess(abs(got.position.z - target.position.z), 1e-3)
        # plan_kinematic_path to the pose (plan only)
        req = GetMotionPlanRequest()
        r = req.motion_plan_request
        r.group_name = 'toy_arm'
        r.allowed_planning_time = 10.0
        r.start_state.is_diff = True
        c = Constraints()
        pc = PositionConstraint(link_name='toy_link8', weight=1.0)
        pc.header.frame_id = 'world'
        pc.constraint_region.primitives.append(
            SolidPrimitive(type=SolidPrimitive.SPHERE, dimensions=[1e-4])
        )
        pc.constraint_region.primitive_poses.append(
            Pose(position=target.position, orientation=target.orientation)
        )
        oc = OrientationConstraint(
            link_name='toy_link8', orientation=target.orientation, weight=1.0
        )
        oc.header.frame_id = 'world'
        oc.absolute_x_axis_tolerance = oc.absolute_y_axis_tolerance = (
            oc.absolute_z_axis_tolerance
        ) = 1e-3
        c.position_constraints.append(pc)
        c.orientation_constraints.append(oc)
        r.goal_constraints.append(c)
        res = rospy.ServiceProxy('plan_kinematic_path', GetMotionPlan)(req).motion_plan_response
        self.assertEqual(res.error_code.val, MoveItErrorCodes.SUCCESS)
        end = res.trajectory.joint_trajectory.points[-1].positions
        reached = self.link_pose('toy_link8', ARM, end)
        self.assertLess(
            np.linalg.norm(
                [
                    reached.position.x - target.position.x,
                    reached.position.y - target.position.y,
                    reached.position.z - target.position.z,
                ]
            ),
            2e-3,
        )

    def test_05_box_added_in_collision_attached_detached_removed(self):
        scene = rospy.ServiceProxy('get_planning_scene', GetPlanningScene)
        hand = self.link_pose('toy_hand')
        co = CollisionObject(id='box', operation=CollisionObject.ADD)
        co.header.frame_id = 'world'
        co.pose = Pose(position=hand.position)
        co.pose.orientation.w = 1.0
        co.primitives.append(SolidPrimitive(type=SolidPrimitive.BOX, dimensions=[0.05, 0.05, 0.05]))
        co.primitive_poses.append(Pose())
        co.primitive_poses[0].orientation.w = 1.0
        pub = rospy.Publisher('collision_object', CollisionObject, queue_size=10, latch=True)
        pub.publish(co)
        names = PlanningSceneComponents(components=PlanningSceneComponents.WORLD_OBJECT_NAMES)

        def world_names():
            return [o.id for o in scene(components=names).scene.world.collision_objects]

        self.assertTrue(wait_for(lambda: 'box' in world_names(), 10))
        validity = rospy.ServiceProxy('check_state_validity', GetStateValidity)
        v = validity(GetStateValidityRequest(group_name='toy_arm'))
        self.assertFalse(v.valid)
        self.assertIn(
            'box', {c.contact_body_1 for c in v.contacts} | {c.contact_body_2 for c in v.contacts}
        )
        # attached to the hand, touching the fingers: no longer a collision
        aco = AttachedCollisionObject(
            link_name='toy_hand', touch_links=['toy_hand', 'toy_leftfinger', 'toy_rightfinger']
        )
        aco.object = CollisionObject(id='box', operation=CollisionObject.ADD)
        attach = rospy.Publisher(
            'attached_collision_object', AttachedCollisionObject, queue_size=10, latch=True
        )
        attach.publish(aco)
        attached = PlanningSceneComponents(
            components=PlanningSceneComponents.ROBOT_STATE_ATTACHED_OBJECTS
        )

        def attached_names():
            return [
                a.object.id
                for a in scene(components=attached).scene.robot_state.attached_collision_objects
            ]

        self.assertTrue(wait_for(lambda: attached_names() == ['box'], 10))
        self.assertNotIn('box', world_names())
        self.assertTrue(validity(GetStateValidityRequest(group_name='toy_arm')).valid)
        aco.object.operation = CollisionObject.REMOVE
        attach.publish(aco)
        self.assertTrue(wait_for(lambda: 'box' in world_names() and not attached_names(), 10))
        co.operation = CollisionObject.REMOVE
        pub.publish(co)
        self.assertTrue(wait_for(lambda: 'box' not in world_names(), 10))

    def test_06_cartesian_path_executed(self):
        start = self.link_pose('toy_link8')
        down = Pose(position=start.position, orientation=start.orientation)
        down.position.z -= 0.05
        req = GetCartesianPathRequest(
            group_name='toy_arm',
            link_name='toy_link8',
            max_step=0.01,
            jump_threshold=0.0,
            avoid_collisions=True,
        )
        req.header.frame_id = 'world'
        req.start_state.is_diff = True
        req.waypoints = [down]
        res = rospy.ServiceProxy('compute_cartesian_path', GetCartesianPath)(req)
        self.assertEqual(res.error_code.val, MoveItErrorCodes.SUCCESS)
        self.assertEqual(res.fraction, 1.0)
        self.assertGreaterEqual(len(res.solution.joint_trajectory.points), 6)
        self.execute.send_goal(ExecuteTrajectoryGoal(trajectory=res.solution))
        self.assertTrue(self.execute.wait_for_result(rospy.Duration(60)))
        self.assertEqual(self.execute.get_result().error_code.val, MoveItErrorCodes.SUCCESS)
        self.assertTrue(
            wait_for(
                lambda: abs(self.link_pose('toy_link8').position.z - down.position.z) < 0.01, 10
            )
        )

    def test_07_trajectory_starting_away_from_the_arm_is_refused(self):
        req = GetMotionPlanRequest()
        r = req.motion_plan_request
        r.group_name = 'toy_arm'
        r.start_state.joint_state.name = ARM
        r.start_state.joint_state.position = READY
        r.goal_constraints.append(
            Constraints(
                joint_constraints=[
                    JointConstraint(
                        joint_name='toy_joint1',
                        position=0.2,
                        tolerance_above=1e-4,
                        tolerance_below=1e-4,
                    )
                ]
            )
        )
        res = rospy.ServiceProxy('plan_kinematic_path', GetMotionPlan)(req).motion_plan_response
        self.assertEqual(res.error_code.val, MoveItErrorCodes.SUCCESS)
        self.execute.send_goal(ExecuteTrajectoryGoal(trajectory=res.trajectory))
        self.assertTrue(self.execute.wait_for_result(rospy.Duration(30)))
        self.assertEqual(self.execute.get_result().error_code.val, MoveItErrorCodes.CONTROL_FAILED)

    def test_08_bad_requests_answered_and_the_node_keeps_serving(self):
        ik = GetPositionIKRequest()
        ik.ik_request.group_name = 'toy_arm'
        ik.ik_request.ik_link_name = 'no_such_link'
        ik.ik_request.pose_stamped.pose.orientation.w = 1.0
        self.assertEqual(self.ik(ik).error_code.val, MoveItErrorCodes.INVALID_LINK_NAME)
        ik.ik_request.group_name = 'no_such_group'
        self.assertEqual(self.ik(ik).error_code.val, MoveItErrorCodes.INVALID_GROUP_NAME)
        bad = CollisionObject(id='bad', operation=CollisionObject.ADD)
        bad.primitives.append(SolidPrimitive(type=99, dimensions=[1.0]))
        bad.primitive_poses.append(Pose())
        pub = rospy.Publisher('collision_object', CollisionObject, queue_size=10, latch=True)
        pub.publish(bad)
        rospy.sleep(0.5)
        scene = rospy.ServiceProxy('get_planning_scene', GetPlanningScene)
        names = PlanningSceneComponents(components=PlanningSceneComponents.WORLD_OBJECT_NAMES)
        self.assertNotIn(
            'bad', [o.id for o in scene(components=names).scene.world.collision_objects]
        )
        self.link_pose('toy_link8')  # still answering

    def test_09_ros_control_manager_executes_through_the_running_controllers(self):
        rospy.wait_for_service('/rc/plan_kinematic_path', 60)
        now = self.position(ARM)
        target = list(now)
        target[0] += 0.2
        req = GetMotionPlanRequest()
        r = req.motion_plan_request
        r.group_name = 'toy_arm'
        r.start_state.is_diff = True
        r.max_velocity_scaling_factor = 0.5
        r.goal_constraints.append(
            Constraints(
                joint_constraints=[
                    JointConstraint(
                        joint_name=n, position=v, tolerance_above=1e-4, tolerance_below=1e-4
                    )
                    for n, v in zip(ARM, target)
                ]
            )
        )
        res = rospy.ServiceProxy('/rc/plan_kinematic_path', GetMotionPlan)(req).motion_plan_response
        self.assertEqual(res.error_code.val, MoveItErrorCodes.SUCCESS)
        client = actionlib.SimpleActionClient('/rc/execute_trajectory', ExecuteTrajectoryAction)
        self.assertTrue(client.wait_for_server(rospy.Duration(30)))
        client.send_goal(ExecuteTrajectoryGoal(trajectory=res.trajectory))
        self.assertTrue(client.wait_for_result(rospy.Duration(60)))
        self.assertEqual(client.get_result().error_code.val, MoveItErrorCodes.SUCCESS)
        self.assertTrue(wait_for(lambda: abs(self.position(ARM)[0] - target[0]) < 0.03, 10))

    def test_10_pickup_and_place_actions(self):
        from geometry_msgs.msg import Vector3
        from moveit_msgs.msg import (
            Grasp,
            PickupAction,
            PickupGoal,
            PlaceAction,
            PlaceGoal,
            PlaceLocation,
        )

        scene = rospy.ServiceProxy('get_planning_scene', GetPlanningScene)
        here, there = (0.4, 0.0, 0.3), (0.4, 0.2, 0.3)
        co = CollisionObject(id='cube', operation=CollisionObject.ADD)
        co.header.frame_id = 'world'
        co.pose.position.x, co.pose.position.y, co.pose.position.z = here
        co.pose.orientation.w = 1.0
        co.primitives.append(SolidPrimitive(type=SolidPrimitive.BOX, dimensions=[0.03] * 3))
        rospy.Publisher('collision_object', CollisionObject, queue_size=10, latch=True).publish(co)
        geometry = PlanningSceneComponents(components=PlanningSceneComponents.WORLD_OBJECT_GEOMETRY)

        def world():
            return {o.id: o for o in scene(components=geometry).scene.world.collision_objects}

        self.assertTrue(wait_for(lambda: 'cube' in world(), 10))
        flange = self.link_pose('toy_link8', ARM, READY).orientation  # the hand pointing down
        fingers = ['toy_finger_joint1', 'toy_finger_joint2']

        def posture(width):
            return JointTrajectory(
                joint_names=fingers,
                points=[
                    JointTrajectoryPoint(
                        positions=[width, width], time_from_start=rospy.Duration(1.0)
                    )
                ],
            )

        def down_up(approach, retreat):
            for motion, sign in ((approach, -1.0), (retreat, 1.0)):
                motion.direction.header.frame_id = 'world'
                motion.direction.vector = Vector3(0.0, 0.0, sign)
                motion.desired_distance, motion.min_distance = 0.08, 0.05

        grasp = Grasp(
            id='top',
            grasp_quality=1.0,
            pre_grasp_posture=posture(0.035),
            grasp_posture=posture(0.012),
        )
        grasp.grasp_pose.header.frame_id = 'world'
        grasp.grasp_pose.pose.position.x, grasp.grasp_pose.pose.position.y = here[:2]
        grasp.grasp_pose.pose.position.z = here[2] + 0.0884  # the finger pads about the cube
        grasp.grasp_pose.pose.orientation = flange
        down_up(grasp.pre_grasp_approach, grasp.post_grasp_retreat)
        pick = actionlib.SimpleActionClient('pickup', PickupAction)
        self.assertTrue(pick.wait_for_server(rospy.Duration(30)))
        pick.send_goal(
            PickupGoal(
                target_name='cube',
                group_name='toy_arm',
                possible_grasps=[grasp],
                allowed_planning_time=10.0,
            )
        )
        self.assertTrue(pick.wait_for_result(rospy.Duration(120)))
        result = pick.get_result()
        self.assertEqual(result.error_code.val, MoveItErrorCodes.SUCCESS)
        self.assertEqual(
            result.trajectory_descriptions, ['plan', 'pre_grasp', 'approach', 'grasp', 'retreat']
        )
        self.assertNotIn('cube', world())
        attached = PlanningSceneComponents(
            components=PlanningSceneComponents.ROBOT_STATE_ATTACHED_OBJECTS
        )
        held = scene(components=attached).scene.robot_state.attached_collision_objects
        self.assertEqual([(a.object.id, a.link_name) for a in held], [('cube', 'toy_link8')])
        location = PlaceLocation(id='left', quality=1.0, post_place_posture=posture(0.035))
        location.place_pose.header.frame_id = 'world'
        (
            location.place_pose.pose.position.x,
            location.place_pose.pose.position.y,
            location.place_pose.pose.position.z,
        ) = there
        location.place_pose.pose.orientation.w = 1.0
        down_up(location.pre_place_approach, location.post_place_retreat)
        place = actionlib.SimpleActionClient('place', PlaceAction)
        self.assertTrue(place.wait_for_server(rospy.Duration(30)))
        place.send_goal(
            PlaceGoal(
                attached_object_name='cube',
                group_name='toy_arm',
                place_locations=[location],
                allowed_planning_time=10.0,
            )
        )
        self.assertTrue(place.wait_for_result(rospy.Duration(120)))
        self.assertEqual(place.get_result().error_code.val, MoveItErrorCodes.SUCCESS)
        cube = world().get('cube')
        self.assertIsNotNone(cube)
        got = cube.pose.position
        self.assertLess(
            np.linalg.norm([got.x - there[0], got.y - there[1], got.z - there[2]]), 0.02
        )

    def test_11_a_goals_scene_diff_and_start_attached_bodies_hold_for_that_plan(self):
        goal = joint_goal('toy_arm', ARM, READY[:1] + [0.3] + READY[2:])
        goal.planning_options.plan_only = True
        self.assertTrue(self.move.send_goal_and_wait(goal, rospy.Duration(60)) is not None)
        self.assertEqual(self.move.get_result().error_code.val, MoveItErrorCodes.SUCCESS)
        hand = self.link_pose('toy_hand', ARM, READY[:1] + [0.3] + READY[2:])
        co = CollisionObject(id='ghost', operation=CollisionObject.ADD)
        co.header.frame_id = 'world'
        co.pose = Pose(position=hand.position)
        co.pose.orientation.w = 1.0
        co.primitives.append(SolidPrimitive(type=SolidPrimitive.SPHERE, dimensions=[0.1]))
        goal.planning_options.planning_scene_diff.world.collision_objects.append(co)
        self.move.send_goal_and_wait(goal, rospy.Duration(60))
        self.assertEqual(self.move.get_result().error_code.val, MoveItErrorCodes.GOAL_IN_COLLISION)
        scene = rospy.ServiceProxy('get_planning_scene', GetPlanningScene)
        names = PlanningSceneComponents(components=PlanningSceneComponents.WORLD_OBJECT_NAMES)
        self.assertNotIn(
            'ghost', [o.id for o in scene(components=names).scene.world.collision_objects]
        )
        # a start state's attached body: part of that state only (a big plate through the arm)
        req = GetMotionPlanRequest()
        r = req.motion_plan_request
        r.group_name = 'toy_arm'
        r.start_state.is_diff = True
        r.goal_constraints.append(goal.request.goal_constraints[0])
        plate = AttachedCollisionObject(link_name='toy_hand')
        plate.object = CollisionObject(id='plate', operation=CollisionObject.ADD)
        plate.object.header.frame_id = 'toy_hand'
        plate.object.pose.orientation.w = 1.0
        plate.object.primitives.append(
            SolidPrimitive(type=SolidPrimitive.BOX, dimensions=[0.8, 0.8, 0.02])
        )
        r.start_state.attached_collision_objects.append(plate)
        plan = rospy.ServiceProxy('plan_kinematic_path', GetMotionPlan)
        self.assertEqual(
            plan(req).motion_plan_response.error_code.val, MoveItErrorCodes.START_STATE_IN_COLLISION
        )
        r.start_state.attached_collision_objects = []
        self.assertEqual(plan(req).motion_plan_response.error_code.val, MoveItErrorCodes.SUCCESS)
        attached = PlanningSceneComponents(
            components=PlanningSceneComponents.ROBOT_STATE_ATTACHED_OBJECTS
        )
        self.assertEqual(
            scene(components=attached).scene.robot_state.attached_collision_objects, []
        )


if __name__ == '__main__':
    rostest.rosrun('arm1', 'move_group', MoveGroupTest)
