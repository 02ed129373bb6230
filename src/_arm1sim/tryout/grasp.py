"""try_grasp's ROS-free part: how each vendor gripper is driven (its own interface), where a
box goes between its open fingers (from the finger links' poses), and whether a lift held it.

The verdict is issue 21's: the box rises with the gripper by at least MIN_LIFT and, held for
HOLD_S of sim time, moves at most MAX_SLIP against the gripper (pick_place's hold verdict
judges rise ratio and slip the same way).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Dict, Optional, Sequence, Tuple

from _arm1sim.goal.pick_place import MAX_SLIP, MIN_RISE_RATIO, HoldVerdict, judge_hold

Vec = Tuple[float, float, float]
Quat = Tuple[float, float, float, float]  # x, y, z, w as geometry_msgs

MIN_LIFT = 0.04  # the box must rise at least this far (m)
HOLD_S = 5.0  # sim seconds the lifted box is held before it is judged


@dataclass(frozen=True)
class Gripper:
    """A vendor arm as its own package drives it.

    ``kind`` 'topics': std_msgs/Float64 on ``gripper_topic`` and one Float64 topic per arm
    joint (``arm_topics``); 'trajectory': FollowJointTrajectory actions ``gripper_action`` over
    ``finger_joints`` and ``arm_action`` over ``arm_joints``; 'franka': franka_gripper's own
    actions under ``gripper_action`` (``move`` to the open width, ``grasp`` at the box's width
    with ``grasp_epsilon``, ``grasp_speed``, ``grasp_force``; positions are widths) and the
    arm's FollowJointTrajectory ``arm_action``.
    """

    name: str
    model: str
    kind: str
    palm_link: str  # the frame the slip is measured in
    finger_links: Tuple[str, ...]  # the box goes to the centroid of these links' origins
    offset: Vec  # then this far in the palm's frame (pads ahead of the link origins)
    open_position: Tuple[float, ...]
    closed_position: Tuple[float, ...]
    arm_joints: Tuple[str, ...]
    start: Tuple[float, ...]  # arm pose the box is placed in
    lift: Tuple[float, ...]  # arm pose change that raises the gripper (palm kept level)
    reach_s: float = 2.0  # sim seconds the arm is given to reach its start pose
    box_size: float = 0.03
    gripper_topic: str = ''
    arm_topics: Tuple[str, ...] = ()
    finger_joints: Tuple[str, ...] = ()  # the finger joints (reported through the hold)
    follower_joints: Tuple[str, ...] = ()  # fingers a mimic plugin moves (reported too)
    gripper_action: str = ''
    arm_action: str = ''
    grasp_epsilon: float = 0.0  # kind 'franka': the grasp's inner and outer tolerance (m)
    grasp_speed: float = 0.0  # m/s
    grasp_force: float = 0.0  # N
    notes: Dict[str, str] = field(default_factory=dict)

    def lifted(self) -> Tuple[float, ...]:
        return tuple(s + d for s, d in zip(self.start, self.lift))

    def command_topics(self) -> Tuple[str, ...]:
        """The topics another node could command this arm and gripper on, beside the tries:
        the Float64 topics, or each trajectory controller's ``command`` topic."""
        if self.kind == 'topics':
            return (self.gripper_topic, *self.arm_topics)
        actions = [self.arm_action]
        if self.kind == 'trajectory':
            actions.append(self.gripper_action)
        suffix = '/follow_joint_trajectory'
        return tuple(a[: -len(suffix)] + '/command' for a in actions if a.endswith(suffix))


# OpenMANIPULATOR-X (open_manipulator_gazebo): Float64 position commands, as its own
# omx_gripper_sub_publisher relays gripper_position/command to the second finger.
# joint2 back and joint4 forward by the same angle raise the gripper and keep it level.
OMX = Gripper(
    name='omx',
    model='open_manipulator',
    kind='topics',
    palm_link='link5',
    finger_links=('gripper_link', 'gripper_link_sub'),
    offset=(0.045, 0.0, 0.0),
    open_position=(0.019,),
    closed_position=(-0.01,),
    arm_joints=('joint1', 'joint2', 'joint3', 'joint4'),
    start=(0.0, 0.0, 0.0, 0.0),
    lift=(0.0, -0.4, 0.0, 0.4),
    box_size=0.03,
    finger_joints=('gripper', 'gripper_sub'),
    gripper_topic='/gripper_position/command',
    arm_topics=tuple('/joint%d_position/command' % i for i in range(1, 5)),
)

# Kinova JACO2 j2n6s300 (kinova_gazebo robot_launch.launch): its effort trajectory controllers.
# A pick from above: the palm faces down (link_6's z axis up), so the box on its column stands
# below the hand and clear of every finger (its launch file's spawn pose holds the hand on its
# side, fingers 2 and 3 under the box: the column ran through finger 3). The box's centre 18 mm
# beyond the finger links' centroid and midway between finger 1 and fingers 2 and 3, where the
# open fingers leave 15 mm or more on every side (ray tests on its meshes). The lift raises the
# palm 60 mm straight up, level (joint deltas from inverse kinematics at the start pose).
_J = 'j2n6s300'
JACO = Gripper(
    name='jaco',
    model=_J,
    kind='trajectory',
    palm_link=_J + '_link_6',
    finger_links=tuple(
        '%s_link_finger_%s%d' % (_J, part, i) for part in ('', 'tip_') for i in (1, 2, 3)
    ),
    offset=(0.0, 0.0135, -0.018),
    open_position=(0.0, 0.0, 0.0),
    closed_position=(1.3, 1.3, 1.3),
    arm_joints=tuple('%s_joint_%d' % (_J, i) for i in range(1, 7)),
    start=(-0.846, 3.694, 1.266, -2.925, -0.83, -0.63),  # palm down, 0.35 m above the ground
    lift=(-0.004, -0.113, 0.096, 0.074, -0.249, 0.07),  # the palm 60 mm up, level
    # from its launch file's spawn pose joint5 turns 2.2 rad, capped at 0.84 rad/s
    reach_s=5.0,
    box_size=0.04,
    finger_joints=tuple('%s_joint_finger_%d' % (_J, i) for i in (1, 2, 3)),
    gripper_action='/%s/effort_finger_trajectory_controller/follow_joint_trajectory' % _J,
    arm_action='/%s/effort_joint_trajectory_controller/follow_joint_trajectory' % _J,
)

# Franka Emika Panda (franka_gazebo panda.launch controller:=effort_joint_trajectory_controller):
# the hand through franka_gripper's move and grasp actions, as a franka_ros user drives it (a
# grasp at the object's width, +-5 mm, 0.1 m/s, 10 N), the arm through its effort trajectory
# controller. The hand link is lumped into link7 (fixed joints, as Gazebo lumps them), turned
# 45 degrees about its axis from the fingers: the slip is measured in the left finger's frame,
# which is the hand's. The rubber pads sit 36-54.5 mm along the finger links' z (the hand's
# axis, pointing down at the start pose): the box's centre 45 mm from the finger origins.
# Start pose: panda.launch's own (the hand down, its TCP at 0.307, 0, 0.487 m); the lift:
# joints 2, 4 and 6 raise the TCP 60 mm straight up, the hand level (pybullet kinematics of
# its URDF at the start pose).
PANDA = Gripper(
    name='panda',
    model='panda',
    kind='franka',
    palm_link='panda_leftfinger',
    finger_links=('panda_leftfinger', 'panda_rightfinger'),
    offset=(0.0, 0.0, 0.045),
    open_position=(0.08,),
    closed_position=(0.04,),  # the grasp's width: the box's
    arm_joints=tuple('panda_joint%d' % i for i in range(1, 8)),
    start=(0.0, -0.785398163, 0.0, -2.35619449, 0.0, 1.57079632679, 0.785398163397),
    lift=(0.0, 0.0521, 0.0, 0.1894, 0.0, -0.1373, 0.0),
    box_size=0.04,
    finger_joints=('panda_finger_joint1', 'panda_finger_joint2'),
    gripper_action='/franka_gripper',
    arm_action='/effort_joint_trajectory_controller/follow_joint_trajectory',
    grasp_epsilon=0.005,
    grasp_speed=0.1,
    grasp_force=10.0,
)

# TurtleBot3 Waffle Pi with OpenMANIPULATOR-X (turtlebot3_manipulation_gazebo): its
# arm_controller (position JointTrajectoryController over gazebo_ros_control pid_gains) and
# gripper_controller (effort JointTrajectoryController of `gripper`; the roboticsgroup mimic
# plugin moves gripper_sub). The arm and fingers are OpenMANIPULATOR-X's (as omx: pads 24-65 mm
# ahead of the finger links, joint2 -0.4 and joint4 +0.4 rad raise the palm level).
TB3_OMX = replace(
    OMX,
    name='tb3_omx',
    model='robot',
    kind='trajectory',
    finger_joints=('gripper',),
    follower_joints=('gripper_sub',),
    gripper_topic='',
    arm_topics=(),
    gripper_action='/gripper_controller/follow_joint_trajectory',
    arm_action='/arm_controller/follow_joint_trajectory',
)

GRIPPERS = {g.name: g for g in (OMX, JACO, PANDA, TB3_OMX)}


def rotate(q: Quat, v: Vec) -> Vec:
    """v rotated by the unit quaternion q (x, y, z, w)."""
    x, y, z, w = q
    # t = 2 q_vec x v; v' = v + w t + q_vec x t
    tx = 2 * (y * v[2] - z * v[1])
    ty = 2 * (z * v[0] - x * v[2])
    tz = 2 * (x * v[1] - y * v[0])
    return (
        v[0] + w * tx + (y * tz - z * ty),
        v[1] + w * ty + (z * tx - x * tz),
        v[2] + w * tz + (x * ty - y * tx),
    )


def to_frame(position: Vec, orientation: Quat, point: Vec) -> Vec:
    """point (world) in the frame at position/orientation."""
    x, y, z, w = orientation
    d = (point[0] - position[0], point[1] - position[1], point[2] - position[2])
    return rotate((-x, -y, -z, w), d)


def angle_between(a: Quat, b: Quat) -> float:
    """The rotation angle (rad) from orientation a to b."""
    import math

    dot = abs(sum(x * y for x, y in zip(a, b)))
    return 2 * math.acos(min(1.0, dot))


def box_pose(
    finger_positions: Sequence[Vec], palm_orientation: Quat, offset: Vec
) -> Tuple[Vec, Quat]:
    """Where the box goes: the centroid of the finger links' origins moved by offset (in the
    palm's frame), turned as the palm is (its faces square to the fingers)."""
    if not finger_positions:
        raise ValueError('no finger link poses to place the box between')
    n = len(finger_positions)
    c = tuple(sum(p[i] for p in finger_positions) / n for i in range(3))
    o = rotate(palm_orientation, offset)
    return (c[0] + o[0], c[1] + o[1], c[2] + o[2]), palm_orientation


@dataclass(frozen=True)
class LiftVerdict:
    hold: HoldVerdict

    @property
    def rise(self) -> float:
        return self.hold.object_rise

    @property
    def slip(self) -> float:
        return self.hold.slip

    @property
    def ok(self) -> bool:
        return (
            self.rise >= MIN_LIFT
            and self.hold.rise_ratio >= MIN_RISE_RATIO
            and self.slip <= MAX_SLIP
        )

    def as_dict(self) -> Dict[str, object]:
        return {
            'gripper_rise_mm': round(self.hold.gripper_rise * 1e3, 1),
            'box_rise_mm': round(self.rise * 1e3, 1),
            'slip_mm': round(self.slip * 1e3, 2),
            'ok': self.ok,
        }

    def __str__(self) -> str:
        return 'box rose %.1f mm (gripper %.1f mm), slipped %.2f mm: %s' % (
            self.rise * 1e3,
            self.hold.gripper_rise * 1e3,
            self.slip * 1e3,
            'LIFTED' if self.ok else 'NOT lifted',
        )


def judge_lift(
    palm_before: Vec,
    box_before: Vec,
    palm_after: Vec,
    box_after: Vec,
    box_in_palm: Sequence[Vec],
) -> LiftVerdict:
    """World positions of the gripper (the palm, or the point where it gripped the box) and
    the box once closed (before) and after the hold, and the box's
    position in the palm's frame sampled through the hold (the first at its start): slip is
    the farthest it moved from that first sample."""
    if not box_in_palm:
        raise ValueError('no samples of the hold')
    first = box_in_palm[0]
    dist = [sum((a - b) ** 2 for a, b in zip(p, first)) ** 0.5 for p in box_in_palm]
    hold = judge_hold(palm_before[2], box_before[2], palm_after[2], box_after[2], dist)
    return LiftVerdict(hold)


def box_urdf(name: str, size: float, mass: float, mu: float) -> str:
    from _arm1sim.goal.pick_place import PickObject

    return PickObject(name, 'box', (size, size, size), mass, mu).urdf()


def pedestal_sdf(name: str, width: float, height: float) -> str:
    """A static column (SDF: <static>) the box stands on until the fingers close, its top at
    its model pose; narrower than the box so no finger touches it."""
    g = '<geometry><box><size>%g %g %g</size></box></geometry>' % (width, width, height)
    return (
        '<sdf version="1.6"><model name="%s"><static>true</static><link name="link">'
        '<pose>0 0 %g 0 0 0</pose><visual name="v">%s</visual>'
        '<collision name="c">%s</collision></link></model></sdf>' % (name, -height / 2, g, g)
    )


def summary(verdicts: Sequence[Optional[LiftVerdict]]) -> str:
    ok = sum(1 for v in verdicts if v is not None and v.ok)
    return '%d of %d lifted' % (ok, len(verdicts))
