"""A robot's semantic description (SRDF) resolved against its URDF, as MoveIt's RobotModel
resolves it: planning groups, named group states, end effectors and the model frame.

No ROS here: moveit_commander's stand-in reads the two texts from the parameter server and
asks this module what a group is made of (its joints, variables and links in the model's
order, the end-effector link of a chain). Semantics follow moveit_core's robot_model.cpp
and joint_model_group.cpp (noetic): a chain adds the parent joints from its tip up to, not
including, its base link's; a <link> adds its parent joint; a <joint> itself; a subgroup
all its joints. A group's links are the child links of its joints.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Tuple, Union

from . import safe_xml
from .urdf_model import RobotModel, parse_urdf

# An SRDF holds a few elements per link pair (disable_collisions): 100 000 is far beyond
# the largest vendor SRDF (Panda's: about 120 pairs).
MAX_SRDF_ELEMENTS = 100_000


class SrdfError(ValueError):
    """The semantic description is unusable; the message names the culprit."""


@dataclass
class GroupSpec:
    """One <group> as written: what it names, before resolution."""

    name: str
    chains: List[Tuple[str, str]] = field(default_factory=list)
    joints: List[str] = field(default_factory=list)
    links: List[str] = field(default_factory=list)
    subgroups: List[str] = field(default_factory=list)


@dataclass
class EndEffector:
    name: str
    parent_link: str
    group: str
    parent_group: str = ''


@dataclass
class Group:
    """A resolved planning group."""

    name: str
    joints: List[str]  # every joint, fixed ones too, in model order
    variables: List[str]  # joints with a value (mimic ones too), in model order
    active_joints: List[str]  # variables that are neither mimic nor passive
    links: List[str]  # child links of the joints, in model order
    is_chain: bool

    @property
    def end_effector_link(self) -> str:
        """MoveGroupInterface's default: the last link of a chain, else none."""
        return self.links[-1] if self.is_chain and self.links else ''


@dataclass
class SemanticModel:
    robot_name: str
    model_frame: str
    root_link: str
    groups: Dict[str, Group]
    group_states: Dict[str, Dict[str, Dict[str, float]]]  # group -> state -> joint -> value
    end_effectors: List[EndEffector]
    joint_order: List[str]  # every joint of the URDF, in model (depth-first) order
    joint_child: Dict[str, str]  # joint -> its child link
    variable_joints: List[str]  # joints with a value, in model order
    limits: Dict[str, Tuple[Optional[float], Optional[float]]]
    disabled_collisions: List[Tuple[str, str]]


def default_value(bounds: Tuple[Optional[float], Optional[float]]) -> float:
    """RobotState::setToDefaultValues for one joint: 0 if within its bounds, else mid-range."""
    lower, upper = bounds
    if lower is None or upper is None or lower <= 0.0 <= upper:
        return 0.0
    return (lower + upper) / 2.0


def _text_root(text: Union[str, bytes], what: str) -> ET.Element:
    try:
        return safe_xml.parse(text, what, max_elements=MAX_SRDF_ELEMENTS)
    except safe_xml.XmlRefused as e:
        raise SrdfError(str(e)) from e


def _required(e: ET.Element, attr: str, where: str) -> str:
    value = e.get(attr)
    if not value:
        raise SrdfError('%s lacks the attribute %s' % (where, attr))
    return value


def parse_group_specs(root: ET.Element) -> List[GroupSpec]:
    specs = []
    for g in root.findall('group'):
        spec = GroupSpec(_required(g, 'name', '<group>'))
        where = "group '%s'" % spec.name
        for c in g.findall('chain'):
            base = _required(c, 'base_link', where + ' <chain>')
            spec.chains.append((base, _required(c, 'tip_link', where + ' <chain>')))
        spec.joints = [_required(j, 'name', where + ' <joint>') for j in g.findall('joint')]
        spec.links = [_required(x, 'name', where + ' <link>') for x in g.findall('link')]
        spec.subgroups = [_required(s, 'name', where + ' <group>') for s in g.findall('group')]
        specs.append(spec)
    return specs


def _model_order(urdf: RobotModel) -> List[str]:
    """Joints depth-first from the root, children in document order (RobotModel's order)."""
    children: Dict[str, List[str]] = {}
    for j in urdf.joints.values():
        children.setdefault(j.parent, []).append(j.name)
    order: List[str] = []
    todo = list(reversed(children.get(urdf.root_link, [])))
    while todo:
        name = todo.pop()
        order.append(name)
        todo.extend(reversed(children.get(urdf.joints[name].child, [])))
    return order


def _chain_joints(
    urdf: RobotModel, parent_joint: Dict[str, str], base: str, tip: str, group: str
) -> List[str]:
    for link in (base, tip):
        if link not in urdf.links:
            raise SrdfError("group '%s': chain link '%s' is not in the URDF" % (group, link))
    out, link = [], tip
    while link != base:
        joint = parent_joint.get(link)
        if joint is None:
            raise SrdfError(
                "group '%s': chain from '%s' to '%s' does not pass through its base link "
                '(chains across the root are not supported here)' % (group, base, tip)
            )
        out.append(joint)
        link = urdf.joints[joint].parent
    return out


def load(urdf_text: Union[str, bytes], srdf_text: Union[str, bytes]) -> SemanticModel:
    """The semantic model of a robot: raises SrdfError (or UrdfError) naming the culprit."""
    urdf = parse_urdf(urdf_text)
    root = _text_root(srdf_text, 'robot_description_semantic')
    if root.tag != 'robot':
        raise SrdfError('robot_description_semantic has root <%s>, expected <robot>' % root.tag)
    order = _model_order(urdf)
    index = {name: i for i, name in enumerate(order)}
    parent_joint = {j.child: j.name for j in urdf.joints.values()}
    mimic = {m.follower for m in urdf.mimics}
    passive = {_required(p, 'name', '<passive_joint>') for p in root.findall('passive_joint')}

    model_frame = urdf.root_link
    for vj in root.findall('virtual_joint'):
        if vj.get('child_link') == urdf.root_link and vj.get('parent_frame'):
            model_frame = vj.get('parent_frame', model_frame)

    groups: Dict[str, Group] = {}
    pending = parse_group_specs(root)
    # subgroups may be defined after the group naming them: resolve until nothing moves
    while pending:
        progressed = False
        for spec in list(pending):
            if any(s not in groups for s in spec.subgroups):
                continue
            groups[spec.name] = _resolve(spec, urdf, groups, parent_joint, index, mimic, passive)
            pending.remove(spec)
            progressed = True
        if not progressed:
            missing = {s for spec in pending for s in spec.subgroups if s not in groups}
            raise SrdfError(
                "group '%s' names subgroup(s) %s, which are not defined (or form a cycle)"
                % (pending[0].name, ', '.join(sorted(missing)))
            )

    states: Dict[str, Dict[str, Dict[str, float]]] = {}
    for s in root.findall('group_state'):
        name = _required(s, 'name', '<group_state>')
        group = _required(s, 'group', "group_state '%s'" % name)
        values = {}
        for j in s.findall('joint'):
            joint = _required(j, 'name', "group_state '%s' <joint>" % name)
            try:
                values[joint] = float(_required(j, 'value', "group_state '%s' <joint>" % name))
            except ValueError as e:
                raise SrdfError(
                    "group_state '%s': joint '%s' value is not a number" % (name, joint)
                ) from e
        states.setdefault(group, {})[name] = values

    eefs = [
        EndEffector(
            _required(e, 'name', '<end_effector>'),
            _required(e, 'parent_link', '<end_effector>'),
            _required(e, 'group', '<end_effector>'),
            e.get('parent_group', ''),
        )
        for e in root.findall('end_effector')
    ]
    disabled = [
        (
            _required(d, 'link1', '<disable_collisions>'),
            _required(d, 'link2', '<disable_collisions>'),
        )
        for d in root.findall('disable_collisions')
    ]
    variable_joints = [
        j for j in order if urdf.joints[j].type not in ('fixed', 'floating', 'planar')
    ]
    limits = {
        j: (urdf.joints[j].limits.lower, urdf.joints[j].limits.upper) for j in variable_joints
    }
    return SemanticModel(
        robot_name=root.get('name') or urdf.name,
        model_frame=model_frame,
        root_link=urdf.root_link,
        groups=groups,
        group_states=states,
        end_effectors=eefs,
        joint_order=order,
        joint_child={j.name: j.child for j in urdf.joints.values()},
        variable_joints=variable_joints,
        limits=limits,
        disabled_collisions=disabled,
    )


def _resolve(
    spec: GroupSpec,
    urdf: RobotModel,
    groups: Dict[str, Group],
    parent_joint: Dict[str, str],
    index: Dict[str, int],
    mimic: set,
    passive: set,
) -> Group:
    where = "group '%s'" % spec.name
    jset = set()
    for base, tip in spec.chains:
        jset.update(_chain_joints(urdf, parent_joint, base, tip, spec.name))
    for j in spec.joints:
        if j not in urdf.joints:
            raise SrdfError("%s names joint '%s', which is not in the URDF" % (where, j))
        jset.add(j)
    for link in spec.links:
        if link not in urdf.links:
            raise SrdfError("%s names link '%s', which is not in the URDF" % (where, link))
        if link in parent_joint:  # the root link has none
            jset.add(parent_joint[link])
    for s in spec.subgroups:
        jset.update(groups[s].joints)
    if not jset:
        raise SrdfError('%s has no joint' % where)
    joints = sorted(jset, key=index.__getitem__)
    variables = [j for j in joints if urdf.joints[j].type not in ('fixed', 'floating', 'planar')]
    return Group(
        name=spec.name,
        joints=joints,
        variables=variables,
        active_joints=[j for j in variables if j not in mimic and j not in passive],
        links=[urdf.joints[j].child for j in joints],
        is_chain=_is_chain(joints, urdf, parent_joint) and bool(variables),
    )


def _is_chain(joints: List[str], urdf: RobotModel, parent_joint: Dict[str, str]) -> bool:
    """joint_model_group.cpp: in model order, each joint descends from the one before."""
    for before, joint in zip(joints, joints[1:]):
        link = urdf.joints[joint].parent
        while link in parent_joint and parent_joint[link] != before:
            link = urdf.joints[parent_joint[link]].parent
        if parent_joint.get(link) != before:
            return False
    return True
