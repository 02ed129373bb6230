"""What moveit_commander's client side knows of a robot: its planning groups resolved against
the URDF as MoveIt's RobotModel resolves them (description/srdf.py reads the SRDF and picks a
group's joints), ordered and classified as moveit_core's joint_model_group.cpp does (noetic).

No ROS here. A group's joints are in model order (depth-first from the root, children in
document order); its variables are those with a value (mimic ones too), its active joints
leave out mimic and passive ones; its links are the child links of its joints; it is a
chain when each joint descends from the one before, and then its last link is the default
end effector (MoveGroupInterface). The model frame is the root virtual joint's parent frame,
else the URDF's root link.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Dict, List, Optional, Tuple, Union

from . import srdf as srdf_reader
from .srdf import EndEffector, SrdfError
from .urdf_model import RobotModel, parse_urdf

__all__ = ['Group', 'SemanticModel', 'SrdfError', 'default_value', 'load']

NO_VALUE = ('fixed', 'floating', 'planar')  # joint types without a single value


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


def default_value(bounds: Tuple[Optional[float], Optional[float]]) -> float:
    """RobotState::setToDefaultValues for one joint: 0 if within its bounds, else mid-range."""
    lower, upper = bounds
    if lower is None or upper is None or lower <= 0.0 <= upper:
        return 0.0
    return (lower + upper) / 2.0


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


def _is_chain(joints: List[str], urdf: RobotModel, parent_joint: Dict[str, str]) -> bool:
    """joint_model_group.cpp: in model order, each joint descends from the one before."""
    for before, joint in zip(joints, joints[1:]):
        link = urdf.joints[joint].parent
        while link in parent_joint and parent_joint[link] != before:
            link = urdf.joints[parent_joint[link]].parent
        if parent_joint.get(link) != before:
            return False
    return True


def load(urdf_text: Union[str, bytes], srdf_text: Union[str, bytes]) -> SemanticModel:
    """The semantic model of a robot: raises SrdfError (or UrdfError) naming the culprit."""
    urdf = parse_urdf(urdf_text)
    semantic = srdf_reader.parse_srdf(
        srdf_text.decode('utf-8') if isinstance(srdf_text, bytes) else srdf_text
    )
    order = _model_order(urdf)
    index = {name: i for i, name in enumerate(order)}
    tree = {
        j.name: srdf_reader.TreeJoint(j.name, j.type, j.parent, j.child)
        for j in urdf.joints.values()
    }
    parent_joint = {j.child: j.name for j in urdf.joints.values()}
    mimic = {m.follower for m in urdf.mimics}
    passive = set(semantic.passive_joints)
    groups = {}
    for name in semantic.groups:
        joints = sorted(srdf_reader.resolve_group(semantic, name, tree), key=index.__getitem__)
        if not joints:
            raise SrdfError("group '%s' has no joint" % name)
        variables = [j for j in joints if urdf.joints[j].type not in NO_VALUE]
        groups[name] = Group(
            name=name,
            joints=joints,
            variables=variables,
            active_joints=[j for j in variables if j not in mimic and j not in passive],
            links=[urdf.joints[j].child for j in joints],
            is_chain=bool(variables) and _is_chain(joints, urdf, parent_joint),
        )
    model_frame = next(
        (v.parent_frame for v in semantic.virtual_joints if v.child_link == urdf.root_link),
        urdf.root_link,
    )
    variable_joints = [j for j in order if urdf.joints[j].type not in NO_VALUE]
    return SemanticModel(
        robot_name=semantic.name or urdf.name,
        model_frame=model_frame,
        root_link=urdf.root_link,
        groups=groups,
        group_states=semantic.group_states,
        end_effectors=semantic.end_effectors,
        joint_order=order,
        joint_child={j.name: j.child for j in urdf.joints.values()},
        variable_joints=variable_joints,
        limits={
            j: (urdf.joints[j].limits.lower, urdf.joints[j].limits.upper) for j in variable_joints
        },
    )
