#!/usr/bin/env python
"""Pick by friction alone: a row of pick_arms (test/robots/pick_arm, arm:=false), one per object
of _arm1sim.goal.pick_place.OBJECTS, each closes its two-finger mimic gripper on its object on the
table, lifts it 0.1 m and holds it 5 s (sim time); the object must rise with >= 95 % of the
gripper's rise and slip <= 2 mm, in every one of ``tries`` tries, and fall once the gripper
opens. Between tries each object is put back on the table by /gazebo/set_model_state, a little
off centre and turned (a different grasp each try). Params: ``fingers`` (effort or position:
the fingers' hardware interface), ``grasp_plugin`` (the arms carry libgazebo_grasp_fix.so),
``tries``."""

import math
import os
import subprocess
import sys
import time

import actionlib
import rospy
import rostest
from control_msgs.msg import GripperCommandAction, GripperCommandGoal
from controller_manager_msgs.srv import LoadController, SwitchController
from gazebo_msgs.msg import ModelState
from gazebo_msgs.srv import GetLinkState, SetModelState
from geometry_msgs.msg import Point, Pose, Quaternion, Twist
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rostest_util import Recorder, SpawningTestCase, sim_wait, spawn_urdf, wait_for  # noqa: E402

from _arm1sim.goal.pick_place import HOLD_S, LIFT_RISE, OBJECTS, judge_hold, pick_lift  # noqa: E402
from _arm1sim.ros.common.packages import find_package  # noqa: E402

SPACING = 0.4  # m between the arms along y (the table in pick_rows.world is long enough)
REACH_X = 0.3  # where an arm:=false pick_arm's fingers are
CONTROLLERS = ['joint_state_controller', 'lift_controller', 'gripper_controller']
CLOSED, OPEN = 0.045, 0.0
SQUEEZE = 5.0  # N: max_effort of a closing goal (effort fingers)
# sim s: the fingers close in ~0.3 s and a goal ends stall_timeout (0.3 s) after they stop
GRIP_S = 2.0


def quat_z(yaw):
    return Quaternion(0, 0, math.sin(yaw / 2), math.cos(yaw / 2))


class Arm:
    """One pick_arm and the object it picks."""

    def __init__(self, index, obj, fingers, grasp_plugin):
        self.obj, self.name = obj, 'pick_%d' % index
        self.y = index * SPACING
        ns = '/' + self.name
        path = os.path.join(find_package('arm1'), 'test/robots/pick_arm')
        # The xacro command a launch file's $(find xacro)/xacro runs (PyPI's xacro lives in
        # the workspace's venv, not necessarily in this node's interpreter).
        xml = subprocess.check_output(
            [
                os.path.join(find_package('xacro'), 'xacro'),
                os.path.join(path, 'urdf/pick_arm.urdf.xacro'),
                'arm:=false',
                'fingers:=' + fingers,
                'ns:=' + ns,
                'grasp_plugin:=%s' % str(bool(grasp_plugin)).lower(),
            ],
            text=True,
        )
        rospy.set_param(ns + '/robot_description', xml)
        import yaml

        with open(os.path.join(path, 'config/controllers.yaml')) as f:
            controllers = yaml.safe_load(f)
        if fingers == 'position':
            controllers['gripper_controller']['type'] = (
                'position_controllers/GripperActionController'
            )
        rospy.set_param(ns, controllers)
        spawn_urdf(self.name, xml, ns, (0.0, self.y, 0.0))
        cm = ns + '/controller_manager/'
        rospy.wait_for_service(cm + 'switch_controller', 60)
        load = rospy.ServiceProxy(cm + 'load_controller', LoadController)
        for c in CONTROLLERS:
            assert load(c).ok, 'could not load %s in %s' % (c, ns)
        switch = rospy.ServiceProxy(cm + 'switch_controller', SwitchController)
        assert switch(start_controllers=CONTROLLERS, strictness=2).ok, 'could not start ' + ns
        self.lift_pub = rospy.Publisher(
            ns + '/lift_controller/command', JointTrajectory, queue_size=1
        )
        self.gripper = actionlib.SimpleActionClient(
            ns + '/gripper_controller/gripper_cmd', GripperCommandAction
        )
        assert self.gripper.wait_for_server(rospy.Duration(60)), 'no gripper_cmd in ' + ns
        spawn_urdf(obj.name, obj.urdf(), '', (REACH_X, self.y, 0.3))

    def lift_to(self, position, seconds):
        msg = JointTrajectory(joint_names=['lift_joint'])
        msg.points.append(
            # At rest at the end: a cubic from where the lift is, no jolt to shake the grip.
            JointTrajectoryPoint(
                positions=[position], velocities=[0.0], time_from_start=rospy.Duration(seconds)
            )
        )
        self.lift_pub.publish(msg)

    def grip(self, position):
        goal = GripperCommandGoal()
        goal.command.position, goal.command.max_effort = position, SQUEEZE
        self.gripper.send_goal(goal)

    def place_object(self, dx, dy, yaw):
        state = ModelState(model_name=self.obj.name, reference_frame='world')
        state.pose = Pose(
            Point(REACH_X + dx, self.y + dy, 0.2 + self.obj.height / 2 + 0.0005), quat_z(yaw)
        )
        state.twist = Twist()
        res = SET_STATE(state)
        assert res.success, res.status_message


def heights(arm):
    """World z of the palm (lift link) and of the object."""
    palm = GET_LINK(arm.name + '::lift', 'world').link_state.pose.position.z
    return palm, GET_LINK(arm.obj.name + '::link', 'world').link_state.pose.position.z


def offset(arm):
    """The object's z in the palm's frame: one reading, so both are of the same step."""
    return GET_LINK(arm.obj.name + '::link', arm.name + '::lift').link_state.pose.position.z


class Pick(SpawningTestCase):
    NODE = 'test_pick'
    SERVICES = SpawningTestCase.SERVICES + ('/gazebo/set_model_state', '/gazebo/get_link_state')

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        global SET_STATE, GET_LINK
        SET_STATE = rospy.ServiceProxy('/gazebo/set_model_state', SetModelState)
        GET_LINK = rospy.ServiceProxy('/gazebo/get_link_state', GetLinkState)
        cls.fingers = rospy.get_param('~fingers', 'effort')
        cls.tries = rospy.get_param('~tries', 10)
        grasp_plugin = rospy.get_param('~grasp_plugin', False)
        cls.events = None
        if grasp_plugin:
            from gazebo_grasp_plugin_ros.msg import GazeboGraspEvent

            cls.events = Recorder('/gazebo/grasp_events', GazeboGraspEvent)
        cls.arms = [Arm(i, o, cls.fingers, grasp_plugin) for i, o in enumerate(OBJECTS)]

    def wait_for_grips(self, k, failures):
        """All the closing goals at once, for GRIP_S sim s at most: each ends on its object
        (stalled there) or at the closed position; one still active is a failure."""
        start = rospy.Time.now()

        def ended():
            return all(a.gripper.simple_state == actionlib.SimpleGoalState.DONE for a in self.arms)

        wait_for(lambda: ended() or (rospy.Time.now() - start).to_sec() >= GRIP_S, 20 * GRIP_S + 5)
        for arm in self.arms:
            if arm.gripper.simple_state != actionlib.SimpleGoalState.DONE:
                failures.append(
                    'try %d %s: the closing goal still active after %g sim s'
                    % (k, arm.obj.name, GRIP_S)
                )

    def check_events(self, k, attached, failures):
        """With the grasp plugin: each object's last event says attached (held) or not."""
        for arm in self.arms:
            mine = [e for e in self.events.since(0) if e.object.startswith(arm.obj.name + '::')]
            if not mine or mine[-1].attached != attached:
                failures.append(
                    'try %d %s: no %s event from the grasp plugin'
                    % (k, arm.obj.name, 'attach' if attached else 'detach')
                )

    def test_objects_are_held_through_the_hold_and_fall_when_released(self):
        failures, lines = [], []
        for k in range(self.tries):
            wall, sim = time.time(), rospy.Time.now()
            # A different grasp each try: up to 3 mm off centre, up to 0.03 rad turned.
            dx, dy, yaw = 0.002 * math.sin(k), 0.003 * math.cos(1.7 * k), 0.03 * math.sin(2.3 * k)
            for arm in self.arms:
                arm.grip(OPEN)
                arm.lift_to(pick_lift(arm.obj), 0.8)
            sim_wait(1.0)
            for arm in self.arms:
                arm.place_object(dx, dy, yaw)
            sim_wait(0.3)
            for arm in self.arms:
                arm.grip(CLOSED)
            self.wait_for_grips(k, failures)
            sim_wait(0.3)
            before = [heights(arm) for arm in self.arms]
            for arm in self.arms:
                arm.lift_to(pick_lift(arm.obj) + LIFT_RISE, 2.0)
            sim_wait(2.3)
            after = [heights(arm) for arm in self.arms]
            offsets = [[offset(arm)] for arm in self.arms]
            for _ in range(int(HOLD_S)):
                sim_wait(1.0)
                for arm, o in zip(self.arms, offsets):
                    o.append(offset(arm))
            for arm, b, a, o in zip(self.arms, before, after, offsets):
                verdict = judge_hold(b[0], b[1], a[0], a[1], o)
                lines.append('try %d %s: %s' % (k, arm.obj.name, verdict))
                if not verdict.held:
                    failures.append(lines[-1])
            if self.events is not None:
                self.check_events(k, True, failures)
            for arm in self.arms:
                arm.grip(OPEN)
            sim_wait(0.8)
            if self.events is not None:
                sim_wait(1.0)  # the plugin lets go as its grip counter runs down
                self.check_events(k, False, failures)
            for arm, a in zip(self.arms, after):
                z = heights(arm)[1]
                if z > a[1] - 0.5 * LIFT_RISE:
                    failures.append(
                        'try %d %s: still at z %.3f after the gripper opened' % (k, arm.obj.name, z)
                    )
            # What a try costs, for the .test files' tries (sim s is fixed, wall s is the load's).
            lines.append(
                'try %d: %.1f sim s, %.1f wall s'
                % (k, (rospy.Time.now() - sim).to_sec(), time.time() - wall)
            )
        rospy.loginfo('\n'.join(lines))
        if self.events is not None:
            print('grasp events: %d' % len(self.events.since(0)))
        print('\n'.join(lines))
        self.assertEqual(failures, [], '\n'.join(failures))


if __name__ == '__main__':
    rostest.rosrun('arm1', 'pick', Pick)
