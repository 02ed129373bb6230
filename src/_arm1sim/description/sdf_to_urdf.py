"""An SDF model (sdf_model's link tree) written out as URDF, for the URDF spawn path.

URDF puts each link's frame at its parent joint, so the converter moves every element
into that frame; the root link's frame is the model frame, so that the model's pose (model
states) is Gazebo's. Link states therefore report the model frame for the root link and
the joint frame for the others, where Gazebo reports each link's own: they differ only
where a root link's or a joint's ``<pose>`` is not zero.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from typing import Callable, Dict, List, Optional, Sequence, Tuple

from .limits import Limits
from .pose_math import rpy_from_quat
from .sdf_model import (
    IDENTITY,
    UNLIMITED,
    FindModelDir,
    Geometry,
    SdfModel,
    Tf,
    compose,
    inverse,
    parse_request,
)


def _num(v: float) -> str:
    return repr(float(v)) if v != 0 else '0'


def _origin(parent: ET.Element, tf: Tf) -> None:
    if tf == IDENTITY:
        return
    ET.SubElement(
        parent,
        'origin',
        xyz=' '.join(_num(v) for v in tf.p),
        rpy=' '.join(_num(v) for v in rpy_from_quat(tf.q)),
    )


def _geometry_urdf(parent: ET.Element, tag: str, g: Geometry, frame: Tf, link: str) -> None:
    element = ET.SubElement(parent, tag, name=g.name) if g.name else ET.SubElement(parent, tag)
    pose = compose(frame, g.pose)
    geometry = ET.Element('geometry')
    if g.kind == 'box':
        ET.SubElement(geometry, 'box', size=' '.join(_num(v) for v in g.size))
    elif g.kind == 'sphere':
        ET.SubElement(geometry, 'sphere', radius=_num(g.size[0]))
    elif g.kind == 'cylinder':
        ET.SubElement(geometry, 'cylinder', radius=_num(g.size[0]), length=_num(g.size[1]))
    elif g.kind == 'mesh':
        ET.SubElement(geometry, 'mesh', filename=g.uri, scale=' '.join(_num(v) for v in g.scale))
    else:  # a plane as a thin box, its top face on the plane
        n = g.normal
        norm = math.sqrt(sum(c * c for c in n)) or 1.0
        n = (n[0] / norm, n[1] / norm, n[2] / norm)
        pose = compose(pose, Tf((0.0, 0.0, 0.0), _z_to(n)))
        pose = compose(pose, Tf((0.0, 0.0, -0.005), IDENTITY.q))
        ET.SubElement(geometry, 'box', size='%s %s 0.01' % (_num(g.size[0]), _num(g.size[1])))
    _origin(element, pose)
    element.append(geometry)
    if tag == 'visual' and g.color is not None:
        # URDF materials are global by name: the link's name keeps each its own
        material = ET.SubElement(element, 'material', name='%s::%s' % (link, g.name or tag))
        ET.SubElement(material, 'color', rgba=' '.join(_num(v) for v in g.color))


def _z_to(n: Sequence[float]) -> Tuple[float, float, float, float]:
    """The rotation taking +z onto unit vector ``n``."""
    x, y, z = -n[1], n[0], 0.0  # z cross n
    w = 1.0 + n[2]
    if w < 1e-9:
        return (1.0, 0.0, 0.0, 0.0)
    norm = math.sqrt(x * x + y * y + z * z + w * w)
    return (x / norm, y / norm, z / norm, w / norm)


def to_urdf(model: SdfModel, name: Optional[str] = None) -> str:
    """URDF text of the model's tree, named ``name`` (default: the model's).

    The URDF root link's frame is the model frame; links' ``<sensor>``s, ``<surface>``
    values and ``<plugin>``s go into ``<gazebo>`` blocks as Gazebo's URDF reader takes them.
    """
    robot = ET.Element('robot', name=name or model.name)
    frames: Dict[str, Tf] = {model.root: IDENTITY}  # each URDF link frame, in the model
    if model.root == 'world':
        ET.SubElement(robot, 'link', name='world')
    for j in model.joints:
        frames[j.child] = j.pose
    for link in model.links.values():
        element = ET.SubElement(robot, 'link', name=link.name)
        to_link = compose(inverse(frames[link.name]), link.pose)  # link frame in its URDF frame
        inertial = ET.SubElement(element, 'inertial')
        _origin(inertial, compose(to_link, link.inertial.pose))
        ET.SubElement(inertial, 'mass', value=_num(link.inertial.mass))
        ET.SubElement(
            inertial,
            'inertia',
            dict(zip(('ixx', 'ixy', 'ixz', 'iyy', 'iyz', 'izz'), map(_num, link.inertial.inertia))),
        )
        for g in link.visuals:
            _geometry_urdf(element, 'visual', g, to_link, link.name)
        for g in link.collisions:
            _geometry_urdf(element, 'collision', g, to_link, link.name)
    for j in model.joints:
        jtype = j.type
        if jtype == 'revolute' and j.lower <= -UNLIMITED and j.upper >= UNLIMITED:
            jtype = 'continuous'
        element = ET.SubElement(robot, 'joint', name=j.name, type=jtype)
        _origin(element, compose(inverse(frames[j.parent]), j.pose))
        ET.SubElement(element, 'parent', link=j.parent)
        ET.SubElement(element, 'child', link=j.child)
        if jtype == 'fixed':
            continue
        ET.SubElement(element, 'axis', xyz=' '.join(_num(v) for v in j.axis))
        limit = {
            'effort': _num(j.effort if j.effort >= 0 else 0),
            'velocity': _num(j.velocity if j.velocity >= 0 else 0),
        }
        if jtype != 'continuous':
            limit['lower'], limit['upper'] = _num(j.lower), _num(j.upper)
        ET.SubElement(element, 'limit', limit)
        if j.damping or j.friction:
            ET.SubElement(element, 'dynamics', damping=_num(j.damping), friction=_num(j.friction))
    for link in model.links.values():
        if link.extras or link.surface:
            gazebo = ET.SubElement(robot, 'gazebo', reference=link.name)
            for tag, text in link.surface.items():  # as sdformat's URDF reader names them
                ET.SubElement(gazebo, tag).text = text
            gazebo.extend(link.extras)
    for j in model.joints:
        if j.type == 'fixed' and j.parent != 'world':
            # Gazebo lumps fixed joints of URDFs only: an SDF model keeps its links.
            gazebo = ET.SubElement(robot, 'gazebo', reference=j.name)
            ET.SubElement(gazebo, 'preserveFixedJoint').text = 'true'
    if model.plugins:
        ET.SubElement(robot, 'gazebo').extend(model.plugins)
    return ET.tostring(robot, encoding='unicode')


@dataclass
class ModelSpawn:
    """A model ready for the URDF spawn path: its name, URDF and the model frame's world pose."""

    name: str
    urdf: str
    position: Tuple[float, float, float]
    orientation: Tuple[float, float, float, float]
    warnings: List[str] = field(default_factory=list)


def model_spawn(model: SdfModel, pose: Tf = IDENTITY, name: Optional[str] = None) -> ModelSpawn:
    """The spawn of ``model`` at ``pose`` composed with the model's own ``<pose>``
    (Gazebo's spawn: initial pose, then the SDF's pose in it)."""
    tf = compose(pose, model.pose)
    name = name or model.name
    return ModelSpawn(name, to_urdf(model, name), tf.p, tf.q, list(model.warnings))


def sdf_spawn(
    xml_text: str,
    name: str,
    position: Sequence[float] = (0.0, 0.0, 0.0),
    orientation: Sequence[float] = (0.0, 0.0, 0.0, 1.0),
    limits: Optional[Limits] = None,
    find_model_dir: Optional[FindModelDir] = None,
    find_model: Optional[Callable[[str], str]] = None,
) -> Optional[ModelSpawn]:
    """A spawn_sdf_model request's SDF (sdf_model.parse_request) as a URDF spawn, as
    Gazebo's spawn treats it: the model's ``<pose>`` is taken in the initial pose.
    None when the document is a URDF ``<robot>``."""
    parsed = parse_request(xml_text, name, limits, find_model_dir, find_model)
    if parsed is None:
        return None
    initial = Tf(
        (float(position[0]), float(position[1]), float(position[2])),
        (
            float(orientation[0]),
            float(orientation[1]),
            float(orientation[2]),
            float(orientation[3]),
        ),
    )
    return model_spawn(parsed, initial, name)
