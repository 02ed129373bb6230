"""pick_place_demo: pick_arm (test/robots/pick_arm) picks a box from the table and puts it down
elsewhere, printing a live table of the box's and the gripper's heights.

Run against `roslaunch arm1 pick_place.launch demo:=false` (the launch runs this node itself
by default). The box is spawned by this node on the table at the pick spot; the arm moves
through FollowJointTrajectory goals and closes with a GripperCommand, as MoveIt would; the
box is held by friction alone. Exits 0 if the box was carried and set down at the place spot.
"""

from __future__ import annotations

import argparse
import math
import sys
import threading
from typing import List, Optional, Sequence, Tuple

import actionlib
import rospy
from control_msgs.msg import (
    FollowJointTrajectoryAction,
    GripperCommandAction,
    GripperCommandGoal,
)
from gazebo_msgs.srv import GetLinkState, SpawnModel
from geometry_msgs.msg import Point, Pose, Quaternion

from ...goal.pick_place import LIFT_RISE, OBJECTS, TABLE_TOP, pick_lift
from .trajectory_demo import make_goal

JOINTS = ['turret_joint', 'reach_joint', 'lift_joint']
REACH = 0.1  # reach_joint: the fingers 0.3 m from the column
PICK_TURRET, PLACE_TURRET = -0.6, 0.6  # rad: either side of the table's middle
FINGERS_OPEN, FINGERS_CLOSED, SQUEEZE = 0.0, 0.045, 5.0
OBJECT = OBJECTS[1]  # the 4 cm box


def spot(turret: float) -> Tuple[float, float]:
    """Where the fingers are over the table at this turret angle (x, y)."""
    radius = 0.2 + REACH
    return radius * math.cos(turret), radius * math.sin(turret)


class Table:
    """The live table: sim time, step, gripper and box heights, finger opening, once a period
    of sim time on its own thread."""

    def __init__(self, arm: str, box: str, period: float) -> None:
        self.get = rospy.ServiceProxy('/gazebo/get_link_state', GetLinkState)
        self.palm, self.box, self.period = arm + '::lift', box + '::link', period
        self.phase = 'start'
        self.rows: List[Tuple[float, str, float, float, float, float]] = []
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def start(self) -> None:
        print(
            '%8s  %-16s %10s %10s %10s %10s'
            % ('sim t', 'step', 'gripper z', 'box z', 'box x', 'box y'),
            flush=True,
        )
        self._thread.start()

    def sample(self) -> Tuple[float, float, float, float]:
        palm = self.get(self.palm, 'world').link_state.pose.position
        box = self.get(self.box, 'world').link_state.pose.position
        return palm.z, box.z, box.x, box.y

    def _run(self) -> None:
        while not self._stop.is_set() and not rospy.is_shutdown():
            try:
                g, z, x, y = self.sample()
            except rospy.ServiceException:
                return
            t = rospy.Time.now().to_sec()
            self.rows.append((t, self.phase, g, z, x, y))
            print(
                '%8.2f  %-16s %10.4f %10.4f %10.4f %10.4f' % (t, self.phase, g, z, x, y), flush=True
            )
            try:
                rospy.sleep(self.period)
            except rospy.ROSInterruptException:
                return

    def stop(self) -> None:
        self._stop.set()
        self._thread.join(2.0)


def main(argv: Optional[Sequence[str]] = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--ns', default='/pick_arm', help="the arm's robot namespace")
    parser.add_argument('--model', default='pick_arm', help="the arm's model name")
    parser.add_argument('--period', type=float, default=0.5, help='sim s between table rows')
    parser.add_argument('--timeout', type=float, default=60.0, help='wall s to wait for the arm')
    args = parser.parse_args(rospy.myargv(list(argv) if argv is not None else sys.argv)[1:])
    rospy.init_node('pick_place_demo', anonymous=True)
    arm = actionlib.SimpleActionClient(
        args.ns + '/arm_controller/follow_joint_trajectory', FollowJointTrajectoryAction
    )
    gripper = actionlib.SimpleActionClient(
        args.ns + '/gripper_controller/gripper_cmd', GripperCommandAction
    )
    for client in (arm, gripper):
        if not client.wait_for_server(rospy.Duration(args.timeout)):
            print(
                'pick_place_demo: no action server at %s (is pick_place.launch running?)'
                % client.action_client.ns,
                file=sys.stderr,
            )
            return 2
    pick, place = spot(PICK_TURRET), spot(PLACE_TURRET)
    rospy.wait_for_service('/gazebo/spawn_urdf_model', args.timeout)
    spawn = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)
    yaw = PICK_TURRET  # square to the fingers
    pose = Pose(
        Point(pick[0], pick[1], TABLE_TOP + OBJECT.height / 2 + 0.001),
        Quaternion(0, 0, math.sin(yaw / 2), math.cos(yaw / 2)),
    )
    res = spawn(OBJECT.name, OBJECT.urdf(), '', pose, 'world')
    if not res.success:
        print('pick_place_demo: the box was not spawned: %s' % res.status_message, file=sys.stderr)
        return 1
    down, up = pick_lift(OBJECT), pick_lift(OBJECT) + LIFT_RISE
    table = Table(args.model, OBJECT.name, args.period)
    table.start()

    def move(phase: str, turret: float, lift: float, seconds: float) -> bool:
        table.phase = phase
        # From where the arm is, at rest at the end (the controller's cubic), in one segment.
        arm.send_goal(make_goal([(seconds, [turret, REACH, lift])], JOINTS))
        arm.wait_for_result(rospy.Duration(args.timeout))
        return arm.get_result() is not None and arm.get_result().error_code == 0

    def grip(phase: str, position: float) -> None:
        table.phase = phase
        goal = GripperCommandGoal()
        goal.command.position, goal.command.max_effort = position, SQUEEZE
        gripper.send_goal(goal)
        # Closed on the box the goal ends stalled; in any case the grip is made within 2 s.
        gripper.wait_for_result(rospy.Duration(2.0))
        rospy.sleep(0.3)

    ok = True
    ok &= move('over the box', PICK_TURRET, up, 3.0)
    grip('open', FINGERS_OPEN)
    ok &= move('down', PICK_TURRET, down, 2.0)
    grip('close', FINGERS_CLOSED)
    _, box_before, _, _ = table.sample()
    ok &= move('lift', PICK_TURRET, up, 2.0)
    _, box_up, _, _ = table.sample()
    ok &= move('carry', PLACE_TURRET, up, 3.0)
    _, box_carried, _, _ = table.sample()
    ok &= move('down', PLACE_TURRET, down, 2.0)
    grip('release', FINGERS_OPEN)
    ok &= move('up', PLACE_TURRET, up, 2.0)
    rospy.sleep(0.5)
    table.stop()
    _, box_end, x, y = table.sample()
    lifted = box_up - box_before
    off = math.hypot(x - place[0], y - place[1])
    on_table = abs(box_end - (TABLE_TOP + OBJECT.height / 2)) < 0.003
    print(
        'box lifted %.1f mm with the gripper\'s %.1f; %.1f mm above the table while carried'
        % (lifted * 1e3, LIFT_RISE * 1e3, (box_carried - TABLE_TOP - OBJECT.height / 2) * 1e3)
    )
    print(
        'box put down %.1f mm from the place spot (%.3f, %.3f), %s; arm goals %s'
        % (
            off * 1e3,
            place[0],
            place[1],
            'standing on the table' if on_table else 'NOT on the table',
            'all succeeded' if ok else 'NOT all succeeded',
        )
    )
    done = ok and lifted > 0.95 * LIFT_RISE and off < 0.01 and on_table
    print('pick_place_demo: %s' % ('the box was picked and placed' if done else 'FAILED'))
    return 0 if done else 1
