"""Links without ``<inertial>`` weigh nothing, as in Gazebo, not pybullet's default 1 kg.

Gazebo (sdformat's URDF parser) lumps every link on a fixed joint into its parent, so a
frame link without ``<inertial>`` (base, flange, tool0 of every ROS-Industrial arm) adds no
mass. pybullet gives such a link 1 kg and unit inertia, and needs a positive mass on
dynamic links; on a fixed joint the link is rigid with its parent, so a negligible mass
(FRAME_MASS) has the same effect as lumping. A massless link on a moving joint is left out
by Gazebo with its subtree; pybullet cannot drop it, so it keeps pybullet's default and
the caller warns once, naming the link.
"""

from __future__ import annotations

import logging
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from typing import Dict, List

log = logging.getLogger('arm1.description')

FRAME_MASS = 1e-6  # kg: far below any real part, but positive for pybullet
FRAME_INERTIA = 1e-9  # kg m^2 on the diagonal


@dataclass
class MasslessReport:
    weightless: List[str] = field(default_factory=list)  # frame links given FRAME_MASS
    moving: List[str] = field(default_factory=list)  # massless on a moving joint: 1 kg stays


def _declares_mass(link: ET.Element) -> bool:
    inertial = link.find('inertial')
    if inertial is None:
        return False
    mass = inertial.find('mass')
    try:
        return mass is not None and float(mass.get('value', '0')) > 0
    except ValueError:
        return False  # parse_urdf reports a bad number; here it only counts as no mass


def weightless_frames(root: ET.Element) -> MasslessReport:
    """Give each link without a positive ``<inertial>`` mass on a fixed joint FRAME_MASS,
    in place; links of moving joints are only reported. The root link and ``world`` are
    left as they are (the root is the base: fixed or carried by its own children)."""
    parent_joint: Dict[str, str] = {}
    for joint in root.findall('joint'):
        child = joint.find('child')
        if child is not None and child.get('link'):
            parent_joint[child.get('link', '')] = joint.get('type', '')
    report = MasslessReport()
    for link in root.findall('link'):
        name = link.get('name', '')
        if name == 'world' or name not in parent_joint or _declares_mass(link):
            continue
        if parent_joint[name] != 'fixed':
            report.moving.append(name)
            continue
        old = link.find('inertial')
        if old is not None:
            link.remove(old)
        inertial = ET.SubElement(link, 'inertial')
        ET.SubElement(inertial, 'mass', value=repr(FRAME_MASS))
        i = repr(FRAME_INERTIA)
        ET.SubElement(inertial, 'inertia', ixx=i, iyy=i, izz=i, ixy='0', ixz='0', iyz='0')
        report.weightless.append(name)
    return report


def lighten(urdf_text: str, model: str) -> str:
    """``urdf_text`` (already parsed once safely: our own serialisation) with
    weightless_frames applied; warns once per spawn about massless moving links."""
    root = ET.fromstring(urdf_text)
    report = weightless_frames(root)
    if report.moving:
        log.warning(
            "model '%s': link(s) %s have no <inertial> but move on a non-fixed joint: Gazebo "
            'leaves them (and what hangs on them) out; pybullet gives each 1 kg',
            model,
            ', '.join(report.moving),
        )
    return ET.tostring(root, encoding='unicode') if report.weightless else urdf_text
