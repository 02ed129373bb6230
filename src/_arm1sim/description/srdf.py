"""A robot's semantic description (SRDF, as srdfdom reads it): planning groups, named
states, end effectors, virtual and passive joints and the link pairs never checked for
collision. ROS-free; ``resolve`` turns a group into its joints with the URDF's tree.

A group is the union of its <chain base_link tip_link> (the joints from base to tip),
<joint>s, <link>s (the joint whose child the link is) and <group>s (subgroups), as
srdfdom and MoveIt's RobotModel build it.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from typing import Dict, List, Mapping, Optional, Set, Tuple

from . import safe_xml


class SrdfError(ValueError):
    """The semantic description is unusable; the message names the culprit."""


@dataclass
class Group:
    name: str
    chains: List[Tuple[str, str]] = field(default_factory=list)  # (base_link, tip_link)
    joints: List[str] = field(default_factory=list)
    links: List[str] = field(default_factory=list)
    subgroups: List[str] = field(default_factory=list)


@dataclass
class EndEffector:
    name: str
    group: str
    parent_link: str
    parent_group: str = ''


@dataclass
class VirtualJoint:
    name: str
    type: str  # fixed, floating or planar
    parent_frame: str
    child_link: str


@dataclass
class Srdf:
    name: str
    groups: Dict[str, Group] = field(default_factory=dict)
    group_states: Dict[str, Dict[str, Dict[str, float]]] = field(default_factory=dict)
    end_effectors: List[EndEffector] = field(default_factory=list)
    virtual_joints: List[VirtualJoint] = field(default_factory=list)
    passive_joints: List[str] = field(default_factory=list)
    disabled_collisions: Set[Tuple[str, str]] = field(default_factory=set)  # sorted pairs
    # <disable_default_collisions link>: the link collides with nothing by default ...
    default_disabled: Set[str] = field(default_factory=set)
    # ... but the pairs of <enable_collisions> (srdfdom 0.6), which win over both
    enabled_collisions: Set[Tuple[str, str]] = field(default_factory=set)

    def collision_disabled(self, a: str, b: str) -> bool:
        """Whether MoveIt's allowed-collision matrix from this SRDF allows the pair: an
        entry (enabled, else disabled) over the links' default entries."""
        pair = (min(a, b), max(a, b))
        if pair in self.enabled_collisions:
            return False
        return (
            pair in self.disabled_collisions
            or a in self.default_disabled
            or b in self.default_disabled
        )


def _required(element: ET.Element, attribute: str, where: str) -> str:
    value = (element.get(attribute) or '').strip()
    if not value:
        raise SrdfError('%s: <%s> has no %s' % (where, element.tag, attribute))
    return value


def parse_srdf(text: str) -> Srdf:
    """Everything MoveIt reads from robot_description_semantic; SrdfError on bad input."""
    try:
        root = safe_xml.parse(text, 'robot_description_semantic')
    except safe_xml.XmlRefused as exc:
        raise SrdfError(str(exc)) from None
    if root.tag != 'robot':
        raise SrdfError('robot_description_semantic has root <%s>, expected <robot>' % root.tag)
    srdf = Srdf(root.get('name') or '')
    for g in root.findall('group'):
        name = _required(g, 'name', 'SRDF')
        group = Group(name)
        where = "group '%s'" % name
        for c in g.findall('chain'):
            group.chains.append((_required(c, 'base_link', where), _required(c, 'tip_link', where)))
        group.joints += [_required(j, 'name', where) for j in g.findall('joint')]
        group.links += [_required(link, 'name', where) for link in g.findall('link')]
        group.subgroups += [_required(s, 'name', where) for s in g.findall('group')]
        srdf.groups[name] = group
    for s in root.findall('group_state'):
        name = _required(s, 'name', 'SRDF')
        group_name = _required(s, 'group', "group_state '%s'" % name)
        values = {}
        for j in s.findall('joint'):
            joint = _required(j, 'name', "group_state '%s'" % name)
            try:
                values[joint] = float((j.get('value') or '').split()[0])
            except (ValueError, IndexError):
                raise SrdfError(
                    "group_state '%s': joint '%s' has no numeric value" % (name, joint)
                ) from None
        srdf.group_states.setdefault(group_name, {})[name] = values
    for e in root.findall('end_effector'):
        name = _required(e, 'name', 'SRDF')
        where = "end_effector '%s'" % name
        srdf.end_effectors.append(
            EndEffector(
                name,
                _required(e, 'group', where),
                _required(e, 'parent_link', where),
                (e.get('parent_group') or '').strip(),
            )
        )
    for v in root.findall('virtual_joint'):
        name = _required(v, 'name', 'SRDF')
        where = "virtual_joint '%s'" % name
        kind = _required(v, 'type', where)
        if kind not in ('fixed', 'floating', 'planar'):
            raise SrdfError("%s: type '%s' is none of fixed, floating, planar" % (where, kind))
        srdf.virtual_joints.append(
            VirtualJoint(
                name, kind, _required(v, 'parent_frame', where), _required(v, 'child_link', where)
            )
        )
    srdf.passive_joints = [_required(p, 'name', 'SRDF') for p in root.findall('passive_joint')]
    for d in root.findall('disable_collisions'):
        a, b = _required(d, 'link1', 'SRDF'), _required(d, 'link2', 'SRDF')
        srdf.disabled_collisions.add((min(a, b), max(a, b)))
    for e in root.findall('enable_collisions'):
        a, b = _required(e, 'link1', 'SRDF'), _required(e, 'link2', 'SRDF')
        srdf.enabled_collisions.add((min(a, b), max(a, b)))
    srdf.default_disabled = {
        _required(d, 'link', 'SRDF') for d in root.findall('disable_default_collisions')
    }
    for group in srdf.groups.values():
        for sub in group.subgroups:
            if sub not in srdf.groups:
                raise SrdfError(
                    "group '%s' names subgroup '%s', which is not defined" % (group.name, sub)
                )
    return srdf


@dataclass
class TreeJoint:
    """What group resolution needs of a URDF joint."""

    name: str
    type: str
    parent: str
    child: str


def resolve_group(
    srdf: Srdf, name: str, joints: Mapping[str, TreeJoint], _seen: Optional[Set[str]] = None
) -> List[str]:
    """The group's joints (every type, fixed included), in the URDF's document order."""
    seen = _seen if _seen is not None else set()
    if name in seen:
        raise SrdfError("group '%s' contains itself through its subgroups" % name)
    seen = seen | {name}
    group = srdf.groups.get(name)
    if group is None:
        raise SrdfError("no group '%s' in the SRDF (groups: %s)" % (name, ', '.join(srdf.groups)))
    by_child = {j.child: j for j in joints.values()}
    chosen: Set[str] = set()
    for base, tip in group.chains:
        link, path = tip, []
        while link != base:
            joint = by_child.get(link)
            if joint is None:
                raise SrdfError(
                    "group '%s': chain from '%s' to '%s' is not a path of the URDF's tree"
                    % (name, base, tip)
                )
            path.append(joint.name)
            link = joint.parent
        chosen.update(path)
    for joint_name in group.joints:
        if joint_name not in joints:
            if any(v.name == joint_name for v in srdf.virtual_joints):
                continue  # a virtual joint: MoveIt's root joint, nothing to plan here
            raise SrdfError("group '%s' names joint '%s', not in the URDF" % (name, joint_name))
        chosen.add(joint_name)
    for link in group.links:
        joint = by_child.get(link)
        if joint is not None:
            chosen.add(joint.name)
        elif not any(j.parent == link for j in joints.values()):
            raise SrdfError("group '%s' names link '%s', not in the URDF" % (name, link))
    for sub in group.subgroups:
        chosen.update(resolve_group(srdf, sub, joints, seen))
    return [j for j in joints if j in chosen]


def group_links(srdf: Srdf, name: str, joints: Mapping[str, TreeJoint]) -> List[str]:
    """The links a group moves or names (children of its joints, its <link>s, chain bases)."""
    group = srdf.groups[name]
    links = [joints[j].child for j in resolve_group(srdf, name, joints)]
    for extra in group.links + [base for base, _ in group.chains]:
        if extra not in links:
            links.append(extra)
    for sub in group.subgroups:
        links += [link for link in group_links(srdf, sub, joints) if link not in links]
    return links
