"""The robot as the planner sees it: joints, limits, groups, forward kinematics and Jacobians,
on a pybullet DIRECT client of its own (never the simulation's).

Links stay as the URDF has them (no lumping of fixed joints: MoveIt keeps every link);
pybullet's URDF reader gives the kinematics, numpy the rest. The model frame is the URDF's
root link, as MoveIt's (a virtual joint's parent frame names the same pose: the virtual
joint is taken as fixed at the identity).
"""

from __future__ import annotations

import math
import os
import tempfile
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from typing import Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import pybullet as p

from ..description import safe_xml
from ..description.compact_urdf import compact_urdf
from ..description.srdf import Srdf, TreeJoint, group_links, resolve_group
from ..description.urdf_model import UrdfError, parse_description, parse_urdf, resolve_mesh_uris
from .config import JointBounds, JointLimitsConfig, apply_joint_limits

Pose = Tuple[np.ndarray, np.ndarray]  # position (3,), quaternion x y z w (4,)
Vector = Union[Sequence[float], np.ndarray]


class ModelError(ValueError):
    """The robot model cannot be built or a request names what it lacks."""


@dataclass
class Mimic:
    leader: str
    multiplier: float = 1.0
    offset: float = 0.0


def _no_packages(name: str) -> str:
    raise LookupError("package '%s' (no package path given)" % name)


def _with_inertials(urdf: str) -> str:
    """The URDF with a unit inertial at the frame of each link that has none: planning
    never steps, and pybullet would print a warning per such link."""
    root = safe_xml.parse_trusted(urdf)  # our own compact text, parsed once already
    for link in root.findall('link'):
        if link.find('inertial') is None:
            ET.SubElement(link, 'inertial').extend(
                [
                    ET.Element('mass', value='1'),
                    ET.Element('inertia', ixx='1', iyy='1', izz='1', ixy='0', ixz='0', iyz='0'),
                ]
            )
    return ET.tostring(root, encoding='unicode')


def quat_to_matrix(q: Vector) -> np.ndarray:
    return np.array(p.getMatrixFromQuaternion(list(q))).reshape(3, 3)


def rotation_error(q_target: Vector, q_current: Vector) -> np.ndarray:
    """The rotation vector (axis * angle, model frame) taking q_current to q_target."""
    r = quat_to_matrix(q_target) @ quat_to_matrix(q_current).T
    angle = math.acos(max(-1.0, min(1.0, (np.trace(r) - 1.0) / 2.0)))
    if angle < 1e-9:
        return np.zeros(3)
    axis = np.array([r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1]])
    norm = np.linalg.norm(axis)
    if norm < 1e-9:  # angle near pi: the axis from the symmetric part
        w, v = np.linalg.eigh((r + r.T) / 2.0)
        axis = v[:, int(np.argmax(w))]
        return axis * angle
    return axis / norm * angle


class RobotKinematics:
    def __init__(
        self,
        urdf_xml: str,
        srdf: Srdf,
        joint_limits: Optional[JointLimitsConfig] = None,
        find_package: Optional[Callable[[str], str]] = None,
    ) -> None:
        try:
            root = parse_description(urdf_xml)
            model = parse_urdf(root)
            resolved = _with_inertials(
                resolve_mesh_uris(compact_urdf(root), find_package or _no_packages)
            )
        except (UrdfError, LookupError) as exc:
            raise ModelError('robot_description: %s' % exc) from None
        self.srdf = srdf
        self.root_link = model.root_link
        virtual = srdf.virtual_joints[0] if srdf.virtual_joints else None
        self.model_frame = virtual.parent_frame if virtual else model.root_link
        self.tree = {
            name: TreeJoint(name, j.type, j.parent, j.child) for name, j in model.joints.items()
        }
        self.mimics: Dict[str, Mimic] = {}
        for j in root.findall('joint'):
            m = j.find('mimic')
            if m is not None and m.get('joint'):
                self.mimics[j.get('name') or ''] = Mimic(
                    m.get('joint') or '',
                    float(m.get('multiplier', 1.0)),
                    float(m.get('offset', 0.0)),
                )
        cfg = joint_limits or JointLimitsConfig()
        self.bounds: Dict[str, JointBounds] = {}
        self.variables: List[str] = []  # every movable joint, in document order
        for name, j in model.joints.items():
            if j.type in ('fixed', 'floating', 'planar'):
                continue
            continuous = j.type == 'continuous'
            lo, hi = j.limits.lower, j.limits.upper
            b = JointBounds(
                lower=-math.pi if continuous or lo is None else lo,
                upper=math.pi if continuous or hi is None else hi,
                max_velocity=j.limits.velocity if j.limits.velocity else None,
                continuous=continuous,
            )
            self.bounds[name] = apply_joint_limits(b, name, cfg)
            self.variables.append(name)
        self.passive = set(srdf.passive_joints)
        self.client: Optional[int] = p.connect(p.DIRECT)
        self._tmp = tempfile.TemporaryDirectory(prefix='arm1-planning-')
        path = os.path.join(self._tmp.name, 'robot.urdf')
        with open(path, 'w') as f:
            f.write(resolved)
        # Parent-child pairs too (MoveIt checks them unless the SRDF disables them). A free
        # base, never stepped: Bullet skips pairs of two static bodies, and a fixed base
        # would be one against the world's objects.
        flags = p.URDF_USE_SELF_COLLISION | p.URDF_USE_SELF_COLLISION_INCLUDE_PARENT
        try:
            self.body = p.loadURDF(
                path, useFixedBase=False, flags=flags, physicsClientId=self.client
            )
        except p.error as exc:
            p.disconnect(self.client)
            raise ModelError('robot_description: pybullet could not build it (%s)' % exc) from None
        c = self.client
        self.link_index: Dict[str, int] = {
            p.getBodyInfo(self.body, physicsClientId=c)[0].decode(): -1
        }
        self.joint_index: Dict[str, int] = {}
        self.dof_order: List[str] = []  # pybullet's order of movable joints (Jacobian columns)
        for i in range(p.getNumJoints(self.body, physicsClientId=c)):
            info = p.getJointInfo(self.body, i, physicsClientId=c)
            self.joint_index[info[1].decode()] = i
            self.link_index[info[12].decode()] = i
            if info[2] != p.JOINT_FIXED:
                self.dof_order.append(info[1].decode())
        # the link frame's place in pybullet's centre-of-mass frame, for Jacobians
        self._com_to_frame: Dict[int, Tuple[float, float, float]] = {}
        for link, i in self.link_index.items():
            if i < 0:
                continue
            state = p.getLinkState(self.body, i, physicsClientId=c)
            self._com_to_frame[i] = tuple(p.invertTransform(state[2], state[3])[0])
        base = p.getDynamicsInfo(self.body, -1, physicsClientId=c)[3:5]
        self._base_frame = p.invertTransform(*base)
        self.positions: Dict[str, float] = {n: self.default_position(n) for n in self.variables}
        self._applied: Dict[str, float] = {}  # what pybullet holds
        self.set_positions(self.positions)

    def close(self) -> None:
        if self.client is not None:
            p.disconnect(self.client)
            self.client = None
            self._tmp.cleanup()

    # --- joints and groups -------------------------------------------------------------

    def default_position(self, name: str) -> float:
        """MoveIt's default value of a variable: 0 when within bounds, else their middle."""
        b = self.bounds[name]
        return 0.0 if b.lower <= 0.0 <= b.upper else (b.lower + b.upper) / 2.0

    def group_joints(self, group: str) -> List[str]:
        """The variables planning moves in ``group``: movable, neither mimic nor passive."""
        try:
            joints = resolve_group(self.srdf, group, self.tree)
        except ValueError as exc:
            raise ModelError(str(exc)) from None
        return [
            j for j in joints if j in self.bounds and j not in self.mimics and j not in self.passive
        ]

    def group_links(self, group: str) -> List[str]:
        return group_links(self.srdf, group, self.tree)

    def group_tip(self, group: str) -> str:
        """The link a pose target of ``group`` means by default: the last chain's tip, or the
        child of the group's last joint (MoveIt's end-effector link when none is set)."""
        g = self.srdf.groups.get(group)
        if g is None:
            raise ModelError("no group '%s' in the SRDF" % group)
        for ee in self.srdf.end_effectors:
            if ee.parent_group == group:
                return ee.parent_link
        if g.chains:
            return g.chains[-1][1]
        joints = resolve_group(self.srdf, group, self.tree)
        if not joints:
            raise ModelError("group '%s' has no joints" % group)
        return self.tree[joints[-1]].child

    def named_states(self, group: str) -> Dict[str, Dict[str, float]]:
        return dict(self.srdf.group_states.get(group, {}))

    def clamp(self, name: str, value: float) -> float:
        b = self.bounds[name]
        if b.continuous:
            return math.atan2(math.sin(value), math.cos(value))
        return min(b.upper, max(b.lower, value))

    def within_bounds(self, values: Mapping[str, float], margin: float = 0.0) -> bool:
        for name, v in values.items():
            b = self.bounds.get(name)
            if (
                b is not None
                and not b.continuous
                and not (b.lower - margin <= v <= b.upper + margin)
            ):
                return False
        return True

    # --- state ---------------------------------------------------------------------------

    def set_positions(self, values: Mapping[str, float]) -> None:
        """Put the model's joints at ``values`` (others keep theirs); mimics follow."""
        c = self.client
        for name, v in values.items():
            if name in self.bounds:
                self.positions[name] = float(v)
        for follower, m in self.mimics.items():
            if m.leader in self.positions and follower in self.positions:
                self.positions[follower] = m.multiplier * self.positions[m.leader] + m.offset
        changed = [n for n, v in self.positions.items() if self._applied.get(n) != v]
        if changed:  # one call for all: pybullet's per-call overhead dominates a check
            p.resetJointStatesMultiDof(
                self.body,
                [self.joint_index[n] for n in changed],
                [[self.positions[n]] for n in changed],
                physicsClientId=c,
            )
            self._applied.update((n, self.positions[n]) for n in changed)

    def link_pose(self, link: str) -> Pose:
        """The link frame's pose in the model frame, at the current positions."""
        i = self.link_index.get(link)
        if i is None:
            raise ModelError("no link '%s' in the robot model" % link)
        c = self.client
        if i < 0:
            com = p.getBasePositionAndOrientation(self.body, physicsClientId=c)
            pos, orn = p.multiplyTransforms(com[0], com[1], *self._base_frame)
            return np.array(pos), np.array(orn)
        s = p.getLinkState(self.body, i, computeForwardKinematics=True, physicsClientId=c)
        return np.array(s[4]), np.array(s[5])

    def jacobian(self, link: str, joints: Sequence[str]) -> np.ndarray:
        """6 x len(joints): the link frame's linear and angular velocity per joint velocity."""
        i = self.link_index.get(link)
        if i is None or i < 0:
            raise ModelError("link '%s' is not moved by any joint" % link)
        q = [self.positions[n] for n in self.dof_order]
        zeros = [0.0] * len(q)
        lin, ang = p.calculateJacobian(
            self.body, i, list(self._com_to_frame[i]), q, zeros, zeros, physicsClientId=self.client
        )
        full = np.vstack([np.array(lin), np.array(ang)])[:, -len(q) :]  # less the free base's 6
        cols = [self.dof_order.index(j) for j in joints]
        out = full[:, cols]
        # a mimic's motion follows its leader's: its column adds to the leader's
        for follower, m in self.mimics.items():
            if m.leader in joints and follower in self.dof_order:
                out[:, list(joints).index(m.leader)] += (
                    m.multiplier * full[:, self.dof_order.index(follower)]
                )
        return out
