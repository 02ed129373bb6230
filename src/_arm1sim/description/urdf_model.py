"""Reads what the simulator needs from a URDF: joints, limits, transmissions, Gazebo tags.

A robot description may come from any ROS client, so it is parsed as hostile:
defusedxml with no DTD, a bounded size and tree (safe_xml), the world's Limits
on links, joints and names, and mesh URIs that stay where they point.
"""

from __future__ import annotations

import logging
import math
import os
import stat
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from typing import Callable, Dict, Optional, Union

from . import safe_xml
from .joint_limits import JointLimits, SoftLimits, canonical_interface
from .limits import LimitError, Limits
from .mesh_limits import MESH_EXTENSIONS, MeshError, count_triangles, mesh_kind
from .names import shown
from .surface import SurfaceError, sdf_surface_tags

log = logging.getLogger('_arm1sim.description')

ACTUATED_TYPES = ('revolute', 'continuous', 'prismatic')
CONTROL_PLUGIN = 'libgazebo_ros_control.so'
# roboticsgroup's mimic joint plugin, under its old and its current name
MIMIC_PLUGINS = (
    'libroboticsgroup_upatras_gazebo_mimic_joint_plugin.so',
    'libroboticsgroup_gazebo_mimic_joint_plugin.so',
)


class UrdfError(ValueError):
    """The robot description is unusable; the message names the culprit."""


class UrdfLimitError(UrdfError, LimitError):
    """The description exceeds one of the world's Limits (caught as either kind)."""


# Elements a description may hold for each link and joint the limits allow: a link with
# visual, collision, inertial and Gazebo tags has about 20, so 100 is room to spare.
ELEMENTS_PER_PART = 100


@dataclass
class Joint:
    name: str
    type: str
    parent: str
    child: str
    limits: JointLimits = field(default_factory=JointLimits)


@dataclass
class Transmission:
    name: str
    joint: str  # the first <joint>: a SimpleTransmission has one
    interfaces: list  # the first joint's hardware interfaces
    type: str = 'transmission_interface/SimpleTransmission'
    # every <joint> as (name, role): a vendor's state transmissions name several
    joints: list = field(default_factory=list)


@dataclass
class Mimic:
    """A joint that follows another: follower = leader * multiplier + offset."""

    follower: str
    leader: str
    multiplier: float = 1.0
    offset: float = 0.0
    max_effort: Optional[float] = None  # None: the follower's effort limit
    sensitiveness: float = 0.0  # acts only when |target - position| >= it
    plugin: bool = False  # roboticsgroup's plugin (else a URDF <mimic>, which Gazebo 11 ignores)
    # <hasPID>: the parameter namespace of the follower's PID gains (the plugin's
    # <robotNamespace> joined with the tag's text, else gazebo_ros_control/pid_gains/<follower>);
    # None: no <hasPID>, the follower is set to its target
    pid_gains: Optional[str] = None


@dataclass
class ControlPlugin:
    """The gazebo_ros_control ``<plugin>`` of a description."""

    robot_namespace: Optional[str] = None  # None: no <robotNamespace> (empty: the root)
    robot_sim_type: str = 'gazebo_ros_control/DefaultRobotHWSim'
    control_period: Optional[float] = None


@dataclass
class RobotModel:
    name: str
    root_link: str
    links: list
    joints: dict  # name -> Joint, in document order
    transmissions: list
    control_plugin: Optional[ControlPlugin] = None
    gazebo_refs: dict = field(default_factory=dict)  # link -> {tag: text}
    sensors: list = field(default_factory=list)  # (link, <sensor> Element)
    mimics: list = field(default_factory=list)  # Mimic, one per follower
    model_plugins: list = field(default_factory=list)  # <plugin> Elements of <gazebo> blocks
    # (reference, <sensor> Element) of <gazebo reference> blocks naming no link of the URDF:
    # Gazebo's URDF->SDF inserts an extension into its link only, so these go nowhere.
    unplaced_sensors: list = field(default_factory=list)

    def actuated_joints(self):
        """Joints named by a transmission, with their hardware interface. A transmission of
        several joints drives none, as default_robot_hw_sim skips it (a vendor's state and
        model interfaces are such; its own hardware sim reads them)."""
        out = []
        for t in self.transmissions:
            if len(t.joints) > 1:
                continue
            joint = self.joints.get(t.joint)
            if joint is None:
                raise UrdfError(
                    "transmission '%s' names joint '%s', which is not in the URDF"
                    % (t.name, t.joint)
                )
            if joint.type in ACTUATED_TYPES:
                out.append((joint, t.interfaces[0] if t.interfaces else None))
        return out


def _float(text, what):
    try:
        return float(text)
    except (TypeError, ValueError):
        raise UrdfError('%s: %r is not a number' % (what, text))


def _check(limits: Limits, name: str, value: float, what: str) -> None:
    try:
        limits.check(name, value, what)
    except LimitError as exc:
        raise UrdfLimitError(str(exc)) from None


def parse_description(xml_text: Union[str, bytes], limits: Optional[Limits] = None) -> ET.Element:
    """The root element of a robot description from a request, parsed as hostile input.

    Refused before parsing when over ``limits.description_bytes``; parsed with no
    DTD (so no entity expansion or external entity) and at most
    ELEMENTS_PER_PART elements for each link and joint the limits allow.
    """
    limits = limits or Limits()
    _check(limits, 'description_bytes', safe_xml.utf8_size(xml_text), 'robot description')
    budget = int(ELEMENTS_PER_PART * (limits.links_per_model + limits.joints_per_model))
    try:
        return safe_xml.parse(xml_text, 'robot description', budget)
    except safe_xml.TooManyElements as exc:
        raise UrdfLimitError(
            '%s: %d for each link and joint the limits allow (raise them with the world node '
            'parameters ~limits/links_per_model and ~limits/joints_per_model or the world file '
            'plugin arm1_limits)' % (exc, ELEMENTS_PER_PART)
        ) from None
    except safe_xml.XmlRefused as exc:
        raise UrdfError(str(exc)) from None


def _named(elements: list, kind: str, limits: Limits) -> list:
    """The names of ``elements``, each present and within limits.name_length."""
    names: list = []
    seen: set = set()
    for e in elements:
        name = e.get('name')
        if not name:
            raise UrdfError('a <%s> has no name' % kind)
        _check(limits, 'name_length', len(name), '%s name %s' % (kind, shown(name)))
        if name in seen:  # urdfdom refuses it too; pybullet would say only "Cannot load URDF"
            raise UrdfError('%s %s is not unique' % (kind, shown(name)))
        seen.add(name)
        names.append(name)
    return names


def _check_inertial(link: ET.Element) -> None:
    """A link's <inertial> mass and inertia are finite numbers (NaN would reach pybullet,
    lumped into a parent or not, and poison the whole model's motion)."""
    inertial = link.find('inertial')
    if inertial is None:
        return
    what = 'link %s <inertial>' % shown(link.get('name') or '')
    for tag, keys in (
        ('mass', ('value',)),
        ('inertia', ('ixx', 'iyy', 'izz', 'ixy', 'ixz', 'iyz')),
    ):
        element = inertial.find(tag)
        if element is None:
            continue
        for key in keys:
            text = element.get(key)
            if text is not None and not math.isfinite(
                _float(text, '%s <%s> %s' % (what, tag, key))
            ):
                raise UrdfError('%s <%s> %s: %r is not a finite number' % (what, tag, key, text))
    mass = inertial.find('mass')
    if mass is not None and _float(mass.get('value', '0'), what) < 0:
        raise UrdfError('%s <mass> %s is negative' % (what, mass.get('value')))


# Sizes of each shape: (attribute, how many numbers); none may be non-finite, nor negative
# but a mesh's scale
# (pybullet takes them: a NaN box fell through the ground, a NaN cylinder flew off).
SHAPE_SIZES = {
    'box': (('size', 3),),
    'sphere': (('radius', 1),),
    'cylinder': (('radius', 1), ('length', 1)),
    'mesh': (('scale', 3),),
}


def _check_geometry(link: ET.Element) -> None:
    """Each collision's and visual's shape sizes are finite and not negative."""
    for kind in ('collision', 'visual'):
        for geometry in link.findall(kind + '/geometry'):
            for shape in geometry:
                for key, count in SHAPE_SIZES.get(shape.tag, ()):
                    text = shape.get(key)
                    if text is None:
                        continue
                    try:
                        values = [float(v) for v in text.split()]
                    except ValueError:
                        values = []
                    # a mesh's scale may mirror it (negative); sizes may not
                    low = -math.inf if shape.tag == 'mesh' else 0.0
                    if len(values) != count or not all(
                        math.isfinite(v) and v >= low for v in values
                    ):
                        raise UrdfError(
                            'link %s <%s> <%s %s>: %s is not %d finite number(s)%s'
                            % (
                                shown(link.get('name') or ''),
                                kind,
                                shape.tag,
                                key,
                                shown(text),
                                count,
                                '' if shape.tag == 'mesh' else ' >= 0',
                            )
                        )


# pybullet's loadURDF builds each link's shapes in one call on the physics thread: a box or
# mesh costs it ~7 us, a sphere, cylinder or capsule ~200-380 us (it is tessellated into a
# mesh to be drawn), measured on a busy 2-core machine; shapes_per_model counts in these units.
ROUND_SHAPES = ('sphere', 'cylinder', 'capsule')
ROUND_SHAPE_UNITS = 20
SHAPES_COUNTED = '(<visual> and <collision> elements; a sphere, cylinder or capsule counts %d)' % (
    ROUND_SHAPE_UNITS
)


def shape_units(links: list) -> int:
    """What the links' visuals and collisions cost pybullet to build, in box shapes."""
    units = 0
    for link in links:
        for kind in ('visual', 'collision'):
            for element in link.iterfind(kind):
                round_ = any(element.find('geometry/' + tag) is not None for tag in ROUND_SHAPES)
                units += ROUND_SHAPE_UNITS if round_ else 1
    return units


def parse_urdf(
    xml_text: Union[str, bytes, ET.Element], limits: Optional[Limits] = None
) -> RobotModel:
    """What the simulator needs of a URDF (its text, or its root as parse_description gave
    it); ``limits`` default to Limits()'s defaults.

    Raises UrdfError naming the culprit; UrdfLimitError (also a LimitError) when
    the description exceeds a limit.
    """
    limits = limits or Limits()
    if isinstance(xml_text, ET.Element):
        root = xml_text
    else:
        root = parse_description(xml_text, limits)
    if root.tag != 'robot':
        raise UrdfError('robot description has root <%s>, expected <robot>' % root.tag)
    robot = 'robot %s' % shown(root.get('name') or '')
    link_elements, joint_elements = root.findall('link'), root.findall('joint')
    _check(limits, 'links_per_model', len(link_elements), robot)
    _check(limits, 'joints_per_model', len(joint_elements), robot)
    links = _named(link_elements, 'link', limits)
    for e in link_elements:
        _check_inertial(e)
        _check_geometry(e)
    _check(limits, 'shapes_per_model', shape_units(link_elements), robot + ' ' + SHAPES_COUNTED)
    if not links:
        raise UrdfError("robot '%s' has no <link>" % root.get('name'))
    joints = {}
    mimics: list = []
    for j, name in zip(joint_elements, _named(joint_elements, 'joint', limits)):
        jtype = j.get('type')
        parent, child = j.find('parent'), j.find('child')
        if parent is None or child is None:
            raise UrdfError("joint '%s' lacks <parent> or <child>" % name)
        joint_limits = JointLimits()
        lim = j.find('limit')
        if lim is not None:
            what = "joint '%s' <limit>" % name
            joint_limits = JointLimits(
                lower=_float(lim.get('lower', '0'), what) if jtype != 'continuous' else None,
                upper=_float(lim.get('upper', '0'), what) if jtype != 'continuous' else None,
                effort=_float(lim.get('effort', '0'), what),
                velocity=_float(lim.get('velocity', '0'), what),
            )
            safety = j.find('safety_controller')
            if safety is not None:
                what = "joint '%s' <safety_controller>" % name
                if safety.get('k_velocity') is None:
                    raise UrdfError('%s has no k_velocity' % what)
                joint_limits.soft = SoftLimits(
                    *(
                        _float(safety.get(key, '0'), what)
                        for key in (
                            'soft_lower_limit',
                            'soft_upper_limit',
                            'k_position',
                            'k_velocity',
                        )
                    )
                )
        joints[name] = Joint(
            name, jtype or '', parent.get('link') or '', child.get('link') or '', joint_limits
        )
        mimic = j.find('mimic')
        if mimic is not None:
            what = "joint '%s' <mimic>" % name
            mimics.append(
                Mimic(
                    name,
                    mimic.get('joint') or '',
                    _float(mimic.get('multiplier', '1'), what),
                    _float(mimic.get('offset', '0'), what),
                )
            )
    children = {j.child for j in joints.values()}
    roots = [name for name in links if name not in children]
    if len(roots) != 1:
        raise UrdfError('robot must have exactly one root link, found %s' % roots)
    transmissions = []
    for t in root.findall('transmission'):
        tj = t.find('joint')
        if tj is None:
            continue
        ifaces = [canonical_interface(h.text) for h in tj.findall('hardwareInterface')]
        transmissions.append(
            Transmission(
                t.get('name') or '',
                tj.get('name') or '',
                ifaces,
                (t.findtext('type') or Transmission.type).strip(),
                [
                    (j.get('name') or '', (j.findtext('role') or '').strip())
                    for j in t.findall('joint')
                ],
            )
        )
    model = RobotModel(root.get('name') or '', roots[0], links, joints, transmissions)
    blocks: Dict[str, Dict[str, str]] = {}  # reference -> the tags its <collision>s' <surface> say
    for g in root.findall('gazebo'):
        ref = g.get('reference')
        if ref is None:
            model.model_plugins.extend(g.findall('plugin'))
            for p in g.findall('plugin'):
                if p.get('filename') == CONTROL_PLUGIN:
                    period = p.findtext('controlPeriod')
                    model.control_plugin = ControlPlugin(
                        _stripped(p.findtext('robotNamespace')),
                        (p.findtext('robotSimType') or ControlPlugin.robot_sim_type).strip(),
                        _float(period, 'controlPeriod') if period else None,
                    )
                elif p.get('filename') in MIMIC_PLUGINS:
                    mimics.append(_mimic_plugin(p))
            continue
        tags = model.gazebo_refs.setdefault(ref, {})
        for child in g:
            if child.tag == 'sensor':
                if ref in links:
                    model.sensors.append((ref, child))
                else:
                    model.unplaced_sensors.append((ref, child))
            elif child.tag == 'collision':
                said = blocks.setdefault(ref, {})
                said.update(_collision_block(child, "<gazebo reference='%s'> <collision>" % ref))
            else:
                tags[child.tag] = _key_value(child)
    # sdformat writes a reference's flat tags (mu1, kp, ...) over its <collision> blocks'
    for ref, said in blocks.items():
        for tag, text in said.items():
            model.gazebo_refs[ref].setdefault(tag, text)
    model.mimics = _checked_mimics(mimics, joints)
    return model


def _key_value(tag: ET.Element) -> str:
    """A ``<gazebo reference>`` tag's value as sdformat's URDF reader takes it: its ``value``
    attribute when it has one (``<mu1 value="100.0"/>``, Hello Robot Stretch's), else its
    text."""
    value = tag.get('value')
    return (value if value is not None else tag.text or '').strip()


def _collision_block(block: ET.Element, where: str) -> Dict[str, str]:
    """A ``<gazebo reference>``'s ``<collision>`` block: sdformat's URDF reader inserts its
    children into every collision of the link; its ``<surface>`` becomes the link's tags
    (pybullet has one surface per link). Its other children (max_contacts, ...) have no
    pybullet setting."""
    try:
        return sdf_surface_tags(block.find('surface'), where)
    except SurfaceError as exc:
        raise UrdfError(str(exc)) from None


def _stripped(text: Optional[str]) -> Optional[str]:
    return None if text is None else text.strip()


def _mimic_plugin(p: ET.Element) -> Mimic:
    """roboticsgroup's plugin: <joint> leads, <mimicJoint> follows; with <hasPID> a PID
    drives it, its gains read where the plugin reads them (Mimic.pid_gains)."""
    what = "mimic joint plugin '%s'" % (p.get('name') or '')

    def number(tag: str, default: Optional[float]) -> Optional[float]:
        text = p.findtext(tag)
        return _float(text, '%s <%s>' % (what, tag)) if text and text.strip() else default

    follower = (p.findtext('mimicJoint') or '').strip()
    if not follower:
        raise UrdfError('%s has no <mimicJoint>' % what)
    has_pid = p.find('hasPID')
    gains = None
    if has_pid is not None:
        # as the plugin: ros::NodeHandle(NodeHandle(<robotNamespace>), <hasPID> or default)
        name = (has_pid.text or '').strip() or 'gazebo_ros_control/pid_gains/' + follower
        namespace = (p.findtext('robotNamespace') or '').strip().strip('/')
        gains = name if name.startswith('/') else '/'.join(['', namespace, name]).replace('//', '/')
    return Mimic(
        follower,
        (p.findtext('joint') or '').strip(),
        number('multiplier', 1.0) or 0.0,
        number('offset', 0.0) or 0.0,
        number('maxEffort', None),
        abs(number('sensitiveness', 0.0) or 0.0),
        plugin=True,
        pid_gains=gains,
    )


def _checked_mimics(mimics: list, joints: dict) -> list:
    """One Mimic per follower (the plugin's wins over <mimic>), both joints movable."""
    by_follower = {}
    for m in mimics:
        for role, name in (('follower', m.follower), ('leader', m.leader)):
            joint = joints.get(name)
            if joint is None or joint.type not in ACTUATED_TYPES:
                raise UrdfError(
                    'mimic of joint %s: %s %s is not a movable joint of the URDF'
                    % (shown(m.follower), role, shown(name))
                )
        numbers = (m.multiplier, m.offset, m.sensitiveness, m.max_effort or 0.0)
        if not all(math.isfinite(v) for v in numbers):
            raise UrdfError(
                "mimic of joint '%s': multiplier, offset, sensitiveness and maxEffort "
                'must be finite' % m.follower
            )
        if m.follower == m.leader:
            raise UrdfError("joint '%s' mimics itself" % m.follower)
        by_follower[m.follower] = m
    return list(by_follower.values())


def resolve_mesh_uris(
    xml_text: Union[str, bytes], find_package: Callable[[str], str], limits: Optional[Limits] = None
) -> str:
    """The description with every link's mesh URI rewritten to an absolute path, each checked.

    ``find_package(name)`` returns a package's directory or raises LookupError.
    ``package://pkg/rel`` must stay inside pkg's directory once ``..`` is
    collapsed (symlinks the package itself holds are followed: installed and
    devel-space packages are made of them). ``file://`` URIs and paths are
    taken as they are, as Gazebo does. Each mesh must be a regular .stl, .obj or
    .dae file within ``limits.mesh_bytes`` and ``limits.mesh_triangles``. Errors
    name the link, the URI and the path, never the file's contents.

    A mesh file that is not there (or whose package is unknown) does not refuse the
    model, as in Gazebo, whose server logs "Unable to load mesh" and goes on: its
    ``<visual>`` is left out, its ``<collision>`` too (the link keeps its inertia and
    collides with nothing), each with a warning naming the link and the file.
    """
    limits = limits or Limits()
    root = parse_description(xml_text, limits)
    checked: Dict[str, Optional[str]] = {}  # uri -> path (None: missing), checked once
    for link in root.findall('link'):
        name = link.get('name') or ''
        for part in list(link):
            if part.tag not in ('visual', 'collision'):
                continue
            for mesh in part.iter('mesh'):
                uri = mesh.get('filename', '')
                if uri not in checked:
                    checked[uri] = _checked_mesh(uri, name, find_package, limits)
                path = checked[uri]
                if path is None:
                    log.warning(
                        "link '%s': %s mesh %s not found: %s",
                        name,
                        part.tag,
                        shown(uri, 200),
                        'left out (the model spawns without it, as in Gazebo)'
                        if part.tag == 'visual'
                        else 'the link keeps its inertia and collides with nothing (as in Gazebo)',
                    )
                    link.remove(part)
                    break
                mesh.set('filename', path)
    return ET.tostring(root, encoding='unicode')


class _MissingPackage(UrdfError):
    """A package:// URI's package is not on the package path: the mesh is missing."""


def _mesh_path(uri: str, where: str, find_package: Callable[[str], str]) -> str:
    """The file ``uri`` names, package:// kept inside its package."""
    scheme, sep, rest = uri.partition('://')
    if not sep:
        path = uri
    elif scheme == 'file':
        path = rest
    elif scheme == 'package':
        pkg, _, rel = rest.partition('/')
        if not pkg:
            raise UrdfError('%s names no package' % where)
        try:
            pkg_dir = os.path.abspath(find_package(pkg))  # abspath also collapses '..'
        except LookupError:
            raise _MissingPackage(
                "%s: package '%s' not found on the ROS package path" % (where, pkg)
            ) from None
        path = os.path.normpath(os.path.join(pkg_dir, rel))
        if os.path.commonpath([pkg_dir, path]) != pkg_dir:
            raise UrdfError(
                "%s leaves package '%s': a package:// URI must name a file inside "
                "its package's directory" % (where, pkg)
            )
        return path
    else:
        raise UrdfError(
            "%s: URI scheme '%s://' is not supported (package://, file:// or a path)"
            % (where, shown(scheme, 30)[1:-1])
        )
    # as Gazebo: a path is opened as written, a relative one from the world's directory
    return path if os.path.isabs(path) else os.path.join(os.getcwd(), path)


def _checked_mesh(
    uri: str, link: str, find_package: Callable[[str], str], limits: Limits
) -> Optional[str]:
    """The path of ``uri``'s mesh once it passed every check, None for a file (or package)
    that is not there; UrdfError otherwise."""
    where = 'link %s: mesh %s' % (shown(link or ''), shown(uri, 200))
    try:
        path = _mesh_path(uri, where, find_package)
    except _MissingPackage:
        return None
    kind = mesh_kind(path)
    if kind is None:
        raise UrdfError(
            '%s: only %s meshes (any case) are loaded' % (where, ', '.join(MESH_EXTENSIONS))
        )
    try:
        st = os.stat(path)
    except (FileNotFoundError, NotADirectoryError):
        return None
    except OSError as exc:
        raise UrdfError('%s: %s cannot be read: %s' % (where, path, exc.strerror)) from None
    if not stat.S_ISREG(st.st_mode):  # a fifo or device would block or never end
        raise UrdfError('%s: %s is not a regular file' % (where, path))
    _check(limits, 'mesh_bytes', st.st_size, where)
    try:
        triangles = count_triangles(path, stop_above=limits.mesh_triangles)
    except MeshError as exc:
        raise UrdfError('%s: %s' % (where, exc)) from None
    if triangles > limits.mesh_triangles and kind != '.stl':
        where += ' (counted until past the limit)'  # OBJ and COLLADA stop reading there
    _check(limits, 'mesh_triangles', triangles, where)
    return path
