"""The URDF handed to pybullet: only the elements its URDF reader acts on, one per line.

A request's description may be tens of megabytes of comments, whitespace, ``<gazebo>``
extensions, transmissions or tags of other tools. pybullet's ``loadURDF`` parses the whole
file in one call on the physics thread, which cannot step meanwhile (a 50 MB description of
``<gazebo>`` text: 0.26-1.3 s). What it acts on is the robot's links, joints and materials,
all in attributes: that much is written here, from the tree parsed once, a link or joint at
a time (so that other threads run between them), without any text.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from typing import List

from .gazebo_tags import PYBULLET_LINE
from .names import shown
from .urdf_model import UrdfError

TOP_LEVEL = ('link', 'joint', 'material')
# Every element pybullet's URDF reader reads below a link, joint or material (its
# UrdfParser), and what the lumping and mimic code here read: anything else is dropped.
KEPT = frozenset(
    (
        # link
        'inertial', 'origin', 'mass', 'inertia', 'visual', 'collision', 'geometry',
        'box', 'sphere', 'cylinder', 'capsule', 'mesh', 'plane', 'material', 'color',
        'texture', 'specular', 'contact', 'lateral_friction', 'rolling_friction',
        'spinning_friction', 'restitution', 'stiffness', 'damping', 'friction_anchor',
        'inertia_scaling', 'contact_cfm', 'contact_erp',
        # joint
        'parent', 'child', 'axis', 'limit', 'dynamics', 'mimic', 'safety_controller',
        'calibration',
    )
)  # fmt: skip


def compact_urdf(root: ET.Element) -> str:
    """``root`` (a parsed ``<robot>``, left unchanged) as the URDF pybullet needs: its links,
    joints and materials, each element on a line of its own, no text, no comments.

    Raises UrdfError naming the element when a kept element is longer than a line pybullet
    reads whole (gazebo_tags.PYBULLET_LINE)."""
    head = ET.Element('robot', {k: v for k, v in root.attrib.items() if k == 'name'})
    lines: List[str] = [ET.tostring(head, encoding='unicode')[: -len(' />')] + '>\n']
    for child in root:
        if child.tag in TOP_LEVEL:
            # each piece is small: the interpreter lock changes hands between them
            lines.append(ET.tostring(_copy(child, child), encoding='unicode'))
    lines.append('</robot>\n')
    return ''.join(lines)


def _copy(element: ET.Element, top: ET.Element) -> ET.Element:
    """``element`` and its kept descendants, one per line, without text."""
    length = len(element.tag) + sum(len(k) + len(v) + 4 for k, v in element.attrib.items())
    if length > PYBULLET_LINE:
        longest = max(element.attrib, key=lambda k: len(element.attrib[k]))
        raise UrdfError(
            '<%s> of %s %s is %d characters long (attribute %s: %d); pybullet reads at most %d '
            'on a line' % (element.tag, top.tag, shown(top.get('name', '')), length,
                           longest, len(element.attrib[longest]), PYBULLET_LINE)
        )  # fmt: skip
    out = ET.Element(element.tag, element.attrib)
    out.tail = '\n'
    kept = [_copy(c, top) for c in element if c.tag in KEPT]
    if kept:
        out.text = '\n'
        out.extend(kept)
    return out
