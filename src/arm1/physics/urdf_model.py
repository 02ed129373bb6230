"""Reads what the simulator needs from a URDF: joints, limits, transmissions, Gazebo tags."""
import os
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

from ..control.hardware_interface import JointLimits, canonical_interface

ACTUATED_TYPES = ('revolute', 'continuous', 'prismatic')
CONTROL_PLUGIN = 'libgazebo_ros_control.so'


class UrdfError(ValueError):
    """The robot description is unusable; the message names the culprit."""


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
    joint: str
    interfaces: list


@dataclass
class ControlPlugin:
    """The gazebo_ros_control ``<plugin>`` of a description."""
    robot_namespace: str = ''
    robot_sim_type: str = 'gazebo_ros_control/DefaultRobotHWSim'
    control_period: float = None


@dataclass
class RobotModel:
    name: str
    root_link: str
    links: list
    joints: dict  # name -> Joint, in document order
    transmissions: list
    control_plugin: ControlPlugin = None
    gazebo_refs: dict = field(default_factory=dict)  # link -> {tag: text}
    sensors: list = field(default_factory=list)  # (link, <sensor> Element)

    def actuated_joints(self):
        """Joints named by a transmission, with their hardware interface."""
        out = []
        for t in self.transmissions:
            joint = self.joints.get(t.joint)
            if joint is None:
                raise UrdfError("transmission '%s' names joint '%s', which is not in the URDF"
                                % (t.name, t.joint))
            if joint.type in ACTUATED_TYPES:
                out.append((joint, t.interfaces[0] if t.interfaces else None))
        return out


def _float(text, what):
    try:
        return float(text)
    except (TypeError, ValueError):
        raise UrdfError('%s: %r is not a number' % (what, text))


def parse_urdf(xml_text):
    try:
        root = ET.fromstring(xml_text)
    except ET.ParseError as exc:
        raise UrdfError('robot description is not well-formed XML: %s' % exc)
    if root.tag != 'robot':
        raise UrdfError('robot description has root <%s>, expected <robot>' % root.tag)
    links = [l.get('name') for l in root.findall('link')]
    if not links:
        raise UrdfError("robot '%s' has no <link>" % root.get('name'))
    joints = {}
    for j in root.findall('joint'):
        name, jtype = j.get('name'), j.get('type')
        parent, child = j.find('parent'), j.find('child')
        if parent is None or child is None:
            raise UrdfError("joint '%s' lacks <parent> or <child>" % name)
        limits = JointLimits()
        lim = j.find('limit')
        if lim is not None:
            what = "joint '%s' <limit>" % name
            limits = JointLimits(
                lower=_float(lim.get('lower', '0'), what) if jtype != 'continuous' else None,
                upper=_float(lim.get('upper', '0'), what) if jtype != 'continuous' else None,
                effort=_float(lim.get('effort', '0'), what),
                velocity=_float(lim.get('velocity', '0'), what))
        joints[name] = Joint(name, jtype, parent.get('link'), child.get('link'), limits)
    children = {j.child for j in joints.values()}
    roots = [l for l in links if l not in children]
    if len(roots) != 1:
        raise UrdfError('robot must have exactly one root link, found %s' % roots)
    transmissions = []
    for t in root.findall('transmission'):
        j = t.find('joint')
        if j is None:
            continue
        ifaces = [canonical_interface(h.text) for h in j.findall('hardwareInterface')]
        transmissions.append(Transmission(t.get('name'), j.get('name'), ifaces))
    model = RobotModel(root.get('name'), roots[0], links, joints, transmissions)
    for g in root.findall('gazebo'):
        ref = g.get('reference')
        if ref is None:
            for p in g.findall('plugin'):
                if p.get('filename') == CONTROL_PLUGIN:
                    period = p.findtext('controlPeriod')
                    model.control_plugin = ControlPlugin(
                        (p.findtext('robotNamespace') or '').strip(),
                        (p.findtext('robotSimType') or ControlPlugin.robot_sim_type).strip(),
                        _float(period, 'controlPeriod') if period else None)
            continue
        tags = model.gazebo_refs.setdefault(ref, {})
        for child in g:
            if child.tag == 'sensor':
                model.sensors.append((ref, child))
            else:
                tags[child.tag] = (child.text or '').strip()
    return model


def resolve_mesh_uris(xml_text, find_package):
    """Rewrite ``package://`` and ``file://`` mesh URIs to absolute paths.

    ``find_package(name)`` returns a package's directory or raises LookupError.
    A mesh that does not exist raises UrdfError naming its link and path.
    """
    root = ET.fromstring(xml_text)
    for link in root.findall('link'):
        for mesh in link.iter('mesh'):
            uri = mesh.get('filename', '')
            if uri.startswith('package://'):
                pkg, _, rel = uri[len('package://'):].partition('/')
                try:
                    path = os.path.join(find_package(pkg), rel)
                except LookupError:
                    raise UrdfError("link '%s': mesh %s: package '%s' not found on the ROS "
                                    "package path" % (link.get('name'), uri, pkg))
            elif uri.startswith('file://'):
                path = uri[len('file://'):]
            else:
                path = uri
            if not os.path.isfile(path):
                raise UrdfError("link '%s': mesh file not found: %s (from %s)"
                                % (link.get('name'), path, uri))
            mesh.set('filename', path)
    return ET.tostring(root, encoding='unicode')
