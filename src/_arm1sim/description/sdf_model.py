"""An SDF ``<model>`` read into a link tree (sdf_to_urdf writes it out as URDF for the spawn path).

ROS-free and pybullet-free. What pybullet cannot build (ball, universal, screw joints,
kinematic loops, links no joint ties to the root, nested models) is dropped with a
warning naming it, never silently. Poses follow SDFormat: a link's ``<pose>`` is in the
model frame, a joint's in its child link's frame, a collision's, visual's or inertial's in
its link's; ``relative_to`` may name a link, a joint, a ``<frame>`` or ``__model__``.
A static model, or one with a joint to ``world``, gets a ``world`` root: the world node
loads it with a fixed base, as Gazebo keeps it in place. A spawn request's SDF is hostile
input: bounded by Limits as a URDF is.
"""

from __future__ import annotations

import math
import os
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from typing import Callable, Dict, List, NamedTuple, Optional, Sequence, Set, Tuple

from . import safe_xml
from .limits import LimitError, Limits
from .names import IllegalName, check_name, shown
from .pose_math import multiply, quat_from_rpy, rotate
from .surface import SurfaceError, sdf_surface_tags

# Elements a model may hold per link and joint the limits allow (as urdf_model's budget).
ELEMENTS_PER_PART = 100
# SDF's default joint limits are +-1e16: anything this wide is a continuous joint.
UNLIMITED = 1e15
JOINT_TYPES = ('revolute', 'prismatic', 'fixed', 'continuous')
MODEL_FRAME = '__model__'
# Gazebo's stock material scripts the stand-in colours as Gazebo draws them.
GAZEBO_MATERIALS = {
    'Gazebo/White': (1.0, 1.0, 1.0, 1.0),
    'Gazebo/Grey': (0.7, 0.7, 0.7, 1.0),
    'Gazebo/DarkGrey': (0.35, 0.35, 0.35, 1.0),
    'Gazebo/Black': (0.0, 0.0, 0.0, 1.0),
    'Gazebo/Red': (1.0, 0.0, 0.0, 1.0),
    'Gazebo/Green': (0.0, 1.0, 0.0, 1.0),
    'Gazebo/Blue': (0.0, 0.0, 1.0, 1.0),
    'Gazebo/Yellow': (1.0, 1.0, 0.0, 1.0),
    'Gazebo/Orange': (1.0, 0.5, 0.0, 1.0),
    'Gazebo/Wood': (0.6, 0.4, 0.2, 1.0),
}

# model://NAME/... -> the folder of model NAME; raises LookupError when on no model path.
FindModelDir = Callable[[str], str]


class SdfModelError(ValueError):
    """The model cannot be built at all; the message names the model and the culprit."""


class Tf(NamedTuple):
    """A rigid transform: translation and quaternion (x, y, z, w)."""

    p: Tuple[float, float, float]
    q: Tuple[float, float, float, float]


IDENTITY = Tf((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))


def compose(a: Tf, b: Tf) -> Tf:
    """``a`` then ``b`` expressed in ``a``'s frame."""
    r = rotate(a.q, b.p)
    return Tf((a.p[0] + r[0], a.p[1] + r[1], a.p[2] + r[2]), multiply(a.q, b.q))


def inverse(a: Tf) -> Tf:
    qi = (-a.q[0], -a.q[1], -a.q[2], a.q[3])
    r = rotate(qi, a.p)
    return Tf((-r[0], -r[1], -r[2]), qi)


def tf_from_pose(pose: Sequence[float]) -> Tf:
    """x y z roll pitch yaw -> Tf."""
    return Tf((pose[0], pose[1], pose[2]), quat_from_rpy(pose[3], pose[4], pose[5]))


@dataclass
class Geometry:
    name: str
    pose: Tf  # in the link frame
    kind: str  # box, cylinder, sphere, plane, mesh
    size: Tuple[float, ...] = ()  # box xyz; cylinder (r, length); sphere (r,); plane (sx, sy)
    normal: Tuple[float, float, float] = (0.0, 0.0, 1.0)  # plane only
    uri: str = ''  # mesh only: a path or package:// URI
    scale: Tuple[float, float, float] = (1.0, 1.0, 1.0)
    color: Optional[Tuple[float, float, float, float]] = None


@dataclass
class Inertial:
    mass: float = 1.0  # SDFormat's defaults
    pose: Tf = IDENTITY  # centre of mass and inertia axes, in the link frame
    inertia: Tuple[float, float, float, float, float, float] = (1.0, 0.0, 0.0, 1.0, 0.0, 1.0)


@dataclass
class Link:
    name: str
    pose: Tf  # in the model frame
    inertial: Inertial = field(default_factory=Inertial)
    collisions: List[Geometry] = field(default_factory=list)
    visuals: List[Geometry] = field(default_factory=list)
    extras: List[ET.Element] = field(default_factory=list)  # <sensor>s, for <gazebo reference>
    # its collisions' <surface> as <gazebo reference> tags (surface.SDF_TO_TAG)
    surface: Dict[str, str] = field(default_factory=dict)


@dataclass
class Joint:
    name: str
    type: str  # one of JOINT_TYPES
    parent: str  # a link name or 'world'
    child: str
    pose: Tf  # the joint frame in the model frame
    axis: Tuple[float, float, float] = (0.0, 0.0, 1.0)  # in the joint frame
    lower: float = -1e16
    upper: float = 1e16
    effort: float = -1.0  # SDF: -1 is no limit
    velocity: float = -1.0
    damping: float = 0.0
    friction: float = 0.0


@dataclass
class SdfModel:
    name: str
    pose: Tf  # the model frame in its parent (world) frame
    static: bool
    links: Dict[str, Link]
    joints: List[Joint]
    root: str  # the root link of the tree ('world' when fixed to it)
    plugins: List[ET.Element] = field(default_factory=list)
    warnings: List[str] = field(default_factory=list)  # what was dropped, and why


# ------------------------------------------------------------------------------------ parsing
def _numbers(text: Optional[str], n: int, what: str) -> Tuple[float, ...]:
    try:
        values = tuple(float(v) for v in (text or '').split())
    except ValueError:
        raise SdfModelError('%s: %s is not %d numbers' % (what, shown(text or '', 80), n))
    if len(values) != n or not all(math.isfinite(v) for v in values):
        raise SdfModelError('%s: %s is not %d finite numbers' % (what, shown(text or '', 80), n))
    return values


def _number(element: Optional[ET.Element], tag: str, default: float, what: str) -> float:
    text = element.findtext(tag) if element is not None else None
    if text is None or not text.strip():
        return default
    return _numbers(text, 1, '%s <%s>' % (what, tag))[0]


def _bool(text: Optional[str]) -> bool:
    return (text or '').strip() in ('1', 'true')


def pose_of(element: Optional[ET.Element], what: str) -> Tuple[Tf, str]:
    """The element's ``<pose>`` and its ``relative_to`` ('' when not given)."""
    pose = element.find('pose') if element is not None else None
    if pose is None or not (pose.text or '').strip():
        return IDENTITY, (pose.get('relative_to', '') if pose is not None else '')
    what += ' <pose>'
    if pose.get('rotation_format', 'euler_rpy') == 'quat_xyzw':
        v = _numbers(pose.text, 7, what)
        norm = math.sqrt(sum(c * c for c in v[3:]))
        if norm == 0:
            raise SdfModelError('%s: the quaternion is zero' % what)
        return Tf(v[:3], tuple(c / norm for c in v[3:])), pose.get('relative_to', '')  # type: ignore[arg-type]
    v = _numbers(pose.text, 6, what)
    if _bool(pose.get('degrees')):
        v = v[:3] + tuple(math.radians(a) for a in v[3:])
    return tf_from_pose(v), pose.get('relative_to', '')


class _Frames:
    """SDFormat frame graph of one model: links, joints and <frame>s, resolved in the model."""

    def __init__(self, model_name: str) -> None:
        self.model = model_name
        self.raw: Dict[str, Tuple[Tf, str]] = {}  # name -> (pose, relative to)
        self.resolved: Dict[str, Tf] = {MODEL_FRAME: IDENTITY}

    def add(self, name: str, pose: Tf, relative_to: str) -> None:
        self.raw[name] = (pose, relative_to)

    def resolve(self, name: str) -> Tf:
        """``name``'s frame in the model; a loop, not recursion, so a long chain cannot
        overflow the stack."""
        chain: List[str] = []
        seen: Set[str] = set()
        while name not in self.resolved:
            if name not in self.raw:
                raise SdfModelError(
                    'model %s: relative_to names %s, which is no link, joint or frame of the '
                    'model' % (shown(self.model), shown(name))
                )
            if name in seen:
                raise SdfModelError(
                    'model %s: the poses of %s are relative to each other in a cycle'
                    % (shown(self.model), ', '.join(shown(n) for n in chain[chain.index(name) :]))
                )
            chain.append(name)
            seen.add(name)
            name = self.raw[name][1] or MODEL_FRAME
        tf = self.resolved[name]
        for n in reversed(chain):
            tf = compose(tf, self.raw[n][0])
            self.resolved[n] = tf
        return tf


def _color(visual: ET.Element) -> Optional[Tuple[float, float, float, float]]:
    material = visual.find('material')
    if material is None:
        return None
    for tag in ('diffuse', 'ambient'):
        text = material.findtext(tag)
        if text:
            try:
                v = tuple(float(c) for c in text.split())
            except ValueError:
                continue
            if len(v) in (3, 4) and all(math.isfinite(c) for c in v):
                return (v[0], v[1], v[2], v[3] if len(v) == 4 else 1.0)
    script = material.findtext('script/name')
    return GAZEBO_MATERIALS.get((script or '').strip())


def _mesh_uri(
    uri: str, what: str, base_dir: Optional[str], find_model_dir: Optional[FindModelDir]
) -> str:
    """A mesh URI as the URDF loader takes it: an absolute path, or package:// left as is."""
    scheme, sep, rest = uri.partition('://')
    if not sep:
        if os.path.isabs(uri):
            return uri
        if base_dir is None:
            raise SdfModelError(
                '%s: relative mesh URI %s has no file to be relative to (use model:// or '
                'package://)' % (what, shown(uri, 200))
            )
        return os.path.normpath(os.path.join(base_dir, uri))
    if scheme in ('package', 'file'):
        return uri
    if scheme == 'model':
        name, _, rel = rest.partition('/')
        if not name or '..' in name.split('/'):
            raise SdfModelError('%s: %s names no model' % (what, shown(uri, 200)))
        if find_model_dir is None:
            raise SdfModelError('%s: %s: no model path to look in' % (what, shown(uri, 200)))
        try:
            folder = os.path.abspath(find_model_dir(name))
        except LookupError as exc:
            raise SdfModelError('%s: %s' % (what, exc)) from None
        path = os.path.normpath(os.path.join(folder, rel))
        if os.path.commonpath([folder, path]) != folder:
            raise SdfModelError(
                '%s: %s leaves model %s: a model:// URI must name a file inside its model'
                % (what, shown(uri, 200), shown(name))
            )
        return path
    raise SdfModelError(
        '%s: URI scheme %s is not supported (model://, package://, file:// or a path)'
        % (what, shown(scheme + '://', 30))
    )


def _geometry(
    element: ET.Element,
    link: str,
    frames: _Frames,
    link_tf: Tf,
    base_dir: Optional[str],
    find_model_dir: Optional[FindModelDir],
) -> Optional[Geometry]:
    name = element.get('name', '')
    what = 'link %s %s %s' % (shown(link), element.tag, shown(name))
    pose, rel = pose_of(element, what)
    if rel:
        pose = compose(inverse(link_tf), compose(frames.resolve(rel), pose))
    geometry = element.find('geometry')
    if geometry is None:
        raise SdfModelError('%s has no <geometry>' % what)
    for g in geometry:
        if g.tag == 'box':
            return Geometry(name, pose, 'box', _numbers(g.findtext('size'), 3, what + ' box size'))
        if g.tag == 'sphere':
            return Geometry(name, pose, 'sphere', _numbers(g.findtext('radius'), 1, what))
        if g.tag == 'cylinder':
            size = _numbers(g.findtext('radius'), 1, what + ' radius')
            return Geometry(name, pose, 'cylinder', size + _numbers(g.findtext('length'), 1, what))
        if g.tag == 'plane':
            normal = _numbers(g.findtext('normal') or '0 0 1', 3, what + ' plane normal')
            size = _numbers(g.findtext('size') or '1 1', 2, what + ' plane size')
            return Geometry(name, pose, 'plane', size, normal=normal)  # type: ignore[arg-type]
        if g.tag == 'mesh':
            uri = (g.findtext('uri') or '').strip()
            if not uri:
                raise SdfModelError('%s: <mesh> has no <uri>' % what)
            scale = _numbers(g.findtext('scale') or '1 1 1', 3, what + ' mesh scale')
            return Geometry(
                name,
                pose,
                'mesh',
                uri=_mesh_uri(uri, what, base_dir, find_model_dir),
                scale=scale,  # type: ignore[arg-type]
            )
        if g.tag in ('empty',):
            return None
        raise SdfModelError(
            '%s: geometry <%s> is not built (box, cylinder, sphere, plane, mesh)'
            % (what, shown(g.tag, 30)[1:-1])
        )
    return None


def _inertial(element: Optional[ET.Element], link: str, frames: _Frames, link_tf: Tf) -> Inertial:
    if element is None:
        return Inertial()
    what = 'link %s <inertial>' % shown(link)
    pose, rel = pose_of(element, what)
    if rel:
        pose = compose(inverse(link_tf), compose(frames.resolve(rel), pose))
    mass = _number(element, 'mass', 1.0, what)
    if mass < 0:
        raise SdfModelError('%s: <mass> %g is negative' % (what, mass))
    inertia = element.find('inertia')
    values = tuple(
        _number(inertia, tag, 1.0 if tag in ('ixx', 'iyy', 'izz') else 0.0, what)
        for tag in ('ixx', 'ixy', 'ixz', 'iyy', 'iyz', 'izz')
    )
    return Inertial(mass, pose, values)  # type: ignore[arg-type]


def _axis(
    joint: ET.Element, what: str, joint_tf: Tf, frames: _Frames
) -> Tuple[Tuple[float, ...], ET.Element]:
    axis = joint.find('axis')
    if axis is None:
        return (0.0, 0.0, 1.0), ET.Element('axis')
    xyz_el = axis.find('xyz')
    xyz = _numbers(xyz_el.text if xyz_el is not None else '0 0 1', 3, what + ' <axis><xyz>')
    norm = math.sqrt(sum(c * c for c in xyz))
    if norm == 0:
        raise SdfModelError('%s: <axis><xyz> is zero' % what)
    xyz = tuple(c / norm for c in xyz)
    expressed = xyz_el.get('expressed_in', '') if xyz_el is not None else ''
    if _bool(axis.findtext('use_parent_model_frame')):
        expressed = MODEL_FRAME
    if expressed:
        # from that frame's axes into the joint frame's
        q = multiply(inverse(joint_tf).q, frames.resolve(expressed).q)
        xyz = rotate(q, xyz)
    return xyz, axis


def _joint(
    element: ET.Element, frames: _Frames, link_names: Set[str]
) -> Tuple[Optional[Joint], str]:
    """The joint, or None and why it is dropped."""
    name = element.get('name', '')
    jtype = element.get('type', '')
    what = 'joint %s' % shown(name)
    parent = (element.findtext('parent') or '').strip()
    child = (element.findtext('child') or '').strip()
    if not parent or not child:
        raise SdfModelError('%s lacks <parent> or <child>' % what)
    for end in (parent, child):
        if end != 'world' and end not in link_names:
            raise SdfModelError('%s: %s is no link of the model' % (what, shown(end)))
    if child == 'world':
        return None, "%s: its child is 'world'" % what
    if jtype not in JOINT_TYPES:
        return None, '%s: type %s is not built (revolute, prismatic, fixed, continuous)' % (
            what,
            shown(jtype, 30),
        )
    pose, rel = pose_of(element, what)
    joint_tf = compose(frames.resolve(rel or child), pose)
    axis, axis_el = _axis(element, what, joint_tf, frames)
    limit = axis_el.find('limit')
    dynamics = axis_el.find('dynamics')
    joint = Joint(
        name,
        jtype,
        parent,
        child,
        joint_tf,
        axis,  # type: ignore[arg-type]
        _number(limit, 'lower', -1e16, what),
        _number(limit, 'upper', 1e16, what),
        _number(limit, 'effort', -1.0, what),
        _number(limit, 'velocity', -1.0, what),
        _number(dynamics, 'damping', 0.0, what),
        _number(dynamics, 'friction', 0.0, what),
    )
    return joint, ''


def _link_surface(link: ET.Element, name: str, warnings: List[str]) -> Dict[str, str]:
    """The link's contact surface: pybullet has one per link, ODE one per collision. The
    first collision's is kept and a link whose collisions differ is warned about."""
    said: List[Tuple[str, Dict[str, str]]] = []
    for c in link.findall('collision'):
        where = 'link %s collision %s <surface>' % (shown(name), shown(c.get('name', '')))
        try:
            said.append((c.get('name', ''), sdf_surface_tags(c.find('surface'), where)))
        except SurfaceError as exc:
            raise SdfModelError(str(exc)) from None
    if not said:
        return {}
    if any(tags != said[0][1] for _, tags in said[1:]):
        warnings.append(
            'link %s: its collisions have different <surface>s; pybullet has one per link: '
            'collision %s\'s is used' % (shown(name), shown(said[0][0]))
        )
    return said[0][1]


def _check_name(name: str, kind: str, limits: Limits) -> None:
    try:
        check_name(name, kind, limits.name_length)
    except IllegalName as exc:
        raise SdfModelError(str(exc)) from None


def _check(limits: Limits, name: str, value: float, what: str) -> None:
    try:
        limits.check(name, value, what)
    except LimitError as exc:
        raise SdfModelError(str(exc)) from None


def parse_model(
    model: ET.Element,
    limits: Optional[Limits] = None,
    base_dir: Optional[str] = None,
    find_model_dir: Optional[FindModelDir] = None,
) -> SdfModel:
    """An SDF ``<model>`` element as a link tree. Raises SdfModelError naming the culprit.

    ``base_dir``: where relative mesh URIs start (the SDF file's folder; None for a request).
    ``find_model_dir(name)``: the folder of ``model://name``.
    """
    limits = limits or Limits()
    name = model.get('name', '')
    _check_name(name, 'model', limits)
    what = 'model %s' % shown(name)
    warnings: List[str] = []
    link_elements = model.findall('link')
    joint_elements = model.findall('joint')
    _check(limits, 'links_per_model', len(link_elements), what)
    _check(limits, 'joints_per_model', len(joint_elements), what)
    for nested in model.findall('model'):
        warnings.append('nested model %s is not built' % shown(nested.get('name', '')))
    for nested in model.findall('include'):
        uri = (nested.findtext('name') or nested.findtext('uri') or '').strip()
        warnings.append('nested <include> %s is not built' % shown(uri, 200))
    if not link_elements:
        raise SdfModelError('%s has no <link>' % what)
    frames = _Frames(name)
    names: Set[str] = set()
    for kind, elements in (('link', link_elements), ('joint', joint_elements)):
        for e in elements:
            n = e.get('name', '')
            _check_name(n, kind, limits)
            if n in names:
                raise SdfModelError('%s: the name %s is used twice' % (what, shown(n)))
            names.add(n)
    link_names = {e.get('name', '') for e in link_elements}
    for e in link_elements:
        pose, rel = pose_of(e, 'link %s' % shown(e.get('name', '')))
        frames.add(e.get('name', ''), pose, rel)
    for e in model.findall('frame'):
        n = e.get('name', '')
        if n in names or not n:
            raise SdfModelError('%s: <frame> name %s is empty or used twice' % (what, shown(n)))
        pose, rel = pose_of(e, 'frame %s' % shown(n))
        frames.add(n, pose, rel or e.get('attached_to', ''))
    for e in joint_elements:
        pose, rel = pose_of(e, 'joint %s' % shown(e.get('name', '')))
        child = (e.findtext('child') or '').strip()
        frames.add(e.get('name', ''), pose, rel or (child if child in link_names else ''))
    links: Dict[str, Link] = {}
    for e in link_elements:
        n = e.get('name', '')
        tf = frames.resolve(n)
        link = Link(n, tf, _inertial(e.find('inertial'), n, frames, tf))
        for tag, out in (('collision', link.collisions), ('visual', link.visuals)):
            for g in e.findall(tag):
                geometry = _geometry(g, n, frames, tf, base_dir, find_model_dir)
                if geometry is None:
                    continue
                if tag == 'visual':
                    geometry.color = _color(g)
                out.append(geometry)
        link.extras = e.findall('sensor')
        link.surface = _link_surface(e, n, warnings)
        links[n] = link
    joints: List[Joint] = []
    for e in joint_elements:
        joint, why = _joint(e, frames, link_names)
        if joint is None:
            warnings.append(why + ': dropped')
        else:
            joints.append(joint)
    static = _bool(model.findtext('static'))
    model_pose, _ = pose_of(model, what)
    canonical = model.get('canonical_link') or link_elements[0].get('name') or ''
    if canonical not in links:
        raise SdfModelError('%s: canonical_link %s is no link of it' % (what, shown(canonical)))
    root, joints, dropped = _tree(links, joints, canonical, static, warnings)
    for n in dropped:
        del links[n]
    return SdfModel(
        name, model_pose, static, links, joints, root, model.findall('plugin'), warnings
    )


def _tree(
    links: Dict[str, Link], joints: List[Joint], canonical: str, static: bool, warnings: List[str]
) -> Tuple[str, List[Joint], List[str]]:
    """The root, the joints of a spanning tree from it, and the links it does not reach."""
    to_world = [j for j in joints if j.parent == 'world']
    root = 'world' if (static or to_world) else canonical
    if root != 'world':
        children = {j.child for j in joints}
        if canonical in children:  # the tree's own root, as joints point, is the better root
            roots = [n for n in links if n not in children]
            root = roots[0] if roots else canonical
    kept: List[Joint] = []
    reached = {root}
    pending = list(joints)

    def grow(start: str) -> None:
        nonlocal pending
        frontier = [start]
        while frontier:
            current = frontier.pop(0)
            rest = []
            for j in pending:
                if j.parent != current:
                    rest.append(j)
                elif j.child in reached:
                    warnings.append(
                        'joint %s closes a kinematic loop (link %s already has a parent): dropped'
                        % (shown(j.name), shown(j.child))
                    )
                else:
                    kept.append(j)
                    reached.add(j.child)
                    frontier.append(j.child)
            pending = rest

    grow(root)
    if root == 'world':
        # A static model's links stay where they are, as in Gazebo: each free one is fixed.
        for n, link in links.items():
            if static and n not in reached and all(j.child != n for j in pending):
                kept.append(Joint('%s_world_joint' % n, 'fixed', 'world', n, link.pose))
                reached.add(n)
                grow(n)
    for j in pending:
        warnings.append(
            'joint %s: link %s is not tied to root link %s by the joints built: dropped'
            % (shown(j.name), shown(j.parent), shown(root))
        )
    dropped = [n for n in links if n not in reached]
    for n in dropped:
        warnings.append(
            'link %s is not tied to root link %s by the joints built: dropped'
            % (shown(n), shown(root))
        )
    if static:  # nothing of a static model moves
        kept = [j if j.type == 'fixed' else _fixed(j) for j in kept]
    return root, kept, dropped


def _fixed(joint: Joint) -> Joint:
    return Joint(joint.name, 'fixed', joint.parent, joint.child, joint.pose)


# -------------------------------------------------------------------------------- SDF text
def parse_sdf_text(
    xml_text: str, limits: Optional[Limits] = None, what: str = 'SDF model'
) -> ET.Element:
    """The ``<model>`` element of an SDF document from a request, parsed as hostile input
    (or its ``<robot>`` root: URDF)."""
    limits = limits or Limits()
    _check(limits, 'description_bytes', safe_xml.utf8_size(xml_text), what)
    budget = int(ELEMENTS_PER_PART * (limits.links_per_model + limits.joints_per_model))
    try:
        root = safe_xml.parse(xml_text, what, budget)
    except safe_xml.XmlRefused as exc:
        raise SdfModelError(str(exc)) from None
    if root.tag in ('model', 'robot'):  # a <robot> is the caller's to take as URDF
        return root
    if root.tag == 'sdf':
        models = root.findall('model')
        if len(models) == 1:
            return models[0]
        if len(models) > 1:
            raise SdfModelError('%s holds %d <model>s; spawn one at a time' % (what, len(models)))
        if root.find('light') is not None:
            raise SdfModelError('%s is a <light>: the stand-in has no lights to spawn' % what)
        includes = root.findall('world/include')
        if len(includes) == 1:  # what spawn_model -database sends
            return includes[0]
    raise SdfModelError('%s has no <sdf><model> (root <%s>)' % (what, shown(root.tag, 40)[1:-1]))


def model_dir_finder(model_paths: Sequence[str]) -> FindModelDir:
    """model://NAME's folder: the first ``model_paths`` entry holding NAME (GAZEBO_MODEL_PATH)."""

    def find(name: str) -> str:
        for base in model_paths:
            folder = os.path.join(base, name)
            if os.path.isdir(folder):
                return folder
        raise LookupError(
            'model://%s not found; tried: %s (set GAZEBO_MODEL_PATH or export gazebo_model_path)'
            % (name, ', '.join(model_paths))
        )

    return find


def parse_request(
    xml_text: str,
    name: str,
    limits: Optional[Limits] = None,
    find_model_dir: Optional[FindModelDir] = None,
    find_model: Optional[Callable[[str], str]] = None,
) -> Optional[SdfModel]:
    """A spawn_sdf_model request's SDF as Gazebo's spawn reads it: the ``<model name>``
    becomes ``name``. An ``<sdf><world><include>`` (spawn_model -database) is looked up with
    ``find_model`` (``model://NAME`` -> its SDF file); its ``<pose>`` replaces the model's.
    None when the document is a URDF ``<robot>`` (spawn_sdf_model takes those too)."""
    what = 'SDF model %s' % shown(name)
    model = parse_sdf_text(xml_text, limits, what)
    if model.tag == 'robot':
        return None
    base_dir, include_pose = None, None
    if model.tag == 'include':
        include_pose, _ = pose_of(model, what + ' <include>')
        model, base_dir = _included(model, limits, what, find_model)
    model.set('name', name)
    parsed = parse_model(model, limits, base_dir, find_model_dir)
    if include_pose is not None:
        parsed.pose = include_pose
    return parsed


def _included(
    include: ET.Element,
    limits: Optional[Limits],
    what: str,
    find_model: Optional[Callable[[str], str]],
) -> Tuple[ET.Element, str]:
    """The ``<model>`` an ``<include>`` names, and its file's folder."""
    uri = (include.findtext('uri') or '').strip()
    if find_model is None:
        raise SdfModelError('%s: cannot look up %s: no model path' % (what, shown(uri, 200)))
    try:
        path = find_model(uri)
        with open(path, encoding='utf-8') as f:
            text = f.read(int((limits or Limits()).description_bytes) + 1)
    except (LookupError, ValueError) as exc:  # resource_paths.ResourceNotFound is a ValueError
        raise SdfModelError('%s: %s' % (what, exc)) from None
    except OSError as exc:
        raise SdfModelError('%s: cannot read %s: %s' % (what, shown(uri, 200), exc.strerror))
    model = parse_sdf_text(text, limits, '%s (%s)' % (what, path))
    if model.tag != 'model':
        raise SdfModelError('%s: %s holds no <model>' % (what, path))
    return model, os.path.dirname(path)
