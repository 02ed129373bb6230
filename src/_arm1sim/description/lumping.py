"""Fixed-joint lumping and massless links, as Gazebo's URDF-to-SDF conversion does them.

sdformat's parser (parser_urdf.cc, ReduceFixedJoints) removes every fixed joint whose parent
is not ``world`` and merges its child into the parent: masses and inertias combined at the
combined centre of mass, collisions and visuals moved by the joint's transform, the child's
own child joints re-parented. ``<gazebo reference="JOINT"><preserveFixedJoint>true`` or
``<disableFixedJointLumping>true`` keeps a joint (here always as a fixed joint: Gazebo makes
the latter a revolute joint with limits [0, 0], which holds the same). A merged link is gone
from the model (link_states, get_link_state) but its frame lives on in the link it was
merged into at a fixed offset: ``Lumped.frames``, for sensors and cameras attached to it.

Links without ``<inertial>`` weigh nothing: lumped, they add nothing; left on a fixed joint
(to ``world`` or a preserved one) they get FRAME_MASS, as pybullet needs a positive mass;
on a moving joint Gazebo leaves them out with what hangs on them, which pybullet cannot do:
they keep pybullet's default (1 kg) and the spawn warns once, naming them.

Works on the ElementTree of a URDF already parsed safely (our own serialisation); no ROS,
no pybullet.
"""

from __future__ import annotations

import logging
import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence, Tuple

from .sdf_values import vector3

log = logging.getLogger('_arm1sim.description')

FRAME_MASS = 1e-6  # kg: far below any real part, but positive for pybullet
FRAME_INERTIA = 1e-9  # kg m^2 on the diagonal

Vec3 = Tuple[float, float, float]
Quat = Tuple[float, float, float, float]  # x, y, z, w
Pose = Tuple[Vec3, Quat]
Matrix = Tuple[Vec3, Vec3, Vec3]  # rows

IDENTITY_POSE: Pose = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))
TRUE_WORDS = ('true', 'yes', '1')  # how sdformat reads a boolean extension


# ---------------------------------------------------------------- rigid transforms


def rpy_matrix(rpy: Sequence[float]) -> Matrix:
    """URDF's fixed-axis roll, pitch, yaw: R = Rz(yaw) Ry(pitch) Rx(roll)."""
    cr, sr = math.cos(rpy[0]), math.sin(rpy[0])
    cp, sp = math.cos(rpy[1]), math.sin(rpy[1])
    cy, sy = math.cos(rpy[2]), math.sin(rpy[2])
    return (
        (cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
        (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
        (-sp, cp * sr, cp * cr),
    )


def matrix_rpy(m: Matrix) -> Vec3:
    sp = max(-1.0, min(1.0, -m[2][0]))
    pitch = math.asin(sp)
    if abs(sp) > 1.0 - 1e-12:  # gimbal lock: all yaw, no roll
        return (0.0, pitch, math.atan2(-m[0][1], m[1][1]))
    return (math.atan2(m[2][1], m[2][2]), pitch, math.atan2(m[1][0], m[0][0]))


def matmul(a: Matrix, b: Matrix) -> Matrix:
    rows = tuple(
        tuple(sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)) for i in range(3)
    )
    return rows  # type: ignore[return-value]


def transpose(a: Matrix) -> Matrix:
    return tuple(tuple(a[j][i] for j in range(3)) for i in range(3))  # type: ignore[return-value]


def rotate(m: Matrix, v: Sequence[float]) -> Vec3:
    return (
        m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
        m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
        m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2],
    )


def matrix_quaternion(m: Matrix) -> Quat:
    """x, y, z, w of a rotation matrix (Shepperd's method)."""
    t = m[0][0] + m[1][1] + m[2][2]
    if t > 0:
        s = math.sqrt(t + 1.0) * 2
        return ((m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, s / 4)
    if m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        s = math.sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]) * 2
        return (s / 4, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s, (m[2][1] - m[1][2]) / s)
    if m[1][1] > m[2][2]:
        s = math.sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]) * 2
        return ((m[0][1] + m[1][0]) / s, s / 4, (m[1][2] + m[2][1]) / s, (m[0][2] - m[2][0]) / s)
    s = math.sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]) * 2
    return ((m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, s / 4, (m[1][0] - m[0][1]) / s)


@dataclass(frozen=True)
class Transform:
    xyz: Vec3 = (0.0, 0.0, 0.0)
    rot: Matrix = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))

    def __mul__(self, other: 'Transform') -> 'Transform':
        t = rotate(self.rot, other.xyz)
        return Transform(
            (self.xyz[0] + t[0], self.xyz[1] + t[1], self.xyz[2] + t[2]),
            matmul(self.rot, other.rot),
        )

    @property
    def pose(self) -> Pose:
        return self.xyz, matrix_quaternion(self.rot)


def _numbers(text: Optional[str], where: str) -> Vec3:
    values = vector3(text)
    if values is None:
        raise ValueError('%s: %r is not 3 finite numbers' % (where, text))
    return values


def origin_of(element: ET.Element, where: str) -> Transform:
    """The transform of an element's ``<origin xyz rpy>`` (identity without one)."""
    origin = element.find('origin')
    if origin is None:
        return Transform()
    return Transform(
        _numbers(origin.get('xyz'), where + ' <origin> xyz'),
        rpy_matrix(_numbers(origin.get('rpy'), where + ' <origin> rpy')),
    )


def set_origin(element: ET.Element, t: Transform) -> None:
    origin = element.find('origin')
    if origin is None:
        origin = ET.Element('origin')
        element.insert(0, origin)
    origin.set('xyz', ' '.join(repr(v) for v in t.xyz))
    origin.set('rpy', ' '.join(repr(v) for v in matrix_rpy(t.rot)))


# ---------------------------------------------------------------- mass


@dataclass
class Mass:
    """A body's mass, centre of mass and inertia about it, in some link's frame and axes."""

    mass: float = 0.0
    com: Vec3 = (0.0, 0.0, 0.0)
    inertia: Matrix = ((0.0, 0.0, 0.0),) * 3

    def moved(self, t: Transform) -> 'Mass':
        """The same body seen from the frame in which ``t`` places the current one."""
        r = t.rot
        return Mass(
            self.mass, (t * Transform(self.com)).xyz, matmul(matmul(r, self.inertia), transpose(r))
        )

    def __add__(self, other: 'Mass') -> 'Mass':
        total = self.mass + other.mass
        if total <= 0:
            return Mass()
        com = tuple((self.mass * a + other.mass * b) / total for a, b in zip(self.com, other.com))
        inertia = [[self.inertia[i][j] + other.inertia[i][j] for j in range(3)] for i in range(3)]
        for part in (self, other):  # parallel-axis theorem about the combined centre
            d = [part.com[i] - com[i] for i in range(3)]
            dd = sum(v * v for v in d)
            for i in range(3):
                for j in range(3):
                    inertia[i][j] += part.mass * ((dd if i == j else 0.0) - d[i] * d[j])
        return Mass(total, com, tuple(tuple(row) for row in inertia))  # type: ignore[arg-type]


def mass_of(link: ET.Element) -> Optional[Mass]:
    """The link's ``<inertial>`` in its own frame; None without one or with mass <= 0."""
    inertial = link.find('inertial')
    where = "link '%s' <inertial>" % link.get('name', '')
    if inertial is None or inertial.find('mass') is None:
        return None
    try:
        mass = float(inertial.find('mass').get('value', '0'))  # type: ignore[union-attr]
    except ValueError:
        return None  # parse_urdf reports a bad number; here it only counts as no mass
    if not mass > 0:
        return None
    i = inertial.find('inertia')
    values = {}
    for key in ('ixx', 'iyy', 'izz', 'ixy', 'ixz', 'iyz'):
        try:
            values[key] = float(i.get(key, '0')) if i is not None else 0.0
        except ValueError:
            raise ValueError('%s <inertia> %s is not a number' % (where, key)) from None
    tensor = (
        (values['ixx'], values['ixy'], values['ixz']),
        (values['ixy'], values['iyy'], values['iyz']),
        (values['ixz'], values['iyz'], values['izz']),
    )
    return Mass(mass, (0.0, 0.0, 0.0), tensor).moved(origin_of(inertial, where))


def write_inertial(link: ET.Element, m: Mass) -> None:
    """Replace the link's ``<inertial>`` by ``m`` (centre at its origin, link axes)."""
    old = link.find('inertial')
    if old is not None:
        link.remove(old)
    inertial = ET.SubElement(link, 'inertial')
    ET.SubElement(inertial, 'origin', xyz=' '.join(repr(v) for v in m.com), rpy='0 0 0')
    ET.SubElement(inertial, 'mass', value=repr(m.mass))
    t = m.inertia
    ET.SubElement(
        inertial,
        'inertia',
        ixx=repr(t[0][0]),
        iyy=repr(t[1][1]),
        izz=repr(t[2][2]),
        ixy=repr(t[0][1]),
        ixz=repr(t[0][2]),
        iyz=repr(t[1][2]),
    )


# ---------------------------------------------------------------- lumping


@dataclass
class Lumped:
    """What lumping did to a description."""

    # lumped link -> (link it was merged into, pose of its frame in that link's frame)
    frames: Dict[str, Tuple[str, Pose]] = field(default_factory=dict)
    joints: List[str] = field(default_factory=list)  # fixed joints removed
    weightless: List[str] = field(default_factory=list)  # kept frame links given FRAME_MASS
    moving: List[str] = field(default_factory=list)  # massless on a moving joint: 1 kg stays

    def merged_into(self, link: str) -> List[str]:
        """The links merged into ``link``, nearest first."""
        return [name for name, (parent, _) in self.frames.items() if parent == link]


def flag(refs: Dict[str, Dict[str, str]], name: str, tag: str) -> bool:
    return refs.get(name, {}).get(tag, '').strip().lower() in TRUE_WORDS


def kept_fixed(refs: Dict[str, Dict[str, str]], joint: str) -> bool:
    """A fixed joint Gazebo does not lump: preserveFixedJoint or disableFixedJointLumping."""
    return flag(refs, joint, 'preserveFixedJoint') or flag(refs, joint, 'disableFixedJointLumping')


def lump_fixed_joints(root: ET.Element, refs: Dict[str, Dict[str, str]]) -> Lumped:
    """Merge, in place, every link on a lumped fixed joint into its nearest kept ancestor;
    then give kept massless frame links FRAME_MASS. ``refs`` is RobotModel.gazebo_refs."""
    links = {link.get('name', ''): link for link in root.findall('link')}
    parent_joint: Dict[str, ET.Element] = {}
    for joint in root.findall('joint'):
        child = joint.find('child')
        if child is not None and child.get('link') in links:
            parent_joint[child.get('link', '')] = joint

    def lumped(name: str) -> bool:
        joint = parent_joint.get(name)
        if joint is None or joint.get('type') != 'fixed':
            return False
        parent = joint.find('parent')
        return (
            parent is not None
            and parent.get('link') not in ('world', None)
            and not kept_fixed(refs, joint.get('name', ''))
        )

    # Where each lumped link goes: its nearest kept ancestor and its pose there.
    home: Dict[str, Tuple[str, Transform]] = {}

    def resolve(name: str) -> None:
        # Up the fixed chain to the first kept link (a loop, not recursion: chains may be
        # as long as the limits allow), then down again composing the joint origins.
        chain: List[str] = []
        link = name
        while lumped(link) and link not in home:
            if link in chain:
                raise ValueError('fixed joints form a loop through link %r' % link)
            chain.append(link)
            link = parent_joint[link].find('parent').get('link', '')  # type: ignore[union-attr]
        anchor, offset = home.get(link, (link, Transform()))
        for link in reversed(chain):
            joint = parent_joint[link]
            offset = offset * origin_of(joint, "joint '%s'" % joint.get('name', ''))
            home[link] = (anchor, offset)

    report = Lumped()
    for name in links:
        resolve(name)
    masses: Dict[str, Mass] = {}
    for name, (anchor, t) in home.items():
        link = links[name]
        report.frames[name] = (anchor, t.pose)
        target = links[anchor]
        m = mass_of(link)
        if m is not None:
            base = masses.get(anchor) or mass_of(target) or Mass()
            masses[anchor] = base + m.moved(t)
        for kind in ('visual', 'collision'):
            for element in link.findall(kind):
                where = "link '%s' <%s>" % (name, kind)
                set_origin(element, t * origin_of(element, where))
                if not element.get('name'):
                    element.set('name', name)  # as Gazebo: it keeps its link's name
                target.append(element)
        joint = parent_joint[name]
        report.joints.append(joint.get('name', ''))
        root.remove(joint)
        root.remove(link)
    # Joints hanging from a lumped link now hang from its anchor, their origin moved.
    for child_name, joint in parent_joint.items():
        holder = joint.find('parent')
        if child_name in home or holder is None or holder.get('link') not in home:
            continue
        anchor, t = home[holder.get('link', '')]
        set_origin(joint, t * origin_of(joint, "joint '%s'" % joint.get('name', '')))
        holder.set('link', anchor)
    for anchor, m in masses.items():
        write_inertial(links[anchor], m)
    _weightless_frames(root, report)
    return report


def _weightless_frames(root: ET.Element, report: Lumped) -> None:
    """Kept links without mass: FRAME_MASS on a fixed joint, reported on a moving one. The
    root link and ``world`` stay as they are (the root is the base: fixed or carried)."""
    kinds: Dict[str, str] = {}
    for joint in root.findall('joint'):
        child = joint.find('child')
        if child is not None:
            kinds[child.get('link', '')] = joint.get('type', '')
    for link in root.findall('link'):
        name = link.get('name', '')
        if name == 'world' or name not in kinds or mass_of(link) is not None:
            continue
        if kinds[name] != 'fixed':
            report.moving.append(name)
            continue
        i = FRAME_INERTIA
        write_inertial(link, Mass(FRAME_MASS, (0.0, 0.0, 0.0), ((i, 0, 0), (0, i, 0), (0, 0, i))))
        report.weightless.append(name)


def warn_moving_massless(report: Lumped, model: str) -> None:
    if report.moving:
        log.warning(
            "model '%s': link(s) %s have no <inertial> but move on a non-fixed joint: Gazebo "
            'leaves them (and what hangs on them) out; pybullet gives each 1 kg',
            model,
            ', '.join(report.moving),
        )
